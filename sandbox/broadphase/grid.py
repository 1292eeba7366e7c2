"""Uniform grid with hashed cells (slides, "Regular Grids": test only bodies sharing same cells).

The plane is cut into square cells of side ``h``; cell ``(cx, cy)`` is ``[cx h, (cx + 1) h) x
[cy h, (cy + 1) h)``, a lattice fixed to the world origin as on the slide. The default ``h`` is
twice the median of the shapes' larger AABB side, so a typical shape covers 1 or 2 cells
(smaller cells mean fewer tests but more cell entries to sort; ``2 x`` was the fastest on random
worlds). Each shape is entered in every cell its AABB touches, and the cells are found through
a hash table (``hash(cx, cy) mod T``), so empty space costs nothing and the world needs no
bounds.

Two shapes are tested only if they share a cell, and a pair sharing several cells is tested
once: in the lower-left cell of the two cell ranges' intersection, ``(max(cx0_i, cx0_j),
max(cy0_i, cy0_j))``, decided on integers before any test.

A shape covering more than ``MAX_CELLS`` cells (a long static floor under tiny balls) is not
entered in the grid; it is tested against every other shape instead.
"""

from __future__ import annotations

import math

import numpy as np

from sandbox.broadphase.aabb import collect, overlap, put_pair, skip_pair
from sandbox.jit import njit
from sandbox.sorting import select

MAX_CELLS = 1024
CELL_FACTOR = 2.0


@njit
def default_cell_size(aabb: np.ndarray) -> float:
    """Twice the median of max(width, height) over the shapes (m); falls back to the mean,
    then 1 m. The median is np.median's, by quickselect (:func:`sandbox.sorting.select`): numba's
    np.median compiled 1.2 s of numpy's library from an empty cache."""
    m = aabb.shape[0]
    if m == 0:
        return 1.0
    ext = np.empty(m)
    total = 0.0
    for i in range(m):
        ext[i] = max(aabb[i, 2] - aabb[i, 0], aabb[i, 3] - aabb[i, 1])
        total += ext[i]
    h = total  # with a NaN, np.median's NaN: the mean (NaN), then 1 m
    if not np.isnan(total):
        h = select(ext, m, m // 2)  # the upper middle; ext[:m // 2] is no larger
        if m % 2 == 0:
            lower = ext[0]
            for i in range(1, m // 2):
                lower = max(lower, ext[i])
            h = 0.5 * (h + lower)
    if not h > 0.0:
        h = total / m
    if not (h > 0.0 and np.isfinite(h)):
        return 1.0
    return CELL_FACTOR * h


@njit(python=True)
def cell_ranges(aabb: np.ndarray, h: float):
    """Each shape's cell range ``(m, 4)`` int64 ``[cx0, cy0, cx1, cy1]``, ``c = floor(x / h)``:
    cell ``(cx, cy)`` is ``[cx h, (cx + 1) h) x [cy h, (cy + 1) h)``, fixed to the world."""
    m = aabb.shape[0]
    cells = np.empty((m, 4), dtype=np.int64)
    for i in range(m):
        cells[i, 0] = int(math.floor(aabb[i, 0] / h))
        cells[i, 1] = int(math.floor(aabb[i, 1] / h))
        cells[i, 2] = int(math.floor(aabb[i, 2] / h))
        cells[i, 3] = int(math.floor(aabb[i, 3] / h))
    return cells


@njit
def cell_hash(cx: int, cy: int, mask: int) -> int:
    """Spatial hash of a cell (two large primes, xor), reduced to the table size."""
    return ((cx * 73856093) ^ (cy * 19349663)) & mask


@njit
def grid_kernel(
    aabb: np.ndarray,
    static: np.ndarray,
    body: np.ndarray,
    h: float,
    buf: np.ndarray,
    tested: np.ndarray,
):
    """``(k pairs, pair_tests)`` with cells of side ``h`` (m); pairs written to ``buf``, tested
    pairs to ``tested`` (as far as they fit; see ``aabb.collect``)."""
    m = aabb.shape[0]
    cells = cell_ranges(aabb, h)
    big = np.zeros(m, dtype=np.bool_)
    entries = 0
    for i in range(m):
        n = (cells[i, 2] - cells[i, 0] + 1) * (cells[i, 3] - cells[i, 1] + 1)
        if n > MAX_CELLS:
            big[i] = True
        else:
            entries += n
    size = 16
    while size < entries:
        size *= 2
    mask = size - 1
    # counting sort of (cell, shape) entries into hash buckets, shapes in increasing order
    start = np.zeros(size + 1, dtype=np.int64)
    for i in range(m):
        if not big[i]:
            for cx in range(cells[i, 0], cells[i, 2] + 1):
                for cy in range(cells[i, 1], cells[i, 3] + 1):
                    start[cell_hash(cx, cy, mask) + 1] += 1
    for b in range(size):
        start[b + 1] += start[b]
    fill = start[:size].copy()
    e_cell = np.empty(entries, dtype=np.int64)  # cx * 2^32 + cy
    e_tag = np.empty(entries, dtype=np.int64)  # 4 * shape + (cx == cx0) + 2 * (cy == cy0)
    for i in range(m):
        if not big[i]:
            for cx in range(cells[i, 0], cells[i, 2] + 1):
                for cy in range(cells[i, 1], cells[i, 3] + 1):
                    b = cell_hash(cx, cy, mask)
                    e_cell[fill[b]] = (cx << 32) + cy
                    e_tag[fill[b]] = 4 * i + (cx == cells[i, 0]) + 2 * (cy == cells[i, 1])
                    fill[b] += 1
    k = 0
    tests = 0
    for b in range(size):
        for p in range(start[b], start[b + 1]):
            cell, tag = e_cell[p], e_tag[p]
            for q in range(p + 1, start[b + 1]):
                if e_cell[q] != cell:
                    continue  # another cell with the same hash
                # test the pair only in the first cell both occupy, the lower-left corner of
                # their cell ranges' intersection: there cx = max(cx0_i, cx0_j), i.e. the
                # first column of i or of j, and likewise for the row
                first = tag | e_tag[q]
                if (first & 3) != 3:
                    continue
                i = tag >> 2
                j = e_tag[q] >> 2
                if skip_pair(static, body, i, j):
                    continue
                put_pair(tested, tests, i, j)
                tests += 1
                if overlap(aabb, i, j):
                    put_pair(buf, k, i, j)
                    k += 1
    # shapes too big for the grid: against everything (big-big pairs once)
    for i in range(m):
        if big[i]:
            for j in range(m):
                if j == i or (big[j] and j < i) or skip_pair(static, body, i, j):
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
    cell_size: float | None = None,
):
    """``(pairs, pair_tests, tested)``; ``cell_size`` (m) defaults to :func:`default_cell_size`."""
    h = _cell(aabb, cell_size)
    return collect(grid_kernel, len(aabb), record, aabb, static, body, h)


def _cell(aabb: np.ndarray, cell_size: float | None) -> float:
    """The cell side: given or default, never so small that cell indices pass 2^30 (the
    kernel packs a cell into one int64 as ``cx * 2^32 + cy``)."""
    h = default_cell_size(aabb) if cell_size is None else float(cell_size)
    if not (h > 0.0 and math.isfinite(h)):
        raise ValueError(f"grid cell_size must be a positive number, got {cell_size!r}")
    if len(aabb):
        reach = float(np.max(np.abs(aabb)))
        if math.isfinite(reach):
            h = max(h, reach / 2.0**30)
    return h


def describe(aabb: np.ndarray, cell_size: float | None = None) -> dict:
    """The grid for drawing: ``cell_size`` h, ``cells`` (c, 2) occupied cells ``(cx, cy)`` (cell
    ``(cx, cy)`` spans ``h [cx, cx + 1] x h [cy, cy + 1]``), per-shape cell ``ranges`` (m, 4)
    and the ``big`` shapes left out of the grid."""
    h = _cell(aabb, cell_size)
    if len(aabb) == 0:
        return {"cell_size": h, "cells": np.zeros((0, 2), np.int64)}
    ranges = cell_ranges(aabb, h)
    n = (ranges[:, 2] - ranges[:, 0] + 1) * (ranges[:, 3] - ranges[:, 1] + 1)
    big = n > MAX_CELLS
    occupied = set()
    for i in np.flatnonzero(~big):
        cx0, cy0, cx1, cy1 = (int(v) for v in ranges[i])
        occupied.update((cx, cy) for cx in range(cx0, cx1 + 1) for cy in range(cy0, cy1 + 1))
    cells = np.array(sorted(occupied), dtype=np.int64).reshape(-1, 2)
    return {"cell_size": h, "cells": cells, "ranges": ranges, "big": big}
