"""kd-tree (slides, "Collision Detection Performance": KD-trees).

Each node with more than ``capacity`` boxes is split by a line through the median of the box
centres, across the axis along which the centres spread more. Boxes wholly below the line go to
the lower child, boxes wholly above to the upper child, and boxes straddling it (``lo <= split
<= hi``) stay at the node. Boxes in different subtrees are separated by a line and never tested.

Pairs are tested in two ways, each pair at most once:

1. boxes kept at the same node: all of them cross the split line, so they already overlap on
   the split axis; they are sorted by their lower end along the line and swept (as in
   ``sap``). Leaves are swept along x.
2. a box against the boxes kept at each of its ancestors: those are sorted along the ancestor's
   line, so a binary search finds the first one that can reach the box (lower end at least
   ``lo - widest``) and the scan stops at the first one starting beyond the box. An ancestor
   is skipped at once when the box misses the band its kept boxes cover across the line.
"""

from __future__ import annotations

import numpy as np

from sandbox.broadphase.aabb import check_tree_options, collect, overlap, put_pair, skip_pair
from sandbox.jit import njit
from sandbox.sorting import argsort, select

CAPACITY = 8
MAX_DEPTH = 40


@njit
def sort_kept(idx: np.ndarray, key: np.ndarray, s: int, o: int, aabb: np.ndarray, u: int):
    """Sort ``idx[s:s + o]`` by the boxes' lower end on axis ``u`` (stable), filling ``key``."""
    for p in range(s, s + o):
        key[p] = aabb[idx[p], u]
    if o <= 32:  # insertion sort for the usual short lists
        for a in range(s + 1, s + o):
            kv, iv = key[a], idx[a]
            b = a - 1
            while b >= s and key[b] > kv:
                key[b + 1] = key[b]
                idx[b + 1] = idx[b]
                b -= 1
            key[b + 1] = kv
            idx[b + 1] = iv
    else:
        order = argsort(key[s : s + o])
        kept = idx[s : s + o].copy()
        for r in range(o):
            idx[s + r] = kept[order[r]]
            key[s + r] = aabb[idx[s + r], u]


@njit(python=True)
def build_kdtree(aabb: np.ndarray, capacity: int, max_depth: int):
    """Nodes and the box order ``idx``: node ``q`` keeps ``idx[start[q]:start[q] + own[q]]``
    (sorted by ``key``, their lower end along the node's line, axis ``line[q]``), followed by
    its subtree's boxes. ``axis[q]`` is the split axis (-1 for a leaf), ``split[q]`` the line's
    coordinate, ``wide[q]`` the widest kept box along the line, ``band[q]`` the range the kept
    boxes cover on the split axis, ``region[q]`` the node's rectangle (for drawing)."""
    m = aabb.shape[0]
    cap = 2 * m + 2  # every leaf holds a box and every inner node keeps one or has two children
    start = np.empty(cap, dtype=np.int64)
    end = np.empty(cap, dtype=np.int64)
    own = np.empty(cap, dtype=np.int64)
    axis = np.empty(cap, dtype=np.int64)
    line = np.empty(cap, dtype=np.int64)
    split = np.zeros(cap)
    wide = np.zeros(cap)
    band = np.zeros((cap, 2))
    parent = np.empty(cap, dtype=np.int64)
    depth = np.empty(cap, dtype=np.int64)
    region = np.empty((cap, 4))
    idx = np.arange(m)
    key = np.empty(m)
    centre = np.empty((m, 2))
    scratch = np.empty(m)
    side = np.empty(m, dtype=np.int64)
    moved = np.empty(m, dtype=np.int64)
    counts = np.zeros(3, dtype=np.int64)
    region[0, 0] = region[0, 1] = np.inf
    region[0, 2] = region[0, 3] = -np.inf
    for i in range(m):
        centre[i, 0] = 0.5 * (aabb[i, 0] + aabb[i, 2])
        centre[i, 1] = 0.5 * (aabb[i, 1] + aabb[i, 3])
        region[0, 0] = min(region[0, 0], aabb[i, 0])
        region[0, 1] = min(region[0, 1], aabb[i, 1])
        region[0, 2] = max(region[0, 2], aabb[i, 2])
        region[0, 3] = max(region[0, 3], aabb[i, 3])
    start[0], end[0], parent[0], depth[0] = 0, m, -1, 0
    nn = 1
    q = 0
    while q < nn:
        s, e = start[q], end[q]
        n = e - s
        ax = -1
        if n > capacity and depth[q] < max_depth:
            # split across the axis of larger spread of the centres
            lox, hix = np.inf, -np.inf
            loy, hiy = np.inf, -np.inf
            for p in range(s, e):
                i = idx[p]
                lox, hix = min(lox, centre[i, 0]), max(hix, centre[i, 0])
                loy, hiy = min(loy, centre[i, 1]), max(hiy, centre[i, 1])
            if hix - lox > 0.0 or hiy - loy > 0.0:
                ax = 0 if hix - lox >= hiy - loy else 1
        if ax < 0:
            own[q] = n  # leaf: every box stays, swept along x
            axis[q] = -1
            line[q] = 0
        else:
            for p in range(s, e):
                scratch[p - s] = centre[idx[p], ax]
            cut = select(scratch, n, (n - 1) // 2)  # the (lower) median centre
            # stable three-way partition: straddling (kept) | wholly below | wholly above
            # (side 0, 1, 2 computed without branches: they would be mispredicted half the time)
            counts[:] = 0
            for p in range(s, e):
                i = idx[p]
                c = np.int64(aabb[i, ax + 2] < cut) + 2 * np.int64(aabb[i, ax] > cut)
                side[p - s] = c
                counts[c] += 1
            kept, below = counts[0], counts[1]
            counts[0], counts[1], counts[2] = 0, kept, kept + below  # write positions
            for p in range(s, e):
                c = side[p - s]
                moved[counts[c]] = idx[p]
                counts[c] += 1
            band[q, 0], band[q, 1] = np.inf, -np.inf
            for r in range(n):
                idx[s + r] = moved[r]
                if r < kept:
                    band[q, 0] = min(band[q, 0], aabb[moved[r], ax])
                    band[q, 1] = max(band[q, 1], aabb[moved[r], ax + 2])
            own[q] = kept
            axis[q] = ax
            line[q] = 1 - ax
            split[q] = cut
            for lo, hi, bound in ((s + kept, s + kept + below, ax + 2), (s + kept + below, e, ax)):
                if hi > lo:
                    start[nn], end[nn], parent[nn], depth[nn] = lo, hi, q, depth[q] + 1
                    for c in range(4):
                        region[nn, c] = region[q, c]
                    region[nn, bound] = cut
                    nn += 1
        # the kept boxes sorted by their lower end along the line
        u = line[q]
        sort_kept(idx, key, s, own[q], aabb, u)
        wmax = 0.0
        for p in range(s, s + own[q]):
            wmax = max(wmax, aabb[idx[p], u + 2] - aabb[idx[p], u])
        wide[q] = wmax
        q += 1
    return (
        idx,
        key,
        start[:nn],
        own[:nn],
        axis[:nn],
        line[:nn],
        split[:nn],
        wide[:nn],
        band[:nn],
        parent[:nn],
        depth[:nn],
        region[:nn],
    )


@njit
def first_not_below(key: np.ndarray, start: int, end: int, value: float) -> int:
    """The first place in sorted ``key[start:end]`` whose key is not below ``value``
    (``start + np.searchsorted(key[start:end], value)``, by bisection: numpy's compiled
    searchsorted took 0.5 s to compile from an empty cache)."""
    lo, hi = start, end
    while lo < hi:
        mid = (lo + hi) // 2
        if key[mid] < value:
            lo = mid + 1
        else:
            hi = mid
    return lo


@njit
def kdtree_kernel(
    aabb: np.ndarray,
    static: np.ndarray,
    body: np.ndarray,
    capacity: int,
    max_depth: int,
    buf: np.ndarray,
    tested: np.ndarray,
):
    """``(k pairs, pair_tests)``; pairs written to ``buf``, tested pairs to ``tested`` (as far
    as they fit; see ``aabb.collect``)."""
    idx, key, start, own, axis, line, split, wide, band, parent, depth, region = build_kdtree(
        aabb, capacity, max_depth
    )
    k = 0
    tests = 0
    for q in range(start.shape[0]):
        s, e, u = start[q], start[q] + own[q], line[q]
        for a in range(s, e):
            i = idx[a]
            # 1. boxes kept at this node: sweep along the line
            hi = aabb[i, u + 2]
            for b in range(a + 1, e):
                if key[b] > hi:
                    break
                j = idx[b]
                if skip_pair(static, body, i, j):
                    continue
                put_pair(tested, tests, i, j)
                tests += 1
                if overlap(aabb, i, j):
                    put_pair(buf, k, i, j)
                    k += 1
            # 2. against the boxes kept at every ancestor
            anc = parent[q]
            while anc >= 0:
                aa = axis[anc]
                if aabb[i, aa + 2] < band[anc, 0] or aabb[i, aa] > band[anc, 1]:
                    anc = parent[anc]
                    continue  # the box misses every box kept there
                ua = line[anc]
                lo_i, hi_i = aabb[i, ua], aabb[i, ua + 2]
                sa, ea = start[anc], start[anc] + own[anc]
                reach = lo_i - wide[anc] - 1e-9 * (abs(lo_i) + wide[anc])
                first = first_not_below(key, sa, ea, reach)
                for b in range(first, ea):
                    if key[b] > hi_i:
                        break
                    j = idx[b]
                    if skip_pair(static, body, i, j):
                        continue
                    put_pair(tested, tests, i, j)
                    tests += 1
                    if overlap(aabb, i, j):
                        put_pair(buf, k, i, j)
                        k += 1
                anc = parent[anc]
    return k, tests


def find(
    aabb: np.ndarray,
    static: np.ndarray,
    body: np.ndarray,
    record: bool = False,
    capacity: int = CAPACITY,
    max_depth: int = MAX_DEPTH,
):
    """``(pairs, pair_tests, tested)`` with leaves of up to ``capacity`` boxes."""
    capacity, max_depth = check_tree_options("kdtree", capacity, max_depth)
    return collect(kdtree_kernel, len(aabb), record, aabb, static, body, capacity, max_depth)


def describe(aabb: np.ndarray, capacity: int = CAPACITY, max_depth: int = MAX_DEPTH) -> dict:
    """The tree for drawing: per node ``region`` (q, 4), split ``axis`` (-1 leaf) and ``split``
    coordinate, ``depth``, ``kept`` (boxes stored at the node), and ``node_of`` (m,) per box."""
    capacity, max_depth = check_tree_options("kdtree", capacity, max_depth)
    idx, key, start, own, axis, line, split, wide, band, parent, depth, region = build_kdtree(
        aabb, capacity, max_depth
    )
    node_of = np.empty(len(aabb), dtype=np.int64)
    for q in range(len(start)):
        node_of[idx[start[q] : start[q] + own[q]]] = q
    return {
        "region": region,
        "axis": axis,
        "split": split,
        "depth": depth,
        "kept": own,
        "node_of": node_of,
    }
