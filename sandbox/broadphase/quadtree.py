"""Quadtree (slides, "Collision Detection Performance": quadtrees in 2D, octrees in 3D).

Recursive subdivision of a square around all boxes into four quadrants. A node holding more
than ``capacity`` boxes is split (down to ``max_depth``), and each box is handed to *every*
child quadrant it touches, so boxes live in all leaves they touch. Only boxes sharing a leaf are
tested. A pair that shares several leaves is tested once, in the leaf containing the lower-left
corner of the two boxes' overlap, ``p = (max(xmin_i, xmin_j), max(ymin_i, ymin_j))`` (leaf
rectangles are half-open, so ``p`` lies in exactly one leaf; if the boxes overlap, ``p`` lies
in both and both are stored in that leaf). That check is a de-duplication, not an overlap test,
and is not counted in ``pair_tests``.

A node is not split when its boxes are so large that the quadrants together would hold more
than ``SPREAD`` times as many entries as the node (splitting would copy boxes, not separate
them).
"""

from __future__ import annotations

import numpy as np

from sandbox.broadphase.aabb import check_tree_options, collect, overlap, put_pair, skip_pair
from sandbox.jit import njit

CAPACITY = 8
MAX_DEPTH = 16
SPREAD = 2.0


@njit
def root_square(aabb: np.ndarray):
    """``(x0, y0, x1, y1)``: a square from the lowest corner of all boxes, a hair larger than
    their extent so every box lies inside its half-open area."""
    m = aabb.shape[0]
    x0 = np.inf
    y0 = np.inf
    x1 = -np.inf
    y1 = -np.inf
    for i in range(m):
        x0 = min(x0, aabb[i, 0])
        y0 = min(y0, aabb[i, 1])
        x1 = max(x1, aabb[i, 2])
        y1 = max(y1, aabb[i, 3])
    side = max(x1 - x0, y1 - y0)
    pad = 1e-9 * side + 1e-12 * max(abs(x0), abs(y0), abs(x1), abs(y1)) + 1e-300
    while x0 + side + pad <= x1 or y0 + side + pad <= y1:
        pad *= 2.0
    return x0, y0, x0 + side + pad, y0 + side + pad


@njit(python=True)
def build_quadtree(aabb: np.ndarray, capacity: int, max_depth: int):
    """Nodes ``rect (q, 4)``, ``depth``, ``child`` (first of 4 children, -1 for a leaf),
    ``start``/``count`` into ``items`` (the shapes stored at each node, in increasing order)."""
    m = aabb.shape[0]
    node_cap = 64 + 8 * (m // capacity)
    item_cap = 64 + 12 * m
    while True:
        rect = np.empty((node_cap, 4))
        depth = np.empty(node_cap, dtype=np.int64)
        child = np.empty(node_cap, dtype=np.int64)
        start = np.empty(node_cap, dtype=np.int64)
        count = np.empty(node_cap, dtype=np.int64)
        items = np.empty(item_cap, dtype=np.int64)
        nn, ni = _fill_quadtree(aabb, capacity, max_depth, rect, depth, child, start, count, items)
        if nn > 0:
            return rect[:nn], depth[:nn], child[:nn], start[:nn], count[:nn], items[:ni]
        # out of room: try again with twice the space (arrays are not grown inside the loop)
        node_cap *= 2
        item_cap *= 2


@njit
def _fill_quadtree(aabb, capacity, max_depth, rect, depth, child, start, count, items):
    """Build into preallocated arrays; ``(nodes, items used)``, or ``(-1, -1)`` when full."""
    m = aabb.shape[0]
    x0, y0, x1, y1 = root_square(aabb)
    rect[0, 0], rect[0, 1], rect[0, 2], rect[0, 3] = x0, y0, x1, y1
    depth[0], child[0], start[0], count[0] = 0, -1, 0, m
    for i in range(m):
        items[i] = i
    nn = 1
    ni = m
    mask = np.empty(m, dtype=np.int64)
    hits = np.zeros(4, dtype=np.int64)
    put = np.zeros(4, dtype=np.int64)
    q = 0
    while q < nn:
        s, c = start[q], count[q]
        if c > capacity and depth[q] < max_depth:
            x0, y0, x1, y1 = rect[q, 0], rect[q, 1], rect[q, 2], rect[q, 3]
            mx = 0.5 * (x0 + x1)
            my = 0.5 * (y0 + y1)
            # quadrants 0 lower-left, 1 lower-right, 2 upper-left, 3 upper-right, half-open
            # [x0, mx) x [y0, my) ...; a box in this node touches quadrant h when bit h is set
            hits[:] = 0
            for a in range(s, s + c):
                i = items[a]
                left = aabb[i, 0] < mx
                right = aabb[i, 2] >= mx
                low = aabb[i, 1] < my
                high = aabb[i, 3] >= my
                bits = (left and low) | (right and low) << 1 | (left and high) << 2
                bits |= (right and high) << 3
                mask[a - s] = bits
                for h in range(4):
                    hits[h] += (bits >> h) & 1
            total = hits[0] + hits[1] + hits[2] + hits[3]
            if total <= SPREAD * c:
                if nn + 4 > rect.shape[0] or ni + total > items.shape[0]:
                    return -1, -1
                child[q] = nn
                for h in range(4):
                    put[h] = ni
                    start[nn + h] = ni
                    count[nn + h] = hits[h]
                    depth[nn + h] = depth[q] + 1
                    child[nn + h] = -1
                    ni += hits[h]
                rect[nn, 0], rect[nn, 1], rect[nn, 2], rect[nn, 3] = x0, y0, mx, my
                rect[nn + 1, 0], rect[nn + 1, 1], rect[nn + 1, 2], rect[nn + 1, 3] = mx, y0, x1, my
                rect[nn + 2, 0], rect[nn + 2, 1], rect[nn + 2, 2], rect[nn + 2, 3] = x0, my, mx, y1
                rect[nn + 3, 0], rect[nn + 3, 1], rect[nn + 3, 2], rect[nn + 3, 3] = mx, my, x1, y1
                for a in range(s, s + c):
                    bits = mask[a - s]
                    for h in range(4):
                        if (bits >> h) & 1:
                            items[put[h]] = items[a]
                            put[h] += 1
                nn += 4
        q += 1
    return nn, ni


@njit
def quadtree_kernel(
    aabb: np.ndarray,
    static: np.ndarray,
    body: np.ndarray,
    capacity: int,
    max_depth: int,
    buf: np.ndarray,
    tested: np.ndarray,
):
    """``(k pairs, pair_tests)``, testing inside the leaves; pairs written to ``buf``, tested
    pairs to ``tested`` (as far as they fit; see ``aabb.collect``)."""
    rect, depth, child, start, count, items = build_quadtree(aabb, capacity, max_depth)
    k = 0
    tests = 0
    for q in range(rect.shape[0]):
        if child[q] >= 0:
            continue
        x0, y0, x1, y1 = rect[q, 0], rect[q, 1], rect[q, 2], rect[q, 3]
        s, e = start[q], start[q] + count[q]
        for a in range(s, e):
            i = items[a]
            for b in range(a + 1, e):
                j = items[b]
                # de-duplication: only the leaf holding the overlap's lower-left corner
                px = max(aabb[i, 0], aabb[j, 0])
                py = max(aabb[i, 1], aabb[j, 1])
                if px < x0 or px >= x1 or py < y0 or py >= y1:
                    continue
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
    capacity: int = CAPACITY,
    max_depth: int = MAX_DEPTH,
):
    """``(pairs, pair_tests, tested)`` with leaves of up to ``capacity`` boxes."""
    capacity, max_depth = check_tree_options("quadtree", capacity, max_depth)
    return collect(quadtree_kernel, len(aabb), record, aabb, static, body, capacity, max_depth)


def describe(aabb: np.ndarray, capacity: int = CAPACITY, max_depth: int = MAX_DEPTH) -> dict:
    """The tree for drawing: node ``rects`` (q, 4) ``[x0, y0, x1, y1]``, ``depth``, ``leaf``
    flags and ``count`` (boxes stored per leaf; entries of split nodes are not used)."""
    capacity, max_depth = check_tree_options("quadtree", capacity, max_depth)
    rect, depth, child, start, count, items = build_quadtree(aabb, capacity, max_depth)
    leaf = child < 0
    return {"rects": rect, "depth": depth, "leaf": leaf, "count": np.where(leaf, count, 0)}
