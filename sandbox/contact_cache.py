"""Warm starting: last step's contact impulses, found again for this step's contacts.

A resting stack needs nearly the same impulses every step. Starting the iterations from last
step's answer instead of zero (box2d-lite's ``Arbiter::Update``) lets a few iterations reach
it. A point of this step matches a point of the last step when the shapes (a, b) and the
narrowphase's feature id are the same; unmatched points start from zero.

The cache is the last solved set of contact rows in the world's
:class:`~sandbox.contact.ContactBuffers` (``world._solver_cache["buffers"]``), which is made
anew when the world's shapes change (shape indices would mean something else). Its manifolds
are in pair order, sorted by (shape a, shape b), as are this step's, so one forward walk
through both finds every match (a merge, O(k)).
"""

from __future__ import annotations

import numpy as np

from sandbox.contact import (
    I_COUNT,
    I_FEATURE,
    I_SA,
    I_SB,
    INT_COLS,
    PN,
    PT,
    S_POINT,
    S_STRIDE,
    SOLVER_COLS,
    buffers,
)
from sandbox.jit import njit


def pair_keys(sa: np.ndarray, sb: np.ndarray, m: int) -> np.ndarray:
    """One int64 per shape pair: sa * m + sb (m shapes)."""
    return sa.astype(np.int64) * np.int64(max(m, 1)) + sb.astype(np.int64)


@njit
def _before(sa0, sb0, sa, sb) -> bool:
    """The shape pair (sa0, sb0) comes before (sa, sb)."""
    return sa0 < sa or (sa0 == sa and sb0 < sb)


@njit
def match_rows(ints, solver, k, old_ints, old_solver, k_old) -> int:
    """Fill the impulses ``PN``, ``PT`` of this step's rows (``ints``, ``solver``, ``k``
    manifolds) with those of the last step's points (``old_*``, ``k_old``, sorted by shape
    pair) that have the same shapes and feature id; zero where none. Returns the number of
    points matched."""
    found = 0
    q = 0  # walks forward through the old rows
    for i in range(k):
        for j in range(2):
            solver[i, S_POINT + S_STRIDE * j + PN] = 0.0
            solver[i, S_POINT + S_STRIDE * j + PT] = 0.0
        sa, sb = ints[i, I_SA], ints[i, I_SB]
        if q > 0 and not _before(old_ints[q - 1, I_SA], old_ints[q - 1, I_SB], sa, sb):
            lo, hi = 0, q  # not in pair order (hand-made manifolds): binary search
            while lo < hi:
                mid = (lo + hi) // 2
                if _before(old_ints[mid, I_SA], old_ints[mid, I_SB], sa, sb):
                    lo = mid + 1
                else:
                    hi = mid
            q = lo
        while q < k_old and _before(old_ints[q, I_SA], old_ints[q, I_SB], sa, sb):
            q += 1
        if q == k_old or old_ints[q, I_SA] != sa or old_ints[q, I_SB] != sb:
            continue
        for j in range(ints[i, I_COUNT]):
            for jj in range(old_ints[q, I_COUNT]):
                if old_ints[q, I_FEATURE + jj] == ints[i, I_FEATURE + j]:
                    p, pp = S_POINT + S_STRIDE * j, S_POINT + S_STRIDE * jj
                    solver[i, p + PN] = old_solver[q, pp + PN]
                    solver[i, p + PT] = old_solver[q, pp + PT]
                    found += 1
                    break
    return found


def _rows_of(manifolds) -> tuple[np.ndarray, np.ndarray]:
    """The ints and the impulse columns of the solver rows of ``manifolds``, sorted by shape
    pair (as the step's rows are)."""
    m = manifolds
    order = np.lexsort((m.sb, m.sa))
    ints = np.zeros((len(m), INT_COLS), dtype=np.int64)
    ints[:, I_SA], ints[:, I_SB], ints[:, I_COUNT] = m.sa[order], m.sb[order], m.count[order]
    ints[:, I_FEATURE : I_FEATURE + 2] = m.feature[order]
    solver = np.zeros((len(m), SOLVER_COLS))
    for j in range(2):
        solver[:, S_POINT + S_STRIDE * j + PN] = m.normal_impulse[order, j]
        solver[:, S_POINT + S_STRIDE * j + PT] = m.tangent_impulse[order, j]
    return ints, solver, order


def load(world, manifolds) -> int:
    """Fill ``manifolds.normal_impulse`` / ``tangent_impulse`` with last step's impulses of the
    matching points (zero elsewhere). Returns the number of points matched."""
    cache = buffers(world)
    ints, solver, order = _rows_of(manifolds)
    old_ints, _, old_solver = cache.rows(cache.now)
    found = match_rows(ints, solver, len(ints), old_ints, old_solver, cache.k[cache.now])
    for j in range(2):
        manifolds.normal_impulse[order, j] = solver[:, S_POINT + S_STRIDE * j + PN]
        manifolds.tangent_impulse[order, j] = solver[:, S_POINT + S_STRIDE * j + PT]
    return int(found)


def save(world, manifolds) -> None:
    """Remember these impulses for the next step's warm start (as a solve does)."""
    cache = buffers(world)
    if manifolds is None or len(manifolds) == 0:
        cache.forget()
        return
    ints, solver, _ = _rows_of(manifolds)
    k = len(ints)
    cache.reserve(k)
    s = cache.begin()
    cache.ints[s][:k] = ints
    cache.solver[s][:k] = solver
    cache.geoms[s][:k] = 0.0
    cache.commit(s, k)
