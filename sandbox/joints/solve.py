"""The joint stages of the step: every joint record, by kind (pin or pivot; springs are forces
and are skipped here). Box2D's ``b2PrepareJointsTask``, ``b2WarmStartJoint``, ``b2SolveJoint``.

Per step::

    prepare_joints        arms, effective masses, arc-corrected targets (after the velocities
                          were integrated: the arc correction reads this step's velocities)
    warm_start_joints     last step's accumulated impulses again (``settings.warm_start``)
    solve_joint_velocities  once per solver iteration, interleaved with the contacts
    ... positions move ...
    solve_joint_positions   once per position pass, after the contacts' pass (returns the
                            largest error, m or rad)

The soft step (:mod:`sandbox.solvers.soft`) prepares them once per step
(``prepare_joints_soft``) and in each substep warm starts them, then solves them with the soft
bias and relaxes them without (``solve_joints_soft_pass``): all together
(:mod:`sandbox.joints.direct`; by default wherever that is cheap) or one at a time
(``solve_joints_soft``).
"""

from __future__ import annotations

from sandbox.jit import njit
from sandbox.joints.direct import has_axial, has_loop, narrow, solve_joints_direct
from sandbox.joints.pin import (
    prepare_pin,
    solve_pin_position,
    solve_pin_soft,
    solve_pin_velocity,
    warm_start_pin,
    warm_start_pin_soft,
)
from sandbox.joints.pivot import (
    prepare_pivot,
    solve_pivot_position,
    solve_pivot_soft,
    solve_pivot_velocity,
    warm_start_pivot,
    warm_start_pivot_soft,
)
from sandbox.records import PIN, PIVOT

AUTO, DIRECT, SWEEPS = 0, 1, 2  # settings.joint_solver (sandbox.settings.JOINT_SOLVERS)


@njit(python=True)
def prepare_joints(joints, bodies, context) -> None:
    """Every pin and pivot prepared for a step of ``ctx["dt"]``."""
    ctx = context[0]
    warm = ctx["warm_start"]
    for i in range(joints.shape[0]):
        j = joints[i]
        if j["kind"] == PIN:
            prepare_pin(j, bodies, ctx["dt"], warm)
        elif j["kind"] == PIVOT:
            prepare_pivot(j, bodies, ctx["dt"], warm)


@njit(python=True)
def warm_start_joints(joints, bodies) -> None:
    """Apply every joint's accumulated impulses again."""
    for i in range(joints.shape[0]):
        j = joints[i]
        if j["kind"] == PIN:
            warm_start_pin(j, bodies)
        elif j["kind"] == PIVOT:
            warm_start_pivot(j, bodies)


@njit
def solve_joint_velocities(joints, bodies, accumulate: bool) -> None:
    """One velocity pass over the joints."""
    for i in range(joints.shape[0]):
        j = joints[i]
        if j["kind"] == PIN:
            solve_pin_velocity(j, bodies)
        elif j["kind"] == PIVOT:
            solve_pivot_velocity(j, bodies, accumulate)


@njit
def solve_joint_positions(joints, bodies) -> float:
    """One position pass over the joints; returns the largest error found (m or rad)."""
    worst = 0.0
    for i in range(joints.shape[0]):
        j = joints[i]
        if j["kind"] == PIN:
            worst = max(worst, solve_pin_position(j, bodies))
        elif j["kind"] == PIVOT:
            worst = max(worst, solve_pivot_position(j, bodies))
    return worst


# --- the soft step (sandbox.solvers.soft): prepared once per step, then every substep ----------
@njit
def prepare_joints_soft(joints, bodies, context) -> None:
    """:func:`prepare_joints` for a substep h = dt / substeps, and each joint's
    c_b - c_a at the start of the step."""
    ctx = context[0]
    h = ctx["dt"] / ctx["substeps"]
    for i in range(joints.shape[0]):
        j = joints[i]
        a, b = bodies[j["a"]], bodies[j["b"]]
        j["delta_center"][0] = b["com"][0] - a["com"][0]
        j["delta_center"][1] = b["com"][1] - a["com"][1]
        if j["kind"] == PIN:
            prepare_pin(j, bodies, h, ctx["warm_start"])
        elif j["kind"] == PIVOT:
            prepare_pivot(j, bodies, h, ctx["warm_start"])


@njit
def warm_start_joints_soft(joints, bodies) -> None:
    """Every joint's accumulated impulses again, at the bodies' current poses."""
    for i in range(joints.shape[0]):
        j = joints[i]
        if j["kind"] == PIN:
            warm_start_pin_soft(j, bodies)
        elif j["kind"] == PIVOT:
            warm_start_pivot_soft(j, bodies)


@njit(python=True)
def solve_joints_soft(joints, bodies, soft, use_bias: bool, inv_h: float) -> None:
    """One soft pass over the joints (``soft`` = (bias_rate, mass_scale, impulse_scale));
    rigid and without bias when ``use_bias`` is off (the relax pass)."""
    for i in range(joints.shape[0]):
        j = joints[i]
        if j["kind"] == PIN:
            solve_pin_soft(j, bodies, soft, use_bias)
        elif j["kind"] == PIVOT:
            solve_pivot_soft(j, bodies, soft, use_bias, inv_h)


@njit(python=True)
def soft_joint_plan(joints, bodies, context) -> tuple[bool, bool, int]:
    """How a soft step treats its joints, decided once per step (the joint graph does not change
    within it): (solve them together in the biased pass, together in the relax pass, biased
    passes per substep).

    Together (:mod:`sandbox.joints.direct`) under ``joint_solver: direct``, and under ``auto``
    where the factorisation is cheap (:func:`~sandbox.joints.direct.narrow`); once, or
    ``iterations`` times while motors or limits are swept beside the point rows. Swept:
    ``iterations`` times in the solve (joints are few and a chain's error travels), once in the
    relax. Where the joints close a loop (:func:`~sandbox.joints.direct.has_loop`) the relax
    pass is swept: its rigid system can be singular there, and the velocity targets of the arc
    correction are not quite consistent around a loop, which a solve together would amplify."""
    ctx = context[0]
    how = ctx["joint_solver"]
    together = joints.shape[0] > 0 and (how == DIRECT or (how == AUTO and narrow(joints, bodies)))
    relax_together = together and not has_loop(joints, bodies)
    passes = ctx["iterations"] if not together or has_axial(joints) else 1
    return together, relax_together, passes


@njit
def solve_joints_soft_pass(joints, bodies, joint_soft, use_bias: bool, inv_h: float, plan) -> None:
    """The joints' share of a soft substep's solve (``use_bias``) or relax pass, as
    :func:`soft_joint_plan` decided."""
    if joints.shape[0] == 0:
        return
    together, relax_together, passes = plan
    direct = together if use_bias else relax_together
    for _ in range(passes if use_bias else 1):
        if direct:
            solve_joints_direct(joints, bodies, joint_soft, use_bias, inv_h)
        else:
            solve_joints_soft(joints, bodies, joint_soft, use_bias, inv_h)
