"""Contacts with circles: circle-circle and polygon-circle (one point each).

Every function works on world-frame data and returns one contact as the tuple
``(count, nx, ny, px, py, depth)``: ``count`` is 0 (no contact) or 1, ``(nx, ny)`` the unit normal
pointing from the first shape to the second, ``(px, py)`` the contact point midway between the
two surfaces and ``depth`` the penetration (> 0 overlapping, < 0 a gap). A contact is reported
when ``depth >= -margin`` (touching shapes give a contact at ``margin = 0``).
"""

from __future__ import annotations

import math

from sandbox.jit import njit

# below this centre distance (m) the direction between two centres is not trusted
TINY = 1e-12


@njit
def circle_circle(p1x, p1y, r1, p2x, p2y, r2, fx, fy, margin):
    """Circle 1 (centre p1, radius r1) against circle 2; ``(fx, fy)`` is the unit normal used
    when the centres coincide (the slides' formula divides by d = 0 there)."""
    # slides, "Sphere Collision Detection Example": d = |p2 - p1| <= r1 + r2
    dx = p2x - p1x
    dy = p2y - p1y
    d = math.sqrt(dx * dx + dy * dy)
    # penetration p = r1 + r2 - d
    p = r1 + r2 - d
    if p < -margin:
        return 0, 0.0, 0.0, 0.0, 0.0, 0.0
    # contact normal n = (p2 - p1) / d
    if d > TINY:
        nx = dx / d
        ny = dy / d
    else:
        nx = fx
        ny = fy
    # contact point p_c = p1 + (r1 - p / 2) n
    k = r1 - 0.5 * p
    return 1, nx, ny, p1x + k * nx, p1y + k * ny, p


@njit
def polygon_circle(wp, o, count, cx, cy, r, margin):
    """Convex polygon (world-frame rows ``o`` to ``o + count`` of ``wp``: vertex x, y and the
    outward normal of the edge starting there, CCW) against the circle of centre ``(cx, cy)``
    and radius ``r``; the normal points from the polygon to the circle.

    The edge of largest separation n_i . (c - v_i) decides the region of the centre: beyond one
    of the edge's end vertices (vertex region: the normal points from that vertex to the centre)
    or over the edge itself (face region: the normal is the edge normal; this includes a centre
    inside the polygon, so coincident centres still give a valid normal).
    """
    best = -math.inf
    edge = 0
    for i in range(count):
        v = o + i
        sep = wp[v, 2] * (cx - wp[v, 0]) + wp[v, 3] * (cy - wp[v, 1])
        if sep > best:
            best = sep
            edge = i
    if best - r > margin:
        return 0, 0.0, 0.0, 0.0, 0.0, 0.0
    i1 = o + edge
    i2 = o + (edge + 1 if edge + 1 < count else 0)
    v1x, v1y = wp[i1, 0], wp[i1, 1]
    v2x, v2y = wp[i2, 0], wp[i2, 1]
    ex, ey = v2x - v1x, v2y - v1y
    u1 = (cx - v1x) * ex + (cy - v1y) * ey  # < 0: the centre is behind v1 along the edge
    u2 = (cx - v2x) * -ex + (cy - v2y) * -ey  # < 0: the centre is beyond v2
    if best > TINY and (u1 < 0.0 or u2 < 0.0):
        # vertex region: closest polygon point is the vertex itself
        if u1 < 0.0:
            qx, qy = v1x, v1y
        else:
            qx, qy = v2x, v2y
        dx, dy = cx - qx, cy - qy
        dist = math.sqrt(dx * dx + dy * dy)  # >= best > 0
        depth = r - dist
        if depth < -margin:
            return 0, 0.0, 0.0, 0.0, 0.0, 0.0
        nx, ny = dx / dist, dy / dist
    else:
        # face region: the centre projects onto the edge (or lies inside the polygon)
        nx, ny = wp[i1, 2], wp[i1, 3]
        depth = r - best
        qx, qy = cx - best * nx, cy - best * ny
    # midway between the polygon surface point q and the deepest circle point c - r n
    px = 0.5 * (qx + cx - r * nx)
    py = 0.5 * (qy + cy - r * ny)
    return 1, nx, ny, px, py, depth
