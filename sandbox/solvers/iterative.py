"""Iterative solver: sequential impulses (slides, "Simultaneous Collision Resolution",
"Iterative Solver"; box2d-lite's ``World::Step``).

All contacts are considered together by sweeping over them ``settings.iterations`` times; each
visit applies the collision equation's impulse that makes that one point right, given what the
others did so far. Repeated, the sweeps converge towards impulses that satisfy every contact at
once, which is what a stack needs.

The box2d-lite teaching switches:

- ``accumulate_impulses``: clamp the running total of each point's impulse (>= 0, friction
  within mu times it) instead of each increment, so later sweeps can correct earlier ones;
- ``warm_start``: start from last step's impulses of the same contact points
  (:mod:`sandbox.contact_cache`; needs ``accumulate_impulses``);
- ``position_correction``: the penetration fix after the positions moved
  (:mod:`sandbox.penetration`, ``settings.penetration``; ``position_iterations`` passes).

Restitution is a pass after the sweeps, from the approach velocities measured before them
and before this step's gravity and forces were added (Box2D measures them in its prepare step,
before integrating velocities), so resting contacts do not bounce and bounces gain no energy. Overlap is removed on positions only (no Baumgarte
velocity bias): the velocities stay free of the extra push a velocity bias adds, which would
make resting boxes hop and stacks jitter.
"""

from __future__ import annotations

import numpy as np

from sandbox import penetration
from sandbox.contact import (
    BIAS,
    DEPTH,
    G_BOUNCE,
    G_FRICTION,
    G_NX,
    G_NY,
    G_POINT,
    G_REBOUND,
    G_RESTITUTION,
    G_STRIDE,
    I_A,
    I_B,
    I_COUNT,
    KN,
    KT,
    LAX,
    LAY,
    LBX,
    LBY,
    PMAX,
    PN,
    PT,
    RN1,
    RN2,
    RT1,
    RT2,
    S_BLOCK,
    S_II1,
    S_II2,
    S_IM1,
    S_IM2,
    S_K12,
    S_M11,
    S_M12,
    S_M22,
    S_MU,
    S_NX,
    S_NY,
    S_POINT,
    S_STRIDE,
    VN0,
    X,
    Y,
    buffers,
    impulses_of_rows,
    rows_from_manifolds,
)
from sandbox.contact_cache import match_rows
from sandbox.jit import njit
from sandbox.solvers import impulse
from sandbox.solvers.impulse import along, apply, cross, load, relative_velocity, store


@njit
def block_normal(i, nx, ny, r1, r2, kblock, bias, pn, mass, v) -> None:
    """Both normal impulses of a two-point manifold at once (Box2D's block solver).

    Find the accumulated x = (pn1, pn2) >= 0 with velocities v_n = K x + b >= bias and
    x_j (v_n,j - bias_j) = 0, trying in turn: both points push, only the first, only the
    second, neither. K is the 2x2 effective mass matrix (its diagonal is each point's k;
    ``kblock`` holds k11, k12, k22 and det K). Solving the pair together keeps a box standing
    on two corners from rocking, which solving one corner after the other provokes.
    """
    k11, k12, k22, det = kblock[i, 0], kblock[i, 1], kblock[i, 2], kblock[i, 3]
    a1, a2 = pn[i, 0], pn[i, 1]
    # b: the velocity error each point would have without the impulses applied so far
    b1 = along(i, 0, nx, ny, r1, r2, v) - bias[i, 0] - (k11 * a1 + k12 * a2)
    b2 = along(i, 1, nx, ny, r1, r2, v) - bias[i, 1] - (k12 * a1 + k22 * a2)
    x1 = -(k22 * b1 - k12 * b2) / det  # both push: x = -K^-1 b
    x2 = -(k11 * b2 - k12 * b1) / det
    if x1 < 0.0 or x2 < 0.0:
        x1, x2 = -b1 / k11, 0.0  # only the first pushes
        if x1 < 0.0 or k12 * x1 + b2 < 0.0:
            x1, x2 = 0.0, -b2 / k22  # only the second
            if x2 < 0.0 or k12 * x2 + b1 < 0.0:
                x1, x2 = 0.0, 0.0  # neither
                if b1 < 0.0 or b2 < 0.0:
                    return  # no solution (degenerate): leave as is
    apply(i, 0, (x1 - a1) * nx, (x1 - a1) * ny, r1, r2, mass, v)
    apply(i, 1, (x2 - a2) * nx, (x2 - a2) * ny, r1, r2, mass, v)
    pn[i, 0], pn[i, 1] = x1, x2


@njit
def sequential_impulses(
    a, b, normal, count, friction, r1, r2, kn, kt, kblock, bias, pn, pt, pmax,
    vel, omega, inv_mass, inv_moment, iterations, accumulate,
) -> None:  # fmt: skip
    """``iterations`` sweeps over every manifold, in order.

    Per point: the normal impulse that makes v_r . n = bias, and Coulomb friction, the impulse
    that stops sliding (v_r . t = 0, t = (n_y, -n_x)) within |P_t| <= mu P_n.

    Accumulated (box2d-lite): the running totals are clamped (pn >= 0, |pt| <= mu pn), so a
    later sweep may take back part of an earlier impulse; friction goes first, within the cone
    of the current normal impulse, and the two normal impulses of a manifold are solved
    together (:func:`block_normal`). Not accumulated: each increment is clamped on its own
    (dpn >= 0, then |dpt| <= mu dpn), which can only push.
    """
    v = np.empty(6)  # (v1x, v1y, w1, v2x, v2y, w2) of the manifold's two bodies
    for _ in range(iterations):
        for i in range(len(a)):
            ia, ib = a[i], b[i]
            nx, ny = normal[i, 0], normal[i, 1]
            mu = friction[i]
            mass = (inv_mass[ia], inv_moment[ia], inv_mass[ib], inv_moment[ib])
            load(v, vel, omega, ia, ib)
            if accumulate:
                for j in range(count[i]):  # friction, within the current cone
                    old = pt[i, j]
                    vt = along(i, j, ny, -nx, r1, r2, v)
                    pt[i, j] = min(max(old - kt[i, j] * vt, -mu * pn[i, j]), mu * pn[i, j])
                    dp = pt[i, j] - old
                    apply(i, j, dp * ny, -dp * nx, r1, r2, mass, v)
                if count[i] == 2 and kblock[i, 3] > 0.0:
                    block_normal(i, nx, ny, r1, r2, kblock, bias, pn, mass, v)
                else:
                    for j in range(count[i]):
                        old = pn[i, j]
                        vn = along(i, j, nx, ny, r1, r2, v)
                        pn[i, j] = max(old + kn[i, j] * (bias[i, j] - vn), 0.0)
                        dp = pn[i, j] - old
                        apply(i, j, dp * nx, dp * ny, r1, r2, mass, v)
            else:
                for j in range(count[i]):
                    vn = along(i, j, nx, ny, r1, r2, v)
                    dp = max(kn[i, j] * (bias[i, j] - vn), 0.0)
                    pn[i, j] += dp
                    apply(i, j, dp * nx, dp * ny, r1, r2, mass, v)
                    vt = along(i, j, ny, -nx, r1, r2, v)
                    dt = min(max(-kt[i, j] * vt, -mu * dp), mu * dp)
                    pt[i, j] += dt
                    apply(i, j, dt * ny, -dt * nx, r1, r2, mass, v)
            for j in range(count[i]):
                pmax[i, j] = max(pmax[i, j], pn[i, j])
            store(v, vel, omega, ia, ib)


# --- the same solver on contact rows (what the world's step runs) ------------------------------
# ``sandbox.contact`` keeps each manifold in one row of a few preallocated arrays. The formulas
# are the ones above, with the lever-arm cross products r x n and r x t worked out once per step
# (``prepare_rows``), so an iteration reads a short row and applies each impulse with a
# multiply-add per velocity component: v_r . n = n . (v2 - v1) + (r2 x n) w2 - (r1 x n) w1, and
# P = p n changes v1 by -p n / m1 and w1 by -p (r1 x n) / I1.


@njit
def visit(q: int, half: int) -> int:
    """The manifold visited ``q``-th in a sweep: alternately from the first and the second half
    of the list (0, half, 1, half + 1, ...). Neighbours in the sorted list usually share a body,
    so each would wait for the one before; two halves rarely do, so the processor overlaps
    them. Any fixed order is a valid sweep (Gauss-Seidel), this one is simply faster."""
    return (q >> 1) + (q & 1) * half


@njit
def prepare_rows(
    ints, geoms, solver, k, com, cs, vel0, omega0, inv_mass, inv_moment, inv_dt, beta, slop
):  # fmt: skip
    """:func:`sandbox.solvers.impulse.prepare` for contact rows: lever arms (as r x n, r x t and
    in each body's frame), effective masses, velocity targets, approach velocities and the
    inverse of the 2x2 block matrix K; impulses and the restitution columns start at zero
    (also in an unused second slot, whose other columns nothing reads).

    ``vel0``, ``omega0``: the velocities at the start of the step, before this step's gravity
    and forces were added; only the approach velocities ``VN0`` (for restitution) read them."""
    for i in range(k):
        ia, ib, count = ints[i, I_A], ints[i, I_B], ints[i, I_COUNT]
        nx, ny = geoms[i, G_NX], geoms[i, G_NY]
        im1, im2, ii1, ii2 = inv_mass[ia], inv_mass[ib], inv_moment[ia], inv_moment[ib]
        c1, s1, c2, s2 = cs[ia, 0], cs[ia, 1], cs[ib, 0], cs[ib, 1]
        solver[i, S_NX], solver[i, S_NY], solver[i, S_MU] = nx, ny, geoms[i, G_FRICTION]
        solver[i, S_IM1], solver[i, S_II1], solver[i, S_IM2], solver[i, S_II2] = im1, ii1, im2, ii2
        geoms[i, G_REBOUND] = 0.0
        for j in range(2):
            g = G_POINT + G_STRIDE * j
            p = S_POINT + S_STRIDE * j
            geoms[i, G_BOUNCE + j] = 0.0
            solver[i, p + PN] = solver[i, p + PT] = solver[i, p + PMAX] = 0.0
            if j >= count:  # an unused slot: nothing reads the rest
                continue
            r1x, r1y = geoms[i, g + X] - com[ia, 0], geoms[i, g + Y] - com[ia, 1]
            r2x, r2y = geoms[i, g + X] - com[ib, 0], geoms[i, g + Y] - com[ib, 1]
            geoms[i, g + LAX], geoms[i, g + LAY] = c1 * r1x + s1 * r1y, -s1 * r1x + c1 * r1y
            geoms[i, g + LBX], geoms[i, g + LBY] = c2 * r2x + s2 * r2y, -s2 * r2x + c2 * r2y
            rn1, rn2 = cross(r1x, r1y, nx, ny), cross(r2x, r2y, nx, ny)
            rt1, rt2 = cross(r1x, r1y, ny, -nx), cross(r2x, r2y, ny, -nx)  # t = (n_y, -n_x)
            solver[i, p + RN1], solver[i, p + RN2] = rn1, rn2
            solver[i, p + RT1], solver[i, p + RT2] = rt1, rt2
            kn = im1 + im2 + ii1 * rn1 * rn1 + ii2 * rn2 * rn2  # impulse.effective_mass
            kt = im1 + im2 + ii1 * rt1 * rt1 + ii2 * rt2 * rt2
            solver[i, p + KN] = 1.0 / kn if kn > 0.0 else 0.0
            solver[i, p + KT] = 1.0 / kt if kt > 0.0 else 0.0
            vx, vy = relative_velocity(
                vel0[ia, 0], vel0[ia, 1], omega0[ia], r1x, r1y,
                vel0[ib, 0], vel0[ib, 1], omega0[ib], r2x, r2y,
            )  # fmt: skip
            geoms[i, g + VN0] = vx * nx + vy * ny  # approach velocity before gravity
            d = geoms[i, g + DEPTH]
            solver[i, p + BIAS] = d * inv_dt if d < 0.0 else beta * inv_dt * max(d - slop, 0.0)
        solver[i, S_BLOCK] = 0.0
        if count == 2:  # the block solver's K (see block_normal), kept as its inverse
            p0, p1 = S_POINT, S_POINT + S_STRIDE
            a1, a2 = solver[i, p0 + RN1], solver[i, p1 + RN1]
            b1, b2 = solver[i, p0 + RN2], solver[i, p1 + RN2]
            k11 = im1 + im2 + ii1 * a1 * a1 + ii2 * b1 * b1
            k22 = im1 + im2 + ii1 * a2 * a2 + ii2 * b2 * b2
            k12 = im1 + im2 + ii1 * a1 * a2 + ii2 * b1 * b2
            det = k11 * k22 - k12 * k12
            if k11 * k11 < 1000.0 * det:  # well conditioned
                solver[i, S_K12] = k12
                solver[i, S_M11] = k22 / det
                solver[i, S_M12] = -k12 / det
                solver[i, S_M22] = k11 / det
                solver[i, S_BLOCK] = 1.0


@njit
def warm_start_rows(ints, solver, k, vel, omega) -> None:
    """:func:`sandbox.solvers.impulse.warm_start` for contact rows: P = pn n + pt t again."""
    for i in range(k):
        ia, ib = ints[i, I_A], ints[i, I_B]
        nx, ny = solver[i, S_NX], solver[i, S_NY]
        im1, ii1, im2, ii2 = solver[i, S_IM1], solver[i, S_II1], solver[i, S_IM2], solver[i, S_II2]
        for j in range(ints[i, I_COUNT]):
            p = S_POINT + S_STRIDE * j
            pn, pt = solver[i, p + PN], solver[i, p + PT]
            px, py = pn * nx + pt * ny, pn * ny - pt * nx
            vel[ia, 0] -= im1 * px
            vel[ia, 1] -= im1 * py
            omega[ia] -= ii1 * (solver[i, p + RN1] * pn + solver[i, p + RT1] * pt)
            vel[ib, 0] += im2 * px
            vel[ib, 1] += im2 * py
            omega[ib] += ii2 * (solver[i, p + RN2] * pn + solver[i, p + RT2] * pt)


@njit
def solve_rows(ints, solver, k, vel, omega, iterations, accumulate) -> None:
    """:func:`sequential_impulses` for contact rows (same clamps, same block solver), visiting
    the manifolds in :func:`visit` order. The velocities of a manifold's two bodies stay in local
    variables while its points are solved."""
    half = (k + 1) // 2
    for _ in range(iterations):
        for q in range(k):
            i = visit(q, half)
            ia, ib, count = ints[i, I_A], ints[i, I_B], ints[i, I_COUNT]
            nx, ny, mu = solver[i, S_NX], solver[i, S_NY], solver[i, S_MU]
            im1, ii1 = solver[i, S_IM1], solver[i, S_II1]
            im2, ii2 = solver[i, S_IM2], solver[i, S_II2]
            v1x, v1y, w1 = vel[ia, 0], vel[ia, 1], omega[ia]
            v2x, v2y, w2 = vel[ib, 0], vel[ib, 1], omega[ib]
            if accumulate:
                for j in range(count):  # friction, within the current cone: v_r . t -> 0
                    p = S_POINT + S_STRIDE * j
                    rt1, rt2 = solver[i, p + RT1], solver[i, p + RT2]
                    vt = (v2x - v1x) * ny - (v2y - v1y) * nx + rt2 * w2 - rt1 * w1
                    old = solver[i, p + PT]
                    limit = mu * solver[i, p + PN]
                    new = min(max(old - solver[i, p + KT] * vt, -limit), limit)
                    solver[i, p + PT] = new
                    d = new - old  # P = d t, t = (n_y, -n_x)
                    v1x, v1y, w1 = v1x - im1 * ny * d, v1y + im1 * nx * d, w1 - ii1 * rt1 * d
                    v2x, v2y, w2 = v2x + im2 * ny * d, v2y - im2 * nx * d, w2 + ii2 * rt2 * d
                if count == 2 and solver[i, S_BLOCK] > 0.0:  # block_normal
                    p0, p1 = S_POINT, S_POINT + S_STRIDE
                    a1, a2 = solver[i, p0 + PN], solver[i, p1 + PN]
                    rn1a, rn2a = solver[i, p0 + RN1], solver[i, p0 + RN2]
                    rn1b, rn2b = solver[i, p1 + RN1], solver[i, p1 + RN2]
                    k12 = solver[i, S_K12]
                    m11, m12, m22 = solver[i, S_M11], solver[i, S_M12], solver[i, S_M22]
                    # b = v_n - bias - K a (K a does not depend on the velocities)
                    k11 = im1 + im2 + ii1 * rn1a * rn1a + ii2 * rn2a * rn2a
                    k22 = im1 + im2 + ii1 * rn1b * rn1b + ii2 * rn2b * rn2b
                    c1 = solver[i, p0 + BIAS] + (k11 * a1 + k12 * a2)
                    c2 = solver[i, p1 + BIAS] + (k12 * a1 + k22 * a2)
                    dn = (v2x - v1x) * nx + (v2y - v1y) * ny
                    b1 = dn + rn2a * w2 - rn1a * w1 - c1
                    b2 = dn + rn2b * w2 - rn1b * w1 - c2
                    x1, x2 = -(m11 * b1 + m12 * b2), -(m12 * b1 + m22 * b2)  # both push: -K^-1 b
                    solved = True
                    if x1 < 0.0 or x2 < 0.0:
                        x1, x2 = -b1 * solver[i, p0 + KN], 0.0  # only the first pushes
                        if x1 < 0.0 or k12 * x1 + b2 < 0.0:
                            x1, x2 = 0.0, -b2 * solver[i, p1 + KN]  # only the second
                            if x2 < 0.0 or k12 * x2 + b1 < 0.0:
                                x1, x2 = 0.0, 0.0  # neither
                                solved = b1 >= 0.0 and b2 >= 0.0
                    if solved:
                        d1, d2 = x1 - a1, x2 - a2
                        d = d1 + d2
                        v1x, v1y = v1x - im1 * nx * d, v1y - im1 * ny * d
                        w1 -= ii1 * (rn1a * d1 + rn1b * d2)
                        v2x, v2y = v2x + im2 * nx * d, v2y + im2 * ny * d
                        w2 += ii2 * (rn2a * d1 + rn2b * d2)
                        solver[i, p0 + PN], solver[i, p1 + PN] = x1, x2
                else:
                    for j in range(count):  # v_r . n -> bias, total pn >= 0
                        p = S_POINT + S_STRIDE * j
                        rn1, rn2 = solver[i, p + RN1], solver[i, p + RN2]
                        vn = (v2x - v1x) * nx + (v2y - v1y) * ny + rn2 * w2 - rn1 * w1
                        old = solver[i, p + PN]
                        new = max(old + solver[i, p + KN] * (solver[i, p + BIAS] - vn), 0.0)
                        solver[i, p + PN] = new
                        d = new - old
                        v1x, v1y, w1 = v1x - im1 * nx * d, v1y - im1 * ny * d, w1 - ii1 * rn1 * d
                        v2x, v2y, w2 = v2x + im2 * nx * d, v2y + im2 * ny * d, w2 + ii2 * rn2 * d
            else:
                for j in range(count):  # each increment clamped on its own
                    p = S_POINT + S_STRIDE * j
                    rn1, rn2 = solver[i, p + RN1], solver[i, p + RN2]
                    rt1, rt2 = solver[i, p + RT1], solver[i, p + RT2]
                    vn = (v2x - v1x) * nx + (v2y - v1y) * ny + rn2 * w2 - rn1 * w1
                    dn = max(solver[i, p + KN] * (solver[i, p + BIAS] - vn), 0.0)
                    solver[i, p + PN] += dn
                    v1x, v1y, w1 = v1x - im1 * nx * dn, v1y - im1 * ny * dn, w1 - ii1 * rn1 * dn
                    v2x, v2y, w2 = v2x + im2 * nx * dn, v2y + im2 * ny * dn, w2 + ii2 * rn2 * dn
                    vt = (v2x - v1x) * ny - (v2y - v1y) * nx + rt2 * w2 - rt1 * w1
                    dt = min(max(-solver[i, p + KT] * vt, -mu * dn), mu * dn)
                    solver[i, p + PT] += dt
                    v1x, v1y, w1 = v1x - im1 * ny * dt, v1y + im1 * nx * dt, w1 - ii1 * rt1 * dt
                    v2x, v2y, w2 = v2x + im2 * ny * dt, v2y - im2 * nx * dt, w2 + ii2 * rt2 * dt
            for j in range(count):
                p = S_POINT + S_STRIDE * j
                solver[i, p + PMAX] = max(solver[i, p + PMAX], solver[i, p + PN])
            vel[ia, 0], vel[ia, 1], omega[ia] = v1x, v1y, w1
            vel[ib, 0], vel[ib, 1], omega[ib] = v2x, v2y, w2


@njit
def restitution_rows(ints, geoms, solver, k, vel, omega, threshold) -> None:
    """:func:`sandbox.solvers.impulse.restitution` for contact rows. The bounce's impulse goes
    to the ``G_BOUNCE`` columns (reported with the manifolds), not to the solver's ``PN``: the
    next step warm starts from the impulses before the bounce, as before."""
    for i in range(k):
        geoms[i, G_REBOUND] = 0.0
        e = geoms[i, G_RESTITUTION]
        if e == 0.0:
            continue
        ia, ib = ints[i, I_A], ints[i, I_B]
        nx, ny = solver[i, S_NX], solver[i, S_NY]
        im1, ii1, im2, ii2 = solver[i, S_IM1], solver[i, S_II1], solver[i, S_IM2], solver[i, S_II2]
        for j in range(ints[i, I_COUNT]):
            g = G_POINT + G_STRIDE * j
            p = S_POINT + S_STRIDE * j
            vn0 = geoms[i, g + VN0]
            if vn0 > -threshold or solver[i, p + PMAX] == 0.0:
                continue
            rn1, rn2 = solver[i, p + RN1], solver[i, p + RN2]
            vn = (vel[ib, 0] - vel[ia, 0]) * nx + (vel[ib, 1] - vel[ia, 1]) * ny
            vn += rn2 * omega[ib] - rn1 * omega[ia]
            old = solver[i, p + PN] + geoms[i, G_BOUNCE + j]
            new = max(old - solver[i, p + KN] * (vn + e * vn0), 0.0)  # target -e vn0
            geoms[i, G_BOUNCE + j] += new - old
            d = new - old
            vel[ia, 0] -= im1 * nx * d
            vel[ia, 1] -= im1 * ny * d
            omega[ia] -= ii1 * rn1 * d
            vel[ib, 0] += im2 * nx * d
            vel[ib, 1] += im2 * ny * d
            omega[ib] += ii2 * rn2 * d
            geoms[i, G_REBOUND] = max(geoms[i, G_REBOUND], (1.0 + e) * -geoms[i, g + DEPTH])


@njit
def velocity_phase(
    ints, geoms, solver, k, old_ints, old_solver, k_old, vel, omega, warm, accumulate,
    iterations, threshold,
) -> int:  # fmt: skip
    """The velocity phase on contact rows already prepared (:func:`prepare_rows`, with the
    velocities of the start of the step), no joints: warm start from the last set of rows
    (``old_*``, ``k_old`` manifolds), ``iterations`` sweeps, restitution, on ``vel``, ``omega``
    (this step's free motion already added). Returns the number of warm-started points."""
    found = 0
    if warm:
        found = match_rows(ints, solver, k, old_ints, old_solver, k_old)
        warm_start_rows(ints, solver, k, vel, omega)
    solve_rows(ints, solver, k, vel, omega, iterations, accumulate)
    restitution_rows(ints, geoms, solver, k, vel, omega, threshold)
    return found


def sweep(world, m, cons, iterations: int) -> None:
    """``iterations`` sweeps of the readable :func:`sequential_impulses` over every contact (one
    compiled call). The world's step runs :func:`solve_rows`, the same sweeps on contact
    rows; this is the reference it is tested against."""
    if len(m) and iterations > 0:
        sequential_impulses(
            m.a, m.b, m.normal, m.count, m.friction, cons.r1, cons.r2, cons.kn, cons.kt,
            cons.kblock, cons.bias, m.normal_impulse, m.tangent_impulse, cons.pmax, world.vel,
            world.omega, world.inv_mass, world.inv_moment, int(iterations),
            bool(world.settings.accumulate_impulses),
        )  # fmt: skip


def relax(world, manifolds, dt: float, start=None):
    """Prepare, warm start, ``settings.iterations`` sweeps over contacts and joints, bounce, on
    the world's contact rows (``sandbox.contact.ContactBuffers``), which then hold the impulses
    for the next step's warm start. The impulses applied are also written into the manifolds,
    which are returned. ``start``: ``(vel, omega)`` at the start of the step, before this step's
    gravity and forces (default: the current velocities), for the bounces."""
    s = world.settings
    m = impulse.empty_manifolds(manifolds)
    k = len(m)
    cache = buffers(world)
    cache.reserve(k)
    old = cache.now
    cur = cache.begin()
    ints, geoms, solver = cache.rows(cur)
    old_ints, _, old_solver = cache.rows(old)
    if k:
        rows_from_manifolds(
            m.a, m.b, m.sa, m.sb, m.normal, m.count, m.point, m.depth, m.feature, m.friction,
            m.restitution, ints, geoms,
        )  # fmt: skip
    warm = bool(s.warm_start and s.accumulate_impulses)
    accumulate = bool(s.accumulate_impulses)
    vel0, omega0 = impulse.start_velocities(world, start)
    prepare_rows(
        ints, geoms, solver, k, world.com, world.cs, vel0, omega0, world.inv_mass,
        world.inv_moment, 1.0 / dt, 0.0, float(s.slop),
    )  # fmt: skip
    if world.joints:
        found = 0
        if warm:
            found = match_rows(ints, solver, k, old_ints, old_solver, cache.k[old])
            warm_start_rows(ints, solver, k, world.vel, world.omega)
        impulse.prepare_joints(world, dt)
        for _ in range(s.iterations):
            impulse.solve_joints(world)
            solve_rows(ints, solver, k, world.vel, world.omega, 1, accumulate)
        restitution_rows(
            ints, geoms, solver, k, world.vel, world.omega, float(s.restitution_threshold)
        )
    else:
        found = velocity_phase(
            ints, geoms, solver, k, old_ints, old_solver, cache.k[old], world.vel, world.omega,
            warm, accumulate, int(s.iterations), float(s.restitution_threshold),
        )  # fmt: skip
    cache.commit(cur, k)
    cache.source = m
    world.stats["warm_started_points"] = int(found)
    if k:
        impulses_of_rows(geoms, solver, k, m.normal_impulse, m.tangent_impulse)
    return m


def solve_velocities(world, manifolds, dt: float, start=None) -> None:
    """Contact and joint impulses for this step (changes ``world.vel`` and ``world.omega``);
    ``start``: the velocities at the start of the step (see :func:`relax`)."""
    relax(world, manifolds, dt, start)


def solve_positions(world, manifolds, dt: float) -> None:
    """The penetration fix (``settings.penetration``), ``position_iterations`` passes, on the
    contact rows of this step's solve (made now if ``manifolds`` were not solved)."""
    s = world.settings
    if not s.position_correction:
        return
    m = impulse.empty_manifolds(manifolds)
    cache = buffers(world)
    k = len(m)
    if manifolds is not None and cache.source is manifolds:
        rows = cache.now
    else:  # not solved here: prepare them in the other set (the warm-start cache stays)
        cache.reserve(k)
        rows = cache.begin()
        ints, geoms, solver = cache.rows(rows)
        if k:
            rows_from_manifolds(
                m.a, m.b, m.sa, m.sb, m.normal, m.count, m.point, m.depth, m.feature,
                m.friction, m.restitution, ints, geoms,
            )  # fmt: skip
        prepare_rows(
            ints, geoms, solver, k, world.com, world.cs, world.vel, world.omega,
            world.inv_mass, world.inv_moment, 1.0 / dt, 0.0, float(s.slop),
        )  # fmt: skip
    if s.penetration == "impulse" and not world.joints:
        ints, geoms, solver = cache.rows(rows)
        penetration.position_phase(
            ints, geoms, solver, k, world.com, world.rot, world.cs, world._dphi, world.inv_mass,
            world.orientation_kind, bool(s.renormalise), float(s.baumgarte), float(s.slop),
            int(s.position_iterations),
        )  # fmt: skip
    else:
        cons = penetration.constraints_of_rows(cache, rows, k)
        penetration.solve_positions(world, m, cons, s.position_iterations)
