"""The analytic projectile model (slides, "Analytical Model Example").

    p(t) = s + u t + a t^2 / 2        v(t) = u + a t
    theta(t) = theta0 + omega0 t + alpha t^2 / 2

State as a function of time: no error accumulates, but nothing can interact.
"""

from __future__ import annotations

import numpy as np


def position(s, u, a, t: float | np.ndarray) -> np.ndarray:
    """p(t) = s + u t + a t^2 / 2 (m); ``t`` may be an array of times, giving one row each."""
    s, u, a = (np.asarray(x, dtype=float) for x in (s, u, a))
    t = np.asarray(t, dtype=float)[..., None]
    return s + u * t + 0.5 * a * t * t


def velocity(u, a, t: float | np.ndarray) -> np.ndarray:
    """v(t) = u + a t (m/s)."""
    u, a = np.asarray(u, dtype=float), np.asarray(a, dtype=float)
    t = np.asarray(t, dtype=float)[..., None]
    return u + a * t


def angle(theta0: float, omega0: float, t, alpha: float = 0.0):
    """theta(t) = theta0 + omega0 t + alpha t^2 / 2 (rad, not wrapped)."""
    return theta0 + omega0 * np.asarray(t, dtype=float) + 0.5 * alpha * np.asarray(t) ** 2


def euler_position(s, u, a, dt: float, n: int | np.ndarray) -> np.ndarray:
    """Where the slides' explicit Euler puts the projectile after n steps (closed form).

    p_n = s + u n dt + a dt^2 n (n - 1) / 2: each step adds the velocity of the step before, so
    the numeric path lags the analytic one by a dt^2 n / 2, growing linearly with time.
    """
    s, u, a = (np.asarray(x, dtype=float) for x in (s, u, a))
    n = np.asarray(n, dtype=float)[..., None]
    return s + u * n * dt + a * dt * dt * n * (n - 1.0) / 2.0


def semi_implicit_position(s, u, a, dt: float, n: int | np.ndarray) -> np.ndarray:
    """Semi-implicit Euler after n steps: p_n = s + u n dt + a dt^2 n (n + 1) / 2."""
    s, u, a = (np.asarray(x, dtype=float) for x in (s, u, a))
    n = np.asarray(n, dtype=float)[..., None]
    return s + u * n * dt + a * dt * dt * n * (n + 1.0) / 2.0


def flight_time(u_y: float, g: float) -> float:
    """Time to come back to the launch height: T = 2 u_y / g (s)."""
    return 2.0 * u_y / g


def apex(u, g: float) -> tuple[float, float]:
    """Highest point (x, y) of a launch from the origin: t = u_y / g, y = u_y^2 / (2 g)."""
    ux, uy = float(u[0]), float(u[1])
    t = uy / g
    return ux * t, uy * uy / (2.0 * g)


def advance_analytic(world, dt: float) -> None:
    """A world under ``integrator: analytic``: every body on its closed-form path from where it
    was when the path started, p(t) = s + u t + a t^2 / 2, theta(t) = theta0 + omega0 t +
    alpha t^2 / 2, a = g + F / m (slides). Bodies do not collide; joints and forces are refused."""
    from sandbox.orientation import NAMES, place_bodies
    from sandbox.records import DYNAMIC, STATIC

    w = world
    if w.joints or w.forces:
        raise ValueError("settings.integrator: analytic motion cannot have joints or forces")
    if w._analytic_ref is None:
        dyn = (w.kind == DYNAMIC)[:, None]
        force = w.force + w.const_force
        a = np.where(dyn, w.gravity + force * w.inv_mass[:, None], 0.0)
        alpha = (w.torque + w.const_torque) * w.inv_moment
        w._analytic_ref = (w.time, w.com.copy(), w.vel.copy(), a, w.angles(), w.omega.copy(), alpha)
    t0, s0, u, a, th0, w0, alpha = w._analytic_ref
    t = w.time + dt - t0
    moving = w.kind != STATIC
    w.com[moving] = (s0 + u * t + 0.5 * a * t * t)[moving]
    w.vel[moving] = (u + a * t)[moving]
    w.omega[moving] = (w0 + alpha * t)[moving]
    w.state["angle"] = np.where(moving, th0 + w0 * t + 0.5 * alpha * t * t, th0)
    place_bodies(w.state, w.rot, NAMES[w.settings.orientation])
    w.force[:] = 0.0
    w.torque[:] = 0.0
    w.context[0]["contact_count"][:] = 0
