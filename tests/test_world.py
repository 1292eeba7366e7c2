"""The world without collisions: forces, torque, body types, conservation, settings."""

import math

import numpy as np
import pytest

from sandbox import Body, Box, Circle, World


def one_body(shape=None, **kw):
    w = World(
        **{k: kw.pop(k) for k in list(kw) if k in ("gravity", "dt", "orientation", "integrator")}
    )
    b = w.add_body(Body("b", **kw))
    b.add_shape(shape or Box(2.0, 1.0))
    return w, b


def test_off_centre_force_spins_the_body_up_at_tau_over_i():
    # slides, "Torque": tau = r x f, alpha = tau / I; a = F / m
    w, b = one_body(gravity=(0, 0))
    for _ in range(60):
        b.apply_force((0.0, 3.0), point=np.add(b.center_of_mass, (1.0, 0.0)))
        w.step()
    tau, inertia, mass = 3.0 * 1.0, 2.0 * (4 + 1) / 12, 2.0
    assert b.angular_velocity == pytest.approx(tau / inertia * 1.0, rel=1e-12)
    assert b.velocity[1] == pytest.approx(3.0 / mass * 1.0, rel=1e-12)


def test_accumulators_are_cleared_each_step():
    w, b = one_body(gravity=(0, 0))
    b.apply_force((1.0, 0.0))
    w.step()
    v = b.velocity[0]
    w.step()
    assert b.velocity[0] == v


def test_static_and_kinematic_bodies():
    w = World()
    s = w.add_body(Body("s", type="static", position=(1, 2)))
    s.add_shape(Circle(1))
    k = w.add_body(Body("k", type="kinematic", velocity=(1, 0), angular_velocity=0.5))
    k.add_shape(Box(1, 1))
    for _ in range(60):
        w.step()
    assert s.position == (1.0, 2.0)
    assert k.position[0] == pytest.approx(1.0, abs=1e-12)  # ignores gravity
    assert k.position[1] == 0.0
    assert k.angle == pytest.approx(0.5, abs=1e-12)
    assert math.isinf(s.mass)


def test_origin_and_centre_of_mass_differ_for_offset_shapes():
    w = World(gravity=(0, 0))
    b = w.add_body(Body("b", position=(1.0, 0.0), angular_velocity=1.0))
    b.add_shape(Circle(0.5, offset=(1.0, 0.0)))
    assert b.center_of_mass == pytest.approx((2.0, 0.0))
    for _ in range(90):
        w.step()
    # the centre of mass stays put; the origin circles it at radius 1
    assert b.center_of_mass == pytest.approx((2.0, 0.0), abs=1e-12)
    x, y = b.position
    assert math.hypot(x - 2.0, y) == pytest.approx(1.0, abs=1e-12)
    assert b.angle == pytest.approx(1.5, abs=1e-12)


@pytest.mark.parametrize("orientation", ["angle", "matrix", "complex"])
def test_switching_orientation_changes_nothing_else(orientation):
    w, b = one_body(orientation=orientation, velocity=(1, 2), angular_velocity=3.0)
    for _ in range(200):
        w.step()
    ref, rb = one_body(orientation="angle", velocity=(1, 2), angular_velocity=3.0)
    for _ in range(200):
        ref.step()
    assert b.position == pytest.approx(rb.position, abs=1e-12)
    assert math.cos(b.angle - rb.angle) == pytest.approx(1.0, abs=1e-12)


def test_energy_and_momentum_in_free_flight():
    # semi-implicit Euler in uniform gravity: momentum changes by m g dt per step exactly;
    # the body falls g dt^2 n / 2 further than exact, so energy drops by exactly m g^2 dt t / 2
    w, b = one_body(velocity=(3, 4), angular_velocity=2.0)
    e0 = w.energy()
    for _ in range(600):
        w.step()
    m = b.mass
    np.testing.assert_allclose(w.momentum(), m * np.array([3.0, 4.0 - 9.81 * 10.0]), rtol=1e-10)
    assert e0 - w.energy() == pytest.approx(m * 9.81**2 * w.dt * 10.0 / 2, rel=1e-9)
    assert w.kinetic_energy() == pytest.approx(
        0.5 * m * (9 + (4 - 98.1) ** 2) + 0.5 * b.moment * 4.0, rel=1e-9
    )


def test_angular_momentum_about_origin_is_conserved_without_gravity():
    w, b = one_body(gravity=(0, 0), position=(1, 2), velocity=(3, -1), angular_velocity=2.0)
    l0 = w.angular_momentum()
    for _ in range(100):
        w.step()
    assert w.angular_momentum() == pytest.approx(l0, rel=1e-12)
    assert l0 == pytest.approx(b.mass * (1 * -1 - 2 * 3) + b.moment * 2.0)


def test_analytic_mode_is_closed_form():
    w, b = one_body(gravity=(0, -1), dt=1.0, integrator="analytic", velocity=(3, 4))
    for _ in range(8):
        w.step()
    assert b.position == (24.0, 0.0)


def test_bad_settings_and_dt_are_refused():
    with pytest.raises(ValueError, match="settings.solver"):
        World(solver="magic")
    with pytest.raises(ValueError, match="dt"):
        World(dt=0)
    w = World()
    w.add_body(Body("empty"))
    with pytest.raises(ValueError, match="needs shapes"):
        w.step()
