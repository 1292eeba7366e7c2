"""The physics lesson 16 (the soft step) claims and ``tests/test_soft_step.py`` does not check:
the softness coefficients are implicit Euler of a mass-spring-damper, a soft constraint holds a
steady load at the static error F / (m omega^2) whatever the substeps, the soft contact is that
spring plus a relax pass (a one-contact model reproduces the engine), and a 1 kg box under a
400 kg box stays under with 8 substeps even without the hold (``hold_ratio`` 0; with it, at the
defaults: ``tests/test_soft_mass_ratio.py``)."""

import math

import numpy as np
import pytest

from sandbox import Body, Box, Circle, PivotJoint, World
from sandbox.solvers.soft import MAX_CONTACT_HERTZ_PER_RATE, softness

G, DT = 9.81, 1.0 / 60.0


def test_softness_impulses_are_implicit_euler_of_a_mass_spring_damper():
    # m x'' + c x' + k x = 0 with k = m w^2, c = 2 m zeta w, integrated by solving the implicit
    # Euler equations directly, against the impulse form -m (s_m v + s_m b x) - s_i lambda_acc
    # with one and with ten passes per substep: equal to rounding (1e-12 m on a 0.1 m swing)
    m, f, zeta, h, x0 = 2.0, 2.0, 0.25, 1.0 / 240.0, 0.1
    w = 2 * math.pi * f
    k, c = m * w**2, 2 * m * zeta * w
    system = np.array([[1.0, -h], [k * h / m, 1.0 + c * h / m]])
    rate, mass_scale, scale = softness(f, zeta, h)
    direct, state = [], np.array([x0, 0.0])
    soft = {1: [], 10: []}
    for passes, out in soft.items():
        x, v = x0, 0.0
        for _ in range(360):
            total = 0.0
            for _ in range(passes):
                lam = -m * (mass_scale * v + mass_scale * rate * x) - scale * total
                total += lam
                v += lam / m
            x += h * v
            out.append(x)
    for _ in range(360):
        state = np.linalg.solve(system, state)
        direct.append(state[0])
    for out in soft.values():
        assert np.allclose(out, direct, rtol=0, atol=1e-12)


def hanging(light: float, heavy: float, **settings) -> World:
    """A static hook, a pivot to a disc of ``light`` kg, a pivot 1 m below it to ``heavy`` kg;
    the position pass off, so that the soft joints alone hold the load."""
    w = World(gravity=(0, -G), dt=DT, solver="soft", position_correction=False, **settings)
    hook = w.add_body(Body("hook", type="static", position=(0, 10)))
    a = w.add_body(Body("light", position=(0, 9)))
    a.add_shape(Circle(0.1, mass=light))
    b = w.add_body(Body("heavy", position=(0, 8)))
    b.add_shape(Circle(0.3, mass=heavy))
    w.add_joint(PivotJoint(hook, a, (0, -1), (0, 0)))
    w.add_joint(PivotJoint(a, b, (0, -1), (0, 0)))
    return w


@pytest.mark.parametrize(
    "light, heavy, settings",
    [(1.0, 400.0, {}), (1.0, 400.0, {"substeps": 8}), (1.0, 1.0, {}), (1.0, 100.0, {})],
)
def test_soft_joint_static_error_is_load_over_effective_mass_omega_squared(light, heavy, settings):
    # at rest: C = F / (m_eff w^2), w = 2 pi joint_hertz; hook joint F = (m1 + m2) g, m_eff = m1;
    # second joint F = m2 g, m_eff = (1/m1 + 1/m2)^-1 (27.68 mm for 400 kg under 1 kg at 60 Hz,
    # whatever the substeps); within 1e-6 relative after 10 s (measured 2e-13 to 4e-11)
    w = hanging(light, heavy, **settings)
    for _ in range(600):
        w.step()
    k = (2 * math.pi * w.settings.joint_hertz) ** 2
    expected = ((light + heavy) * G / (light * k), heavy * G * (1 / light + 1 / heavy) / k)
    for joint, c in zip(w.joints, expected, strict=True):
        assert joint.anchor_error() == pytest.approx(c, rel=1e-6)


def one_contact_model(overlap: float, steps: int, hertz: float, zeta: float, substeps: int):
    """The soft step for a 1 kg disc on a static ground contact, by hand: per substep gravity,
    warm start, biased soft solve (speculative when apart, push at most 3 m/s), move, relax
    (rigid, no bias). Returns the separation (m) after each step."""
    h = DT / substeps
    rate, mass_scale, scale = softness(hertz, zeta, h)
    s, v, total, out = -overlap, 0.0, 0.0, []
    for _ in range(steps):
        for _ in range(substeps):
            v += -G * h + total
            if s > 0.0:
                bias, ms, si = s / h, 1.0, 0.0
            else:
                bias, ms, si = max(mass_scale * rate * s, -3.0), mass_scale, scale
            new = max(total - (ms * v + bias) - si * total, 0.0)
            v, total = v + new - total, new
            s += h * v
            new = max(total - (v + (s / h if s > 0.0 else 0.0)), 0.0)
            v, total = v + new - total, new
        out.append(s)
    return np.array(out)


def test_soft_contact_is_the_one_contact_model_and_rests_at_its_static_error():
    # a 1 kg disc starting 2 cm deep in the ground, position pass off: the engine's separation
    # equals the hand model's to 1e-12 m over 60 steps, and it comes to rest at -g / w^2 with
    # w = 2 pi (2 contact_hertz), contact_hertz capped at an eighth of the substep rate (a
    # static body: twice as stiff), 1e-9 m
    w = World(gravity=(0, -G), dt=DT, solver="soft", position_correction=False)
    w.settings.sag_recovery_time = 0.0  # Box2D's spring, which keeps its sag (the model's)
    w.add_body(Body("ground", type="static", position=(0, -0.5))).add_shape(Box(20, 1))
    disc = w.add_body(Body("disc", position=(0, 0.5 - 0.02)))
    disc.add_shape(Circle(0.5, mass=1.0))
    engine = []
    for _ in range(60):
        w.step()
        engine.append(disc.position[1] - 0.5)
    s = w.settings
    hertz = 2 * min(s.contact_hertz, MAX_CONTACT_HERTZ_PER_RATE * s.substeps / DT)  # the cap
    model = one_contact_model(0.02, 60, hertz, s.contact_damping_ratio, s.substeps)
    assert np.allclose(engine, model, rtol=0, atol=1e-12)
    assert engine[-1] == pytest.approx(-G / (2 * math.pi * hertz) ** 2, abs=1e-9)


def test_light_box_stays_under_a_400_kg_box_with_8_substeps_without_the_hold():
    # 1 kg box of 1 m on the ground, a 400 kg box of 1 m on it, 10 s, solver soft with 8
    # substeps, hold_ratio 0 and the sag kept (the lesson's row: Box2D's soft step): the light
    # box never leaves from under the heavy one (offset < 0.5 m) and neither sinks more than
    # 2.5 cm (measured 2.0 cm and 2.2 cm)
    w = World(gravity=(0, -G), dt=DT, solver="soft", substeps=8, hold_ratio=0.0)
    w.settings.sag_recovery_time = 0.0
    w.add_body(Body("ground", type="static", position=(0, -0.5))).add_shape(
        Box(40, 1, friction=0.6)
    )
    light = w.add_body(Body("light", position=(0, 0.5)))
    light.add_shape(Box(1, 1, friction=0.6, mass=1.0))
    heavy = w.add_body(Body("heavy", position=(0, 1.5)))
    heavy.add_shape(Box(1, 1, friction=0.6, mass=400.0))
    for _ in range(600):
        w.step()
        assert abs(light.position[0] - heavy.position[0]) < 0.5
        assert 0.5 - light.position[1] < 0.025
        assert 1.0 + light.position[1] - heavy.position[1] < 0.025
