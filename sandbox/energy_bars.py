"""The energy-bars panel (as in PhET's simulations): a bar per kind of energy, every frame.

Bars, top to bottom (joules): kinetic energy of motion along a path (linear, m v^2 / 2) and of
turning (rotational, I omega^2 / 2), gravity's potential energy (measured from y = 0, so it is
negative below the origin), elastic energy stored in springs, their total E, the work W done by
forces and motors (only when some was), and what was lost: E(0) + W - E(t), the energy impacts,
friction and damping took. For a closed system W = 0 and lost = E(0) - E(t).

The numbers come from a recording made with ``record(..., energy=True)``
(:mod:`sandbox.energy`); :func:`bar_values` gives them per frame as the panel draws them.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np
from matplotlib.collections import PolyCollection

from sandbox.energy import ENERGY_SERIES
from sandbox.recording import Recording

PANEL = "energy-bars"
BARS = (  # (label, colour) in the order of bar_values' columns
    ("kinetic, linear", (0.84, 0.19, 0.15)),
    ("kinetic, rotation", (0.96, 0.55, 0.12)),
    ("gravity potential", (0.18, 0.42, 0.8)),
    ("elastic (springs)", (0.16, 0.6, 0.28)),
    ("total E", (0.25, 0.25, 0.25)),
    ("work by forces W", (0.55, 0.3, 0.7)),
    ("lost", (0.55, 0.36, 0.2)),
)
TOTAL, WORK, LOST = 4, 5, 6


def bar_values(run: Recording) -> np.ndarray:
    """``(F, 7)`` joules per frame: linear and rotational kinetic, gravity, elastic, total,
    work done since frame 0 (NaN when not measured), lost = E(0) + W - E(t) (W taken as 0
    when not measured)."""
    missing = [name for name in ENERGY_SERIES if name not in run.series]
    if missing:
        raise ValueError(
            f"panel {PANEL!r}: the recording has no energies ({missing[0]}): "
            "record it with record(..., energy=True)"
        )
    parts = np.array([run.series[name] for name in ENERGY_SERIES[:4]], dtype=float).T
    work = np.asarray(run.series["energy.work"], dtype=float)
    total = parts.sum(axis=1)
    lost = total[0] + np.nan_to_num(work) - total
    return np.column_stack([parts, total, work, lost])


class EnergyBars:
    """The panel on axes ``ax``: one bar per kind of energy for each run (runs side by side
    in ``colors``; one run in the bars' own colours), with the value in joules beside each."""

    def __init__(
        self, ax: Any, runs: Sequence[Recording], colors: Sequence[tuple], fontsize: float
    ) -> None:
        self.ax, self.runs = ax, list(runs)
        self.values = [bar_values(r) for r in self.runs]
        every = np.concatenate(self.values)
        measured = np.isfinite(every[:, WORK])
        scale = float(np.nanmax(np.abs(every[:, : TOTAL + 1]))) if len(every) else 1.0
        self.show_work = bool(np.any(np.abs(every[measured, WORK]) > 1e-9 * max(scale, 1e-300)))
        self.rows = [i for i in range(len(BARS)) if i != WORK or self.show_work]
        shown = every[:, self.rows]
        lo = min(0.0, float(np.nanmin(shown)))
        hi = max(0.0, float(np.nanmax(shown)))
        span = hi - lo if hi > lo else 1.0
        self.small = 0.05 * span  # a negative value this small gets its label right of zero
        # room for the value labels beside the bars
        ax.set_xlim(lo - (0.28 * span if lo < -self.small else 0.02 * span), hi + 0.28 * span)
        ax.set_ylim(len(self.rows) - 0.5, -0.5)  # first row on top
        ax.set_yticks(range(len(self.rows)), [BARS[i][0] for i in self.rows])
        ax.tick_params(labelsize=fontsize)
        ax.axvline(0.0, color="0.2", linewidth=0.8)
        ax.grid(axis="x", alpha=0.3)
        ax.set_xlabel("energy (J)", fontsize=fontsize)
        ax.set_title("Energy", fontsize=fontsize * 1.1)
        ax.set_autoscale_on(False)
        self.note = self._note(bool(measured.all()))
        ax.annotate(  # under the axis label, whatever the image size
            self.note,
            xy=(0.0, 0.0),
            xycoords="axes fraction",
            xytext=(0.0, -12 - 2.5 * fontsize),
            textcoords="offset points",
            ha="left",
            va="top",
            fontsize=0.85 * fontsize,
            color="0.25",
        )
        n = len(self.runs)
        self.height = 0.7 / n
        single = n == 1
        self.polys, self.labels = [], []
        for color in colors[:n]:
            faces = [BARS[i][1] for i in self.rows] if single else [color] * len(self.rows)
            poly = PolyCollection([], facecolors=faces, edgecolors="none", animated=True)
            ax.add_collection(poly)
            self.polys.append(poly)
        if single:  # the value beside each bar
            for _ in self.rows:
                text = ax.text(0, 0, "", fontsize=0.9 * fontsize, va="center", animated=True)
                self.labels.append(text)
        self.artists = [*self.polys, *self.labels]
        self.span, self.offset = span, span * 0.015

    def _note(self, measured: bool) -> str:
        lost = "lost = E(0) + W - E(t)" if self.show_work else "lost = E(0) - E(t)"
        if not measured:
            why = "work of forces and motors not measured"
        elif self.show_work:
            why = "W: work of forces and motors"
        else:
            why = "no force or motor did work"
        return f"{lost} ({why}):\nimpacts, friction, damping.  Gravity from y = 0."

    def update(self, ks: Sequence[int]) -> None:
        """Bars at frame ``ks[i]`` of each run."""
        h = self.height
        for r, (poly, values, k) in enumerate(zip(self.polys, self.values, ks, strict=True)):
            v = np.nan_to_num(values[k, self.rows])
            y0 = np.arange(len(self.rows)) - 0.35 + r * h
            y1 = y0 + h
            zero = np.zeros_like(v)
            poly.set_verts(
                np.stack(
                    [
                        np.stack([zero, y0], 1),
                        np.stack([v, y0], 1),
                        np.stack([v, y1], 1),
                        np.stack([zero, y1], 1),
                    ],
                    axis=1,
                )
            )
        if self.labels:
            values = self.values[0][ks[0], self.rows]
            for text, value, y in zip(self.labels, values, range(len(self.rows)), strict=True):
                value = 0.0 if abs(value) < 1e-9 * self.span else value  # no "-1e-15 J"
                right = not value < -self.small
                x = max(value, 0.0) + self.offset if right else value - self.offset
                text.set_position((x, y))
                text.set_horizontalalignment("left" if right else "right")
                text.set_text("n/a" if math.isnan(value) else f"{value:.4g} J")

    def colors(self) -> list[tuple]:
        return [c for _, c in BARS]
