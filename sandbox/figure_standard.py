"""The figure standard every lesson figure meets, checked on the matplotlib objects themselves.

A figure passes when

- it has a **title**: a suptitle, or a title on every panel (a panel is the axes drawn in one
  place: an axes and its ``twinx`` are one panel);
- every **data axis** is labelled, with its unit in brackets at the end: ``"x (m)"``,
  ``"t (s)"``, ``"T / T0 (1)"``. An axis is a data axis when it is visible and shows numeric tick
  labels (categorical tick labels, hidden ticks and axes turned off need no label);
- a panel with **several series** has a legend (its own or the figure's) and every series is
  named in it, by its label or by sharing the colour of a named series;
- **no legend covers data**: no line segment, marker, scatter point or shape edge of the panel
  passes through a legend's box, and no filled shape lies under it.

:func:`check_figure` returns the problems as lines of text. :func:`enforce` raises
:class:`FigureStandardError` when the environment variable ``SANDBOX_CHECK_FIGURES`` is set
(the lesson tests set it; ``warn`` prints the problems instead); ``sandbox.lessonkit.save_figure``
calls it for every lesson figure.
"""

from __future__ import annotations

import math
import os
import re
import sys
from collections.abc import Iterator

import numpy as np
from matplotlib.axes import Axes
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.collections import Collection, PathCollection
from matplotlib.colors import to_rgba
from matplotlib.container import BarContainer
from matplotlib.figure import Figure
from matplotlib.legend import Legend
from matplotlib.lines import Line2D
from matplotlib.transforms import Bbox

ENV = "SANDBOX_CHECK_FIGURES"
UNIT = re.compile(r"[(\[][^()\[\]]*[^()\[\]\s][^()\[\]]*[)\]]\s*$")  # "... (unit)" at the end
NO_MARKER = (None, "", " ", "None", "none")


class FigureStandardError(ValueError):
    """A lesson figure that breaks the figure standard (the message lists every problem)."""


def enabled() -> bool:
    """True when ``SANDBOX_CHECK_FIGURES`` is set to anything but "", "0" or "false"."""
    return os.environ.get(ENV, "").strip().lower() not in ("", "0", "false", "no")


def enforce(fig: Figure, name: str = "figure") -> None:
    """Raise :class:`FigureStandardError` listing the problems of ``fig`` when checking is on
    (``SANDBOX_CHECK_FIGURES=warn`` prints them to stderr instead)."""
    if not enabled():
        return
    problems = check_figure(fig)
    if problems:
        text = f"{name} breaks the figure standard:\n  " + "\n  ".join(problems)
        if os.environ.get(ENV, "").strip().lower() == "warn":
            print(text, file=sys.stderr)
            return
        raise FigureStandardError(text)


# ------------------------------------------------------------------------------------ panels


def _panels(fig: Figure) -> list[list[Axes]]:
    """Axes grouped by where they are drawn (an axes and its twins share a place)."""
    groups: dict[tuple, list[Axes]] = {}
    for ax in fig.axes:
        if not ax.get_visible():
            continue
        key = tuple(round(v, 3) for v in ax.get_position().bounds)
        groups.setdefault(key, []).append(ax)
    return list(groups.values())


def _has_data(ax: Axes) -> bool:
    return bool(ax.lines or ax.collections or ax.patches or ax.images or ax.containers)


def _label(artist) -> str | None:
    """The legend label of an artist, None when it has none (matplotlib's "_..." labels)."""
    text = artist.get_label()
    return text if text and not str(text).startswith("_") else None


def _colour(artist) -> tuple | None:
    """The colour a reader identifies a series by (RGB, rounded), or None."""
    try:
        if isinstance(artist, Line2D):
            c = artist.get_color()
        elif isinstance(artist, BarContainer):
            c = artist.patches[0].get_facecolor() if artist.patches else None
        elif isinstance(artist, Collection):
            faces = artist.get_facecolor()
            c = faces[0] if len(faces) else artist.get_edgecolor()[0]
        else:
            c = artist.get_facecolor()
        return None if c is None else tuple(round(float(v), 2) for v in to_rgba(c)[:3])
    except (IndexError, TypeError, ValueError):
        return None


def _series(ax: Axes) -> list:
    """The data series of an axes: named artists, curves of 3 points or more, scatters of 2 or
    more points, bar groups. Unnamed segments, shapes and lines across the axes are drawings."""
    out = []
    for line in ax.lines:
        if line.get_visible() and (_label(line) or len(line.get_xydata()) >= 3):
            out.append(line)
    for coll in ax.collections:
        if not coll.get_visible():
            continue
        if _label(coll) or (isinstance(coll, PathCollection) and len(coll.get_offsets()) >= 2):
            out.append(coll)
    out += [c for c in ax.containers if isinstance(c, BarContainer)]
    return out


def _legends(fig: Figure, panel: list[Axes]) -> list[Legend]:
    return [ax.get_legend() for ax in panel if ax.get_legend() is not None] + list(fig.legends)


# ------------------------------------------------------------------------------- data geometry


def _segments_hit(p0: np.ndarray, p1: np.ndarray, box: Bbox) -> bool:
    """Does any segment p0[i] -> p1[i] (display pixels) pass through ``box`` (Liang-Barsky)?"""
    keep = np.isfinite(p0).all(axis=1) & np.isfinite(p1).all(axis=1)
    p0, p1 = p0[keep], p1[keep]
    if not len(p0):
        return False
    d = p1 - p0
    t0, t1 = np.zeros(len(p0)), np.ones(len(p0))
    ok = np.ones(len(p0), dtype=bool)
    for p, q in (
        (-d[:, 0], p0[:, 0] - box.x0),
        (d[:, 0], box.x1 - p0[:, 0]),
        (-d[:, 1], p0[:, 1] - box.y0),
        (d[:, 1], box.y1 - p0[:, 1]),
    ):
        parallel = p == 0.0
        ok &= ~(parallel & (q < 0.0))
        with np.errstate(divide="ignore", invalid="ignore"):
            r = np.where(parallel, 0.0, q / np.where(parallel, 1.0, p))
        t0 = np.where(~parallel & (p < 0.0), np.maximum(t0, r), t0)
        t1 = np.where(~parallel & (p > 0.0), np.minimum(t1, r), t1)
    return bool(np.any(ok & (t0 <= t1)))


def _points_hit(points: np.ndarray, radius: float, box: Bbox) -> bool:
    points = points[np.isfinite(points).all(axis=1)]
    if not len(points):
        return False
    x, y = points[:, 0], points[:, 1]
    inside = (x >= box.x0 - radius) & (x <= box.x1 + radius)
    inside &= (y >= box.y0 - radius) & (y <= box.y1 + radius)
    return bool(inside.any())


def _polylines(path, transform) -> Iterator[np.ndarray]:
    """Display-space vertex runs of a path (curves flattened; each run drawn as a polyline)."""
    for poly in path.to_polygons(transform, closed_only=False):
        if len(poly):
            yield np.asarray(poly, dtype=float)


def _covers(artist, box: Bbox, px_per_point: float) -> bool:
    """Does any part of ``artist`` (drawn in display pixels) lie inside ``box``?"""
    if isinstance(artist, Line2D):
        xy = artist.get_transform().transform(artist.get_xydata())
        if artist.get_linestyle() not in ("None", "none", "", " ") and len(xy) >= 2:
            if _segments_hit(xy[:-1], xy[1:], box):
                return True
        if artist.get_marker() not in NO_MARKER:
            return _points_hit(xy, 0.5 * artist.get_markersize() * px_per_point, box)
        return len(xy) == 1 and _points_hit(xy, 0.0, box)
    if isinstance(artist, PathCollection):
        offsets = np.asarray(artist.get_offsets(), dtype=float)
        if len(offsets):
            xy = artist.get_offset_transform().transform(offsets)
            sizes = artist.get_sizes()
            size = float(np.max(sizes)) if len(sizes) else 36.0
            return _points_hit(xy, 0.5 * math.sqrt(size) * px_per_point, box)
        return False
    if isinstance(artist, Collection):
        offsets = np.asarray(artist.get_offsets(), dtype=float)
        if len(offsets) > 1 or (len(offsets) == 1 and np.any(offsets != 0.0)):
            xy = artist.get_offset_transform().transform(offsets)  # e.g. arrows of a quiver
            return _points_hit(xy, 2.0, box)
        return any(_path_hit(p, artist.get_transform(), box, False) for p in artist.get_paths())
    filled = bool(getattr(artist, "get_fill", lambda: False)())
    return _path_hit(artist.get_path(), artist.get_transform(), box, filled)


def _path_hit(path, transform, box: Bbox, filled: bool) -> bool:
    for run in _polylines(path, transform):
        if len(run) >= 2 and _segments_hit(run[:-1], run[1:], box):
            return True
        if len(run) == 1 and _points_hit(run, 0.0, box):
            return True
    if filled:  # a legend entirely inside a filled shape hides it too
        return bool(path.transformed(transform).contains_point((box.x0 + 1.0, box.y0 + 1.0)))
    return False


def _drawn(ax: Axes) -> Iterator:
    yield from (a for a in ax.lines if a.get_visible())
    yield from (a for a in ax.collections if a.get_visible())
    yield from (a for a in ax.patches if a.get_visible() and a is not ax.patch)


# ------------------------------------------------------------------------------------- checks


def _is_categorical(axis) -> bool:
    """Tick labels that are words (bar names), not numbers (plain, mathtext or log)."""
    for tick in axis.get_ticklabels():
        text = re.sub(
            r"\\mathdefault|\\times|[${}\\\s]", "", tick.get_text().replace("\u2212", "-")
        )
        if text and not re.fullmatch(r"[-+0-9.eE^x%]+", text):
            return True
    return False


def _shows_numbers(ax: Axes, axis) -> bool:
    """A visible axis with visible, non-categorical tick labels."""
    if not ax.axison or not axis.get_visible():
        return False
    if not any(t.get_visible() and t.get_text() for t in axis.get_ticklabels()):
        return False
    return not _is_categorical(axis)


def _axis_problems(ax: Axes, where: str) -> list[str]:
    problems = []
    for name, axis in (("x", ax.xaxis), ("y", ax.yaxis)):
        if not _shows_numbers(ax, axis):
            continue
        label = axis.get_label_text().strip()
        if not label:
            problems.append(f"{where}: the {name} axis has no label")
        elif not UNIT.search(label):
            problems.append(f"{where}: the {name} label {label!r} ends with no (unit)")
    return problems


def _title(ax: Axes) -> str:
    return " ".join(ax.get_title(loc) for loc in ("left", "center", "right")).strip()


def _legend_problems(fig: Figure, panel: list[Axes], where: str, renderer) -> list[str]:
    problems = []
    series = [s for ax in panel for s in _series(ax)]
    legends = _legends(fig, panel)
    if len(series) >= 2:
        if not legends:
            problems.append(f"{where}: {len(series)} series share the axes but there is no legend")
        else:
            named = {_colour(s) for s in series if _label(s)}
            for legend in legends:
                for handle in legend.legend_handles:
                    if handle is not None:
                        named.add(_colour(handle))
            for s in series:
                if not _label(s) and _colour(s) not in named:
                    problems.append(f"{where}: a series (colour {_colour(s)}) is in no legend")
    px_per_point = fig.dpi / 72.0
    for legend in legends:
        box = legend.get_window_extent(renderer).shrunk(1.0, 1.0)
        box = Bbox.from_extents(box.x0 + 1.0, box.y0 + 1.0, box.x1 - 1.0, box.y1 - 1.0)
        for ax in panel:
            clip = Bbox.intersection(box, ax.get_window_extent(renderer))
            if clip is None or clip.width <= 0 or clip.height <= 0:
                continue
            hidden = [a for a in _drawn(ax) if _covers(a, clip, px_per_point)]
            if hidden:
                names = ", ".join(sorted({_label(a) or type(a).__name__ for a in hidden}))
                problems.append(f"{where}: the legend covers data ({names})")
                break
    return problems


def check_figure(fig: Figure) -> list[str]:
    """Every way ``fig`` breaks the figure standard (an empty list when it meets it)."""
    if not isinstance(fig.canvas, FigureCanvasAgg):
        FigureCanvasAgg(fig)
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    problems: list[str] = []
    panels = [p for p in _panels(fig) if any(_has_data(ax) for ax in p)]
    suptitle = fig.get_suptitle().strip()
    for k, panel in enumerate(panels):
        titles = [t for t in (_title(ax) for ax in panel) if t]
        where = f"panel {k + 1}" + (f" ({titles[0]!r})" if titles else "")
        if not suptitle and not titles:
            problems.append(f"{where}: no title (and the figure has no suptitle)")
        for ax in panel:
            problems += _axis_problems(ax, where)
        problems += _legend_problems(fig, panel, where, renderer)
    if not panels:
        problems.append("the figure draws no data")
    return problems
