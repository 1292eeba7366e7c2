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
from sandbox.records import PROXY


@njit
def sweep_axis(proxies) -> int:
    """0 (x) or 1 (y): the axis of larger variance of the box centres (x on a tie)."""
    m = proxies.shape[0]
    if m < 2:
        return 0
    sx = 0.0
    sy = 0.0
    for i in range(m):
        a = proxies[i]["aabb"]
        sx += a[0] + a[2]
        sy += a[1] + a[3]
    mx = 0.5 * sx / m
    my = 0.5 * sy / m
    vx = 0.0
    vy = 0.0
    for i in range(m):
        a = proxies[i]["aabb"]
        dx = 0.5 * (a[0] + a[2]) - mx
        dy = 0.5 * (a[1] + a[3]) - my
        vx += dx * dx
        vy += dy * dy
    return 1 if vy > vx else 0


@njit
def gather(proxies) -> None:
    """Copy the boxes into sweep order: place s gets the box, body and fixed flag of shape
    ``proxies[s]["order"]``. The sweep then reads memory front to back instead of jumping
    around (several times faster for thousands of shapes)."""
    for s in range(proxies.shape[0]):
        p = proxies[s]
        src = proxies[p["order"]]
        box, a = p["sweep_box"], src["aabb"]
        box[0], box[1], box[2], box[3] = a[0], a[1], a[2], a[3]
        p["sweep_body"] = src["body"]
        p["sweep_fixed"] = src["fixed"]


@njit
def sap_kernel(proxies, axis, buf):
    """``(k pairs, pair_tests)`` sweeping along ``axis`` (0 x, 1 y) over boxes already in sweep
    order (:func:`gather`); the pairs are written to ``buf`` as far as they fit.

    Box ``s`` is tested against the boxes after it until one starts beyond its upper end. They
    all overlap it on the sweep axis (they start between its two ends), so the AABB test is
    left with the other axis. The loop is written without a branch on that test's outcome
    (which is as good as random, so the processor would guess it wrong half the time): every
    candidate is written at the end of the pair list, which then grows by 1 or 0.
    """
    m = proxies.shape[0]
    other = 1 - axis
    k = 0
    tests = 0
    nb = buf.shape[0]
    for s in range(m):
        p = proxies[s]
        hi = p["sweep_box"][axis + 2]
        i, body_i, fixed_i = p["order"], p["sweep_body"], p["sweep_fixed"]
        lo_o, hi_o = p["sweep_box"][other], p["sweep_box"][other + 2]
        first = k
        for r in range(s + 1, m):
            q = proxies[r]
            box = q["sweep_box"]
            if box[axis] > hi:
                break  # sorted by lo: nothing further along can reach box s
            # not one body, not both fixed (aabb.skip_pair): one test
            tested = (q["sweep_body"] != body_i) & ((fixed_i & q["sweep_fixed"]) == 0)
            hit = tested & (box[other] <= hi_o) & (lo_o <= box[other + 2])
            if k < nb:
                buf[k, 1] = q["order"]
            k += hit
            tests += tested
        for q in range(first, min(k, nb)):  # the pairs (i, j) of box s, with i < j
            j = buf[q, 1]
            buf[q, 0], buf[q, 1] = min(i, j), max(i, j)
    return k, tests


@njit
def tested_pairs(proxies, axis, tested) -> None:
    """The pairs :func:`sap_kernel` tests, in its order, written to ``tested`` (for drawing
    and counting; as far as they fit)."""
    m = proxies.shape[0]
    t = 0
    for s in range(m):
        p = proxies[s]
        hi = p["sweep_box"][axis + 2]
        for r in range(s + 1, m):
            q = proxies[r]
            if q["sweep_box"][axis] > hi:
                break
            if q["sweep_body"] == p["sweep_body"] or (p["sweep_fixed"] & q["sweep_fixed"]) != 0:
                continue
            put_pair(tested, t, p["order"], q["order"])
            t += 1


@njit
def update_order(proxies, axis, sorted_axis) -> None:
    """Sort the sweep order ``proxies["order"]`` by (lower end on ``axis``, shape index).

    Bodies move little between steps, so last step's order is nearly sorted and an insertion
    sort finishes in about O(m) (incremental sort and sweep). When the order was kept for the
    other axis (``sorted_axis``), or the insertion sort has moved too much, a full stable sort
    takes over.
    """
    m = proxies.shape[0]
    if sorted_axis == axis:
        budget = 8 * m + 64  # shifts allowed before a full sort is cheaper
        for s in range(1, m):
            i = proxies[s]["order"]
            lo = proxies[i]["aabb"][axis]
            r = s - 1
            while r >= 0:
                j = proxies[r]["order"]
                lo_j = proxies[j]["aabb"][axis]
                if lo_j < lo or (lo_j == lo and j < i):
                    break
                proxies[r + 1]["order"] = j
                r -= 1
            proxies[r + 1]["order"] = i
            budget -= s - 1 - r
            if budget < 0:
                break
        if budget >= 0:
            return
    keys = np.empty(m)
    for i in range(m):
        keys[i] = proxies[i]["aabb"][axis]
    order = np.argsort(keys, kind="mergesort")  # stable: ties in index order
    for s in range(m):
        proxies[s]["order"] = order[s]


@njit
def sweep(proxies, sorted_axis: int, buf):
    """One sweep of the step: choose the axis, bring the kept order up to date, copy the boxes
    into it and sweep. Returns ``(axis, k pairs, pair_tests)``; pairs in ``buf`` as far as they
    fit (as :func:`sap_kernel`)."""
    axis = sweep_axis(proxies)
    update_order(proxies, axis, sorted_axis)
    gather(proxies)
    k, tests = sap_kernel(proxies, axis, buf)
    return axis, k, tests


def proxies_of(aabb: np.ndarray, static: np.ndarray, body: np.ndarray) -> np.ndarray:
    """PROXY records for plain arrays: boxes (m, 4), a fixed flag and a body per shape."""
    proxies = np.zeros(len(aabb), dtype=PROXY)
    proxies["aabb"], proxies["fixed"], proxies["body"] = aabb, static, body
    return proxies


def find(
    aabb: np.ndarray,
    static: np.ndarray,
    body: np.ndarray,
    record: bool = False,
    axis: int | None = None,
):
    """``(pairs, pair_tests, tested)``; ``axis`` (0 or 1) defaults to :func:`sweep_axis`."""
    proxies = proxies_of(aabb, static, body)
    a = sweep_axis(proxies) if axis is None else int(axis)
    if a not in (0, 1):
        raise ValueError(f"sap axis must be 0 (x) or 1 (y), got {axis!r}")
    m = len(aabb)
    update_order(proxies, a, -1)
    gather(proxies)
    buf = np.empty((4 * m + 64, 2), dtype=np.int64)
    k, tests = sap_kernel(proxies, a, buf)
    if k > len(buf):
        buf = np.empty((k, 2), dtype=np.int64)
        k, tests = sap_kernel(proxies, a, buf)
    tested = np.empty((tests if record else 0, 2), dtype=np.int64)
    if record:
        tested_pairs(proxies, a, tested)
    return sort_pairs(buf, k, m), int(tests), tested


def describe(aabb: np.ndarray, axis: int | None = None) -> dict:
    """The sweep for drawing: ``axis``, ``order`` (shapes sorted by ``lo``) and ``intervals``
    (m, 2) ``[lo, hi]`` of each shape on the sweep axis."""
    a = (
        sweep_axis(proxies_of(aabb, np.zeros(len(aabb)), np.arange(len(aabb))))
        if axis is None
        else int(axis)
    )
    intervals = np.ascontiguousarray(aabb[:, [a, a + 2]])
    order = np.argsort(intervals[:, 0], kind="stable")
    return {"axis": a, "order": order, "intervals": intervals}
