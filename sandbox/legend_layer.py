"""A legend drawn once and laid over every frame of an animation.

A legend is text: laying it out and drawing it costs matplotlib 8 to 17 ms, more than the
bodies of a 100-ball frame (about 6 ms), and the legend is the same in every frame. It must
still be drawn over the bodies (they pass under it, seen through its translucent frame), so it
cannot be part of the saved background. Instead it is drawn once, alone, onto a transparent
canvas of the figure's size, and each frame composites those pixels over its own with the
"over" operator, C = C_legend a + C_frame (1 - a), a the legend's alpha per pixel: what Agg
computes when it draws the legend over the frame, to within two levels of 255 (Agg rounds
after each of the legend's parts, this after all of them: one level over white, two over a
body; tests/test_render.py).
"""

from __future__ import annotations

import numpy as np
from matplotlib.artist import Artist
from matplotlib.backends.backend_agg import RendererAgg


def lay_over(below: np.ndarray, color: np.ndarray, alpha: np.ndarray) -> None:
    """The "over" operator on ``below`` ((rows, cols, 3) uint8 pixels, changed in place):
    C = C_top a + C_below (1 - a), with ``color`` = C_top a (premultiplied, 0 to 255) and
    ``alpha`` = a ((rows, cols, 1), 0 to 1)."""
    below[...] = np.rint(color + below.astype(np.float64) * (1.0 - alpha))


class LegendLayer:
    """The pixels of ``artist`` (a legend) drawn alone on a transparent ``width`` x ``height``
    canvas at ``dpi``, cropped to where it drew anything."""

    def __init__(self, artist: Artist, width: int, height: int, dpi: float) -> None:
        renderer = RendererAgg(width, height, dpi)
        artist.draw(renderer)
        rgba = np.asarray(renderer.buffer_rgba())
        rows, cols = np.nonzero(rgba[..., 3])
        self.empty = rows.size == 0
        if self.empty:
            return
        self.rows = slice(int(rows.min()), int(rows.max()) + 1)
        self.cols = slice(int(cols.min()), int(cols.max()) + 1)
        part = rgba[self.rows, self.cols].astype(np.float64)
        self.alpha = part[..., 3:] / 255.0
        self.color = part[..., :3] * self.alpha  # premultiplied: C_legend a

    def over(self, rgb: np.ndarray) -> np.ndarray:
        """Lay the legend over the frame ``rgb`` ((height, width, 3) uint8, changed in place):
        C = C_legend a + C_frame (1 - a). Returns ``rgb``."""
        if self.empty:
            return rgb
        lay_over(rgb[self.rows, self.cols], self.color, self.alpha)
        return rgb
