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
(Box2D), so resting contacts do not bounce. Overlap is removed on positions only (no Baumgarte
velocity bias): the velocities stay free of the extra push a velocity bias adds, which would
make resting boxes hop and stacks jitter.
"""

from __future__ import annotations

import numpy as np

from sandbox import contact_cache, penetration
from sandbox.jit import njit
from sandbox.solvers import impulse
from sandbox.solvers.impulse import along, apply, load, store


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


def sweep(world, m, cons, iterations: int) -> None:
    """``iterations`` sweeps over every contact (one compiled call)."""
    if len(m) and iterations > 0:
        sequential_impulses(
            m.a, m.b, m.normal, m.count, m.friction, cons.r1, cons.r2, cons.kn, cons.kt,
            cons.kblock, cons.bias, m.normal_impulse, m.tangent_impulse, cons.pmax, world.vel,
            world.omega, world.inv_mass, world.inv_moment, int(iterations),
            bool(world.settings.accumulate_impulses),
        )  # fmt: skip


def relax(world, manifolds, dt: float):
    """Prepare, warm start, ``settings.iterations`` sweeps over contacts and joints, remember
    the impulses for the next step, bounce. Returns the manifolds and their constraints."""
    s = world.settings
    m = impulse.empty_manifolds(manifolds)
    cons = impulse.build(world, m, dt)
    impulse.start(world, m, cons, s.warm_start and s.accumulate_impulses)
    if world.joints:
        impulse.prepare_joints(world, dt)
        for _ in range(s.iterations):
            impulse.solve_joints(world)
            sweep(world, m, cons, 1)
    else:
        sweep(world, m, cons, s.iterations)
    contact_cache.save(world, m)
    impulse.bounce(world, m, cons)
    return m, cons


def solve_velocities(world, manifolds, dt: float) -> None:
    """Contact and joint impulses for this step (changes ``world.vel`` and ``world.omega``)."""
    relax(world, manifolds, dt)


def solve_positions(world, manifolds, dt: float) -> None:
    """The penetration fix (``settings.penetration``), ``position_iterations`` passes."""
    m = impulse.empty_manifolds(manifolds)
    cons = impulse.built(world, manifolds) or impulse.build(world, m, dt)
    penetration.solve_positions(world, m, cons, world.settings.position_iterations)
