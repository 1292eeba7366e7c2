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
"""

from __future__ import annotations

from sandbox.jit import njit
from sandbox.joints.pin import prepare_pin, solve_pin_position, solve_pin_velocity, warm_start_pin
from sandbox.joints.pivot import (
    prepare_pivot,
    solve_pivot_position,
    solve_pivot_velocity,
    warm_start_pivot,
)
from sandbox.records import PIN, PIVOT


@njit
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


@njit
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
