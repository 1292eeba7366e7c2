"""Pivot joint (hinge): two anchors held together, with optional angle limits and a motor.

Point constraint (slides, "Further Topics": hinges), pa and pb the world anchors:

    C = pb - pa = 0,      Cdot = vb + wb x rb - va - wa x ra = 0     (two rows)

solved with the 2x2 effective-mass matrix K (Box2D's revolute joint):

    K = (1/ma + 1/mb) I + [ra_y^2/Ia + rb_y^2/Ib, -ra_x ra_y/Ia - rb_x rb_y/Ib; ..., ra_x^2/Ia + rb_x^2/Ib]

Relative angle theta = angle_b - angle_a (as pymunk's ``RotaryLimitJoint``; the bodies' angles
are continuous, so a wheel turning many times does not wrap). Limits lo <= theta <= hi are two
one-sided angular constraints (impulses that only push); the motor drives wb - wa to ``rate``
with an angular impulse bounded by ``max_torque * dt``. Position pass: non-linear Gauss-Seidel
on the limits, then on the point.

Arc correction: a turning body's anchor moves on an arc, R(w dt) r, not along the tangent
r + (w dt) x r that the velocity rows assume; the point rows aim at the arc's end
(:func:`~sandbox.joints.base.arc_error`), so a swinging rod or chain drifts and loses energy
much less.
"""

from __future__ import annotations

import math

from sandbox.jit import njit
from sandbox.joints.base import (
    ANGULAR_SLOP,
    MAX_ANGULAR_CORRECTION,
    Joint,
    anchor_velocity,
    apply_joint_impulse,
    arc_error,
    arm,
    inverse_masses,
    move_joint_bodies,
)
from sandbox.math2d import inverse_or_zero, set_velocity, velocity, velocity_of
from sandbox.records import PIVOT


@njit
def point_matrix(mass, ra, rb) -> tuple[float, float, float]:
    """K = [[k11, k12], [k12, k22]] of the point constraint (inverse masses ``mass``)."""
    ma, ia, mb, ib = mass
    k11 = ma + mb + ia * ra[1] * ra[1] + ib * rb[1] * rb[1]
    k12 = -ia * ra[0] * ra[1] - ib * rb[0] * rb[1]
    k22 = ma + mb + ia * ra[0] * ra[0] + ib * rb[0] * rb[0]
    return k11, k12, k22


@njit
def solve2(k, bx: float, by: float) -> tuple[float, float]:
    """x with K x = b (Cramer's rule); zero when K is singular."""
    k11, k12, k22 = k
    det = k11 * k22 - k12 * k12
    if det == 0.0:
        return 0.0, 0.0
    inv = 1.0 / det
    return inv * (k22 * bx - k12 * by), inv * (k11 * by - k12 * bx)


@njit
def relative_angle(j, bodies) -> float:
    """angle_b - angle_a (rad), continuous, including what the position passes turned."""
    a, b = bodies[j["a"]], bodies[j["b"]]
    return (b["angle"] + b["turn"]) - (a["angle"] + a["turn"])


@njit
def prepare_pivot(j, bodies, dt: float, warm: bool) -> None:
    """Arms, K, the axial mass 1 / (1/Ia + 1/Ib), the relative angle and the arc targets."""
    a, b = bodies[j["a"]], bodies[j["b"]]
    mass = inverse_masses(j, bodies)
    ra, rb = arm(a, j["local_a"]), arm(b, j["local_b"])
    j["anchor_a"][0], j["anchor_a"][1] = ra
    j["anchor_b"][0], j["anchor_b"][1] = rb
    j["k"][0], j["k"][1], j["k"][2] = point_matrix(mass, ra, rb)
    axial = mass[1] + mass[3]
    j["axial_mass"] = inverse_or_zero(axial)
    j["dt"] = dt
    j["angle"] = relative_angle(j, bodies)
    # arc correction: aim the point rows at where the anchors really go by the end of the
    # step, c + v dt + R(w dt) r, not at the straight-line c + r + (v + w x r) dt
    ea = arc_error(ra[0], ra[1], a["omega"] * dt)
    eb = arc_error(rb[0], rb[1], b["omega"] * dt)
    j["target"][0], j["target"][1] = (ea[0] - eb[0]) / dt, (ea[1] - eb[1]) / dt
    if not warm:
        j["impulse"][0] = j["impulse"][1] = 0.0
        j["motor_impulse"] = j["lower_impulse"] = j["upper_impulse"] = 0.0
    if not j["has_limits"] or axial == 0.0:
        j["lower_impulse"] = j["upper_impulse"] = 0.0
    if not j["has_motor"] or axial == 0.0:
        j["motor_impulse"] = 0.0


@njit
def warm_start_pivot(j, bodies) -> None:
    """Apply last step's point impulse and angular impulses (motor, limits) again."""
    va, vb = velocity_of(bodies, j["a"]), velocity_of(bodies, j["b"])
    ra, rb = (j["anchor_a"][0], j["anchor_a"][1]), (j["anchor_b"][0], j["anchor_b"][1])
    axial = j["motor_impulse"] + j["lower_impulse"] - j["upper_impulse"]
    mass = inverse_masses(j, bodies)
    va, vb = apply_joint_impulse(va, vb, mass, ra, rb, j["impulse"][0], j["impulse"][1], axial)
    set_velocity(bodies, j["a"], va)
    set_velocity(bodies, j["b"], vb)


@njit
def push_only(lam: float, total: float, accumulate: bool) -> tuple[float, float]:
    """Clamp a limit impulse so the accumulated (or, without accumulation, the single) impulse
    only pushes (>= 0); returns (impulse to apply, new total)."""
    if accumulate:
        new = max(total + lam, 0.0)
        return new - total, new
    lam = max(lam, 0.0)
    return lam, total + lam


@njit
def angular(va, vb, mass, lam: float):
    """An angular impulse lam on b and -lam on a."""
    return (va[0], va[1], va[2] - mass[1] * lam), (vb[0], vb[1], vb[2] + mass[3] * lam)


@njit
def solve_pivot_velocity(j, bodies, accumulate: bool) -> None:
    """Motor, then the limits, then the point (Box2D's revolute joint order)."""
    va, vb = velocity_of(bodies, j["a"]), velocity_of(bodies, j["b"])
    mass = inverse_masses(j, bodies)
    axial_mass = j["axial_mass"]
    if axial_mass > 0.0 and j["has_motor"]:
        # motor: Cdot = wb - wa - rate, |impulse| <= max_torque dt
        lam = -axial_mass * (vb[2] - va[2] - j["motor_rate"])
        bound = j["max_torque"] * j["dt"]
        if accumulate:
            old = j["motor_impulse"]
            j["motor_impulse"] = min(max(old + lam, -bound), bound)
            lam = j["motor_impulse"] - old
        else:
            lam = min(max(lam, -bound), bound)
            j["motor_impulse"] += lam
        va, vb = angular(va, vb, mass, lam)
    if axial_mass > 0.0 and j["has_limits"]:
        inv_dt = 1.0 / j["dt"]
        # lower: C = theta - lo >= 0; a gap C > 0 may close at C / dt this step (speculative)
        c = j["angle"] - j["lower"]
        lam = -axial_mass * (vb[2] - va[2] + max(c, 0.0) * inv_dt)
        lam, j["lower_impulse"] = push_only(lam, j["lower_impulse"], accumulate)
        va, vb = angular(va, vb, mass, lam)
        # upper: C = hi - theta >= 0, pushing the other way
        c = j["upper"] - j["angle"]
        lam = -axial_mass * (va[2] - vb[2] + max(c, 0.0) * inv_dt)
        lam, j["upper_impulse"] = push_only(lam, j["upper_impulse"], accumulate)
        va, vb = angular(va, vb, mass, -lam)
    # point: Cdot = vb + wb x rb - va - wa x ra, impulse = K^-1 (target - Cdot)
    ra, rb = (j["anchor_a"][0], j["anchor_a"][1]), (j["anchor_b"][0], j["anchor_b"][1])
    cx, cy = anchor_velocity(va, ra, vb, rb)
    k = (j["k"][0], j["k"][1], j["k"][2])
    px, py = solve2(k, j["target"][0] - cx, j["target"][1] - cy)
    j["impulse"][0] += px
    j["impulse"][1] += py
    va, vb = apply_joint_impulse(va, vb, mass, ra, rb, px, py, 0.0)
    set_velocity(bodies, j["a"], va)
    set_velocity(bodies, j["b"], vb)


@njit
def limit_error(theta: float, lo: float, hi: float) -> float:
    """How far theta is outside [lo, hi] beyond the angular slop (rad, signed), clamped."""
    if hi - lo < 2.0 * ANGULAR_SLOP:
        return min(max(theta - lo, -MAX_ANGULAR_CORRECTION), MAX_ANGULAR_CORRECTION)
    if theta <= lo:
        return min(max(theta - lo + ANGULAR_SLOP, -MAX_ANGULAR_CORRECTION), 0.0)
    if theta >= hi:
        return min(max(theta - hi - ANGULAR_SLOP, 0.0), MAX_ANGULAR_CORRECTION)
    return 0.0


@njit
def solve_limit_position(j, bodies) -> float:
    """NGS on the limits alone: the relative angle turned back within [lower, upper]; returns
    how far outside it was (rad)."""
    mass = inverse_masses(j, bodies)
    axial = mass[1] + mass[3]
    if not j["has_limits"] or axial <= 0.0:
        return 0.0
    c = limit_error(relative_angle(j, bodies), j["lower"], j["upper"])
    if c != 0.0:
        move_joint_bodies(j, bodies, (0.0, 0.0), (0.0, 0.0), 0.0, 0.0, -c / axial)
    return abs(c)


@njit
def solve_pivot_position(j, bodies) -> float:
    """NGS on the limits, then on the point; returns the larger error found (m, or rad for a
    limit)."""
    mass = inverse_masses(j, bodies)
    angular_error = solve_limit_position(j, bodies)
    a, b = bodies[j["a"]], bodies[j["b"]]
    ra, rb = arm(a, j["local_a"]), arm(b, j["local_b"])
    cx = b["com"][0] + rb[0] - a["com"][0] - ra[0]
    cy = b["com"][1] + rb[1] - a["com"][1] - ra[1]
    px, py = solve2(point_matrix(mass, ra, rb), -cx, -cy)
    move_joint_bodies(j, bodies, ra, rb, px, py, 0.0)
    return max(math.hypot(cx, cy), angular_error)


# --- the soft step (sandbox.solvers.soft) ----------------------------------------------------
@njit
def arms_now(j, bodies):
    """Arms r_a, r_b at the bodies' current poses."""
    return arm(bodies[j["a"]], j["local_a"]), arm(bodies[j["b"]], j["local_b"])


@njit
def warm_start_pivot_soft(j, bodies) -> None:
    """The accumulated point and angular impulses again, at the arms as they are now."""
    ra, rb = arms_now(j, bodies)
    va, vb = velocity_of(bodies, j["a"]), velocity_of(bodies, j["b"])
    axial = j["motor_impulse"] + j["lower_impulse"] - j["upper_impulse"]
    mass = inverse_masses(j, bodies)
    va, vb = apply_joint_impulse(va, vb, mass, ra, rb, j["impulse"][0], j["impulse"][1], axial)
    set_velocity(bodies, j["a"], va)
    set_velocity(bodies, j["b"], vb)


@njit
def soft_limit(axial_mass, c, cdot, total, soft, use_bias, inv_h) -> float:
    """A one-sided angular limit C >= 0 as a soft constraint (speculative while C > 0);
    returns the change of the accumulated impulse (which stays >= 0)."""
    bias, mass_scale, impulse_scale = 0.0, 1.0, 0.0
    if c > 0.0:
        bias = c * inv_h
    elif use_bias:
        bias, mass_scale, impulse_scale = soft[0] * c, soft[1], soft[2]
    lam = -axial_mass * mass_scale * (cdot + bias) - impulse_scale * total
    return max(total + lam, 0.0) - total


@njit
def solve_pivot_axial_soft(j, bodies, soft, use_bias: bool, inv_h: float) -> None:
    """The motor, then the limits as soft one-sided constraints (Box2D v3's revolute joint)."""
    axial_mass = j["axial_mass"]
    if axial_mass == 0.0 or not (j["has_motor"] or j["has_limits"]):
        return
    va, vb = velocity_of(bodies, j["a"]), velocity_of(bodies, j["b"])
    mass = inverse_masses(j, bodies)
    if j["has_motor"]:
        bound = j["max_torque"] * j["dt"]
        old = j["motor_impulse"]
        j["motor_impulse"] = min(
            max(old - axial_mass * (vb[2] - va[2] - j["motor_rate"]), -bound), bound
        )
        va, vb = angular(va, vb, mass, j["motor_impulse"] - old)
    if j["has_limits"]:
        theta = relative_angle(j, bodies)
        lam = soft_limit(
            axial_mass, theta - j["lower"], vb[2] - va[2], j["lower_impulse"], soft, use_bias, inv_h
        )
        j["lower_impulse"] += lam
        va, vb = angular(va, vb, mass, lam)
        lam = soft_limit(
            axial_mass, j["upper"] - theta, va[2] - vb[2], j["upper_impulse"], soft, use_bias, inv_h
        )
        j["upper_impulse"] += lam
        va, vb = angular(va, vb, mass, -lam)
    set_velocity(bodies, j["a"], va)
    set_velocity(bodies, j["b"], vb)


@njit
def pivot_point_error(j, pair, soft, use_bias: bool):
    """The point rows' arms and what the impulse must cancel, Cdot + bias (m/s): the anchors'
    relative velocity, aimed at the arc's end, plus the soft bias on C = (dc_b - dc_a) +
    (r_b - r_a) + (c_b - c_a at the start) = pb - pa (none in the relax pass). ``pair``: the
    BODY records of the joint's bodies a and b (records, not the bodies' array: called once a
    joint and a pass, the array was reference-counted at every call)."""
    a, b = pair
    va, vb = velocity(a), velocity(b)
    ra, rb = arm(a, j["local_a"]), arm(b, j["local_b"])
    cx, cy = anchor_velocity(va, ra, vb, rb)
    # arc correction: the anchors move on arcs R(w h) r, not along the tangents the velocity
    # rows assume; aim at where they really go by the end of the substep
    h = j["dt"]
    ea, eb = arc_error(ra[0], ra[1], va[2] * h), arc_error(rb[0], rb[1], vb[2] * h)
    cx, cy = cx - (ea[0] - eb[0]) / h, cy - (ea[1] - eb[1]) / h
    if use_bias:
        sx = b["delta_position"][0] - a["delta_position"][0] + rb[0] - ra[0] + j["delta_center"][0]
        sy = b["delta_position"][1] - a["delta_position"][1] + rb[1] - ra[1] + j["delta_center"][1]
        cx, cy = cx + soft[0] * sx, cy + soft[0] * sy
    return ra, rb, cx, cy


@njit
def solve_pivot_soft(j, bodies, soft, use_bias: bool, inv_h: float) -> None:
    """Motor, limits and point as soft constraints (Box2D v3's revolute joint): the point
    impulse P = -mass_scale K^-1 (Cdot + bias) - impulse_scale P_total."""
    solve_pivot_axial_soft(j, bodies, soft, use_bias, inv_h)
    pair = bodies[j["a"]], bodies[j["b"]]
    ra, rb, ex, ey = pivot_point_error(j, pair, soft, use_bias)
    mass_scale, impulse_scale = (soft[1], soft[2]) if use_bias else (1.0, 0.0)
    mass = inverse_masses(j, bodies)
    ux, uy = solve2(point_matrix(mass, ra, rb), ex, ey)
    px = -mass_scale * ux - impulse_scale * j["impulse"][0]
    py = -mass_scale * uy - impulse_scale * j["impulse"][1]
    j["impulse"][0] += px
    j["impulse"][1] += py
    va, vb = velocity_of(bodies, j["a"]), velocity_of(bodies, j["b"])
    va, vb = apply_joint_impulse(va, vb, mass, ra, rb, px, py, 0.0)
    set_velocity(bodies, j["a"], va)
    set_velocity(bodies, j["b"], vb)


class PivotJoint(Joint):
    """Pin ``anchor_a`` of ``a`` to ``anchor_b`` of ``b`` (m, origin frames): a hinge.

    ``limits=(lo, hi)`` (rad) bounds angle_b - angle_a; ``motor={"rate": r, "max_torque": t}``
    drives omega_b - omega_a to r (rad/s) with at most t (N m). Both may be changed between steps
    (``joint.limits``, ``joint.rate``, ``joint.max_torque``).
    """

    type = "pivot"
    code = PIVOT

    def __init__(self, a, b, anchor_a=(0.0, 0.0), anchor_b=(0.0, 0.0), limits=None, motor=None):
        super().__init__(a, b, anchor_a, anchor_b)
        self.limits = limits
        if motor is not None:
            self.max_torque = float(motor.get("max_torque", math.inf))
            self.rate = float(motor["rate"])

    @property
    def limits(self) -> tuple[float, float] | None:
        """(lo, hi) bounds of angle_b - angle_a (rad), or None."""
        r = self.record
        return (float(r["lower"]), float(r["upper"])) if r["has_limits"] else None

    @limits.setter
    def limits(self, value) -> None:
        r = self.record
        if value is None:
            r["has_limits"] = False
            return
        lo, hi = (float(x) for x in value)
        if not lo <= hi:
            raise ValueError(f"limits: expected lo <= hi, got [{lo}, {hi}]")
        r["lower"], r["upper"], r["has_limits"] = lo, hi, True

    @property
    def rate(self) -> float | None:
        """The motor's target rate omega_b - omega_a (rad/s), or None without a motor."""
        r = self.record
        return float(r["motor_rate"]) if r["has_motor"] else None

    @rate.setter
    def rate(self, value) -> None:
        r = self.record
        if value is None:
            r["has_motor"] = False
            return
        if not r["max_torque"] > 0:
            r["max_torque"] = math.inf
        r["motor_rate"], r["has_motor"] = float(value), True

    @property
    def max_torque(self) -> float | None:
        """The motor's largest torque (N m), or None without a motor."""
        r = self.record
        return float(r["max_torque"]) if r["has_motor"] else None

    @max_torque.setter
    def max_torque(self, value) -> None:
        value = float(value)
        if not value > 0:
            raise ValueError(f"motor.max_torque: expected > 0, got {value}")
        self.record["max_torque"] = value

    @property
    def motor(self) -> dict | None:
        if self.rate is None:
            return None
        return {"rate": self.rate, "max_torque": self.max_torque}

    @property
    def angle(self) -> float:
        """angle_b - angle_a (rad) at the last step's start, continuous."""
        return float(self.record["angle"])

    @property
    def impulse(self) -> tuple[float, float]:
        """Accumulated point impulse on b (N s) of the last step."""
        return float(self.record["impulse"][0]), float(self.record["impulse"][1])

    @property
    def motor_impulse(self) -> float:
        return float(self.record["motor_impulse"])

    @property
    def lower_impulse(self) -> float:
        return float(self.record["lower_impulse"])

    @property
    def upper_impulse(self) -> float:
        return float(self.record["upper_impulse"])

    def attached(self, world) -> None:
        self.record["angle"] = self.relative_angle(world)

    def to_dict(self) -> dict:
        limits = self.limits
        return {
            **self._anchors_dict(),
            "limits": None if limits is None else list(limits),
            "motor": self.motor,
        }

    def relative_angle(self, world=None) -> float:
        """angle_b - angle_a (rad), continuous across turns."""
        w = world if world is not None else self.world
        return float(w.state["angle"][self.ib] - w.state["angle"][self.ia])

    def anchor_error(self, world=None) -> float:
        """|pb - pa| (m)."""
        return self.anchor_distance(world)

    @property
    def reaction_force(self) -> tuple[float, float]:
        """Force on b from the pin during the last step: impulse / dt (N)."""
        dt = self.record["dt"]
        if dt <= 0:
            return (0.0, 0.0)
        return (self.impulse[0] / dt, self.impulse[1] / dt)

    @property
    def motor_torque(self) -> float:
        """Torque the motor applied on b in the last step (N m)."""
        dt = self.record["dt"]
        return self.motor_impulse / dt if dt > 0 else 0.0
