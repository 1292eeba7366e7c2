"""The soft step's position stage over its joints, solved together: the position twin of
:mod:`sandbox.joints.direct` (non-linear Gauss-Seidel with one linear solve per pass instead of
one joint at a time), run where the relax pass solves the joints together
(:func:`sandbox.joints.solve.soft_joint_plan`) by :func:`sandbox.penetration.fix_positions`.
"""

from __future__ import annotations

import numpy as np

from sandbox.jit import njit
from sandbox.joints.base import MAX_LINEAR_CORRECTION, arm, inverse_masses
from sandbox.joints.direct import count_rows, set_row, solve_rows
from sandbox.joints.pin import rod
from sandbox.joints.pivot import solve_limit_position
from sandbox.math2d import cross, nudge
from sandbox.records import JOINT_ROW, PIN, PIVOT

# the position passes solved together: turning counts TURN_WEIGHT times what the body's
# moment of inertia says (1/I scaled by it); no pass turns a body more than MAX_TURN (rad)
TURN_WEIGHT = 0.01
MAX_TURN = 0.15


@njit
def solve_joint_positions_together(joints, bodies) -> float:
    """The position stage's pass over the joints, solved together: limits swept (as
    :func:`~sandbox.joints.pivot.solve_pivot_position`), then every point row at once, the
    position twin of :func:`~sandbox.joints.direct.solve_joints_direct`: K Delta = -C, K at the
    arms now, C the anchors' gap (a pivot's (c_b + r_b) - (c_a + r_a), a pin's |p_b - p_a| - L
    along the rod, at most ``MAX_LINEAR_CORRECTION``), and each body moved by its share.

    Swept one joint at a time, a light chain passes a heavy ball's pull on as slowly as the
    velocity sweeps do, and three passes left a 10-link chain under a ball of 100 links 7 to
    15 mm stretched. Solved together with the bodies' own masses, the linear solve closes a
    snapping chain's gaps by turning its light links (cheap, against moving the heavy ball) and
    turning is not linear: near a straight taut line it barely shortens the chain, and passes
    turned links by tenths of a radian while the gaps stayed. A position pass is a projection
    onto the joints, not dynamics, so any correction that closes them will do: here turning
    weighs 1 / TURN_WEIGHT times more than the moments of inertia say, the bodies move rather
    than turn, and moving is linear (a pivot's gap closes in one pass where only moves close
    it). A pass that would still turn a body more than MAX_TURN or move it more than
    ``MAX_LINEAR_CORRECTION`` is scaled down (a joint placed far from closed is not closed in
    one jump through whatever lies between). Returns the largest error found before the pass
    (m or rad)."""
    worst = 0.0
    for i in range(joints.shape[0]):
        if joints[i]["kind"] == PIVOT:
            worst = max(worst, solve_limit_position(joints[i], bodies))
    m = count_rows(joints)
    if m == 0:
        return worst
    rows = np.empty(m, dtype=JOINT_ROW)
    arms = np.zeros((joints.shape[0], 4))  # r_a, r_b before the pass: K's arms
    r = 0
    for i in range(joints.shape[0]):
        j = joints[i]
        if j["kind"] == PIVOT:
            ra, rb = arm(bodies[j["a"]], j["local_a"]), arm(bodies[j["b"]], j["local_b"])
            cx = bodies[j["b"]]["com"][0] + rb[0] - bodies[j["a"]]["com"][0] - ra[0]
            cy = bodies[j["b"]]["com"][1] + rb[1] - bodies[j["a"]]["com"][1] - ra[1]
            worst = max(worst, np.hypot(cx, cy))
            set_row(rows[r], i, j, bodies, (ra, rb), (1.0, 0.0), cx, 0.0)
            set_row(rows[r + 1], i, j, bodies, (ra, rb), (0.0, 1.0), cy, 0.0)
            r += 2
        elif j["kind"] == PIN:
            ra, rb, u, length, _ = rod(j, bodies)
            error = length - j["length"]
            worst = max(worst, abs(error))
            error = min(max(error, -MAX_LINEAR_CORRECTION), MAX_LINEAR_CORRECTION)
            set_row(rows[r], i, j, bodies, (ra, rb), u, error, 0.0)
            r += 1
        else:
            continue
        arms[i, 0], arms[i, 1], arms[i, 2], arms[i, 3] = ra[0], ra[1], rb[0], rb[1]
    for r in range(m):  # turning weighs more (see above): 1/I_a, 1/I_b scaled down
        rows[r]["inverse"][1] *= TURN_WEIGHT
        rows[r]["inverse"][3] *= TURN_WEIGHT
    delta = solve_rows(rows, bodies, 0.0)
    push = np.zeros((joints.shape[0], 2))  # each joint's pseudo impulse P = sum of Delta_r d_r
    turn = np.zeros(bodies.shape[0])  # how far P would turn each body (rad) ...
    move = np.zeros((bodies.shape[0], 2))  # ... and move it (m)
    for r in range(m):
        i = rows[r]["joint"]
        push[i, 0] += delta[r] * rows[r]["d"][0]
        push[i, 1] += delta[r] * rows[r]["d"][1]
    for i in range(joints.shape[0]):
        j = joints[i]
        mass = inverse_masses(j, bodies)
        mass = (mass[0], TURN_WEIGHT * mass[1], mass[2], TURN_WEIGHT * mass[3])
        turn[j["a"]] -= mass[1] * cross(arms[i, 0], arms[i, 1], push[i, 0], push[i, 1])
        turn[j["b"]] += mass[3] * cross(arms[i, 2], arms[i, 3], push[i, 0], push[i, 1])
        for q in range(2):
            move[j["a"], q] -= mass[0] * push[i, q]
            move[j["b"], q] += mass[2] * push[i, q]
    # bounded steps: the whole pass scaled down where a body would turn or move too far
    scale = 1.0
    for x in range(bodies.shape[0]):
        scale = min(scale, MAX_TURN / max(abs(turn[x]), 1e-300))
        scale = min(scale, MAX_LINEAR_CORRECTION / max(np.hypot(move[x, 0], move[x, 1]), 1e-300))
    for x in range(bodies.shape[0]):
        if move[x, 0] != 0.0 or move[x, 1] != 0.0 or turn[x] != 0.0:
            nudge(bodies[x], scale * move[x, 0], scale * move[x, 1], scale * turn[x])
    return worst
