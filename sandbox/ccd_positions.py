"""Continuous collision for the position stage: a ``ccd`` body pushed out of one shape is not
pushed through another (slides, "Conservative Advancement", applied to the position passes).

The position stage (:mod:`sandbox.penetration`) moves bodies to remove overlap, and sees only
the contacts the narrowphase found at the start of the step. When a heavy body drives deep
into a light ``ccd`` body (continuous collision leaves a pair whose core already overlaps to
the solver and this stage), the stage takes the light body out in one pass: a metre or more,
through a wall no contact knew of. So the stage's move of each ``ccd`` body is swept like the
step's own motion (:func:`sandbox.toi.ccd_fractions`), from its pose before the stage to its
pose after, and cut at the first impact; the next step's narrowphase finds that contact.
"""

from __future__ import annotations

import numpy as np

from sandbox.jit import njit
from sandbox.orientation import turn_body
from sandbox.toi import impact_target, limit_ccd_motion


@njit(python=True)
def poses(bodies) -> np.ndarray:
    """Each body's pose (x, y, angle) as (n, 3): centre of mass (m) and continuous angle (rad)."""
    out = np.empty((bodies.shape[0], 3))
    for i in range(bodies.shape[0]):
        b = bodies[i]
        out[i, 0], out[i, 1], out[i, 2] = b["com"][0], b["com"][1], b["angle"]
    return out


@njit
def sweep_position_moves(bodies, rot, shapes, vertices, context, before, found) -> None:
    """Cut each ``ccd`` body's move by the position stage, from pose ``before``
    (:func:`poses`, taken before the stage) to where the stage left it, at its first impact:
    ``motion`` and ``motion_turn`` become the stage's move, other bodies stand still (they
    have moved already), and :func:`~sandbox.toi.limit_ccd_motion` (with ``found`` = this
    step's (contacts, k, joints, True)) shortens it as it does the step's own motion. Nothing at
    all unless some ``ccd`` body moved further than the impact target: a smaller move cannot
    cross a face the narrowphase would not see next step."""
    target = impact_target(context)
    after = poses(bodies)
    far = False
    for i in range(bodies.shape[0]):
        b = bodies[i]
        dx, dy, turn = after[i, 0] - before[i, 0], after[i, 1] - before[i, 1], 0.0
        if b["ccd"]:
            turn = after[i, 2] - before[i, 2]
            far = far or dx * dx + dy * dy > target * target
        else:
            dx = dy = 0.0
        b["motion"][0], b["motion"][1], b["motion_turn"] = dx, dy, turn
    for k in range(shapes.shape[0]):  # a turn moves a shape's points by up to turn * bound
        far = far or abs(bodies[shapes[k]["body"]]["motion_turn"]) * shapes[k]["bound"] > target
    if not far:
        return
    for i in range(bodies.shape[0]):  # the sweep starts from where the stage began
        if bodies[i]["ccd"]:
            b = bodies[i]
            b["com"][0], b["com"][1], b["angle"] = before[i, 0], before[i, 1], before[i, 2]
    frac = limit_ccd_motion(bodies, shapes, vertices, context, found)
    kind, renormalise = context[0]["orientation"], context[0]["renormalise"]
    for i in range(bodies.shape[0]):
        b = bodies[i]
        if not b["ccd"]:
            continue
        b["angle"] = after[i, 2]
        if frac[i] == 1.0:  # the whole move, exactly as the stage left it
            b["com"][0], b["com"][1] = after[i, 0], after[i, 1]
            continue
        b["com"][0], b["com"][1] = before[i, 0] + b["motion"][0], before[i, 1] + b["motion"][1]
        turn = after[i, 2] - before[i, 2]
        if turn != 0.0:  # back by the part of the turn past the impact
            turn_body(bodies, rot, i, kind, -(1.0 - frac[i]) * turn, renormalise)
