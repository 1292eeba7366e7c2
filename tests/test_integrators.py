"""Integrators against closed forms: the slides' tables and each method's order of convergence."""

import math

import numpy as np
import pytest

from sandbox import integrators, projectile

G = np.array([0.0, -1.0])


def spring_accel(k=4.0):
    """Harmonic oscillator a = -k x (omega = 2 rad/s), angular part alpha = -k phi."""
    return lambda p, v, phi, w: (-k * p, -k * phi)


def test_explicit_euler_reproduces_the_slides_numeric_table():
    accel = integrators.constant_acceleration(G)
    p, v = np.zeros(2), np.array([3.0, 4.0])
    expected = [(3, 4), (6, 7), (9, 9), (12, 10), (15, 10), (18, 9), (21, 7), (24, 4), (27, 0)]
    for row in expected:  # slides, "Numerical Model Example": exact to the last bit
        p, v, _, _ = integrators.integrate("explicit_euler", p, v, 0.0, 0.0, accel, 1.0)
        assert tuple(p) == row


def test_analytic_table_matches_the_slides():
    t = np.arange(9.0)
    p = projectile.position([0, 0], [3, 4], [0, -1], t)
    assert p[:, 1].tolist() == [0.0, 3.5, 6.0, 7.5, 8.0, 7.5, 6.0, 3.5, 0.0]
    assert p[:, 0].tolist() == (3 * t).tolist()


@pytest.mark.parametrize("name", ["explicit_euler", "semi_implicit_euler"])
def test_euler_closed_forms(name):
    # p_n = s + u n dt + a dt^2 n (n -+ 1) / 2, exact for constant acceleration (1e-12)
    accel = integrators.constant_acceleration(G)
    s, u, dt, n = np.array([1.0, 2.0]), np.array([3.0, 4.0]), 0.1, 37
    p, _, _, _ = integrators.integrate(name, s, u, 0.0, 0.0, accel, dt, steps=n)
    closed = (
        projectile.euler_position if name == "explicit_euler" else projectile.semi_implicit_position
    )
    np.testing.assert_allclose(p, closed(s, u, G, dt, n), rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("name", ["verlet", "rk4"])
def test_higher_order_methods_are_exact_for_constant_acceleration(name):
    accel = integrators.constant_acceleration(G)
    p, v, _, _ = integrators.integrate(name, [0, 0], [3, 4], 0.0, 0.0, accel, 0.5, steps=16)
    np.testing.assert_allclose(p, projectile.position([0, 0], [3, 4], G, 8.0), atol=1e-12)
    np.testing.assert_allclose(v, projectile.velocity([3, 4], G, 8.0), atol=1e-12)


@pytest.mark.parametrize("name", ["explicit_euler", "semi_implicit_euler", "verlet", "rk4"])
def test_order_of_convergence_on_the_harmonic_oscillator(name):
    # x(t) = cos(2 t): fitted slope of log(error) against log(dt) within 0.25 of the order
    accel = spring_accel()
    T = 2.0
    dts = np.array([0.02, 0.01, 0.005, 0.0025])
    errors = []
    for dt in dts:
        steps = round(T / dt)
        p, _, phi, _ = integrators.integrate(
            name, [1.0, 0.0], [0.0, 0.0], 1.0, 0.0, accel, dt, steps
        )
        errors.append(abs(p[0] - math.cos(2 * T)))
        assert phi == pytest.approx(p[0], abs=1e-12)  # angular state integrates alike
    order = np.polyfit(np.log(dts), np.log(errors), 1)[0]
    assert abs(order - integrators.ORDER[name]) < 0.25, (name, order)


def test_symplectic_euler_keeps_oscillator_energy_bounded_explicit_does_not():
    accel = spring_accel()
    energy = {}
    for name in ("explicit_euler", "semi_implicit_euler"):
        p, v, _, _ = integrators.integrate(name, [1.0, 0.0], [0, 0], 0.0, 0.0, accel, 0.01, 5000)
        energy[name] = 0.5 * v[0] ** 2 + 2.0 * p[0] ** 2  # initial energy 2.0
    assert energy["explicit_euler"] > 2.0 * 1.5  # grows: (1 + k dt^2)^n
    assert abs(energy["semi_implicit_euler"] - 2.0) < 0.05  # bounded oscillation (2.5%)
