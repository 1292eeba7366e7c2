"""The energy-bars panel: its numbers are the world's energies, conserved in free fall as the
integrator conserves them, and the lost bar grows at a bounce by m g h (1 - e^2)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from sandbox import Body, Box, Circle, World, load_scene
from sandbox.cli import main
from sandbox.energy_bars import LOST, TOTAL, WORK, bar_values
from sandbox.joints import PivotJoint
from sandbox.recording import record
from sandbox.render import FrameRenderer, render_gif
from sandbox.replay import recording_from_rows
from sandbox.trace import run_world

ROOT = Path(__file__).resolve().parent.parent
DROP = ROOT / "scenes" / "drop.json"
G, DT = 9.81, 1.0 / 60.0


def test_bars_are_the_worlds_kinetic_and_potential_energy():
    world = load_scene(ROOT / "scenes" / "spring.json")  # gravity and a spring's k x^2 / 2
    series = {"ke": lambda w: w.kinetic_energy(), "pe": lambda w: w.potential_energy()}
    rec = record(world, 90, every=3, series=series, energy=True)
    bars = bar_values(rec)
    ke, pe = np.array(rec.series["ke"]), np.array(rec.series["pe"])
    # same sums in another order: equal to rounding (1e-12 relative)
    np.testing.assert_allclose(bars[:, 0] + bars[:, 1], ke, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(bars[:, 2] + bars[:, 3], pe, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(bars[:, TOTAL], ke + pe, rtol=1e-12)
    assert bars[:, 3].max() > 1.0  # the spring stores energy (J)
    assert np.all(bars[:, WORK] == 0.0)  # nothing but gravity and the spring


def test_rotational_energy_is_its_own_bar():
    world = World(gravity=(0.0, 0.0))
    wheel = world.add_body(Body("wheel", velocity=(1.0, 0.0), angular_velocity=3.0))
    wheel.add_shape(Circle(0.5))
    bars = bar_values(record(world, 1, energy=True))
    assert bars[0, 0] == pytest.approx(0.5 * wheel.mass * 1.0, rel=1e-12)
    assert bars[0, 1] == pytest.approx(0.5 * wheel.moment * 9.0, rel=1e-12)


def drop_bars(steps: int = 140) -> tuple[np.ndarray, float, list[int]]:
    """Bars of every step of the drop scene, the ball's mass, and the steps with contacts."""
    world = load_scene(DROP)
    rec = record(world, steps, draw="contacts", energy=True)
    touching = [k for k, c in enumerate(rec.overlays.contacts) if len(c)]
    return bar_values(rec), world.body("ball").mass, touching


def test_free_fall_keeps_potential_plus_kinetic_as_semi_implicit_euler_does():
    """In free fall semi-implicit Euler loses exactly m g^2 dt^2 / 2 per step (v' = v - g dt,
    y' = y + v' dt), so the lost bar after n steps is n m g^2 dt^2 / 2 (to rounding, 1e-9
    relative), under 1.2 % of the total before the ball lands."""
    bars, m, touching = drop_bars()
    first = touching[0]
    n = np.arange(first)
    np.testing.assert_allclose(bars[:first, LOST], n * 0.5 * m * G**2 * DT**2, rtol=1e-9, atol=1e-9)
    assert bars[first - 1, LOST] < 0.012 * bars[0, TOTAL]
    np.testing.assert_allclose(bars[:first, TOTAL], bars[0, TOTAL] - bars[:first, LOST], rtol=1e-12)


def test_lost_bar_grows_at_the_bounce_by_m_g_h_one_minus_e_squared():
    """Ball of radius 0.5 m dropped from y = 10 m onto the ground (y = 0), e = 0.5 x 1.0: the
    bounce takes m g h (1 - e^2) with h = 9.5 m. The discrete step differs by about one step of
    gravity's work at the impact speed v: tolerance m g v dt (0.9 J of 55 J)."""
    bars, m, touching = drop_bars()
    first = touching[0]
    h, e = 10.0 - 0.5, 0.5
    theory = m * G * h * (1.0 - e**2)
    v = np.sqrt(2.0 * G * h)
    after = bars[first + 1, LOST]  # the step after the bounce, the ball in the air again
    assert abs(after - theory) < m * G * v * DT
    assert bars[first - 1, LOST] < 0.02 * theory  # nothing was lost before


def test_work_of_a_constant_force_is_measured_and_not_counted_as_lost():
    """A 2 N push on a free 1 kg box (no gravity): W = F x. With semi-implicit Euler the box
    moves with the new velocity, so F x outruns the kinetic energy by F^2 dt^2 / (2 m) per step:
    lost = n F^2 dt^2 / (2 m) exactly (rounding: 1e-9 relative)."""
    world = World(gravity=(0.0, 0.0), dt=DT)
    box = world.add_body(Body("box", force=(2.0, 0.0), mass=1.0, moment=1.0))
    box.add_shape(Box(1.0, 1.0))
    bars = bar_values(record(world, 60, energy=True))
    x = box.position[0]
    assert bars[-1, WORK] == pytest.approx(2.0 * x, rel=1e-12)
    n = np.arange(61)
    np.testing.assert_allclose(bars[:, LOST], n * 4.0 * DT**2 / 2.0, rtol=1e-9, atol=1e-12)


def test_a_motors_work_is_counted():
    """A motor spins a wheel up from rest to 2 rad/s with at most 10 N m: its work is the
    wheel's kinetic energy plus semi-implicit Euler's (tau dt)^2 / (2 I) per step of the spin-up
    (as for the constant force above): full steps of 10 N m until I omega is reached, then
    one partial step. Lost = sum (tau dt)^2 / (2 I), to 1e-9 J."""
    world = World(gravity=(0.0, 0.0), dt=DT)
    axle = world.add_body(Body("axle", type="static"))
    wheel = world.add_body(Body("wheel"))
    wheel.add_shape(Circle(1.0))
    world.add_joint(PivotJoint(axle, wheel, motor={"rate": 2.0, "max_torque": 10.0}))
    bars = bar_values(record(world, 60, energy=True))
    assert bars[-1, 1] == pytest.approx(0.5 * wheel.moment * 4.0, rel=1e-9)
    assert bars[-1, WORK] > bars[-1, 1]
    momentum, full = wheel.moment * 2.0, 10.0 * DT  # angular impulse needed, one full step's
    steps = int(momentum // full)
    lost = (steps * full**2 + (momentum - steps * full) ** 2) / (2.0 * wheel.moment)
    assert bars[-1, LOST] == pytest.approx(lost, abs=1e-9)


def test_a_trace_gives_the_same_energies_as_the_running_world():
    """Energies from trace rows (the pymunk path) put the world back in each state: they match
    the recorder's to rounding (1e-9 J)."""
    world = load_scene(ROOT / "scenes" / "newtons_cradle.json")
    rows = list(run_world(world, 40))
    live = bar_values(
        record(load_scene(ROOT / "scenes" / "newtons_cradle.json"), 40, 4, energy=True)
    )
    traced = bar_values(
        recording_from_rows(
            load_scene(ROOT / "scenes" / "newtons_cradle.json"), rows, 4, energy=True
        )
    )
    np.testing.assert_allclose(traced[:, :5], live[:, :5], atol=1e-9)


def test_panel_is_drawn_beside_the_scene_and_needs_energies(tmp_path):
    world = load_scene(DROP)
    rec = record(world, 20, every=5, energy=True)
    path = render_gif(rec, tmp_path / "e.gif", size_px=240, panel="energy-bars")
    with Image.open(path) as im:
        assert im.size == (480, 240) and im.n_frames == 5
    with FrameRenderer(rec, size_px=240, panel="energy-bars") as r:
        r.frame(0)
        labels = [t.get_text() for t in r.bars.labels]
        assert labels[-1] == f"{bar_values(rec)[0, LOST]:.4g} J"
        r.frame(4)
        assert [t.get_text() for t in r.bars.labels][TOTAL] == f"{bar_values(rec)[4, TOTAL]:.4g} J"
        total_bar = r.bars.polys[0].get_paths()[TOTAL].vertices  # rows: no work bar here
        assert total_bar[:, 0].max() == pytest.approx(bar_values(rec)[4, TOTAL], rel=1e-12)
        ax = r.bars.ax
        assert ax.get_xlabel() == "energy (J)" and ax.get_title() == "Energy"
    with pytest.raises(ValueError, match="record it with record"):
        render_gif(record(load_scene(DROP), 2), tmp_path / "x.gif", panel="energy-bars")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["e.gif"]


def test_cli_panel_energy_bars(tmp_path):
    gif, png = tmp_path / "e.gif", tmp_path / "e.png"
    args = ["simulate", str(DROP), "--steps", "30", "--gif", gif, "--png", png]
    assert main([str(a) for a in [*args, "--panel", "energy-bars"]]) == 0
    with Image.open(gif) as im:
        assert im.size == (960, 480)
    args = ["simulate", str(DROP), "--steps", "30", "--engine", "pymunk", "--png", png]
    assert main([str(a) for a in [*args, "--panel", "energy-bars"]]) == 0
