"""Debug drawing over the bodies of an animation, as in the Box2D samples (layers: see
:mod:`sandbox.overlays`; colours, sizes and the key: :mod:`sandbox.layer_key`).

Speed: every layer is one or two matplotlib artists built once and handed new vertices per
frame, drawn over the bodies: a layer's lines (arrow shafts, boxes) are ONE line broken by NaNs,
its arrow heads ONE compound path, its points one line of markers; each is a single path for
the renderer however many bodies there are (a collection of many small paths costs far more).
Arrows are sized in pixels (heads, normals, torque arcs) or by a scale in metres per unit, one
scale per unit shared by every run and frame, so arrows compare across the whole animation.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np
from matplotlib.lines import Line2D
from matplotlib.patches import PathPatch
from matplotlib.path import Path

from sandbox.arrows import ArrowGeometry, arcs, arrows, auto_scale, boxes, nice_value
from sandbox.layer_key import (
    ARROWS,
    COLORS,
    HEAD_PX,
    HEAD_WIDTH_PX,
    MARKER_PX,
    NORMAL_PX,
    SHAFT_PX,
    SLEEP_FACE,
    TORQUE_RADIUS_PX,
    UNITS,
    WIDTH,
    KeyEntry,
)
from sandbox.outlines import OutlineArrays, place
from sandbox.overlays import DATA_OF_LAYER, LayerError, Layers
from sandbox.recording import Recording

TYPICAL, LONGEST = 0.1, 0.35  # typical and longest arrow, fractions of the view height
TYPICAL_SWEEP = 0.75 * math.pi  # a typical torque's arc (rad)
KEY_ARROW_PX = 48.0  # a key's reference arrow is at most this long (and over 0.4 of it)


def _check_recorded(runs: Sequence[Recording], names: tuple[str, ...]) -> None:
    for i, run in enumerate(runs):
        for name in names:
            kind = DATA_OF_LAYER.get(name)
            if kind is not None and kind not in run.overlays.recorded:
                raise LayerError(
                    f"layer {name!r} was not recorded in run {i}: "
                    f"record it with record(..., draw=({name!r}, ...))"
                )
            if name == "gravity" and (run.overlays.mass is None or run.overlays.gravity is None):
                raise LayerError(f"layer 'gravity' needs the bodies' masses (run {i})")


class LayerArtists:
    """The artists of ``layers`` over ``runs``, on axes ``ax`` whose pixels are ``mpp`` metres.

    ``px`` is the image's size factor (size_px / 480). :meth:`update` moves them to a frame;
    ``artists`` are drawn in order after the bodies; :meth:`key` lists the key's entries.
    """

    def __init__(
        self,
        ax: Any,
        runs: Sequence[Recording],
        shapes: Sequence[OutlineArrays],
        layers: Layers,
        mpp: float,
        px: float,
    ) -> None:
        self.runs, self.shapes, self.names = list(runs), list(shapes), layers.names
        _check_recorded(self.runs, self.names)
        self.mpp, self.px = mpp, px
        self.head = (HEAD_PX * px * mpp, HEAD_WIDTH_PX * px * mpp)
        height = mpp * ax.bbox.height  # the view's height (m)
        self.longest = LONGEST * height
        self.scales = self._scales(layers, TYPICAL * height)
        lw = max(0.72, SHAFT_PX * px * 0.72)  # points
        self.artists: list[Any] = []
        self.arrow_sets: dict[str, tuple[Line2D, PathPatch]] = {}

        def line(color: tuple, width: float) -> Line2D:
            (artist,) = ax.plot([], [], color=color, linewidth=width, solid_capstyle="butt")
            return artist

        self.aabb = self.levers = None
        if "aabbs" in self.names:
            self.aabb = line(COLORS["aabb"], 0.6 * lw)
            self.artists.append(self.aabb)
        if "joints" in self.names:
            self.levers = line(COLORS["joint"], 0.6 * lw)
            self.artists.append(self.levers)
        for kind, layer in ARROWS.items():  # wide arrows first, thin ones over them
            if layer in self.names:
                color = COLORS["force" if kind == "torque" else kind]
                shafts = line(color, WIDTH.get(kind, 1.0) * lw)
                heads = ax.add_patch(PathPatch(_EMPTY, facecolor=color, edgecolor="none"))
                self.arrow_sets[kind] = (shafts, heads)
                self.artists += [shafts, heads]
        ms = MARKER_PX * px
        self.markers: dict[str, Line2D] = {}
        for kind, style in (
            ("speculative", dict(marker="o", mfc="white", mec=COLORS["speculative"])),
            ("contact", dict(marker="o", mfc=COLORS["contact"], mec=COLORS["contact"])),
            ("com", dict(marker="o", mfc="white", mec=COLORS["com"])),
            ("com+", dict(marker="+", mec=COLORS["com"])),
            ("joint", dict(marker="s", mfc="white", mec=COLORS["joint"])),
        ):
            layer = {"contact": "contacts", "speculative": "contacts", "joint": "joints"}
            if layer.get(kind, "com") in self.names:
                size = ms * (1.6 if kind.startswith("com") else 1.0)
                (line,) = ax.plot(
                    [], [], linestyle="none", markersize=size, markeredgewidth=0.9 * lw, **style
                )
                self.markers[kind] = line
                self.artists.append(line)
        for artist in self.artists:
            artist.set_animated(True)
            artist.set_zorder(5)

    def _scales(self, layers: Layers, typical: float) -> dict[str, float]:
        """Metres per unit for each arrow kind (radians per N m for torque): given or chosen."""
        given = layers.scales()
        values: dict[str, list[np.ndarray]] = {"impulse": [], "force": [], "velocity": []}
        torque: list[np.ndarray] = []
        for run in self.runs:
            o = run.overlays
            if "impulses" in self.names:
                values["impulse"] += [c[:, 4:6] for c in o.contacts]
            if "forces" in self.names:
                values["force"] += [np.hypot(f[:, 0], f[:, 1]) for f in o.forces]
                torque += [f[:, 2] for f in o.forces]
            if "gravity" in self.names:
                values["force"].append(o.mass * float(np.hypot(*o.gravity)))
            if "velocities" in self.names:
                moving = np.array([t != "static" for t in run.types], dtype=bool)
                values["velocity"] += [np.hypot(v[moving, 0], v[moving, 1]) for v in o.velocities]
        # a speed that matters in this view: a tenth of what falling its height gives, so that
        # the jitter of bodies at rest is not blown up to a typical arrow
        g = max(
            (
                float(np.hypot(*r.overlays.gravity))
                for r in self.runs
                if r.overlays.gravity is not None
            ),
            default=0.0,
        )
        floor = {"velocity": 0.1 * math.sqrt(g * typical / TYPICAL)}
        scales = {}
        for key, parts in values.items():
            data = np.concatenate([p.ravel() for p in parts]) if parts else np.zeros(0)
            scales[key] = given[key] or auto_scale(data, typical, floor=floor.get(key, 0.0))
        data = np.concatenate(torque) if torque else np.zeros(0)
        scales["torque"] = given["torque"] or auto_scale(data, TYPICAL_SWEEP)
        return scales

    def faces(self, i: int, k: int, base: np.ndarray) -> np.ndarray | None:
        """Face colours of run ``i``'s shapes at frame ``k`` with sleeping bodies grey, or None
        when the sleep layer is off or the frame has no sleep flags."""
        if "sleep" not in self.names:
            return None
        asleep = self.runs[i].overlays.sleeping[k]
        if asleep is None:
            return None
        faces = base.copy()
        faces[asleep[self.shapes[i].body]] = SLEEP_FACE
        return faces

    def update(self, ks: Sequence[int], placed: Sequence[np.ndarray]) -> None:
        """Move every layer to frame ``ks[i]`` of each run; ``placed[i]`` are run i's shapes
        in the world at that frame (P, V, 2)."""
        parts: dict[str, list] = {}

        def add(kind: str, *arrays: np.ndarray) -> None:
            parts.setdefault(kind, []).append(arrays)

        for run, shapes, k, verts in zip(self.runs, self.shapes, ks, placed, strict=True):
            o, pose = run.overlays, run.frames[k]
            n = run.n_bodies
            centers = o.centers if o.centers is not None else np.zeros((n, 2))
            com = place(centers[:, None, :], np.arange(n), pose)[:, 0]
            moving = np.array([t != "static" for t in run.types], dtype=bool)
            if "contacts" in self.names or "normals" in self.names or "impulses" in self.names:
                c = o.contacts[k]
                touching = c[:, 6] >= 0.0
                add("contact", c[touching, :2])
                add("speculative", c[~touching, :2])
                add("normal", c[:, :2], c[:, 2:4])
                t = np.stack([c[:, 3], -c[:, 2]], axis=1)  # the solver's tangent (n_y, -n_x)
                add("normal impulse", c[:, :2], c[:, 2:4] * c[:, 4:5])
                add("friction impulse", c[:, :2], t * c[:, 5:6])
            if "forces" in self.names:
                f = o.forces[k]
                add("force", com, f[:, :2])
                add("torque", com, f[:, 2])
            if "gravity" in self.names:
                weight = o.mass[:, None] * o.gravity[None, :]
                add("gravity", com, weight)
            if "velocities" in self.names:
                add("velocity", com[moving], o.velocities[k][moving])
            if "com" in self.names:
                add("com", com[moving])
            if "joints" in self.names and run.joints:
                ends = run.joint_frames[k]  # (J, 2, 2)
                body = np.array([(j.a, j.b) for j in run.joints], dtype=np.int64).ravel()
                arms = np.stack([com[body], ends.reshape(-1, 2)], axis=1)
                add("joint", ends.reshape(-1, 2))
                add("lever", arms[moving[body]])  # a static body's arm turns nothing
            if "aabbs" in self.names and len(shapes.body):
                lo, hi = verts.min(axis=1), verts.max(axis=1)
                circle = shapes.radius > 0
                if circle.any():
                    mid = place(shapes.marker[circle, :1], shapes.body[circle], pose)[:, 0]
                    r = shapes.radius[circle, None]
                    lo[circle], hi[circle] = mid - r, mid + r
                add("aabb", boxes(lo, hi))
        self._apply(parts)

    def _apply(self, parts: dict[str, list]) -> None:
        def joined(kind: str, column: int = 0) -> np.ndarray:
            arrays = [p[column] for p in parts.get(kind, [])]
            return np.concatenate(arrays) if arrays else np.zeros((0, 2))

        for kind, line in self.markers.items():
            xy = joined("com" if kind == "com+" else kind).reshape(-1, 2)
            line.set_data(xy[:, 0], xy[:, 1])
        if self.aabb is not None:
            self.aabb.set_data(*polylines(joined("aabb")).T)
        if self.levers is not None:
            self.levers.set_data(*polylines(joined("lever")).T)
        for kind, (shafts, heads) in self.arrow_sets.items():
            tails, vectors = joined(kind, 0), joined(kind, 1)
            hl, hw = (WIDTH.get(kind, 1.0) ** 0.5 * h for h in self.head)
            if kind == "torque":
                radius = TORQUE_RADIUS_PX * self.px * self.mpp
                sweeps = np.clip(vectors * self.scales["torque"], -1.75 * math.pi, 1.75 * math.pi)
                geometry = arcs(tails, sweeps, radius, 0.8 * hl, 0.8 * hw)
            elif kind == "normal":
                unit = NORMAL_PX * self.px * self.mpp
                geometry = arrows(tails, vectors * unit, 0.8 * hl, 0.8 * hw)
            else:
                scale = self.scales[_unit_of(kind)]
                geometry = arrows(tails, vectors * scale, hl, hw, self.longest, 0.5 * self.mpp)
            _set(shafts, heads, geometry)

    def key(self) -> list[KeyEntry]:
        """The key's entries for the layers drawn, with each arrow's reference value."""
        out: list[KeyEntry] = []
        for name in self.names:
            out += self._key_of(name)
        return out

    def _reference(self, kind: str) -> tuple[float, str]:
        """A round value and its arrow length in pixels for ``kind``'s scale."""
        unit = _unit_of(kind)
        per_px = self.scales[unit] / self.mpp  # pixels per unit
        value = nice_value(KEY_ARROW_PX * self.px / per_px)
        return value * per_px, _format(value, UNITS[unit])

    def _key_of(self, name: str) -> list[KeyEntry]:
        c = COLORS
        if name == "contacts":
            return [
                KeyEntry("marker", c["contact"], "contact point"),
                KeyEntry("marker", c["speculative"], "not yet touching", filled=False),
            ]
        if name == "normals":
            length, width = 0.8 * NORMAL_PX * self.px, WIDTH["normal"]
            return [KeyEntry("arrow", c["normal"], "contact normal", length, width=width)]
        if name == "sleep":
            flags = any(x is not None for r in self.runs for x in r.overlays.sleeping)
            label = "asleep" if flags else "asleep (no sleep flags recorded)"
            return [KeyEntry("swatch", SLEEP_FACE, label)]
        if name == "aabbs":
            return [KeyEntry("box", c["aabb"], "AABB")]
        if name == "com":
            return [KeyEntry("marker", c["com"], "centre of mass", filled=False, marker="+o")]
        if name == "joints":
            return [KeyEntry("marker", c["joint"], "joint anchor", filled=False, marker="s")]
        kinds = {
            "impulses": ["normal impulse", "friction impulse"],
            "forces": ["force"],
            "gravity": ["gravity"],
            "velocities": ["velocity"],
        }[name]
        out = []
        for kind in kinds:
            length, value = self._reference(kind)
            label = {"force": "applied force", "gravity": "weight m g"}.get(kind, kind)
            width = WIDTH.get(kind, 1.0)
            out.append(KeyEntry("arrow", c[kind], f"{value} {label}", length, width=width))
        if name == "forces":  # a round torque whose arc turns at most half a turn
            torque = nice_value(math.pi / self.scales["torque"])
            sweep = torque * self.scales["torque"]
            label = f"{_format(torque, 'N m')} torque"
            out.append(KeyEntry("arc", c["force"], label, sweep, width=WIDTH["torque"]))
        return out

    def colors(self) -> list[tuple]:
        """RGB(A) colours drawn exactly (for a GIF's palette)."""
        return [*COLORS.values(), SLEEP_FACE]


def _unit_of(kind: str) -> str:
    return {"gravity": "force", "normal impulse": "impulse", "friction impulse": "impulse"}.get(
        kind, kind
    )


def _format(value: float, unit: str) -> str:
    text = f"{value:g}" if 1e-3 <= value < 1e5 else f"{value:.0e}"
    return f"{text} {unit}"


_EMPTY = Path(np.zeros((0, 2)))


def polylines(paths: np.ndarray) -> np.ndarray:
    """Polylines ``(S, V, 2)`` as one ``(S (V + 1), 2)`` array, each followed by a NaN row that
    breaks the line: all of them are one path for a single Line2D."""
    paths = np.asarray(paths, dtype=float)
    if paths.size == 0:
        return np.zeros((0, 2))
    out = np.full((paths.shape[0], paths.shape[1] + 1, 2), np.nan)
    out[:, :-1] = paths
    return out.reshape(-1, 2)


def polygons(polys: np.ndarray) -> Path:
    """Polygons ``(P, V, 2)`` as one compound path (filled with the non-zero rule: the heads
    all turn the same way, so overlaps stay filled)."""
    p, v = polys.shape[:2]
    if p == 0:
        return _EMPTY
    verts = np.concatenate([polys, polys[:, :1]], axis=1).reshape(-1, 2)
    codes = np.full((p, v + 1), Path.LINETO, dtype=Path.code_type)
    codes[:, 0], codes[:, -1] = Path.MOVETO, Path.CLOSEPOLY
    return Path(verts, codes.ravel())


def _set(shafts: Line2D, heads: PathPatch, geometry: ArrowGeometry) -> None:
    shafts.set_data(*polylines(geometry.shafts).T)
    heads.set_path(polygons(geometry.heads))
