"""Pivot joint (hinge): two anchors held together, with optional angle limits and a motor.

Point constraint (slides, "Further Topics": hinges), pa and pb the world anchors:

    C = pb - pa = 0,      Cdot = vb + wb x rb - va - wa x ra = 0     (two rows)

solved with the 2x2 effective-mass matrix K (Box2D's revolute joint):

    K = (1/ma + 1/mb) I + [ra_y^2/Ia + rb_y^2/Ib, -ra_x ra_y/Ia - rb_x rb_y/Ib; ..., ra_x^2/Ia + rb_x^2/Ib]

Relative angle theta = angle_b - angle_a (as pymunk's ``RotaryLimitJoint``; kept continuous, so
a wheel turning many times does not wrap). Limits lo <= theta <= hi are two one-sided angular
constraints (impulses that only push); the motor drives wb - wa to ``rate`` with an angular
impulse bounded by ``max_torque * dt``. Position pass: non-linear Gauss-Seidel on the limits,
then on the point.

Arc correction: a turning body's anchor moves on an arc, R(w dt) r, not along the tangent
r + (w dt) x r that the velocity rows assume; the point rows aim at the arc's end
(``base.arc_error``), so a swinging rod or chain drifts and loses energy much less.
"""

from __future__ import annotations

import math

from sandbox.joints.base import (
    ANGULAR_SLOP,
    MAX_ANGULAR_CORRECTION,
    Joint,
    arc_error,
    body_angle,
    lever,
    unwrap,
)


def _k_matrix(ma: float, mb: float, ja: float, jb: float, ra, rb) -> tuple[float, float, float]:
    """K = [[k11, k12], [k12, k22]] of the point constraint (inverse masses ma, mb, ja, jb)."""
    k11 = ma + mb + ja * ra[1] * ra[1] + jb * rb[1] * rb[1]
    k12 = -ja * ra[0] * ra[1] - jb * rb[0] * rb[1]
    k22 = ma + mb + ja * ra[0] * ra[0] + jb * rb[0] * rb[0]
    return k11, k12, k22


def _solve2(k11: float, k12: float, k22: float, bx: float, by: float) -> tuple[float, float]:
    """x with K x = b (Cramer's rule); zero when K is singular."""
    det = k11 * k22 - k12 * k12
    if det == 0.0:
        return 0.0, 0.0
    inv = 1.0 / det
    return inv * (k22 * bx - k12 * by), inv * (k11 * by - k12 * bx)


class PivotJoint(Joint):
    """Pin ``anchor_a`` of ``a`` to ``anchor_b`` of ``b`` (m, origin frames): a hinge.

    ``limits=(lo, hi)`` (rad) bounds angle_b - angle_a; ``motor={"rate": r, "max_torque": t}``
    drives omega_b - omega_a to r (rad/s) with at most t (N m). Both may be changed between steps
    (``joint.limits``, ``joint.rate``, ``joint.max_torque``).
    """

    type = "pivot"

    def __init__(self, a, b, anchor_a=(0.0, 0.0), anchor_b=(0.0, 0.0), limits=None, motor=None):
        super().__init__(a, b, anchor_a, anchor_b)
        self.limits = None
        if limits is not None:
            lo, hi = (float(x) for x in limits)
            if not lo <= hi:
                raise ValueError(f"limits: expected lo <= hi, got [{lo}, {hi}]")
            self.limits = (lo, hi)
        self.rate = self.max_torque = None
        if motor is not None:
            self.rate = float(motor["rate"])
            self.max_torque = float(motor.get("max_torque", math.inf))
            if not self.max_torque > 0:
                raise ValueError(f"motor.max_torque: expected > 0, got {self.max_torque}")
        self.impulse = (0.0, 0.0)  # N s, point constraint, accumulated
        self.motor_impulse = 0.0  # N m s
        self.lower_impulse = self.upper_impulse = 0.0  # N m s, >= 0 each
        self.angle = 0.0  # rad, angle_b - angle_a, continuous
        self._ra = self._rb = (0.0, 0.0)
        self._k = (0.0, 0.0, 0.0)
        self._axial = 0.0
        self._target = (0.0, 0.0)
        self._dt = 0.0

    @property
    def motor(self) -> dict | None:
        if self.rate is None:
            return None
        return {"rate": self.rate, "max_torque": self.max_torque}

    def attach(self, world) -> None:
        super().attach(world)
        self.angle = body_angle(world, self.ib) - body_angle(world, self.ia)

    def to_dict(self) -> dict:
        return {
            **self._anchors_dict(),
            "limits": None if self.limits is None else list(self.limits),
            "motor": self.motor,
        }

    def relative_angle(self, world=None) -> float:
        """angle_b - angle_a (rad), continuous across turns."""
        w = world if world is not None else self.world
        return unwrap(body_angle(w, self.ib) - body_angle(w, self.ia), self.angle)

    def anchor_error(self, world=None) -> float:
        """|pb - pa| (m)."""
        pa, pb = self.world_anchors(world)
        return float(math.hypot(*(pb - pa)))

    @property
    def reaction_force(self) -> tuple[float, float]:
        """Force on b from the pin during the last step: impulse / dt (N)."""
        if self._dt <= 0:
            return (0.0, 0.0)
        return (self.impulse[0] / self._dt, self.impulse[1] / self._dt)

    @property
    def motor_torque(self) -> float:
        """Torque the motor applied on b in the last step (N m)."""
        return self.motor_impulse / self._dt if self._dt > 0 else 0.0

    # --- solver -------------------------------------------------------------------------------
    def prepare(self, world, dt: float) -> None:
        self._load_masses(world)
        self._ra, self._rb = lever(world, self._i, self._qa), lever(world, self._j, self._qb)
        self._k = _k_matrix(self._ma, self._mb, self._ja, self._jb, self._ra, self._rb)
        axial = self._ja + self._jb
        self._axial = 1.0 / axial if axial > 0.0 else 0.0
        self._dt = dt
        self.angle = self.relative_angle(world)
        # arc correction: aim the point rows at where the anchors really go by the end of the
        # step, c + v dt + R(w dt) r, not at the straight-line c + r + (v + w x r) dt
        ea = arc_error(self._ra, world.omega.item(self._i) * dt)
        eb = arc_error(self._rb, world.omega.item(self._j) * dt)
        self._target = ((ea[0] - eb[0]) / dt, (ea[1] - eb[1]) / dt)
        if not world.settings.warm_start:
            self.impulse, self.motor_impulse = (0.0, 0.0), 0.0
            self.lower_impulse = self.upper_impulse = 0.0
        if self.limits is None or axial == 0.0:
            self.lower_impulse = self.upper_impulse = 0.0
        if self.rate is None or axial == 0.0:
            self.motor_impulse = 0.0

    def warm_start(self, world) -> None:
        axial = self.motor_impulse + self.lower_impulse - self.upper_impulse
        self._apply(world, self.impulse[0], self.impulse[1], self._ra, self._rb, axial)

    def _angular(self, world, lam: float) -> None:
        """An angular impulse lam on b and -lam on a."""
        om = world.omega
        om[self._i] = om.item(self._i) - self._ja * lam
        om[self._j] = om.item(self._j) + self._jb * lam

    def solve_velocity(self, world) -> None:
        i, j, vel, om = self._i, self._j, world.vel, world.omega
        accumulate = world.settings.accumulate_impulses
        if self._axial > 0.0 and self.rate is not None:
            # motor: Cdot = wb - wa - rate, |impulse| <= max_torque dt
            lam = -self._axial * (om.item(j) - om.item(i) - self.rate)
            bound = self.max_torque * self._dt
            if accumulate:
                old = self.motor_impulse
                self.motor_impulse = min(max(old + lam, -bound), bound)
                lam = self.motor_impulse - old
            else:
                lam = min(max(lam, -bound), bound)
                self.motor_impulse += lam
            self._angular(world, lam)
        if self._axial > 0.0 and self.limits is not None:
            lo, hi = self.limits
            inv_dt = 1.0 / self._dt
            # lower: C = theta - lo >= 0; a gap C > 0 may close at C / dt this step (speculative)
            c = self.angle - lo
            lam = -self._axial * (om.item(j) - om.item(i) + max(c, 0.0) * inv_dt)
            lam, self.lower_impulse = _push_only(lam, self.lower_impulse, accumulate)
            self._angular(world, lam)
            # upper: C = hi - theta >= 0, pushing the other way
            c = hi - self.angle
            lam = -self._axial * (om.item(i) - om.item(j) + max(c, 0.0) * inv_dt)
            lam, self.upper_impulse = _push_only(lam, self.upper_impulse, accumulate)
            self._angular(world, -lam)
        # point: Cdot = vb + wb x rb - va - wa x ra, impulse = K^-1 (target - Cdot)
        ra, rb = self._ra, self._rb
        wa, wb = om.item(i), om.item(j)
        cx = vel.item(j, 0) - wb * rb[1] - vel.item(i, 0) + wa * ra[1]
        cy = vel.item(j, 1) + wb * rb[0] - vel.item(i, 1) - wa * ra[0]
        px, py = _solve2(*self._k, self._target[0] - cx, self._target[1] - cy)
        self.impulse = (self.impulse[0] + px, self.impulse[1] + py)
        self._apply(world, px, py, ra, rb)

    def solve_position(self, world) -> float:
        """NGS on the limits, then on the point; returns the larger error found (m, or rad for
        a limit)."""
        i, j, com = self._i, self._j, world.com
        correct = world.settings.position_correction
        angular_error = 0.0
        axial = self._ja + self._jb
        if self.limits is not None and axial > 0.0:
            lo, hi = self.limits
            theta = self.relative_angle(world)
            c = 0.0
            if hi - lo < 2.0 * ANGULAR_SLOP:
                c = min(max(theta - lo, -MAX_ANGULAR_CORRECTION), MAX_ANGULAR_CORRECTION)
            elif theta <= lo:
                c = min(max(theta - lo + ANGULAR_SLOP, -MAX_ANGULAR_CORRECTION), 0.0)
            elif theta >= hi:
                c = min(max(theta - hi - ANGULAR_SLOP, 0.0), MAX_ANGULAR_CORRECTION)
            angular_error = abs(c)
            if correct and c != 0.0:
                self._move(world, 0.0, 0.0, (0.0, 0.0), (0.0, 0.0), -c / axial)
        ra, rb = lever(world, i, self._qa), lever(world, j, self._qb)
        cx = com.item(j, 0) + rb[0] - com.item(i, 0) - ra[0]
        cy = com.item(j, 1) + rb[1] - com.item(i, 1) - ra[1]
        if correct:
            k = _k_matrix(self._ma, self._mb, self._ja, self._jb, ra, rb)
            px, py = _solve2(*k, -cx, -cy)
            self._move(world, px, py, ra, rb)
        return max(math.hypot(cx, cy), angular_error)


def _push_only(lam: float, total: float, accumulate: bool) -> tuple[float, float]:
    """Clamp a limit impulse so the accumulated (or, without accumulation, the single) impulse
    only pushes (>= 0); returns (impulse to apply, new total)."""
    if accumulate:
        new = max(total + lam, 0.0)
        return new - total, new
    lam = max(lam, 0.0)
    return lam, total + lam
