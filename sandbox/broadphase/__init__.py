"""Broadphase: which pairs of shapes have overlapping AABBs (slides, "Collision Detection
Performance").

One interface, five swappable strategies (``STRATEGIES``)::

    pairs, pair_tests = find_pairs(name, aabb, static, body)

- ``aabb`` (m, 4) float64 ``[xmin, ymin, xmax, ymax]`` (see :func:`aabb.shape_aabbs`),
  ``static`` (m,) bool (the shape's body cannot move), ``body`` (m,) int64 owner. ``static``
  may also hold integer bit flags: two shapes are left out when their flags share a bit (the
  step uses 3 for a static body, 1 for a sleeping one and 2 for a moving kinematic one, so a
  moving kinematic body still meets a sleeping one; see :func:`sandbox.step.place_proxies`).
- ``pairs`` (k, 2) int64: exactly the shape pairs whose boxes overlap (touching counts),
  ``pairs[:, 0] < pairs[:, 1]``, sorted lexicographically, no duplicates, never two static
  shapes nor two shapes of one body. The list is identical for every strategy, so a simulation
  is bit-identical whichever one is chosen.
- ``pair_tests``: how many AABB-vs-AABB overlap tests the strategy performed. Pairs ruled out
  by the static/same-body filter or by a strategy's de-duplication rule are not counted; brute
  force therefore reports m(m-1)/2 minus the filtered pairs.

Options per strategy: ``grid`` ``cell_size`` (m); ``sap`` ``axis`` (0 or 1); ``quadtree`` and
``kdtree`` ``capacity`` and ``max_depth``. :func:`describe` returns the structure for drawing.
"""

from __future__ import annotations

import numpy as np

from sandbox.broadphase import brute, grid, kdtree, quadtree, sap
from sandbox.broadphase.aabb import shape_aabbs, swept_aabbs

STRATEGIES: tuple[str, ...] = ("brute", "grid", "sap", "quadtree", "kdtree")

_MODULES = {"brute": brute, "grid": grid, "sap": sap, "quadtree": quadtree, "kdtree": kdtree}

__all__ = [
    "STRATEGIES",
    "describe",
    "find_pairs",
    "find_pairs_traced",
    "shape_aabbs",
    "swept_aabbs",
]


def _module(name: str):
    try:
        return _MODULES[name]
    except (KeyError, TypeError):
        raise ValueError(
            f"unknown broadphase {name!r}; expected one of {', '.join(STRATEGIES)}"
        ) from None


def _boxes(aabb) -> np.ndarray:
    box = np.ascontiguousarray(aabb, dtype=np.float64)
    if box.size == 0:
        return np.zeros((0, 4))
    if box.ndim != 2 or box.shape[1] != 4:
        raise ValueError(f"aabb must have shape (m, 4), got {box.shape}")
    return box


def _inputs(aabb, static, body):
    box = _boxes(aabb)
    m = len(box)
    fixed = np.zeros(m, dtype=np.int64) if static is None else np.asarray(static).astype(np.int64)
    owner = np.arange(m, dtype=np.int64) if body is None else np.asarray(body, dtype=np.int64)
    if fixed.shape != (m,) or owner.shape != (m,):
        raise ValueError(f"static and body must have shape ({m},) like aabb")
    return box, np.ascontiguousarray(fixed), np.ascontiguousarray(owner)


def find_pairs_traced(
    name: str,
    aabb: np.ndarray,
    static: np.ndarray | None = None,
    body: np.ndarray | None = None,
    record: bool = False,
    **options,
) -> tuple[np.ndarray, int, np.ndarray]:
    """:func:`find_pairs` plus ``tested`` (t, 2): the pairs the strategy actually tested, in
    the order it tested them (empty unless ``record``)."""
    module = _module(name)
    box, fixed, owner = _inputs(aabb, static, body)
    empty = np.zeros((0, 2), dtype=np.int64)
    if len(box) < 2:
        return empty, 0, empty
    pairs, tests, tested = module.find(box, fixed, owner, record, **options)
    return pairs, int(tests), tested


def find_pairs(
    name: str,
    aabb: np.ndarray,
    static: np.ndarray | None = None,
    body: np.ndarray | None = None,
    **options,
) -> tuple[np.ndarray, int]:
    """``(pairs (k, 2) int64, pair_tests)`` for strategy ``name`` (one of ``STRATEGIES``).

    ``static`` defaults to all False, ``body`` to one body per shape.
    """
    pairs, tests, _ = find_pairs_traced(name, aabb, static, body, False, **options)
    return pairs, tests


def describe(name: str, aabb: np.ndarray, **options) -> dict:
    """The strategy's structure for drawing (``grid``: cells used; ``sap``: sweep intervals;
    ``quadtree``: node rectangles; ``kdtree``: regions and split lines; ``brute``: nothing)."""
    module = _module(name)
    box = _boxes(aabb)
    if len(box) == 0 and name in ("quadtree", "kdtree"):
        return {}
    return module.describe(box, **options)
