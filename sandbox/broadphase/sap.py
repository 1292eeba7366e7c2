"""Sort and sweep (sweep and prune) along one direction, in bands across it (slides, "Collision
Detection Performance": co-ordinate sorting).

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

Swept along x alone, a box is tested against every box whose x interval overlaps its own: a
strip one box wide across the whole world, however tall. A pile of m discs holds about
sqrt(m) of them in such a strip, and the tests grow as m^1.5 (the rain of 5,000 discs at rest:
337,864 tests for 14,896 overlapping pairs). So the boxes are also cut into bands across the
sweep (:func:`band_layout`: along x, horizontal bands twice as tall as the mean box,
:data:`BAND_SPAN`), a box goes into every band it crosses, and each band is swept on its own.
Two overlapping boxes are tested in one band only, the band where their overlap begins (the
later of their first bands), so no pair is tested twice. The same pile then takes 30,970 tests
(34,360 candidates visited), and the sweep's loop 128 us instead of 869 (209 us with the
copies into bands and the kept order brought up to date). Bands also undo the lattice's
shared ``lo``: a row of balls far apart along x falls in one band but is swept along x there
(1,000 balls on a 10 m grid: no test at all, against 875 along the best turned direction). So
the step chooses between x and y only, by their candidates counted band by band; the turned
directions remain for the sweep in one band (``bands=False``), as the broadphase lesson
compares them.

The world's step keeps the order from one step to the next (:func:`update_order`): bodies move
little in a step, so an insertion sort of last step's order takes about O(m) (incremental sort
and sweep). Either way the boxes are sorted by (lower end, index), so the pairs and the test
count are the same.
"""

from __future__ import annotations

import math

import numpy as np

from sandbox.broadphase.aabb import put_pair, sort_pairs
from sandbox.jit import ON, literally, njit
from sandbox.records import PROXY, SWEEP_ENTRY
from sandbox.sorting import argsort, sort_in_place

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
# a band across the sweep is this many times the boxes' mean extent across it. Measured on the
# rain of 5,000 discs at rest, swept along x: 1.5 visits 31,624 candidates, 2 visits 34,188,
# 3 visits 41,396 and 4 visits 48,052 (each box in 1.7, 1.5, 1.3 and 1.25 bands); 1.5 and 2
# took as long (a first version of the loop, 190 us)
BAND_SPAN = 2.0
MAX_BANDS = 1024  # a far outlier makes the bands no finer than the span of the world / this
ONE_BAND = (0.0, 0.0, 1)  # the layout of a sweep in one band (band_layout)
MIN_BANDED = 64  # fewer boxes are swept in one band: they gain nothing (rain of 100: 3 us both)


@njit(python=True)
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
def candidates(proxies, d: int, layout) -> int:
    """How many boxes the sweep along direction ``d`` would test, band by band (``layout``
    from :func:`band_layout`; :data:`ONE_BAND` for the plain sweep): in each band the pairs
    (i, j), j after i in the sorted order, with lo_j <= hi_i. Box i at place p of its band has
    ``#{j: lo_j <= hi_i}`` boxes with such a ``lo``, itself and the p before it included, so
    a band's count is the sum of those numbers less 1 + 2 + ... + n; with both ends sorted,
    one walk along them finds all the numbers. A pair that shares two bands is counted in
    both, as the sweep visits it in both (and tests it in one)."""
    starts, entries = gather(proxies, d, layout)  # any kept order: each band is sorted here
    lo, hi = entries["lo"].copy(), entries["hi"].copy()
    total = 0
    for b in range(starts.shape[0] - 1):
        s0, s1 = starts[b], starts[b + 1]
        sort_in_place(lo[s0:s1])
        sort_in_place(hi[s0:s1])
        j = s0  # the boxes with lo_j <= the current hi
        for i in range(s0, s1):
            while j < s1 and lo[j] <= hi[i]:
                j += 1
            total += j - s0
        total -= (s1 - s0) * (s1 - s0 + 1) // 2
    return total


@njit(python=True)
def choose_direction(proxies, current: int, recount: int, banded: bool = True) -> tuple[int, int]:
    """``(direction, steps until the next choice)``: ``current`` while its time runs, else the
    direction whose :func:`candidates` cost least (the first on a tie): x or y in their bands,
    or unless ``banded``, any of :data:`DIRECTIONS` in one band, a slanted one's count
    weighing :data:`SLANTED_COST` times. In bands the turned directions never pay: a lattice's
    rows and columns fall apart into bands, and a slanted sweep is not cut."""
    if current >= 0 and recount > 0:
        return current, recount - 1
    best, least = 0, -1.0
    if proxies.shape[0] >= 2:
        for d in range(2 if banded else DIRECTIONS.shape[0]):
            layout = band_layout(proxies, d) if banded else ONE_BAND
            cost = candidates(proxies, d, layout) * (SLANTED_COST if d >= 2 else 1.0)
            if least < 0.0 or cost < least:
                best, least = d, cost
    return best, RECOUNT


@njit(python=True)
def across(d: int) -> int:
    """The axis the bands cut across sweep direction ``d``: y (1) for x and the slanted ones,
    x (0) for y."""
    return 1 if d >= 2 else 1 - d


@njit(python=True)
def band_layout(proxies, d: int) -> tuple[float, float, int]:
    """``(y0 (m), bands per metre (1/m), count)`` of the bands across sweep direction ``d``.

    Along x the boxes are cut into horizontal bands (along y, vertical ones) of equal height,
    from the lowest box to the highest: as many as fit :data:`BAND_SPAN` times the boxes' mean
    extent across the sweep, plus one (so a band is at most that tall), at most
    :data:`MAX_BANDS` and never more than the boxes. A slanted sweep, a
    world of fewer than :data:`MIN_BANDED` boxes, and boxes that are not finite get one band
    (the plain sweep)."""
    m = proxies.shape[0]
    if d >= 2 or m < MIN_BANDED:
        return ONE_BAND
    o = across(d)
    y0, y1, extent = math.inf, -math.inf, 0.0
    for s in range(m):
        a = proxies[s]["aabb"]
        y0, y1 = min(y0, a[o]), max(y1, a[o + 2])
        extent += a[o + 2] - a[o]
    height = BAND_SPAN * extent / m
    if not (np.isfinite(y1 - y0) and height > 0.0):
        return ONE_BAND
    count = min(MAX_BANDS, m, int((y1 - y0) / height) + 1)
    if count == 1:
        return ONE_BAND
    return y0, count / (y1 - y0), count


@njit(python=True)
def band_of(y: float, layout) -> int:
    """The band holding ``y`` (m), ``layout`` from :func:`band_layout`: the first and last
    bands take what lies beyond them, and a value that is not a number falls in the first."""
    y0, per, count = layout
    if count == 1:
        return 0
    t = (y - y0) * per
    if not t >= 1.0:  # below the second band, or not a number
        return 0
    if t >= count:  # beyond the last band, or infinite (which int() would not survive)
        return count - 1
    return int(t)


@njit
def band_spans(proxies, d: int, layout):
    """``(starts, spans)``: each shape's first and last band ``spans`` (m, 2) (``layout`` from
    :func:`band_layout`), and where each band's entries start (``count + 1``, the last the
    number of entries), a box entered in every band it crosses."""
    o = across(d)
    count = layout[2]
    starts = np.zeros(count + 1, dtype=np.int64)
    spans = np.empty((proxies.shape[0], 2), dtype=np.int64)
    for s in range(proxies.shape[0]):
        a = proxies[s]["aabb"]
        first, last = band_of(a[o], layout), band_of(a[o + 2], layout)
        spans[s, 0], spans[s, 1] = first, last
        for b in range(first, last + 1):
            starts[b + 1] += 1
    for b in range(count):
        starts[b + 1] += starts[b]
    return starts, spans


@njit(python=True)
def gather(proxies, d: int, layout):
    """The boxes band by band (``layout`` from :func:`band_layout`), each band in sweep order
    (the kept ``proxies["order"]``): a box goes into every band it crosses.

    Returns ``(starts, entries)``: band ``b`` holds ``entries[starts[b]:starts[b + 1]]``,
    SWEEP_ENTRY records (each box's interval along ``d``, the box, its shape, body, fixed
    flags and first band). The sweep then reads memory front to back, one record a box,
    instead of jumping around (several times faster for thousands of shapes; a record read
    against three arrays: 124 against 177 us on the rain of 5,000 at rest)."""
    m, count = proxies.shape[0], layout[2]
    o = across(d)
    starts, spans = band_spans(proxies, d, layout)
    entries = np.empty(starts[count], dtype=SWEEP_ENTRY)
    fill = starts[:count].copy()
    for s in range(m):
        i = proxies[s]["order"]
        p = proxies[i]
        a = p["aabb"]
        first = spans[i, 0]
        for b in range(first, spans[i, 1] + 1):
            e = entries[fill[b]]
            fill[b] += 1
            e["lo"], e["hi"] = interval(a, d)
            e["lo_across"], e["hi_across"], e["x0"], e["x1"] = a[o], a[o + 2], a[0], a[2]
            e["shape"], e["body"], e["fixed"], e["first"] = i, p["body"], p["fixed"], first
    return starts, entries


@njit
def sap_kernel(bands, d: int, buf, tested, slanted: bool, record: bool):
    """``(k pairs, pair_tests)`` sweeping along direction ``d`` over the bands of
    :func:`gather` (``bands`` = (starts, entries)); the pairs are written to ``buf`` as far as
    they fit, and with ``record`` the pairs tested to ``tested`` (as far as they fit).
    ``slanted`` must be ``d >= 2``; it and ``record`` are compiled in (``literally``: a version
    for each value), so that the plain sweep's loop carries neither test (the rain of 5,000 at
    rest in one band: 1,221 us with both tests in the loop, 916 without).

    In each band, box ``e`` is tested against the boxes after it until one starts beyond its
    upper end. Two boxes that overlap share the band of their overlap's lower edge, the later
    of their first bands: they are tested there and nowhere else, so a pair is tested once.
    Along x or y the candidates all overlap box ``e`` on that axis (they start between its two
    ends), so the AABB test is left with the other axis; along a slanted direction it takes
    both. The loop is written without a branch on the test's outcome (which is as good as
    random, so the processor would guess it wrong half the time): every candidate is written
    at the end of the pair list, which then grows by 1 or 0.
    """
    literally(slanted)
    literally(record)
    starts, entries = bands
    k = 0
    tests = 0
    nb = buf.shape[0]
    for band in range(starts.shape[0] - 1):
        end = starts[band + 1]
        for e in range(starts[band], end):
            p = entries[e]
            hi, x0, x1, lo_o, hi_o = p["hi"], p["x0"], p["x1"], p["lo_across"], p["hi_across"]
            i, body_i, fixed_i, first_i = p["shape"], p["body"], p["fixed"], p["first"]
            first = k
            for r in range(e + 1, end):
                q = entries[r]
                if q["lo"] > hi:
                    break  # sorted by lo: nothing further along can reach box e
                # not one body, not both fixed (aabb.skip_pair), met in this band: one test
                here = max(first_i, q["first"]) == band
                test = (q["body"] != body_i) & ((fixed_i & q["fixed"]) == 0) & here
                hit = test & (q["lo_across"] <= hi_o) & (lo_o <= q["hi_across"])
                if slanted:  # and x too
                    hit &= (q["x0"] <= x1) & (x0 <= q["x1"])
                if k < nb:
                    buf[k, 1] = q["shape"]
                if record and test:
                    put_pair(tested, tests, i, q["shape"])
                k += hit
                tests += test
            for q in range(first, min(k, nb)):  # the pairs (i, j) of box e, with i < j
                j = buf[q, 1]
                buf[q, 0], buf[q, 1] = min(i, j), max(i, j)
    return k, tests


@njit(python=True)
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
    order = argsort(keys)  # stable: ties in index order
    for s in range(m):
        proxies[s]["order"] = order[s]


@njit
def sweep(proxies, kept: int, recount: int, buf):
    """One sweep of the step: choose the direction (:func:`choose_direction`; ``kept`` is the
    one the order is sorted along, ``recount`` the steps left until the next choice), bring the
    kept order up to date, copy the boxes into it band by band and sweep. Returns
    ``(direction, recount, k pairs, pair_tests)``; pairs in ``buf`` as far as they fit (as
    :func:`sap_kernel`)."""
    d, recount = choose_direction(proxies, kept, recount, ON)  # in bands
    update_order(proxies, d, kept)
    bands = gather(proxies, d, band_layout(proxies, d))
    none = np.empty((0, 2), dtype=np.int64)
    if d >= 2:  # only a direction kept from a sweep in one band (choose_direction)
        k, tests = sap_kernel(bands, d, buf, none, True, False)
    else:
        k, tests = sap_kernel(bands, d, buf, none, False, False)
    return d, recount, k, tests


@njit
def sweep_bands(bands, d: int, buf, tested, record: bool) -> tuple[int, int]:
    """:func:`sap_kernel` with its compiled-in choices made at run time (for :func:`find`)."""
    if d >= 2:
        if record:
            return sap_kernel(bands, d, buf, tested, True, True)
        return sap_kernel(bands, d, buf, tested, True, False)
    if record:
        return sap_kernel(bands, d, buf, tested, False, True)
    return sap_kernel(bands, d, buf, tested, False, False)


def proxies_of(aabb: np.ndarray, static: np.ndarray, body: np.ndarray) -> np.ndarray:
    """PROXY records for plain arrays: boxes (m, 4), a fixed flag and a body per shape."""
    proxies = np.zeros(len(aabb), dtype=PROXY)
    proxies["aabb"], proxies["fixed"], proxies["body"] = aabb, static, body
    proxies["order"] = np.arange(len(aabb))  # a sweep order from the start, if not a sorted one
    return proxies


def find(
    aabb: np.ndarray,
    static: np.ndarray,
    body: np.ndarray,
    record: bool = False,
    axis: int | None = None,
    bands: bool = True,
):
    """``(pairs, pair_tests, tested)``; ``axis``: the sweep direction, an index into
    :data:`DIRECTIONS` (0 x, 1 y, 2 and 3 slanted); by default :func:`choose_direction`'s;
    ``bands``: cut the boxes into bands across the sweep (:func:`band_layout`, as the step
    does), or sweep them all in one."""
    proxies = proxies_of(aabb, static, body)
    d = _direction(proxies, axis, bands)
    m = len(aabb)
    update_order(proxies, d, -1)
    swept = gather(proxies, d, band_layout(proxies, d) if bands else ONE_BAND)
    buf = np.empty((4 * m + 64, 2), dtype=np.int64)
    tested = np.empty((0, 2), dtype=np.int64)
    k, tests = sweep_bands(swept, d, buf, tested, False)
    if k > len(buf) or record:
        buf = np.empty((k, 2), dtype=np.int64)
        tested = np.empty((tests if record else 0, 2), dtype=np.int64)
        k, tests = sweep_bands(swept, d, buf, tested, record)
    return sort_pairs(buf, k, m), int(tests), tested


def _direction(proxies: np.ndarray, axis: int | None, bands: bool) -> int:
    if axis is None:
        return choose_direction(proxies, -1, 0, bands)[0]
    if axis not in range(len(DIRECTIONS)):
        raise ValueError(f"sap axis must be 0 (x), 1 (y), 2 or 3 (slanted), got {axis!r}")
    return int(axis)


def describe(aabb: np.ndarray, axis: int | None = None, bands: bool = True) -> dict:
    """The sweep for drawing: ``axis`` (the direction's index in :data:`DIRECTIONS`),
    ``direction`` (its unit vector), ``label`` (its name), ``order`` (shapes sorted by ``lo``),
    ``intervals`` (m, 2) ``[lo, hi]`` of each shape along the direction (m), ``across`` (the
    axis the bands cut, 0 x or 1 y, -1 for one band), ``edges`` (the bands' edges along it,
    m; the outer two stand for the world's ends) and ``band`` (m, 2) the first and last band
    of each shape."""
    box = np.asarray(aabb, float).reshape(-1, 4)
    proxies = proxies_of(box, np.zeros(len(box)), np.arange(len(box)))
    d = _direction(proxies, axis, bands)
    intervals = np.array([interval(b, d) for b in box]).reshape(-1, 2)
    order = np.argsort(intervals[:, 0], kind="stable")
    layout = band_layout(proxies, d) if bands else ONE_BAND
    y0, per, count = layout
    o = across(d)
    band = np.array([[band_of(b[o], layout), band_of(b[o + 2], layout)] for b in box], int)
    return {
        "axis": d,
        "direction": DIRECTIONS[d].copy(),
        "label": NAMES[d],
        "order": order,
        "intervals": intervals,
        "across": o if count > 1 else -1,
        "edges": y0 + np.arange(count + 1) / per if count > 1 else np.zeros(0),
        "band": band.reshape(-1, 2),
    }
