"""Numerical integration of linear and angular motion (slides, "Numerical Integration").

Each integrator turns the state (p, v, phi, omega) and an acceleration function into the
*increments* of one step, for free motion (no contacts or joints):

    dp, dv, dphi, domega

The world applies the increments, letting contact and joint impulses add to the velocity in
between (see ``docs/architecture.md``), so in free flight a body follows its integrator exactly.

``accel(p, v, phi, omega) -> (a, alpha)`` returns linear (n, 2) and angular (n,) accelerations for
all bodies at the given state; integrators that look ahead (Verlet, RK4) call it more than once.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from sandbox.jit import njit

Accel = Callable[[np.ndarray, np.ndarray, np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]]
Increments = tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]

NAMES = ("explicit_euler", "semi_implicit_euler", "verlet", "rk4", "analytic")
ORDER = {"explicit_euler": 1, "semi_implicit_euler": 1, "verlet": 2, "rk4": 4}


def explicit_euler(p, v, phi, w, accel: Accel, dt: float) -> Increments:
    """The slides' first-order step: p' = p + v dt, v' = v + a dt (both from the old state)."""
    a, alpha = accel(p, v, phi, w)
    return v * dt, a * dt, w * dt, alpha * dt


def semi_implicit_euler(p, v, phi, w, accel: Accel, dt: float) -> Increments:
    """Symplectic Euler: v' = v + a dt first, then p' = p + v' dt (what pymunk and Box2D use)."""
    a, alpha = accel(p, v, phi, w)
    dv, dw = a * dt, alpha * dt
    return (v + dv) * dt, dv, (w + dw) * dt, dw


def verlet(p, v, phi, w, accel: Accel, dt: float) -> Increments:
    """Velocity Verlet: p' = p + v dt + a dt^2 / 2, v' = v + (a + a') dt / 2, a' = a(p', v*)."""
    a, alpha = accel(p, v, phi, w)
    dp = v * dt + 0.5 * a * dt * dt
    dphi = w * dt + 0.5 * alpha * dt * dt
    # the velocity at the new position is not known yet: predict it with Euler for a(p', v)
    a1, alpha1 = accel(p + dp, v + a * dt, phi + dphi, w + alpha * dt)
    return dp, 0.5 * (a + a1) * dt, dphi, 0.5 * (alpha + alpha1) * dt


def rk4(p, v, phi, w, accel: Accel, dt: float) -> Increments:
    """Classical fourth-order Runge-Kutta on the first-order system (p, v)' = (v, a(p, v))."""
    a1, b1 = accel(p, v, phi, w)
    p2, v2, f2, w2 = p + 0.5 * dt * v, v + 0.5 * dt * a1, phi + 0.5 * dt * w, w + 0.5 * dt * b1
    a2, b2 = accel(p2, v2, f2, w2)
    p3, v3, f3, w3 = p + 0.5 * dt * v2, v + 0.5 * dt * a2, phi + 0.5 * dt * w2, w + 0.5 * dt * b2
    a3, b3 = accel(p3, v3, f3, w3)
    p4, v4, f4, w4 = p + dt * v3, v + dt * a3, phi + dt * w3, w + dt * b3
    a4, b4 = accel(p4, v4, f4, w4)
    dp = dt / 6.0 * (v + 2.0 * v2 + 2.0 * v3 + v4)
    dv = dt / 6.0 * (a1 + 2.0 * a2 + 2.0 * a3 + a4)
    dphi = dt / 6.0 * (w + 2.0 * w2 + 2.0 * w3 + w4)
    dw = dt / 6.0 * (b1 + 2.0 * b2 + 2.0 * b3 + b4)
    return dp, dv, dphi, dw


INTEGRATORS: dict[str, Callable[..., Increments]] = {
    "explicit_euler": explicit_euler,
    "semi_implicit_euler": semi_implicit_euler,
    "verlet": verlet,
    "rk4": rk4,
}


def integrate(
    name: str,
    p: np.ndarray,
    v: np.ndarray,
    phi: np.ndarray,
    w: np.ndarray,
    accel: Accel,
    dt: float,
    steps: int = 1,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Advance a free state ``steps`` times with integrator ``name``; returns (p, v, phi, omega).

    A small stand-alone driver for lessons and tests (the world has its own loop).
    """
    step = INTEGRATORS[name]
    p, v = np.array(p, dtype=float), np.array(v, dtype=float)
    phi, w = np.array(phi, dtype=float), np.array(w, dtype=float)
    for _ in range(steps):
        dp, dv, dphi, dw = step(p, v, phi, w, accel, dt)
        p, v, phi, w = p + dp, v + dv, phi + dphi, w + dw
    return p, v, phi, w


def constant_acceleration(a: np.ndarray, alpha: np.ndarray | float = 0.0) -> Accel:
    """An ``accel`` function returning the same (a, alpha) everywhere (e.g. gravity)."""
    a = np.asarray(a, dtype=float)

    def accel(p, v, phi, w):
        return np.broadcast_to(a, np.shape(p)), np.broadcast_to(alpha, np.shape(w))

    return accel


# --- the two Euler methods compiled over the world's arrays (the fast path of World.step) -------
# Same formulas as explicit_euler / semi_implicit_euler above, split in two halves so that the
# contact and joint impulses can change the velocity in between.


@njit
def euler_velocities(
    kind: np.ndarray,
    vel: np.ndarray,
    omega: np.ndarray,
    force: np.ndarray,
    torque: np.ndarray,
    inv_mass: np.ndarray,
    inv_moment: np.ndarray,
    gx: float,
    gy: float,
    dt: float,
) -> None:
    """v' = v + a dt, omega' = omega + alpha dt for dynamic bodies (kind 0), a = g + F / m."""
    for i in range(kind.shape[0]):
        if kind[i] != 0:
            continue
        vel[i, 0] += (gx + force[i, 0] * inv_mass[i]) * dt
        vel[i, 1] += (gy + force[i, 1] * inv_mass[i]) * dt
        omega[i] += torque[i] * inv_moment[i] * dt


@njit
def euler_positions(
    kind: np.ndarray,
    com: np.ndarray,
    vel: np.ndarray,
    omega: np.ndarray,
    force: np.ndarray,
    torque: np.ndarray,
    inv_mass: np.ndarray,
    inv_moment: np.ndarray,
    gx: float,
    gy: float,
    dt: float,
    explicit: bool,
    dphi: np.ndarray,
) -> None:
    """p' = p + v dt with the new velocity (semi-implicit) or the old one (explicit: v - a dt).

    Writes each body's turn omega dt into ``dphi`` (for the orientation update) and clears the
    force and torque accumulators. Static bodies (kind 1) do not move.
    """
    for i in range(kind.shape[0]):
        if kind[i] == 1:
            dphi[i] = 0.0
            continue
        vx, vy, w = vel[i, 0], vel[i, 1], omega[i]
        if explicit and kind[i] == 0:  # the slides' p' = p + v dt uses the step's first velocity
            vx -= (gx + force[i, 0] * inv_mass[i]) * dt
            vy -= (gy + force[i, 1] * inv_mass[i]) * dt
            w -= torque[i] * inv_moment[i] * dt
        com[i, 0] += vx * dt
        com[i, 1] += vy * dt
        dphi[i] = w * dt
    force[:] = 0.0
    torque[:] = 0.0
