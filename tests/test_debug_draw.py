"""Debug-drawing layers: what is recorded (and only that), where arrows point, that each layer
draws on a frame exactly when it has something to show, and the command line's --draw."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from sandbox import Body, Box, Circle, World, load_scene
from sandbox.arrows import arrows, nice_value
from sandbox.cli import main
from sandbox.controllers import Thruster
from sandbox.joints import PinJoint, PivotJoint, SpringJoint
from sandbox.overlays import LAYERS, LayerError, Layers, parse_layers
from sandbox.recording import CircleOutline, Recording, record
from sandbox.render import FrameRenderer, render_frames

ROOT = Path(__file__).resolve().parent.parent
DROP = ROOT / "scenes" / "drop.json"
SIZE = 200  # px: small images keep the file fast


def test_layer_names_parse_and_an_unknown_one_is_named():
    assert parse_layers("contacts, impulses,contacts") == ("contacts", "impulses")
    assert parse_layers(None) == ()
    assert parse_layers("all") == tuple(LAYERS)
    with pytest.raises(LayerError, match="unknown layer 'foo'"):
        parse_layers(["contacts", "foo"])


def test_only_the_data_of_the_layers_asked_for_is_recorded():
    rec = record(load_scene(DROP), 10, draw="contacts,normals")
    o = rec.overlays
    assert o.recorded == ("contacts",)
    assert len(o.contacts) == len(rec) == 11
    assert o.velocities == [] and o.forces == [] and o.sleeping == []
    assert record(load_scene(DROP), 3).overlays.recorded == ()


def test_resting_contact_impulse_is_the_weight_times_dt_and_points_into_the_ball():
    """A ball at rest on the ground: the contact pushes it up by m g dt per step (N s)."""
    world = load_scene(DROP)
    rec = record(world, 400, every=400, draw="impulses")
    rows = rec.overlays.contacts[-1]
    ball = world.body("ball")
    assert abs(ball.velocity[1]) < 1e-6  # at rest
    # the normal is drawn into the ball (the ground is static), whichever is body a
    np.testing.assert_allclose(rows[:, 2:4], [[0.0, 1.0]] * len(rows), atol=1e-12)
    # sum of normal impulses = m g dt: the solver has converged to 1e-6 N s at rest
    assert rows[:, 4].sum() == pytest.approx(ball.mass * 9.81 / 60, abs=1e-6)
    assert np.all(np.abs(rows[:, 5]) < 1e-9)  # no friction on level ground at rest


def test_applied_force_and_torque_are_recorded_per_frame():
    world = World(gravity=(0.0, 0.0))
    box = world.add_body(Body("box", force=(3.0, -2.0), torque=0.5))
    box.add_shape(Box(1.0, 1.0))
    rec = record(world, 2, draw="forces")
    np.testing.assert_array_equal(rec.overlays.forces[0], [[0.0, 0.0, 0.0]])  # before a step
    np.testing.assert_array_equal(rec.overlays.forces[2], [[3.0, -2.0, 0.5]])


def test_arrow_geometry_tip_and_cut():
    geometry = arrows([[1.0, 2.0]], [[3.0, 4.0]], head_length=0.5, head_width=0.2)
    np.testing.assert_allclose(geometry.heads[0, 0], [4.0, 6.0])  # the tip is tail + vector
    assert len(geometry.heads) == 1
    cut = arrows([[0.0, 0.0], [0.0, 0.0]], [[10.0, 0.0], [0.0, 0.0]], 0.5, 0.2, max_length=2.0)
    assert len(cut.shafts) == 1  # the zero vector is left out
    np.testing.assert_allclose(cut.heads[:, 0], [[2.0, 0.0], [1.5, 0.0]])  # two heads
    assert [nice_value(x) for x in (0.7, 3.0, 49.0, 1.0)] == [0.5, 2.0, 20.0, 1.0]


def busy_world() -> World:
    """Contacts (a box on the ground), joints (pin, pivot with a motor, spring), an applied
    force and torque (a thruster), so every layer has something to draw."""
    world = World(dt=1 / 60)
    ground = world.add_body(Body("ground", type="static"))
    ground.add_shape(Box(12.0, 1.0, offset=(0.0, -0.5)))
    crate = world.add_body(Body("crate", position=(-3.0, 0.5), torque=1.0))
    crate.add_shape(Box(1.0, 1.0))
    thruster = Thruster((-0.5, 0.0), direction=(1.0, 0.0), max_thrust=20.0)  # slides it
    crate.controller = lambda body, w: thruster.fire(body, 8.0)
    beam = world.add_body(Body("beam", type="static", position=(2.0, 5.0)))
    beam.add_shape(Box(3.0, 0.2))
    bob = world.add_body(Body("bob", position=(3.0, 3.0), velocity=(2.0, 0.0)))
    bob.add_shape(Circle(0.3))
    wheel = world.add_body(Body("wheel", position=(0.5, 4.0)))
    wheel.add_shape(Circle(0.4))
    weight = world.add_body(Body("weight", position=(-1.0, 3.0)))
    weight.add_shape(Box(0.5, 0.5))
    world.add_joint(PinJoint(beam, bob, (1.0, 0.0), (0.0, 0.0)))
    world.add_joint(PivotJoint(beam, wheel, (-1.5, -1.0), motor={"rate": 3.0, "max_torque": 5.0}))
    world.add_joint(SpringJoint(beam, weight, (-1.5, 0.0), (0.0, 0.25), stiffness=40.0))
    return world


def scene_pixels(renderer: FrameRenderer, k: int) -> np.ndarray:
    """Frame k without the key strip (the scene and its legend)."""
    rgb = renderer.frame(k)
    return rgb[: rgb.shape[0] - renderer.key_px]


@pytest.fixture(scope="module")
def busy_recording() -> Recording:
    return record(busy_world(), 12, every=4, draw="all", energy=True)


def test_every_layer_draws_on_a_scene_with_contacts_joints_and_forces(busy_recording):
    view = (-4.5, 4.5, -1.5, 6.5)
    with FrameRenderer(busy_recording, size_px=SIZE, view=view) as plain:
        base = scene_pixels(plain, -1)
    drawn = {}
    for name in LAYERS:
        with FrameRenderer(busy_recording, size_px=SIZE, view=view, draw=name) as r:
            assert r.key_px > 0  # a key strip below the scene
            drawn[name] = np.abs(scene_pixels(r, -1).astype(int) - base).max(axis=2) > 0
    for name in set(LAYERS) - {"sleep"}:
        assert drawn[name].sum() > 10, name  # pixels changed where the layer draws
    assert drawn["sleep"].sum() == 0  # the world has no sleep flags: nothing to grey
    # all layers and the energy bars together render too
    with FrameRenderer(busy_recording, size_px=SIZE, draw="all", panel="energy-bars") as r:
        assert r.frame(-1).shape[1] == 2 * SIZE


def test_torque_and_force_arrows_need_their_data():
    rec = record(busy_world(), 2, draw="contacts")
    with pytest.raises(LayerError, match="'forces' was not recorded"):
        FrameRenderer(rec, size_px=SIZE, draw="forces")


def test_sleep_layer_greys_a_body_flagged_asleep():
    rec = Recording(["a", "b"], ["dynamic", "dynamic"], [[CircleOutline(np.zeros(2), 1.0)]] * 2)
    rec.overlays.layers = ("sleep",)
    rec.add_frame([[-2.0, 0.0, 0.0], [2.0, 0.0, 0.0]], 0.0, overlay={"sleeping": [True, False]})
    view = (-4.0, 4.0, -4.0, 4.0)
    with FrameRenderer(rec, size_px=100, view=view, draw="sleep", show_time=False) as r:
        rgb = r.frame(0)
    # pixel of each body's centre (the orientation marker runs to the right of it)
    asleep, awake = rgb[50, 25 - 5], rgb[50, 75 - 5]
    np.testing.assert_array_equal(asleep, [199, 199, 199])  # SLEEP_FACE 0.78 of 255
    assert awake[2] > awake[0] + 40  # still the run's blue fill


def gif_frames(path: Path) -> list[np.ndarray]:
    with Image.open(path) as im:
        out = []
        for k in range(im.n_frames):
            im.seek(k)
            out.append(np.asarray(im.convert("RGB")))
    return out


def test_cli_draw_contacts_changes_exactly_the_frames_with_contacts(tmp_path):
    """--draw contacts: frames with contact points differ from the plain GIF; the others are
    the same pixels (above the key strip)."""
    steps = 120  # dt = 1/60 at the default 30 frames/s: every 2nd step is a GIF frame
    plain, drawn = tmp_path / "plain.gif", tmp_path / "drawn.gif"
    assert main(["simulate", str(DROP), "--steps", str(steps), "--gif", str(plain)]) == 0
    args = ["simulate", str(DROP), "--steps", str(steps), "--gif", str(drawn)]
    assert main([*args, "--draw", "contacts"]) == 0
    a, b = gif_frames(plain), gif_frames(drawn)
    assert len(a) == len(b) == steps // 2 + 1
    assert b[0].shape[0] > a[0].shape[0]  # the key strip
    contacts = record(load_scene(DROP), steps, every=2, draw="contacts").overlays.contacts
    has = [len(c) > 0 for c in contacts]
    assert 0 < sum(has) < len(has)  # both kinds of frame are tested
    for k, (fa, fb) in enumerate(zip(a, b, strict=True)):
        same = np.array_equal(fa, fb[: fa.shape[0]])
        assert same != has[k], f"frame {k}: contacts {has[k]}, same pixels {same}"


def test_cli_png_draws_too_and_every_named_layer_is_accepted(tmp_path):
    out = tmp_path / "d.png"
    args = ["simulate", str(DROP), "--steps", "90", "--png", str(out)]
    assert main([*args, "--draw", "contacts,normals,impulses,forces,velocities,aabbs"]) == 0
    with Image.open(out) as im:
        assert im.size[0] == 480 and im.size[1] > 480


@pytest.mark.parametrize(
    "extra, message",
    [
        (["--draw", "contacts,foo"], "error: --draw: unknown layer 'foo' (known: contacts,"),
        (["--draw", ""], "error: --draw: expected a comma-separated list of layers"),
        (["--panel", "foo"], "error: --panel: unknown panel 'foo' (known: energy-bars)"),
        (["--engine", "pymunk", "--draw", "impulses"], "error: --draw: layer 'impulses' is not"),
    ],
)
def test_cli_bad_layer_or_panel_exits_2_with_one_line_and_writes_nothing(
    tmp_path, capsys, extra, message
):
    gif = tmp_path / "out.gif"
    assert main(["simulate", str(DROP), "--steps", "5", "--gif", str(gif), *extra]) == 2
    err = capsys.readouterr().err
    assert err.startswith(message) and err.count("\n") == 1
    assert list(tmp_path.iterdir()) == []


def test_cli_draw_without_an_image_exits_2(capsys):
    assert main(["simulate", str(DROP), "--steps", "5", "--draw", "contacts"]) == 2
    assert "--draw: draws on an image" in capsys.readouterr().err


def test_pymunk_trace_draws_the_layers_it_holds(tmp_path):
    out = tmp_path / "p.png"
    args = ["simulate", str(DROP), "--steps", "30", "--engine", "pymunk", "--png", str(out)]
    assert main([*args, "--draw", "velocities,aabbs,com,joints,gravity"]) == 0
    assert out.stat().st_size > 0


def test_render_frames_takes_layers_as_an_option():
    rec = record(load_scene(DROP), 4, draw="velocities")
    plain = next(render_frames(rec, frames=[4], size_px=SIZE))
    drawn = next(render_frames(rec, frames=[4], size_px=SIZE, draw="velocities"))
    assert drawn.shape[0] > plain.shape[0]


def test_arrow_length_is_the_value_times_the_scale():
    """A 3 m/s velocity at 1 m per m/s ends 3 m right of the centre of mass (20 px per m here,
    the tip found to a pixel: its last, partly covered pixel is not white)."""
    rec = Recording(["ball"], ["dynamic"], [[CircleOutline(np.zeros(2), 0.2)]])
    rec.overlays.layers = ("velocities",)
    rec.add_frame([[0.0, 0.05, 0.0]], 0.0, overlay={"velocities": [[3.0, 0.0]]})
    view = (-5.0, 5.0, -5.0, 5.0)
    for scale, tip in ((1.0, 3.0), (0.5, 1.5)):
        layers = Layers("velocities", velocity=scale)
        with FrameRenderer(rec, size_px=200, view=view, draw=layers, show_time=False) as r:
            rows = r.frame(0)[92:108]  # round y = 0: the line snaps to a row
        drawn = np.flatnonzero((rows < 250).any(axis=(0, 2)))
        assert drawn.max() == pytest.approx(100 + 20 * tip, abs=1.0)  # the tip, in pixels
