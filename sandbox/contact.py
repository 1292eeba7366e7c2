"""Contacts: the manifold arrays the narrowphase fills and the solvers read (``Manifolds``), and
the :class:`Contact` objects the Python API hands out (slides, "Collision Detection Output": a
point of contact, a contact normal and a penetration distance).

Conventions (``docs/architecture.md``, "Contact manifolds"): the normal is a unit vector from
body ``a`` to body ``b``; points are in world coordinates, midway between the two surfaces;
depth > 0 means overlap (m); each manifold has 1 or 2 points.
"""

from __future__ import annotations

import weakref
from collections.abc import Sequence

import numpy as np

from sandbox.jit import njit

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


# --- contact rows: the same manifolds in preallocated arrays, as the compiled step keeps them ---
# One row per manifold in three arrays (columns below), so that a compiled call takes a few large
# arrays instead of many small ones and nothing is allocated per step. Point j of a manifold uses
# the columns ``G_POINT + G_STRIDE * j + field`` (geometry) and ``S_POINT + S_STRIDE * j + field``
# (solver); unused second slots hold zeros (feature -1).

# ints (k, INT_COLS): bodies, shapes, point count, feature id of point j at I_FEATURE + j
I_A, I_B, I_SA, I_SB, I_COUNT, I_FEATURE = 0, 1, 2, 3, 4, 5
INT_COLS = 8
# geometry (k, GEOM_COLS): what the narrowphase found, what the position pass needs, the
# approach velocity v_r . n at the start of the step (VN0, before this step's gravity and forces,
# what restitution reflects) and the restitution pass's impulse of point j at G_BOUNCE + j (kept
# apart from the solver's PN, which is what the next step warm starts from)
G_NX, G_NY, G_FRICTION, G_RESTITUTION, G_REBOUND = 0, 1, 2, 3, 4
G_POINT, G_STRIDE = 5, 8
X, Y, DEPTH, LAX, LAY, LBX, LBY, VN0 = 0, 1, 2, 3, 4, 5, 6, 7  # per point
G_BOUNCE = 21
GEOM_COLS = 24
# solver (k, SOLVER_COLS): everything the velocity iterations read, nothing else
S_NX, S_NY, S_MU, S_IM1, S_II1, S_IM2, S_II2 = 0, 1, 2, 3, 4, 5, 6
S_POINT, S_STRIDE = 7, 10
RN1, RN2, RT1, RT2, KN, KT, BIAS, PN, PT, PMAX = 0, 1, 2, 3, 4, 5, 6, 7, 8, 9  # per point
S_K12, S_M11, S_M12, S_M22, S_BLOCK = 27, 28, 29, 30, 31  # 2x2 block: K12 and K^-1
SOLVER_COLS = 32


class ContactBuffers:
    """One world's contact arrays, kept from step to step (``world._solver_cache["buffers"]``).

    - broadphase scratch: ``aabb`` (m, 4), the sweep ``order`` kept from step to step and
      ``state[0]`` the axis it is sorted on (-1: none yet), the boxes in that order
      (``sweep_box``, ``sweep_int``: index, body, static), ``pair_count`` (pair sorting);
    - ``pairs`` (capacity, 2) and ``pairs_raw``: the pair list, sorted and as found;
    - two sets of contact rows (``ints``, ``geoms``, ``solver``, see the column names above):
      the set ``now`` holds the last solved contacts (the warm-start cache), the next solve
      writes the other set and then becomes ``now``.

    Built for one :class:`~sandbox.geometry_arrays.Geometry` (shape indices mean nothing for
    another one); :func:`buffers` makes a new one when the world's shapes change.
    """

    def __init__(self, geometry, capacity: int | None = None) -> None:
        self.geometry = geometry
        m = len(geometry)
        self.aabb = np.zeros((m, 4))
        self.order = np.arange(m, dtype=np.int64)
        self.sweep_box = np.zeros((m, 4))
        self.sweep_int = np.zeros((m, 3), dtype=np.int64)
        self.pair_count = np.zeros(m + 1, dtype=np.int64)
        self.state = np.full(4, -1, dtype=np.int64)
        self.now = 0
        self.k = [0, 0]
        self.source = None  # the Manifolds set ``now`` was solved for, if any
        self.settings_raw = self.settings = None  # see sandbox.collision._settings
        self._views = [None, None]  # weak references to the Manifolds handed out per set
        self.capacity = 0
        self._allocate(4 * m + 64 if capacity is None else int(capacity))

    def _allocate(self, capacity: int) -> None:
        old = (self.ints, self.geoms, self.solver) if self.capacity else None
        self.capacity = capacity
        self.pairs = np.zeros((capacity, 2), dtype=np.int64)
        self.pairs_raw = np.zeros((capacity, 2), dtype=np.int64)
        self.ints = [np.zeros((capacity, INT_COLS), dtype=np.int64) for _ in range(2)]
        self.geoms = [np.zeros((capacity, GEOM_COLS)) for _ in range(2)]
        self.solver = [np.zeros((capacity, SOLVER_COLS)) for _ in range(2)]
        if old is not None:  # keep both sets: the warm-start cache and any unread manifolds
            for new_sets, old_sets in zip((self.ints, self.geoms, self.solver), old, strict=True):
                for s in range(2):
                    new_sets[s][: self.k[s]] = old_sets[s][: self.k[s]]

    def reserve(self, rows: int) -> None:
        """Room for at least ``rows`` pairs and manifolds."""
        if rows > self.capacity:
            self._allocate(max(rows + rows // 4, 2 * self.capacity))

    def begin(self) -> int:
        """The set the next solve writes (the one not holding the warm-start cache). Manifolds
        read from it earlier and still held by someone are copied out first."""
        s = 1 - self.now
        view = self._views[s]() if self._views[s] is not None else None
        if view is not None:
            view._fill()
        self._views[s] = None
        return s

    def commit(self, s: int, k: int) -> None:
        """Set ``s`` now holds this step's ``k`` manifolds (the next warm-start cache)."""
        self.now = s
        self.k[s] = k

    def forget(self) -> None:
        """No contacts to remember (nothing warm starts from the last set)."""
        self.k[self.now] = 0

    def rows(self, s: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(ints, geoms, solver)`` of set ``s``."""
        return self.ints[s], self.geoms[s], self.solver[s]

    def manifolds(self, s: int | None = None) -> Manifolds:
        """The manifolds of set ``s`` (default: the last solved), as a lazy :class:`Manifolds`:
        the arrays are copied out of the rows when first read."""
        s = self.now if s is None else s
        view = RowManifolds(self, s, self.k[s])
        self._views[s] = weakref.ref(view)
        return view

    def copy_out(self, s: int, k: int) -> Manifolds:
        """The first ``k`` manifolds of set ``s`` as a new :class:`Manifolds` (copies)."""
        ints, geoms, solver = self.ints[s][:k], self.geoms[s][:k], self.solver[s][:k]
        pg = [G_POINT + G_STRIDE * j for j in (0, 1)]
        ps = [S_POINT + S_STRIDE * j for j in (0, 1)]
        return Manifolds(
            ints[:, I_A].copy(),
            ints[:, I_B].copy(),
            ints[:, I_SA].copy(),
            ints[:, I_SB].copy(),
            geoms[:, [G_NX, G_NY]].copy(),
            ints[:, I_COUNT].copy(),
            np.stack([geoms[:, [p + X, p + Y]] for p in pg], axis=1),
            geoms[:, [p + DEPTH for p in pg]].copy(),
            ints[:, I_FEATURE : I_FEATURE + 2].copy(),
            geoms[:, G_FRICTION].copy(),
            geoms[:, G_RESTITUTION].copy(),
            solver[:, [p + PN for p in ps]] + geoms[:, G_BOUNCE : G_BOUNCE + 2],
            solver[:, [p + PT for p in ps]].copy(),
        )


@njit
def rows_from_manifolds(
    a, b, sa, sb, normal, count, point, depth, feature, friction, restitution, ints, geoms
) -> None:  # fmt: skip
    """Write manifold arrays into contact rows (``ints`` and the narrowphase columns of
    ``geoms``)."""
    for i in range(len(a)):
        ints[i, I_A], ints[i, I_B], ints[i, I_SA], ints[i, I_SB] = a[i], b[i], sa[i], sb[i]
        ints[i, I_COUNT] = count[i]
        geoms[i, G_NX], geoms[i, G_NY] = normal[i, 0], normal[i, 1]
        geoms[i, G_FRICTION], geoms[i, G_RESTITUTION] = friction[i], restitution[i]
        for j in range(2):
            g = G_POINT + G_STRIDE * j
            used = j < count[i]
            ints[i, I_FEATURE + j] = feature[i, j] if used else -1
            geoms[i, g + X] = point[i, j, 0] if used else 0.0
            geoms[i, g + Y] = point[i, j, 1] if used else 0.0
            geoms[i, g + DEPTH] = depth[i, j] if used else 0.0


@njit
def impulses_of_rows(geoms, solver, k, normal_impulse, tangent_impulse) -> None:
    """The impulses a solve applied (normal: the solver's plus the bounce's; tangent) into the
    manifold arrays ``normal_impulse``, ``tangent_impulse`` (k, 2)."""
    for i in range(k):
        for j in range(2):
            p = S_POINT + S_STRIDE * j
            normal_impulse[i, j] = solver[i, p + PN] + geoms[i, G_BOUNCE + j]
            tangent_impulse[i, j] = solver[i, p + PT]


class RowManifolds(Manifolds):
    """:class:`Manifolds` whose arrays are copied out of a :class:`ContactBuffers` set when first
    read (most steps nobody looks at them). Before the buffers reuse the set, they fill every
    such object still alive, so it keeps showing the step it came from."""

    __slots__ = ("_buffers", "_set", "_k", "__weakref__")

    def __init__(self, buffers: ContactBuffers, s: int, k: int) -> None:
        self._buffers, self._set, self._k = buffers, s, k

    def __len__(self) -> int:
        return self._k

    def __getattr__(self, name: str):  # only called while a field is still unset
        if name in _FIELDS and self._buffers is not None:
            self._fill()
            return getattr(self, name)
        raise AttributeError(name)

    def _fill(self) -> None:
        if self._buffers is None:
            return
        full = self._buffers.copy_out(self._set, self._k)
        self._buffers = None
        for name in _FIELDS:
            setattr(self, name, getattr(full, name))


def buffers(world) -> ContactBuffers:
    """The world's :class:`ContactBuffers` for its current shapes (made on first use, and again
    after shapes change)."""
    geometry = world.geometry()
    found = world._solver_cache.get("buffers")
    if found is None or found.geometry is not geometry:
        found = ContactBuffers(geometry)
        world._solver_cache["buffers"] = found
    return found


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
