"""Drawing frames: one or several runs of a scene overlaid on matplotlib's Agg canvas.

One colour per run (as Box2D's Solver2D testbed does), static bodies grey, each shape with an
orientation marker (centre to rim for a circle, centre to the middle of the first edge for a
polygon). Joints are drawn in their run's colour, thinner: a pin as a line between its anchors, a
spring as a zig-zag, a pivot as a dot; water (a recording's ``fluids``) as a translucent blue band
below its surface. An optional side panel plots recorded series (energy, momentum, ...) against
time with a moving cursor.

Speed: the figure and its artists are built once; each frame only moves vertices. Every shape
is a polygon (a circle is a ``circle_sides``-gon) padded to a common vertex count, so all
shapes of a run are placed in one numpy expression and handed to one ``PolyCollection``; the
static parts of the figure are drawn once and restored from a saved background (blitting).
Likewise the pins and springs of a run are one ``LineCollection`` and its pivots one line of
markers, and the water is part of the background.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.collections import LineCollection, PolyCollection
from matplotlib.colors import to_rgba
from matplotlib.figure import Figure
from matplotlib.patches import Patch
from matplotlib.text import Text
from PIL import Image

from sandbox.debug_draw import LayerArtists
from sandbox.energy_bars import PANEL, EnergyBars
from sandbox.frame_text import FrameText
from sandbox.layer_key import COLORS as LAYER_COLORS
from sandbox.layer_key import SLEEP_FACE, draw_key, key_layout
from sandbox.legend_layer import LegendLayer
from sandbox.outlines import OutlineArrays, bounds, place, zigzag
from sandbox.overlays import Layers
from sandbox.recording import Recording
from sandbox.series_panels import SeriesPanels

DEFAULT_COLORS = ("C0", "C1", "C2", "C3", "C4", "C5", "C6", "C8", "C9")
STATIC_FACE = (0.62, 0.62, 0.62, 0.7)
STATIC_EDGE = (0.35, 0.35, 0.35, 1.0)
FILL_ALPHA = 0.4
WATER_FACE = (0.16, 0.45, 0.85, 0.25)
WATER_EDGE = (0.16, 0.45, 0.85, 0.9)
JOINT_WIDTH = 0.75  # joint lines, as a fraction of the outline width (never below one pixel)
SPRING_HALF_WIDTH_PX = 4.0  # a spring's zig-zag peaks, pixels off its axis at 480 px
_DPI = 100
CIRCLE_SIDES = 20  # a circle is drawn as a regular polygon of this many sides
PROGRESS_FRAMES = 50  # renders longer than this show a progress bar (on a terminal)


def _fit_view(view: Sequence[float], aspect: float, margin: float) -> tuple[float, ...]:
    """Grow ``view`` by ``margin`` (fraction of its size), then to width/height = ``aspect``."""
    xmin, xmax, ymin, ymax = (float(v) for v in view)
    size = max(xmax - xmin, ymax - ymin)
    pad = margin * size if size > 0 else 1.0
    xmin, xmax, ymin, ymax = xmin - pad, xmax + pad, ymin - pad, ymax + pad
    w, h = xmax - xmin, ymax - ymin
    cx, cy = 0.5 * (xmin + xmax), 0.5 * (ymin + ymax)
    if w / h < aspect:
        w = h * aspect
    else:
        h = w / aspect
    return cx - 0.5 * w, cx + 0.5 * w, cy - 0.5 * h, cy + 0.5 * h


def as_runs(runs: Recording | Sequence[Recording]) -> list[Recording]:
    if isinstance(runs, Recording):
        return [runs]
    runs = list(runs)
    if not runs or not all(isinstance(r, Recording) for r in runs):
        raise TypeError("runs must be a Recording or a non-empty list of Recordings")
    return runs


class FrameRenderer:
    """A figure built once for ``runs``; :meth:`frame` returns the RGB pixels of frame ``k``.

    ``runs``: a Recording or a list of them (same scene, same duration), overlaid in
    ``colors`` (default matplotlib's cycle) with a legend of ``labels``. ``panel``: a series
    name or list of names plotted beside the scene against time. ``trail``: True draws each
    moving body's origin path so far, an int only its last ``trail`` frames. ``view``:
    ``(xmin, xmax, ymin, ymax)`` in metres (default: every shape in every frame), grown by
    ``margin`` and to equal aspect. ``axes``: draw ticks in metres. ``draw``: debug-drawing
    layers (``"contacts,impulses"``, a list, or a :class:`~sandbox.overlays.Layers` with arrow
    scales; see :mod:`sandbox.overlays`) over the bodies, with a key below the scene.
    ``panel="energy-bars"`` draws the energy bars (:mod:`sandbox.energy_bars`) beside it.

    Image size: the scene is ``size_px`` square; a panel adds ``size_px`` to the width, the
    layers' key a strip to the height. Labels and title are drawn exactly as given (no
    mathtext: they often hold scene and body names).
    """

    def __init__(
        self,
        runs: Recording | Sequence[Recording],
        size_px: int = 480,
        labels: Sequence[str] | None = None,
        colors: Sequence[Any] | None = None,
        panel: str | Sequence[str] | None = None,
        trail: bool | int = False,
        view: Sequence[float] | None = None,
        margin: float = 0.05,
        axes: bool = False,
        show_time: bool = True,
        title: str | None = None,
        draw: str | Sequence[str] | Layers | None = None,
    ) -> None:
        self.runs = as_runs(runs)
        for r in self.runs:
            if len(r) == 0:
                raise ValueError("a recording to render needs at least one frame")
        if size_px < 16:
            raise ValueError(f"size_px must be at least 16, got {size_px}")
        self.n_frames = max(len(r) for r in self.runs)
        self.poses = [r.poses() for r in self.runs]
        self.shapes = [OutlineArrays.of(r, CIRCLE_SIDES) for r in self.runs]
        self.joint_ends = [r.joint_segments() for r in self.runs]  # (F, J, 2, 2) per run
        self.fluids = sorted({y for r in self.runs for y in r.fluids})
        colors = list(colors) if colors is not None else list(DEFAULT_COLORS)
        if len(colors) < len(self.runs):
            raise ValueError(f"{len(self.runs)} runs need as many colors, got {len(colors)}")
        self.colors = [to_rgba(c) for c in colors[: len(self.runs)]]
        if labels is None and len(self.runs) > 1:
            labels = [f"run {i + 1}" for i in range(len(self.runs))]
        if labels is not None and len(labels) != len(self.runs):
            raise ValueError(f"{len(self.runs)} runs need as many labels, got {len(labels)}")
        panels = [panel] if isinstance(panel, str) else list(panel or [])
        self.energy = PANEL in panels
        if self.energy and len(panels) > 1:
            raise ValueError(f"panel {PANEL!r} cannot share the panel with series {panels}")
        for name in [] if self.energy else panels:
            for i, r in enumerate(self.runs):
                if name not in r.series:
                    raise KeyError(f"run {i} has no series {name!r} (has {sorted(r.series)})")
        self.trail = int(trail) if not isinstance(trail, bool) else (-1 if trail else 0)

        layers = Layers.of(draw)
        scale = size_px / 480.0
        width_px = size_px + (size_px if panels else 0)
        fontsize = max(5.0, 9.0 * scale)
        em = fontsize * _DPI / 72.0  # font size in pixels
        key_columns, key_px = key_layout(layers.names, width_px, scale, em)
        self.key_px = int(math.ceil(key_px))  # rows of the key strip at the bottom
        height_px = size_px + self.key_px
        self.fig = Figure(figsize=(width_px / _DPI, height_px / _DPI), dpi=_DPI)
        self.canvas = FigureCanvasAgg(self.fig)

        def rect(x: float, y: float, w: float, h: float) -> tuple[float, ...]:
            """Figure fractions of a box in pixels, y from the bottom of the scene."""
            return (x / width_px, (y + self.key_px) / height_px, w / width_px, h / height_px)

        self._rect = rect
        pad = 3.2 * em if axes else 0.0  # room for tick labels
        top = 0.3 * pad + (1.8 * em if title else 0.0)
        box_w, box_h = size_px - 1.3 * pad, size_px - pad - top
        ax = self.fig.add_axes(rect(pad, pad, box_w, box_h))
        self.ax = ax
        if not axes:
            ax.set_axis_off()
        ax.tick_params(labelsize=fontsize)
        if view is None:
            found = [
                bounds(s, p, j)
                for s, p, j in zip(self.shapes, self.poses, self.joint_ends, strict=True)
            ]
            b = np.array([f for f in found if f is not None]).reshape(-1, 4)
            if len(b):
                view = (b[:, 0].min(), b[:, 1].max(), b[:, 2].min(), b[:, 3].max())
                if self.fluids:  # the water's surface is in view
                    y = [view[2], view[3], *self.fluids]
                    view = (view[0], view[1], min(y), max(y))
            else:
                view = (-1.0, 1.0, -1.0, 1.0)  # nothing finite to show
        else:
            margin = 0.0
        self.view = _fit_view(view, box_w / box_h, margin)
        ax.set_xlim(self.view[0], self.view[1])
        ax.set_ylim(self.view[2], self.view[3])
        if title:
            ax.set_title(title, fontsize=fontsize, parse_math=False)  # literal: user text

        lw = max(0.72, 1.0 * scale)  # points; never thinner than one pixel (0.72 pt at 100 dpi)
        jlw = max(0.72, JOINT_WIDTH * lw)
        self._draw_water(jlw)
        metres_per_px = (self.view[3] - self.view[2]) / box_h
        self.spring_half_width = SPRING_HALF_WIDTH_PX * scale * metres_per_px
        self.polys, self.markers, self.trails = [], [], []
        self.joint_lines, self.pivots, self.faces = [], [], []
        for color, shapes, run in zip(self.colors, self.shapes, self.runs, strict=True):
            kinds = np.array([j.kind for j in run.joints], dtype=object)
            lines = np.flatnonzero(kinds != "pivot")
            springs = kinds[lines] == "spring"
            line = None
            if len(lines):
                line = LineCollection([], colors=[color], linewidths=jlw, animated=True)
                ax.add_collection(line)
            self.joint_lines.append((lines, springs, line))
            pivots = np.flatnonzero(kinds == "pivot")
            dot = None
            if len(pivots):
                (dot,) = ax.plot(
                    [],
                    [],
                    linestyle="none",
                    marker="o",
                    markersize=max(2.5, 4.0 * scale),
                    markerfacecolor="white",
                    markeredgecolor=color,
                    markeredgewidth=jlw,
                    animated=True,
                )
            self.pivots.append((pivots, dot))
            face = np.tile((*color[:3], FILL_ALPHA), (len(shapes.body), 1))
            edge = np.tile(color, (len(shapes.body), 1))
            face[shapes.static], edge[shapes.static] = STATIC_FACE, STATIC_EDGE
            self.faces.append(face)
            poly = PolyCollection(
                [], facecolors=face, edgecolors=edge, linewidths=lw, animated=True
            )
            ax.add_collection(poly)
            self.polys.append(poly)
            # markers: one polyline broken by NaNs per colour (moving bodies, static bodies)
            markers = []
            for mask, c in ((~shapes.static, color), (shapes.static, STATIC_EDGE)):
                if mask.any():
                    (line,) = ax.plot([], [], color=c, linewidth=lw, animated=True)
                    markers.append((np.flatnonzero(mask), line))
            self.markers.append(markers)
            if self.trail:
                line = LineCollection(
                    [], colors=[(*color[:3], 0.6)], linewidths=0.8 * lw, animated=True
                )
                ax.add_collection(line)
                self.trails.append(line)
        self.movers = [np.array([t != "static" for t in r.types], dtype=bool) for r in self.runs]
        self.layers = None
        if layers.names:
            self.layers = LayerArtists(ax, self.runs, self.shapes, layers, metres_per_px, scale)
            key_ax = self.fig.add_axes((0.0, 0.0, 1.0, self.key_px / height_px))
            draw_key(key_ax, self.layers.key(), key_columns, scale, fontsize)
        self.animated: list[Any] = [*self.trails]  # drawn over the saved background, in order
        for i, (poly, markers) in enumerate(zip(self.polys, self.markers, strict=True)):
            joints, pivots = self.joint_lines[i][2], self.pivots[i][1]
            self.animated += [joints] if joints is not None else []  # strings under the bodies
            self.animated += [poly, *(line for _, line in markers)]
            self.animated += [pivots] if pivots is not None else []  # hinges on top
        if self.layers is not None:  # over every run's bodies
            self.animated += self.layers.artists
        self.legend = None
        if labels is not None:
            handles = [
                Patch(facecolor=(*c[:3], FILL_ALPHA), edgecolor=c, label=str(lab))
                for c, lab in zip(self.colors, labels, strict=True)
            ]
            legend = ax.legend(handles=handles, loc="upper right", fontsize=fontsize)
            for text in legend.get_texts():
                text.set_parse_math(False)  # a scene or body name with "$" is shown as typed
            legend.set_animated(True)  # not in the background: laid over each frame instead
            self.legend = legend
        self.time_text = None
        if show_time:
            self.time_text = ax.text(
                0.02,
                0.98,
                "",
                transform=ax.transAxes,
                ha="left",
                va="top",
                fontsize=fontsize,
                animated=True,
            )
            self.animated.append(self.time_text)
        self.bars = self.series = None
        if self.energy:
            em = fontsize * _DPI / 72.0
            box = rect(size_px + 10.5 * em, 6.6 * em, size_px - 12.0 * em, size_px - 8.6 * em)
            self.bars = EnergyBars(self.fig.add_axes(box), self.runs, self.colors, fontsize)
            self.animated += self.bars.artists
        elif panels:
            self.series = SeriesPanels(
                self.fig, rect, self.runs, self.colors, panels, size_px, scale, fontsize
            )
            self.animated += self.series.artists
        # the strings that change every frame (the time, the joules) are drawn by Pillow
        texts = [artist for artist in self.animated if isinstance(artist, Text)]
        self.animated = [artist for artist in self.animated if not isinstance(artist, Text)]
        self.texts = FrameText(texts, self.canvas)
        self.canvas.draw()
        self.background = self.canvas.copy_from_bbox(self.fig.bbox)
        self.legend_layer = None
        if self.legend is not None:  # drawn once, over the bodies in every frame
            width, height = self.canvas.get_width_height()
            self.legend_layer = LegendLayer(self.legend, width, height, self.fig.dpi)

    def _draw_water(self, linewidth: float) -> None:
        """Each fluid as a translucent band from below the view up to its surface (background)."""
        ymin, ymax = self.view[2], self.view[3]
        for surface in self.fluids:
            if surface <= ymin:
                continue
            top = min(surface, ymax + (ymax - ymin))
            self.ax.axhspan(ymin - (ymax - ymin), top, color=WATER_FACE, linewidth=0, zorder=0.5)
            if surface < ymax:
                self.ax.axhline(surface, color=WATER_EDGE, linewidth=linewidth, zorder=0.6)

    @property
    def size(self) -> tuple[int, int]:
        """Image (width, height) in pixels."""
        w, h = self.canvas.get_width_height()
        return int(w), int(h)

    def frame(self, k: int) -> np.ndarray:
        """RGB pixels ``(height, width, 3)`` uint8 of frame ``k`` (negative counts from the end)."""
        rgb = self._draw(k)[..., :3].copy()
        return rgb if self.legend_layer is None else self.legend_layer.over(rgb)

    def image(self, k: int) -> Image.Image:
        """Frame ``k`` as an RGB image: the pixels of :meth:`frame`, taken from the canvas by
        Pillow (a quarter of the time numpy takes to copy three of its four channels: 0.5
        against 2.0 ms at 960 x 480, for every frame of an animation)."""
        rgba = self._draw(k)
        if self.legend_layer is not None:  # over the canvas itself: restored next frame
            self.legend_layer.over(rgba[..., :3])
        height, width = rgba.shape[:2]
        return Image.frombuffer("RGBA", (width, height), rgba, "raw", "RGBA", 0, 1).convert("RGB")

    def _draw(self, k: int) -> np.ndarray:
        """Draw frame ``k`` on the canvas; its RGBA pixels (a view of the canvas)."""
        if not -self.n_frames <= k < self.n_frames:
            raise IndexError(f"frame {k} out of range for {self.n_frames} frames")
        k %= self.n_frames
        ks = [min(k, len(r) - 1) for r in self.runs]
        placed: list[np.ndarray] = []
        for i, (shapes, poses) in enumerate(zip(self.shapes, self.poses, strict=True)):
            pose = poses[ks[i]]
            placed.append(place(shapes.local, shapes.body, pose))
            self.polys[i].set_verts(placed[i])
            if self.layers is not None and "sleep" in self.layers.names:
                faces = self.layers.faces(i, ks[i], self.faces[i])
                self.polys[i].set_facecolor(self.faces[i] if faces is None else faces)
            ends = place(shapes.marker, shapes.body, pose)
            for index, line in self.markers[i]:
                xy = ends[index].reshape(-1, 2)
                line.set_data(xy[:, 0], xy[:, 1])
            lines, springs, joint_line = self.joint_lines[i]
            if joint_line is not None:
                seg = self.joint_ends[i][ks[i], lines]
                paths = list(seg)
                if springs.any():
                    zig = zigzag(seg[springs], self.spring_half_width)
                    for j, path in zip(np.flatnonzero(springs), zig, strict=True):
                        paths[j] = path
                joint_line.set_segments(paths)
            pivots, dot = self.pivots[i]
            if dot is not None:
                at = self.joint_ends[i][ks[i], pivots].mean(axis=1)  # the two anchors, held
                dot.set_data(at[:, 0], at[:, 1])
            if self.trail:
                start = 0 if self.trail < 0 else max(0, ks[i] - self.trail + 1)
                path = poses[start : ks[i] + 1][:, self.movers[i], :2]
                self.trails[i].set_segments(path.transpose(1, 0, 2))
        if self.layers is not None:
            self.layers.update(ks, placed)
        if self.bars is not None:
            self.bars.update(ks)
        times = [r.times[kr] for r, kr in zip(self.runs, ks, strict=True)]
        if self.time_text is not None:
            self.time_text.set_text(f"t = {times[0]:.2f} s")
        if self.series is not None:
            self.series.update(ks, times)
        self.canvas.restore_region(self.background)
        for artist in self.animated:
            artist.axes.draw_artist(artist)
        return self.texts.over(np.asarray(self.canvas.buffer_rgba()))  # over all of them

    def palette_colors(self) -> np.ndarray:
        """RGB uint8 colours this renderer draws with (run fills and edges, greys, white)."""
        cols = [(1, 1, 1, 1), (0, 0, 0, 1), STATIC_EDGE, STATIC_FACE, (0.2, 0.2, 0.2, 1)]
        if self.fluids:
            cols += [WATER_FACE, WATER_EDGE]
        for c in self.colors:
            cols += [c, (*c[:3], FILL_ALPHA), (*c[:3], 0.6)]
        # the layers' colours always: a drawn GIF and a plain one share their palette
        cols += [to_rgba(c) for c in (*LAYER_COLORS.values(), SLEEP_FACE)]
        if self.bars is not None:
            cols += [to_rgba(c) for c in self.bars.colors()]
        rgb = [np.array(c[:3]) * c[3] + (1.0 - c[3]) for c in cols]  # over a white background
        return np.clip(np.round(np.array(rgb) * 255), 0, 255).astype(np.uint8)

    def close(self) -> None:
        self.fig.clear()

    def __enter__(self) -> FrameRenderer:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()
