"""Archimedes in 2D: the submerged part of a shape below a flat water surface.

Slides, "Further Topics on Physics Animation" (modelling forces: buoyancy). A body in a fluid of
density rho_fluid (kg/m^2 in 2D) feels a lift equal to the weight of the fluid it displaces,

    F = -rho_fluid * A * g        acting at c, the centroid of the submerged area A,

so the torque about the centre of mass is r x F with r = c - com. These are the formulas of
Box2D's buoyancy controller, used by both this engine (:class:`sandbox.forces.Buoyancy`) and the
pymunk bridge, so the two engines agree. The functions here are pure geometry (world frame,
metres); the closed forms at the bottom give the draft of a floating box or disc, for checks.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np


def polygon_area_centroid(points: Sequence[Sequence[float]]) -> tuple[float, float, float]:
    """Area (>= 0, m^2) and centroid (x, y) of a simple polygon, either winding (shoelace)."""
    n = len(points)
    if n < 3:
        return 0.0, 0.0, 0.0
    a2 = cx = cy = 0.0
    x0, y0 = points[0]
    for i in range(1, n - 1):  # fan of triangles from vertex 0
        x1, y1 = points[i]
        x2, y2 = points[i + 1]
        cross = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0)
        a2 += cross
        cx += cross * (x0 + x1 + x2)
        cy += cross * (y0 + y1 + y2)
    if a2 == 0.0:
        return 0.0, 0.0, 0.0
    return abs(0.5 * a2), cx / (3.0 * a2), cy / (3.0 * a2)


def clip_below(points: Sequence[Sequence[float]], surface_y: float) -> list[tuple[float, float]]:
    """The part of a convex polygon with y <= surface_y (Sutherland-Hodgman, one clip line)."""
    out: list[tuple[float, float]] = []
    n = len(points)
    for i in range(n):
        xa, ya = points[i]
        xb, yb = points[(i + 1) % n]
        if ya <= surface_y:
            out.append((xa, ya))
        if (ya <= surface_y) != (yb <= surface_y):  # the edge crosses the surface
            t = (surface_y - ya) / (yb - ya)
            out.append((xa + t * (xb - xa), surface_y))
    return out


def circle_submerged(
    cx: float, cy: float, radius: float, surface_y: float
) -> tuple[float, float, float]:
    """Area and centroid (x, y) of the part of a circle below y = surface_y.

    With d = surface_y - cy and h = sqrt(r^2 - d^2): the cap above the line has area
    r^2 acos(d/r) - d h; the submerged part is the rest, with centroid cy - 2 h^3 / (3 A).
    """
    d = surface_y - cy
    if d >= radius:
        return math.pi * radius * radius, cx, cy
    if d <= -radius:
        return 0.0, cx, cy
    h = math.sqrt(radius * radius - d * d)
    area = math.pi * radius * radius - (radius * radius * math.acos(d / radius) - d * h)
    if area <= 0.0:
        return 0.0, cx, cy
    return area, cx, cy - 2.0 * h**3 / (3.0 * area)


def submerged_by_body(
    geometry, p: np.ndarray, phi: np.ndarray, surface_y: float, targets: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Submerged area A (n,) and its centroid c (n, 2) of every body marked in ``targets``.

    ``geometry`` is the world's flattened shape arrays (:class:`sandbox.geometry_arrays.Geometry`,
    shapes about each body's centre of mass); ``p`` (n, 2) centres of mass and ``phi`` (n,)
    angles place them (a shape point q is at p + R(phi) q). A body's shapes are summed: A is the
    total, c the area-weighted mean of the parts' centroids. Bodies out of the water get A = 0 and
    c = p.
    """
    n = len(p)
    area = np.zeros(n)
    moment = np.zeros((n, 2))
    for k in range(len(geometry)):
        i = int(geometry.shape_body[k])
        if not targets[i]:
            continue
        px, py = float(p[i, 0]), float(p[i, 1])
        if py - float(geometry.shape_bound[k]) > surface_y:
            continue  # the whole shape is above the water
        c, s = math.cos(float(phi[i])), math.sin(float(phi[i]))
        if geometry.shape_kind[k] == 0:  # circle
            qx, qy = geometry.shape_center[k]
            a, x, y = circle_submerged(
                px + c * qx - s * qy, py + s * qx + c * qy, float(geometry.shape_radius[k]),
                surface_y,
            )  # fmt: skip
        else:
            start, count = int(geometry.shape_vstart[k]), int(geometry.shape_vcount[k])
            local = geometry.verts[start : start + count]
            points = [(px + c * qx - s * qy, py + s * qx + c * qy) for qx, qy in local]
            a, x, y = polygon_area_centroid(clip_below(points, surface_y))
        area[i] += a
        moment[i, 0] += a * x
        moment[i, 1] += a * y
    centroid = np.array(p, dtype=float, copy=True)
    wet = area > 0.0
    centroid[wet] = moment[wet] / area[wet, None]
    return area, centroid


# --- closed forms: how deep a floating body sits -------------------------------------------------
def box_draft(height: float, density_ratio: float) -> float:
    """Draft (m) of a box floating flat: the displaced area w d equals w h rho_body / rho_fluid."""
    return height * min(max(density_ratio, 0.0), 1.0)


def circle_segment_area(radius: float, depth: float) -> float:
    """Area (m^2) of the part of a disc of ``radius`` lying within ``depth`` of its lowest point."""
    h = min(max(depth, 0.0), 2.0 * radius)
    return radius * radius * math.acos((radius - h) / radius) - (radius - h) * math.sqrt(
        max(2.0 * radius * h - h * h, 0.0)
    )


def disc_draft(radius: float, density_ratio: float) -> float:
    """Draft (m) of a floating disc: the depth whose segment area is pi r^2 rho_body / rho_fluid.

    Solved by bisection (the segment area grows monotonically with depth).
    """
    target = math.pi * radius * radius * min(max(density_ratio, 0.0), 1.0)
    lo, hi = 0.0, 2.0 * radius
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        if circle_segment_area(radius, mid) < target:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)
