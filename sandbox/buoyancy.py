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

import numpy as np

from sandbox.jit import njit
from sandbox.math2d import rotate
from sandbox.records import CIRCLE, DYNAMIC


@njit
def polygon_area_centroid(points: np.ndarray, n: int) -> tuple[float, float, float]:
    """Area (>= 0, m^2) and centroid (x, y) of the simple polygon ``points[:n]`` (rows x, y),
    either winding (shoelace, as a fan of triangles from vertex 0)."""
    if n < 3:
        return 0.0, 0.0, 0.0
    a2 = cx = cy = 0.0
    x0, y0 = points[0, 0], points[0, 1]
    for i in range(1, n - 1):
        x1, y1 = points[i, 0], points[i, 1]
        x2, y2 = points[i + 1, 0], points[i + 1, 1]
        cross = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0)
        a2 += cross
        cx += cross * (x0 + x1 + x2)
        cy += cross * (y0 + y1 + y2)
    if a2 == 0.0:
        return 0.0, 0.0, 0.0
    return abs(0.5 * a2), cx / (3.0 * a2), cy / (3.0 * a2)


@njit
def clip_below(points: np.ndarray, n: int, surface_y: float, out: np.ndarray) -> int:
    """The part of the convex polygon ``points[:n]`` with y <= surface_y (Sutherland-Hodgman,
    one clip line), written to ``out`` (at least 2n rows); returns its vertex count."""
    k = 0
    for i in range(n):
        xa, ya = points[i, 0], points[i, 1]
        xb, yb = points[(i + 1) % n, 0], points[(i + 1) % n, 1]
        if ya <= surface_y:
            out[k, 0], out[k, 1] = xa, ya
            k += 1
        if (ya <= surface_y) != (yb <= surface_y):  # the edge crosses the surface
            t = (surface_y - ya) / (yb - ya)
            out[k, 0], out[k, 1] = xa + t * (xb - xa), surface_y
            k += 1
    return k


@njit(python=True)
def polygon_submerged(points: np.ndarray, surface_y: float) -> tuple[float, float, float]:
    """Submerged area and its centroid of a convex polygon (world frame rows x, y)."""
    n = points.shape[0]
    out = np.empty((2 * n, 2))
    return polygon_area_centroid(out, clip_below(points, n, surface_y, out))


@njit(python=True)
def circle_submerged(cx: float, cy: float, radius: float, surface_y: float):
    """Area below ``surface_y`` of the circle (centre, radius) and that area's centroid.

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


@njit
def shape_submerged(shape, vertices, px: float, py: float, phi: float, surface_y: float):
    """Submerged area and centroid of one shape record of a body at (px, py), angle phi."""
    c, s = math.cos(phi), math.sin(phi)
    if shape["kind"] == CIRCLE:
        x, y = rotate(c, s, shape["center"][0], shape["center"][1])
        return circle_submerged(px + x, py + y, shape["radius"], surface_y)
    first, n = shape["first_vertex"], shape["vertex_count"]
    points = np.empty((n, 2))
    for v in range(n):
        q = vertices[first + v]["point"]
        x, y = rotate(c, s, q[0], q[1])
        points[v, 0], points[v, 1] = px + x, py + y
    return polygon_submerged(points, surface_y)


@njit(python=True)
def submerged_by_body(bodies, shapes, vertices, state, surface_y: float, bit: np.uint64):
    """Submerged area A (n,) and its centroid c (n, 2) of every dynamic body acted on by the
    generator ``bit`` (``BODY["generators"]``), at the integrator's ``state`` (MOTION records).
    A body's shapes are summed: A is the total, c the area-weighted mean of the parts'
    centroids. Bodies out of the water get A = 0 and c = their centre of mass."""
    n = bodies.shape[0]
    area = np.zeros(n)
    centroid = np.zeros((n, 2))
    for k in range(shapes.shape[0]):
        i = shapes[k]["body"]
        if bodies[i]["kind"] != DYNAMIC or not (bodies[i]["generators"] & bit):
            continue
        px, py, phi = state[i]["p"][0], state[i]["p"][1], state[i]["phi"]
        if py - shapes[k]["bound"] > surface_y:
            continue  # the whole shape is above the water
        a, x, y = shape_submerged(shapes[k], vertices, px, py, phi, surface_y)
        area[i] += a
        centroid[i, 0] += a * x
        centroid[i, 1] += a * y
    for i in range(n):
        if area[i] > 0.0:
            centroid[i, 0] /= area[i]
            centroid[i, 1] /= area[i]
        else:
            centroid[i, 0], centroid[i, 1] = state[i]["p"][0], state[i]["p"][1]
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
