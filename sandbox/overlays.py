"""Debug-drawing layers (as in the Box2D samples): their names, and what each needs per frame.

A layer draws one kind of inside information over the bodies of an animation:

========== ===========================================================================
contacts   contact points of the last step (filled: touching; hollow: speculative, not yet
           touching, within the contact margin)
normals    contact normals, drawn a fixed length, pointing into the body pushed
impulses   normal and friction impulses of the last step at each contact point (N s)
forces     forces and torques applied in the last step (controllers, thrust, constant body
           forces: ``world.applied_force`` at the centre of mass, ``world.applied_torque``)
gravity    each dynamic body's weight m g at its centre of mass (N, the forces' scale)
velocities velocity of each moving body's centre of mass (m/s)
aabbs      axis-aligned bounding box of every shape
com        centre of mass of every body
joints     joint anchors, and the lever arm from each body's centre of mass to its anchor
sleep      bodies that sleep drawn grey (from an optional per-body flag ``world.sleeping``)
========== ===========================================================================

Only the layers asked for are recorded (:class:`Overlays`): contacts (for contacts, normals
and impulses) as one ``(P, 7)`` array per frame, velocities ``(n, 2)``, forces ``(n, 3)``,
sleeping ``(n,)`` bool or None. The other layers are drawn from the recording's geometry.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

LAYERS: dict[str, str] = {
    "contacts": "contact points",
    "normals": "contact normals",
    "impulses": "normal and friction impulses (N s)",
    "forces": "applied forces (N) and torques (N m)",
    "gravity": "weights m g (N)",
    "velocities": "velocities (m/s)",
    "aabbs": "bounding boxes",
    "com": "centres of mass",
    "joints": "joint anchors",
    "sleep": "sleeping bodies in grey",
}

# the per-frame data a layer reads (layers not listed draw from the recording's geometry)
DATA_OF_LAYER = {
    "contacts": "contacts",
    "normals": "contacts",
    "impulses": "contacts",
    "forces": "forces",
    "velocities": "velocities",
    "sleep": "sleeping",
}

# what a trace of poses and velocities (e.g. a pymunk run) can draw
FROM_TRACE = ("velocities", "aabbs", "com", "joints", "gravity")

# one contact point per row: where, the normal (unit, into the body the impulse is drawn on),
# the normal and friction impulses on that body (N s), the depth (m, < 0: not yet touching)
CONTACT_COLUMNS = ("x", "y", "nx", "ny", "jn", "jt", "depth")


class LayerError(ValueError):
    """An unknown or unavailable layer; ``message`` says which (without the option name)."""

    def __init__(self, message: str) -> None:
        super().__init__(f"draw: {message}")
        self.message = message


def parse_layers(draw: str | Iterable[str] | None) -> tuple[str, ...]:
    """Layer names from ``"contacts,normals"``, a list of names, or None (no layer).

    ``"all"`` names every layer. Order is kept, repeats dropped; an unknown name raises
    :class:`LayerError` naming it and the known ones.
    """
    if draw is None:
        return ()
    names = draw.split(",") if isinstance(draw, str) else list(draw)
    out: list[str] = []
    for name in names:
        name = str(name).strip()
        if not name:
            continue
        chosen = list(LAYERS) if name == "all" else [name]
        for layer in chosen:
            if layer not in LAYERS:
                known = ", ".join(LAYERS)
                raise LayerError(f"unknown layer {name!r} (known: {known}, or all)")
            if layer not in out:
                out.append(layer)
    return tuple(out)


@dataclass
class Layers:
    """Layers to draw, with optional arrow scales: ``Layers("impulses,forces", force=0.05)``.

    A scale is metres of arrow per unit: ``impulse`` (m per N s), ``force`` (m per N, also for
    gravity), ``velocity`` (m per m/s); ``torque`` is radians of arc per N m. A scale left None
    is chosen from the recording so that typical arrows are about a tenth of the view.
    """

    names: tuple[str, ...] = ()
    impulse: float | None = None
    force: float | None = None
    velocity: float | None = None
    torque: float | None = None

    def __init__(
        self,
        names: str | Iterable[str] | None = (),
        impulse: float | None = None,
        force: float | None = None,
        velocity: float | None = None,
        torque: float | None = None,
    ) -> None:
        self.names = parse_layers(names)
        for key, value in (
            ("impulse", impulse),
            ("force", force),
            ("velocity", velocity),
            ("torque", torque),
        ):
            if value is not None and not (np.isfinite(value) and value > 0):
                raise LayerError(f"{key} scale must be a finite number > 0, got {value}")
            setattr(self, key, None if value is None else float(value))

    @classmethod
    def of(cls, draw: str | Iterable[str] | Layers | None) -> Layers:
        """``draw`` as a :class:`Layers` (names are parsed and checked)."""
        return draw if isinstance(draw, Layers) else cls(draw)

    def scales(self) -> dict[str, float | None]:
        return {
            "impulse": self.impulse,
            "force": self.force,
            "velocity": self.velocity,
            "torque": self.torque,
        }


def contact_rows(manifolds: Any, kind: np.ndarray) -> np.ndarray:
    """One ``(P, 7)`` row per contact point of ``manifolds`` (see ``CONTACT_COLUMNS``).

    The solver's impulse P = jn n + jt t, t = (n_y, -n_x), acts on body b (and -P on a). It is
    drawn on b, unless b does not move and a does: then on a, with n and t reversed (jn and jt
    keep their values). ``kind`` (n,) is the bodies' type code (0 dynamic).
    """
    if manifolds is None or len(manifolds) == 0:
        return np.zeros((0, len(CONTACT_COLUMNS)))
    count = np.asarray(manifolds.count)
    used = np.arange(2)[None, :] < count[:, None]  # (k, 2) slots that hold a point
    normal = np.asarray(manifolds.normal, dtype=float)
    flip = (kind[manifolds.b] != 0) & (kind[manifolds.a] == 0)
    normal = np.where(flip[:, None], -normal, normal)
    rows = np.empty((int(used.sum()), len(CONTACT_COLUMNS)))
    rows[:, 0:2] = np.asarray(manifolds.point)[used]
    rows[:, 2:4] = np.broadcast_to(normal[:, None, :], (len(count), 2, 2))[used]
    rows[:, 4] = np.asarray(manifolds.normal_impulse)[used]
    rows[:, 5] = np.asarray(manifolds.tangent_impulse)[used]
    rows[:, 6] = np.asarray(manifolds.depth)[used]
    return rows


@dataclass
class Overlays:
    """The per-frame data of the layers asked for, plus the bodies' constant properties.

    ``centers`` (n, 2): each body's centre of mass in its origin frame (m); ``mass`` (n,) kg of
    dynamic bodies (0 for others); ``gravity`` (2,) m/s^2. Per frame, for the data the layers
    need (``DATA_OF_LAYER``): ``contacts`` (P, 7) rows, ``velocities`` (n, 2) m/s of the centres
    of mass, ``forces`` (n, 3) ``[fx, fy, torque]`` (N, N m), ``sleeping`` (n,) bool or None.
    """

    layers: tuple[str, ...] = ()
    centers: np.ndarray | None = None
    mass: np.ndarray | None = None
    gravity: np.ndarray | None = None
    contacts: list[np.ndarray] = field(default_factory=list)
    velocities: list[np.ndarray] = field(default_factory=list)
    forces: list[np.ndarray] = field(default_factory=list)
    sleeping: list[np.ndarray | None] = field(default_factory=list)

    def __post_init__(self) -> None:
        self.layers = parse_layers(self.layers)

    @property
    def recorded(self) -> tuple[str, ...]:
        """The kinds of per-frame data kept (``contacts``, ``velocities``, ``forces``, ...)."""
        kinds = {DATA_OF_LAYER[name] for name in self.layers if name in DATA_OF_LAYER}
        return tuple(k for k in ("contacts", "velocities", "forces", "sleeping") if k in kinds)

    @classmethod
    def for_world(cls, world: Any, draw: str | Iterable[str] | None = ()) -> Overlays:
        """Empty overlays for ``world``'s bodies, recording what the layers ``draw`` need."""
        dynamic = np.asarray(world.kind) == 0
        return cls(
            layers=parse_layers(draw),
            centers=np.array(world.local_com, dtype=float).reshape(-1, 2),
            mass=np.where(dynamic, np.asarray(world.mass, dtype=float), 0.0),
            gravity=np.array(world.gravity, dtype=float).reshape(2),
        )

    def frame_data(self, world: Any) -> dict[str, Any]:
        """The current frame's data from ``world`` for the recorded kinds (contacts of its
        last step, ``world.vel``, ``world.applied_force`` and ``applied_torque``, and the
        optional ``world.sleeping``)."""
        kinds = self.recorded
        data: dict[str, Any] = {}
        if "contacts" in kinds:
            data["contacts"] = contact_rows(world.manifolds, np.asarray(world.kind))
        if "velocities" in kinds:
            data["velocities"] = world.vel
        if "forces" in kinds:
            data["forces"] = np.column_stack([world.applied_force, world.applied_torque])
        if "sleeping" in kinds:
            data["sleeping"] = getattr(world, "sleeping", None)
        return data

    def add(self, n: int, data: Mapping[str, Any]) -> None:
        """Append one frame of ``n`` bodies: ``data`` maps a recorded kind to its array.

        Every recorded kind but ``sleeping`` (optional: None when the engine has no flag) must
        be given; kinds not recorded are ignored.
        """
        shapes = {"contacts": (-1, len(CONTACT_COLUMNS)), "velocities": (n, 2), "forces": (n, 3)}
        for kind in self.recorded:
            value = data.get(kind)
            if kind == "sleeping":
                self.sleeping.append(None if value is None else np.array(value, dtype=bool))
                if value is not None and self.sleeping[-1].shape != (n,):
                    raise ValueError(f"sleeping: expected ({n},) flags, got {np.shape(value)}")
                continue
            if value is None:
                raise ValueError(f"{kind}: the layers {self.layers} need it in every frame")
            array = np.array(value, dtype=float)
            want = shapes[kind]
            if array.ndim != 2 or array.shape[1] != want[1] or want[0] not in (-1, len(array)):
                raise ValueError(f"{kind}: expected shape {want}, got {array.shape}")
            getattr(self, kind).append(array)

    def check(self, frames: int) -> None:
        """Each recorded kind has one entry per frame (ValueError naming the kind if not)."""
        for kind in self.recorded:
            if len(getattr(self, kind)) != frames:
                raise ValueError(
                    f"overlays.{kind}: {len(getattr(self, kind))} entries for {frames} frames"
                )
