"""Brute force: test every pair of shapes (slides, "Collision Detection Performance": the
simplest solution, n(n-1)/2 combinations).

``pair_tests`` is m(m-1)/2 minus the pairs skipped *before* the test because both shapes are
static or share a body; for m shapes on m distinct dynamic bodies it is exactly m(m-1)/2.
"""

from __future__ import annotations

import numpy as np

from sandbox.broadphase.aabb import collect, overlap, put_pair, skip_pair
from sandbox.jit import njit


@njit
def brute_kernel(
    aabb: np.ndarray, static: np.ndarray, body: np.ndarray, buf: np.ndarray, tested: np.ndarray
):
    """``(k pairs, pair_tests)`` over all pairs i < j, pairs written to ``buf``, tested pairs to
    ``tested`` (as far as they fit; see ``aabb.collect``)."""
    m = aabb.shape[0]
    k = 0
    tests = 0
    for i in range(m):
        for j in range(i + 1, m):
            if skip_pair(static, body, i, j):
                continue
            put_pair(tested, tests, i, j)
            tests += 1
            if overlap(aabb, i, j):
                put_pair(buf, k, i, j)
                k += 1
    # pairs come out in lexicographic order already
    return k, tests


def find(aabb: np.ndarray, static: np.ndarray, body: np.ndarray, record: bool = False):
    """``(pairs, pair_tests, tested)`` for every pair of shapes."""
    return collect(brute_kernel, len(aabb), record, aabb, static, body)


def describe(aabb: np.ndarray) -> dict:
    """Nothing to draw: brute force has no structure."""
    return {"m": int(len(aabb))}
