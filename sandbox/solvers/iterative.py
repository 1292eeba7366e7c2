"""Iterative solver: sequential impulses (slides, "Simultaneous Collision Resolution",
"Iterative Solver"; box2d-lite's ``World::Step``).

All contacts are considered together by sweeping over them ``settings.iterations`` times; each
visit applies the collision equation's impulse that makes that one point right, given what the
others did so far. Repeated, the sweeps converge towards impulses that satisfy every contact at
once, which is what a stack needs. Joints take their turn in every sweep.

Any fixed order of visits is a valid sweep. With accumulated impulses (the default) the sweeps
visit the contacts colour by colour (:func:`coloured_sweeps`): no two contacts of a colour
share a moving body, so the processor visits eight of them at once with its vector
instructions (:mod:`sandbox.solvers.wide`), with the very same arithmetic as one visit here
(:mod:`sandbox.solvers.impulses`). Without, one by one (:func:`sweep`).

The box2d-lite teaching switches:

- ``accumulate_impulses``: clamp the running total of each point's impulse (>= 0, friction
  within mu times it) instead of each increment, so later sweeps can correct earlier ones;
- ``warm_start``: start from last step's impulses of the same contact points
  (:func:`sandbox.solvers.common.match_previous`; needs ``accumulate_impulses``);
- ``position_correction``: the penetration fix after the positions moved
  (:mod:`sandbox.penetration`, ``settings.penetration``; ``position_iterations`` passes).

Restitution is a pass after the sweeps (:func:`sandbox.solvers.common.restitution`), from the
approach speeds measured before this step's gravity, so resting contacts do not bounce and
bounces gain no energy. Overlap is removed on positions only (no Baumgarte velocity bias): the
velocities stay free of the extra push a velocity bias adds, which would make resting boxes hop
and stacks jitter.
"""

from __future__ import annotations

import math

import numpy as np

from sandbox.jit import JIT_ENABLED, OFF, ON, njit
from sandbox.joints.solve import solve_joint_velocities
from sandbox.math2d import (
    push_along,
    put_velocities,
    set_velocity,
    speed_along,
    take_velocities,
    velocity_of,
)
from sandbox.solvers import handoff
from sandbox.solvers import wide_single as single
from sandbox.solvers.common import masses, normal_speed
from sandbox.solvers.impulses import block_totals, friction_step, normal_step
from sandbox.solvers.wide import (
    BLOCK,
    COLOURS,
    LANES,
    VAX,
    buffers,
    colour,
    groups,
    has_two_points,
    pack,
    place,
    unpack,
    visit_blocks,
)

# at a large dt (:func:`large_step`): sweep until no normal constraint is off by more than
# RESIDUAL x slop / dt (a point sinks a thousandth of the slop in the step), at most
# MAX_SWEEPS x iterations sweeps in all (tests/test_large_dt.py; a hundredth of the slop left
# tilted stacks drifting several times as far)
RESIDUAL = 1e-3
MAX_SWEEPS = 20

# ``inline="always"``: the per-contact functions below are compiled into :func:`sweep` itself
# (numba inlines them before LLVM sees them); called, each visit of each sweep pays a call and
# hands its velocities through memory, about 5 % of a large scene's step. Same arithmetic.
# A visit reads each record field once (:func:`sweep` the contact's, the functions below each
# point's arms r x n, r x t) and works with :func:`sandbox.math2d.speed_along` and
# :func:`~sandbox.math2d.push_along` directly: under ``SANDBOX_JIT=0`` every record read and
# every call costs a Python object, and the sweeps are most of a step's time there.


@njit
def visit(q: int, half: int) -> int:
    """The contact visited ``q``-th in a sweep: alternately from the first and the second half
    of the list (0, half, 1, half + 1, ...). Neighbours in the sorted list usually share a body,
    so each would wait for the one before; two halves rarely do, so the processor overlaps
    them. Any fixed order is a valid sweep (Gauss-Seidel), this one is simply faster."""
    return (q >> 1) + (q & 1) * half


@njit(inline="always")
def friction(points, count: int, nx: float, ny: float, mass, va, vb, mu: float):
    """Coulomb friction within the cone of the current normal impulse: the impulse that stops
    sliding (v_r . t -> 0), its running total clamped to |p_t| <= mu p_n."""
    tx, ty = ny, -nx  # t = (n_y, -n_x)
    for j in range(count):
        p = points[j]
        rt = p["rt_a"], p["rt_b"]  # r x t at each body
        limit = mu * p["normal_impulse"]
        new, va, vb = friction_step(
            va, vb, mass, (tx, ty), rt, p["tangent_impulse"], p["tangent_mass"], limit
        )
        p["tangent_impulse"] = new
    return va, vb


@njit(inline="always")
def normal(points, count: int, nx: float, ny: float, mass, va, vb):
    """Each point in turn: the impulse that makes v_r . n = bias, running total >= 0
    (slides, "Collision Equation", step 1, with the target bias instead of -e v_r . n)."""
    for j in range(count):
        p = points[j]
        rn = p["rn_a"], p["rn_b"]  # r x n at each body
        new, va, vb = normal_step(
            va, vb, mass, (nx, ny), rn, p["normal_impulse"], p["normal_mass"], p["bias"]
        )
        p["normal_impulse"] = new
    return va, vb


@njit(inline="always")
def block_normal(c, points, nx: float, ny: float, mass, va, vb):
    """Both normal impulses of a two-point manifold at once (Box2D's block solver).

    Find the accumulated x = (p_n1, p_n2) >= 0 with normal speeds v_n = K x + b >= bias and
    x_j (v_n,j - bias_j) = 0, trying in turn: both points push, only the first, only the
    second, neither. K is the 2x2 effective mass matrix (its diagonal holds each point's k).
    Solving the pair together keeps a box standing on two corners from rocking, which solving
    one corner after the other provokes.
    """
    p0, p1 = points[0], points[1]
    rn_a0, rn_b0, rn_a1, rn_b1 = p0["rn_a"], p0["rn_b"], p1["rn_a"], p1["rn_b"]  # r x n
    a1, a2 = p0["normal_impulse"], p1["normal_impulse"]
    k, mk = c["block_k"], c["block_mass"]
    k11, k12, k22 = k[0], k[1], k[2]
    m = mk[0], mk[1], mk[2]  # K^-1 as (m11, m12, m22)
    # b: the normal speed each point would have without the impulses applied so far, minus bias
    b1 = speed_along(va, vb, nx, ny, rn_a0, rn_b0) - p0["bias"] - (k11 * a1 + k12 * a2)
    b2 = speed_along(va, vb, nx, ny, rn_a1, rn_b1) - p1["bias"] - (k12 * a1 + k22 * a2)
    x1, x2 = block_totals(a1, a2, b1, b2, k12, m, p0["normal_mass"], p1["normal_mass"])
    va, vb = push_along(va, vb, mass, nx, ny, rn_a0, rn_b0, x1 - a1)  # P = (x1 - a1) n
    va, vb = push_along(va, vb, mass, nx, ny, rn_a1, rn_b1, x2 - a2)
    p0["normal_impulse"], p1["normal_impulse"] = x1, x2
    return va, vb


@njit(inline="always")
def each_increment(points, count: int, nx: float, ny: float, mass, va, vb, mu: float):
    """Without accumulation: each increment is clamped on its own (dp_n >= 0, then
    |dp_t| <= mu dp_n), which can only push."""
    tx, ty = ny, -nx  # t = (n_y, -n_x)
    for j in range(count):
        p = points[j]
        rn_a, rn_b, rt_a, rt_b = p["rn_a"], p["rn_b"], p["rt_a"], p["rt_b"]  # r x n, r x t
        v_n = speed_along(va, vb, nx, ny, rn_a, rn_b)  # v_r . n
        dn = max(p["normal_mass"] * (p["bias"] - v_n), 0.0)
        p["normal_impulse"] += dn
        va, vb = push_along(va, vb, mass, nx, ny, rn_a, rn_b, dn)  # P = dn n
        v_t = speed_along(va, vb, tx, ty, rt_a, rt_b)  # v_r . t
        dt = min(max(-p["tangent_mass"] * v_t, -mu * dn), mu * dn)
        p["tangent_impulse"] += dt
        va, vb = push_along(va, vb, mass, tx, ty, rt_a, rt_b, dt)  # P = dt t
    return va, vb


@njit(python=True)
def sweep(contacts, k: int, bodies, accumulate: bool) -> None:
    """One sweep of sequential impulses over the first ``k`` contacts, in :func:`visit` order
    (:func:`visit_contact`)."""
    half = (k + 1) // 2
    for q in range(k):
        visit_contact(contacts[visit(q, half)], bodies, accumulate)


@njit
def sweeps(contacts, k: int, joints, bodies, accumulate: bool, n: int) -> None:
    """``n`` sweeps one contact at a time: in each, the joints, then :func:`sweep`."""
    for _ in range(n):
        solve_joint_velocities(joints, bodies, accumulate)
        sweep(contacts, k, bodies, accumulate)


@njit(python=True)
def visit_contact(c, bodies, accumulate: bool) -> None:
    """One visit of contact ``c`` (:func:`visit_points`) with its bodies' velocities."""
    a, b = c["a"], c["b"]
    va, vb = visit_points(c, velocity_of(bodies, a), velocity_of(bodies, b), accumulate)
    set_velocity(bodies, a, va)
    set_velocity(bodies, b, vb)


# compiled once and called, not inlined: inlined into its two callers it took 5.9 s to compile
# from an empty cache, called 1.7 s; a record sweep (pyramid of 20, 590 contacts) then takes
# 20 us instead of 18, and the default sweeps visit records only for the contacts no colour
# takes (and at a large dt)
@njit
def visit_points(c, va, vb, accumulate: bool):
    """One visit of contact ``c`` given its bodies' velocities ``va``, ``vb`` (vx, vy, w), which
    it returns changed: accumulated (box2d-lite), friction first, within the cone of the
    current normal impulse, then the normal impulses (two points together when the block
    solver applies); else :func:`each_increment`."""
    # what every visit reads, read once (in plain Python each record read costs a view)
    points, count = c["points"], c["count"]
    n = c["normal"]
    nx, ny = n[0], n[1]
    mass = masses(c)
    if not accumulate:
        va, vb = each_increment(points, count, nx, ny, mass, va, vb, c["friction"])
    else:
        va, vb = friction(points, count, nx, ny, mass, va, vb, c["friction"])
        if c["use_block"]:
            va, vb = block_normal(c, points, nx, ny, mass, va, vb)
        else:
            va, vb = normal(points, count, nx, ny, mass, va, vb)
    for j in range(count):
        p = points[j]
        p["max_normal_impulse"] = max(p["max_normal_impulse"], p["normal_impulse"])
    return va, vb


@njit(python=True)
def coloured_sweeps(contacts, k: int, joints, bodies, n: int) -> None:
    """``n`` sweeps of accumulated impulses, each the joints, then the contacts colour by
    colour, eight at a time: in each colour those with two points (:mod:`sandbox.solvers.wide`),
    then those with one (:mod:`sandbox.solvers.wide_single`); then any no colour could take,
    one by one in :func:`visit` order. The same visits as :func:`sweep`'s, in another order."""
    if k == 0:  # nothing touches: the joints alone, with no lanes to fill or velocities to copy
        for _ in range(n):  # (1,000 free bodies: 3.3 of a step's 85 us went to that)
            solve_joint_velocities(joints, bodies, ON)
        return
    colours = np.empty(k, dtype=np.int64)
    ends = np.empty((4, k), dtype=np.int64)
    count = colour(contacts, k, bodies, colours, OFF, ON, ends)
    empty = len(bodies)  # the row of velocities that empty lanes read and write
    # two-point contacts in two groups a colour: with the block solver (2 c), without (2 c + 1)
    if has_two_points(contacts, k):
        owners, starts = buffers(k, 2 * count)
        keys = groups(ends, k, colours, count, 2, True)
        blocks = place(ends, k, keys, 2 * count, owners, empty, starts)
    else:  # discs alone: no two-point lanes to place (rain of 100: 0.988 of its time a step)
        owners = np.empty((3, 0), dtype=np.int64)
        starts, blocks = np.zeros(2 * count + 1, dtype=np.int64), 0
    owners1 = np.empty((3, ((k + LANES - 1) // LANES + count) * LANES), dtype=np.int64)
    starts1 = np.empty(count + 1, dtype=np.int64)
    blocks1 = place(
        ends, k, groups(ends, k, colours, count, 1, False), count, owners1, empty, starts1
    )
    alone = np.nonzero(colours == COLOURS)[0]
    half = (len(alone) + 1) // 2
    if not JIT_ENABLED:  # uncompiled, lanes buy nothing: the same visits one by one, same numbers
        for _ in range(n):
            solve_joint_velocities(joints, bodies, ON)
            for c in range(count):  # colour by colour: two points (both groups), then one
                for ids, first, end in ((owners, starts[2 * c], starts[2 * c + 2]),
                                        (owners1, starts1[c], starts1[c + 1])):  # fmt: skip
                    for q in range(first * LANES, end * LANES):
                        if ids[0, q] >= 0:
                            visit_contact(contacts[ids[0, q]], bodies, ON)
            for q in range(len(alone)):
                visit_contact(contacts[alone[visit(q, half)]], bodies, ON)
        return
    # one array for both layouts, so that a lane can take its bodies' velocities from a lane of
    # either (:mod:`sandbox.solvers.handoff`)
    base1 = blocks * BLOCK
    lanes = np.empty(base1 + blocks1 * single.BLOCK)
    pack(contacts, lanes[:base1], owners, blocks)
    single.pack(contacts, lanes[base1:], owners1, blocks1)
    layouts = ((0, BLOCK, VAX, 0), (base1, single.BLOCK, single.VAX, owners.shape[1]))
    order = handoff.sweep_order(starts, starts1, count)
    sources, firsts, lasts = handoff.plan(order, (owners, owners1), layouts, empty + 1)
    velocities = np.zeros((empty + 1, 3))
    take_velocities(bodies, velocities)
    # with nothing between the colours but the colours, the lanes keep the velocities from one
    # sweep to the next; joints and the contacts no colour takes read and write the rows
    chained = len(joints) == 0 and len(alone) == 0
    for s in range(n):
        if len(joints) > 0:  # joints read and write the bodies' records
            put_velocities(velocities, bodies)
            solve_joint_velocities(joints, bodies, ON)
            take_velocities(bodies, velocities)
        fresh = s == 0 or not chained
        if fresh:
            handoff.prime(lanes, firsts, velocities)
        now = sources[0 if fresh else 1]
        for c in range(count):
            first, middle, end = starts[2 * c], starts[2 * c + 1], starts[2 * c + 2]
            if middle > first:  # each call counts references to its arrays: none for nothing
                handoff.hand_in(lanes, now, layouts[0], first, middle)
                visit_blocks(lanes, np.uint64(first) * np.uint64(BLOCK), middle - first, True)
            if end > middle:
                handoff.hand_in(lanes, now, layouts[0], middle, end)
                visit_blocks(lanes, np.uint64(middle) * np.uint64(BLOCK), end - middle, False)
            first, end = starts1[c], starts1[c + 1]
            if end > first:
                handoff.hand_in(lanes, now, layouts[1], first, end)
                at = np.uint64(base1) + np.uint64(first) * np.uint64(single.BLOCK)
                single.visit_blocks(lanes, at, end - first)
        if not chained or s == n - 1:
            handoff.hand_back(lanes, lasts, velocities)
        for q in range(len(alone)):
            visit_rows(contacts[alone[visit(q, half)]], velocities)
    put_velocities(velocities, bodies)
    unpack(contacts, lanes[:base1], owners, blocks)
    single.unpack(contacts, lanes[base1:], owners1, blocks1)


@njit
def visit_rows(c, velocities) -> None:
    """:func:`visit_points` (accumulated) with the bodies' velocities in rows of
    ``velocities`` (vx, vy, w)."""
    v, w = velocities[c["a"]], velocities[c["b"]]
    va, vb = visit_points(c, (v[0], v[1], v[2]), (w[0], w[1], w[2]), ON)
    v[0], v[1], v[2] = va
    w[0], w[1], w[2] = vb


@njit
def normal_residual(contacts, k: int, bodies) -> float:
    """The largest error of the normal constraints at the current velocities (m/s): how far a
    pushing point's v_r . n is from its bias, or how far a point that does not push is below
    it (the complementarity conditions, slides "Linear Complementary Problem Formulation")."""
    worst = 0.0
    for i in range(k):
        c = contacts[i]
        nx, ny = c["normal"][0], c["normal"][1]
        va, vb = velocity_of(bodies, c["a"]), velocity_of(bodies, c["b"])
        for j in range(c["count"]):
            p = c["points"][j]
            excess = normal_speed(va, vb, p, nx, ny) - p["bias"]
            worst = max(worst, -excess if p["normal_impulse"] == 0.0 else abs(excess))
    return worst


@njit
def large_step(context) -> bool:
    """Whether this dt is long enough that a body falling from rest moves past the contact
    margin and the slop within one step, |g| dt^2 > max(``contact_margin``, ``slop``) (dt >
    45 ms at 9.81 m/s^2 and the default 2 cm: the regime in which the step widens its margin to
    |g| dt^2), and warm starting is on (off, the sweeps are left as they are: that switch is
    there to show what it buys)."""
    ctx = context[0]
    g = math.hypot(ctx["gravity"][0], ctx["gravity"][1])
    reach = max(ctx["touch_margin"], ctx["slop"])  # m
    return ctx["warm_start"] and g * ctx["dt"] * ctx["dt"] > reach


@njit(python=True)
def solve(contacts, k: int, joints, bodies, context) -> None:
    """``settings.iterations`` sweeps; in each, the joints and then the contacts.

    At a large dt (:func:`large_step`) the sweeps then go on until the normal constraints hold
    to within ``RESIDUAL`` times the slop per dt (:func:`normal_residual`), at most
    ``MAX_SWEEPS`` times ``settings.iterations`` sweeps in all. There, what the sweeps leave
    moves the bodies far within one step: new contacts start from zero impulse and a stack's
    weight needs many sweeps to travel down it (a chain of n bodies converges by about
    cos^2(pi / (2n + 1)) per sweep), so a 5-box stack at dt = 0.5 s sank up to 1.9 m into
    itself in its first step; and even warm started, a stack left unconverged step after step
    topples from a tilt of 1e-4 rad (tests/test_large_dt.py)."""
    ctx = context[0]
    n = ctx["iterations"]
    ctx["sweeps"] = n
    if ctx["accumulate"]:
        coloured_sweeps(contacts, k, joints, bodies, n)
    else:
        # False, read rather than written: a constant argument compiles a version of its own
        sweeps(contacts, k, joints, bodies, ctx["accumulate"], n)
    if k == 0 or not large_step(context):
        return
    tolerance = RESIDUAL * ctx["slop"] * ctx["inv_dt"]  # m/s
    for _ in range((MAX_SWEEPS - 1) * n):
        if normal_residual(contacts, k, bodies) <= tolerance:
            break
        sweeps(contacts, k, joints, bodies, ctx["accumulate"], 1)
        ctx["sweeps"] += 1
