"""Torque-free rotation of a 3D rigid body with a full inertia tensor (SI units, radians).

State: an orientation (any :mod:`sandbox.rotation3d` representation, body -> world) and the
angular velocity in the body frame ``w`` (rad/s). With no torque, Euler's equations in the
body frame are

    I w' + w x (I w) = 0,   i.e.   alpha = I^-1 (-(w x I w)),

an ODE for ``w`` alone: the orientation follows from the world angular velocity ``R w``. The
slides' tau = I alpha leaves out the gyroscopic term w x (I w); without it a free body could
only spin at constant w, and the tennis-racket flip below could not happen.

Conserved: kinetic energy E = 1/2 w . I w and the world angular momentum L = R I w.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from sandbox.rotation3d import Orientation, cross

INTEGRATORS = ("euler", "rk4")


def euler_rhs(inertia: np.ndarray, inertia_inv: np.ndarray, w: np.ndarray) -> np.ndarray:
    """Body-frame angular acceleration of a free body: I^-1 (-(w x I w)) (rad/s^2)."""
    return inertia_inv @ -cross(w, inertia @ w)  # Euler's equations, tau = 0


def kinetic_energy(inertia: np.ndarray, w: np.ndarray) -> float:
    """E = 1/2 w . I w (J), ``w`` in the body frame."""
    return 0.5 * float(w @ inertia @ w)


def angular_momentum(rotation: np.ndarray, inertia: np.ndarray, w: np.ndarray) -> np.ndarray:
    """World-frame angular momentum L = R I w (kg m^2/s)."""
    return rotation @ (inertia @ w)


def omega_step(
    inertia: np.ndarray, inertia_inv: np.ndarray, w: np.ndarray, dt: float, method: str
) -> np.ndarray:
    """One step of Euler's equations for ``w``: explicit Euler (the slides') or classic RK4."""
    if method == "euler":
        return w + euler_rhs(inertia, inertia_inv, w) * dt  # slides: w + alpha dt
    if method == "rk4":
        k1 = euler_rhs(inertia, inertia_inv, w)
        k2 = euler_rhs(inertia, inertia_inv, w + 0.5 * dt * k1)
        k3 = euler_rhs(inertia, inertia_inv, w + 0.5 * dt * k2)
        k4 = euler_rhs(inertia, inertia_inv, w + dt * k3)
        return w + dt / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
    raise ValueError(f"unknown integrator {method!r}; use one of {INTEGRATORS}")


def integrate_omega(
    inertia: np.ndarray, w0: np.ndarray, dt: float, steps: int, method: str = "rk4"
) -> np.ndarray:
    """Body-frame angular velocity at every step, shape ``(steps + 1, 3)`` (no orientation)."""
    inertia = np.asarray(inertia, dtype=float)
    inv = np.linalg.inv(inertia)
    out = np.empty((steps + 1, 3))
    out[0] = w0
    for i in range(steps):
        out[i + 1] = omega_step(inertia, inv, out[i], dt, method)
    return out


@dataclass
class Trajectory:
    """What :func:`simulate` records at every step (``steps + 1`` rows)."""

    t: np.ndarray  # (n,) s
    omega_body: np.ndarray  # (n, 3) rad/s
    matrix: np.ndarray  # (n, 3, 3) the representation's matrix, as stored (not renormalised)
    drift: np.ndarray  # (n,) the representation's drift measure
    energy: np.ndarray  # (n,) J
    momentum: np.ndarray  # (n, 3) world frame, kg m^2/s

    def energy_error(self) -> np.ndarray:
        """|E(t) - E(0)| / E(0)."""
        return np.abs(self.energy - self.energy[0]) / self.energy[0]

    def momentum_error(self) -> np.ndarray:
        """|L(t) - L(0)| / |L(0)| (direction and length of the world angular momentum)."""
        diff = self.momentum - self.momentum[0]
        return np.sqrt(np.sum(diff * diff, axis=1)) / np.linalg.norm(self.momentum[0])


def simulate(
    inertia: np.ndarray,
    omega_body: np.ndarray,
    orientation: Orientation,
    dt: float,
    steps: int,
    method: str = "euler",
    renormalise_every: int = 0,
) -> Trajectory:
    """Integrate a torque-free body; ``orientation`` (body -> world) is updated in place.

    ``"euler"``: the slides' explicit Euler. The orientation takes the representation's own
    update rule (``integrate``) with the world angular velocity at the start of the step, then
    w <- w + alpha dt.

    ``"rk4"``: w by classic RK4; the orientation by the exact rotation for the step's mean body
    angular velocity, q <- q exp(w_mid dt), written in the world frame as
    exp((R w_mid) dt) q (``integrate_exact``); second order in dt.

    ``renormalise_every``: call ``renormalise()`` every that many steps (0: never).
    """
    inertia = np.asarray(inertia, dtype=float)
    inv = np.linalg.inv(inertia)
    w = np.array(omega_body, dtype=float)
    n = steps + 1
    t = np.arange(n) * dt
    ws, mats = np.empty((n, 3)), np.empty((n, 3, 3))
    drift, energy, mom = np.empty(n), np.empty(n), np.empty((n, 3))

    def record(i: int) -> None:
        m = orientation.matrix()
        ws[i], mats[i], drift[i] = w, m, orientation.drift()
        energy[i] = kinetic_energy(inertia, w)
        mom[i] = angular_momentum(m, inertia, w)

    record(0)
    for i in range(steps):
        if method == "euler":
            w_world = orientation.rotate(w)
            orientation.integrate(w_world, dt)  # slides: orientation with w(t) ...
            w = omega_step(inertia, inv, w, dt, "euler")  # ... then w(t + dt) = w + alpha dt
        elif method == "rk4":
            w_new = omega_step(inertia, inv, w, dt, "rk4")
            w_mid = 0.5 * (w + w_new)
            orientation.integrate_exact(orientation.rotate(w_mid), dt)
            w = w_new
        else:
            raise ValueError(f"unknown integrator {method!r}; use one of {INTEGRATORS}")
        if renormalise_every and (i + 1) % renormalise_every == 0:
            orientation.renormalise()
        record(i + 1)
    return Trajectory(t, ws, mats, drift, energy, mom)


def sign_change_times(t: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Times (s) where the sampled signal ``x(t)`` changes sign, by linear interpolation."""
    t, x = np.asarray(t, dtype=float), np.asarray(x, dtype=float)
    k = np.nonzero(np.signbit(x[1:]) != np.signbit(x[:-1]))[0]
    return t[k] + (t[k + 1] - t[k]) * x[k] / (x[k] - x[k + 1])


def elliptic_k(k: float) -> float:
    """Complete elliptic integral of the first kind K(k) = pi / (2 AGM(1, sqrt(1 - k^2)))."""
    a, b = 1.0, float(np.sqrt(1.0 - k * k))
    for _ in range(60):
        if abs(a - b) <= 1e-16 * a:
            break
        a, b = 0.5 * (a + b), float(np.sqrt(a * b))
    return float(np.pi / (2.0 * a))


def omega_period(moments: np.ndarray, w: np.ndarray) -> float:
    """Closed-form period (s) of the body angular velocity of a free asymmetric body.

    ``moments``: three distinct principal moments (the diagonal of a diagonal tensor); ``w``:
    body angular velocity in the same axes. Euler's equations are solved by Jacobi's elliptic
    functions (sn, cn, dn); the components return after T = 4 K(k) / rate, and the component
    along the middle axis changes sign every T / 2 (the tennis-racket flip).
    """
    i = np.asarray(moments, dtype=float)
    w = np.asarray(w, dtype=float)
    energy2 = float(np.sum(i * w * w))  # 2E
    m2 = float(np.sum((i * w) ** 2))  # |L|^2
    i1, i2, i3 = np.sort(i)
    if m2 < energy2 * i2:  # the axis of w circles the smallest-moment axis: swap the roles
        i1, i3 = i3, i1
    rate = np.sqrt((i3 - i2) * (m2 - energy2 * i1) / (i1 * i2 * i3))
    k2 = (i2 - i1) * (energy2 * i3 - m2) / ((i3 - i2) * (m2 - energy2 * i1))
    return float(4.0 * elliptic_k(float(np.sqrt(k2))) / rate)
