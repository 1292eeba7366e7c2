"""Why a run diverged: a likely cause for :class:`sandbox.SimulationError`, from the world's
contents. Explicit integration of a spring of stiffness k on a mass m is stable only for
dt < 2 sqrt(m / k), the period over pi; between two moving bodies m is the reduced mass. Its
damping c narrows that: semi-implicit Euler's step of m x'' = -k x - c x' has determinant
1 - c dt / m and trace 2 - (k dt^2 + c dt) / m, and stays bounded while
k dt^2 / m + 2 c dt / m < 4, that is for dt < 4 / (c/m + sqrt((c/m)^2 + 4 k/m)) (2 m / c for a
damper alone): a light body on a well-damped spring is the usual culprit."""

from __future__ import annotations

import math

import numpy as np

from sandbox.records import DYNAMIC


def stiffest_spring(world) -> tuple[float, float, float] | None:
    """(stiffness k (N/m), damping c (N s/m), mass m (kg) it moves) of the spring with the
    shortest stable step (:func:`stable_dt`), or None: m is the reduced mass
    m_a m_b / (m_a + m_b) when both ends move, else the moving end's mass."""
    best = None
    for joint in world.joints:
        if getattr(joint, "type", "") != "spring":
            continue
        masses = [world.mass[b.index] for b in (joint.a, joint.b) if b.type == "dynamic"]
        if not masses or (joint.stiffness <= 0 and joint.damping <= 0):
            continue
        m = masses[0] * masses[1] / (masses[0] + masses[1]) if len(masses) == 2 else masses[0]
        spring = (joint.stiffness, joint.damping, m)
        if best is None or stable_dt(*spring) < stable_dt(*best):
            best = spring
    return best


def stable_dt(k: float, c: float, m: float) -> float:
    """The largest stable step (s) of a spring k (N/m) with damping c (N s/m) on m (kg):
    k dt^2 / m + 2 c dt / m = 4 (module docstring)."""
    a, b = c / m, k / m
    return 4.0 / (a + math.sqrt(a * a + 4.0 * b))


def likely_cause(world, i: int) -> str:
    """A one-line cause and what to try, for body ``i`` whose state stopped being finite."""
    dt = world.context[0]["dt"]
    spring = stiffest_spring(world)
    if spring is not None:
        k, c, m = spring
        limit = stable_dt(k, c, m)
        if dt > 0.5 * limit:
            if c * limit < m:  # the stiffness sets the limit (c = 0: 2 sqrt(m / k))
                return (
                    f"spring stiffness too high for dt: a spring of {k:g} N/m moving {m:g} kg "
                    f"needs dt < {limit:.3g} s; try dt <= {0.25 * limit:.3g} s or a softer spring"
                )
            return (
                f"spring damping too high for dt: a spring of {k:g} N/m and {c:g} N s/m moving "
                f"{m:g} kg needs dt < {limit:.3g} s; try dt <= {0.25 * limit:.3g} s or less "
                "damping"
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
