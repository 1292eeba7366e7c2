"""Wide sweeps: the iterative solver's sequential impulses, eight contacts at a time (Box2D v3's
graph colouring and wide contact constraints, ``constraint_graph.c`` and ``contact_solver.c``;
Erin Catto, "Solver2D").

A sweep visits the contacts one after another, each given what the ones before it did; any
fixed order is a valid sweep (Gauss-Seidel). Colour the contacts so that no two of one colour
share a body that moves (a body that cannot move, static or held, only pushes and is never
pushed, so any number of one colour may touch it): within a colour no visit changes what
another reads, so visiting a colour's contacts one by one or all at once gives the same
numbers. A sweep is then one colour after another, and within a colour the processor visits
eight contacts with each vector instruction (its SIMD lanes: eight doubles in AVX-512, two
times four in AVX2), about five times faster than one by one.

Each visit is the very same arithmetic as :func:`sandbox.solvers.iterative.sweep`'s
(:mod:`sandbox.solvers.impulses`, :func:`~sandbox.math2d.speed_along`,
:func:`~sandbox.math2d.push_along`); only the order of the contacts differs (colour by colour).

Layout (:func:`place`, :func:`pack`): each colour's contacts fill blocks of ``LANES``; a block holds each
field of its eight contacts side by side, ``LANES`` numbers per field (``lanes[block][field]
[lane]``, as Box2D's ``b2ContactConstraintSIMD``), so that lane ``l`` of field ``F`` of the
block starting at ``i`` is ``lanes[i + F + l]``. A colour's last block is filled with empty
lanes (no bodies, zero masses: they push nothing). Contacts with one point (discs) have lanes
of a layout of their own (:mod:`sandbox.solvers.wide_single`), visited after each colour's
two-point lanes; any contact for which 63 colours do not suffice (one body touching more than
63 others) is visited one by one after the colours (:func:`colour`). Before a colour's visits
its lanes take their bodies' velocities from the lanes that last held them
(:mod:`sandbox.solvers.handoff`).
"""

from __future__ import annotations

import numpy as np

from sandbox.bits import lowest_bit
from sandbox.jit import literally, njit
from sandbox.math2d import push_along, speed_along
from sandbox.prefetch import AHEAD, prefetch_record, span, where
from sandbox.records import CONTACT
from sandbox.solvers.impulses import block_totals, friction_step, normal_step

LANES = 8  # contacts a block holds: one AVX-512 register of doubles
COLOURS = 63  # at most (a body's colours are the bits of one int64); the rest one by one
# what the colouring reads of a contact's record: two of its ten lines (sandbox.prefetch)
COLOUR_READ = span(CONTACT, "a", "use_block")
ALL_COLOURS = (1 << COLOURS) - 1  # every colour taken


def _offsets(count: int) -> list[np.uint64]:
    # where each of ``count`` fields begins within a block (each is LANES numbers long):
    # unsigned, so that the compiled code knows an index is never negative (numba would
    # otherwise test each one for Python's negative indexing, and the loop over the lanes
    # would not become vector instructions)
    return [np.uint64(f * LANES) for f in range(count)]


# a contact's fields in a block, in this order: its bodies' inverse masses, the normal and the
# friction, the block solver's K and K^-1, both bodies' velocities while the colour is visited,
# then each point's fields (at P0 and P1)
IM_A, II_A, IM_B, II_B, NX, NY, MU, K11, K12, K22, M11, M12, M22, *_rest = _offsets(20)
VAX, VAY, WA, VBX, VBY, WB, P0 = _rest
# a point's fields, from P0 or P1 on
POINT_FIELDS = RN_A, RN_B, RT_A, RT_B, NORMAL_MASS, TANGENT_MASS, BIAS, *_rest = _offsets(10)
NORMAL_IMPULSE, TANGENT_IMPULSE, MAX_NORMAL_IMPULSE = _rest
P1 = P0 + np.uint64(len(POINT_FIELDS) * LANES)
FIELDS_PER_POINT = len(POINT_FIELDS)
FIELDS = int(P1) // LANES + FIELDS_PER_POINT  # fields per contact
BLOCK = FIELDS * LANES  # numbers per block


@njit(python=True)
def colour(
    contacts, k: int, bodies, colours, own: bool = False, single: bool = False, ends=None
) -> int:
    """Give each of the first ``k`` contacts with two points (``single``: and those with one)
    the first colour none of its moving bodies has yet (greedy, in list order):
    ``colours[i]``, or ``COLOURS`` for a contact visited alone (no colour left, or one point
    and not ``single``). A body moves when the contact's copy of its inverse mass or moment is
    not zero (``own``: the body's own, as the position passes use them). Returns the number of
    colours used. ``ends`` (4, k), if given, gets each contact's number of points, its bodies
    a and b and whether it uses the block solver, for :func:`place` and :func:`groups` (which
    then read no record: the records are hundreds of bytes apart, and reading them again cost
    as much as the colouring).

    One-point contacts (discs) have lanes of their own (:mod:`sandbox.solvers.wide_single`):
    in these a lane's second point and block solver would be wasted arithmetic."""
    used = np.zeros(len(bodies), dtype=np.int64)  # bit c set: the body has colour c
    count = 0
    contacts_at = where(contacts)
    for i in range(k):
        # asked for ahead: the loop reads two lines of each record and waits for them (rain of
        # 5,000, 12,709 contacts: 256 -> 185 us; pyramid of 40, caches flushed: 46 -> 34 us)
        prefetch_record(contacts_at, i + 2 * AHEAD, COLOUR_READ)
        c = contacts[i]
        a, b = c["a"], c["b"]
        if ends is not None:
            ends[0, i], ends[1, i], ends[2, i] = c["count"], a, b
            ends[3, i] = 1 if c["use_block"] else 0
        if c["count"] != 2 and not (single and c["count"] == 1):
            colours[i] = COLOURS
            continue
        move_a = c["inv_mass_a"] != 0.0 or c["inv_moment_a"] != 0.0
        move_b = c["inv_mass_b"] != 0.0 or c["inv_moment_b"] != 0.0
        if own:  # a copy is the body's own or 0 (held): only a 0 needs a look at the body
            move_a = move_a or bodies[a]["inv_mass"] != 0.0 or bodies[a]["inv_moment"] != 0.0
            move_b = move_b or bodies[b]["inv_mass"] != 0.0 or bodies[b]["inv_moment"] != 0.0
        taken = (used[a] if move_a else 0) | (used[b] if move_b else 0)
        chosen = COLOURS
        if taken != ALL_COLOURS:
            free = ~taken & (taken + 1)  # the lowest bit not taken
            chosen = lowest_bit(free)
            if move_a:
                used[a] |= free
            if move_b:
                used[b] |= free
            count = max(count, chosen + 1)
        colours[i] = chosen
    return count


@njit
def has_two_points(contacts, k: int) -> bool:
    """Whether any of the first ``k`` contacts has two points (only those go in the two-point
    lanes, here and in :mod:`sandbox.solvers.wide_positions`)."""
    for i in range(k):
        if contacts[i]["count"] == 2:
            return True
    return False


@njit
def buffers(k: int, count: int):
    """(owners, starts) with room for ``k`` contacts in ``count`` groups (:func:`place`):
    ``owners`` (3, lanes) holds each lane's contact and its two bodies."""
    blocks = (k + LANES - 1) // LANES + count
    return np.empty((3, blocks * LANES), dtype=np.int64), np.empty(count + 1, dtype=np.int64)


@njit
def place(ends, k: int, keys, count: int, owners, empty: int, starts) -> int:
    """Where each of the first ``k`` contacts goes, group by group (``keys[i]``: contact i's
    group, below ``count``, or ``count`` and above to leave it out: :func:`groups`; ``ends``
    as :func:`colour` fills it): contact i of its group in block i // LANES, lane i % LANES
    (:mod:`module layout <sandbox.solvers.wide>`); ``owners[:, block * LANES + lane]``: the
    contact's index in ``contacts`` and its bodies a and b (an empty lane: -1 and twice
    ``empty``, a row of velocities no body uses); ``starts[g]``: group g's first block
    (``starts[count]``: the end). Returns the number of blocks."""
    sizes = np.zeros(count + 1, dtype=np.int64)
    for i in range(k):
        sizes[min(keys[i], count)] += 1
    starts[0] = 0
    for g in range(count):
        starts[g + 1] = starts[g] + (sizes[g] + LANES - 1) // LANES
    blocks = starts[count]
    owners[0, : blocks * LANES] = -1
    owners[1:, : blocks * LANES] = empty
    filled = np.zeros(count, dtype=np.int64)
    for i in range(k):
        g = keys[i]
        if g < count:
            q = starts[g] * LANES + filled[g]
            owners[0, q], owners[1, q], owners[2, q] = i, ends[1, i], ends[2, i]
            filled[g] += 1
    return blocks


@njit
def groups(ends, k: int, colours, count: int, points: int, by_solver: bool):
    """Each contact's group for :func:`place`: its colour if it has ``points`` points; with
    ``by_solver`` (the two-point velocity lanes) 2 c for one of colour c that uses the block
    solver and 2 c + 1 for one that solves its points one after the other, so that a block
    holds contacts solved one way only (:func:`visit_blocks`; within a colour the order is
    free). Any other contact gets the number of groups (``count``, or ``2 count``): left out."""
    size = 2 * count if by_solver else count
    keys = np.empty(k, dtype=np.int64)
    for i in range(k):
        c = colours[i]
        if c >= count or ends[0, i] != points:
            keys[i] = size
        elif by_solver:
            keys[i] = 2 * c + 1 - ends[3, i]
        else:
            keys[i] = c
    return keys


@njit
def pack(contacts, lanes, owners, blocks: int) -> None:
    """Copy the contacts into their lanes (:func:`place`); empty lanes get zeros."""
    for q in range(blocks * LANES):
        i = np.uint64(q // LANES) * np.uint64(BLOCK) + np.uint64(q % LANES)
        if owners[0, q] < 0:
            for f in range(FIELDS):
                lanes[i + np.uint64(f * LANES)] = 0.0
        else:
            pack_lane(contacts[owners[0, q]], lanes, i)


@njit
def pack_lane(c, lanes, i) -> None:
    """One contact's fields into the lane starting at ``i``."""
    lanes[i + IM_A], lanes[i + II_A] = c["inv_mass_a"], c["inv_moment_a"]
    lanes[i + IM_B], lanes[i + II_B] = c["inv_mass_b"], c["inv_moment_b"]
    lanes[i + NX], lanes[i + NY], lanes[i + MU] = c["normal"][0], c["normal"][1], c["friction"]
    k, m = c["block_k"], c["block_mass"]
    lanes[i + K11], lanes[i + K12], lanes[i + K22] = k[0], k[1], k[2]
    lanes[i + M11], lanes[i + M12], lanes[i + M22] = m[0], m[1], m[2]
    pack_point(c["points"][0], lanes, i + P0)  # both points used: only those get a colour
    pack_point(c["points"][1], lanes, i + P1)


@njit
def pack_point(p, lanes, base) -> None:
    """A point's fields into the lane whose point fields begin at ``base`` (this layout's and
    :mod:`sandbox.solvers.wide_single`'s)."""
    lanes[base + RN_A], lanes[base + RN_B] = p["rn_a"], p["rn_b"]
    lanes[base + RT_A], lanes[base + RT_B] = p["rt_a"], p["rt_b"]
    lanes[base + NORMAL_MASS], lanes[base + TANGENT_MASS] = p["normal_mass"], p["tangent_mass"]
    lanes[base + BIAS] = p["bias"]
    lanes[base + NORMAL_IMPULSE] = p["normal_impulse"]
    lanes[base + TANGENT_IMPULSE] = p["tangent_impulse"]
    lanes[base + MAX_NORMAL_IMPULSE] = p["max_normal_impulse"]


@njit
def unpack_point(lanes, base, p) -> None:
    """A point's accumulated impulses back from the lane (``base`` as :func:`pack_point`)."""
    p["normal_impulse"] = lanes[base + NORMAL_IMPULSE]
    p["tangent_impulse"] = lanes[base + TANGENT_IMPULSE]
    p["max_normal_impulse"] = lanes[base + MAX_NORMAL_IMPULSE]


@njit
def unpack(contacts, lanes, owners, blocks: int) -> None:
    """The accumulated impulses back into the contact records."""
    for q in range(blocks * LANES):
        if owners[0, q] < 0:
            continue
        c = contacts[owners[0, q]]
        i = np.uint64(q // LANES) * np.uint64(BLOCK) + np.uint64(q % LANES)
        unpack_point(lanes, i + P0, c["points"][0])
        unpack_point(lanes, i + P1, c["points"][1])


@njit
def visit_blocks(lanes, start, blocks: int, block: bool) -> None:
    """One visit of each contact of ``blocks`` blocks from number ``start`` on, as
    :func:`sandbox.solvers.iterative.visit_contact` with accumulated impulses: friction within
    the cone of the current normal impulses, then the normal impulses, both points together
    (block solver) or one after the other. The lanes are independent, so this loop runs as
    vector instructions, eight lanes each: the loop reads and writes ``lanes`` itself (handed
    to another function, the array would be counted as referenced in every lane, and the loop
    would stay one lane at a time). ``block``: the block's contacts use the block solver, or
    else all solve their points one after the other (:func:`groups`); numba compiles a version
    for each (``literally``), so every lane runs the same instructions, and neither works out
    what the other needs (a lane of each kind in one block, both were worked out and one kept:
    13 % slower)."""
    literally(block)
    for nb in range(blocks):  # one call a group, not a block: each call counts references
        for lane in range(LANES):
            i = start + np.uint64(nb) * np.uint64(BLOCK) + np.uint64(lane)
            p0, p1 = i + P0, i + P1  # where each point's fields begin
            mass = lanes[i + IM_A], lanes[i + II_A], lanes[i + IM_B], lanes[i + II_B]
            nx, ny, mu = lanes[i + NX], lanes[i + NY], lanes[i + MU]
            va = lanes[i + VAX], lanes[i + VAY], lanes[i + WA]
            vb = lanes[i + VBX], lanes[i + VBY], lanes[i + WB]
            # friction at each point
            t = ny, -nx  # t = (n_y, -n_x)
            limit = mu * lanes[p0 + NORMAL_IMPULSE]
            rt, old = (lanes[p0 + RT_A], lanes[p0 + RT_B]), lanes[p0 + TANGENT_IMPULSE]
            new, va, vb = friction_step(va, vb, mass, t, rt, old, lanes[p0 + TANGENT_MASS], limit)
            lanes[p0 + TANGENT_IMPULSE] = new
            limit = mu * lanes[p1 + NORMAL_IMPULSE]
            rt, old = (lanes[p1 + RT_A], lanes[p1 + RT_B]), lanes[p1 + TANGENT_IMPULSE]
            new, va, vb = friction_step(va, vb, mass, t, rt, old, lanes[p1 + TANGENT_MASS], limit)
            lanes[p1 + TANGENT_IMPULSE] = new
            # the normal impulses
            n = nx, ny
            rn1, rn2 = (lanes[p0 + RN_A], lanes[p0 + RN_B]), (lanes[p1 + RN_A], lanes[p1 + RN_B])
            a1, a2 = lanes[p0 + NORMAL_IMPULSE], lanes[p1 + NORMAL_IMPULSE]
            bias1, bias2 = lanes[p0 + BIAS], lanes[p1 + BIAS]
            mass1, mass2 = lanes[p0 + NORMAL_MASS], lanes[p1 + NORMAL_MASS]
            if block:  # together: b, the normal speeds without the impulses so far, minus the bias
                k11, k12, k22 = lanes[i + K11], lanes[i + K12], lanes[i + K22]
                m = lanes[i + M11], lanes[i + M12], lanes[i + M22]  # K^-1
                b1 = speed_along(va, vb, nx, ny, rn1[0], rn1[1]) - bias1 - (k11 * a1 + k12 * a2)
                b2 = speed_along(va, vb, nx, ny, rn2[0], rn2[1]) - bias2 - (k12 * a1 + k22 * a2)
                x1, x2 = block_totals(a1, a2, b1, b2, k12, m, mass1, mass2)
                # P = (x1 - a1) n at point 1, then (x2 - a2) n at point 2
                va, vb = push_along(va, vb, mass, nx, ny, rn1[0], rn1[1], x1 - a1)
                va, vb = push_along(va, vb, mass, nx, ny, rn2[0], rn2[1], x2 - a2)
            else:  # one after the other (the second point sees what the first one's impulse did)
                x1, va, vb = normal_step(va, vb, mass, n, rn1, a1, mass1, bias1)
                x2, va, vb = normal_step(va, vb, mass, n, rn2, a2, mass2, bias2)
            lanes[p0 + NORMAL_IMPULSE], lanes[p1 + NORMAL_IMPULSE] = x1, x2
            lanes[p0 + MAX_NORMAL_IMPULSE] = max(lanes[p0 + MAX_NORMAL_IMPULSE], x1)
            lanes[p1 + MAX_NORMAL_IMPULSE] = max(lanes[p1 + MAX_NORMAL_IMPULSE], x2)
            lanes[i + VAX], lanes[i + VAY], lanes[i + WA] = va
            lanes[i + VBX], lanes[i + VBY], lanes[i + WB] = vb
