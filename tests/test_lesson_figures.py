"""Numbers lessons 01 and 02 claim that other tests do not cover: the world's explicit Euler
table, Euler's landing one step late, convergence orders with quadratic drag, the three world
orientation layouts under angular acceleration, and how drift builds up in the array kernels."""

import math
from fractions import Fraction

import numpy as np
import pytest

from sandbox import Body, Box, Circle, World, integrators, orientation, projectile

U, A = np.array([3.0, 4.0]), np.array([0.0, -1.0])


def test_world_explicit_euler_reproduces_the_slides_table_with_velocities():
    # slides, "Numerical Model Example": p and v of every row, exact to the last bit
    w = World(gravity=A, dt=1.0, integrator="explicit_euler")
    ball = w.add_body(Body("ball", velocity=U))
    ball.add_shape(Circle(0.5))
    for n in range(10):
        assert ball.position == (3.0 * n, 4.0 * n - n * (n - 1) / 2)
        assert ball.velocity == (3.0, 4.0 - n)
        w.step()


@pytest.mark.parametrize("dt", [1.0, 0.5, 0.25, 0.1])
def test_explicit_euler_is_the_parabola_of_u_minus_a_dt_over_2_and_lands_one_step_late(dt):
    # p_n = s + u n dt + a dt^2 n (n - 1) / 2 = s + (u - a dt / 2) t + a t^2 / 2 (1e-12)
    n = np.arange(0, 200)
    t = n * dt
    euler = projectile.euler_position([0, 0], U, A, dt, n)
    shifted = projectile.position([0, 0], U - 0.5 * A * dt, A, t)
    np.testing.assert_allclose(euler, shifted, atol=1e-12)
    # back at y = 0 after 2 (u_y + g dt / 2) / g = T + dt: x = u_x (T + dt) (slides: 27, not 24)
    t_land = 2.0 * (U[1] - 0.5 * A[1] * dt) / -A[1]
    n_land = round(t_land / dt)
    assert euler[n_land, 1] == pytest.approx(0.0, abs=1e-9)
    assert euler[n_land, 0] == pytest.approx(U[0] * (8.0 + dt), rel=1e-12)


def drag(c=0.1):
    def accel(p, v, phi, w):
        speed = np.sqrt(np.sum(v * v, axis=-1, keepdims=True))
        return A - c * speed * v, np.zeros_like(w)

    return accel


@pytest.mark.parametrize("name", ["explicit_euler", "semi_implicit_euler", "verlet", "rk4"])
def test_order_of_convergence_with_quadratic_drag(name):
    # a velocity-dependent force: velocity Verlet must still be 2nd order, RK4 4th.
    # Reference: RK4 at dt = 1e-3 (its own error ~1e-14). Fitted slope within 0.2 of the order.
    T, accel = 3.0, drag()
    ref, _, _, _ = integrators.integrate("rk4", [0, 0], U, 0.0, 0.0, accel, 1e-3, 3000)
    dts = np.array([0.1, 0.05, 0.025, 0.0125])
    errors = []
    for dt in dts:
        p, _, _, _ = integrators.integrate(name, [0, 0], U, 0.0, 0.0, accel, dt, round(T / dt))
        errors.append(np.linalg.norm(p - ref))
    order = np.polyfit(np.log(dts), np.log(errors), 1)[0]
    assert abs(order - integrators.ORDER[name]) < 0.2, (name, order)


def test_world_orientation_layouts_agree_under_angular_acceleration():
    # constant omega, then a constant torque tau = I alpha: the three layouts end at the same
    # angle (lesson 02's tolerance, 1e-9 rad) and at the hand-computed explicit Euler angle
    dt, steps, switch, omega0, alpha = 1.0 / 60.0, 1500, 500, 1.3, 0.5
    angles = []
    for kind in ("angle", "matrix", "complex"):
        w = World(gravity=(0, 0), dt=dt, integrator="explicit_euler", orientation=kind)
        b = w.add_body(Body("box", angle=0.2, angular_velocity=omega0))
        b.add_shape(Box(1.6, 0.8))
        for k in range(steps):
            if k == switch:
                b.constant_torque = b.moment * alpha
            w.step()
        angles.append(b.angle)
    # phi_n = phi_0 + sum_k omega_k dt, omega_k = omega0 + alpha dt max(0, k - switch)
    m = steps - switch
    exact = 0.2 + omega0 * dt * steps + alpha * dt * dt * m * (m - 1) / 2
    for a in angles:
        assert abs(orientation.wrap_angle(a - exact)) < 1e-9
        assert abs(orientation.wrap_angle(a - angles[0])) < 1e-9


@pytest.mark.parametrize("name", ["matrix", "complex"])
def test_kernel_drift_builds_up_under_a_constant_increment_and_renormalising_removes_it(name):
    # the same rounded e^{i d} every step, of length 1 + eps (eps computed exactly from the
    # rounded cos and sin): after n steps |z| = 1 + n eps, and a matrix scaled by 1 + n eps has
    # ||Phi^T Phi - I||_F = 2 sqrt(2) n eps. Within 2% (the products' own rounding); with
    # renormalisation every step the drift stays at rounding level (< 1e-15)
    kind, d, n = orientation.NAMES[name], 1.3 / 60.0, 3000
    c, s = math.cos(d), math.sin(d)
    eps = float(Fraction(c) ** 2 + Fraction(s) ** 2 - 1) / 2
    assert eps > 1e-17  # this increment's rounded cos and sin are not exactly unit length
    expected = n * eps * (2 * math.sqrt(2) if name == "matrix" else 1.0)
    drift = {}
    for renormalise in (False, True):
        rot = np.zeros((1, 4))
        orientation.set_angles(kind, rot, np.array([0.2]))
        for _ in range(n):
            orientation.integrate_rotations(kind, rot, np.array([d]), renormalise)
        drift[renormalise] = orientation.drift_of(kind, rot)[0]
    assert drift[False] == pytest.approx(expected, rel=0.02)
    assert drift[True] < 1e-15
