"""The joints of the soft step solved together, exactly: one linear solve per pass instead of
sweeps (``settings.joint_solver: "direct"``; ``"auto"``, the default, where :func:`narrow`).

Sweeps solve one joint at a time (Gauss-Seidel). Along a chain whose links are light and whose
load is heavy (a ball of 100 links on a chain of 10), each joint's impulse is undone by the
next, and the sweeps converge so slowly that the chain stretches by centimetres. The joints'
point rows are linear in the impulses, so all of them can be solved at once.

Each row r is one scalar constraint of one joint (a pivot has two, x and y; a pin one, along
the rod; :data:`sandbox.records.JOINT_ROW`): Cdot_r = d_r . (v_b + w_b x r_b - v_a - w_a x r_a),
with the impulse lambda_r d_r on b and -lambda_r d_r on a. An impulse on row s changes row r's
speed by K_rs lambda_s, K = J M^-1 J^T the effective-mass matrix: for each body X the two rows
share (sign +1 as b, -1 as a),

    K_rs += s_r s_s (d_r . d_s / m_X + (r_rX x d_r)(r_sX x d_s) / I_X).

A soft joint (:mod:`sandbox.solvers.soft`) swept until nothing changes comes to rest where every
joint j satisfies mass_scale (Cdot_j + bias_j) + impulse_scale B_j lambda_j = 0, B_j the block
of K a sweep divides by (a pivot's own 2x2 block, a pin's prepared 1 / m_eff). With Delta the
change of the accumulated impulses lambda_0 in this pass and c = impulse_scale / mass_scale,
that is one linear system,

    (K + c B) Delta = -(Cdot + bias) - c B lambda_0,

solved here by Cholesky factorisation. The result is where infinitely many sweeps of the same
soft joints go: the same springs, with the same static error F / (m_eff omega^2) per joint, and
none of the sweeps' slowness. Exactly so for the linear rows; but each pivot's arc correction
reads the bodies' angular velocities, which a pass changes: one pass uses them as they were at
its start, a sweep as they are. On a chain whipping at tens of rad/s one pass can land metres
per second from where the sweeps converge (the soft step lesson, section 6: 2.5 m/s, where the
ten sweeps a substep would get are 12 m/s off); a second pass takes most of that out. The
relax pass is the rigid case (c = 0, no bias). Where the joints close a loop (:func:`has_loop`)
its rows can be redundant and the rigid system singular; a row that depends on those before it
is dropped, but the arc correction's velocity targets are not quite consistent around a loop,
and a nearly dependent row amplifies that (a 10 x 10 net of hinges blew up), so there the step
sweeps the relax pass (:mod:`sandbox.joints.solve`). Motors and limits stay in sweeps, before the point rows, as in
:func:`sandbox.joints.pivot.solve_pivot_soft`.

Cost: K is sparse (rows couple only through a shared body) and Cholesky keeps its envelope
(:func:`envelope`): along a chain listed in order each row reaches back two joints and a pass
costs O(rows), about three sweeps' worth; a net of joints w rows wide costs O(rows w^2), and
``joint_solver: auto`` sweeps it instead (:func:`narrow`).
"""

from __future__ import annotations

import numpy as np

from sandbox.jit import njit
from sandbox.joints.base import apply_joint_impulse, arm, inverse_masses
from sandbox.joints.pin import pin_rod_error
from sandbox.joints.pivot import pivot_point_error, solve_pivot_axial_soft
from sandbox.math2d import cross, set_velocity, velocity_of
from sandbox.records import JOINT_ROW, PIN, PIVOT
from sandbox.sleep import root  # union-find, as the sleeping islands use it

NARROW = 100.0  # joint_solver auto: together while the mean squared reach is at most this
DEPENDENT = 1e-9  # a pivot below this times its row's diagonal: a redundant row, dropped


@njit
def moves(body) -> bool:
    """Whether an impulse can move the body (it has a finite mass or moment of inertia): a body
    that cannot move couples no joints and closes no loops."""
    return body["inv_mass"] != 0.0 or body["inv_moment"] != 0.0


@njit
def count_rows(joints) -> int:
    """Point rows of the pins (one each) and pivots (two each)."""
    m = 0
    for i in range(joints.shape[0]):
        kind = joints[i]["kind"]
        m += 1 if kind == PIN else 2 if kind == PIVOT else 0
    return m


@njit
def set_row(row, i: int, j, bodies, arms, d, error: float, impulse: float) -> None:
    """Row ``row`` of joint ``j`` (number ``i``) along ``d``, arms ``arms`` = (r_a, r_b)."""
    ra, rb = arms
    row["joint"], row["a"], row["b"] = i, j["a"], j["b"]
    row["d"][0], row["d"][1] = d
    row["arm_a"], row["arm_b"] = cross(ra[0], ra[1], d[0], d[1]), cross(rb[0], rb[1], d[0], d[1])
    mass = inverse_masses(j, bodies)
    for q in range(4):
        row["inverse"][q] = mass[q]
    row["error"], row["impulse"] = error, impulse
    row["own"] = 1.0 / j["axial_mass"] if j["kind"] == PIN and j["axial_mass"] > 0.0 else 0.0


@njit
def gather_rows(joints, bodies, soft, use_bias: bool, rows) -> None:
    """Every pin's and pivot's rows, with their errors Cdot + bias as the bodies move now."""
    m = 0
    for i in range(joints.shape[0]):
        j = joints[i]
        if j["kind"] == PIVOT:
            pair = bodies[j["a"]], bodies[j["b"]]
            ra, rb, ex, ey = pivot_point_error(j, pair, soft, use_bias)
            set_row(rows[m], i, j, bodies, (ra, rb), (1.0, 0.0), ex, j["impulse"][0])
            set_row(rows[m + 1], i, j, bodies, (ra, rb), (0.0, 1.0), ey, j["impulse"][1])
            m += 2
        elif j["kind"] == PIN:
            ra, rb, u, e = pin_rod_error(j, bodies, soft, use_bias)
            set_row(rows[m], i, j, bodies, (ra, rb), u, e, j["impulse"][0])
            m += 1


@njit
def coupling(rows, r: int, s: int) -> float:
    """K_rs: how an impulse on row s changes row r's speed (1/kg), through every body the
    two rows' joints share."""
    p, q = rows[r], rows[s]
    linear = p["d"][0] * q["d"][0] + p["d"][1] * q["d"][1]
    total = 0.0
    for side_p in range(2):
        x = p["a"] if side_p == 0 else p["b"]
        for side_q in range(2):
            if (q["a"] if side_q == 0 else q["b"]) != x:
                continue
            sign = (1.0 if side_p == 1 else -1.0) * (1.0 if side_q == 1 else -1.0)
            turning = (p["arm_b"] if side_p else p["arm_a"]) * (
                q["arm_b"] if side_q else q["arm_a"]
            )
            total += sign * (
                linear * p["inverse"][2 * side_p] + turning * p["inverse"][2 * side_p + 1]
            )
    return total


@njit
def own_block(rows, r: int, s: int) -> float:
    """B_rs for two rows of one joint: the block a sweep divides by, a pivot's own K at the
    arms now, a pin's effective mass along the rod as prepared for the step."""
    return rows[r]["own"] if rows[r]["own"] > 0.0 else coupling(rows, r, s)


@njit
def envelope(rows, moving, first, start) -> None:
    """``first[r]``: the first row of any joint that shares a moving body with row r's joint
    (K_rs = 0 for every s before it); ``start[r]``: where row r's entries first[r] .. r begin
    in the packed lower triangle (``start[m]`` entries in all). Cholesky fills nothing
    outside this envelope."""
    m = rows.shape[0]
    lowest = np.full(moving.shape[0], m, dtype=np.int64)
    start[0] = 0
    for r in range(m):
        reach = r
        for x in (rows[r]["a"], rows[r]["b"]):
            if moving[x]:  # a body that cannot move couples nothing
                lowest[x] = min(lowest[x], r)
                reach = min(reach, lowest[x])
        first[r] = reach
        start[r + 1] = start[r] + r - reach + 1


@njit
def at(first, start, r: int, s: int) -> int:
    """Index of entry (r, s), first[r] <= s <= r, in the packed lower triangle."""
    return start[r] + s - first[r]


@njit
def assemble(rows, c: float, first, start, a, rhs) -> None:
    """A = K + c B packed into ``a``; rhs = -(Cdot + bias) - c B lambda_0."""
    m = rows.shape[0]
    for r in range(m):
        own = 0.0
        for s in range(first[r], m):
            if rows[s]["joint"] == rows[r]["joint"]:
                own += own_block(rows, r, s) * rows[s]["impulse"]
            elif s > r:
                break
        rhs[r] = -rows[r]["error"] - c * own
        for s in range(first[r], r + 1):
            k = coupling(rows, r, s)
            if rows[s]["joint"] == rows[r]["joint"]:
                k += c * own_block(rows, r, s)
            a[at(first, start, r, s)] = k


@njit
def cholesky_solve(a, b, first, start) -> None:
    """Solve A x = b in place (x into ``b``) for the symmetric positive semi-definite A whose
    lower triangle is packed in ``a`` within its envelope (:func:`envelope`; overwritten by L,
    A = L L^T). A row that depends on the rows before it (a closed loop's redundant row: its
    pivot falls below DEPENDENT times its diagonal) is dropped, x_r = 0."""
    m = b.shape[0]
    for i in range(m):
        diagonal = a[at(first, start, i, i)]
        for k in range(first[i], i + 1):
            total = a[at(first, start, i, k)]
            for p in range(max(first[i], first[k]), k):
                total -= a[at(first, start, i, p)] * a[at(first, start, k, p)]
            if k < i:
                total /= a[at(first, start, k, k)]
            elif total > DEPENDENT * diagonal:
                total = np.sqrt(total)
            else:
                total = np.inf  # L's column i is zero below, and x_i = 0
            a[at(first, start, i, k)] = total
    for i in range(m):  # L y = b
        total = b[i]
        for p in range(first[i], i):
            total -= a[at(first, start, i, p)] * b[p]
        b[i] = total / a[at(first, start, i, i)]
    for i in range(m - 1, -1, -1):  # L^T x = y, a column at a time
        b[i] /= a[at(first, start, i, i)]
        for p in range(first[i], i):
            b[p] -= a[at(first, start, i, p)] * b[i]


@njit
def apply_rows(joints, bodies, rows, delta) -> None:
    """Each joint's share of the solution: its impulse P = sum over its rows of Delta_r d_r,
    on b at r_b and -P on a at r_a, and added to its accumulated impulse."""
    r, m = 0, rows.shape[0]
    while r < m:
        i = rows[r]["joint"]
        j = joints[i]
        px = py = 0.0
        q = 0
        while r < m and rows[r]["joint"] == i:
            px += delta[r] * rows[r]["d"][0]
            py += delta[r] * rows[r]["d"][1]
            j["impulse"][q] += delta[r]
            r, q = r + 1, q + 1
        ra, rb = arm(bodies[j["a"]], j["local_a"]), arm(bodies[j["b"]], j["local_b"])
        va, vb = velocity_of(bodies, j["a"]), velocity_of(bodies, j["b"])
        va, vb = apply_joint_impulse(va, vb, inverse_masses(j, bodies), ra, rb, px, py, 0.0)
        set_velocity(bodies, j["a"], va)
        set_velocity(bodies, j["b"], vb)


@njit
def has_axial(joints) -> bool:
    """Whether any pivot has a motor or limits (swept, so passes must repeat)."""
    for i in range(joints.shape[0]):
        j = joints[i]
        if j["kind"] == PIVOT and (j["has_motor"] or j["has_limits"]):
            return True
    return False


@njit
def narrow(joints, bodies) -> bool:
    """Whether solving the joints together costs no more than sweeping them (``joint_solver:
    auto``): Cholesky's work is about the sum over rows of the envelope's width squared, a
    sweep's the number of rows, so together pays while each joint reaches back, on average, at
    most ``sqrt(NARROW)`` joints to the first one sharing a moving body with it (measured: a
    chain reaches back 1, a 5 x 5 net of hinges about 10, where both ways cost the same, a
    10 x 10 net about 20, where together costs 1.5 times as much; a 20 x 20 net 4 times)."""
    n = bodies.shape[0]
    lowest = np.full(n, joints.shape[0], dtype=np.int64)
    work, count = 0.0, 0
    for i in range(joints.shape[0]):
        j = joints[i]
        if j["kind"] != PIN and j["kind"] != PIVOT:
            continue
        reach = i
        for x in (j["a"], j["b"]):
            if moves(bodies[x]):
                lowest[x] = min(lowest[x], i)
                reach = min(reach, lowest[x])
        work += (i - reach) ** 2
        count += 1
    return work <= NARROW * count


@njit
def has_loop(joints, bodies) -> bool:
    """Whether the pins and pivots close a loop through the moving bodies (everything that
    cannot move counts as one ground). A loop can hold more rows than its bodies have degrees of
    freedom (a four-bar linkage has none to spare, a net of hinges many), and the rigid system
    of the relax pass is then singular."""
    n = bodies.shape[0]
    parent = np.arange(n + 1)  # n: the ground
    for i in range(joints.shape[0]):
        j = joints[i]
        if j["kind"] != PIN and j["kind"] != PIVOT:
            continue
        ends = [n, n]
        for side in range(2):
            x = j["a"] if side == 0 else j["b"]
            if moves(bodies[x]):
                ends[side] = x
        a, b = root(parent, ends[0]), root(parent, ends[1])
        if a == b:
            return True
        parent[a] = b
    return False


@njit(python=True)
def solve_joints_direct(joints, bodies, soft, use_bias: bool, inv_h: float) -> None:
    """One pass over the joints: motors and limits swept, then every point row at once (see
    the module); rigid and without bias when ``use_bias`` is off (the relax pass)."""
    for i in range(joints.shape[0]):
        if joints[i]["kind"] == PIVOT:
            solve_pivot_axial_soft(joints[i], bodies, soft, use_bias, inv_h)
    m = count_rows(joints)
    if m == 0:
        return
    rows = np.empty(m, dtype=JOINT_ROW)
    gather_rows(joints, bodies, soft, use_bias, rows)
    c = soft[2] / soft[1] if use_bias else 0.0  # impulse_scale / mass_scale
    apply_rows(joints, bodies, rows, solve_rows(rows, bodies, c))


@njit
def solve_rows(rows, bodies, c: float):
    """Delta of (K + c B) Delta = -(error) - c B lambda_0 over the rows (see the module), K's
    couplings only through bodies that can move."""
    m = rows.shape[0]
    moving = np.empty(bodies.shape[0], dtype=np.bool_)
    for x in range(bodies.shape[0]):
        moving[x] = moves(bodies[x])
    first, start = np.empty(m, dtype=np.int64), np.empty(m + 1, dtype=np.int64)
    envelope(rows, moving, first, start)
    a, delta = np.empty(start[m]), np.empty(m)
    assemble(rows, c, first, start, a, delta)
    cholesky_solve(a, delta, first, start)
    return delta
