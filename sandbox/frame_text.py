"""Text that changes in every frame of an animation, drawn by Pillow rather than matplotlib.

The time in the corner of an animation and the joules beside its energy bars are new strings in
every frame. matplotlib lays out and draws such a string glyph by glyph in Python: about 2 to 3
ms for "t = 1.23 s" (matplotlib 3.11), a quarter of a whole frame of bodies. Pillow draws the
same string with the same font file and the same FreeType in C in about a tenth of a millisecond
(0.4 ms a label with matplotlib's layout and the compositing). So the matplotlib ``Text``
artists stay (they hold the string, font, colour, position and alignment, and tests read them),
but :class:`FrameText` draws them: matplotlib places each string (its layout, as
:meth:`matplotlib.text.Text.draw` has it), Pillow renders its glyphs from that pen origin, and
the pixels are laid over the frame with the "over" operator, C = C_text a + C_frame (1 - a), as
Agg lays its own glyphs (:func:`sandbox.legend_layer.lay_over`, as for the legend). The glyphs'
edges can differ from matplotlib's by FreeType's hinting; their ink lands on the same rows and
columns to within a pixel, its centre within half a pixel (tests/test_frame_text.py).
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np
from matplotlib.colors import to_rgba
from matplotlib.font_manager import findfont
from matplotlib.text import Text
from PIL import ImageFont

from sandbox.legend_layer import lay_over


@lru_cache(maxsize=32)
def pillow_font(path: str, size_px: float) -> ImageFont.FreeTypeFont:
    """The font file at ``path`` at an em size of ``size_px`` pixels, loaded once."""
    return ImageFont.truetype(path, size=size_px, layout_engine=ImageFont.Layout.BASIC)


def plain(text: Text) -> bool:
    """Whether Pillow can draw ``text`` as matplotlib would: one line of ASCII (no glyph
    another font would have to supply), unrotated, unwrapped, no maths, no box, clip or path
    effects around it."""
    s = text.get_text()
    math = text.get_parse_math() and s.count("$") >= 2 and s.count("$") % 2 == 0
    return (
        s.isascii()
        and "\n" not in s
        and not text.get_wrap()
        and not math
        and text.get_rotation() == 0
        and text.get_bbox_patch() is None
        and not text.get_path_effects()
        and not text.get_usetex()
        and (not text.get_clip_on() or text.get_clip_box() is None and not text.get_clip_path())
    )


def pen_origin(text: Text, renderer) -> tuple[float, float] | None:
    """Where matplotlib would start drawing ``text`` (one line): the pen's x and the baseline's
    row (pixels from the left and from the top), as :meth:`matplotlib.text.Text.draw` works it
    out from the text's layout; None where that layout is not the expected one line."""
    try:
        _, info, _ = text._get_layout(renderer)  # what Text.draw itself starts from
        _, _, *place = info[0]  # matplotlib 3.11: (line, size, (x, y)); earlier (line, size, x, y)
        dx, dy = place[0] if len(place) == 1 else place
    except (AttributeError, TypeError, ValueError, IndexError):
        return None
    x, y = text.get_transform().transform(text.get_unitless_position())
    if len(info) != 1 or not np.isfinite(x + y):
        return None
    return x + dx, renderer.height - (y + dy)


class FrameText:
    """Draws ``texts`` (matplotlib ``Text`` artists on ``canvas``, as they stand at each call)
    over the canvas's pixels: with Pillow when they are :func:`plain`, else by matplotlib."""

    def __init__(self, texts: list[Text], canvas) -> None:
        self.texts, self.canvas = texts, canvas

    def over(self, rgba: np.ndarray) -> np.ndarray:
        """Lay every visible, non-empty text over ``rgba`` ((height, width, 3 or 4) uint8, the
        canvas's own pixels, changed in place). Returns ``rgba``."""
        renderer = self.canvas.get_renderer()
        for text in self.texts:
            if not text.get_visible() or not text.get_text():
                continue
            if plain(text):
                self._one(text, rgba, renderer)
            else:
                text.draw(renderer)
        return rgba

    def _one(self, text: Text, rgba: np.ndarray, renderer) -> None:
        s = text.get_text()
        prop = text.get_fontproperties()
        font = pillow_font(findfont(prop), prop.get_size_in_points() * renderer.dpi / 72.0)
        origin = pen_origin(text, renderer)
        if origin is None:  # a layout this code does not know: matplotlib draws it
            text.draw(renderer)
            return
        x, baseline = origin
        fx, fy = x - np.floor(x), baseline - np.floor(baseline)
        mask, (dx, dy) = font.getmask2(s, mode="L", anchor="ls", start=(fx, fy))
        width, height = mask.size
        if width == 0 or height == 0:
            return
        alpha = np.asarray(mask, dtype=np.float64).reshape(height, width) / 255.0
        left, top = int(np.floor(x)) + dx, int(np.floor(baseline)) + dy
        rows = slice(max(top, 0), min(top + height, rgba.shape[0]))
        cols = slice(max(left, 0), min(left + width, rgba.shape[1]))
        if rows.start >= rows.stop or cols.start >= cols.stop:
            return
        a = alpha[rows.start - top : rows.stop - top, cols.start - left : cols.stop - left]
        r, g, b, opacity = to_rgba(text.get_color(), text.get_alpha())
        a = (a * opacity)[..., None]
        lay_over(rgba[rows, cols, :3], 255.0 * np.array([r, g, b]) * a, a)
