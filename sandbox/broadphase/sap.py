"""Sort and sweep (sweep and prune) on one axis (slides, "Collision Detection Performance":
co-ordinate sorting).

The axis is the one along which the box centres spread more (larger variance), so fewer boxes
share an interval. The boxes are sorted by their lower end ``lo`` on that axis and swept in that
order; the active list of box ``i`` is the run of boxes after it whose ``lo`` is at most
``hi_i``, because a box starting later than ``hi_i`` (and every box after it) cannot overlap
``i``. Each box in that run gets one full AABB test. Sorting is O(m log m); the sweep costs one
test per pair overlapping on the sweep axis.
"""

from __future__ import annotations

import numpy as np

from sandbox.broadphase.aabb import collect, overlap, put_pair, skip_pair
from sandbox.jit import njit


@njit
def sweep_axis(aabb: np.ndarray) -> int:
    """0 (x) or 1 (y): the axis of larger variance of the box centres (x on a tie)."""
    m = aabb.shape[0]
    if m < 2:
        return 0
    sx = 0.0
    sy = 0.0
    for i in range(m):
        sx += aabb[i, 0] + aabb[i, 2]
        sy += aabb[i, 1] + aabb[i, 3]
    mx = 0.5 * sx / m
    my = 0.5 * sy / m
    vx = 0.0
    vy = 0.0
    for i in range(m):
        dx = 0.5 * (aabb[i, 0] + aabb[i, 2]) - mx
        dy = 0.5 * (aabb[i, 1] + aabb[i, 3]) - my
        vx += dx * dx
        vy += dy * dy
    return 1 if vy > vx else 0


@njit
def sap_kernel(
    aabb: np.ndarray,
    static: np.ndarray,
    body: np.ndarray,
    axis: int,
    order: np.ndarray,
    buf: np.ndarray,
    tested: np.ndarray,
):
    """``(k pairs, pair_tests)`` sweeping along ``axis`` (0 x, 1 y); pairs written to ``buf``,
    tested pairs to ``tested`` (as far as they fit; see ``aabb.collect``)."""
    m = aabb.shape[0]
    k = 0
    tests = 0
    for s in range(m):
        i = order[s]
        hi = aabb[i, axis + 2]
        for r in range(s + 1, m):
            j = order[r]
            if aabb[j, axis] > hi:
                break  # sorted by lo: nothing further along can reach box i
            if skip_pair(static, body, i, j):
                continue
            put_pair(tested, tests, i, j)
            tests += 1
            if overlap(aabb, i, j):
                put_pair(buf, k, i, j)
                k += 1
    return k, tests


def find(
    aabb: np.ndarray,
    static: np.ndarray,
    body: np.ndarray,
    record: bool = False,
    axis: int | None = None,
):
    """``(pairs, pair_tests, tested)``; ``axis`` (0 or 1) defaults to :func:`sweep_axis`."""
    a = sweep_axis(aabb) if axis is None else int(axis)
    if a not in (0, 1):
        raise ValueError(f"sap axis must be 0 (x) or 1 (y), got {axis!r}")
    # numpy's sort is several times faster than numba's for thousands of keys; the pair list
    # does not depend on how ties are ordered, the stable sort just keeps runs reproducible
    order = np.argsort(aabb[:, a], kind="stable")
    return collect(sap_kernel, len(aabb), record, aabb, static, body, a, order)


def describe(aabb: np.ndarray, axis: int | None = None) -> dict:
    """The sweep for drawing: ``axis``, ``order`` (shapes sorted by ``lo``) and ``intervals``
    (m, 2) ``[lo, hi]`` of each shape on the sweep axis."""
    a = sweep_axis(aabb) if axis is None else int(axis)
    intervals = np.ascontiguousarray(aabb[:, [a, a + 2]])
    order = np.argsort(intervals[:, 0], kind="stable")
    return {"axis": a, "order": order, "intervals": intervals}
