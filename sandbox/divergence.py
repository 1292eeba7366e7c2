"""Why a run diverged: a likely cause for :class:`sandbox.SimulationError`, from the world's
contents (explicit integration of a spring of stiffness k on a mass m is stable only for
dt < 2 sqrt(m / k), the period over pi; between two moving bodies m is the reduced mass)."""

from __future__ import annotations

import math

import numpy as np

from sandbox.records import DYNAMIC


def stiffest_spring(world) -> tuple[float, float] | None:
    """(stiffness k, mass m it moves) of the spring with the largest k / m, or None: the
    reduced mass m_a m_b / (m_a + m_b) when both ends move, else the moving end's mass."""
    best = None
    for joint in world.joints:
        if getattr(joint, "type", "") != "spring":
            continue
        masses = [world.mass[b.index] for b in (joint.a, joint.b) if b.type == "dynamic"]
        if not masses or joint.stiffness <= 0:
            continue
        m = masses[0] * masses[1] / (masses[0] + masses[1]) if len(masses) == 2 else masses[0]
        if best is None or joint.stiffness / m > best[0] / best[1]:
            best = (joint.stiffness, m)
    return best


def likely_cause(world, i: int) -> str:
    """A one-line cause and what to try, for body ``i`` whose state stopped being finite."""
    dt = world.context[0]["dt"]
    spring = stiffest_spring(world)
    if spring is not None:
        k, m = spring
        limit = 2.0 * math.sqrt(m / k)
        if dt > 0.5 * limit:
            return (
                f"spring stiffness too high for dt: a spring of {k:g} N/m moving {m:g} kg needs "
                f"dt < {limit:.3g} s; try dt <= {0.25 * limit:.3g} s or a softer spring"
            )
    g = float(np.hypot(*world.gravity))
    if g * dt * dt > 1e6:
        return f"gravity {g:g} m/s^2 moves bodies by {g * dt * dt:g} m per step; try a smaller dt"
    dyn = world.kind == DYNAMIC
    if dyn.any():
        masses = world.mass[dyn]
        if masses.max() / max(masses.min(), 1e-300) > 1e12:
            return "masses differ by more than 1e12; try closer masses"
    return "the state stopped being finite; try a smaller dt or smaller forces"
