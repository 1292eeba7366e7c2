"""Contact manifolds as arrays: a thin view of the CONTACT records the narrowphase writes and
the solvers update (:mod:`sandbox.records`), one array per field."""

from __future__ import annotations

import numpy as np

from sandbox.records import CONTACT

FIELDS = (
    "a",
    "b",
    "sa",
    "sb",
    "normal",
    "count",
    "point",
    "depth",
    "feature",
    "friction",
    "restitution",
    "normal_impulse",
    "tangent_impulse",
)


class Manifolds:
    """``k`` contact manifolds: a view of CONTACT records with one array per field.

    ``a``, ``b`` (k,) body indices; ``sa``, ``sb`` (k,) shape indices; ``normal`` (k, 2) unit,
    from a to b; ``count`` (k,) 1 or 2; ``point`` (k, 2, 2) world points; ``depth`` (k, 2)
    penetration per point (m, > 0 overlapping); ``feature`` (k, 2) ids for warm starting;
    ``friction``, ``restitution`` (k,) products of the shapes' values; ``normal_impulse``,
    ``tangent_impulse`` (k, 2) the impulses the solver applied per point (N s; the normal one
    includes the restitution pass's). Slots beyond ``count`` hold zeros (feature -1).

    ``records`` is the CONTACT array itself. The step reuses its buffers every other step; a
    view someone still holds is given its own copy first, so it keeps showing its step.
    """

    __slots__ = ("records", "__weakref__")

    def __init__(self, records: np.ndarray, k: int | None = None) -> None:
        self.records = records if k is None else records[:k]

    @classmethod
    def empty(cls) -> Manifolds:
        """No contacts."""
        return cls(np.zeros(0, dtype=CONTACT))

    def detach(self) -> None:
        """Hold a copy of the records instead of the step's buffer."""
        self.records = self.records.copy()

    def __len__(self) -> int:
        return len(self.records)

    @property
    def a(self) -> np.ndarray:
        return self.records["a"]

    @property
    def b(self) -> np.ndarray:
        return self.records["b"]

    @property
    def sa(self) -> np.ndarray:
        return self.records["shape_a"]

    @property
    def sb(self) -> np.ndarray:
        return self.records["shape_b"]

    @property
    def normal(self) -> np.ndarray:
        return self.records["normal"]

    @property
    def count(self) -> np.ndarray:
        return self.records["count"]

    @property
    def point(self) -> np.ndarray:
        return self.records["points"]["point"]

    @property
    def depth(self) -> np.ndarray:
        return self.records["points"]["depth"]

    @property
    def feature(self) -> np.ndarray:
        return self.records["points"]["feature"]

    @property
    def friction(self) -> np.ndarray:
        return self.records["friction"]

    @property
    def restitution(self) -> np.ndarray:
        return self.records["restitution"]

    @property
    def normal_impulse(self) -> np.ndarray:
        """Per point: the solver's impulse plus the restitution pass's (N s; a new array)."""
        points = self.records["points"]
        return points["normal_impulse"] + points["bounce_impulse"]

    @property
    def tangent_impulse(self) -> np.ndarray:
        """Per point: the solver's friction impulse plus the shock pass's (N s; a new array)."""
        points = self.records["points"]
        return points["tangent_impulse"] + points["bounce_tangent"]

    def select(self, mask) -> Manifolds:
        """The manifolds picked by a boolean mask or an index array (copies)."""
        return Manifolds(self.records[np.asarray(mask)].copy())

    def __repr__(self) -> str:
        points = int(np.sum(self.count)) if len(self) else 0
        return f"Manifolds({len(self)} manifolds, {points} points)"
