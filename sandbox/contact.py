"""Contacts as the Python API shows them (slides, "Collision Detection Output": a point of
contact, a contact normal and a penetration distance), and the buffers the step keeps them in.

The narrowphase writes :data:`sandbox.records.CONTACT` records; every solver reads and updates
the same records. :class:`Manifolds` is a thin view of them with one array per field, and
:class:`Contact` one manifold as Python objects. Conventions: the normal is a unit vector from
body ``a`` to body ``b``; points are in world coordinates, midway between the two surfaces;
depth > 0 means overlap (m); each manifold has 1 or 2 points.
"""

from __future__ import annotations

import weakref
from collections.abc import Sequence

import numpy as np

from sandbox.manifolds import FIELDS, Manifolds
from sandbox.records import CONTACT, PROXY
from sandbox.vec2 import Vec2

__all__ = ["FIELDS", "Contact", "ContactBuffers", "Manifolds", "contacts_from_manifolds"]


class ContactBuffers:
    """One world's contact arrays, kept from step to step.

    - ``sets`` (3, capacity) CONTACT records: of the first two, one holds the last step's
      contacts (what the next step warm starts from), the next step writes the other. Which set
      is which, and how many records each holds, is in the world's step context
      (``contact_set``, ``contact_count``), so the compiled step can flip them. The third
      (``sets[STORE]``) keeps the contacts of sleeping islands for when they wake
      (:mod:`sandbox.sleeping_contacts`).
    - ``proxies`` (m,) PROXY records: the broadphase's boxes and sweep order for the m shapes.
    - ``pairs`` (2, capacity, 2) int64: the pair list as found (``pairs[0]``) and sorted
      (``pairs[1]``).

    Made for one set of shapes (indices mean nothing for another): the world makes new buffers
    when its shapes change.
    """

    def __init__(self, shapes: int, capacity: int | None = None) -> None:
        self.proxies = np.zeros(shapes, dtype=PROXY)
        self.proxies["order"] = np.arange(shapes)
        self._views: list = [None, None]
        self.capacity = 0
        self.sets = np.zeros((3, 0), dtype=CONTACT)
        self.pairs = np.zeros((2, 0, 2), dtype=np.int64)
        self.reserve(4 * shapes + 64 if capacity is None else int(capacity))

    def reserve(self, rows: int) -> None:
        """Room for at least ``rows`` pairs and manifolds (all three sets are kept)."""
        if rows <= self.capacity:
            return
        capacity = max(rows + rows // 4, 2 * self.capacity)
        sets = np.zeros((3, capacity), dtype=CONTACT)
        sets[:, : self.capacity] = self.sets
        for s in range(2):
            self.release(s)
        self.sets = sets
        pairs = np.zeros((2, capacity, 2), dtype=np.int64)
        pairs[:, : self.capacity] = self.pairs  # the kept pairs stay (sandbox.step.find_pairs)
        self.pairs = pairs
        self.capacity = capacity

    def release(self, s: int) -> bool:
        """Set ``s`` is about to be written: views of it still held get copies of their own.
        Returns whether a view of the other set may still be held."""
        ref = self._views[s]
        view = ref() if ref is not None else None
        if view is not None:
            view.detach()
        self._views[s] = None
        return self._views[1 - s] is not None

    def manifolds(self, ctx) -> Manifolds:
        """The last step's manifolds (``ctx``: the world's step context), as a view."""
        s = int(ctx["contact_set"])
        view = Manifolds(self.sets[s], int(ctx["contact_count"][s]))
        self._views[s] = weakref.ref(view)
        return view


class Contact:
    """One contact between two bodies, as the Python API shows it.

    ``a``, ``b``: the bodies (the normal points from a to b); ``shape_a``, ``shape_b``: the
    shapes in contact (shape objects when known, else indices into the world's shapes);
    ``normal`` unit vector; ``points``: 1 or 2 world points (m); ``depths``: penetration per
    point (m, > 0 overlapping); ``depth``: the largest of them; ``impulses``: normal impulse
    per point (N s) from the last solve; ``tangent_impulses`` likewise along the tangent;
    ``features``: the narrowphase's feature ids; ``friction``, ``restitution``: the combined
    coefficients.
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
        normal,
        points: list,
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
        self.normal = Vec2(normal)  # two floats from any pair: tuple, list or array
        self.points = [Vec2(p) for p in points]
        self.depths = [float(d) for d in depths]
        n = len(self.points)
        self.impulses = [0.0] * n if impulses is None else [float(x) for x in impulses]
        self.tangent_impulses = (
            [0.0] * n if tangent_impulses is None else [float(x) for x in tangent_impulses]
        )
        self.features = [0] * n if features is None else [int(f) for f in features]
        self.friction = float(friction)
        self.restitution = float(restitution)

    @classmethod
    def of_floats(cls, a, b, shape_a, shape_b, normal, points, depths, impulses, tangents,
                  features, friction, restitution) -> Contact:  # fmt: skip
        """As the constructor, from values that are Python floats and ints already (a record's
        fields as ``tolist`` gives them): nothing converted, nothing checked."""
        c = cls.__new__(cls)
        c.a, c.b, c.shape_a, c.shape_b = a, b, shape_a, shape_b
        c.normal, c.points = Vec2.of_floats(normal), [Vec2.of_floats(p) for p in points]
        c.depths, c.impulses, c.tangent_impulses = depths, impulses, tangents
        c.features, c.friction, c.restitution = features, friction, restitution
        return c

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


def _column(values: np.ndarray) -> list:
    """A field of the records as (nested) Python lists of floats or ints."""
    return np.ascontiguousarray(values).tolist()


def contacts_from_manifolds(
    manifolds: Manifolds | None, bodies: Sequence, shapes: Sequence | None = None
) -> list[Contact]:
    """One :class:`Contact` per manifold. ``bodies[i]`` is body i; ``shapes`` (optional) the
    world's shapes in the order of its shape records, which by default is every body's
    ``shapes`` list in body order; ``shape_a``/``shape_b`` fall back to shape indices."""
    if manifolds is None or len(manifolds) == 0:
        return []
    if shapes is None and all(hasattr(body, "shapes") for body in bodies):
        shapes = [shape for body in bodies for shape in body.shapes]
    # every field as Python lists first, one conversion per column (a contiguous copy first:
    # numpy lists a strided nested field ten times slower): reading the records field by field
    # took 36 to 39 us a contact, this 4 to 7 (benchmarks/bench_contacts.py)
    r = manifolds.records
    a, b, count, shape_a, shape_b, normal, friction, restitution = (
        _column(r[f]) for f in ("a", "b", "count", "shape_a", "shape_b", "normal", "friction",
                                "restitution")
    )  # fmt: skip
    point, depth, feature = (_column(r["points"][f]) for f in ("point", "depth", "feature"))
    impulses, tangents = _column(manifolds.normal_impulse), _column(manifolds.tangent_impulse)
    known = len(shapes) if shapes is not None else 0
    out = []
    rows = zip(a, b, shape_a, shape_b, count, normal, point, depth, impulses, tangents, feature,
               friction, restitution, strict=True)  # fmt: skip
    for ia, ib, sa, sb, n, nk, pk, dk, ik, tk, fk, mu, e in rows:
        if max(sa, sb) < known:  # else the shapes' indices
            sa, sb = shapes[sa], shapes[sb]
        points = (pk[:n], dk[:n], ik[:n], tk[:n], fk[:n])  # each point's column, count long
        out.append(Contact.of_floats(bodies[ia], bodies[ib], sa, sb, nk, *points, mu, e))
    return out


def find_contacts(world) -> tuple[list[Contact], dict]:
    """Broadphase + narrowphase at the world's current state, without stepping, no margin:
    the contacts (:class:`Contact`) and the counters (``pair_tests``, ``pairs``, ``contacts``,
    ``contact_points``)."""
    from sandbox.broadphase import find_pairs
    from sandbox.broadphase.aabb import aabbs_into
    from sandbox.narrowphase import collide
    from sandbox.records import DYNAMIC

    g = world.geometry()
    stats = {"pair_tests": 0, "pairs": 0, "contacts": 0, "contact_points": 0}
    manifolds = Manifolds.empty()
    if len(g) >= 2:
        aabb = np.empty((len(g), 4))
        aabbs_into(g.table, g.vertices, world.state, 0.0, aabb)
        fixed = world.kind[g.table["body"]] != DYNAMIC
        pairs, tests = find_pairs(world.settings.broadphase, aabb, fixed, g.table["body"])
        manifolds = collide(pairs, g.table, g.vertices, world.state, 0.0, world.joint_table)
        stats.update(pair_tests=int(tests), pairs=len(pairs), contacts=len(manifolds))
        stats["contact_points"] = int(np.sum(manifolds.count))
    return contacts_from_manifolds(manifolds, world.bodies), stats
