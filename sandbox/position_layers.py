"""The order of the penetration fix's passes, and layers for piles that need them
(``settings.robust_positions``: shock propagation on positions, :mod:`sandbox.penetration`).

Most steps visit the contacts colour by colour (:mod:`sandbox.solvers.wide_positions`). A step
where a contact began deep in overlap, or where touching bodies differ much in mass
(:func:`needs_layers`), sorts the bodies into layers from the fixed ones up and visits the
contacts from the ground up; a lower body is held under a much heavier upper one
(:func:`holds`), so that nothing pushes a light box out from under a heavy one.
"""

from __future__ import annotations

import numpy as np

from sandbox.jit import njit
from sandbox.solvers.shock import contact_layers, hold_lower, touching
from sandbox.solvers.soft import excess_depth
from sandbox.solvers.wide_positions import plan

HOLD_RATIO = 2.0  # layered passes hold a lower body only under one more than this times heavier


@njit
def position_order(contacts, k: int, bodies, layered: bool, gap: float, bounds, wide: bool):
    """``((order, layer), lanes)``: the order the passes visit the contacts, each body's layer,
    and the lanes of the wide passes (``wide``:
    :func:`sandbox.penetration.wide_position_impulses`, and the order then lists only the
    contacts the lanes leave; else the lanes are empty).

    Layered (``settings.robust_positions``, shock propagation on positions): bodies are sorted
    into layers from the fixed ones up (:func:`sandbox.solvers.shock.contact_layers`) and the
    contacts visited from the ground up (layers over the contacts closer than ``gap``, m: the
    contact margin without what a large dt adds to it). In a contact between two layers where
    the upper body is much the heavier, only it moves (:func:`holds`): nothing pushes a light
    box out from under a heavy one, or a box into the ground. Otherwise every body
    is in one layer and the contacts are visited colour by colour, then the others in the
    velocity sweeps' order (:func:`sandbox.solvers.wide_positions.plan`); ``bounds`` = (slop,
    push) (m), as :func:`~sandbox.solvers.wide_positions.allowed_separation`."""
    if not layered:
        order, lanes, owners, starts, alone = plan(contacts, k, bodies, bounds, wide)
        layering = order, np.zeros(bodies.shape[0], dtype=np.int64)
        return layering, (lanes, owners, starts, alone)
    layer = contact_layers(contacts, k, bodies, gap)
    n = bodies.shape[0]
    key = np.empty(k, dtype=np.int64)
    for i in range(k):
        la, lb = min(layer[contacts[i]["a"]], n), min(layer[contacts[i]["b"]], n)
        key[i] = 2 * max(la, lb) + (la == lb)  # (0, 1), then (1, 1), then (1, 2), ...
    none = np.zeros(0, dtype=np.int64)
    lanes = (np.zeros(0), np.zeros((3, 0), dtype=np.int64), np.zeros(1, dtype=np.int64), none)
    return (counting_order(key, 2 * n + 2), layer), lanes


@njit
def counting_order(key, top: int):
    """The stable order of ``key`` (ints in [0, top)): a counting sort, O(len(key) + top),
    the same order as ``np.argsort(key, kind="stable")``."""
    start = np.zeros(top + 1, dtype=np.int64)
    for i in range(key.shape[0]):
        start[key[i] + 1] += 1
    for v in range(top):
        start[v + 1] += start[v]
    order = np.empty(key.shape[0], dtype=np.int64)
    for i in range(key.shape[0]):
        order[start[key[i]]] = i
        start[key[i]] += 1
    return order


@njit
def needs_layers(contacts, k: int, bodies, triggers, gap: float) -> bool:
    """Whether this step's position passes must go in layers (``settings.robust_positions``).
    ``triggers`` = (deep (m), heavier): a contact began the step more than ``deep`` (the slop
    plus the bounded push) into overlap beyond its load's sag
    (:func:`sandbox.solvers.soft.excess_depth`), or, when ``heavier`` (not in the soft step),
    two touching bodies differ in mass more than ``HOLD_RATIO`` times. Otherwise the layered
    passes would do what the classic ones do (no overlap for the bounded push, no body to
    hold), so the classic ones run: the same results, without sorting into layers."""
    depth, heavier = triggers
    for i in range(k):
        c = contacts[i]
        if not touching(c, gap):
            continue
        for j in range(c["count"]):
            p = c["points"][j]
            if p["depth"] > depth and excess_depth(c, p) > depth:
                return True
        if not heavier:
            continue
        im_a, im_b = bodies[c["a"]]["inv_mass"], bodies[c["b"]]["inv_mass"]
        if im_a > 0.0 and im_b > 0.0 and max(im_a, im_b) > HOLD_RATIO * min(im_a, im_b):
            return True
    return False


@njit
def position_masses(c, bodies, layer):
    """((1/m_a, 1/I_a, 1/m_b, 1/I_b), held) for the position passes: the bodies' own, except
    that the lower body of two layers is held (:func:`sandbox.solvers.shock.hold_lower`) when
    :func:`holds` says so (under a body more than ``HOLD_RATIO`` times heavier, which would
    otherwise squeeze it out)."""
    a, b = bodies[c["a"]], bodies[c["b"]]
    mass = (a["inv_mass"], a["inv_moment"], b["inv_mass"], b["inv_moment"])
    if not holds(c, bodies, layer):
        return mass, False
    return hold_lower(mass, layer[c["a"]], layer[c["b"]]), True


@njit
def holds(c, bodies, layer) -> bool:
    """Whether the layered passes hold the lower body of contact ``c``: it is in a lower layer
    and cannot move anyway (the ground), or the upper body is more than ``HOLD_RATIO`` times
    heavier. Between bodies of like mass both move, as in the classic pass: held, each layer
    would carry its whole overlap up to the next, and a tall pile of equal boxes would sink a
    slop per row (a pyramid of 40: 173 mm instead of 130). Layers are only made in a step that
    needs them (:func:`needs_layers`)."""
    la, lb = layer[c["a"]], layer[c["b"]]
    if la == lb:
        return False
    upper, lower = (bodies[c["b"]], bodies[c["a"]]) if la < lb else (bodies[c["a"]], bodies[c["b"]])
    return lower["inv_mass"] == 0.0 or upper["inv_mass"] * HOLD_RATIO < lower["inv_mass"]
