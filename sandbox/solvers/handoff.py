"""The bodies' velocities handed from lane to lane during the wide sweeps
(:func:`sandbox.solvers.iterative.coloured_sweeps`).

A sweep visits the contacts group by group (each colour's two-point lanes with the block
solver, those without, then its one-point lanes: :mod:`sandbox.solvers.wide`,
:mod:`sandbox.solvers.wide_single`). Before a group's visits its lanes need the current
velocities of their bodies; after them, those velocities are what the next group to touch the
same body must see. Copied through the bodies' rows, that is two copies a lane and a group:
into the lanes from the rows, and back out. Yet the current velocity of a body is always in
one place already: the lane that last held it. So each lane's source is planned once a step
(:func:`plan`), and a group's lanes copy their velocities straight from there
(:func:`hand_in`): one copy a lane, and nothing written back until the sweeps end.

Where a body was last held (in sweep order, in lane order within a group) before group ``g``:

- in a group before ``g``, in this sweep: that lane, as this sweep left it;
- nowhere before ``g`` in this sweep: in the first sweep, the body's row (copied into its first
  lanes before the sweep, :func:`prime`, so that the hand-in copies those lanes onto
  themselves); in a later sweep, its last lane of the sweep before, which no group has visited
  again yet (``sources[1]``). A body held by one group only is handed its own lane.

Joints and contacts no colour takes read the bodies' rows between the colours; with either
the lanes hand the velocities back to the rows after every sweep (:func:`hand_back`) and take
them again before the next. Each number a visit reads is the same as with the rows between the
groups, so the sweeps give the same numbers to the bit: a body that cannot move (static, held,
an empty lane's) can be held by several lanes of one group, each reading it as it was before
the group, and the last of them hands it on, as the last of them wrote its row.
"""

from __future__ import annotations

import numpy as np

from sandbox.gather import WIDTH, gather_lanes
from sandbox.jit import njit
from sandbox.solvers import wide, wide_single
from sandbox.solvers.wide import LANES

# a body's velocity in a lane: vx at the offset, vy and w one and two fields (LANES numbers) on,
# then the other body's (VBX - VAX on, the same in both layouts)
NEXT_FIELD = np.uint64(LANES)
OTHER_BODY = wide.VBX - wide.VAX
assert wide_single.VBX - wide_single.VAX == OTHER_BODY
OTHER = int(OTHER_BODY)
assert WIDTH == LANES  # a block's field is one gather


@njit(inline="always")  # numbers only: nothing to count references to
def velocity_at(layout: tuple, q: int) -> int:
    """Where lane ``q`` of a layout keeps body a's vx (body b's is :data:`OTHER` on):
    ``layout`` = (first number of its blocks, numbers per block, where its velocities begin,
    its first lane's column in :func:`plan`'s sources), lane ``q`` in block ``q // LANES``
    (:mod:`sandbox.solvers.wide`'s layout)."""
    base, size, at, _ = layout
    return base + (q // LANES) * size + np.int64(at) + q % LANES


@njit
def sweep_order(starts, starts1, count: int):
    """(g, 3): the groups of a sweep in order, each its layout (0: two points, 1: one) and its
    first and end block: colour by colour, the two-point lanes with the block solver
    (``starts[2 c]`` on), those without (``starts[2 c + 1]`` on), the one-point lanes
    (``starts1[c]`` on)."""
    order = np.empty((3 * count, 3), dtype=np.int64)
    for c in range(count):
        order[3 * c, 0], order[3 * c, 1], order[3 * c, 2] = 0, starts[2 * c], starts[2 * c + 1]
        order[3 * c + 1, 0], order[3 * c + 1, 1] = 0, starts[2 * c + 1]
        order[3 * c + 1, 2] = starts[2 * c + 2]
        order[3 * c + 2, 0], order[3 * c + 2, 1], order[3 * c + 2, 2] = (
            1,
            starts1[c],
            starts1[c + 1],
        )
    return order


@njit
def plan(order, owners, layouts, rows: int):
    """Each lane's sources for :func:`hand_in`: (sources, firsts, lasts).

    ``order`` (g, 3): the groups (:func:`sweep_order`); ``owners[layout][1 + side, q]``: the
    body (a row below ``rows``) of lane q's side (0: a, 1: b); ``layouts[layout]``: (first
    number of the layout's blocks, numbers per block, where its velocities begin, its first
    lane's column in ``sources``). ``sources[sweep, side, column + q]`` (``sweep`` 0: the
    first, 1: a later one): where the body of the layout's lane q's side is to take its vx
    from, vy and w one and two fields on. One array for both layouts and sweeps, not a tuple of
    them: a tuple's arrays picked by a number are reference-counted (numba's runtime, an atomic
    add) at every group of a sweep. ``firsts`` (m, 2): each lane a body first holds in a sweep
    and the body (for :func:`prime`); ``lasts`` (n, 2): each body held by a lane and where its
    last lane keeps its vx (for :func:`hand_back`)."""
    columns = owners[0].shape[1] + owners[1].shape[1]
    sources = np.empty((2, 2, columns), dtype=np.int64)
    firsts = np.empty((2 * columns, 2), dtype=np.int64)
    later_firsts = np.empty((2 * columns, 2), dtype=np.int64)  # side, column
    last = np.full(rows, -1, dtype=np.int64)
    m = 0
    for g in range(len(order)):
        layout, first, end = order[g, 0], order[g, 1], order[g, 2]
        ids, column = owners[layout], layouts[layout][3]
        for q in range(first * LANES, end * LANES):  # where each body was before the group
            here = velocity_at(layouts[layout], q)
            for side in range(2):
                body = ids[1 + side, q]
                if last[body] >= 0:
                    sources[0, side, column + q] = sources[1, side, column + q] = last[body]
                else:  # the body's first lane in a sweep: primed, so it takes its own numbers
                    sources[0, side, column + q] = here
                    firsts[m, 0], firsts[m, 1] = here, body
                    later_firsts[m, 0], later_firsts[m, 1] = side, column + q
                    m += 1
                here += OTHER
        for q in range(first * LANES, end * LANES):  # the group's last lane of a body hands on
            here = velocity_at(layouts[layout], q)
            last[ids[1, q]], last[ids[2, q]] = here, here + OTHER
    for j in range(m):  # in a later sweep, a body's first lanes take its last of the sweep before
        sources[1, later_firsts[j, 0], later_firsts[j, 1]] = last[firsts[j, 1]]
    lasts, n = np.empty((rows, 2), dtype=np.int64), 0
    for body in range(rows):
        if last[body] >= 0:
            lasts[n, 0], lasts[n, 1] = body, last[body]
            n += 1
    return sources, firsts[:m], lasts[:n]


@njit
def prime(lanes, firsts, velocities) -> None:
    """Each body's row of ``velocities`` (vx, vy, w) into the first lanes it has in a sweep."""
    for j in range(len(firsts)):
        i, v = np.uint64(firsts[j, 0]), velocities[firsts[j, 1]]
        lanes[i], lanes[i + NEXT_FIELD], lanes[i + 2 * NEXT_FIELD] = v[0], v[1], v[2]


@njit
def hand_in(lanes, sources, layout: tuple, first: int, end: int) -> None:
    """Each lane of blocks ``first`` to ``end`` of a layout takes its bodies' velocities from
    their sources (``sources[side, column]``: one sweep's of :func:`plan`). A whole group at
    once, before its visits: their vector loads right after single stores into the same
    numbers would wait for the stores to finish. Each field of a block's eight lanes is one
    gather (:func:`sandbox.gather.gather_lanes`: ten sweeps' hand-ins on the rain of 5,000
    took 409 to 416 us copied one number at a time, 292 to 297 us gathered)."""
    base, size, at, column = layout
    columns = sources.shape[1]
    for b in range(first, end):
        start = np.uint64(base) + np.uint64(b) * np.uint64(size) + at
        q = column + b * LANES  # the block's first lane in sources
        for side in range(2):
            to = start + np.uint64(side) * OTHER_BODY
            for field in range(3):
                at_field = np.uint64(field) * NEXT_FIELD
                gather_lanes(lanes, to + at_field, sources, side * columns + q, at_field)


@njit
def hand_back(lanes, lasts, velocities) -> None:
    """Each body's last lane back into its row of ``velocities``."""
    for j in range(len(lasts)):
        i, v = np.uint64(lasts[j, 1]), velocities[lasts[j, 0]]
        v[0], v[1], v[2] = lanes[i], lanes[i + NEXT_FIELD], lanes[i + 2 * NEXT_FIELD]
