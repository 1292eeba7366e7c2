"""Every integrator and every force generator in one compiled call (``sandbox.step.fast_step``,
``free_step``, ``soft_step``) against the same stages called one by one from Python
(``staged_step``), and the integrator's work arrays the world keeps from step to step."""

import numpy as np
import pytest
from step_paths import fast_and_staged, same_state

from sandbox import Body, Box, Circle, World
from sandbox.forces import Buoyancy, ConstantForce, Drag
from sandbox.integrators import INCREMENTS, INTEGRATORS, constant_acceleration
from sandbox.joints.spring import SpringJoint

LOOK_AHEAD = ("verlet", "rk4")


def fields_pile(integrator: str, solver: str = "iterative") -> World:
    """Boxes and discs falling on a floor into water, two pairs tied by springs, with drag and
    a thruster: every state-dependent force, and contacts."""
    w = World(gravity=(0, -9.81), integrator=integrator, solver=solver)
    w.add_body(Body("floor", type="static", position=(0, -0.5))).add_shape(Box(12, 1))
    for i in range(10):
        x, y = -2.5 + 0.55 * i, 0.8 + 0.7 * (i % 3)
        b = w.add_body(Body(f"b{i}", position=(x, y), angle=0.3 * np.sin(i), angular_velocity=i))
        b.add_shape(Box(0.5, 0.4) if i % 2 else Circle(0.25))
    body = w.body
    w.add_joint(SpringJoint(body("b0"), body("b1"), (0.1, 0), rest_length=0.7, stiffness=60.0))
    w.add_joint(SpringJoint(body("b4"), body("b7"), rest_length=1.0, stiffness=20.0, damping=0.4))
    w.add_force(Drag(linear=0.1, quadratic=0.02, angular=0.01))
    w.add_force(Buoyancy(surface_y=0.6, fluid_density=0.8, linear_drag=0.5, bodies=["b2", "b3"]))
    w.add_force(ConstantForce(force=(2.0, 1.0), point=(0.1, 0.1), bodies=["b5"]))
    return w


@pytest.mark.parametrize("solver", ["iterative", "soft"])
@pytest.mark.parametrize("integrator", ["explicit_euler", "semi_implicit_euler", *LOOK_AHEAD])
def test_one_call_step_with_forces_equals_the_staged_step(integrator, solver):
    # the one-call step and the staged step run the same functions in the same order:
    # bit-identical bodies and impulses (exact equality), with springs, drag, buoyancy, a
    # thruster and contacts
    fast, staged = fast_and_staged(lambda: fields_pile(integrator, solver), 120)
    assert fast._fast and staged.timer.steps == 120
    assert same_state(fast, staged)
    assert np.array_equal(fast.manifolds.normal_impulse, staged.manifolds.normal_impulse)
    assert fast.stats["contacts"] > 3  # the pile has landed: contacts took part


@pytest.mark.parametrize("integrator", LOOK_AHEAD)
def test_one_body_step_with_forces_equals_the_staged_step(integrator):
    # a single body takes free_step (nothing to collide): the same numbers as the stages
    def thrown():
        w = World(gravity=(0, -9.81), integrator=integrator)
        w.add_body(Body("b", velocity=(3.0, 4.0), angular_velocity=2.0)).add_shape(Box(0.4, 0.2))
        w.add_force(Drag(linear=0.3, quadratic=0.1, angular=0.05))
        w.add_force(ConstantForce(force=(0.0, 4.0), point=(0.2, 0.0)))
        return w

    fast, staged = fast_and_staged(thrown, 200)
    assert fast._fast and len(fast.geometry()) == 1
    assert same_state(fast, staged)


@pytest.mark.parametrize("integrator", LOOK_AHEAD)
def test_look_ahead_without_forces_is_exact_for_constant_acceleration(integrator):
    # without a state-dependent force the look-ahead derivatives reuse a = g + F / m; Verlet
    # and RK4 are then exact for a body thrown under gravity and a constant push: closed form
    # p = p0 + v0 t + a t^2 / 2 to rounding (1e-12 m over 2 s), angle phi0 + w0 t + alpha t^2 / 2
    w = World(gravity=(0, -9.81), dt=1 / 60, integrator=integrator)
    b = w.add_body(
        Body("b", velocity=(2.0, 5.0), angular_velocity=1.5, force=(1.0, 0.5), torque=0.2)
    )
    b.add_shape(Circle(0.3))
    for _ in range(120):
        w.step()
    t = w.time
    a = np.array([1.0, 0.5]) / b.mass + np.array([0.0, -9.81])
    alpha = 0.2 / b.moment
    np.testing.assert_allclose(b.position, np.array([2.0, 5.0]) * t + 0.5 * a * t * t, atol=1e-12)
    np.testing.assert_allclose(b.velocity, np.array([2.0, 5.0]) + a * t, atol=1e-12)
    assert b.angle == pytest.approx(1.5 * t + 0.5 * alpha * t * t, abs=1e-12)


@pytest.mark.parametrize("integrator", ["explicit_euler", "semi_implicit_euler", *LOOK_AHEAD])
def test_without_fields_every_method_is_the_slides_function_to_the_bit(integrator):
    # no force depends on the state: each method is worked out body by body
    # (integrators.integrate_constant) with the very operations of the slides' function above it
    # (integrators.explicit_euler ... rk4) given a constant acceleration: equal to the bit
    w = World(gravity=(0, -9.81), dt=1 / 60, integrator=integrator)
    w.add_body(Body("b", velocity=(2.0, 5.0), force=(1.0, 0.5))).add_shape(Circle(0.3))
    a = np.array([0.0, -9.81]) + np.array([1.0, 0.5]) * w.inv_mass[0]
    p, v = w.com[0].copy(), w.vel[0].copy()
    step = INTEGRATORS[integrator]
    for _ in range(60):
        w.step()
        dp, dv, _, _ = step(p, v, 0.0, 0.0, constant_acceleration(a), w.dt)
        p, v = p + dp, v + dv
    assert w._work is None
    assert w.com[0].tobytes() == p.tobytes() and w.vel[0].tobytes() == v.tobytes()


def test_work_arrays_are_kept_between_steps():
    # the integrators write into arrays the world keeps where a force depends on the state (no
    # allocation per step); they grow with the bodies; without such forces no method needs them
    # (and the compiled step leaves the passes over them out)
    w = fields_pile("rk4")
    w.step()
    work = w._work
    assert work.shape == (INCREMENTS + 1, len(w.bodies))
    for _ in range(5):
        w.step()
    assert w._work is work
    w.add_body(Body("late", position=(4.0, 3.0))).add_shape(Circle(0.2))
    w.step()
    assert w._work.shape == (INCREMENTS + 1, len(w.bodies))
    plain = World(integrator="rk4")
    plain.add_body(Body("b")).add_shape(Circle(0.2))
    plain.step()
    assert plain._work is None
    plain.add_force(Drag(linear=0.1))
    plain.step()
    assert plain._work is not None
