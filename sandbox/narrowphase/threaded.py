"""The narrowphase on all cores, with the very same result as on one
(:func:`sandbox.narrowphase.collide_into`).

Pair ``q``'s manifold is worked out on whichever thread numba gives it, into record ``q`` of
the contact buffer (which has a row for every pair); then one thread moves the manifolds found
down to the front, in pair order. Every manifold is computed by the same code from the same
inputs, and the list comes out in the same order, so the step that follows is bit-identical to
the one-thread step.
"""

from __future__ import annotations

import numba

from sandbox.jit import njit
from sandbox.narrowphase import collide_slot, place_polygons


@njit(parallel=True)
def collide_slots(pairs, npairs: int, shapes, wp, bodies, joints, margin: float, contacts) -> None:
    """Pair q's manifold into ``contacts[q]`` (count 0 when none), pairs shared among threads."""
    for q in numba.prange(npairs):
        if not collide_slot(q, pairs, shapes, wp, bodies, joints, margin, contacts[q]):
            contacts[q]["count"] = 0


@njit
def move_manifold(contacts, q: int, k: int) -> None:
    """Copy what the narrowphase writes of record q into record k."""
    c, d = contacts[q], contacts[k]
    d["a"], d["b"], d["shape_a"], d["shape_b"] = c["a"], c["b"], c["shape_a"], c["shape_b"]
    d["count"] = c["count"]
    d["normal"][0], d["normal"][1] = c["normal"][0], c["normal"][1]
    d["friction"], d["restitution"] = c["friction"], c["restitution"]
    for m in range(2):
        p, r = c["points"][m], d["points"][m]
        r["point"][0], r["point"][1] = p["point"][0], p["point"][1]
        r["depth"], r["feature"] = p["depth"], p["feature"]


@njit
def collide_threaded(pairs, npairs, shapes, vertices, bodies, joints, margin, contacts) -> int:
    """:func:`sandbox.narrowphase.collide_into` with the pairs shared among numba's threads;
    ``contacts`` needs a row for every pair. Returns how many manifolds were written."""
    wp = place_polygons(shapes, vertices, bodies)
    collide_slots(pairs, npairs, shapes, wp, bodies, joints, margin, contacts)
    k = 0
    for q in range(npairs):
        if contacts[q]["count"] > 0:
            if k != q:
                move_manifold(contacts, q, k)
            k += 1
    return k
