"""Pin joint: a massless rod keeping two anchors at a fixed distance (a pendulum's string).

Constraint (slides, "Further Topics": joints), with pa, pb the world anchors and u the unit
vector from pa to pb:

    C = |pb - pa| - L = 0,      Cdot = u . (vb + wb x rb - va - wa x ra) = 0

Its Jacobian row is J = [-u, -(ra x u), u, rb x u] on (va, wa, vb, wb), so the effective mass
is 1 / K with K = J M^-1 J^T = 1/ma + 1/mb + (ra x u)^2 / Ia + (rb x u)^2 / Ib.

Velocity pass (sequential impulses, Box2D's distance joint): an impulse lambda u on b (and
-lambda u on a) with lambda = -(Cdot - target) / K, accumulated over iterations and steps (warm
starting). Position pass (non-linear Gauss-Seidel): move the bodies by the pseudo impulse
-C / K u to remove the drift that velocities leave.

Arc correction: a step along the tangent lengthens the rod by about |v_side|^2 dt^2 / 2L (the
bob leaves the circle). The velocity rule therefore asks for the small inward u . Cdot that
lands the anchors at distance L at the END of the step (:func:`arc_target`); the position pass
then has almost nothing to do, and a pendulum keeps its energy instead of losing it each swing.
"""

from __future__ import annotations

import math

from sandbox.jit import njit
from sandbox.joints.base import (
    MAX_ARC_TURN,
    MAX_LINEAR_CORRECTION,
    Joint,
    anchor_velocity,
    apply_joint_impulse,
    arc_error,
    arm,
    inverse_masses,
    move_joint_bodies,
)
from sandbox.math2d import cross, inverse_or_zero, set_velocity, velocity_of
from sandbox.records import PIN


@njit
def rod(j, bodies):
    """Arms r_a, r_b, unit vector u from anchor a to anchor b, length |pb - pa| and
    K = 1/ma + 1/mb + (ra x u)^2/Ia + (rb x u)^2/Ib, at the bodies' current poses."""
    a, b = bodies[j["a"]], bodies[j["b"]]
    ra, rb = arm(a, j["local_a"]), arm(b, j["local_b"])
    dx = b["com"][0] + rb[0] - a["com"][0] - ra[0]
    dy = b["com"][1] + rb[1] - a["com"][1] - ra[1]
    length = math.sqrt(dx * dx + dy * dy)
    ux, uy = (dx / length, dy / length) if length > 1e-12 else (0.0, 0.0)
    ma, ia, mb, ib = inverse_masses(j, bodies)
    cra, crb = cross(ra[0], ra[1], ux, uy), cross(rb[0], rb[1], ux, uy)
    k = ma + mb + ia * cra * cra + ib * crb * crb
    return ra, rb, (ux, uy), length, k


@njit
def arc_target(j, bodies, dt: float) -> float:
    """The rate u . Cdot that brings the anchors to distance L at the END of the step.

    The step moves the anchors apart by D = dt (vb + wb x rb - va - wa x ra) plus each arm's
    arc error e (:func:`~sandbox.joints.base.arc_error`). Its sideways part D_perp also
    lengthens the rod (Pythagoras), so ask for (L + dt u.Cdot + u.e)^2 + |D_perp|^2 = L^2.
    Without this the pendulum drifts outwards every step and the position pass, pulling it
    back, drains its energy.
    """
    va, vb = velocity_of(bodies, j["a"]), velocity_of(bodies, j["b"])
    ra = (j["anchor_a"][0], j["anchor_a"][1])
    rb = (j["anchor_b"][0], j["anchor_b"][1])
    ux, uy = j["axis"][0], j["axis"][1]
    ea, eb = arc_error(ra[0], ra[1], va[2] * dt), arc_error(rb[0], rb[1], vb[2] * dt)
    ex, ey = eb[0] - ea[0], eb[1] - ea[1]
    rel = anchor_velocity(va, ra, vb, rb)
    dx, dy = dt * rel[0] + ex, dt * rel[1] + ey
    along = ux * dx + uy * dy
    side2 = dx * dx + dy * dy - along * along
    length = j["length"]
    side2 = min(side2, (MAX_ARC_TURN * length) ** 2)  # as arc_error: bounded feedback
    return (math.sqrt(length * length - side2) - length - (ux * ex + uy * ey)) / dt


@njit
def prepare_pin(j, bodies, dt: float, warm: bool) -> None:
    """Arms, axis and effective mass for this step, and the arc-corrected target rate."""
    ra, rb, u, _, k = rod(j, bodies)
    j["anchor_a"][0], j["anchor_a"][1] = ra
    j["anchor_b"][0], j["anchor_b"][1] = rb
    j["axis"][0], j["axis"][1] = u
    j["axial_mass"] = inverse_or_zero(k)
    j["dt"] = dt
    j["target"][0] = arc_target(j, bodies, dt)
    if not warm:
        j["impulse"][0] = 0.0


@njit
def warm_start_pin(j, bodies) -> None:
    """Apply last step's accumulated impulse along the axis again."""
    va, vb = velocity_of(bodies, j["a"]), velocity_of(bodies, j["b"])
    lam = j["impulse"][0]
    ra, rb = (j["anchor_a"][0], j["anchor_a"][1]), (j["anchor_b"][0], j["anchor_b"][1])
    mass = inverse_masses(j, bodies)
    va, vb = apply_joint_impulse(va, vb, mass, ra, rb, lam * j["axis"][0], lam * j["axis"][1], 0.0)
    set_velocity(bodies, j["a"], va)
    set_velocity(bodies, j["b"], vb)


@njit
def solve_pin_velocity(j, bodies) -> None:
    """lambda = -(u . Cdot - target) / K along the axis, accumulated."""
    va, vb = velocity_of(bodies, j["a"]), velocity_of(bodies, j["b"])
    ra, rb = (j["anchor_a"][0], j["anchor_a"][1]), (j["anchor_b"][0], j["anchor_b"][1])
    ux, uy = j["axis"][0], j["axis"][1]
    rel = anchor_velocity(va, ra, vb, rb)
    lam = -j["axial_mass"] * (ux * rel[0] + uy * rel[1] - j["target"][0])
    j["impulse"][0] += lam
    va, vb = apply_joint_impulse(va, vb, inverse_masses(j, bodies), ra, rb, lam * ux, lam * uy, 0.0)
    set_velocity(bodies, j["a"], va)
    set_velocity(bodies, j["b"], vb)


@njit
def solve_pin_position(j, bodies) -> float:
    """Non-linear Gauss-Seidel on C = |pb - pa| - L; returns |C| before the push (m)."""
    ra, rb, u, length, k = rod(j, bodies)
    error = length - j["length"]
    if k <= 0.0:
        return abs(error)
    lam = -min(max(error, -MAX_LINEAR_CORRECTION), MAX_LINEAR_CORRECTION) / k
    move_joint_bodies(j, bodies, ra, rb, lam * u[0], lam * u[1], 0.0)
    return abs(error)


# --- the soft step (sandbox.solvers.soft) ----------------------------------------------------
@njit
def rod_now(j, bodies):
    """Arms r_a, r_b at the bodies' current poses, the unit vector from anchor a to anchor b
    and its length, from the moves since the step began: d = (dc_b - dc_a) + (r_b - r_a) +
    (c_b - c_a at the start)."""
    a, b = bodies[j["a"]], bodies[j["b"]]
    ra, rb = arm(a, j["local_a"]), arm(b, j["local_b"])
    dx = b["delta_position"][0] - a["delta_position"][0] + rb[0] - ra[0] + j["delta_center"][0]
    dy = b["delta_position"][1] - a["delta_position"][1] + rb[1] - ra[1] + j["delta_center"][1]
    length = math.sqrt(dx * dx + dy * dy)
    ux, uy = (dx / length, dy / length) if length > 1e-12 else (0.0, 0.0)
    return ra, rb, (ux, uy), length


@njit
def warm_start_pin_soft(j, bodies) -> None:
    """The accumulated impulse again, along the rod as it is now."""
    ra, rb, u, _ = rod_now(j, bodies)
    va, vb = velocity_of(bodies, j["a"]), velocity_of(bodies, j["b"])
    lam = j["impulse"][0]
    va, vb = apply_joint_impulse(
        va, vb, inverse_masses(j, bodies), ra, rb, lam * u[0], lam * u[1], 0.0
    )
    set_velocity(bodies, j["a"], va)
    set_velocity(bodies, j["b"], vb)


@njit
def pin_rod_error(j, bodies, soft, use_bias: bool):
    """The rod's arms and direction u, and what its impulse must cancel, u . Cdot + bias
    (m/s), with the soft bias on C = |pb - pa| - L (none in the relax pass)."""
    ra, rb, u, length = rod_now(j, bodies)
    va, vb = velocity_of(bodies, j["a"]), velocity_of(bodies, j["b"])
    rel = anchor_velocity(va, ra, vb, rb)
    error = u[0] * rel[0] + u[1] * rel[1]
    if use_bias:
        error += soft[0] * (length - j["length"])
    return ra, rb, u, error


@njit
def solve_pin_soft(j, bodies, soft, use_bias: bool) -> None:
    """The rod as a soft constraint: lambda = -mass_scale m_eff (u . Cdot + bias_rate C) -
    impulse_scale lambda_total with C = |pb - pa| - L (``soft`` = (bias_rate, mass_scale,
    impulse_scale), :func:`sandbox.solvers.soft.softness`); rigid without bias (relax)."""
    ra, rb, u, error = pin_rod_error(j, bodies, soft, use_bias)
    mass_scale, impulse_scale = (soft[1], soft[2]) if use_bias else (1.0, 0.0)
    lam = -mass_scale * j["axial_mass"] * error - impulse_scale * j["impulse"][0]
    j["impulse"][0] += lam
    va, vb = velocity_of(bodies, j["a"]), velocity_of(bodies, j["b"])
    va, vb = apply_joint_impulse(
        va, vb, inverse_masses(j, bodies), ra, rb, lam * u[0], lam * u[1], 0.0
    )
    set_velocity(bodies, j["a"], va)
    set_velocity(bodies, j["b"], vb)


class PinJoint(Joint):
    """Keep ``anchor_a`` on body ``a`` and ``anchor_b`` on ``b`` at their distance when attached.

    Anchors are in each body's origin frame (m). The rod pushes and pulls; the bodies turn freely
    about their anchors (pymunk's ``PinJoint``). For anchors that coincide (distance 0, where
    the rod has no direction) use a :class:`~sandbox.joints.PivotJoint`.
    """

    type = "pin"
    code = PIN

    def attached(self, world) -> None:
        self.record["length"] = self.anchor_distance(world)

    @property
    def distance(self) -> float | None:
        """The rod's length L (m), fixed when the joint joins a world."""
        return float(self.record["length"]) if self.world is not None else None

    @property
    def impulse(self) -> float:
        """Accumulated impulse along the axis (N s) of the last step."""
        return float(self.record["impulse"][0])

    def to_dict(self) -> dict:
        return self._anchors_dict()

    def anchor_error(self, world=None) -> float:
        """| |pb - pa| - L | (m)."""
        return abs(self.anchor_distance(world) - self.record["length"])

    @property
    def reaction_force(self) -> float:
        """Tension (N, > 0 pulling the anchors together) of the last step: impulse / dt."""
        dt = self.record["dt"]
        return -self.impulse / dt if dt > 0 else 0.0
