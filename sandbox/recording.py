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
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any, NamedTuple

import numpy as np

from sandbox.energy import WorkMeter, energy_terms
from sandbox.outlines import (  # noqa: F401 (re-exported: lessons import them from here)
    CircleOutline,
    Outline,
    OutlineArrays,
    bounds,
    place,
    shape_outline,
    zigzag,
)
from sandbox.overlays import Overlays, parse_layers

BODY_TYPES = ("dynamic", "static", "kinematic")
JOINT_KINDS = ("pin", "pivot", "spring")  # drawn as: a line, a dot, a zig-zag


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

    ``overlays`` (:class:`~sandbox.overlays.Overlays`) hold what the debug-drawing layers need
    per frame (contacts, velocities, forces), recorded only for the layers asked for.
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
    overlays: Overlays = field(default_factory=Overlays)

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
        self.overlays.check(len(self.frames))

    @property
    def n_bodies(self) -> int:
        return len(self.names)

    def __len__(self) -> int:
        """Number of frames."""
        return len(self.frames)

    @classmethod
    def from_world(cls, world: Any, draw: str | Iterable[str] | None = ()) -> Recording:
        """The geometry of ``world``'s bodies (names, types, outlines), with no frame yet.

        ``draw``: the debug-drawing layers whose data :meth:`capture` will record.
        """
        bodies = list(world.bodies)
        if hasattr(world, "local_com"):
            overlays = Overlays.for_world(world, draw)
        else:  # a stand-in without the engine's arrays: only layers drawn from the geometry
            overlays = Overlays(layers=parse_layers(draw))
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
            overlays=overlays,
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
        self,
        poses: np.ndarray,
        time: float,
        joints: np.ndarray | None = None,
        overlay: Mapping[str, Any] | None = None,
        **values: float,
    ) -> None:
        """Append one frame: ``poses`` (n, 3) ``[x, y, angle]``, ``time`` (s), series values.

        ``joints``: the joints' world anchor points ``(J, 2, 2)`` (m); default: placed from
        ``poses``. ``overlay``: the frame's data for the recorded layers (see
        :meth:`sandbox.overlays.Overlays.add`, e.g. ``{"velocities": v}``).
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
        if self.overlays.recorded:
            self.overlays.add(self.n_bodies, overlay or {})
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
        overlay = self.overlays.frame_data(world) if self.overlays.recorded else None
        self.add_frame(poses, world.time, self.joint_points(poses), overlay, **values)

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


class Recorder:
    """Records a world while it runs: call :meth:`step_done` after each ``world.step()``.

    Captures the state when made, then every ``every`` steps: poses, ``series`` values, the data
    of the layers ``draw`` and, with ``energy``, the energy by part and the work done
    (:mod:`sandbox.energy`, measured over every step) as the series ``ENERGY_SERIES``.
    """

    def __init__(
        self,
        world: Any,
        every: int = 1,
        series: Mapping[str, Callable[[Any], float]] | None = None,
        draw: str | Iterable[str] | None = (),
        energy: bool = False,
    ) -> None:
        if every < 1:
            raise ValueError(f"need every >= 1, got every={every}")
        self.world, self.every, self.steps = world, int(every), 0
        self.series = dict(series or {})
        self.meter = WorkMeter(world) if energy else None
        self.recording = Recording.from_world(world, draw)
        self.capture()

    def capture(self) -> None:
        values = {name: fn(self.world) for name, fn in self.series.items()}
        if self.meter is not None:
            values.update(energy_terms(self.world), **{"energy.work": self.meter.work})
        self.recording.capture(self.world, **values)

    def step_done(self, world: Any = None) -> None:
        if self.meter is not None:
            self.meter.after()
        self.steps += 1
        if self.steps % self.every == 0:
            self.capture()


def record(
    world: Any,
    steps: int,
    every: int = 1,
    series: Mapping[str, Callable[[Any], float]] | None = None,
    draw: str | Iterable[str] | None = (),
    energy: bool = False,
) -> Recording:
    """Step ``world`` ``steps`` times, capturing the initial state and then every ``every`` steps.

    ``series`` maps a name to a function ``world -> float`` evaluated at each captured frame,
    e.g. ``{"energy": lambda w: w.kinetic_energy() + w.potential_energy()}``. ``draw`` names the
    debug-drawing layers to record data for (``"contacts,impulses"`` or a list; see
    :mod:`sandbox.overlays`); ``energy=True`` records the energies the ``"energy-bars"`` panel
    draws. Only what is asked for is kept.
    """
    if steps < 0:
        raise ValueError(f"need steps >= 0, got steps={steps}")
    recorder = Recorder(world, every, series, draw, energy)
    for _ in range(steps):
        world.step()
        recorder.step_done()
    return recorder.recording
