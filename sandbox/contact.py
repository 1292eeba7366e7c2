"""Contacts: the manifold arrays the narrowphase fills and the solvers read (``Manifolds``), and
the :class:`Contact` objects the Python API hands out (slides, "Collision Detection Output": a
point of contact, a contact normal and a penetration distance).

Conventions (``docs/architecture.md``, "Contact manifolds"): the normal is a unit vector from
body ``a`` to body ``b``; points are in world coordinates, midway between the two surfaces;
depth > 0 means overlap (m); each manifold has 1 or 2 points.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

_FIELDS = (
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
    """``k`` contact manifolds as arrays (struct of arrays).

    ``a``, ``b`` (k,) body indices; ``sa``, ``sb`` (k,) shape indices; ``normal`` (k, 2) unit,
    from a to b; ``count`` (k,) 1 or 2; ``point`` (k, 2, 2) world points; ``depth`` (k, 2)
    penetration per point (m, > 0 overlapping); ``feature`` (k, 2) int64 ids for warm starting;
    ``friction``, ``restitution`` (k,) products of the shapes' values; ``normal_impulse``,
    ``tangent_impulse`` (k, 2) the impulses a solver applied per point (N s, zero until then).
    Slots beyond ``count`` hold zeros (feature -1).
    """

    __slots__ = _FIELDS

    def __init__(
        self,
        a: np.ndarray,
        b: np.ndarray,
        sa: np.ndarray,
        sb: np.ndarray,
        normal: np.ndarray,
        count: np.ndarray,
        point: np.ndarray,
        depth: np.ndarray,
        feature: np.ndarray,
        friction: np.ndarray,
        restitution: np.ndarray,
        normal_impulse: np.ndarray | None = None,
        tangent_impulse: np.ndarray | None = None,
    ) -> None:
        k = len(a)
        self.a, self.b, self.sa, self.sb = a, b, sa, sb
        self.normal, self.count, self.point, self.depth = normal, count, point, depth
        self.feature, self.friction, self.restitution = feature, friction, restitution
        self.normal_impulse = np.zeros((k, 2)) if normal_impulse is None else normal_impulse
        self.tangent_impulse = np.zeros((k, 2)) if tangent_impulse is None else tangent_impulse

    @classmethod
    def empty(cls) -> Manifolds:
        """No contacts."""
        i = np.zeros(0, dtype=np.int64)
        return cls(
            i,
            i.copy(),
            i.copy(),
            i.copy(),
            np.zeros((0, 2)),
            i.copy(),
            np.zeros((0, 2, 2)),
            np.zeros((0, 2)),
            np.zeros((0, 2), dtype=np.int64),
            np.zeros(0),
            np.zeros(0),
        )

    def __len__(self) -> int:
        return len(self.a)

    def select(self, mask) -> Manifolds:
        """The manifolds picked by a boolean mask or an index array (copies)."""
        mask = np.asarray(mask)
        return Manifolds(*(np.ascontiguousarray(getattr(self, f)[mask]) for f in _FIELDS))

    def __repr__(self) -> str:
        points = int(np.sum(self.count)) if len(self) else 0
        return f"Manifolds({len(self)} manifolds, {points} points)"


class Contact:
    """One contact between two bodies, as the Python API shows it.

    ``a``, ``b``: the bodies (the normal points from a to b); ``shape_a``, ``shape_b``: the
    shapes in contact (shape objects when known, else indices into the world's shape arrays);
    ``normal`` (2,) unit vector; ``points``: 1 or 2 world points (m); ``depths``: penetration
    per point (m, > 0 overlapping); ``depth``: the largest of them; ``impulses``: normal
    impulse per point (N s) from the last solve; ``tangent_impulses`` likewise along the
    tangent; ``features``: the narrowphase's feature ids; ``friction``, ``restitution``: the
    combined coefficients.
    """

    __slots__ = (
        "a",
        "b",
        "shape_a",
        "shape_b",
        "normal",
        "points",
        "depths",
        "impulses",
        "tangent_impulses",
        "features",
        "friction",
        "restitution",
    )

    def __init__(
        self,
        a,
        b,
        normal: np.ndarray,
        points: list[np.ndarray],
        depths: list[float],
        impulses: list[float] | None = None,
        shape_a=None,
        shape_b=None,
        tangent_impulses: list[float] | None = None,
        features: list[int] | None = None,
        friction: float = 0.0,
        restitution: float = 0.0,
    ) -> None:
        self.a, self.b = a, b
        self.shape_a, self.shape_b = shape_a, shape_b
        self.normal = np.asarray(normal, dtype=float)
        self.points = [np.asarray(p, dtype=float) for p in points]
        self.depths = [float(d) for d in depths]
        n = len(self.points)
        self.impulses = [0.0] * n if impulses is None else [float(x) for x in impulses]
        self.tangent_impulses = (
            [0.0] * n if tangent_impulses is None else [float(x) for x in tangent_impulses]
        )
        self.features = [0] * n if features is None else [int(f) for f in features]
        self.friction = float(friction)
        self.restitution = float(restitution)

    @property
    def depth(self) -> float:
        """Penetration depth (m): the largest over the contact points, > 0 when overlapping."""
        return max(self.depths)

    def __repr__(self) -> str:
        name_a = getattr(self.a, "name", self.a)
        name_b = getattr(self.b, "name", self.b)
        n = self.normal
        return (
            f"Contact({name_a!r} -> {name_b!r}, normal=({n[0]:.3f}, {n[1]:.3f}), "
            f"points={len(self.points)}, depth={self.depth:.4g})"
        )


def contacts_from_manifolds(
    manifolds: Manifolds, bodies: Sequence, shapes: Sequence | None = None
) -> list[Contact]:
    """One :class:`Contact` per manifold. ``bodies[i]`` is body i; ``shapes`` (optional) the
    world's shapes in the order of the shape arrays, which by default is every body's
    ``shapes`` list in body order; ``shape_a``/``shape_b`` fall back to shape indices."""
    if manifolds is None or len(manifolds) == 0:
        return []
    if shapes is None and all(hasattr(body, "shapes") for body in bodies):
        shapes = [shape for body in bodies for shape in body.shapes]
    out = []
    for k in range(len(manifolds)):
        n = int(manifolds.count[k])
        sa, sb = int(manifolds.sa[k]), int(manifolds.sb[k])
        known = shapes is not None and max(sa, sb) < len(shapes)
        out.append(
            Contact(
                bodies[int(manifolds.a[k])],
                bodies[int(manifolds.b[k])],
                manifolds.normal[k].copy(),
                [manifolds.point[k, i].copy() for i in range(n)],
                list(manifolds.depth[k, :n]),
                impulses=list(manifolds.normal_impulse[k, :n]),
                shape_a=shapes[sa] if known else sa,
                shape_b=shapes[sb] if known else sb,
                tangent_impulses=list(manifolds.tangent_impulse[k, :n]),
                features=list(manifolds.feature[k, :n]),
                friction=manifolds.friction[k],
                restitution=manifolds.restitution[k],
            )
        )
    return out
