"""Pairwise solver: the slides' collision algorithm ("Collision Algorithm").

For each collision, in turn: (1) compute the collision impulse j = -(1 + e) v_r . n / k,
(2)-(3) update the linear and angular velocities of both bodies, (4) solve the
interpenetration. Every contact point is visited once, with the velocities the earlier visits
left; a contact that is resolved is never looked at again in the step, even when a later one
pushes its bodies back together. That is the "stacking problem": in a stack each box is pushed
down by the one above after its own contact with the box below was dealt with, so a stack
sinks into itself.

A point collides when it overlaps (depth >= 0) and approaches (v_r . n < 0). The velocities
already carry this step's gravity and forces; the bounce reflects only the approach velocity
the bodies arrived with, v_a . n = v_r . n minus what gravity and forces added in this step, so
that gravity's g dt is cancelled rather than bounced back (a bounce would otherwise gain
height). Restitution applies to approach speeds -v_a . n above ``restitution_threshold``;
friction is the simple Coulomb impulse that stops sliding, at most mu j. Step (4), the
interpenetration fix, is ``settings.penetration`` as for every solver (``position_iterations``
passes), so that the solvers differ only in how they handle velocities.
"""

from __future__ import annotations

import numpy as np

from sandbox import penetration
from sandbox.jit import njit
from sandbox.solvers import impulse
from sandbox.solvers.impulse import along, apply, collision_impulse, load, store


@njit
def resolve_each_once(
    a, b, normal, count, friction, rest, r1, r2, kn, kt, sep0, dvn, pn, pt,
    vel, omega, inv_mass, inv_moment, threshold,
) -> None:  # fmt: skip
    """Slides, "Collision Algorithm" steps (1)-(3) for every point, in order, once.

    ``dvn``: the part of v_r . n that this step's gravity and forces added (see
    :func:`sandbox.solvers.impulse.prepare`). The impulse is the slides' j for the approach
    velocity v_a . n = v_r . n - dvn, plus -dvn / k, which cancels gravity's part: afterwards
    v_r . n = -e v_a . n."""
    v = np.empty(6)  # (v1x, v1y, w1, v2x, v2y, w2)
    for i in range(len(a)):
        ia, ib = a[i], b[i]
        nx, ny = normal[i, 0], normal[i, 1]
        mass = (inv_mass[ia], inv_moment[ia], inv_mass[ib], inv_moment[ib])
        load(v, vel, omega, ia, ib)
        for j in range(count[i]):
            pn[i, j] = pt[i, j] = 0.0
            if sep0[i, j] > 0.0 or kn[i, j] == 0.0:
                continue  # not touching
            vn = along(i, j, nx, ny, r1, r2, v)
            if vn >= 0.0:
                continue  # separating: no collision
            va = vn - dvn[i, j]  # the approach velocity without this step's gravity and forces
            e = rest[i] if -va > threshold else 0.0
            jn = collision_impulse(e, va, 1.0 / kn[i, j]) - dvn[i, j] * kn[i, j]  # (1)
            apply(i, j, jn * nx, jn * ny, r1, r2, mass, v)  # (2), (3a), (3b): +j n to body 2
            # Coulomb friction: stop the sliding v_r . t, at most mu j
            limit = friction[i] * jn
            jt = min(max(-kt[i, j] * along(i, j, ny, -nx, r1, r2, v), -limit), limit)
            apply(i, j, jt * ny, -jt * nx, r1, r2, mass, v)
            pn[i, j], pt[i, j] = jn, jt
        store(v, vel, omega, ia, ib)


def solve_velocities(world, manifolds, dt: float, start=None) -> None:
    """Each contact once, in turn; joints get ``settings.iterations`` passes first. ``start``:
    the velocities at the start of the step (:func:`sandbox.solvers.impulse.start_velocities`)."""
    m = impulse.empty_manifolds(manifolds)
    cons = impulse.build(world, m, dt, start=start)
    if world.joints:
        impulse.prepare_joints(world, dt)
        for _ in range(world.settings.iterations):
            impulse.solve_joints(world)
    if len(m):
        resolve_each_once(
            m.a, m.b, m.normal, m.count, m.friction, m.restitution, cons.r1, cons.r2, cons.kn,
            cons.kt, cons.sep0, cons.dvn, m.normal_impulse, m.tangent_impulse, world.vel,
            world.omega, world.inv_mass, world.inv_moment,
            float(world.settings.restitution_threshold),
        )  # fmt: skip


def solve_positions(world, manifolds, dt: float) -> None:
    """Step (4): the interpenetration fix over the contacts."""
    m = impulse.empty_manifolds(manifolds)
    cons = impulse.built(world, manifolds) or impulse.build(world, m, dt)
    penetration.solve_positions(world, m, cons, world.settings.position_iterations)
