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

from sandbox.jit import njit
from sandbox.narrowphase.circles import TINY, circle_circle, polygon_circle
from sandbox.narrowphase.polygons import polygon_polygon

CIRCLE, POLYGON = 0, 1

__all__ = ["CIRCLE", "POLYGON", "collide", "collide_arrays"]


@njit
def _place_polygon(verts, normals, v0, count, c, s, px, py, wv, wn):
    """World frame of a polygon's vertices (p + R(c, s) q) and normals (R(c, s) n) into wv, wn.

    (Only a few arrays are passed on purpose: every array argument of a compiled call costs a
    reference count update, which here would cost more than the arithmetic.)"""
    for v in range(count):
        qx, qy = verts[v0 + v, 0], verts[v0 + v, 1]
        wv[v, 0] = px + c * qx - s * qy
        wv[v, 1] = py + s * qx + c * qy
        qx, qy = normals[v0 + v, 0], normals[v0 + v, 1]
        wn[v, 0] = c * qx - s * qy
        wn[v, 1] = s * qx + c * qy


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
    """Compiled kernel of :func:`collide`: the manifold arrays as a tuple
    ``(a, b, sa, sb, normal, count, point, depth, feature, friction, restitution)``."""
    k = pairs.shape[0]
    vmax = 1
    for q in range(k):
        vmax = max(vmax, shape_vcount[pairs[q, 0]], shape_vcount[pairs[q, 1]])
    # world-frame scratch for the two shapes of the current pair
    wv_i, wn_i = np.empty((vmax, 2)), np.empty((vmax, 2))
    wv_j, wn_j = np.empty((vmax, 2)), np.empty((vmax, 2))
    out_a = np.empty(k, dtype=np.int64)
    out_b = np.empty(k, dtype=np.int64)
    out_sa = np.empty(k, dtype=np.int64)
    out_sb = np.empty(k, dtype=np.int64)
    normal = np.empty((k, 2))
    count = np.empty(k, dtype=np.int64)
    point = np.zeros((k, 2, 2))
    depth = np.zeros((k, 2))
    feature = np.full((k, 2), -1, dtype=np.int64)
    friction = np.empty(k)
    restitution = np.empty(k)
    n = 0
    for q in range(k):
        i, j = pairs[q, 0], pairs[q, 1]
        bi, bj = shape_body[i], shape_body[j]
        if bi == bj:  # shapes of one body never collide
            continue
        # world transform of a body-frame point q: com + R(cs) q
        ci, si, pxi, pyi = cs[bi, 0], cs[bi, 1], com[bi, 0], com[bi, 1]
        cj, sj, pxj, pyj = cs[bj, 0], cs[bj, 1], com[bj, 0], com[bj, 1]
        qx, qy = shape_center[i, 0], shape_center[i, 1]
        cxi, cyi = pxi + ci * qx - si * qy, pyi + si * qx + ci * qy
        qx, qy = shape_center[j, 0], shape_center[j, 1]
        cxj, cyj = pxj + cj * qx - sj * qy, pyj + sj * qx + cj * qy
        ni, nj = shape_vcount[i], shape_vcount[j]
        if shape_kind[i] == POLYGON:
            _place_polygon(verts, normals, shape_vstart[i], ni, ci, si, pxi, pyi, wv_i, wn_i)
        if shape_kind[j] == POLYGON:
            _place_polygon(verts, normals, shape_vstart[j], nj, cj, sj, pxj, pyj, wv_j, wn_j)
        ri, rj = shape_radius[i], shape_radius[j]
        x1 = y1 = d1 = 0.0
        f0 = f1 = 0
        if shape_kind[i] == CIRCLE and shape_kind[j] == CIRCLE:
            fx, fy = _fallback_normal(i, j, bi, bj, com)
            cnt, nx, ny, x0, y0, d0 = circle_circle(cxi, cyi, ri, cxj, cyj, rj, fx, fy, margin)
        elif shape_kind[j] == CIRCLE:
            cnt, nx, ny, x0, y0, d0 = polygon_circle(wv_i, wn_i, ni, cxj, cyj, rj, margin)
        elif shape_kind[i] == CIRCLE:
            cnt, nx, ny, x0, y0, d0 = polygon_circle(wv_j, wn_j, nj, cxi, cyi, ri, margin)
            nx, ny = -nx, -ny  # the polygon is shape b: normal from a (circle) to b
        else:
            cnt, nx, ny, x0, y0, d0, f0, x1, y1, d1, f1 = polygon_polygon(
                wv_i, wn_i, ni, wv_j, wn_j, nj, i < j, margin
            )
        if cnt == 0:
            continue
        out_a[n], out_b[n], out_sa[n], out_sb[n] = bi, bj, i, j
        normal[n, 0], normal[n, 1] = nx, ny
        count[n] = cnt
        point[n, 0, 0], point[n, 0, 1], depth[n, 0], feature[n, 0] = x0, y0, d0, f0
        if cnt == 2:
            point[n, 1, 0], point[n, 1, 1], depth[n, 1], feature[n, 1] = x1, y1, d1, f1
        friction[n] = shape_friction[i] * shape_friction[j]
        restitution[n] = shape_restitution[i] * shape_restitution[j]
        n += 1
    return (
        out_a[:n],
        out_b[:n],
        out_sa[:n],
        out_sb[:n],
        normal[:n],
        count[:n],
        point[:n],
        depth[:n],
        feature[:n],
        friction[:n],
        restitution[:n],
    )


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
