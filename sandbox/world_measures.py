"""What a world measures about itself: energies, momenta, orientation drift, who sleeps.

A mixin of :class:`~sandbox.world.World` over its per-body arrays. Dynamic bodies count whether
awake or asleep (a sleeping body still has its mass, and its height for the potential energy);
static and kinematic bodies do not.
"""

from __future__ import annotations

import numpy as np

import sandbox.orientation as orientation
from sandbox.records import DYNAMIC, SLEEPING


class Measures:
    """Energies (J), momenta, orientation drift and the sleep flags of a world's bodies."""

    @property
    def sleeping(self) -> np.ndarray:
        """(n,) bool: which bodies sleep (``settings.sleep``; see :mod:`sandbox.sleep`)."""
        return self.kind == SLEEPING

    def _dynamic(self) -> np.ndarray:
        """(n,) bool: the bodies forces move, awake or asleep."""
        return (self.kind == DYNAMIC) | (self.kind == SLEEPING)

    def kinetic_energy(self) -> float:
        """Sum of m |v|^2 / 2 + I omega^2 / 2 over dynamic bodies (J)."""
        dyn = self._dynamic()
        v2 = np.sum(self.vel[dyn] ** 2, axis=1)
        return float(
            np.sum(0.5 * self.mass[dyn] * v2 + 0.5 * self.moment[dyn] * self.omega[dyn] ** 2)
        )

    def potential_energy(self) -> float:
        """Gravitational -m g . c over dynamic bodies, plus springs' k x^2 / 2 (J)."""
        dyn = self._dynamic()
        pe = -float(np.sum(self.mass[dyn] * (self.com[dyn] @ self.gravity)))
        for item in (*self.joints, *self.forces):
            if hasattr(item, "potential_energy"):
                pe += item.potential_energy(self)
        return pe

    def energy(self) -> float:
        """Kinetic + potential (J)."""
        return self.kinetic_energy() + self.potential_energy()

    def momentum(self) -> np.ndarray:
        """Linear momentum sum m v of dynamic bodies (kg m/s)."""
        dyn = self._dynamic()
        return np.sum(self.mass[dyn, None] * self.vel[dyn], axis=0)

    def angular_momentum(self, about=(0.0, 0.0)) -> float:
        """L = sum (r x m v + I omega) about a world point (default the origin) (kg m^2/s)."""
        dyn = self._dynamic()
        r = self.com[dyn] - np.asarray(about, dtype=float)
        v = self.vel[dyn]
        m = self.mass[dyn]
        return float(
            np.sum(m * (r[:, 0] * v[:, 1] - r[:, 1] * v[:, 0]) + self.moment[dyn] * self.omega[dyn])
        )

    def orientation_drift(self) -> np.ndarray:
        """Per-body drift of the stored orientations (0 for scalar angles)."""
        return orientation.drift_of(self.orientation_kind, self.rot)
