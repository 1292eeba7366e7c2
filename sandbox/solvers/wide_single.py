"""Wide sweeps for contacts with one point (discs): the lanes of :mod:`sandbox.solvers.wide`
with a layout of their own, without the second point and the block solver that would only
waste a two-point lane's arithmetic.

Each visit is :func:`sandbox.solvers.iterative.visit_points`' for one point, accumulated:
friction within the cone of the current normal impulse, then the normal impulse
(:mod:`sandbox.solvers.impulses`, :func:`~sandbox.math2d.speed_along`,
:func:`~sandbox.math2d.push_along`). The lanes are visited colour by colour after the colour's
two-point lanes (:func:`sandbox.solvers.iterative.coloured_sweeps`): the colours keep any two
contacts of one colour off a common moving body, whatever their number of points.

Measured on the rain of 5,000 discs at rest (13,158 contacts, 8 colours): ten sweeps with the
colouring and the copying in and out, 1.2 ms eight at a time against 2.2 ms one by one.
"""

from __future__ import annotations

import numpy as np

from sandbox.jit import njit
from sandbox.solvers.impulses import friction_step, normal_step
from sandbox.solvers.wide import (
    BIAS,
    II_A,
    II_B,
    IM_A,
    IM_B,
    LANES,
    MAX_NORMAL_IMPULSE,
    MU,
    NORMAL_IMPULSE,
    NORMAL_MASS,
    NX,
    NY,
    POINT_FIELDS,
    RN_A,
    RN_B,
    RT_A,
    RT_B,
    TANGENT_IMPULSE,
    TANGENT_MASS,
    _offsets,
    pack_point,
    unpack_point,
)

# a lane: the two-point layout's first fields (inverse masses, normal, friction), its point's
# fields (from P on, as the two-point layout's points), both bodies' velocities
P = MU + np.uint64(LANES)
VAX, VAY, WA, VBX, VBY, WB = (P + f for f in _offsets(len(POINT_FIELDS) + 6)[-6:])
FIELDS = int(WB) // LANES + 1
BLOCK = FIELDS * LANES


@njit
def pack(contacts, lanes, owners, blocks: int) -> None:
    """Copy the one-point contacts into their lanes (:func:`sandbox.solvers.wide.place`);
    empty lanes get zeros."""
    for q in range(blocks * LANES):
        i = np.uint64(q // LANES) * np.uint64(BLOCK) + np.uint64(q % LANES)
        if owners[0, q] < 0:
            for f in range(FIELDS):
                lanes[i + np.uint64(f * LANES)] = 0.0
            continue
        c = contacts[owners[0, q]]
        lanes[i + IM_A], lanes[i + II_A] = c["inv_mass_a"], c["inv_moment_a"]
        lanes[i + IM_B], lanes[i + II_B] = c["inv_mass_b"], c["inv_moment_b"]
        lanes[i + NX], lanes[i + NY], lanes[i + MU] = c["normal"][0], c["normal"][1], c["friction"]
        pack_point(c["points"][0], lanes, i + P)


@njit
def unpack(contacts, lanes, owners, blocks: int) -> None:
    """The accumulated impulses back into the contact records."""
    for q in range(blocks * LANES):
        if owners[0, q] >= 0:
            i = np.uint64(q // LANES) * np.uint64(BLOCK) + np.uint64(q % LANES)
            unpack_point(lanes, i + P, contacts[owners[0, q]]["points"][0])


@njit
def visit_blocks(lanes, start, blocks: int) -> None:
    """One visit of each contact of ``blocks`` blocks from number ``start`` on, as
    :func:`sandbox.solvers.wide.visit_blocks` for one point: the loop reads and writes
    ``lanes`` itself, so it runs as vector instructions."""
    for nb in range(blocks):  # one call a group, not a block: each call counts references
        for lane in range(LANES):
            i = start + np.uint64(nb) * np.uint64(BLOCK) + np.uint64(lane)
            mass = lanes[i + IM_A], lanes[i + II_A], lanes[i + IM_B], lanes[i + II_B]
            nx, ny, mu = lanes[i + NX], lanes[i + NY], lanes[i + MU]
            va = lanes[i + VAX], lanes[i + VAY], lanes[i + WA]
            vb = lanes[i + VBX], lanes[i + VBY], lanes[i + WB]
            p = i + P  # where the point's fields begin
            # friction within the cone of the current normal impulse, t = (n_y, -n_x)
            rt, limit = (lanes[p + RT_A], lanes[p + RT_B]), mu * lanes[p + NORMAL_IMPULSE]
            old, tangent_mass = lanes[p + TANGENT_IMPULSE], lanes[p + TANGENT_MASS]
            new, va, vb = friction_step(va, vb, mass, (ny, -nx), rt, old, tangent_mass, limit)
            lanes[p + TANGENT_IMPULSE] = new
            # the normal impulse
            rn, old = (lanes[p + RN_A], lanes[p + RN_B]), lanes[p + NORMAL_IMPULSE]
            new, va, vb = normal_step(
                va, vb, mass, (nx, ny), rn, old, lanes[p + NORMAL_MASS], lanes[p + BIAS]
            )
            lanes[p + NORMAL_IMPULSE] = new
            lanes[p + MAX_NORMAL_IMPULSE] = max(lanes[p + MAX_NORMAL_IMPULSE], new)
            lanes[i + VAX], lanes[i + VAY], lanes[i + WA] = va
            lanes[i + VBX], lanes[i + VBY], lanes[i + WB] = vb
