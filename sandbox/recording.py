"""Recordings: what a run looked like (body outlines once, poses per frame, optional series).

A :class:`Recording` is all :mod:`sandbox.render` needs to draw a run, so a lesson can record a
simulation once and render it several ways, or overlay several runs of the same scene.

Outlines are in each body's ORIGIN frame (the frame of ``body.position`` and ``body.angle``):
a circle is a :class:`CircleOutline` ``(center (2,), radius)``, a polygon an ``(V, 2)`` array of
counter-clockwise vertices. A frame is an ``(n, 3)`` array ``[x, y, angle]`` of every body's origin
(metres, radians).

Joints are noted once (:class:`JointOutline`: kind, the two body indices, the two anchors in the
bodies' origin frames) and their world anchor points stored per frame, ``(J, 2, 2)``. Water is a
list of ``fluids``: the surface heights (m) of the world's buoyancy generators.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any, NamedTuple

import numpy as np

BODY_TYPES = ("dynamic", "static", "kinematic")
JOINT_KINDS = ("pin", "pivot", "spring")  # drawn as: a line, a dot, a zig-zag


class CircleOutline(NamedTuple):
    """A circle in a body's origin frame: ``center`` (2,) in metres, ``radius`` in metres."""

    center: np.ndarray
    radius: float


Outline = CircleOutline | np.ndarray


class JointOutline(NamedTuple):
    """A joint to draw: ``kind`` (one of ``JOINT_KINDS``), body indices ``a`` and ``b``, and
    ``anchor_a``, ``anchor_b`` (2,) in the origin frames of those bodies (m)."""

    kind: str
    a: int
    b: int
    anchor_a: np.ndarray
    anchor_b: np.ndarray


def joint_outline(joint: Any, index: Mapping[int, int]) -> JointOutline:
    """The outline of one joint of the engine (``.type``, ``.a``, ``.b``, anchors).

    ``index`` maps ``id(body)`` to the body's place in the scene. A joint type without a
    drawing of its own (not in ``JOINT_KINDS``) is drawn as a pin: a line between its anchors.
    """
    kind = str(getattr(joint, "type", "pin"))
    return JointOutline(
        kind if kind in JOINT_KINDS else "pin",
        index[id(joint.a)],
        index[id(joint.b)],
        np.asarray(joint.anchor_a, dtype=float).reshape(2).copy(),
        np.asarray(joint.anchor_b, dtype=float).reshape(2).copy(),
    )


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


def _check_joint(joint: JointOutline, n: int, where: str) -> JointOutline:
    kind, a, b, qa, qb = joint
    if kind not in JOINT_KINDS:
        raise ValueError(f"{where}.kind: expected one of {', '.join(JOINT_KINDS)}, got {kind!r}")
    for name, i in (("a", a), ("b", b)):
        if not 0 <= int(i) < n:
            raise ValueError(f"{where}.{name}: body index {i} out of range for {n} bodies")
    qa = np.asarray(qa, dtype=float).reshape(2)
    qb = np.asarray(qb, dtype=float).reshape(2)
    if not (np.isfinite(qa).all() and np.isfinite(qb).all()):
        raise ValueError(f"{where}: anchors must be finite")
    return JointOutline(str(kind), int(a), int(b), qa, qb)


@dataclass
class Recording:
    """Geometry of ``n`` bodies plus a list of frames (poses of their origins) and series.

    ``names``, ``types`` ("dynamic" | "static" | "kinematic") and ``outlines`` are per body, in
    scene order. ``frames[k]`` is the ``(n, 3)`` array ``[x, y, angle]`` at time ``times[k]``
    (seconds). ``series[name][k]`` is an optional value per frame (e.g. energy), NaN where a
    frame did not record it.

    ``joints`` (:class:`JointOutline`) are drawn between bodies; ``joint_frames[k]`` is the
    ``(J, 2, 2)`` array of their world anchor points ``[[xa, ya], [xb, yb]]`` at frame ``k``
    (computed from the poses when not given). ``fluids`` are water surface heights (m): the
    water fills everything below each.
    """

    names: list[str]
    types: list[str]
    outlines: list[list[Outline]]
    frames: list[np.ndarray] = field(default_factory=list)
    times: list[float] = field(default_factory=list)
    series: dict[str, list[float]] = field(default_factory=dict)
    joints: list[JointOutline] = field(default_factory=list)
    joint_frames: list[np.ndarray] = field(default_factory=list)
    fluids: list[float] = field(default_factory=list)

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
        self.joints = [_check_joint(j, n, f"joints[{k}]") for k, j in enumerate(self.joints)]
        self.fluids = [float(y) for y in self.fluids]
        if not all(math.isfinite(y) for y in self.fluids):
            raise ValueError(f"fluids: surface heights must be finite, got {self.fluids}")
        if not self.joint_frames:
            self.joint_frames = [self.joint_points(p) for p in self.frames]
        if len(self.joint_frames) != len(self.frames):
            raise ValueError("joint_frames must have one entry per frame")

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
        index = {id(b): i for i, b in enumerate(bodies)}
        return cls(
            names=[str(b.name) for b in bodies],
            types=[str(b.type) for b in bodies],
            outlines=[[shape_outline(s) for s in b.shapes] for b in bodies],
            joints=[joint_outline(j, index) for j in getattr(world, "joints", ())],
            fluids=[
                float(f.surface_y)
                for f in getattr(world, "forces", ())
                if getattr(f, "type", None) == "buoyancy"
            ],
        )

    def joint_points(self, poses: np.ndarray) -> np.ndarray:
        """World anchor points ``(J, 2, 2)`` of the joints for one frame ``poses`` (n, 3).

        x = p + R(angle) q for each anchor q in its body's origin frame.
        """
        if not self.joints:
            return np.zeros((0, 2, 2))
        local = np.array([(j.anchor_a, j.anchor_b) for j in self.joints]).reshape(-1, 1, 2)
        body = np.array([(j.a, j.b) for j in self.joints], dtype=np.int64).ravel()
        return place(local, body, np.asarray(poses, dtype=float)).reshape(-1, 2, 2)

    def add_frame(
        self, poses: np.ndarray, time: float, joints: np.ndarray | None = None, **values: float
    ) -> None:
        """Append one frame: ``poses`` (n, 3) ``[x, y, angle]``, ``time`` (s), series values.

        ``joints``: the joints' world anchor points ``(J, 2, 2)`` (m); default: placed from
        ``poses``.
        """
        poses = np.array(poses, dtype=float)
        if poses.shape != (self.n_bodies, 3):
            raise ValueError(f"a frame must be ({self.n_bodies}, 3), got {poses.shape}")
        if joints is None:
            joints = self.joint_points(poses)
        joints = np.array(joints, dtype=float)
        if joints.shape != (len(self.joints), 2, 2):
            raise ValueError(
                f"a frame's joints must be ({len(self.joints)}, 2, 2), got {joints.shape}"
            )
        k = len(self.frames)
        self.frames.append(poses)
        self.joint_frames.append(joints)
        self.times.append(float(time))
        for name, value in values.items():
            # a series that starts late is NaN for the frames before it
            self.series.setdefault(name, [math.nan] * k).append(float(value))
        for values_so_far in self.series.values():
            if len(values_so_far) == k:
                values_so_far.append(math.nan)

    def capture(self, world: Any, **values: float) -> None:
        """Append the current poses of ``world``'s bodies and the world anchor points of its
        joints at ``world.time``, and series values."""
        poses = np.array(
            [(b.position[0], b.position[1], b.angle) for b in world.bodies], dtype=float
        ).reshape(-1, 3)
        self.add_frame(poses, world.time, self.joint_points(poses), **values)

    def poses(self) -> np.ndarray:
        """All frames stacked: ``(F, n, 3)``."""
        if not self.frames:
            return np.zeros((0, self.n_bodies, 3))
        return np.stack(self.frames)

    def joint_segments(self) -> np.ndarray:
        """All frames' joint anchor points stacked: ``(F, J, 2, 2)``."""
        if not self.joint_frames:
            return np.zeros((0, len(self.joints), 2, 2))
        return np.stack(self.joint_frames)


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


# a spring's zig-zag: straight leads at both ends, then ZIGZAG_PEAKS alternating peaks between
_LEAD = 0.15
ZIGZAG_PEAKS = 10
_ZIG_T = np.concatenate(
    [[0.0, _LEAD], _LEAD + (1 - 2 * _LEAD) * (np.arange(ZIGZAG_PEAKS) + 0.5) / ZIGZAG_PEAKS]
    + [[1 - _LEAD, 1.0]]
)
_ZIG_SIDE = np.concatenate([[0.0, 0.0], (-1.0) ** np.arange(ZIGZAG_PEAKS), [0.0, 0.0]])


def zigzag(ends: np.ndarray, half_width: float) -> np.ndarray:
    """Zig-zag polylines ``(S, Z, 2)`` between the two points of each row of ``ends`` (S, 2, 2).

    The peaks stand ``half_width`` (m) off the line from end 0 to end 1; a spring of length 0
    is drawn as a point.
    """
    pa, d = ends[:, 0], ends[:, 1] - ends[:, 0]
    length = np.hypot(d[:, 0], d[:, 1])
    scale = np.divide(half_width, length, out=np.zeros_like(length), where=length > 0)
    normal = np.stack([-d[:, 1], d[:, 0]], axis=1) * scale[:, None]  # |normal| = half_width
    return (
        pa[:, None, :]
        + _ZIG_T[None, :, None] * d[:, None, :]
        + _ZIG_SIDE[None, :, None] * normal[:, None, :]
    )


def bounds(
    shapes: OutlineArrays, poses: np.ndarray, points: np.ndarray | None = None
) -> np.ndarray | None:
    """``[xmin, xmax, ymin, ymax]`` of all shapes in all frames ``poses`` (F, n, 3), in metres,
    and of the extra ``points`` (..., 2) (e.g. joint anchors).

    Non-finite coordinates are ignored; None when there is nothing finite to bound.
    """
    lo, hi = np.full(2, np.inf), np.full(2, -np.inf)
    if points is not None and points.size:
        pts = points.reshape(-1, 2)
        pts = pts[np.isfinite(pts).all(axis=1)]
        if len(pts):
            lo, hi = pts.min(axis=0), pts.max(axis=0)
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
