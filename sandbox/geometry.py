"""Plane geometry shared by shapes, mass properties and the scene validator (metres, radians)."""

from __future__ import annotations

import math

import numpy as np


def rotation(angle: float) -> np.ndarray:
    """2x2 rotation matrix R(angle) = [[cos, -sin], [sin, cos]] (CCW positive)."""
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s], [s, c]])


def signed_area(vertices: np.ndarray) -> float:
    """Shoelace formula: A = 1/2 sum(x_i y_{i+1} - x_{i+1} y_i); positive when counter-clockwise (m^2)."""
    v = np.asarray(vertices, dtype=float)
    x, y = v[:, 0], v[:, 1]
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


def make_ccw(vertices: np.ndarray) -> np.ndarray:
    """The same polygon with counter-clockwise winding (a copy)."""
    v = np.array(vertices, dtype=float)
    return v[::-1].copy() if signed_area(v) < 0 else v


def polygon_problem(vertices: object, tol: float = 1e-9) -> str | None:
    """Why ``vertices`` is not a usable convex polygon, or None when it is.

    Accepts either winding. Rejects fewer than three points, repeated points, collinear
    neighbours, zero area and any reflex (concave) corner.
    """
    v = np.asarray(vertices, dtype=float)
    if v.ndim != 2 or v.shape[1] != 2:
        return "must be a list of [x, y] pairs"
    n = len(v)
    if n < 3:
        return f"a polygon needs at least 3 vertices, got {n}"
    if not np.all(np.isfinite(v)):
        return "vertices must be finite numbers"
    size = float(np.max(np.ptp(v, axis=0)))
    if size <= tol:
        return "degenerate polygon (all vertices coincide)"
    area = signed_area(v)
    if abs(area) <= tol * size * size:
        return "degenerate polygon (zero area)"
    sign = 1.0 if area > 0 else -1.0
    for i in range(n):
        a, b, c = v[i], v[(i + 1) % n], v[(i + 2) % n]
        if np.linalg.norm(b - a) <= tol * size:
            return f"vertices {i} and {(i + 1) % n} coincide"
        cross = (b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0])
        if sign * cross <= tol * size * size:
            return f"polygon is not strictly convex at vertex {(i + 1) % n}"
    # a star-shaped loop can turn the same way at every corner yet wind twice round
    turning = 0.0
    for i in range(n):
        a, b, c = v[i], v[(i + 1) % n], v[(i + 2) % n]
        e1, e2 = b - a, c - b
        turning += math.atan2(e1[0] * e2[1] - e1[1] * e2[0], float(e1 @ e2))
    if abs(abs(turning) - 2.0 * math.pi) > 1e-6:
        return "polygon edges cross (it winds more than once)"
    return None


def edge_normals(vertices: np.ndarray) -> np.ndarray:
    """Outward unit normals of a CCW polygon's edges i -> i+1: n = (e_y, -e_x) / |e|."""
    v = np.asarray(vertices, dtype=float)
    e = np.roll(v, -1, axis=0) - v
    n = np.stack([e[:, 1], -e[:, 0]], axis=1)
    return n / np.linalg.norm(n, axis=1)[:, None]


def box_vertices(
    width: float, height: float, offset: tuple[float, float] = (0.0, 0.0), angle: float = 0.0
) -> np.ndarray:
    """Corners of a width x height box centred at ``offset`` and turned by ``angle`` (CCW)."""
    hw, hh = 0.5 * width, 0.5 * height
    corners = np.array([[-hw, -hh], [hw, -hh], [hw, hh], [-hw, hh]])
    return corners @ rotation(angle).T + np.asarray(offset, dtype=float)
