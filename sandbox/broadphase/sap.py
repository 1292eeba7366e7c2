"""Sort and sweep (sweep and prune) along one direction (slides, "Collision Detection
Performance": co-ordinate sorting).

Each box is projected on the sweep direction u, giving the interval [lo, hi] = [u . (xmin,
ymin), u . (xmax, ymax)] (u has no negative component). Two boxes that overlap have overlapping
intervals, so the boxes are sorted by ``lo`` and swept in that order: the candidates of box
``i`` are the run of boxes after it whose ``lo`` is at most ``hi_i``, because a box starting
later than ``hi_i`` (and every box after it) cannot overlap ``i``. Each candidate gets one full
AABB test. Sorting is O(m log m); the sweep costs one test per candidate.

The direction is one of four (:data:`DIRECTIONS`): x, y, and each of them turned by
:data:`SLANT`. The one chosen is the one with the fewest candidates (a slanted test weighs a
third more, :data:`SLANTED_COST`), counted for all four (:func:`candidates`, two sorts each)
when the sweep starts and again every :data:`RECOUNT` steps.
Along x or y a box's interval is shortest, and a random scatter of boxes is best swept there,
along its longer side. But bodies set out on a lattice (a grid of balls, the columns of a
stack) share their ``lo``: a whole row of them overlaps along y, however far apart they are
along x. Along a turned direction the rows fan out, and the test count of 1,000 balls on a
square grid falls from about 15,000 to about 900.

The world's step keeps the order from one step to the next (:func:`update_order`): bodies move
little in a step, so an insertion sort of last step's order takes about O(m) (incremental sort
and sweep). Either way the boxes are sorted by (lower end, index), so the pairs and the test
count are the same.
"""

from __future__ import annotations

import math

import numpy as np

from sandbox.broadphase.aabb import put_pair, sort_pairs
from sandbox.jit import njit
from sandbox.records import PROXY

SLANT = 0.15  # rad: the turn of the two slanted sweep directions
DIRECTIONS = np.array(
    [
        [1.0, 0.0],  # x
        [0.0, 1.0],  # y
        [math.cos(SLANT), math.sin(SLANT)],  # x turned towards y
        [math.sin(SLANT), math.cos(SLANT)],  # y turned towards x
    ]
)
NAMES = ("x", "y", f"x turned {SLANT} rad", f"y turned {SLANT} rad")
RECOUNT = 30  # steps between two choices of the direction (half a second at 60 Hz)
# a test along a slanted direction compares both axes and projects the box: measured about a
# third dearer than one along x or y (pyramid of 40: 24,047 slanted tests take as long as
# 32,020 along y), so a slanted direction is chosen only when it saves more than that
SLANTED_COST = 4.0 / 3.0


@njit
def interval(a, d: int) -> tuple[float, float]:
    """The interval ``(lo, hi)`` (m) of box ``a`` = [xmin, ymin, xmax, ymax] along direction
    ``d`` (an index into :data:`DIRECTIONS`): u . (xmin, ymin), u . (xmax, ymax)."""
    if d == 0:
        return a[0], a[2]
    if d == 1:
        return a[1], a[3]
    u = DIRECTIONS[d]
    return u[0] * a[0] + u[1] * a[1], u[0] * a[2] + u[1] * a[3]


@njit
def candidates(proxies, d: int) -> int:
    """How many boxes the sweep along direction ``d`` would test: the pairs (i, j), j after i
    in the sorted order, with lo_j <= hi_i. Box i at place p has ``#{j: lo_j <= hi_i}`` boxes
    with such a ``lo``, itself and the p before it included, so the count is the sum of those
    numbers less 1 + 2 + ... + m; with both ends sorted, one walk along them finds all the
    numbers."""
    m = proxies.shape[0]
    lo = np.empty(m)
    hi = np.empty(m)
    for i in range(m):
        lo[i], hi[i] = interval(proxies[i]["aabb"], d)
    lo.sort()
    hi.sort()
    total = 0
    j = 0  # the boxes with lo_j <= the current hi
    for i in range(m):
        while j < m and lo[j] <= hi[i]:
            j += 1
        total += j
    return total - m * (m + 1) // 2


@njit
def choose_direction(proxies, current: int, recount: int) -> tuple[int, int]:
    """``(direction, steps until the next choice)``: ``current`` while its time runs, else the
    direction of :data:`DIRECTIONS` whose :func:`candidates` cost least, a slanted one's
    counted :data:`SLANTED_COST` times (the first on a tie)."""
    if current >= 0 and recount > 0:
        return current, recount - 1
    best, least = 0, -1.0
    if proxies.shape[0] >= 2:
        for d in range(DIRECTIONS.shape[0]):
            cost = candidates(proxies, d) * (SLANTED_COST if d >= 2 else 1.0)
            if least < 0.0 or cost < least:
                best, least = d, cost
    return best, RECOUNT


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
def sap_kernel(proxies, d: int, buf):
    """``(k pairs, pair_tests)`` sweeping along direction ``d`` over boxes already in sweep
    order (:func:`gather`); the pairs are written to ``buf`` as far as they fit.

    Box ``s`` is tested against the boxes after it until one starts beyond its upper end.
    Along x or y the candidates all overlap box ``s`` on that axis (they start between its two
    ends), so the AABB test is left with the other axis; along a slanted direction it takes
    both. The loop is written without a branch on the test's outcome (which is as good as
    random, so the processor would guess it wrong half the time): every candidate is written
    at the end of the pair list, which then grows by 1 or 0.
    """
    m = proxies.shape[0]
    k = 0
    tests = 0
    nb = buf.shape[0]
    slanted = d >= 2
    other = 1 if slanted else 1 - d  # the axis whose overlap the sweep leaves to the test
    for s in range(m):
        p = proxies[s]
        x0, x1 = p["sweep_box"][0], p["sweep_box"][2]
        hi = interval(p["sweep_box"], d)[1]
        lo_o, hi_o = p["sweep_box"][other], p["sweep_box"][other + 2]
        i, body_i, fixed_i = p["order"], p["sweep_body"], p["sweep_fixed"]
        first = k
        for r in range(s + 1, m):
            q = proxies[r]
            box = q["sweep_box"]
            if interval(box, d)[0] > hi:
                break  # sorted by lo: nothing further along can reach box s
            # not one body, not both fixed (aabb.skip_pair): one test
            tested = (q["sweep_body"] != body_i) & ((fixed_i & q["sweep_fixed"]) == 0)
            hit = tested & (box[other] <= hi_o) & (lo_o <= box[other + 2])
            if slanted:  # and x too
                hit &= (box[0] <= x1) & (x0 <= box[2])
            if k < nb:
                buf[k, 1] = q["order"]
            k += hit
            tests += tested
        for q in range(first, min(k, nb)):  # the pairs (i, j) of box s, with i < j
            j = buf[q, 1]
            buf[q, 0], buf[q, 1] = min(i, j), max(i, j)
    return k, tests


@njit
def tested_pairs(proxies, d: int, tested) -> None:
    """The pairs :func:`sap_kernel` tests, in its order, written to ``tested`` (for drawing
    and counting; as far as they fit)."""
    m = proxies.shape[0]
    t = 0
    for s in range(m):
        p = proxies[s]
        hi = interval(p["sweep_box"], d)[1]
        for r in range(s + 1, m):
            q = proxies[r]
            if interval(q["sweep_box"], d)[0] > hi:
                break
            if q["sweep_body"] == p["sweep_body"] or (p["sweep_fixed"] & q["sweep_fixed"]) != 0:
                continue
            put_pair(tested, t, p["order"], q["order"])
            t += 1


@njit
def update_order(proxies, d: int, sorted_d: int) -> None:
    """Sort the sweep order ``proxies["order"]`` by (lower end along direction ``d``, shape
    index).

    Bodies move little between steps, so last step's order is nearly sorted and an insertion
    sort finishes in about O(m) (incremental sort and sweep). When the order was kept for
    another direction (``sorted_d``), or the insertion sort has moved too much, a full stable
    sort takes over.
    """
    m = proxies.shape[0]
    for i in range(m):
        proxies[i]["lo"] = interval(proxies[i]["aabb"], d)[0]
    if sorted_d == d:
        budget = 8 * m + 64  # shifts allowed before a full sort is cheaper
        for s in range(1, m):
            i = proxies[s]["order"]
            lo = proxies[i]["lo"]
            r = s - 1
            while r >= 0:
                j = proxies[r]["order"]
                lo_j = proxies[j]["lo"]
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
        keys[i] = proxies[i]["lo"]
    order = np.argsort(keys, kind="mergesort")  # stable: ties in index order
    for s in range(m):
        proxies[s]["order"] = order[s]


@njit
def sweep(proxies, kept: int, recount: int, buf):
    """One sweep of the step: choose the direction (:func:`choose_direction`; ``kept`` is the
    one the order is sorted along, ``recount`` the steps left until the next choice), bring the
    kept order up to date, copy the boxes into it and sweep. Returns ``(direction, recount, k
    pairs, pair_tests)``; pairs in ``buf`` as far as they fit (as :func:`sap_kernel`)."""
    d, recount = choose_direction(proxies, kept, recount)
    update_order(proxies, d, kept)
    gather(proxies)
    k, tests = sap_kernel(proxies, d, buf)
    return d, recount, k, tests


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
    """``(pairs, pair_tests, tested)``; ``axis``: the sweep direction, an index into
    :data:`DIRECTIONS` (0 x, 1 y, 2 and 3 slanted); by default :func:`choose_direction`'s."""
    proxies = proxies_of(aabb, static, body)
    d = _direction(proxies, axis)
    m = len(aabb)
    update_order(proxies, d, -1)
    gather(proxies)
    buf = np.empty((4 * m + 64, 2), dtype=np.int64)
    k, tests = sap_kernel(proxies, d, buf)
    if k > len(buf):
        buf = np.empty((k, 2), dtype=np.int64)
        k, tests = sap_kernel(proxies, d, buf)
    tested = np.empty((tests if record else 0, 2), dtype=np.int64)
    if record:
        tested_pairs(proxies, d, tested)
    return sort_pairs(buf, k, m), int(tests), tested


def _direction(proxies: np.ndarray, axis: int | None) -> int:
    if axis is None:
        return choose_direction(proxies, -1, 0)[0]
    if axis not in range(len(DIRECTIONS)):
        raise ValueError(f"sap axis must be 0 (x), 1 (y), 2 or 3 (slanted), got {axis!r}")
    return int(axis)


def describe(aabb: np.ndarray, axis: int | None = None) -> dict:
    """The sweep for drawing: ``axis`` (the direction's index in :data:`DIRECTIONS`),
    ``direction`` (its unit vector), ``label`` (its name), ``order`` (shapes sorted by ``lo``)
    and ``intervals`` (m, 2) ``[lo, hi]`` of each shape along the direction (m)."""
    proxies = proxies_of(aabb, np.zeros(len(aabb)), np.arange(len(aabb)))
    d = _direction(proxies, axis)
    intervals = np.array([interval(box, d) for box in np.asarray(aabb, float)]).reshape(-1, 2)
    order = np.argsort(intervals[:, 0], kind="stable")
    return {
        "axis": d,
        "direction": DIRECTIONS[d].copy(),
        "label": NAMES[d],
        "order": order,
        "intervals": intervals,
    }
