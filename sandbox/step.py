"""One step of the world (slides, "State Update" and "Retroactive Collision Detection";
box2d-lite's ``World::Step``, Box2D's ``b2SolverStep``).

The stages, in order, each a function named after what it does:

1. ``find_pairs``            broadphase: shapes whose boxes overlap (:mod:`sandbox.broadphase`)
2. ``collide``               narrowphase: contact manifolds at the current poses
                             (:mod:`sandbox.narrowphase`), as CONTACT records
3. ``integrate_velocities``  gravity and forces: v += a dt, the integrator's increment
                             (:mod:`sandbox.integrators`), after keeping the velocities the
                             bodies arrived with, for the approach speeds
4. ``prepare_joints``        arms, effective masses, targets (:mod:`sandbox.joints.solve`)
5. ``prepare_contacts``      effective masses, approach speeds (at the velocities before
                             gravity), last step's impulses found again and applied again
                             (warm starting: :mod:`sandbox.solvers.common`), in one pass
6. ``warm_start``            the joints' last impulses applied again
7. ``solve``                 the solver's sweeps over contacts and joints (``settings.solver``)
8. ``restitution``           bounces, from the approach speeds of stage 5
9. ``integrate_positions``   p += dp + (v - v_free) dt; continuous collision may shorten it
                             (:mod:`sandbox.toi`)
10. ``fix_positions``        the penetration fix and the joints' position pass
                             (:mod:`sandbox.penetration`); continuous collision cuts its
                             moves of ccd bodies (:mod:`sandbox.ccd_positions`)
11. ``store_impulses``       this step's contacts become the next step's warm-start source; a
                             body whose state stopped being finite is reported

:func:`sandbox.staged_step.staged_step` calls the stages one by one from Python, whatever the
settings, and can time each (``timer``). :func:`fast_step` is the same sequence in one compiled
call, for the usual world (sweep and prune, the iterative or soft solver, no continuous
collision; any integrator and force generator); each compiled call from Python costs about a
microsecond, as much as a small world's whole step. Both run the very same stage functions in
the same order, so they give bit-identical results (``tests/test_step.py``,
``tests/test_step_integrators.py``). The look-ahead integrators write into work arrays the world
keeps (``work``) where a force depends on the state; without such forces every integrator is
worked out body by body, the world passes ``work=None``, and its compiled step leaves the passes
over them out.
"""

from __future__ import annotations

import numpy as np

from sandbox.broadphase.aabb import shape_box, sort_pairs_into
from sandbox.broadphase.sap import sweep
from sandbox.energy_growth import closed_energy, fastest_body
from sandbox.integrators import (
    clear_forces,
    gather_forces,
    integrate_constant,
    integrate_velocities,
    move_bodies,
    plan_motion,
)
from sandbox.jit import njit
from sandbox.joints.solve import (
    prepare_joints,
    prepare_joints_soft,
    soft_joint_plan,
    solve_joints_soft_pass,
    warm_start_joints,
    warm_start_joints_soft,
)
from sandbox.narrowphase import collide_into
from sandbox.penetration import fix_positions
from sandbox.records import STORE
from sandbox.sleep import fall_asleep, moving_kinematic, wake_touched
from sandbox.sleeping_contacts import wake_contacts
from sandbox.solvers import iterative
from sandbox.solvers.common import (
    arrived_velocities,
    match_previous,
    prepare_contacts,
    restitution,
    warm_start,
)
from sandbox.solvers.soft import (
    hold_under_heavy_loads,
    prepare_soft,
    soft_order,
    softness,
    solve_soft,
)
from sandbox.speculative import box_reach
from sandbox.toi import hold_stopped, limit_ccd_motion

STAGES = (
    "find_pairs",
    "collide",
    "integrate_velocities",
    "prepare_joints",
    "prepare_contacts",
    "warm_start",
    "solve",
    "restitution",
    "integrate_positions",
    "fix_positions",
    "store_impulses",
)


# --- the stages -------------------------------------------------------------------------------
# the broadphase leaves out pairs whose flags share a bit: static with static, sleeping or
# kinematic; sleeping with sleeping. A moving kinematic body still meets a sleeping one (to wake it)
FIXED_FLAGS = (0, 3, 3, 1)  # by kind: DYNAMIC, STATIC, KINEMATIC (standing still), SLEEPING
MOVING_KINEMATIC = 2
# m: sweep and prune sweeps boxes this much larger than the contact margin needs and keeps its
# pairs until a shape leaves its box (Box2D's aabbMargin is 0.1 m). Measured on the pyramid of
# base 40 under soft, 300 steps: 12 sweeps at 1 cm, 6 at 2 cm, 2 at 5 cm
FAT_MARGIN = 0.02
# It also stretches each box along its body's velocity by settings.box_prediction steps of
# travel (2 by default, as Box2D 2.3's aabbMultiplier; Chipmunk stretches its boxes by the
# velocity too), so a moving shape stays within its swept box for a few steps. Measured over
# 200 steps, sweeps and pairs a step: 1,000 free bodies 193 sweeps unstretched, 65 at 2; rain
# of 5,000 198 and 9,036, 133 and 13,816 at 2, 127 and 16,632 at 4, 122 and 22,982 at 8 (the
# extra pairs out of reach cost the narrowphase about what the sweeps saved)


@njit(python=True)
def place_proxies(shapes, vertices, bodies, reach, proxies) -> None:
    """Each shape's box grown by ``reach`` = (margin (m), look-ahead (s), prediction (s)): the
    margin, with speculative contacts as far as the shape moves in the look-ahead
    (:func:`sandbox.speculative.box_reach`; :func:`sandbox.broadphase.aabb.shape_box`), and
    stretched on the side its body moves to by the body's velocity times the prediction; its
    body and whether that body can be pushed (the broadphase's filter), in one pass."""
    margin, ahead, predict = reach
    for k in range(shapes.shape[0]):
        b = shapes[k]["body"]
        body = bodies[b]
        p = proxies[k]
        a = p["aabb"]
        grow = margin + box_reach(body, shapes[k], ahead)
        a[0], a[1], a[2], a[3] = shape_box(shapes[k], vertices, body, grow)
        for d in range(2):  # the stretch along the velocity: d = v t, on the side it points to
            stretch = body["vel"][d] * predict
            a[d] += min(stretch, 0.0)
            a[d + 2] += max(stretch, 0.0)
        p["body"] = b
        p["fixed"] = broadphase_flags(body)


@njit
def broadphase_flags(body) -> int:
    """A body's broadphase filter bits (:data:`FIXED_FLAGS`; a moving kinematic body's own)."""
    return MOVING_KINEMATIC if moving_kinematic(body) else FIXED_FLAGS[body["kind"]]


@njit(python=True)
def find_pairs(shapes, vertices, bodies, proxies, pairs, context) -> int:
    """Stage 1 by sweep and prune, keeping the sweep order from step to step: the sorted pair
    list into ``pairs[1]``. Returns the number of pairs, or minus the rows needed when ``pairs``
    is too small (nothing else changed).

    The boxes are swept grown by :data:`FAT_MARGIN` more than the contact margin and stretched
    along their velocities by ``settings.box_prediction`` steps of travel, and last step's pairs
    are kept while every shape's box stays within the box it was swept with (:func:`boxes_hold`,
    as Box2D's fat AABBs): any two shapes whose boxes overlap now had overlapping swept boxes,
    so the kept pairs hold all of them, and the narrowphase leaves out the rest (out of reach).
    A pile at rest sweeps again only when something moved."""
    ctx = context[0]
    m = shapes.shape[0]
    margin, ahead = ctx["contact_margin"], ctx["look_ahead"]
    if ctx["pairs_kept"] and boxes_hold(shapes, vertices, bodies, (margin, ahead), proxies):
        ctx["pair_tests"] = 0
        return ctx["pairs"]
    ctx["pairs_kept"] = False
    predict = ctx["box_prediction"] * ctx["dt"]
    place_proxies(shapes, vertices, bodies, (margin + FAT_MARGIN, ahead, predict), proxies)
    d, recount, k, tests = sweep(proxies, ctx["sweep_direction"], ctx["sweep_recount"], pairs[0])
    ctx["sweep_direction"], ctx["sweep_recount"] = d, recount
    ctx["pair_tests"] = tests
    if k > pairs.shape[1]:
        return -k
    sort_pairs_into(pairs[0], k, m, np.empty(m + 1, dtype=np.int64), pairs[1])
    ctx["pairs"] = k
    ctx["pairs_kept"] = True
    return k


@njit
def boxes_hold(shapes, vertices, bodies, reach, proxies) -> bool:
    """Whether every shape's box grown by ``reach`` (as :func:`place_proxies`) still lies
    within its swept box (``PROXY["aabb"]``), on the same body with the same broadphase
    flags."""
    margin, ahead = reach
    for k in range(shapes.shape[0]):
        b = shapes[k]["body"]
        body, p = bodies[b], proxies[k]
        if p["body"] != b or p["fixed"] != broadphase_flags(body):
            return False
        grow = margin + box_reach(body, shapes[k], ahead)
        x0, y0, x1, y1 = shape_box(shapes[k], vertices, body, grow)
        a = p["aabb"]
        if x0 < a[0] or y0 < a[1] or x1 > a[2] or y1 > a[3]:
            return False
    return True


@njit(python=True)
def prepare(contacts, k: int, kept, shapes, moving, context) -> None:
    """Stage 5: :func:`sandbox.solvers.common.prepare_contacts` (the block solver's matrices
    when ``context["block_solver"]`` says so: the soft step has none), with the warm-start
    impulses from ``kept`` = (the last step's contacts, the store of sleeping islands'
    contacts): the contacts of islands that just woke from the store
    (:func:`sandbox.sleeping_contacts.wake_contacts`), the others from the last step's.
    ``moving`` = (the BODY records, their velocities as the step began:
    :func:`sandbox.solvers.common.arrived_velocities`). The rigid steps (those with a block
    solver) warm start the contacts here too: without such islands in the prepare loop itself,
    as it goes (one pass over the records instead of three); the soft step warm starts them
    in each substep."""
    ctx = context[0]
    previous, store = kept
    warm = ctx["warm_start"]
    k_old = ctx["contact_count"][ctx["contact_set"]] if warm else 0
    stored = warm and ctx["contact_count"][STORE] > 0
    block = ctx["block_solver"]  # a rigid step: the warm start here (none in the soft step)
    # the last step's impulses in the same loop, unless islands woke: theirs come first
    last = (previous, 0 if stored else k_old, warm and block and not stored)
    found = prepare_contacts(contacts, k, shapes, moving, 0.0, context, block, last)
    if stored:
        found = wake_contacts(contacts, k, moving[0], store, context, (previous, k_old))
        found += match_previous(contacts, k, previous, k_old)
        if block:
            warm_start(contacts, k, moving[0])
    if not warm:
        ctx["contact_count"][STORE] = 0  # nothing warm starts: the kept contacts would go stale
    ctx["warm_started_points"] = found


@njit
def store_impulses(k: int, bodies, context) -> int:
    """Stage 11: the set just written holds the next step's warm-start source; report the
    first body whose state is not finite, or, in a closed system whose energy grew by orders
    of magnitude (:mod:`sandbox.energy_growth`), the body moving fastest (``ctx["diverged"]``,
    -1 when none). Returns 0, or 1 plus that body's index."""
    ctx = context[0]
    cur = 1 - ctx["contact_set"]
    ctx["contact_set"] = cur
    ctx["contact_count"][cur] = k
    ctx["contacts"] = k
    ctx["diverged"] = -1
    for i in range(bodies.shape[0]):
        b = bodies[i]
        s = b["com"][0] + b["com"][1] + b["vel"][0] + b["vel"][1] + b["omega"] + b["angle"]
        if not np.isfinite(s):
            ctx["diverged"] = i
            return 1 + i
    if ctx["energy_limit"] < np.inf:
        ctx["energy"] = closed_energy(bodies, ctx["gravity"][0], ctx["gravity"][1])
        if ctx["energy"] > ctx["energy_limit"]:
            ctx["diverged"] = fastest_body(bodies)
            return 1 + ctx["diverged"]
    return 0


@njit
def find_contacts(shapes, vertices, bodies, joints, proxies, pairs, contacts, context) -> int:
    """Stages 1 and 2: the pairs, then their manifolds into ``contacts``. Returns how many
    contacts, or minus the pair rows needed (as :func:`find_pairs`). With sleep on, an awake
    body touching a sleeping island wakes it (:func:`sandbox.sleep.wake_touched`) and both
    stages run again, for the island's own contacts, left out while it slept."""
    if shapes.shape[0] < 2:
        return 0
    ctx = context[0]
    k = 0
    for _ in range(2):
        npairs = find_pairs(shapes, vertices, bodies, proxies, pairs, context)
        if npairs < 0:
            return npairs
        reach = (ctx["contact_margin"], ctx["look_ahead"])
        k = collide_into(pairs[1], npairs, shapes, vertices, bodies, joints, reach, contacts)
        if not ctx["sleep"] or wake_touched(contacts, k, bodies) == 0:
            break
    return k


@njit
def settle(contacts, k: int, joints, bodies, context) -> None:
    """With sleep on, the end of the step: islands at rest long enough fall asleep
    (:func:`sandbox.sleep.fall_asleep`); ``ctx["awake"]`` counts the bodies still awake,
    ``ctx["fell_asleep"]`` those that fell asleep now (the world then keeps their contacts:
    :func:`sandbox.sleeping_contacts.keep_sleeping_contacts`)."""
    ctx = context[0]
    if ctx["sleep"]:
        ctx["awake"], ctx["fell_asleep"] = fall_asleep(contacts, k, joints, bodies, ctx["dt"])


@njit(python=True)
def finish_step(contacts, k: int, joints, bodies, context) -> int:
    """The end of every step: clear the forces, let islands at rest fall asleep
    (:func:`settle`), keep the impulses (:func:`store_impulses`, whose status it returns). The
    contact points were counted in the prepare stage."""
    clear_forces(bodies)
    settle(contacts, k, joints, bodies, context)
    return store_impulses(k, bodies, context)


# --- the step, in one compiled call ------------------------------------------------------------
@njit
def fast_step(
    bodies, rot, shapes, vertices, joints, generators, sets, proxies, pairs, context, work
) -> int:
    """The stages of :func:`~sandbox.staged_step.staged_step` in one compiled call (sweep and
    prune, the iterative solver, no continuous collision; any integrator and forces, with
    ``work`` the integrator's work arrays, or None without state-dependent forces: see
    :func:`sandbox.integrators.integrate_velocities`). Returns 0, minus the pair rows
    needed when ``pairs`` is too small (nothing changed: grow the buffers and call again), or 1
    plus the index of a body whose state stopped being finite."""
    ctx = context[0]
    model = (bodies, shapes, vertices, joints, generators)
    contacts, previous = sets[1 - ctx["contact_set"]], sets[ctx["contact_set"]]
    k = find_contacts(shapes, vertices, bodies, joints, proxies, pairs, contacts, context)
    if k < 0:
        return k
    arrived = arrived_velocities(bodies)  # stage 5 measures the approach speeds at these
    gather_forces(bodies)
    integrate_velocities(model, context, ctx["dt"], work)
    prepare_joints(joints, bodies, context)
    prepare(contacts, k, (previous, sets[STORE]), shapes, (bodies, arrived), context)
    warm_start_joints(joints, bodies)
    iterative.solve(contacts, k, joints, bodies, context)
    restitution(contacts, k, bodies, ctx["restitution_threshold"])
    plan_motion(bodies, ctx["dt"])
    move_bodies(bodies, rot, context)
    ctx["joints_together"] = False  # the rigid step sweeps its joints' position passes
    fix_positions(contacts, k, joints, bodies, rot, context)
    return finish_step(contacts, k, joints, bodies, context)


# each substep solves with the soft bias, moves the bodies, then relaxes (no bias); a loop over
# the two rather than two calls, so that each solver is compiled once for a bias flag known only
# as it runs (a constant True or False would compile a version of each)
SOLVE_THEN_RELAX = (True, False)


@njit(python=True)
def soft_substeps(contacts, k: int, model, rot, context, ccd, work, plan) -> None:
    """The soft step's substeps (:mod:`sandbox.solvers.soft`; Box2D v3's ``b2SolverStep``):
    each integrates the velocities over h = dt / substeps, warm starts, solves the joints (as
    ``plan``, :func:`~sandbox.joints.solve.soft_joint_plan`, decided once for the step) and
    the contacts with the soft bias, moves the bodies, and relaxes (solves again without
    bias). ``ccd``: None, or for a world with ``ccd`` bodies this step's (contacts, k,
    joints, True), which each substep's moves are limited by
    (:func:`sandbox.toi.limit_ccd_motion`).

    None, not a flag: numba leaves out a branch on ``is not None`` of an argument that is None
    before it types the function, so a step without continuous collision never compiles it
    (a constant False still had it compiled, 8.7 s of the soft step's 20 from an empty cache)."""
    bodies, shapes, vertices, joints, _ = model
    ctx = context[0]
    h = ctx["dt"] / ctx["substeps"]
    joint_soft = softness(ctx["joint_hertz"], ctx["joint_damping_ratio"], h)
    order = soft_order(contacts, k)
    stopped = np.zeros(bodies.shape[0] if ccd is not None else 0, dtype=np.bool_)
    for _ in range(ctx["substeps"]):
        integrate_velocities(model, context, h, work)
        warm_start_joints_soft(joints, bodies)
        if ctx["warm_start"]:
            warm_start(contacts, k, bodies)
        for biased in SOLVE_THEN_RELAX:
            solve_joints_soft_pass(joints, bodies, joint_soft, biased, 1.0 / h, plan)
            solve_soft(contacts, order, bodies, context, biased)
            if not biased:
                break
            plan_motion(bodies, h)
            if ccd is not None:  # no narrowphase between substeps: what it found before them
                frac = limit_ccd_motion(bodies, shapes, vertices, context, ccd)
                hold_stopped(bodies, frac, stopped)
            move_bodies(bodies, rot, context)


@njit(python=True)
def begin_soft(contacts, k: int, kept, model, context) -> None:
    """The soft step's prepare stages: contacts (with their softness and base separations)
    and joints, once for the whole step; the bodies' moves are counted from here."""
    bodies, shapes, joints = model[0], model[1], model[3]
    for i in range(bodies.shape[0]):
        bodies[i]["delta_position"][0] = bodies[i]["delta_position"][1] = 0.0
    prepare(contacts, k, kept, shapes, (bodies, arrived_velocities(bodies)), context)
    ctx = context[0]
    if ctx["hold_ratio"] > 0.0:
        hold_under_heavy_loads(contacts, k, bodies, context)
    prepare_soft(contacts, k, bodies, context)
    gather_forces(bodies)
    prepare_joints_soft(joints, bodies, context)


@njit
def soft_step(
    bodies, rot, shapes, vertices, joints, generators, sets, proxies, pairs, context, work
) -> int:
    """:func:`fast_step` for ``solver: soft``: the pairs and manifolds as always, then the
    soft step's stages (:func:`begin_soft`, :func:`soft_substeps`), the position stage
    (what the soft constraints let sink or stretch beyond the slop), restitution, store."""
    ctx = context[0]
    model = (bodies, shapes, vertices, joints, generators)
    contacts, previous = sets[1 - ctx["contact_set"]], sets[ctx["contact_set"]]
    k = find_contacts(shapes, vertices, bodies, joints, proxies, pairs, contacts, context)
    if k < 0:
        return k
    begin_soft(contacts, k, (previous, sets[STORE]), model, context)
    plan = soft_joint_plan(joints, bodies, context)
    soft_substeps(contacts, k, model, rot, context, None, work, plan)
    ctx["joints_together"] = plan[1]  # as the relax pass
    fix_positions(contacts, k, joints, bodies, rot, context)
    restitution(contacts, k, bodies, ctx["restitution_threshold"])
    return finish_step(contacts, k, joints, bodies, context)


@njit
def free_step(bodies, rot, context, fields) -> int:
    """:func:`fast_step` for a world with fewer than two shapes and no joints (nothing can
    touch anything): the velocities, then the positions. ``fields``: None when no force
    depends on the bodies' state (the constant forces then need the bodies and the context
    alone), else ``(shapes, vertices, joints, generators, work)`` for
    :func:`sandbox.integrators.integrate_velocities`. This is the whole cost of stepping a
    single body, and each array handed over from Python costs about 50 ns (numba wraps it in
    a memory record of its own for the call): three arrays rather than eight."""
    gather_forces(bodies)
    dt = context[0]["dt"]
    if fields is None:  # numba compiles a version for each, without the other's branch
        integrate_constant(bodies, context, dt)
    else:
        shapes, vertices, joints, generators, work = fields
        integrate_velocities((bodies, shapes, vertices, joints, generators), context, dt, work)
    plan_motion(bodies, dt)
    move_bodies(bodies, rot, context)
    context[0]["contact_points"] = 0
    clear_forces(bodies)
    return store_impulses(np.int64(0), bodies, context)  # no contacts (np.int64: see jit.ON)


def __getattr__(name: str):
    """``sandbox.step.StageTimer`` and ``staged_step``, where they were before they moved to
    :mod:`sandbox.staged_step` (imported on first use: that module imports this one)."""
    if name in ("StageTimer", "staged_step"):
        from sandbox import staged_step

        return getattr(staged_step, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
