"""Divergence is reported, never written: a state that stops being finite, or a closed system
whose energy grows by orders of magnitude (:mod:`sandbox.energy_growth`), stops the run with
:class:`sandbox.SimulationError` naming the body, the step and a likely cause; a system that
is not closed, or a closed one that merely drifts, runs on."""

from __future__ import annotations

import math

import numpy as np
import pytest

from sandbox import Body, Box, Circle, ConstantForce, SimulationError, SpringJoint, World
from sandbox.cli import main
from sandbox.energy_growth import GROWTH, energy_limit


def spring_world(stiffness: float, mass: float = 1.0, damping: float = 0.0, **settings) -> World:
    """A disc of ``mass`` kg hung 1 m below a static anchor on a spring of rest length 0.5 m
    (``damping`` N s/m)."""
    w = World(gravity=(0, -9.81), **settings)
    hook = w.add_body(Body("hook", type="static", position=(0, 0)))
    bob = w.add_body(Body("bob", position=(0, -1)))
    bob.add_shape(Circle(0.1, mass=mass))
    w.add_joint(SpringJoint(hook, bob, rest_length=0.5, stiffness=stiffness, damping=damping))
    return w


def finite_state(w: World) -> bool:
    return bool(np.all(np.isfinite(w.com)) and np.all(np.isfinite(w.vel)))


@pytest.mark.parametrize("integrator", ["semi_implicit_euler", "explicit_euler", "rk4"])
def test_a_too_stiff_spring_is_caught_while_the_numbers_are_finite(integrator):
    # k = 1e6 N/m on 1 kg at dt = 1/60: omega dt = 16.7, far beyond every integrator's limit
    # (2 for semi-implicit Euler). The energy passes a million times its scale within a few
    # steps, long before it overflows: the error names the bob, and the spring as the cause.
    w = spring_world(1e6, integrator=integrator)
    with pytest.raises(SimulationError) as info:
        for _ in range(200):
            w.step()
    assert info.value.body == "bob"
    assert info.value.step < 40
    assert "spring stiffness too high for dt" in info.value.cause
    assert finite_state(w)


def test_a_too_damped_spring_is_named_with_its_step_limit():
    # k = 10 N/m and c = 200 N s/m on 1 kg at dt = 1/60: k dt^2 / m + 2 c dt / m = 6.7 > 4,
    # unstable although the stiffness alone would allow dt < 2 sqrt(1 / 10) = 0.63 s. The
    # limit 4 / (c/m + sqrt((c/m)^2 + 4 k/m)) = 0.009998 s is named, with the damping
    w = spring_world(10.0, damping=200.0)
    with pytest.raises(SimulationError) as info:
        for _ in range(200):
            w.step()
    assert info.value.body == "bob"
    assert "spring damping too high for dt" in info.value.cause
    assert "needs dt < 0.01 s; try dt <= 0.0025 s" in info.value.cause
    # c = 100 N s/m: 2 c dt / m = 3.3 and k dt^2 / m = 0.003, a sum under 4: it runs on
    w = spring_world(10.0, damping=100.0)
    for _ in range(600):
        w.step()
    assert finite_state(w)


def test_a_stable_spring_and_a_settling_pile_run_on():
    # the same spring at k = 100 N/m (omega dt = 0.17), and 30 boxes dropped in a heap, 20 s
    w = spring_world(100.0)
    for _ in range(1200):
        w.step()
    pile = World(gravity=(0, -9.81))
    pile.add_body(Body("ground", type="static", position=(0, -0.5))).add_shape(Box(20, 1))
    for i in range(30):
        pile.add_body(Body(f"b{i}", position=(0.3 * (i % 5), 1 + i))).add_shape(Box(1, 1))
    for _ in range(1200):
        pile.step()
    assert finite_state(w) and finite_state(pile)


def test_a_long_fall_is_not_growth():
    # 1 kg falling for 2000 s under explicit Euler: 19.6 km/s and 196,000 kJ of kinetic
    # energy, all of it from the potential energy: a closed system whose energy holds
    w = World(gravity=(0, -9.81), integrator="explicit_euler")
    w.add_body(Body("ball")).add_shape(Circle(0.1, mass=1.0))
    for _ in range(120_000):
        w.step()
    assert w.bodies[0].velocity[1] == pytest.approx(-9.81 * 2000, rel=1e-9)


def test_a_system_driven_from_outside_may_gain_energy():
    # a constant 1000 N on 1 kg for 100 s: 5e9 J gained, far beyond the closed-system bound,
    # and no error: a force from outside does work
    w = World(gravity=(0, 0))
    ball = w.add_body(Body("ball"))
    ball.add_shape(Circle(0.1, mass=1.0))
    w.add_force(ConstantForce((1000.0, 0.0), bodies=[ball]))
    w.step()
    assert w.context[0]["energy_limit"] == math.inf
    for _ in range(5999):
        w.step()
    assert ball.velocity[0] == pytest.approx(1e5, rel=1e-9)


def test_the_bound_is_taken_again_when_the_program_sets_a_state():
    # a body the program throws at 1000 m/s (5e5 J, a million times the 0.5 J scale of the
    # resting body) is a new state, not growth
    w = World(gravity=(0, 0))
    ball = w.add_body(Body("ball"))
    ball.add_shape(Circle(0.1, mass=1.0))
    w.step()
    assert w.context[0]["energy_limit"] == pytest.approx(GROWTH * 0.5)
    ball.velocity = (1000.0, 0.0)
    w.step()
    assert w.context[0]["energy_limit"] == pytest.approx(energy_limit(w), rel=1e-12)
    assert ball.velocity[0] == 1000.0


def test_the_command_line_reports_it_in_one_line_and_writes_nothing(tmp_path, capsys):
    scene = tmp_path / "s.json"
    scene.write_text(
        '{"name": "stiff", "bodies": [{"name": "hook", "type": "static"}, {"name": "bob", '
        '"position": [0, -1], "shapes": [{"type": "circle", "radius": 0.1, "mass": 1}]}], '
        '"joints": [{"type": "spring", "a": "hook", "b": "bob", "rest_length": 0.5, '
        '"stiffness": 1e6}]}'
    )
    out = tmp_path / "t.csv"
    assert main(["simulate", str(scene), "--steps", "200", "--trace", str(out)]) == 1
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error: ") and "'bob'" in err[0], err
    assert not out.exists()
