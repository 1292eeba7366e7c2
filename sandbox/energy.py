"""Energy of a world split into its parts, and the work done on it, for the energy-bars panel.

Per frame (joules, y up, gravity potential measured from y = 0 as ``world.potential_energy()``):

- kinetic, linear: sum over dynamic bodies of m |v|^2 / 2 (v of the centre of mass);
- kinetic, rotational: sum of I omega^2 / 2 (I about the centre of mass);
- potential, gravity: -sum m g . c;
- elastic: sum of ``potential_energy(world)`` of joints and force generators (springs: k x^2 / 2);
- work: the work done since the first frame by what pushes from outside: forces applied by
  controllers, thrust and constant body forces (``world.applied_force``, ``applied_torque``),
  force generators (constant forces, drag, buoyancy) and joint motors.

The energy lost to impacts, friction and spring damping is then E(0) + W - E(t).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

# series names in a Recording, in the panel's order
ENERGY_SERIES = (
    "energy.kinetic_linear",
    "energy.kinetic_rotational",
    "energy.potential_gravity",
    "energy.elastic",
    "energy.work",
)


def energy_terms(world: Any) -> dict[str, float]:
    """The world's energy by part (J): linear and rotational kinetic, gravity, elastic.

    The first two add up to ``world.kinetic_energy()``, the last two to
    ``world.potential_energy()``.
    """
    dyn = np.asarray(world.kind) == 0
    m, v = world.mass[dyn], world.vel[dyn]
    linear = 0.5 * float(np.sum(m * np.sum(v * v, axis=1)))
    rotational = 0.5 * float(np.sum(world.moment[dyn] * world.omega[dyn] ** 2))
    gravity = -float(np.sum(m * (world.com[dyn] @ np.asarray(world.gravity, dtype=float))))
    elastic = 0.0
    for item in (*world.joints, *world.forces):
        if hasattr(item, "potential_energy"):
            elastic += float(item.potential_energy(world))
    return {
        "energy.kinetic_linear": linear,
        "energy.kinetic_rotational": rotational,
        "energy.potential_gravity": gravity,
        "energy.elastic": elastic,
    }


def does_work(world: Any) -> bool:
    """Whether anything but gravity, contacts, joints and springs may do work on ``world``:
    constant forces or torques, controllers, force generators, joint motors."""
    return bool(
        world.forces
        or any(getattr(j, "motor", None) is not None for j in world.joints)
        or any(
            b.controller is not None or np.any(b.constant_force) or b.constant_torque
            for b in world.bodies
        )
    )


def _wrap(angle: np.ndarray) -> np.ndarray:
    """Angles into [-pi, pi) (a turn within one step is less than half a revolution)."""
    return (angle + math.pi) % (2.0 * math.pi) - math.pi


class WorkMeter:
    """Work done on a world since it was attached (J), measured step by step.

    Call :meth:`after` after each ``world.step()`` (the state it leaves is the next step's
    start; change the world between steps and the work of that change is not counted). A force
    F held over the step does the work F . (c' - c) on a centre of mass moving from c to c', a
    torque tau the work tau (theta' - theta); a motor's torque on body b (and its reaction on a)
    the work tau ((theta_b' - theta_a') - (theta_b - theta_a)). Force generators are evaluated
    at the state before the step (exact for constant forces, first order for drag and
    buoyancy); ``world.applied_force`` is read after the step (what the step applied).
    """

    def __init__(self, world: Any) -> None:
        self.world = world
        self.work = 0.0
        self._motors = [j for j in world.joints if getattr(j, "motor", None) is not None]
        self._before()

    def _before(self) -> None:
        """Note the state and the force generators' forces at the start of a step."""
        w = self.world
        angles = np.asarray(w.angles(), dtype=float)
        f = np.zeros_like(w.com)
        tau = np.zeros(len(angles))
        for generator in w.forces:
            generator.accumulate(w, w.com, w.vel, angles, w.omega, f, tau)
        self._start = (w.com.copy(), angles, f, tau)

    def after(self) -> None:
        """Add the work done by the step just taken."""
        w = self.world
        com0, angle0, f, tau = self._start
        angles = np.asarray(w.angles(), dtype=float)
        dc, dphi = w.com - com0, _wrap(angles - angle0)
        dyn = np.asarray(w.kind) == 0
        f = (f + w.applied_force)[dyn]
        tau = (tau + w.applied_torque)[dyn]
        work = float(np.sum(f * dc[dyn]) + np.sum(tau * dphi[dyn]))
        for joint in self._motors:
            i, j = joint.a.index, joint.b.index
            work += float(joint.motor_torque) * float(dphi[j] - dphi[i])
        self.work += work
        self._before()
