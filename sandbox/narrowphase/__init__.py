"""Narrowphase: contact manifolds for the shape pairs the broadphase found (slides, "Collision
Detection Output": for each contact a point, a normal and a penetration distance).

:func:`collide_into` writes one :data:`sandbox.records.CONTACT` record per touching pair of
shapes (geometry about each body's centre of mass, in the body frame), at most two points each:

- ``normal``: unit vector pointing from shape a's body to shape b's body;
- ``points[j]["point"]``: world-frame contact points, midway between the two surfaces;
- ``points[j]["depth"]``: penetration per point (> 0 overlapping); points with ``depth >= -margin`` are kept,
  so touching shapes give contacts and ``margin > 0`` adds speculative contacts;
- ``points[j]["feature"]``: ids that stay the same while the same features touch (0 for circle contacts,
  see :mod:`sandbox.narrowphase.polygons` for polygons); unused second slots hold -1;
- ``friction``, ``restitution``: products of the two shapes' values.

Per pair: circle-circle and polygon-circle in :mod:`~sandbox.narrowphase.circles`,
polygon-polygon in :mod:`~sandbox.narrowphase.polygons`.
"""

from __future__ import annotations

import math

import numpy as np

from sandbox.borrowed import borrowed
from sandbox.jit import njit
from sandbox.manifolds import Manifolds
from sandbox.math2d import rotate
from sandbox.narrowphase.circles import TINY, circle_circle, polygon_circle
from sandbox.narrowphase.polygons import polygon_polygon
from sandbox.records import CIRCLE, CONTACT, JOINT, POLYGON
from sandbox.speculative import closing_reach

__all__ = ["collide", "collide_into", "joined"]


@njit
def place_polygons(shapes, vertices, bodies):
    """World frame of every polygon's vertices (p + R q) and edge normals (R n), as rows
    ``[x, y, nx, ny]`` (V, 4) in the order of ``vertices``: once per shape, not once per pair."""
    wp = np.empty((vertices.shape[0], 4))
    for k in range(shapes.shape[0]):
        shape = shapes[k]
        if shape["kind"] != POLYGON:
            continue
        body = bodies[shape["body"]]
        c, s = body["cs"][0], body["cs"][1]
        first = shape["first_vertex"]
        for v in range(first, first + shape["vertex_count"]):
            q, n = vertices[v]["point"], vertices[v]["normal"]
            x, y = rotate(c, s, q[0], q[1])
            wp[v, 0], wp[v, 1] = body["com"][0] + x, body["com"][1] + y
            wp[v, 2], wp[v, 3] = rotate(c, s, n[0], n[1])
    return wp


@njit
def joined(joints, n_bodies: int, a: int, b: int) -> bool:
    """Whether bodies a and b share a joint (binary search of ``joints["sorted_key"]``):
    joined bodies do not collide (as in the pymunk bridge)."""
    key = min(a, b) * n_bodies + max(a, b)
    lo, hi = 0, joints.shape[0]
    while lo < hi:
        mid = (lo + hi) // 2
        if joints[mid]["sorted_key"] < key:
            lo = mid + 1
        else:
            hi = mid
    return lo < joints.shape[0] and joints[lo]["sorted_key"] == key


@njit
def circle_center(shape, body) -> tuple[float, float]:
    """World centre of a circle shape: com + R q."""
    x, y = rotate(body["cs"][0], body["cs"][1], shape["center"][0], shape["center"][1])
    return body["com"][0] + x, body["com"][1] + y


@njit
def fallback_normal(i: int, j: int, body_i, body_j) -> tuple[float, float]:
    """Normal for coincident circle centres: from body a's centre of mass to body b's, or, when
    those coincide too, +y / -y by shape index (so swapping the pair flips it)."""
    dx = body_j["com"][0] - body_i["com"][0]
    dy = body_j["com"][1] - body_i["com"][1]
    d = math.sqrt(dx * dx + dy * dy)
    if d > TINY:
        return dx / d, dy / d
    return 0.0, (1.0 if i < j else -1.0)


@njit
def within_reach(shape_i, shape_j, body_i, body_j, margin: float) -> bool:
    """The shapes lie within circles of radius ``bound`` about the centres of mass: apart by
    more than the margin (and a hair, for rounding), they cannot touch."""
    com_i, com_j = body_i["com"], body_j["com"]
    dx, dy = com_j[0] - com_i[0], com_j[1] - com_i[1]
    reach = shape_i["bound"] + shape_j["bound"] + margin
    return dx * dx + dy * dy <= reach * reach * (1.0 + 1e-9) + 1e-12


@njit(inline="always")
def circles_pair(i, j, shape_pair, body_pair, margin):
    """The manifold of circles i and j, as :func:`collide_pair` gives it. Without ``wp``: the
    loop over pairs calls this for two circles, and inlined, ``wp`` is reference-counted
    (numba's runtime, an atomic add coming in and going out) wherever it is an argument, which
    took about a tenth of the narrowphase's time on the rain of 5,000 discs (279 against 257 us)."""
    (shape_i, shape_j), (body_i, body_j) = shape_pair, body_pair
    xi, yi = circle_center(shape_i, body_i)
    xj, yj = circle_center(shape_j, body_j)
    fx = fy = 0.0  # the normal for coincident centres, only worked out when needed
    if (xj - xi) ** 2 + (yj - yi) ** 2 <= 4.0 * TINY * TINY:
        fx, fy = fallback_normal(i, j, body_i, body_j)
    count, nx, ny, x0, y0, d0 = circle_circle(
        xi, yi, shape_i["radius"], xj, yj, shape_j["radius"], fx, fy, margin
    )
    return count, nx, ny, x0, y0, d0, 0, 0.0, 0.0, 0.0, -1


# inlined into the loop over pairs: as a call it took two fifths of the narrowphase (the manifold
# returned through memory, wp reference-counted coming in and going out). The two shapes and
# bodies come as records, not as the arrays they are rows of: an array handed to an inlined
# function is reference-counted on every pair (pyramid of base 40: 230 against 197 us)
@njit(inline="always")
def collide_pair(i, j, shape_pair, body_pair, wp, margin):
    """The manifold of shapes i and j: ``(count, nx, ny, x0, y0, d0, f0, x1, y1, d1, f1)``.
    ``shape_pair``: their SHAPE records; ``body_pair``: their bodies' BODY records.

    Circle-circle (:func:`circles_pair`) and polygon-circle (:mod:`~sandbox.narrowphase.circles`),
    polygon-polygon (:mod:`~sandbox.narrowphase.polygons`)."""
    (shape_i, shape_j), (body_i, body_j) = shape_pair, body_pair
    if shape_i["kind"] == CIRCLE and shape_j["kind"] == CIRCLE:
        return circles_pair(i, j, shape_pair, body_pair, margin)
    if shape_j["kind"] == CIRCLE:
        xj, yj = circle_center(shape_j, body_j)
        first, n = shape_i["first_vertex"], shape_i["vertex_count"]
        count, nx, ny, x0, y0, d0 = polygon_circle(wp, first, n, xj, yj, shape_j["radius"], margin)
        return count, nx, ny, x0, y0, d0, 0, 0.0, 0.0, 0.0, -1
    if shape_i["kind"] == CIRCLE:
        xi, yi = circle_center(shape_i, body_i)
        first, n = shape_j["first_vertex"], shape_j["vertex_count"]
        count, nx, ny, x0, y0, d0 = polygon_circle(wp, first, n, xi, yi, shape_i["radius"], margin)
        return count, -nx, -ny, x0, y0, d0, 0, 0.0, 0.0, 0.0, -1  # the normal from a to b
    return polygon_polygon(
        wp,
        shape_i["first_vertex"],
        shape_i["vertex_count"],
        shape_j["first_vertex"],
        shape_j["vertex_count"],
        i < j,
        margin,
    )


@njit(python=True)
def collide_into(pairs, npairs, shapes, vertices, bodies, joints, reach, contacts) -> int:
    """Contact manifolds of the shape pairs ``pairs[:npairs]`` at the bodies' current poses,
    written in pair order into ``contacts`` (CONTACT records), at most one per pair; pairs of
    one body, of joined bodies or out of reach are skipped. Returns how many were written.

    ``reach`` = (margin (m), look-ahead (s)) keeps points with a gap up to the margin
    (speculative contacts), and up to as far as the pair can close in the look-ahead beyond it
    (:func:`sandbox.speculative.closing_reach`; 0 s: the margin alone).

    The skips are written out in the loop, each a ``continue``: gathered into a function that
    returns early (inlined by numba or not), the same arithmetic took 1.5 times as long on
    rain's 2,783 circle pairs (160 against 107 us, measured; the difference is in the machine
    code numba makes of the two shapes of loop)."""
    wp = place_polygons(shapes, vertices, bodies)
    return collide_placed(pairs, npairs, shapes, wp, bodies, joints, reach, contacts)


@njit
def collide_placed(pairs, npairs, shapes, wp, bodies, joints, reach, contacts) -> int:
    """:func:`collide_into`'s loop over the pairs, the polygons placed (``wp``, from
    :func:`place_polygons`). The polygon functions get ``wp`` at every pair, inlined: as a
    view numba counts no references to (:func:`sandbox.borrowed.borrowed`), 4,760 atomic adds a
    step fewer on the pyramid of base 40 (the narrowphase 227 -> 174 us). ``wp`` is this
    function's argument, so the caller keeps it alive while the view is used."""
    wp = borrowed(wp)
    base, ahead = reach
    k = 0
    for q in range(npairs):  # contacts[k] exists: k <= q < npairs <= len(contacts)
        i, j = pairs[q, 0], pairs[q, 1]
        shape_i, shape_j = shapes[i], shapes[j]
        a, b = shape_i["body"], shape_j["body"]
        body_a, body_b = bodies[a], bodies[b]
        margin = base + closing_reach(body_a, shape_i, body_b, shape_j, ahead)
        if a == b or not within_reach(shape_i, shape_j, body_a, body_b, margin):
            continue  # one body's shapes, or too far apart to touch
        if joints.shape[0] > 0 and joined(joints, bodies.shape[0], a, b):
            continue  # joined bodies do not collide
        shape_pair, body_pair = (shape_i, shape_j), (body_a, body_b)
        if shape_i["kind"] == CIRCLE and shape_j["kind"] == CIRCLE:  # without wp (circles_pair)
            manifold = circles_pair(i, j, shape_pair, body_pair, margin)
        else:
            manifold = collide_pair(i, j, shape_pair, body_pair, wp, margin)
        if manifold[0] > 0:
            write_manifold(contacts[k], i, j, shapes, manifold)
            k += 1
    return k


@njit
def write_manifold(c, i: int, j: int, shapes, manifold) -> None:
    """Shape pair (i, j)'s manifold (:func:`collide_pair`) into the CONTACT record ``c``:
    the bodies, the normal, the mixed friction and restitution, both point slots (an unused
    second slot as :func:`collide_pair` gives it: zeros and feature -1)."""
    count, nx, ny, x0, y0, d0, f0, x1, y1, d1, f1 = manifold
    shape_i, shape_j = shapes[i], shapes[j]
    c["a"], c["b"], c["shape_a"], c["shape_b"] = shape_i["body"], shape_j["body"], i, j
    c["count"] = count
    c["normal"][0], c["normal"][1] = nx, ny
    c["friction"] = shape_i["friction"] * shape_j["friction"]
    c["restitution"] = shape_i["restitution"] * shape_j["restitution"]
    p = c["points"][0]
    point = p["point"]
    point[0], point[1], p["depth"], p["feature"] = x0, y0, d0, f0
    p = c["points"][1]
    point = p["point"]
    point[0], point[1], p["depth"], p["feature"] = x1, y1, d1, f1


def collide(pairs, shapes, vertices, bodies, margin: float = 0.0, joints=None):
    """Contact manifolds of the shape ``pairs`` ((k, 2) shape indices) at the bodies' poses:
    a :class:`sandbox.contact.Manifolds` over new CONTACT records. ``shapes``, ``vertices``,
    ``bodies``: SHAPE, VERTEX and BODY records (``bodies`` needs ``com`` and ``cs``);
    ``margin`` (m) keeps contacts whose gap is up to ``margin``, 0 keeps touching shapes."""
    pairs = np.ascontiguousarray(pairs, dtype=np.int64).reshape(-1, 2)
    contacts = np.zeros(len(pairs), dtype=CONTACT)
    joints = np.zeros(0, dtype=JOINT) if joints is None else joints
    reach = (float(margin), 0.0)
    k = collide_into(pairs, len(pairs), shapes, vertices, bodies, joints, reach, contacts)
    return Manifolds(contacts, k)
