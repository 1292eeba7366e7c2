"""Damped spring between two anchors: a force, not a constraint.

Hooke's law with a dashpot (slides, "Further Topics": springs; "Force": forces add as vectors).
With d = pb - pa between the world anchors, d_hat = d / |d| and x = |d| - L the stretch:

    F_b = -k x d_hat - c ((v_pb - v_pa) . d_hat) d_hat,      F_a = -F_b

applied at the anchors, so each body also feels the torque r x F (slides, "Torque").

Design choice: a spring is a force generator. It lives in ``world.joints`` (it is a joint in the
scene file) but is evaluated through ``accumulate(world, p, v, phi, w, f, tau)`` together with
the other forces, so look-ahead integrators (Verlet, RK4) see it at their intermediate states,
and its potential energy k x^2 / 2 counts in ``world.potential_energy()``. Its solver methods do
nothing.
"""

from __future__ import annotations

import math

import numpy as np

from sandbox.joints.base import Joint, cross


class SpringJoint(Joint):
    """Damped spring: ``stiffness`` k (N/m), ``damping`` c (N s/m), ``rest_length`` L (m).

    ``rest_length=None`` takes the anchors' distance when attached (as the pymunk bridge does).
    """

    type = "spring"

    def __init__(
        self,
        a,
        b,
        anchor_a=(0.0, 0.0),
        anchor_b=(0.0, 0.0),
        rest_length: float | None = None,
        stiffness: float = 1.0,
        damping: float = 0.0,
    ) -> None:
        super().__init__(a, b, anchor_a, anchor_b)
        self.rest_length = None if rest_length is None else float(rest_length)
        self.stiffness = float(stiffness)
        self.damping = float(damping)
        for name, value in (("stiffness", self.stiffness), ("damping", self.damping)):
            if not (math.isfinite(value) and value >= 0.0):
                raise ValueError(f"{name}: expected a number >= 0, got {value}")
        if self.rest_length is not None and not self.rest_length >= 0.0:
            raise ValueError(f"rest_length: expected a number >= 0, got {self.rest_length}")

    def attach(self, world) -> None:
        super().attach(world)
        if self.rest_length is None:
            pa, pb = self.world_anchors(world)
            self.rest_length = float(math.hypot(*(pb - pa)))

    def to_dict(self) -> dict:
        return {
            **self._anchors_dict(),
            "rest_length": self.rest_length,
            "stiffness": self.stiffness,
            "damping": self.damping,
        }

    # --- the force ----------------------------------------------------------------------------
    def _arm(self, world, i: int, anchor: np.ndarray, angle: float) -> tuple[float, float]:
        qx = anchor[0] - world.local_com[i, 0]
        qy = anchor[1] - world.local_com[i, 1]
        c, s = math.cos(angle), math.sin(angle)
        return float(c * qx - s * qy), float(s * qx + c * qy)

    def force_on_b(self, world, p, v, phi, w) -> tuple[float, float, tuple, tuple]:
        """Spring + damper force on b (N) at the state (p, v, phi, w), and the two arms (m)."""
        ia, ib = self.ia, self.ib
        ra = self._arm(world, ia, self.anchor_a, float(phi[ia]))
        rb = self._arm(world, ib, self.anchor_b, float(phi[ib]))
        dx = float(p[ib, 0] + rb[0] - p[ia, 0] - ra[0])
        dy = float(p[ib, 1] + rb[1] - p[ia, 1] - ra[1])
        length = math.hypot(dx, dy)
        if length <= 1e-12:
            return 0.0, 0.0, ra, rb
        ux, uy = dx / length, dy / length
        # relative velocity of the anchors: vb + wb x rb - va - wa x ra
        wa, wb = float(w[ia]), float(w[ib])
        rvx = float(v[ib, 0] - wb * rb[1] - v[ia, 0] + wa * ra[1])
        rvy = float(v[ib, 1] + wb * rb[0] - v[ia, 1] - wa * ra[0])
        magnitude = -self.stiffness * (length - self.rest_length) - self.damping * (
            rvx * ux + rvy * uy
        )
        return magnitude * ux, magnitude * uy, ra, rb

    def accumulate(self, world, p, v, phi, w, f, tau) -> None:
        """Add the spring's forces and torques at the state (p, v, phi, w) into f and tau."""
        fx, fy, ra, rb = self.force_on_b(world, p, v, phi, w)
        ia, ib = self.ia, self.ib
        f[ib, 0] += fx
        f[ib, 1] += fy
        tau[ib] += cross(rb[0], rb[1], fx, fy)
        f[ia, 0] -= fx
        f[ia, 1] -= fy
        tau[ia] -= cross(ra[0], ra[1], fx, fy)

    def length(self, world=None) -> float:
        """Current distance between the anchors (m)."""
        pa, pb = self.world_anchors(world)
        return float(math.hypot(*(pb - pa)))

    def potential_energy(self, world=None) -> float:
        """k x^2 / 2 with x = |d| - L (J)."""
        x = self.length(world) - self.rest_length
        return 0.5 * self.stiffness * x * x

    def anchor_error(self, world=None) -> float:
        """0: a spring is a force, not a constraint (its stretch is :meth:`length` - L)."""
        return 0.0
