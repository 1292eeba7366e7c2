"""Text that changes every frame, drawn by Pillow (sandbox.frame_text): in matplotlib's place,
in its colour, and left to matplotlib where Pillow would not draw it as matplotlib does."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import numpy as np
import pytest
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from sandbox.frame_text import FrameText, plain


def canvas_with(**text_options):
    """A 300 x 200 px canvas (white, 100 dpi) with one animated text; the text and canvas."""
    fig = Figure(figsize=(3.0, 2.0), dpi=100)
    canvas = FigureCanvasAgg(fig)
    ax = fig.add_axes((0.0, 0.0, 1.0, 1.0))
    ax.set_axis_off()
    ax.set_xlim(0.0, 3.0)
    ax.set_ylim(0.0, 2.0)
    text = ax.text(animated=True, **text_options)
    canvas.draw()
    return text, canvas


def drawn(text, canvas, by_pillow: bool) -> np.ndarray:
    """(height, width) ink of ``text`` alone on white (0 none, 765 black): drawn by
    matplotlib, or by FrameText."""
    background = canvas.copy_from_bbox(canvas.figure.bbox)
    canvas.restore_region(background)
    rgba = np.asarray(canvas.buffer_rgba())
    if by_pillow:
        FrameText([text], canvas).over(rgba)
    else:
        text.axes.draw_artist(text)
    ink = 765 - rgba[..., :3].astype(int).sum(axis=2)
    canvas.restore_region(background)
    return ink


def extent(ink: np.ndarray) -> tuple[float, ...]:
    """First and last inked row and column, and the ink's centre (row, column)."""
    rows, cols = np.nonzero(ink > 40)
    weight = ink[rows, cols]
    centre = (rows @ weight / weight.sum(), cols @ weight / weight.sum())
    return rows.min(), rows.max(), cols.min(), cols.max(), *centre


@pytest.mark.parametrize(
    "options",
    [
        dict(x=0.1, y=1.9, s="t = 1.23 s", ha="left", va="top", fontsize=9),
        dict(x=1.5, y=1.0, s="78.57 J", ha="left", va="center", fontsize=8.1),
        dict(x=1.5, y=0.5, s="-1.234e-05 J", ha="right", va="center", fontsize=8.1),
        dict(x=0.2, y=0.3, s="n/a", ha="left", va="baseline", fontsize=12),
        dict(x=2.9, y=0.1, s="t = 10.07 s", ha="right", va="bottom", fontsize=7),
    ],
)
def test_pillow_draws_the_string_where_matplotlib_does(options):
    # the same font file and FreeType: the ink starts and ends on the same rows and columns
    # to within a pixel (hinting), its centre within 0.6 px (Pillow starts the glyphs on a
    # whole row), and is as dark in all
    text, canvas = canvas_with(**options)
    agg, pillow = drawn(text, canvas, False), drawn(text, canvas, True)
    a, p = extent(agg), extent(pillow)
    assert np.abs(np.subtract(a[:4], p[:4])).max() <= 1, (a, p)
    assert np.abs(np.subtract(a[4:], p[4:])).max() <= 0.6, (a, p)
    assert abs(pillow.sum() / agg.sum() - 1.0) < 0.15


def test_colour_and_alpha_are_the_texts():
    text, canvas = canvas_with(x=0.2, y=1.0, s="88 J", fontsize=30, color="tab:red", alpha=0.5)
    background = canvas.copy_from_bbox(canvas.figure.bbox)
    rgba = np.asarray(canvas.buffer_rgba())
    FrameText([text], canvas).over(rgba)
    inked = rgba[..., :3].astype(int)
    core = inked.reshape(-1, 3)[np.argmin(inked.sum(axis=2))]
    red = np.array(matplotlib.colors.to_rgb("tab:red")) * 255
    # fully covered pixels: half the text's colour, half the white below (within a level)
    assert np.abs(core - (0.5 * red + 0.5 * 255)).max() <= 2, core
    assert (rgba[..., 3] == 255).all()  # the canvas stays opaque
    canvas.restore_region(background)


@pytest.mark.parametrize(
    "options",
    [
        dict(x=0.2, y=1.0, s="$\\omega$ = 3 rad/s"),  # mathtext
        dict(x=0.2, y=1.0, s="two\nlines"),
        dict(x=1.0, y=1.0, s="turned", rotation=30),
        dict(x=0.2, y=1.0, s="boxed", bbox=dict(facecolor="yellow")),
        dict(x=0.2, y=1.0, s="\u03c9 = 3 rad/s"),  # beyond ASCII: matplotlib's font fallback
        dict(x=0.2, y=1.0, s="wrapped", wrap=True),
    ],
)
def test_what_pillow_would_draw_otherwise_matplotlib_draws(options):
    text, canvas = canvas_with(fontsize=10, **options)
    assert not plain(text)
    assert np.array_equal(drawn(text, canvas, False), drawn(text, canvas, True))


def test_a_dollar_sign_alone_is_plain_text():
    text, _ = canvas_with(x=0.2, y=1.0, s="costs $5")
    assert plain(text)


def test_hidden_empty_and_off_canvas_texts_draw_nothing():
    for options in (
        dict(x=0.2, y=1.0, s="hidden", visible=False),
        dict(x=0.2, y=1.0, s=""),
        dict(x=30.0, y=1.0, s="far right"),
        dict(x=0.2, y=-5.0, s="far below"),
    ):
        text, canvas = canvas_with(**options)
        assert drawn(text, canvas, True).max() == 0, options


def test_text_half_off_the_canvas_is_cut_at_its_edge():
    text, canvas = canvas_with(x=-0.1, y=1.0, s="cut at the edge", fontsize=12)
    agg, pillow = drawn(text, canvas, False), drawn(text, canvas, True)
    assert pillow.max() > 0
    assert abs(extent(agg)[3] - extent(pillow)[3]) <= 1


def test_an_animations_time_is_drawn_by_pillow_where_matplotlib_puts_it():
    # a frame's time label: Pillow's ink where matplotlib draws it (the frame without the
    # label, then matplotlib's own label over it), and a new time in every frame
    from test_render import moving_ball

    from sandbox.frames import FrameRenderer

    with FrameRenderer(moving_ball(frames=3), size_px=160) as r:
        label = r.time_text
        assert label is not None and label in r.texts.texts and label not in r.animated
        inks = []
        for k in (1, 2):
            pillow = r.frame(k).astype(int)
            label.set_visible(False)
            bare = r.frame(k).astype(int)
            label.set_visible(True)
            label.axes.draw_artist(label)
            agg = np.asarray(r.canvas.buffer_rgba())[..., :3].astype(int)
            a = extent(np.abs(agg - bare).sum(axis=2))
            p = extent(np.abs(pillow - bare).sum(axis=2))
            assert np.abs(np.subtract(a[:4], p[:4])).max() <= 1, (k, a, p)
            inks.append(np.abs(pillow - bare).sum(axis=2))
        assert label.get_text() == "t = 0.07 s"
        assert not np.array_equal(inks[0], inks[1])
