"""Recordings and headless rendering: files are whole images, shapes land on the right pixels,
joints and water are drawn where the bodies and the surface are."""

from __future__ import annotations

import math

import numpy as np
import pytest
from matplotlib.colors import to_rgb
from PIL import Image

from sandbox import Body as WorldBody
from sandbox import Box, Circle, World, render
from sandbox.forces import Buoyancy
from sandbox.geometry import box_vertices
from sandbox.joints import PinJoint, PivotJoint, SpringJoint
from sandbox.recording import CircleOutline, JointOutline, Recording, record, zigzag
from sandbox.render import FILL_ALPHA, STATIC_FACE, render_gif, render_png

VIEW = (-5.0, 5.0, -5.0, 5.0)  # 10 m square: at 100 px, 10 px per metre, no margin
Y = 1.05  # the middle of pixel row 39, so a horizontal 1 px line covers one row


def fill_rgb(color: object, alpha: float = FILL_ALPHA) -> np.ndarray:
    """A fill colour composited over the white background, 0..255."""
    return 255.0 * (alpha * np.array(to_rgb(color)) + (1.0 - alpha))


def pixel(x: float, y: float, size_px: int = 100) -> tuple[int, int]:
    """(row, column) of world point (x, y) in a ``size_px`` image of VIEW."""
    scale = size_px / (VIEW[1] - VIEW[0])
    return int((VIEW[3] - y) * scale), int((x - VIEW[0]) * scale)


def moving_ball(frames: int = 5, x0: float = 0.0) -> Recording:
    """A ball of radius 1 m moving +1 m per frame along y = Y, and a static ground box."""
    rec = Recording(
        names=["ground", "ball"],
        types=["static", "dynamic"],
        outlines=[[box_vertices(8.0, 1.0)], [CircleOutline(np.zeros(2), 1.0)]],
    )
    for k in range(frames):
        rec.add_frame([[0.0, -4.0, 0.0], [x0 + k, Y, 0.0]], k / 30, height=float(k))
    return rec


class Shape:
    def __init__(self, kind: str, **fields: object) -> None:
        self.kind = kind
        for key, value in fields.items():
            setattr(self, key, np.asarray(value, dtype=float) if key != "radius" else value)


class Body:
    def __init__(self, name: str, type: str, position, angle: float, shapes: list) -> None:
        self.name, self.type, self.angle, self.shapes = name, type, angle, shapes
        self.position = tuple(position)


class FakeWorld:
    """Bodies on known paths: the ball moves at 1 m/s in x, dt = 0.5 s."""

    def __init__(self) -> None:
        self.time = 0.0
        self.bodies = [
            Body(
                "ground",
                "static",
                (0.0, -4.0),
                0.0,
                [Shape("polygon", vertices=box_vertices(8, 1))],
            ),
            Body("ball", "dynamic", (-2.0, Y), 0.0, [Shape("circle", radius=1.0, offset=(0, 0))]),
        ]

    def step(self) -> None:
        self.time += 0.5
        ball = self.bodies[1]
        ball.position = (ball.position[0] + 0.5, ball.position[1])


def test_record_captures_initial_state_then_every_nth_step():
    world = FakeWorld()
    rec = record(world, steps=5, every=2, series={"x": lambda w: w.bodies[1].position[0]})
    # steps 0, 2, 4 captured: hand-computed times 0, 1, 2 s and x = -2 + 0.5 * step
    assert rec.times == [0.0, 1.0, 2.0]
    assert rec.series["x"] == [-2.0, -1.0, 0.0]
    assert rec.poses().shape == (3, 2, 3)
    np.testing.assert_array_equal(rec.frames[2][1], [0.0, Y, 0.0])
    assert rec.names == ["ground", "ball"] and rec.types == ["static", "dynamic"]
    assert isinstance(rec.outlines[1][0], CircleOutline) and rec.outlines[1][0].radius == 1.0


def test_series_missing_from_a_frame_is_nan():
    rec = moving_ball(frames=2)
    rec.add_frame([[0, -4, 0], [2, 1, 0]], 0.1)  # no "height", and a late new series
    rec.add_frame([[0, -4, 0], [3, 1, 0]], 0.2, late=1.0)
    assert rec.series["height"][:2] == [0.0, 1.0] and np.isnan(rec.series["height"][2:]).all()
    assert np.isnan(rec.series["late"][:3]).all() and rec.series["late"][3] == 1.0


def test_png_circle_lands_on_expected_pixel(tmp_path):
    path = render_png(moving_ball(), tmp_path / "ball.png", frame=2, size_px=100, view=VIEW)
    with Image.open(path) as im:
        assert im.format == "PNG" and im.size == (100, 100)
        rgb = np.asarray(im.convert("RGB"), dtype=float)
    # frame 2: ball centre at (2, Y); half a radius to its left (the marker points right)
    inside = rgb[pixel(1.5, Y)]
    np.testing.assert_allclose(inside, fill_rgb("C0"), atol=3)  # 3 of 255: rounding only
    np.testing.assert_array_equal(rgb[pixel(0.5, Y)], [255, 255, 255])  # 1.5 m off: empty
    # orientation marker runs from the centre to the rim at angle 0: dark, not fill
    row, col = pixel(2.5, Y)
    darkest = rgb[row - 1 : row + 2, col].sum(axis=1).min()  # Agg snaps lines to +-1 px
    assert darkest < inside.sum() - 150  # a 1 px line in the full colour, hand-measured ~260
    # static ground (centre (0, -4)) is grey
    np.testing.assert_allclose(
        rgb[pixel(-2.0, -4.0)], fill_rgb(STATIC_FACE[:3], STATIC_FACE[3]), atol=3
    )


def test_png_of_a_world_draws_its_current_state(tmp_path):
    world = FakeWorld()
    render_png(world, tmp_path / "w.png", size_px=100, view=VIEW)
    with Image.open(tmp_path / "w.png") as im:
        rgb = np.asarray(im.convert("RGB"), dtype=float)
    np.testing.assert_allclose(rgb[pixel(-2.5, Y)], fill_rgb("C0"), atol=3)  # ball at (-2, Y)


def test_gif_frame_count_size_duration_and_motion(tmp_path):
    rec = moving_ball(frames=6, x0=-3.0)
    path = render_gif(rec, tmp_path / "ball.gif", fps=25, size_px=100, view=VIEW)
    with Image.open(path) as im:
        assert im.format == "GIF" and im.size == (100, 100) and im.n_frames == 6
        assert im.info["duration"] == 40  # 1000 / 25 ms
        assert im.info["loop"] == 0
        im.seek(4)  # ball centre at (1, Y)
        rgb = np.asarray(im.convert("RGB"), dtype=float)
    # one shared palette, no dithering: the fill stays within a few levels of the true colour
    np.testing.assert_allclose(rgb[pixel(0.5, Y)], fill_rgb("C0"), atol=8)
    np.testing.assert_array_equal(rgb[pixel(-2.5, Y)], [255, 255, 255])  # where frame 0 was


def test_trail_marks_the_path_already_travelled(tmp_path):
    rec = moving_ball(frames=6, x0=-3.0)
    path = render_png(rec, tmp_path / "t.png", frame=4, size_px=100, view=VIEW, trail=True)
    with Image.open(path) as im:
        rgb = np.asarray(im.convert("RGB"), dtype=float)
    # the ball's origin went from (-3, Y) to (1, Y): (-2.5, Y) is now 1.5 m behind the ball
    row, col = pixel(-2.5, Y)
    assert rgb[row - 1 : row + 2, col].sum(axis=1).min() < 3 * 255 - 60  # a line is there
    np.testing.assert_array_equal(rgb[pixel(-2.5, Y - 1.5)], [255, 255, 255])  # off the path


def test_gif_with_panel_is_wider_and_stride_skips_frames(tmp_path):
    rec = moving_ball(frames=7)
    path = render_gif(rec, tmp_path / "p.gif", size_px=120, panel="height", stride=2)
    with Image.open(path) as im:
        assert im.size == (240, 120) and im.n_frames == 4  # frames 0, 2, 4, 6
    with pytest.raises(KeyError):
        render_gif(rec, tmp_path / "q.gif", size_px=64, panel="energy")
    assert not (tmp_path / "q.gif").exists()


def test_runs_are_overlaid_in_distinct_colours(tmp_path):
    a, b = moving_ball(frames=3, x0=-3.0), moving_ball(frames=3, x0=1.0)
    path = render_gif([a, b], tmp_path / "two.gif", size_px=100, view=VIEW, labels=["a", "b"])
    with Image.open(path) as im:
        assert im.n_frames == 3
        im.seek(1)  # run a's ball at (-2, Y), run b's at (2, Y)
        rgb = np.asarray(im.convert("RGB"), dtype=float)
    ca, cb = rgb[pixel(-2.5, Y)], rgb[pixel(1.5, Y)]
    np.testing.assert_allclose(ca, fill_rgb("C0"), atol=8)
    np.testing.assert_allclose(cb, fill_rgb("C1"), atol=8)
    assert np.abs(ca - cb).max() > 50


def test_failing_render_leaves_no_file(tmp_path, monkeypatch):
    rec = moving_ball(frames=6)
    original = render.FrameRenderer._draw  # every frame is drawn here, as pixels or an image
    calls = []

    def flaky(self, k):
        calls.append(k)
        if len(calls) == 4:
            raise RuntimeError("disk on fire")
        return original(self, k)

    monkeypatch.setattr(render.FrameRenderer, "_draw", flaky)
    target = tmp_path / "out.gif"
    with pytest.raises(RuntimeError, match="disk on fire"):
        render_gif(rec, target, size_px=64)
    assert list(tmp_path.iterdir()) == []  # neither the GIF nor a temporary file
    target.write_bytes(b"old")
    calls.clear()
    with pytest.raises(RuntimeError):
        render_gif(rec, target, size_px=64)
    assert target.read_bytes() == b"old" and list(tmp_path.iterdir()) == [target]


def test_bad_arguments_are_rejected(tmp_path):
    rec = moving_ball(frames=2)
    with pytest.raises(ValueError):
        render_gif([rec, rec], tmp_path / "x.gif", colors=["red"])
    with pytest.raises(ValueError):
        render_png(
            Recording(["a"], ["dynamic"], [[CircleOutline(np.zeros(2), 1.0)]]), tmp_path / "e.png"
        )
    with pytest.raises(ValueError):
        Recording(["a"], ["floating"], [[]])
    assert list(tmp_path.iterdir()) == []


def pendulum_world() -> tuple[World, list]:
    """A bob hung by a pin from an off-centre anchor; its shape is off its origin (com != origin)
    and the pin holds it off its origin too, so the anchors test x = p + R(angle) q."""
    world = World(dt=1 / 60)
    beam = world.add_body(WorldBody("beam", type="static", position=(0.5, 3.0), angle=0.3))
    beam.add_shape(Box(2.0, 0.2))
    bob = world.add_body(WorldBody("bob", position=(2.0, 0.5), angle=0.4))
    bob.add_shape(Circle(0.4, offset=(0.2, -0.1)))
    link = world.add_body(WorldBody("link", position=(2.6, 0.0)))
    link.add_shape(Box(0.6, 0.1))
    joints = [
        world.add_joint(PinJoint(beam, bob, (0.7, 0.05), (0.1, 0.3))),
        world.add_joint(PivotJoint(bob, link, (0.3, -0.1), (-0.3, 0.0))),
        world.add_joint(SpringJoint(beam, link, (-0.9, 0.0), (0.3, 0.0), stiffness=50.0)),
    ]
    return world, joints


def test_recorded_joint_ends_are_the_world_anchors():
    world, joints = pendulum_world()
    rec = Recording.from_world(world)
    expected = []
    for _ in range(6):
        rec.capture(world)
        expected.append([joint.world_anchors(world) for joint in joints])
        for _ in range(5):
            world.step()
    assert [j.kind for j in rec.joints] == ["pin", "pivot", "spring"]
    assert [(j.a, j.b) for j in rec.joints] == [(0, 1), (1, 2), (0, 2)]
    ends = rec.joint_segments()
    assert ends.shape == (6, 3, 2, 2)
    # the engine's anchors (com + R (q - local_com)) and the recording's (p + R q): 1e-12 m
    np.testing.assert_allclose(ends, np.array(expected), rtol=0, atol=1e-12)
    assert np.abs(ends[-1] - ends[0]).max() > 0.1  # the bodies did swing
    # a frame added from poses alone places the anchors the same way (replays, pymunk runs)
    again = Recording.from_world(world)
    again.add_frame(rec.frames[-1], rec.times[-1])
    np.testing.assert_array_equal(again.joint_frames[0], ends[-1])


def hanging_pendulum(frames: int = 2) -> Recording:
    """A shapeless static anchor at (X, 4) and a ball of radius 1 at (X, -2) on a pin: a vertical
    rod through the middle of pixel column 50 (at 100 px of VIEW)."""
    x = 0.05
    rec = Recording(
        names=["anchor", "bob"],
        types=["static", "dynamic"],
        outlines=[[], [CircleOutline(np.zeros(2), 1.0)]],
        joints=[JointOutline("pin", 0, 1, np.zeros(2), np.zeros(2))],
    )
    for k in range(frames):
        rec.add_frame([[x, 4.0, 0.0], [x, -2.0, 0.0]], k / 30)
    return rec


def test_pin_is_drawn_as_a_line_in_the_run_colour(tmp_path):
    rec = hanging_pendulum()
    np.testing.assert_array_equal(rec.joint_frames[1], [[[0.05, 4.0], [0.05, -2.0]]])
    path = render_png(rec, tmp_path / "pin.png", size_px=100, view=VIEW)
    with Image.open(path) as im:
        rgb = np.asarray(im.convert("RGB"), dtype=float)
    row, col = pixel(0.05, 1.0)  # midway between the anchor (y = 4) and the bob (y = -2)
    near = rgb[row, col - 1 : col + 2]
    darkest = near[near.sum(axis=1).argmin()]
    # a vertical 1 px line snapped onto one pixel column: the run colour, 8 of 255 for rounding
    np.testing.assert_allclose(darkest, 255 * np.array(to_rgb("C0")), atol=8)
    np.testing.assert_array_equal(rgb[pixel(1.05, 1.0)], [255, 255, 255])  # 1 m off the rod


def test_pivot_dot_and_spring_zigzag(tmp_path):
    rec = Recording(
        names=["left", "right"],
        types=["static", "dynamic"],
        outlines=[[], []],
        joints=[
            JointOutline("spring", 0, 1, np.zeros(2), np.zeros(2)),
            JointOutline("pivot", 0, 1, np.zeros(2), np.array([-4.0, 0.0])),
        ],
    )
    rec.add_frame([[-3.0, Y, 0.0], [1.0, Y, 0.0]], 0.0)
    rgb = next(render.render_frames(rec, size_px=100, view=VIEW))
    # the pivot's anchors meet at (-3, Y): a dot with a white middle and a run-coloured rim
    row, col = pixel(-3.0, Y)
    ring = rgb[row - 3 : row + 4, col - 3 : col + 4].reshape(-1, 3).astype(float)
    assert np.abs(ring - 255 * np.array(to_rgb("C0"))).sum(axis=1).min() < 60  # hand-set bound
    # the spring's zig-zag: its ends are the anchors, its peaks half_width off the axis
    zig = zigzag(rec.joint_frames[0][:1], 0.25)[0]
    np.testing.assert_array_equal(zig[[0, -1]], [[-3.0, Y], [1.0, Y]])
    np.testing.assert_allclose(np.abs(zig[:, 1] - Y).max(), 0.25, rtol=1e-12)
    assert np.isfinite(zigzag(np.zeros((1, 2, 2)), 0.25)).all()  # length 0: a point, no NaN
    # the middle of the spring (x = -1) is drawn: some pixel of that column is dark
    col = pixel(-1.0, Y)[1]
    assert rgb[row - 4 : row + 5, col].sum(axis=1).min() < 3 * 255 - 150


def test_buoyancy_world_draws_water_below_its_surface(tmp_path):
    world = World(dt=1 / 60)
    box = world.add_body(WorldBody("box", position=(2.0, 0.2)))
    box.add_shape(Box(1.0, 1.0))
    world.add_force(Buoyancy(surface_y=-0.5, fluid_density=2.0))
    rec = Recording.from_world(world)
    assert rec.fluids == [-0.5] and rec.joints == []
    path = render_png(world, tmp_path / "water.png", size_px=100, view=VIEW)
    with Image.open(path) as im:
        rgb = np.asarray(im.convert("RGB"), dtype=float)
    water, air = rgb[pixel(-3.0, -2.0)], rgb[pixel(-3.0, 2.0)]
    assert water[2] > water[0] + 40  # bluish: hand-measured blue - red = 44 at alpha 0.25
    np.testing.assert_array_equal(air, [255, 255, 255])
    # default view: the surface is in it even when every body is above the water
    rec.capture(world)
    rec.fluids = [-3.0]  # the box spans y in [-0.3, 0.7]
    with render.FrameRenderer(rec, size_px=64) as renderer:
        assert renderer.view[2] < -3.0 < renderer.view[3]


def test_recordings_without_joints_still_render_and_joints_are_checked(tmp_path):
    rec = moving_ball(frames=3)
    assert rec.joints == [] and rec.joint_segments().shape == (3, 0, 2, 2)
    assert render_png(rec, tmp_path / "plain.png", size_px=64).exists()
    with pytest.raises(ValueError):
        hanging_pendulum().add_frame([[0, 4, 0], [0, -2, 0]], 1.0, joints=np.zeros((2, 2, 2)))
    with pytest.raises(ValueError):
        Recording(["a"], ["dynamic"], [[]], joints=[JointOutline("pin", 0, 1, (0, 0), (0, 0))])
    with pytest.raises(ValueError):
        Recording(["a"], ["dynamic"], [[]], fluids=[math.inf])


def test_legend_is_laid_over_the_bodies_as_agg_would_draw_it():
    """The legend, drawn once and composited over each frame (sandbox.legend_layer), gives the
    pixels Agg gives drawing it over that frame, to within two levels of 255 (Agg rounds after
    each of the legend's parts: one level over white, two over a body), also where a body
    passes under it (seen through its translucent frame), and only inside its box."""
    from sandbox.frames import FrameRenderer

    rec = moving_ball(frames=6, x0=-1.0)  # the ball ends at x = 4, under the upper-right legend
    rec.add_frame([[0.0, -4.0, 0.0], [3.6, 3.9, 0.0]], 6 / 30, height=6.0)
    with FrameRenderer(rec, size_px=200, view=VIEW, labels=["a run"], show_time=False) as r:
        layer = r.legend_layer
        assert layer is not None and not layer.empty
        for k in (0, 6):
            laid = r.frame(k)
            r.legend.axes.draw_artist(r.legend)  # the frame just drawn, then Agg's own legend
            drawn = np.asarray(r.canvas.buffer_rgba())[..., :3].astype(int)
            assert np.abs(laid.astype(int) - drawn).max() <= 2
        with FrameRenderer(rec, size_px=200, view=VIEW, show_time=False) as plain:
            bare = plain.frame(6).astype(int)
        changed = np.abs(laid.astype(int) - bare).max(axis=2) > 1
        rows, cols = np.nonzero(changed)
        assert changed.any()  # the legend is there ...
        inside = (rows >= layer.rows.start) & (rows < layer.rows.stop)
        inside &= (cols >= layer.cols.start) & (cols < layer.cols.stop)
        assert inside.all()  # ... and nowhere else
        box = laid[layer.rows, layer.cols].astype(int)
        under = bare[layer.rows, layer.cols]
        ball = np.abs(under - 255).max(axis=2) > 40  # the ball's pixels under the legend
        assert ball.sum() > 20
        assert (np.abs(box - 255).max(axis=2)[ball] > 10).mean() > 0.5  # seen through it


def test_an_animations_images_are_its_frames_pixels():
    # render_gif takes each frame as an image from the canvas (FrameRenderer.image); the
    # pixels are frame()'s, the legend laid over them included, frame after frame (the legend
    # is composited onto the canvas itself, which the next frame restores)
    runs = [moving_ball(frames=4), moving_ball(frames=4, x0=0.5)]
    with render.FrameRenderer(runs, size_px=96, labels=["left", "right"]) as renderer:
        assert renderer.legend_layer is not None and not renderer.legend_layer.empty
        for k in (0, 1, 2, 3, 1):
            image = renderer.image(k)
            assert image.mode == "RGB"
            assert np.array_equal(np.asarray(image), renderer.frame(k)), k
