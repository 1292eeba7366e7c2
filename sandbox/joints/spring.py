"""Damped spring between two anchors: a force, not a constraint.

Hooke's law with a dashpot (slides, "Further Topics": springs; "Force": forces add as vectors).
With d = pb - pa between the world anchors, d_hat = d / |d| and x = |d| - L the stretch:

    F_b = -k x d_hat - c ((v_pb - v_pa) . d_hat) d_hat,      F_a = -F_b

applied at the anchors, so each body also feels the torque r x F (slides, "Torque").

Design choice: a spring is a force generator. It lives in ``world.joints`` (it is a joint in the
scene file) but its force is evaluated with the other forces (:func:`spring_force`, called by
:func:`sandbox.forces.accumulate_forces`), so look-ahead integrators (Verlet, RK4) see it at
their intermediate states, and its potential energy k x^2 / 2 counts in
``world.potential_energy()``. The joint solvers skip it.
"""

from __future__ import annotations

import math

from sandbox.jit import njit
from sandbox.joints.base import Joint
from sandbox.math2d import rotate
from sandbox.records import SPRING


@njit
def spring_force(j, bodies, state) -> tuple[float, float, tuple, tuple]:
    """Spring + damper force on b (N) at the integrator's ``state`` (MOTION records: ``p``
    centre of mass, ``v``, ``phi`` angle, ``w``), and the two arms (m)."""
    sa, sb = state[j["a"]], state[j["b"]]
    ra = rotate(math.cos(sa["phi"]), math.sin(sa["phi"]), j["local_a"][0], j["local_a"][1])
    rb = rotate(math.cos(sb["phi"]), math.sin(sb["phi"]), j["local_b"][0], j["local_b"][1])
    dx = sb["p"][0] + rb[0] - sa["p"][0] - ra[0]
    dy = sb["p"][1] + rb[1] - sa["p"][1] - ra[1]
    length = math.sqrt(dx * dx + dy * dy)
    if length <= 1e-12:
        return 0.0, 0.0, ra, rb
    ux, uy = dx / length, dy / length
    # relative velocity of the anchors: vb + wb x rb - va - wa x ra
    rvx = sb["v"][0] - sb["w"] * rb[1] - sa["v"][0] + sa["w"] * ra[1]
    rvy = sb["v"][1] + sb["w"] * rb[0] - sa["v"][1] - sa["w"] * ra[0]
    magnitude = -j["stiffness"] * (length - j["length"]) - j["damping"] * (rvx * ux + rvy * uy)
    return magnitude * ux, magnitude * uy, ra, rb


class SpringJoint(Joint):
    """Damped spring: ``stiffness`` k (N/m), ``damping`` c (N s/m), ``rest_length`` L (m).

    ``rest_length=None`` takes the anchors' distance when attached (as the pymunk bridge does).
    """

    type = "spring"
    code = SPRING

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
        self._rest_given = rest_length is not None
        self.rest_length = 0.0 if rest_length is None else rest_length
        self.stiffness = stiffness
        self.damping = damping

    def attached(self, world) -> None:
        if not self._rest_given:
            self.record["length"] = self.anchor_distance(world)
            self._rest_given = True

    def _set(self, field: str, name: str, value: float) -> None:
        value = float(value)
        if not (math.isfinite(value) and value >= 0.0):
            raise ValueError(f"{name}: expected a number >= 0, got {value}")
        self.record[field] = value

    @property
    def rest_length(self) -> float | None:
        """L (m); None until attached when it is taken from the anchors' distance."""
        return float(self.record["length"]) if self._rest_given else None

    @rest_length.setter
    def rest_length(self, value: float) -> None:
        self._set("length", "rest_length", value)

    @property
    def stiffness(self) -> float:
        """k (N/m)."""
        return float(self.record["stiffness"])

    @stiffness.setter
    def stiffness(self, value: float) -> None:
        self._set("stiffness", "stiffness", value)

    @property
    def damping(self) -> float:
        """c (N s/m)."""
        return float(self.record["damping"])

    @damping.setter
    def damping(self, value: float) -> None:
        self._set("damping", "damping", value)

    def to_dict(self) -> dict:
        return {
            **self._anchors_dict(),
            "rest_length": self.rest_length,
            "stiffness": self.stiffness,
            "damping": self.damping,
        }

    def length(self, world=None) -> float:
        """Current distance between the anchors (m)."""
        return self.anchor_distance(world)

    def potential_energy(self, world=None) -> float:
        """k x^2 / 2 with x = |d| - L (J)."""
        x = self.length(world) - self.record["length"]
        return 0.5 * self.stiffness * x * x

    def anchor_error(self, world=None) -> float:
        """0: a spring is a force, not a constraint (its stretch is :meth:`length` - L)."""
        return 0.0
