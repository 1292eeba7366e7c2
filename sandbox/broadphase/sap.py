"""Sort and sweep (sweep and prune) on one axis (slides, "Collision Detection Performance":
co-ordinate sorting).

The axis is the one along which the box centres spread more (larger variance), so fewer boxes
share an interval. The boxes are sorted by their lower end ``lo`` on that axis and swept in that
order; the active list of box ``i`` is the run of boxes after it whose ``lo`` is at most
``hi_i``, because a box starting later than ``hi_i`` (and every box after it) cannot overlap
``i``. Each box in that run gets one full AABB test. Sorting is O(m log m); the sweep costs one
test per pair overlapping on the sweep axis.

The world's step keeps the order from one step to the next (:func:`update_order`): bodies move
little in a step, so an insertion sort of last step's order takes about O(m) (incremental sort
and sweep). Either way the boxes are sorted by (lower end, index), so the pairs and the test
count are the same.
"""

from __future__ import annotations

import numpy as np

from sandbox.broadphase.aabb import put_pair, sort_pairs
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
def gather(aabb, static, body, order, box, meta) -> None:
    """Copy the boxes into sweep order: ``box[s]`` is the AABB of shape ``order[s]`` and
    ``meta[s]`` its (index, body, static). The sweep then reads memory front to back instead of
    jumping around ``aabb`` (several times faster for thousands of shapes)."""
    for s in range(order.shape[0]):
        i = order[s]
        box[s, 0], box[s, 1], box[s, 2], box[s, 3] = aabb[i, 0], aabb[i, 1], aabb[i, 2], aabb[i, 3]
        meta[s, 0], meta[s, 1], meta[s, 2] = i, body[i], static[i]


@njit
def sap_kernel(box, meta, axis, buf):
    """``(k pairs, pair_tests)`` sweeping along ``axis`` (0 x, 1 y) over boxes already in sweep
    order (:func:`gather`); the pairs are written to ``buf`` as far as they fit.

    Box ``s`` is tested against the boxes after it until one starts beyond its upper end. They
    all overlap it on the sweep axis (they start between its two ends), so the AABB test is
    left with the other axis. The loop is written without a branch on that test's outcome
    (which is as good as random, so the processor would guess it wrong half the time): every
    candidate is written at the end of the pair list, which then grows by 1 or 0.
    """
    m = box.shape[0]
    other = 1 - axis
    k = 0
    tests = 0
    nb = buf.shape[0]
    for s in range(m):
        hi = box[s, axis + 2]
        i, body_i, static_i = meta[s, 0], meta[s, 1], meta[s, 2]
        lo_o, hi_o = box[s, other], box[s, other + 2]
        first = k
        for r in range(s + 1, m):
            if box[r, axis] > hi:
                break  # sorted by lo: nothing further along can reach box s
            # not one body, not both static (aabb.skip_pair): one test
            tested = (meta[r, 1] != body_i) & ((static_i & meta[r, 2]) == 0)
            hit = tested & (box[r, other] <= hi_o) & (lo_o <= box[r, other + 2])
            if k < nb:
                buf[k, 1] = meta[r, 0]
            k += hit
            tests += tested
        for q in range(first, min(k, nb)):  # the pairs (i, j) of box s, with i < j
            j = buf[q, 1]
            buf[q, 0], buf[q, 1] = min(i, j), max(i, j)
    return k, tests


@njit
def tested_pairs(box, meta, axis, tested) -> None:
    """The pairs :func:`sap_kernel` tests, in its order, written to ``tested`` (for drawing
    and counting; as far as they fit)."""
    m = box.shape[0]
    t = 0
    for s in range(m):
        hi = box[s, axis + 2]
        for r in range(s + 1, m):
            if box[r, axis] > hi:
                break
            if meta[r, 1] == meta[s, 1] or (meta[s, 2] and meta[r, 2]):
                continue
            put_pair(tested, t, meta[s, 0], meta[r, 0])
            t += 1


@njit
def update_order(aabb, axis, order, sorted_axis) -> None:
    """Sort ``order`` (shape indices) by (lower end on ``axis``, index) in place.

    Bodies move little between steps, so last step's order is nearly sorted and an insertion
    sort finishes in about O(m) (incremental sort and sweep). When the order was kept for the
    other axis (``sorted_axis``), or the insertion sort has moved too much, a full stable sort
    takes over.
    """
    m = order.shape[0]
    if sorted_axis == axis:
        budget = 8 * m + 64  # shifts allowed before a full sort is cheaper
        for s in range(1, m):
            i = order[s]
            lo = aabb[i, axis]
            r = s - 1
            while r >= 0:
                j = order[r]
                if aabb[j, axis] < lo or (aabb[j, axis] == lo and j < i):
                    break
                order[r + 1] = j
                r -= 1
            order[r + 1] = i
            budget -= s - 1 - r
            if budget < 0:
                break
        if budget >= 0:
            return
    keys = np.empty(m)
    for i in range(m):
        keys[i] = aabb[i, axis]
    order[:] = np.argsort(keys, kind="mergesort")  # stable: ties in index order


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
    m = len(aabb)
    order = np.argsort(aabb[:, a], kind="stable")
    box = np.empty((m, 4))
    meta = np.empty((m, 3), dtype=np.int64)
    gather(aabb, static, body, order, box, meta)
    buf = np.empty((4 * m + 64, 2), dtype=np.int64)
    k, tests = sap_kernel(box, meta, a, buf)
    if k > len(buf):
        buf = np.empty((k, 2), dtype=np.int64)
        k, tests = sap_kernel(box, meta, a, buf)
    tested = np.empty((tests if record else 0, 2), dtype=np.int64)
    if record:
        tested_pairs(box, meta, a, tested)
    return sort_pairs(buf, k, m), int(tests), tested


def describe(aabb: np.ndarray, axis: int | None = None) -> dict:
    """The sweep for drawing: ``axis``, ``order`` (shapes sorted by ``lo``) and ``intervals``
    (m, 2) ``[lo, hi]`` of each shape on the sweep axis."""
    a = sweep_axis(aabb) if axis is None else int(axis)
    intervals = np.ascontiguousarray(aabb[:, [a, a + 2]])
    order = np.argsort(intervals[:, 0], kind="stable")
    return {"axis": a, "order": order, "intervals": intervals}
