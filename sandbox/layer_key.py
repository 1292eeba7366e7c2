"""How the debug-drawing layers look (colours, sizes in pixels at 480 px) and the key under an
animation that says what each colour means and how long an arrow of a round value is.

The key is a strip below the scene, never over it; it is drawn once, as part of the background.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any, NamedTuple

import numpy as np
from matplotlib.collections import LineCollection, PolyCollection

from sandbox.arrows import arcs, arrows, boxes

COLORS = {
    "contact": (0.86, 0.08, 0.08),
    "speculative": (0.45, 0.45, 0.45),
    "normal": (0.1, 0.1, 0.1),
    "normal impulse": (0.8, 0.0, 0.75),
    "friction impulse": (0.0, 0.6, 0.62),
    "force": (0.95, 0.45, 0.0),
    "gravity": (0.45, 0.2, 0.7),
    "velocity": (0.0, 0.5, 0.1),
    "aabb": (0.55, 0.4, 0.1),
    "com": (0.0, 0.0, 0.0),
    "joint": (0.1, 0.2, 0.65),
}
SLEEP_FACE = (0.78, 0.78, 0.78, 1.0)
# the arrows, in drawing order (wide first), with their layer; widths relative to a shaft
ARROWS = {
    "gravity": "gravity",
    "force": "forces",
    "torque": "forces",
    "velocity": "velocities",
    "normal impulse": "impulses",
    "friction impulse": "impulses",
    "normal": "normals",
}
WIDTH = {"gravity": 2.4, "force": 1.6, "torque": 1.6, "normal": 0.7}
UNITS = {"impulse": "N s", "force": "N", "velocity": "m/s", "torque": "N m"}
# sizes in pixels at 480 px (scaled with the image)
HEAD_PX, HEAD_WIDTH_PX, SHAFT_PX = 8.0, 6.0, 1.8
NORMAL_PX, TORQUE_RADIUS_PX, MARKER_PX = 22.0, 13.0, 4.5


class KeyEntry(NamedTuple):
    """One line of the key: a glyph (``arrow`` of ``length`` px, ``arc`` turning ``length``
    rad, ``marker``, ``box``, ``swatch``) in ``color`` and a ``label``; ``filled`` and
    ``marker`` for markers."""

    glyph: str
    color: tuple
    label: str
    length: float = 0.0
    filled: bool = True
    marker: str = "o"  # "o", "s" (square), or "+o" (a circle with a cross: centre of mass)
    width: float = 1.0  # an arrow's width, relative to a shaft


KEY_LINES = {"contacts": 2, "impulses": 2, "forces": 2}  # key entries per layer (else 1)
KEY_COLUMN_PX = 235.0  # width of one column of the key at 480 px
GLYPH_PX = 54.0  # room for the glyph before each label


def key_layout(names: Sequence[str], width_px: float, px: float, em: float) -> tuple[int, float]:
    """(columns, height in pixels) of the key strip for layers ``names`` in an image
    ``width_px`` wide; ``em`` is the font size in pixels."""
    entries = sum(KEY_LINES.get(name, 1) for name in names)
    if not entries:
        return 1, 0.0
    columns = max(1, int(width_px // (KEY_COLUMN_PX * px)))
    rows = math.ceil(entries / columns)
    return columns, rows * 1.75 * em + 0.9 * em


def draw_key(ax: Any, entries: Sequence[KeyEntry], columns: int, px: float, fontsize: float):
    """Draw ``entries`` on ``ax`` (a strip whose data coordinates are its pixels), in
    ``columns``, row by row from the top. Drawn once: the key is part of the background."""
    ax.set_axis_off()
    x1, y1 = ax.bbox.width, ax.bbox.height
    ax.set_xlim(0.0, x1)
    ax.set_ylim(0.0, y1)
    em = fontsize * 100.0 / 72.0
    col_w = x1 / columns
    lw = max(0.72, SHAFT_PX * px * 0.72)
    for i, entry in enumerate(entries):
        row, col = divmod(i, columns)
        x0 = col * col_w + 0.6 * em
        y = y1 - 0.45 * em - (row + 0.5) * 1.75 * em
        if entry.glyph in ("arrow", "arc"):
            head = tuple(entry.width**0.5 * h for h in (HEAD_PX * px, HEAD_WIDTH_PX * px))
            if entry.glyph == "arrow":
                geometry = arrows([[x0, y]], [[entry.length, 0.0]], *head)
            else:
                r = TORQUE_RADIUS_PX * px
                geometry = arcs([[x0 + 1.5 * r, y - 0.5 * r]], [entry.length], r, *head, 0.0)
            width = lw * entry.width
            ax.add_collection(LineCollection(geometry.shafts, colors=[entry.color], lw=width))
            ax.add_collection(PolyCollection(geometry.heads, facecolors=[entry.color]))
        elif entry.glyph == "marker":
            size = MARKER_PX * px * (1.6 if entry.marker == "+o" else 1.0)
            for marker in ("o", "+") if entry.marker == "+o" else (entry.marker,):
                ax.plot(
                    [x0 + 0.5 * em],
                    [y],
                    marker=marker,
                    markersize=size,
                    mew=0.9 * lw,
                    mfc=entry.color if entry.filled else "white",
                    mec=entry.color,
                )
        else:  # a box outline or a filled swatch
            lo, hi = np.array([[x0, y - 0.4 * em]]), np.array([[x0 + 1.6 * em, y + 0.4 * em]])
            if entry.glyph == "box":
                ax.add_collection(LineCollection(boxes(lo, hi), colors=[entry.color], lw=lw))
            else:
                face = PolyCollection(boxes(lo, hi)[:, :4], facecolors=[entry.color])
                face.set_edgecolor("0.45")
                ax.add_collection(face)
        ax.text(x0 + GLYPH_PX * px, y, entry.label, fontsize=fontsize, va="center", ha="left")
