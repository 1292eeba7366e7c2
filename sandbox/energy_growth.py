"""Energy that grows by orders of magnitude in a closed system: a diverging run caught while
its numbers are still finite, so that it is reported (:class:`sandbox.SimulationError`) and
never written.

In a closed system (gravity, contacts, joints, springs and drag; nothing doing work from
outside: no motor, thruster, constant force, buoyancy, controller, force added by the program
or moving kinematic body) the energy E = KE + PE_gravity + PE_springs never grows, except by
what the position passes add when they push overlapping bodies apart, which is of the order
of the energies in play. So when a step begins from a state the program set, the world notes
E_0 and a scale S of those energies (:func:`energy_limit`), and a step that ends with

    KE + PE_gravity > E_0 + GROWTH * S

has diverged (:func:`closed_energy`, checked in :func:`sandbox.step.store_impulses`). The
springs' elastic energy is >= 0: leaving it out of the check can hide growth, never invent it.
A stable explicit integrator drifts too (explicit Euler gains energy every step), but it takes
thousands of steps to gain six orders of magnitude, and by then the run means nothing.
"""

from __future__ import annotations

import math

import numpy as np

from sandbox.jit import njit
from sandbox.records import BUOYANCY, CONSTANT, DYNAMIC, KINEMATIC, SLEEPING

GROWTH = 1e6  # how many times the energies in play a closed system may gain before it diverged
SPEED_FLOOR = 1.0  # m/s: the scale counts every body as moving at least this fast


@njit
def closed_energy(bodies, gx: float, gy: float) -> float:
    """KE + PE_gravity of the dynamic bodies, awake or asleep (J): sum of m |v|^2 / 2 +
    I omega^2 / 2 - m g . c (as :meth:`sandbox.world.World.energy`, without the springs)."""
    e = 0.0
    for i in range(bodies.shape[0]):
        b = bodies[i]
        if b["kind"] != DYNAMIC and b["kind"] != SLEEPING:
            continue
        v2 = b["vel"][0] ** 2 + b["vel"][1] ** 2
        e += 0.5 * b["mass"] * v2 + 0.5 * b["moment"] * b["omega"] ** 2
        e -= b["mass"] * (gx * b["com"][0] + gy * b["com"][1])
    return e


@njit
def fastest_body(bodies) -> int:
    """The index of the fastest body that forces move (the one a diverged run names)."""
    fastest, top = 0, -1.0
    for i in range(bodies.shape[0]):
        v2 = bodies[i]["vel"][0] ** 2 + bodies[i]["vel"][1] ** 2
        if bodies[i]["inv_mass"] > 0.0 and v2 > top:
            fastest, top = i, v2
    return fastest


def is_closed(world) -> bool:
    """Whether nothing in ``world`` does work on it from outside (see the module)."""
    state = world.state
    if world._controlled or world._python_forces:
        return False
    if np.any(np.isin(world.generator_table["kind"], (BUOYANCY, CONSTANT))):
        return False
    if np.any(world.joint_table["has_motor"]):
        return False
    if np.any(state["const_force"]) or np.any(state["const_torque"]):
        return False
    if np.any(world.force) or np.any(world.torque):
        return False  # the program pushes this step
    moving = state["kind"] == KINEMATIC
    return not (np.any(state["vel"][moving]) or np.any(state["omega"][moving]))


def energy_limit(world) -> float:
    """E_0 + GROWTH * S for the state ``world`` is in (J), or infinity when it is not a closed
    system. S = KE + PE_springs + m |g| L + m SPEED_FLOOR^2 / 2, with m the dynamic bodies'
    total mass and L the size of the region their centres span (at least 1 m)."""
    if not len(world.state) or not is_closed(world):
        return math.inf
    dyn = world._dynamic()
    mass = float(np.sum(world.mass[dyn]))
    if mass == 0.0:
        return math.inf
    kinetic, total = world.kinetic_energy(), world.energy()
    elastic = total - kinetic + float(np.sum(world.mass[dyn] * (world.com[dyn] @ world.gravity)))
    span = world.com[dyn].max(axis=0) - world.com[dyn].min(axis=0)
    size = max(1.0, float(np.hypot(*span)))
    g = float(np.hypot(*world.gravity))
    scale = kinetic + max(elastic, 0.0) + mass * g * size + 0.5 * mass * SPEED_FLOOR**2
    limit = total + GROWTH * scale
    return limit if math.isfinite(limit) else math.inf
