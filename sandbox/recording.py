"""Recordings: what a run looked like (body outlines once, poses per frame, optional series).

A :class:`Recording` is all :mod:`sandbox.render` needs to draw a run, so a lesson can record a
simulation once and render it several ways, or overlay several runs of the same scene.

Outlines are in each body's ORIGIN frame (the frame of ``body.position`` and ``body.angle``):
a circle is a :class:`CircleOutline` ``(center (2,), radius)``, a polygon an ``(V, 2)`` array of
counter-clockwise vertices. A frame is an ``(n, 3)`` array ``[x, y, angle]`` of every body's origin
(metres, radians).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any, NamedTuple

import numpy as np

BODY_TYPES = ("dynamic", "static", "kinematic")


class CircleOutline(NamedTuple):
    """A circle in a body's origin frame: ``center`` (2,) in metres, ``radius`` in metres."""

    center: np.ndarray
    radius: float


Outline = CircleOutline | np.ndarray


def shape_outline(shape: Any) -> Outline:
    """The outline of one shape of the engine (``.kind`` "circle" or "polygon")."""
    if shape.kind == "circle":
        center = np.asarray(getattr(shape, "offset", (0.0, 0.0)), dtype=float).reshape(2).copy()
        return CircleOutline(center, float(shape.radius))
    if shape.kind == "polygon":
        vertices = np.array(shape.vertices, dtype=float).reshape(-1, 2)
        return vertices
    raise ValueError(f"cannot draw a shape of kind {shape.kind!r}")


def _check_outline(outline: Outline, where: str) -> Outline:
    if isinstance(outline, tuple):
        center, radius = outline
        center = np.asarray(center, dtype=float).reshape(2)
        if not (math.isfinite(radius) and radius > 0):
            raise ValueError(f"{where}: circle radius must be a positive number, got {radius}")
        return CircleOutline(center, float(radius))
    vertices = np.asarray(outline, dtype=float)
    if vertices.ndim != 2 or vertices.shape[1] != 2 or len(vertices) < 3:
        raise ValueError(f"{where}: a polygon outline must be an (V>=3, 2) array")
    return vertices


@dataclass
class Recording:
    """Geometry of ``n`` bodies plus a list of frames (poses of their origins) and series.

    ``names``, ``types`` ("dynamic" | "static" | "kinematic") and ``outlines`` are per body, in
    scene order. ``frames[k]`` is the ``(n, 3)`` array ``[x, y, angle]`` at time ``times[k]``
    (seconds). ``series[name][k]`` is an optional value per frame (e.g. energy), NaN where a
    frame did not record it.
    """

    names: list[str]
    types: list[str]
    outlines: list[list[Outline]]
    frames: list[np.ndarray] = field(default_factory=list)
    times: list[float] = field(default_factory=list)
    series: dict[str, list[float]] = field(default_factory=dict)

    def __post_init__(self) -> None:
        n = len(self.names)
        if len(self.types) != n or len(self.outlines) != n:
            raise ValueError("names, types and outlines must have one entry per body")
        for i, kind in enumerate(self.types):
            if kind not in BODY_TYPES:
                raise ValueError(f"bodies[{i}].type: unknown body type {kind!r}")
        self.outlines = [
            [_check_outline(o, f"bodies[{i}].outlines[{j}]") for j, o in enumerate(outlines)]
            for i, outlines in enumerate(self.outlines)
        ]

    @property
    def n_bodies(self) -> int:
        return len(self.names)

    def __len__(self) -> int:
        """Number of frames."""
        return len(self.frames)

    @classmethod
    def from_world(cls, world: Any) -> Recording:
        """The geometry of ``world``'s bodies (names, types, outlines), with no frame yet."""
        bodies = list(world.bodies)
        return cls(
            names=[str(b.name) for b in bodies],
            types=[str(b.type) for b in bodies],
            outlines=[[shape_outline(s) for s in b.shapes] for b in bodies],
        )

    def add_frame(self, poses: np.ndarray, time: float, **values: float) -> None:
        """Append one frame: ``poses`` (n, 3) ``[x, y, angle]``, ``time`` (s), series values."""
        poses = np.array(poses, dtype=float)
        if poses.shape != (self.n_bodies, 3):
            raise ValueError(f"a frame must be ({self.n_bodies}, 3), got {poses.shape}")
        k = len(self.frames)
        self.frames.append(poses)
        self.times.append(float(time))
        for name, value in values.items():
            # a series that starts late is NaN for the frames before it
            self.series.setdefault(name, [math.nan] * k).append(float(value))
        for values_so_far in self.series.values():
            if len(values_so_far) == k:
                values_so_far.append(math.nan)

    def capture(self, world: Any, **values: float) -> None:
        """Append the current poses of ``world``'s bodies at ``world.time``, and series values."""
        poses = np.array(
            [(b.position[0], b.position[1], b.angle) for b in world.bodies], dtype=float
        ).reshape(-1, 3)
        self.add_frame(poses, world.time, **values)

    def poses(self) -> np.ndarray:
        """All frames stacked: ``(F, n, 3)``."""
        if not self.frames:
            return np.zeros((0, self.n_bodies, 3))
        return np.stack(self.frames)


def record(
    world: Any,
    steps: int,
    every: int = 1,
    series: Mapping[str, Callable[[Any], float]] | None = None,
) -> Recording:
    """Step ``world`` ``steps`` times, capturing the initial state and then every ``every`` steps.

    ``series`` maps a name to a function ``world -> float`` evaluated at each captured frame,
    e.g. ``{"energy": lambda w: w.kinetic_energy() + w.potential_energy()}``.
    """
    if steps < 0 or every < 1:
        raise ValueError(f"need steps >= 0 and every >= 1, got steps={steps}, every={every}")
    series = dict(series or {})
    rec = Recording.from_world(world)

    def capture() -> None:
        rec.capture(world, **{name: fn(world) for name, fn in series.items()})

    capture()
    for k in range(1, steps + 1):
        world.step()
        if k % every == 0:
            capture()
    return rec


@dataclass
class OutlineArrays:
    """Every shape of a recording as a polygon with the same vertex count, in array form.

    A circle becomes a regular ``circle_sides``-gon; shorter polygons are padded by repeating
    their last vertex, so all shapes are placed in the world with one numpy expression.
    """

    body: np.ndarray  # (P,) int64: the body owning each shape
    local: np.ndarray  # (P, V, 2) vertices in the body's origin frame
    marker: np.ndarray  # (P, 3, 2) orientation marker: centre, rim / first-edge midpoint, NaN
    static: np.ndarray  # (P,) bool: the owning body is static

    @classmethod
    def of(cls, rec: Recording, circle_sides: int = 20) -> OutlineArrays:
        angles = 2.0 * math.pi * np.arange(circle_sides) / circle_sides
        unit = np.stack([np.cos(angles), np.sin(angles)], axis=1)
        gap = (math.nan, math.nan)  # breaks the marker polyline between shapes
        body, polys, markers = [], [], []
        for i, outlines in enumerate(rec.outlines):
            for outline in outlines:
                if isinstance(outline, CircleOutline):
                    c, r = outline.center, outline.radius
                    polys.append(c + r * unit)
                    markers.append((c, c + (r, 0.0), gap))
                else:
                    polys.append(outline)
                    markers.append((outline.mean(axis=0), 0.5 * (outline[0] + outline[1]), gap))
                body.append(i)
        width = max([circle_sides] + [len(p) for p in polys])
        local = np.zeros((len(polys), width, 2))
        for j, p in enumerate(polys):
            local[j, : len(p)] = p
            local[j, len(p) :] = p[-1]
        return cls(
            body=np.array(body, dtype=np.int64),
            local=local,
            marker=np.array(markers, dtype=float).reshape(-1, 3, 2),
            static=np.array([rec.types[b] == "static" for b in body], dtype=bool),
        )


def place(local: np.ndarray, body: np.ndarray, poses: np.ndarray) -> np.ndarray:
    """World coordinates of body-frame points ``local`` (P, V, 2): x = p + R(angle) q.

    ``body`` (P,) picks each row's pose from ``poses`` (..., n, 3); leading frame axes broadcast,
    so one call places every shape of one frame, or of a block of frames.
    """
    pose = poses[..., body, :]
    c = np.cos(pose[..., 2])[..., None]
    s = np.sin(pose[..., 2])[..., None]
    qx, qy = local[..., 0], local[..., 1]
    out = np.empty(pose.shape[:-1] + local.shape[-2:])
    out[..., 0] = c * qx - s * qy + pose[..., 0, None]
    out[..., 1] = s * qx + c * qy + pose[..., 1, None]
    return out


def bounds(shapes: OutlineArrays, poses: np.ndarray) -> np.ndarray | None:
    """``[xmin, xmax, ymin, ymax]`` of all shapes in all frames ``poses`` (F, n, 3), in metres.

    Non-finite coordinates are ignored; None when there is nothing finite to bound.
    """
    lo, hi = np.full(2, np.inf), np.full(2, -np.inf)
    chunk = max(1, 2_000_000 // max(1, shapes.local.size))  # frames per block, bounded memory
    for k in range(0, len(poses), chunk):
        block = poses[k : k + chunk]
        if len(shapes.body):
            pts = place(shapes.local, shapes.body, block).reshape(-1, 2)
        else:
            pts = block[..., :2].reshape(-1, 2)
        pts = pts[np.isfinite(pts).all(axis=1)]
        if len(pts):
            lo = np.minimum(lo, pts.min(axis=0))
            hi = np.maximum(hi, pts.max(axis=0))
    if not np.isfinite(lo).all():
        return None
    return np.array([lo[0], hi[0], lo[1], hi[1]])
