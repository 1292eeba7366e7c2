"""Polygon-polygon contact manifolds (slides, "Collision Manifolds": vertex-face and edge-face
contacts reduced to at most two points).

1. Separating axis test: for every edge normal n_i of one polygon, the separation of the other
   polygon is min_j n_i . (w_j - v_i). The largest over both polygons' edges is > 0 exactly when
   the polygons are apart (and is minus the penetration depth when they overlap).
2. Reference face: the edge of largest separation. A tolerance keeps the choice stable: the
   preferred polygon (the one with the smaller shape index) keeps the reference face unless
   the other one is clearly better, so near-ties do not flip the face from step to step.
3. Incident edge: the edge of the other polygon whose normal is most anti-parallel.
4. When the polygons are apart by more than a small slop (speculative contacts), the closest
   features may be two vertices; then a single point with the vertex-to-vertex normal is used
   (not for a vertex pair straight across the reference face: parallel faces are clipped).
5. Clipping: the incident edge is clipped to the side planes of the reference face, which leaves
   at most two points; each point's depth is its distance below the reference face, and the
   reported point lies midway between the two surfaces.

Feature ids (for warm starting): ``code * 2**32 + vertex_on_a * 2**16 + vertex_on_b`` with code 0
(face contact) or 2 (vertex-vertex). A clipped point is named by the reference-face vertex
whose side plane clipped it and the incident vertex it came from, a's vertex first whichever
face is the reference (as Box2D v3's ``B2_MAKE_ID``): the faces are antiparallel, so the point
at the end of a's face where vertex i sits is named (i, j) from either side, and the id stays
the same while the same faces touch, even when the reference face changes over. Two equal boxes
half on one another (a pyramid) change it every few steps, as they tip by a fraction of a
degree; with the face in the id, 1 point in 60 of a pyramid of 40 lost its warm start each
step.
"""

from __future__ import annotations

import math

import numpy as np

from sandbox.jit import njit

LINEAR_SLOP = 0.005  # m, the size of "touching" used by the tolerances below
RELATIVE_TOL = 0.98  # the other face must be better than 0.98 x the preferred separation ...
ABSOLUTE_TOL = 0.1 * LINEAR_SLOP  # ... plus this much (m), to take over as reference face
VERTEX_TOL = 0.1 * LINEAR_SLOP  # apart by more than this (m): look for vertex-vertex contact
MERGE_TOL = 1e-9  # m: two clipped points closer than this are one point
ACROSS_TOL = 1e-9  # m: a vertex pair offset sideways by less than this lies straight across
FEATURE_VERTEX_VERTEX = 2 << 32


@njit(inline="always")  # a call per pair: see sandbox.narrowphase.collide_pair
def max_separation(wp, o1, c1, o2, c2):
    """Largest separation of polygon 2 along the edge normals of polygon 1, and that edge.

    Polygons are world-frame rows of ``wp`` (x, y and the outward normal of the edge starting at
    that vertex): polygon 1 is rows ``o1`` to ``o1 + c1``, polygon 2 rows ``o2`` to ``o2 + c2``.
    """
    best = -math.inf
    edge = 0
    for i in range(c1):
        r = np.uint64(o1 + i)  # unsigned: numba then leaves out the test for negative indexing
        nx, ny = wp[r, 2], wp[r, 3]
        px, py = wp[r, 0], wp[r, 1]
        si = math.inf
        for j in range(c2):
            s = np.uint64(o2 + j)
            d = nx * (wp[s, 0] - px) + ny * (wp[s, 1] - py)
            if d < si:
                si = d
        if si > best:
            best = si
            edge = i
    return best, edge


@njit(inline="always")  # a call per pair: see sandbox.narrowphase.collide_pair
def incident_edge(wp, o2, c2, nx, ny):
    """Edge of polygon 2 (rows ``o2`` to ``o2 + c2`` of ``wp``) whose outward normal is most
    anti-parallel to ``(nx, ny)``."""
    best = math.inf
    edge = 0
    for i in range(c2):
        r = np.uint64(o2 + i)
        d = wp[r, 2] * nx + wp[r, 3] * ny
        if d < best:
            best = d
            edge = i
    return edge


@njit
def _clamp01(x):
    return 0.0 if x < 0.0 else (1.0 if x > 1.0 else x)


@njit
def segment_fractions(p1x, p1y, q1x, q1y, p2x, p2y, q2x, q2y):
    """Closest points of segments p1-q1 and p2-q2 as fractions (f1, f2) along each; a fraction
    is exactly 0.0 or 1.0 when the closest point is an end vertex (Ericson, RTCD 5.1.9)."""
    d1x, d1y = q1x - p1x, q1y - p1y
    d2x, d2y = q2x - p2x, q2y - p2y
    rx, ry = p1x - p2x, p1y - p2y
    a = d1x * d1x + d1y * d1y
    e = d2x * d2x + d2y * d2y
    f = d2x * rx + d2y * ry
    c = d1x * rx + d1y * ry
    b = d1x * d2x + d1y * d2y
    denom = a * e - b * b
    f1 = _clamp01((b * f - c * e) / denom) if denom > 0.0 else 0.0
    f2 = (b * f1 + f) / e
    if f2 < 0.0:
        f2 = 0.0
        f1 = _clamp01(-c / a)
    elif f2 > 1.0:
        f2 = 1.0
        f1 = _clamp01((b - c) / a)
    return f1, f2


@njit(inline="always")  # a call per pair: wp reference-counted in and out of each
def polygon_polygon(wp, o_a, c_a, o_b, c_b, prefer_a, margin):
    """Manifold of convex polygons a and b: world-frame rows ``o_a`` to ``o_a + c_a`` of ``wp``
    (vertex x, y, CCW, and the outward normal of the edge starting there), likewise for b.

    ``prefer_a``: polygon a keeps the reference face on near-ties (pass ``sa < sb`` so the
    choice is the same whichever order the pair comes in). Returns
    ``(count, nx, ny, x0, y0, depth0, feature0, x1, y1, depth1, feature1)`` with the normal
    pointing from a to b; points with ``depth < -margin`` are dropped; an unused point is
    zeros with feature -1.
    """
    none = (0, 0.0, 0.0, 0.0, 0.0, 0.0, -1, 0.0, 0.0, 0.0, -1)
    # 1. separating axis test on both polygons' edge normals
    sep_a, edge_a = max_separation(wp, o_a, c_a, o_b, c_b)
    if sep_a > margin:
        return none
    sep_b, edge_b = max_separation(wp, o_b, c_b, o_a, c_a)
    if sep_b > margin:
        return none
    # 2. reference face, with a tolerance that prefers a stable choice
    if prefer_a:
        flip = sep_b > RELATIVE_TOL * sep_a + ABSOLUTE_TOL
    else:
        flip = not (sep_a > RELATIVE_TOL * sep_b + ABSOLUTE_TOL)
    if flip:  # reference face on b
        o1, c1, e1, o2, c2 = o_b, c_b, edge_b, o_a, c_a
    else:
        o1, c1, e1, o2, c2 = o_a, c_a, edge_a, o_b, c_b
    sign = -1.0 if flip else 1.0  # turns the reference normal into the a -> b normal
    nx, ny = wp[o1 + e1, 2], wp[o1 + e1, 3]
    # 3. incident edge on the other polygon
    e2 = incident_edge(wp, o2, c2, nx, ny)
    i11, i12 = e1, (e1 + 1 if e1 + 1 < c1 else 0)
    i21, i22 = e2, (e2 + 1 if e2 + 1 < c2 else 0)
    v11x, v11y = wp[o1 + i11, 0], wp[o1 + i11, 1]
    v12x, v12y = wp[o1 + i12, 0], wp[o1 + i12, 1]
    v21x, v21y = wp[o2 + i21, 0], wp[o2 + i21, 1]
    v22x, v22y = wp[o2 + i22, 0], wp[o2 + i22, 1]

    # 4. apart: the closest features may be two vertices (speculative contact)
    if max(sep_a, sep_b) > VERTEX_TOL:
        f1, f2 = segment_fractions(v11x, v11y, v12x, v12y, v21x, v21y, v22x, v22y)
        if (f1 == 0.0 or f1 == 1.0) and (f2 == 0.0 or f2 == 1.0):
            r = i11 if f1 == 0.0 else i12
            k = i21 if f2 == 0.0 else i22
            wx = wp[o2 + k, 0] - wp[o1 + r, 0]
            wy = wp[o2 + k, 1] - wp[o1 + r, 1]
            # Parallel faces apart and face to face (equal boxes stacked with a gap) are
            # equally close all along their overlap, and the segment distance names one end
            # of it: a vertex pair straight across the reference face (w x n = 0). That is a
            # face contact, which the clipping below gives with both ends; one point at one
            # corner would hold a symmetric stack unevenly and turn it. Only a vertex pair
            # offset sideways (the vertex lies beyond the face's end) is vertex-vertex.
            if abs(wx * ny - wy * nx) > ACROSS_TOL:
                dist = math.sqrt(wx * wx + wy * wy)  # >= the separation > VERTEX_TOL
                if dist > margin:
                    return none
                px = 0.5 * (wp[o1 + r, 0] + wp[o2 + k, 0])
                py = 0.5 * (wp[o1 + r, 1] + wp[o2 + k, 1])
                fid = FEATURE_VERTEX_VERTEX + (k * 65536 + r if flip else r * 65536 + k)
                ux, uy = sign * wx / dist, sign * wy / dist
                return 1, ux, uy, px, py, -dist, fid, 0.0, 0.0, 0.0, -1

    # 5. clip the incident edge to the reference face's side planes; t runs along the face
    tx, ty = -ny, nx
    upper1 = (v12x - v11x) * tx + (v12y - v11y) * ty  # the face spans [0, upper1] along t
    upper2 = (v21x - v11x) * tx + (v21y - v11y) * ty  # the incident edge runs against t
    lower2 = (v22x - v11x) * tx + (v22y - v11y) * ty
    span = upper2 - lower2
    lx, ly = v22x, v22y
    if lower2 < 0.0 and span > 1e-12:
        f = _clamp01((0.0 - lower2) / span)
        lx, ly = v22x + f * (v21x - v22x), v22y + f * (v21y - v22y)
    ux, uy = v21x, v21y
    if upper2 > upper1 and span > 1e-12:
        f = _clamp01((upper1 - lower2) / span)
        ux, uy = v22x + f * (v21x - v22x), v22y + f * (v21y - v22y)
    sep_l = (lx - v11x) * nx + (ly - v11y) * ny
    sep_u = (ux - v11x) * nx + (uy - v11y) * ny
    # midway between the incident point and the reference face
    lx, ly = lx - 0.5 * sep_l * nx, ly - 0.5 * sep_l * ny
    ux, uy = ux - 0.5 * sep_u * nx, uy - 0.5 * sep_u * ny
    if flip:
        fid_l = i22 * 65536 + i11  # a's vertex first: the same id as from a's face
        fid_u = i21 * 65536 + i12
    else:
        fid_l = i11 * 65536 + i22
        fid_u = i12 * 65536 + i21
    keep_l = sep_l <= margin
    keep_u = sep_u <= margin
    if keep_l and keep_u:
        gx, gy = ux - lx, uy - ly
        if gx * gx + gy * gy < MERGE_TOL * MERGE_TOL:  # one point clipped twice: keep the deeper
            if sep_u < sep_l:
                keep_l = False
            else:
                keep_u = False
    nx, ny = sign * nx, sign * ny
    if keep_l and keep_u:
        return 2, nx, ny, lx, ly, -sep_l, fid_l, ux, uy, -sep_u, fid_u
    if keep_l:
        return 1, nx, ny, lx, ly, -sep_l, fid_l, 0.0, 0.0, 0.0, -1
    if keep_u:
        return 1, nx, ny, ux, uy, -sep_u, fid_u, 0.0, 0.0, 0.0, -1
    return none
