"""Series panels: recorded values (energy, momentum, ...) plotted against time beside an
animation, one panel per series, with a cursor at the frame's time and a dot per run."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from sandbox.recording import Recording

_DPI = 100


class SeriesPanels:
    """Panels for the series ``names`` of ``runs`` (in ``colors``) in the right-hand
    ``size_px`` wide column of ``fig``; ``rect(x, y, w, h)`` turns a box in pixels (y from the
    bottom of the scene) into figure fractions. ``artists`` move each frame (:meth:`update`).
    """

    def __init__(
        self,
        fig: Any,
        rect: Callable[[float, float, float, float], tuple[float, ...]],
        runs: Sequence[Recording],
        colors: Sequence[tuple],
        names: Sequence[str],
        size_px: int,
        scale: float,
        fontsize: float,
    ) -> None:
        self.runs, self.names = list(runs), list(names)
        self.cursors, self.dots, self.artists = [], [], []
        em = fontsize * _DPI / 72.0  # font size in pixels: margins leave room for tick labels
        left, right, bottom, top, gap = 5.8 * em, 1.0 * em, 3.8 * em, 1.0 * em, 1.4 * em
        n = len(self.names)
        h = (size_px - bottom - top - gap * (n - 1)) / n
        t_all = np.concatenate([np.asarray(r.times, dtype=float) for r in self.runs])
        t0, t1 = float(t_all.min()), float(t_all.max())
        for j, name in enumerate(self.names):
            y = bottom + (n - 1 - j) * (h + gap)
            ax = fig.add_axes(rect(size_px + left, y, size_px - left - right, h))
            for r, c in zip(self.runs, colors, strict=True):
                ax.plot(r.times, r.series[name], color=c, linewidth=1.2 * scale)
            ax.relim()
            ax.autoscale_view()
            ax.set_autoscale_on(False)  # the cursor and dots must not move the limits
            ax.set_xlim(t0, t1 if t1 > t0 else t0 + 1.0)
            ax.set_ylabel(name, fontsize=fontsize)
            ax.tick_params(labelsize=fontsize)
            ax.grid(alpha=0.3)
            if j == n - 1:
                ax.set_xlabel("t (s)", fontsize=fontsize)
            else:
                ax.tick_params(labelbottom=False)
            cursor = ax.axvline(t0, color="0.2", linewidth=0.8 * scale, animated=True)
            dots = ax.scatter(
                np.zeros(len(self.runs)),
                np.zeros(len(self.runs)),
                c=list(colors),
                s=18 * scale**2,
                zorder=3,
                animated=True,
            )
            self.cursors.append(cursor)
            self.dots.append(dots)
            self.artists += [cursor, dots]

    def update(self, ks: Sequence[int], times: Sequence[float]) -> None:
        """Cursor at ``times[0]`` (s), each run's dot at its frame ``ks[i]``."""
        for name, cursor, dots in zip(self.names, self.cursors, self.dots, strict=True):
            cursor.set_xdata([times[0], times[0]])
            values = [r.series[name][k] for r, k in zip(self.runs, ks, strict=True)]
            dots.set_offsets(np.column_stack([times, values]))
