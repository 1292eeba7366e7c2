"""Recordings and headless rendering: files are whole images, shapes land on the right pixels."""

from __future__ import annotations

import numpy as np
import pytest
from matplotlib.colors import to_rgb
from PIL import Image

from sandbox import render
from sandbox.geometry import box_vertices
from sandbox.recording import CircleOutline, Recording, record
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
    original = render.FrameRenderer.frame
    calls = []

    def flaky(self, k):
        calls.append(k)
        if len(calls) == 4:
            raise RuntimeError("disk on fire")
        return original(self, k)

    monkeypatch.setattr(render.FrameRenderer, "frame", flaky)
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
