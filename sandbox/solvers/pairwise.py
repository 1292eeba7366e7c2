"""Pairwise solver: the slides' collision algorithm ("Collision Algorithm").

For each collision, in turn: (1) compute the collision impulse j = -(1 + e) v_r . n / k,
(2)-(3) update the linear and angular velocities of both bodies, (4) solve the
interpenetration. Every contact point is visited once, with the velocities the earlier visits
left; a contact that is resolved is never looked at again in the step, even when a later one
pushes its bodies back together. That is the "stacking problem": in a stack each box is pushed
down by the one above after its own contact with the box below was dealt with, so a stack
sinks into itself.

A point collides when it overlaps (depth >= 0) and approaches (v_r . n < 0). The velocities
already carry this step's gravity and forces; the bounce reflects only the approach speed the
bodies arrived with (``approach_speed``, measured before gravity), so that gravity's g dt is
cancelled rather than bounced back (a bounce would otherwise gain height). Restitution applies
to approach speeds above ``restitution_threshold``; friction is the simple Coulomb impulse that
stops sliding, at most mu j. Step (4), the interpenetration fix, is ``settings.penetration`` as
for every solver (:mod:`sandbox.penetration`), so the solvers differ only in how they handle
velocities. Joints get ``settings.iterations`` passes first.
"""

from __future__ import annotations

import numpy as np

from sandbox.jit import njit
from sandbox.joints.solve import solve_joint_velocities
from sandbox.math2d import set_velocity, velocity_of
from sandbox.solvers.common import apply_normal, apply_tangent, masses, normal_speed, tangent_speed


@njit
def collision_impulse(e: float, vn: float, k: float) -> float:
    """j = -(1 + e) v_r . n / k (slides, "Collision Equation", step 1)."""
    return -(1.0 + e) * vn / k


@njit
def gravity_speeds(contacts, k: int, bodies):
    """Per point, what this step's gravity and forces added to v_r . n (k, 2)."""
    out = np.zeros((k, 2))
    for i in range(k):
        c = contacts[i]
        va, vb = velocity_of(bodies, c["a"]), velocity_of(bodies, c["b"])
        for j in range(c["count"]):
            p = c["points"][j]
            out[i, j] = (
                normal_speed(va, vb, p, c["normal"][0], c["normal"][1]) - p["approach_speed"]
            )
    return out


@njit
def resolve_each_once(contacts, k: int, bodies, gravity_speed, threshold: float) -> None:
    """Slides, "Collision Algorithm" steps (1)-(3) for every point, in order, once.

    The impulse is the slides' j for the approach speed v_a . n = v_r . n - (gravity's part),
    plus -(gravity's part) / k, which cancels gravity's part: afterwards v_r . n = -e v_a . n."""
    for i in range(k):
        c = contacts[i]
        nx, ny = c["normal"][0], c["normal"][1]
        mass = masses(c)
        va, vb = velocity_of(bodies, c["a"]), velocity_of(bodies, c["b"])
        for j in range(c["count"]):
            p = c["points"][j]
            p["normal_impulse"] = p["tangent_impulse"] = 0.0
            if p["depth"] < 0.0 or p["normal_mass"] == 0.0:
                continue  # not touching
            vn = normal_speed(va, vb, p, nx, ny)
            if vn >= 0.0:
                continue  # separating: no collision
            g = gravity_speed[i, j]
            approach = vn - g  # the approach speed without this step's gravity and forces
            e = c["restitution"] if -approach > threshold else 0.0
            jn = collision_impulse(e, approach, 1.0 / p["normal_mass"]) - g * p["normal_mass"]
            va, vb = apply_normal(va, vb, mass, p, nx, ny, jn)  # (2), (3a), (3b)
            # Coulomb friction: stop the sliding v_r . t, at most mu j
            limit = c["friction"] * jn
            vt = tangent_speed(va, vb, p, nx, ny)
            jt = min(max(-p["tangent_mass"] * vt, -limit), limit)
            va, vb = apply_tangent(va, vb, mass, p, nx, ny, jt)
            p["normal_impulse"], p["tangent_impulse"] = jn, jt  # (the bounce is in jn already)
        set_velocity(bodies, c["a"], va)
        set_velocity(bodies, c["b"], vb)


@njit
def solve(contacts, k: int, joints, bodies, context) -> None:
    """Joints first (``settings.iterations`` passes), then each contact once, in turn."""
    ctx = context[0]
    gravity_speed = gravity_speeds(contacts, k, bodies)
    for _ in range(ctx["iterations"]):
        solve_joint_velocities(joints, bodies, ctx["accumulate"])
    resolve_each_once(contacts, k, bodies, gravity_speed, ctx["restitution_threshold"])
