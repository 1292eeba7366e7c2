"""One stable sort for every kernel that sorts: the sweep's order, the candidates it counts, the
pair list's runs, the kd-tree's splits and the shock layers.

numba compiles its own ``np.sort`` and ``np.argsort`` into every function that calls them, a
few seconds each on a cold cache (the pair list's ``np.sort`` alone took 3.3 s, the sweep's
``argsort`` 1.5 s): the engine's first compile paid for five copies. :func:`argsort` is short,
compiles once for each type of key, and gives what ``np.argsort(keys, kind="stable")`` gives:
equal keys keep their order, and a key that is not a number sorts after every number.
"""

from __future__ import annotations

import numpy as np

from sandbox.jit import njit

RUN = 16  # runs this long are sorted by insertion before the merges


@njit
def before(x, y) -> bool:
    """Whether key ``x`` sorts strictly before ``y``: smaller, or a number before NaN."""
    return x < y or (x == x and y != y)


@njit
def argsort(keys) -> np.ndarray:
    """The indices that sort ``keys`` (1-D), stably, NaN last (bottom-up merge sort: runs of
    :data:`RUN` by insertion, then runs merged pairwise, O(n log n))."""
    n = keys.shape[0]
    order = np.arange(n)
    for lo in range(0, n, RUN):
        for i in range(lo + 1, min(lo + RUN, n)):
            item = order[i]
            j = i - 1
            while j >= lo and before(keys[item], keys[order[j]]):
                order[j + 1] = order[j]
                j -= 1
            order[j + 1] = item
    src, dst = order, np.empty_like(order)
    width = RUN
    while width < n:
        for lo in range(0, n, 2 * width):
            mid, hi = min(lo + width, n), min(lo + 2 * width, n)
            i, j = lo, mid
            for k in range(lo, hi):  # the right run's item only when strictly before: stable
                if j < hi and (i >= mid or before(keys[src[j]], keys[src[i]])):
                    dst[k] = src[j]
                    j += 1
                else:
                    dst[k] = src[i]
                    i += 1
        src, dst = dst, src
        width *= 2
    return src


@njit
def sort_in_place(values) -> None:
    """Sort ``values`` (1-D, a view is sorted where it lies) as :func:`argsort` orders them."""
    order, before_sorting = argsort(values), values.copy()
    for i in range(values.shape[0]):  # a loop: numba's fancy indexing takes seconds to compile
        values[i] = before_sorting[order[i]]


@njit
def select(x: np.ndarray, n: int, k: int) -> float:
    """The ``k``-th smallest of ``x[:n]`` (quickselect, median-of-three pivot; reorders ``x``)."""
    lo = 0
    hi = n - 1
    while lo < hi:
        mid = (lo + hi) // 2
        a, b, c = x[lo], x[mid], x[hi]
        pivot = max(min(a, b), min(max(a, b), c))
        i = lo
        j = hi
        while i <= j:
            while x[i] < pivot:
                i += 1
            while x[j] > pivot:
                j -= 1
            if i <= j:
                x[i], x[j] = x[j], x[i]
                i += 1
                j -= 1
        if k <= j:
            hi = j
        elif k >= i:
            lo = i
        else:
            break
    return x[k]
