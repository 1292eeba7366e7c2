"""Wide position passes: the penetration fix's position impulses (``settings.penetration``
``impulse``, Box2D's non-linear Gauss-Seidel; :func:`sandbox.penetration.position_impulses`)
eight contacts at a time, as the velocity sweeps are (:mod:`sandbox.solvers.wide`).

A position pass visits the contacts one after another and moves their bodies as it goes; any
fixed order is a valid pass. The contacts with two points are coloured as for the velocity
sweeps, except that a body moves when its own inverse mass or moment is not zero (the passes
push with the bodies' own masses: :func:`sandbox.position_layers.position_masses`). A pass is
then each colour's contacts, eight at a time, then the others (one point, or no colour left)
one by one in :func:`sandbox.solvers.iterative.visit` order. :func:`order` lists that order,
and the passes over the records follow it where the lanes do not run (uncompiled; the half
and mass-weighted options), so every path gives the same numbers. A world without two-point
contacts (discs) is passed over in the very same order as before the lanes.

Each point's push is :func:`sandbox.solvers.impulses.push_point`, the same function the
record pass calls. Layout, as the velocity lanes': lane ``l`` of field ``F`` of the block
starting at ``i`` is ``lanes[i + F + l]``. A lane holds its bodies' inverse masses, the
normal, both bodies' poses while the colour is visited (:func:`sandbox.math2d.pose_of`), the
smallest separation it saw, whether it pushed and the overlap it met
(:func:`~sandbox.solvers.impulses.overlap_left`), then for each point its place on each
body, its depth when the step began and the separation it may keep
(:func:`allowed_separation`, fixed for the step).

The passes ran about :data:`MEASURED` on the settled pyramid of base 40.
"""

from __future__ import annotations

import numpy as np

from sandbox.jit import OFF, ON, njit
from sandbox.math2d import pose_of, set_pose
from sandbox.solvers.impulses import overlap_left, push_point
from sandbox.solvers.iterative import visit
from sandbox.solvers.soft import excess_depth
from sandbox.solvers.wide import COLOURS, LANES, _offsets, colour, groups, has_two_points, place

MEASURED = "one pass of 2,369 contacts: 23 us eight at a time against 70 us one by one"

IM_A, II_A, IM_B, II_B, NX, NY, *_rest = _offsets(20)
AX, AY, AC, AS, ATURN, BX, BY, BC, BS, BTURN, WORST, MOVED, OVERLAP, P0 = _rest  # pose_of
POINT_FIELDS = LAX, LAY, LBX, LBY, DEPTH, ALLOWED = _offsets(6)  # from P0 or P1 on
P1 = P0 + np.uint64(len(POINT_FIELDS) * LANES)
FIELDS = int(P1) // LANES + len(POINT_FIELDS)
BLOCK = FIELDS * LANES
POSE_A = (AX, AY, AC, AS, ATURN)
POSE_B = (BX, BY, BC, BS, BTURN)


@njit
def allowed_separation(c, p, slop: float, push: float) -> float:
    """The separation a point is pushed out to this step (m): -slop, except that an overlap
    already there when the step began comes out by at most ``push`` (m, ``max_push_speed``
    times dt), so bodies spawned inside one another separate at a bounded speed instead of
    being fired apart (and through the ground). What the step's own motion pushed in is taken
    out entirely. ``push`` is infinite unless ``settings.robust_positions`` is on. (The
    position stage's, :mod:`sandbox.penetration`; here, where the lanes are packed with it.)"""
    if p["depth"] <= slop + push:  # the usual case: no load sag to look up (it only lowers it)
        return -slop
    return min(-slop, -excess_depth(c, p) + push)


@njit
def plan(contacts, k: int, bodies, bounds, wide: bool):
    """The order of a pass and, when ``wide``, its lanes: ``(order, lanes, owners, starts,
    alone)``. ``order``: the contacts in lanes order (colour by colour), then ``alone`` (the
    others) in :func:`~sandbox.solvers.iterative.visit` order; when ``wide``, only the latter
    (the lanes take the rest). ``owners`` and ``starts`` as
    :func:`sandbox.solvers.wide.place` (an empty lane: contact -1, bodies the row of
    :func:`take_poses` no body uses); ``lanes`` packed (:func:`pack`; ``bounds`` = (slop,
    push) (m), as :func:`allowed_separation`)."""
    if not has_two_points(contacts, k):  # no lanes (discs): the visit order, nothing placed
        order = np.empty(k, dtype=np.int64)
        half = (k + 1) // 2
        for r in range(k):
            order[r] = visit(r, half)
        owners = np.empty((3, 0), dtype=np.int64)
        return order, np.empty(0), owners, np.zeros(1, dtype=np.int64), np.arange(k)
    colours = np.empty(k, dtype=np.int64)
    ends = np.empty((4, k), dtype=np.int64)
    count = colour(contacts, k, bodies, colours, ON, OFF, ends)
    blocks = (k + LANES - 1) // LANES + count
    owners = np.empty((3, blocks * LANES), dtype=np.int64)
    starts = np.empty(count + 1, dtype=np.int64)
    blocks = place(
        ends, k, groups(ends, k, colours, count, 2, False), count, owners, len(bodies), starts
    )
    alone = np.nonzero(colours == COLOURS)[0]
    q = 0 if wide else k - len(alone)
    order = np.empty(q + len(alone), dtype=np.int64)
    if not wide:
        q = 0
        for lane in range(blocks * LANES):
            if owners[0, lane] >= 0:
                order[q] = owners[0, lane]
                q += 1
    half = (len(alone) + 1) // 2
    for r in range(len(alone)):
        order[q + r] = alone[visit(r, half)]
    lanes = np.empty(blocks * BLOCK if wide else 0)
    if wide:
        pack(contacts, bodies, lanes, owners, blocks, bounds)
    return order, lanes, owners, starts, alone


@njit
def pack(contacts, bodies, lanes, owners, blocks: int, bounds) -> None:
    """Each contact's fixed fields into its lane (``bounds`` as :func:`plan`); empty lanes get
    zeros (no mass, no depth: they push nothing)."""
    slop, push = bounds
    for q in range(blocks * LANES):
        i = np.uint64(q // LANES) * np.uint64(BLOCK) + np.uint64(q % LANES)
        ci = owners[0, q]
        if ci < 0:
            for f in range(FIELDS):
                lanes[i + np.uint64(f * LANES)] = 0.0
            continue
        c = contacts[ci]
        a, b = bodies[c["a"]], bodies[c["b"]]  # their own masses, as the record pass
        lanes[i + IM_A], lanes[i + II_A] = a["inv_mass"], a["inv_moment"]
        lanes[i + IM_B], lanes[i + II_B] = b["inv_mass"], b["inv_moment"]
        lanes[i + NX], lanes[i + NY] = c["normal"][0], c["normal"][1]
        # both points used (only those get a colour), each written out: a loop over the two
        # took half as long again
        p, base = c["points"][0], i + P0
        lanes[base + LAX], lanes[base + LAY] = p["local_a"][0], p["local_a"][1]
        lanes[base + LBX], lanes[base + LBY] = p["local_b"][0], p["local_b"][1]
        lanes[base + DEPTH] = p["anchor_depth"]
        lanes[base + ALLOWED] = allowed_separation(c, p, slop, push)
        p, base = c["points"][1], i + P1
        lanes[base + LAX], lanes[base + LAY] = p["local_a"][0], p["local_a"][1]
        lanes[base + LBX], lanes[base + LBY] = p["local_b"][0], p["local_b"][1]
        lanes[base + DEPTH] = p["anchor_depth"]
        lanes[base + ALLOWED] = allowed_separation(c, p, slop, push)


@njit(error_model="numpy")  # a division by k = 0 (an empty lane) gives a number left unused
def visit_block(lanes, start, beta: float) -> None:
    """One push of each point of the block's contacts (``start``: the block's first number),
    the first point and then the second, as the record pass does. As
    :func:`sandbox.solvers.wide.visit_blocks`, the loop reads and writes ``lanes`` itself, so
    it runs as vector instructions; a push that does not happen is one of zero."""
    for lane in range(LANES):
        i = start + np.uint64(lane)
        mass = lanes[i + IM_A], lanes[i + II_A], lanes[i + IM_B], lanes[i + II_B]
        n = lanes[i + NX], lanes[i + NY]
        pa = lanes[i + AX], lanes[i + AY], lanes[i + AC], lanes[i + AS], lanes[i + ATURN]
        pb = lanes[i + BX], lanes[i + BY], lanes[i + BC], lanes[i + BS], lanes[i + BTURN]
        b0, b1 = i + P0, i + P1
        point = (
            (lanes[b0 + LAX], lanes[b0 + LAY]),
            (lanes[b0 + LBX], lanes[b0 + LBY]),
            lanes[b0 + DEPTH],
            lanes[b0 + ALLOWED],
        )
        pa, pb, sep0, pushed0 = push_point(pa, pb, mass, n, point, beta)
        point = (
            (lanes[b1 + LAX], lanes[b1 + LAY]),
            (lanes[b1 + LBX], lanes[b1 + LBY]),
            lanes[b1 + DEPTH],
            lanes[b1 + ALLOWED],
        )
        pa, pb, sep1, pushed1 = push_point(pa, pb, mass, n, point, beta)
        lanes[i + WORST] = min(lanes[i + WORST], min(sep0, sep1))
        lanes[i + MOVED] = max(lanes[i + MOVED], 1.0 if pushed0 | pushed1 else 0.0)
        met = overlap_left(sep0, lanes[b0 + ALLOWED]) + overlap_left(sep1, lanes[b1 + ALLOWED])
        lanes[i + OVERLAP] = lanes[i + OVERLAP] + met
        lanes[i + AX], lanes[i + AY], lanes[i + AC], lanes[i + AS], lanes[i + ATURN] = pa
        lanes[i + BX], lanes[i + BY], lanes[i + BC], lanes[i + BS], lanes[i + BTURN] = pb


@njit(inline="always")  # as a call, its arrays were reference-counted in and out each colour
def visit_colour(lanes, owners, first: int, end: int, poses, beta: float):
    """One push of every point of a colour's contacts (blocks ``first`` to ``end``): the
    bodies' poses (``poses``, a row (x, y, cos, sin, turn) per body, :func:`take_poses`) into
    all the colour's lanes, the pushes, the poses back. (The velocity sweeps hand the
    velocities from lane to lane instead, :mod:`sandbox.solvers.handoff`, with a plan made
    once for ten sweeps; here it would be made for one pass.) Returns (smallest separation seen (m),
    whether anything moved, the overlap met (um, exact: a sum of integers))."""
    for block in range(first, end):
        start = np.uint64(block) * np.uint64(BLOCK)
        for lane in range(LANES):
            q, i = block * LANES + lane, start + np.uint64(lane)
            v, w = poses[owners[1, q]], poses[owners[2, q]]
            lanes[i + AX], lanes[i + AY], lanes[i + AC], lanes[i + AS] = v[0], v[1], v[2], v[3]
            lanes[i + BX], lanes[i + BY], lanes[i + BC], lanes[i + BS] = w[0], w[1], w[2], w[3]
            lanes[i + ATURN], lanes[i + BTURN] = v[4], w[4]
            lanes[i + WORST], lanes[i + MOVED], lanes[i + OVERLAP] = 0.0, 0.0, 0.0
    for block in range(first, end):
        visit_block(lanes, np.uint64(block) * np.uint64(BLOCK), beta)
    worst, moved, overlap = 0.0, 0.0, 0.0
    for block in range(first, end):
        start = np.uint64(block) * np.uint64(BLOCK)
        for lane in range(LANES):
            q, i = block * LANES + lane, start + np.uint64(lane)
            v, w = poses[owners[1, q]], poses[owners[2, q]]
            v[0], v[1], v[2], v[3] = lanes[i + AX], lanes[i + AY], lanes[i + AC], lanes[i + AS]
            w[0], w[1], w[2], w[3] = lanes[i + BX], lanes[i + BY], lanes[i + BC], lanes[i + BS]
            v[4], w[4] = lanes[i + ATURN], lanes[i + BTURN]
            worst = min(worst, lanes[i + WORST])
            moved = max(moved, lanes[i + MOVED])
            overlap += lanes[i + OVERLAP]
    return worst, moved != 0.0, overlap


@njit
def take_poses(bodies, poses) -> None:
    """Each body's pose (:func:`sandbox.math2d.pose_of`) into its row of ``poses``; the last
    row is the empty lanes' (zeros)."""
    for i in range(len(bodies)):
        poses[i, 0], poses[i, 1], poses[i, 2], poses[i, 3], poses[i, 4] = pose_of(bodies[i])


@njit
def put_poses(poses, bodies) -> None:
    """The rows of ``poses`` back into the bodies."""
    for i in range(len(bodies)):
        set_pose(bodies[i], (poses[i, 0], poses[i, 1], poses[i, 2], poses[i, 3], poses[i, 4]))
