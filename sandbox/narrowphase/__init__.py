"""Narrowphase: contact manifolds for the shape pairs the broadphase found (slides, "Collision
Detection Output": for each contact a point, a normal and a penetration distance).

``collide`` takes the flattened shape arrays of ``docs/architecture.md`` (geometry relative to
each body's centre of mass, in the body frame) and returns a :class:`sandbox.contact.Manifolds`
with at most one manifold per pair and at most two points per manifold:

- ``normal``: unit vector pointing from shape a's body to shape b's body;
- ``point``: world-frame contact points, midway between the two surfaces;
- ``depth``: penetration per point (> 0 overlapping); points with ``depth >= -margin`` are kept,
  so touching shapes give contacts and ``margin > 0`` adds speculative contacts;
- ``feature``: ids that stay the same while the same features touch (0 for circle contacts,
  see :mod:`sandbox.narrowphase.polygons` for polygons); unused second slots hold -1;
- ``friction``, ``restitution``: products of the two shapes' values.

Per pair: circle-circle and polygon-circle in :mod:`~sandbox.narrowphase.circles`,
polygon-polygon in :mod:`~sandbox.narrowphase.polygons`.
"""

from __future__ import annotations

import math

import numpy as np

from sandbox.contact import (
    DEPTH,
    G_FRICTION,
    G_NX,
    G_NY,
    G_POINT,
    G_RESTITUTION,
    G_STRIDE,
    GEOM_COLS,
    I_A,
    I_B,
    I_COUNT,
    I_FEATURE,
    I_SA,
    I_SB,
    INT_COLS,
    X,
    Y,
)
from sandbox.geometry_arrays import (
    P_NX,
    P_NY,
    P_X,
    P_Y,
    S_BODY,
    S_BOUND,
    S_CX,
    S_CY,
    S_FRICTION,
    S_KIND,
    S_RADIUS,
    S_RESTITUTION,
    S_VCOUNT,
    S_VSTART,
)
from sandbox.jit import njit
from sandbox.narrowphase.circles import TINY, circle_circle, polygon_circle
from sandbox.narrowphase.polygons import polygon_polygon

CIRCLE, POLYGON = 0, 1

__all__ = ["CIRCLE", "POLYGON", "collide", "collide_arrays", "collide_packed", "collide_rows"]


@njit
def place_polygons(shape_int, poly, com, cs, wp) -> None:
    """World frame of every polygon's vertices (p + R(c, s) q) and edge normals (R(c, s) n),
    into the rows of ``wp`` (V, 4) that ``poly`` uses: once per shape, not once per pair."""
    for k in range(shape_int.shape[0]):
        if shape_int[k, S_KIND] != POLYGON:
            continue
        b = shape_int[k, S_BODY]
        c, s, px, py = cs[b, 0], cs[b, 1], com[b, 0], com[b, 1]
        v0 = shape_int[k, S_VSTART]
        for v in range(v0, v0 + shape_int[k, S_VCOUNT]):
            qx, qy = poly[v, P_X], poly[v, P_Y]
            wp[v, P_X] = px + c * qx - s * qy
            wp[v, P_Y] = py + s * qx + c * qy
            qx, qy = poly[v, P_NX], poly[v, P_NY]
            wp[v, P_NX] = c * qx - s * qy
            wp[v, P_NY] = s * qx + c * qy


@njit
def _fallback_normal(i, j, bi, bj, com):
    """Normal for coincident circle centres: from body a's centre of mass to body b's, or, when
    those coincide too, +y / -y by shape index (so swapping the pair flips it)."""
    dx = com[bj, 0] - com[bi, 0]
    dy = com[bj, 1] - com[bi, 1]
    d = math.sqrt(dx * dx + dy * dy)
    if d > TINY:
        return dx / d, dy / d
    return 0.0, (1.0 if i < j else -1.0)


@njit
def collide_rows(pairs, npairs, shape_int, shape_float, poly, com, cs, margin, ints, geoms):
    """Contact manifolds of the shape pairs ``pairs[:npairs]`` (packed shape arrays,
    ``sandbox.geometry_arrays``) at the bodies' current poses, written into contact rows
    (``sandbox.contact``: ``ints`` and the narrowphase columns of ``geoms``), at most one per
    pair, in pair order. Returns the number of manifolds.

    Per pair: circle-circle and polygon-circle (:mod:`~sandbox.narrowphase.circles`),
    polygon-polygon (:mod:`~sandbox.narrowphase.polygons`). Everything a pair needs is read
    here and handed on as numbers (and the one array of world-frame polygons): every array a
    compiled helper receives costs a reference count update per call, more than a circle pair's
    arithmetic.
    """
    wp = np.empty((poly.shape[0], 4))
    place_polygons(shape_int, poly, com, cs, wp)
    n = 0
    for q in range(npairs):
        i, j = pairs[q, 0], pairs[q, 1]
        bi, bj = shape_int[i, S_BODY], shape_int[j, S_BODY]
        if bi == bj:  # shapes of one body never collide
            continue
        pxi, pyi, pxj, pyj = com[bi, 0], com[bi, 1], com[bj, 0], com[bj, 1]
        # the shapes lie within circles of radius "bound" about the centres of mass: apart by
        # more than the margin (and a hair, for rounding), they cannot touch
        dx, dy = pxj - pxi, pyj - pyi
        reach = shape_float[i, S_BOUND] + shape_float[j, S_BOUND] + margin
        if dx * dx + dy * dy > reach * reach * (1.0 + 1e-9) + 1e-12:
            continue
        kind_i, kind_j = shape_int[i, S_KIND], shape_int[j, S_KIND]
        ri, rj = shape_float[i, S_RADIUS], shape_float[j, S_RADIUS]
        # circle centres in the world: com + R(cs) q
        ci, si, cj, sj = cs[bi, 0], cs[bi, 1], cs[bj, 0], cs[bj, 1]
        qx, qy = shape_float[i, S_CX], shape_float[i, S_CY]
        cxi, cyi = pxi + ci * qx - si * qy, pyi + si * qx + ci * qy
        qx, qy = shape_float[j, S_CX], shape_float[j, S_CY]
        cxj, cyj = pxj + cj * qx - sj * qy, pyj + sj * qx + cj * qy
        x1 = y1 = d1 = 0.0
        f0 = f1 = 0
        if kind_i == CIRCLE and kind_j == CIRCLE:
            fx = fy = 0.0  # the normal for coincident centres, only worked out when needed
            ex, ey = cxj - cxi, cyj - cyi
            if ex * ex + ey * ey <= 4.0 * TINY * TINY:
                fx, fy = _fallback_normal(i, j, bi, bj, com)
            cnt, nx, ny, x0, y0, d0 = circle_circle(cxi, cyi, ri, cxj, cyj, rj, fx, fy, margin)
        elif kind_j == CIRCLE:
            o, c = shape_int[i, S_VSTART], shape_int[i, S_VCOUNT]
            cnt, nx, ny, x0, y0, d0 = polygon_circle(wp, o, c, cxj, cyj, rj, margin)
        elif kind_i == CIRCLE:
            o, c = shape_int[j, S_VSTART], shape_int[j, S_VCOUNT]
            cnt, nx, ny, x0, y0, d0 = polygon_circle(wp, o, c, cxi, cyi, ri, margin)
            nx, ny = -nx, -ny  # the polygon is shape b: normal from a (circle) to b
        else:
            cnt, nx, ny, x0, y0, d0, f0, x1, y1, d1, f1 = polygon_polygon(
                wp, shape_int[i, S_VSTART], shape_int[i, S_VCOUNT],
                shape_int[j, S_VSTART], shape_int[j, S_VCOUNT], i < j, margin,
            )  # fmt: skip
        if cnt == 0:
            continue
        ints[n, I_A], ints[n, I_B] = bi, bj
        ints[n, I_SA], ints[n, I_SB], ints[n, I_COUNT] = i, j, cnt
        ints[n, I_FEATURE], ints[n, I_FEATURE + 1] = f0, (f1 if cnt == 2 else -1)
        geoms[n, G_NX], geoms[n, G_NY] = nx, ny
        geoms[n, G_FRICTION] = shape_float[i, S_FRICTION] * shape_float[j, S_FRICTION]
        geoms[n, G_RESTITUTION] = shape_float[i, S_RESTITUTION] * shape_float[j, S_RESTITUTION]
        p = G_POINT
        geoms[n, p + X], geoms[n, p + Y], geoms[n, p + DEPTH] = x0, y0, d0
        p = G_POINT + G_STRIDE
        if cnt == 2:
            geoms[n, p + X], geoms[n, p + Y], geoms[n, p + DEPTH] = x1, y1, d1
        else:
            geoms[n, p + X] = geoms[n, p + Y] = geoms[n, p + DEPTH] = 0.0
        n += 1
    return n


@njit
def collide_packed(pairs, shape_int, shape_float, poly, com, cs, margin):
    """:func:`collide_rows` for all ``pairs``, as the manifold arrays
    ``(a, b, sa, sb, normal, count, point, depth, feature, friction, restitution)``."""
    k = pairs.shape[0]
    ints = np.empty((k, INT_COLS), dtype=np.int64)
    geoms = np.empty((k, GEOM_COLS))
    n = collide_rows(pairs, k, shape_int, shape_float, poly, com, cs, margin, ints, geoms)
    normal = np.empty((n, 2))
    point = np.empty((n, 2, 2))
    depth = np.empty((n, 2))
    feature = np.empty((n, 2), dtype=np.int64)
    for i in range(n):
        normal[i, 0], normal[i, 1] = geoms[i, G_NX], geoms[i, G_NY]
        for j in range(2):
            p = G_POINT + G_STRIDE * j
            point[i, j, 0], point[i, j, 1] = geoms[i, p + X], geoms[i, p + Y]
            depth[i, j] = geoms[i, p + DEPTH]
            feature[i, j] = ints[i, I_FEATURE + j]
    return (
        ints[:n, I_A].copy(),
        ints[:n, I_B].copy(),
        ints[:n, I_SA].copy(),
        ints[:n, I_SB].copy(),
        normal,
        ints[:n, I_COUNT].copy(),
        point,
        depth,
        feature,
        geoms[:n, G_FRICTION].copy(),
        geoms[:n, G_RESTITUTION].copy(),
    )


@njit
def collide_arrays(
    pairs,
    shape_body,
    shape_kind,
    shape_radius,
    shape_center,
    shape_vstart,
    shape_vcount,
    verts,
    normals,
    shape_friction,
    shape_restitution,
    com,
    cs,
    margin,
):
    """:func:`collide_packed` on the flattened (unpacked) shape arrays."""
    m, nv = shape_body.shape[0], verts.shape[0]
    shape_int = np.empty((m, 4), dtype=np.int64)
    shape_float = np.empty((m, 8))
    poly = np.empty((nv, 4))
    for i in range(m):
        shape_int[i, S_BODY], shape_int[i, S_KIND] = shape_body[i], shape_kind[i]
        shape_int[i, S_VSTART], shape_int[i, S_VCOUNT] = shape_vstart[i], shape_vcount[i]
        shape_float[i, S_RADIUS] = shape_radius[i]
        shape_float[i, S_CX], shape_float[i, S_CY] = shape_center[i, 0], shape_center[i, 1]
        shape_float[i, S_FRICTION] = shape_friction[i]
        shape_float[i, S_RESTITUTION] = shape_restitution[i]
        shape_float[i, S_BOUND] = np.inf
    for v in range(nv):
        poly[v, P_X], poly[v, P_Y] = verts[v, 0], verts[v, 1]
        poly[v, P_NX], poly[v, P_NY] = normals[v, 0], normals[v, 1]
    return collide_packed(pairs, shape_int, shape_float, poly, com, cs, margin)


def collide(
    pairs: np.ndarray,
    shape_body: np.ndarray,
    shape_kind: np.ndarray,
    shape_radius: np.ndarray,
    shape_center: np.ndarray,
    shape_vstart: np.ndarray,
    shape_vcount: np.ndarray,
    verts: np.ndarray,
    normals: np.ndarray,
    shape_friction: np.ndarray,
    shape_restitution: np.ndarray,
    com: np.ndarray,
    cs: np.ndarray,
    margin: float = 0.0,
):
    """Contact manifolds of the shape ``pairs`` ((k, 2) shape indices) at the bodies' current
    poses (``com`` (n, 2) in m, ``cs`` (n, 2) the (cos, sin) of each body's angle).

    Returns a :class:`sandbox.contact.Manifolds`; ``margin`` (m) keeps contacts whose gap is up
    to ``margin`` (speculative contacts), 0 keeps overlapping and touching shapes only.
    """
    from sandbox.contact import Manifolds

    pairs = np.ascontiguousarray(pairs, dtype=np.int64).reshape(-1, 2)
    arrays = collide_arrays(
        pairs,
        np.ascontiguousarray(shape_body, dtype=np.int64),
        np.ascontiguousarray(shape_kind, dtype=np.int64),
        np.ascontiguousarray(shape_radius, dtype=np.float64),
        np.ascontiguousarray(shape_center, dtype=np.float64).reshape(-1, 2),
        np.ascontiguousarray(shape_vstart, dtype=np.int64),
        np.ascontiguousarray(shape_vcount, dtype=np.int64),
        np.ascontiguousarray(verts, dtype=np.float64).reshape(-1, 2),
        np.ascontiguousarray(normals, dtype=np.float64).reshape(-1, 2),
        np.ascontiguousarray(shape_friction, dtype=np.float64),
        np.ascontiguousarray(shape_restitution, dtype=np.float64),
        np.ascontiguousarray(com, dtype=np.float64).reshape(-1, 2),
        np.ascontiguousarray(cs, dtype=np.float64).reshape(-1, 2),
        float(margin),
    )
    return Manifolds(*arrays)
