"""The step stage by stage from Python (:func:`staged_step`), for any settings, and a timer of
its stages (:class:`StageTimer`).

:func:`sandbox.step.fast_step` and :func:`sandbox.step.soft_step` run the stages of a step in
one compiled call, for the usual world. Any other settings (another broadphase or solver,
continuous collision) come here, and so does a world with a stage timer
(``world.timer = StageTimer()``): each stage, the very same compiled function as in the
one-call step and in the same order, is called from Python, so both paths give the same
numbers to the bit (``tests/test_step.py``), and the time between two calls is the stage's.
"""

from __future__ import annotations

import time

import numpy as np

from sandbox.ccd_positions import poses, sweep_position_moves
from sandbox.integrators import gather_forces, integrate_velocities, move_bodies, plan_motion
from sandbox.jit import JIT_ENABLED
from sandbox.joints.solve import prepare_joints, soft_joint_plan, warm_start_joints
from sandbox.narrowphase import collide_into
from sandbox.penetration import fix_positions
from sandbox.plain_records import staged_view
from sandbox.records import STORE
from sandbox.sleep import wake_touched
from sandbox.solvers import SOLVERS
from sandbox.solvers.common import arrived_velocities, restitution
from sandbox.step import (
    STAGES,
    begin_soft,
    find_contacts,
    find_pairs,
    finish_step,
    place_proxies,
    prepare,
    soft_substeps,
)
from sandbox.toi import limit_ccd_motion


class StageTimer:
    """Wall time of every stage, added up over the steps taken with it (s)."""

    def __init__(self) -> None:
        self.seconds = dict.fromkeys(STAGES, 0.0)
        self.steps = 0
        self._last = 0.0

    def start(self) -> None:
        self._last = time.perf_counter()

    def lap(self, stage: str) -> None:
        now = time.perf_counter()
        self.seconds[stage] += now - self._last
        self._last = now

    def done(self) -> None:
        """A step is over."""
        self.steps += 1


class _NoTimer:
    def start(self) -> None:
        pass

    def lap(self, stage: str) -> None:
        pass

    def done(self) -> None:
        pass


def staged_pairs(world, a, ctx) -> int:
    """Stage 1 with the world's broadphase (sweep and prune compiled with its kept order; the
    other strategies through :func:`sandbox.broadphase.find_pairs`)."""
    from sandbox.broadphase import find_pairs as find_pairs_by_name

    if world.settings.broadphase == "sap":
        return find_pairs(
            a.shapes, a.vertices, a.bodies, a.buffers.proxies, a.buffers.pairs, a.context
        )
    proxies = a.buffers.proxies
    reach = (ctx["contact_margin"], ctx["look_ahead"], 0.0)  # the exact boxes: no stretch
    place_proxies(a.shapes, a.vertices, a.bodies, reach, proxies)
    found, tests = find_pairs_by_name(
        world.settings.broadphase,
        np.ascontiguousarray(proxies["aabb"]),
        np.ascontiguousarray(proxies["fixed"]),
        np.ascontiguousarray(proxies["body"]),
    )
    ctx["pair_tests"] = tests
    ctx["pairs_kept"] = False  # boxes without the spare margin: sweep and prune sweeps again
    k = len(found)
    if k > a.buffers.pairs.shape[1]:
        return -k
    a.buffers.pairs[1, :k] = found
    ctx["pairs"] = k
    return k


def staged_step(world, timer: StageTimer | None = None) -> int:
    """One step, stage by stage (any settings). Returns 0, minus the pair rows needed, or 1
    plus the index of a body whose state stopped being finite."""
    a = world.arrays()
    if not JIT_ENABLED:  # uncompiled: the records through their fast view (sandbox.jit.bound)
        a = staged_view(world, a)
    ctx = a.context[0]
    clock = timer if timer is not None else _NoTimer()
    clock.start()
    model = (a.bodies, a.shapes, a.vertices, a.joints, a.generators)
    sets = a.buffers.sets
    contacts, previous = sets[1 - ctx["contact_set"]], sets[ctx["contact_set"]]
    k = 0
    if a.shapes.shape[0] >= 2:
        npairs = staged_pairs(world, a, ctx)
        if npairs < 0:
            return npairs
        clock.lap("find_pairs")
        geometry = (a.shapes, a.vertices, a.bodies, a.joints)
        reach = (ctx["contact_margin"], ctx["look_ahead"])
        k = collide_into(a.buffers.pairs[1], npairs, *geometry, reach, contacts)
        if ctx["sleep"] and wake_touched(contacts, k, a.bodies) > 0:
            buffers = (a.buffers.proxies, a.buffers.pairs)
            k = find_contacts(*geometry, *buffers, contacts, a.context)
            if k < 0:
                return k
        clock.lap("collide")
    if world.settings.solver == "soft":
        return staged_soft(world, (contacts, k, previous), a, clock)
    arrived = arrived_velocities(a.bodies)
    gather_forces(a.bodies)
    integrate_velocities(model, a.context, ctx["dt"], a.work)
    clock.lap("integrate_velocities")
    prepare_joints(a.joints, a.bodies, a.context)
    clock.lap("prepare_joints")
    prepare(contacts, k, (previous, sets[STORE]), a.shapes, (a.bodies, arrived), a.context)
    clock.lap("prepare_contacts")
    warm_start_joints(a.joints, a.bodies)
    clock.lap("warm_start")
    SOLVERS[world.settings.solver].solve(contacts, k, a.joints, a.bodies, a.context)
    clock.lap("solve")
    restitution(contacts, k, a.bodies, ctx["restitution_threshold"])
    clock.lap("restitution")
    plan_motion(a.bodies, ctx["dt"])
    if world.has_ccd:
        limit_ccd_motion(a.bodies, a.shapes, a.vertices, a.context, (contacts, k, a.joints, False))
    move_bodies(a.bodies, a.rot, a.context)
    clock.lap("integrate_positions")
    position_stage(world, a, (contacts, k), False)
    clock.lap("fix_positions")
    status = finish_step(contacts, k, a.joints, a.bodies, a.context)
    clock.lap("store_impulses")
    clock.done()
    return status


def staged_soft(world, found, a, clock) -> int:
    """The rest of :func:`staged_step` for ``solver: soft`` (see :func:`soft_step`)."""
    contacts, k, previous = found
    ctx = a.context[0]
    model = (a.bodies, a.shapes, a.vertices, a.joints, a.generators)
    begin_soft(contacts, k, (previous, a.buffers.sets[STORE]), model, a.context)
    clock.lap("prepare_contacts")
    plan = soft_joint_plan(a.joints, a.bodies, a.context)
    ccd = (contacts, k, a.joints, True) if world.has_ccd else None
    soft_substeps(contacts, k, model, a.rot, a.context, ccd, a.work, plan)
    position_stage(world, a, (contacts, k), plan[1])
    clock.lap("solve")
    restitution(contacts, k, a.bodies, ctx["restitution_threshold"])
    clock.lap("restitution")
    status = finish_step(contacts, k, a.joints, a.bodies, a.context)
    clock.lap("store_impulses")
    clock.done()
    return status


def position_stage(world, a, found, joints_together: bool) -> None:
    """The position stage of the staged steps (:func:`~sandbox.penetration.fix_positions`;
    ``joints_together`` as the soft step plans it, False in the rigid step), with its moves of
    the ``ccd`` bodies swept when the world has any
    (:func:`~sandbox.ccd_positions.sweep_position_moves`). Every argument is passed (the flag
    in the context, as the one-call steps pass it): with a default left out, this call took
    numba's slow dispatch every step, 1.4 ms (tests/test_dispatch.py)."""
    contacts, k = found
    before = poses(a.bodies) if world.has_ccd else None
    a.context[0]["joints_together"] = joints_together
    fix_positions(contacts, k, a.joints, a.bodies, a.rot, a.context)
    if before is not None:
        geometry = (a.bodies, a.rot, a.shapes, a.vertices, a.context)
        sweep_position_moves(*geometry, before, (contacts, k, a.joints, True))
