"""Pin joint: a massless rod keeping two anchors at a fixed distance (a pendulum's string).

Constraint (slides, "Further Topics": joints), with pa, pb the world anchors and u the unit
vector from pa to pb:

    C = |pb - pa| - L = 0,      Cdot = u . (vb + wb x rb - va - wa x ra) = 0

Velocity pass (sequential impulses, Box2D's distance joint): an impulse lambda u on b (and
-lambda u on a) with lambda = -Cdot / K, K = 1/ma + 1/mb + (ra x u)^2 / Ia + (rb x u)^2 / Ib,
accumulated over iterations and steps (warm starting). Position pass (non-linear Gauss-Seidel):
move the bodies by the pseudo impulse -C / K u to remove the drift that velocities leave.

Arc correction: a step along the tangent lengthens the rod by about |v_side|^2 dt^2 / 2L (the
bob leaves the circle). The velocity rule therefore asks for the small inward u . Cdot that
lands the anchors at distance L at the END of the step (see ``_arc_target``); the position pass
then has almost nothing to do, and a pendulum keeps its energy instead of losing it each swing.
"""

from __future__ import annotations

import math

from sandbox.joints.base import (
    MAX_ARC_TURN,
    MAX_LINEAR_CORRECTION,
    Joint,
    arc_error,
    cross,
    lever,
)


class PinJoint(Joint):
    """Keep ``anchor_a`` on body ``a`` and ``anchor_b`` on ``b`` at their distance when attached.

    Anchors are in each body's origin frame (m). The rod pushes and pulls; the bodies turn freely
    about their anchors (pymunk's ``PinJoint``). For anchors that coincide (distance 0, where
    the rod has no direction) use a :class:`~sandbox.joints.PivotJoint`.
    """

    type = "pin"

    def __init__(self, a, b, anchor_a=(0.0, 0.0), anchor_b=(0.0, 0.0)) -> None:
        super().__init__(a, b, anchor_a, anchor_b)
        self.distance = None  # m, fixed when attached
        self.impulse = 0.0  # N s along u, accumulated
        self._u = (0.0, 0.0)
        self._ra = self._rb = (0.0, 0.0)
        self._mass = 0.0
        self._target = 0.0
        self._dt = 0.0

    def attach(self, world) -> None:
        super().attach(world)
        pa, pb = self.world_anchors(world)
        self.distance = float(math.hypot(*(pb - pa)))

    def to_dict(self) -> dict:
        return self._anchors_dict()

    # --- geometry -----------------------------------------------------------------------------
    def _frame(self, world):
        """Arms, unit vector a -> b, current length and K = 1 / effective mass."""
        ia, ib, com = self.a.index, self.b.index, world.com
        ra, rb = lever(world, ia, self._qa), lever(world, ib, self._qb)
        dx = com.item(ib, 0) + rb[0] - com.item(ia, 0) - ra[0]
        dy = com.item(ib, 1) + rb[1] - com.item(ia, 1) - ra[1]
        length = math.hypot(dx, dy)
        u = (dx / length, dy / length) if length > 1e-12 else (0.0, 0.0)
        cra, crb = cross(*ra, *u), cross(*rb, *u)
        k = (
            world.inv_mass.item(ia)
            + world.inv_mass.item(ib)
            + world.inv_moment.item(ia) * cra * cra
            + world.inv_moment.item(ib) * crb * crb
        )
        return ra, rb, u, length, k

    def anchor_error(self, world=None) -> float:
        """| |pb - pa| - L | (m)."""
        w = world if world is not None else self.world
        return abs(self._frame(w)[3] - self.distance)

    @property
    def reaction_force(self) -> float:
        """Tension (N, > 0 pulling the anchors together) of the last step: impulse / dt."""
        return -self.impulse / self._dt if self._dt > 0 else 0.0

    # --- solver -------------------------------------------------------------------------------
    def prepare(self, world, dt: float) -> None:
        self._load_masses(world)
        self._ra, self._rb, self._u, _, k = self._frame(world)
        self._mass = 1.0 / k if k > 0.0 else 0.0
        self._dt = dt
        self._target = self._arc_target(world, dt)
        if not world.settings.warm_start:
            self.impulse = 0.0

    def _arc_target(self, world, dt: float) -> float:
        """The rate u . Cdot that brings the anchors to distance L at the END of the step.

        The step moves the anchors apart by D = dt (vb + wb x rb - va - wa x ra) plus each arm's
        arc error e (:func:`~sandbox.joints.base.arc_error`). Its sideways part D_perp also
        lengthens the rod (Pythagoras), so ask for (L + dt u.Cdot + u.e)^2 + |D_perp|^2 = L^2.
        Without this the pendulum drifts outwards every step and the position pass, pulling
        it back, drains its energy.
        """
        i, j, vel, om = self._i, self._j, world.vel, world.omega
        ra, rb, (ux, uy) = self._ra, self._rb, self._u
        wa, wb = om.item(i), om.item(j)
        ea, eb = arc_error(ra, wa * dt), arc_error(rb, wb * dt)
        ex, ey = eb[0] - ea[0], eb[1] - ea[1]
        dx = dt * (vel.item(j, 0) - wb * rb[1] - vel.item(i, 0) + wa * ra[1]) + ex
        dy = dt * (vel.item(j, 1) + wb * rb[0] - vel.item(i, 1) - wa * ra[0]) + ey
        along = ux * dx + uy * dy
        side2 = dx * dx + dy * dy - along * along
        length = self.distance
        side2 = min(side2, (MAX_ARC_TURN * length) ** 2)  # as arc_error: bounded feedback
        return (math.sqrt(length * length - side2) - length - (ux * ex + uy * ey)) / dt

    def warm_start(self, world) -> None:
        ux, uy = self._u
        self._apply(world, self.impulse * ux, self.impulse * uy, self._ra, self._rb)

    def solve_velocity(self, world) -> None:
        i, j, vel, om = self._i, self._j, world.vel, world.omega
        ra, rb, (ux, uy) = self._ra, self._rb, self._u
        wa, wb = om.item(i), om.item(j)
        # relative velocity of the anchors: vb + wb x rb - va - wa x ra
        dvx = vel.item(j, 0) - wb * rb[1] - vel.item(i, 0) + wa * ra[1]
        dvy = vel.item(j, 1) + wb * rb[0] - vel.item(i, 1) - wa * ra[0]
        lam = -self._mass * (ux * dvx + uy * dvy - self._target)
        self.impulse += lam
        self._apply(world, lam * ux, lam * uy, ra, rb)

    def solve_position(self, world) -> float:
        ra, rb, (ux, uy), length, k = self._frame(world)
        error = length - self.distance
        if not world.settings.position_correction or k <= 0.0:
            return abs(error)
        c = min(max(error, -MAX_LINEAR_CORRECTION), MAX_LINEAR_CORRECTION)
        lam = -c / k
        self._move(world, lam * ux, lam * uy, ra, rb)
        return abs(error)
