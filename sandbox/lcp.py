"""Small linear complementarity problems: the exact view of simultaneous contact (lesson 17).

Contact impulses ``lam`` (N s, one per contact point) must satisfy, with ``A = J M^-1 J^T`` (the
Delassus matrix, 1/kg) and ``b`` the normal velocities the contacts would have without them
(m/s, negative while approaching):

    w = A lam + b >= 0,    lam >= 0,    lam_i w_i = 0 for every i

(no point may approach after the step; a point either pushes and stays in touch, or separates
and does not push). :func:`solve_by_enumeration` finds the exact answer of a small problem by
trying every set of pushing points; :func:`projected_gauss_seidel` is what an iterative solver
does instead (sweep over the points, solve each for its own lam given the others, clamp at 0).
"""

from __future__ import annotations

from itertools import combinations

import numpy as np


def is_solution(a: np.ndarray, b: np.ndarray, lam: np.ndarray, tol: float = 1e-9) -> bool:
    """Do ``lam`` (N s) and w = A lam + b (m/s) satisfy the complementarity conditions?"""
    lam = np.asarray(lam, dtype=float)
    w = np.asarray(a, dtype=float) @ lam + np.asarray(b, dtype=float)
    scale = tol * max(1.0, float(np.abs(b).max(initial=0.0)), float(np.abs(lam).max(initial=0.0)))
    return bool((lam >= -scale).all() and (w >= -scale).all() and np.abs(lam * w).max() <= scale)


def solve_by_enumeration(a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, tuple[int, ...]]:
    """The exact solution of the LCP (A, b) and its set of pushing points.

    Tries every subset S of points as the pushing ones (2^n of them; fine for the few points of
    a lesson): lam_S solves A_SS lam_S = -b_S, the others have lam = 0, and the subset is the
    answer when every lam >= 0 and every w >= 0. For a symmetric positive definite A (any set of
    independent contacts) exactly one subset qualifies. Box2D's block solver does this for the
    two points of one manifold.
    """
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    n = len(b)
    for size in range(n + 1):
        for active in combinations(range(n), size):
            lam = np.zeros(n)
            if active:
                idx = list(active)
                lam[idx] = np.linalg.solve(a[np.ix_(idx, idx)], -b[idx])
            if is_solution(a, b, lam):
                return lam, active
    raise ValueError("no subset of pushing points solves this LCP (is A positive definite?)")


def projected_gauss_seidel(
    a: np.ndarray, b: np.ndarray, sweeps: int, start: np.ndarray | None = None
) -> np.ndarray:
    """Impulses after ``sweeps`` sweeps of projected Gauss-Seidel (sequential impulses).

    Each visit sets point i's total impulse so that w_i = 0 given the others, clamped at 0:
    lam_i <- max(0, lam_i - w_i / A_ii). ``start``: warm-start impulses (default zeros).
    Returns an array (sweeps + 1, n): the impulses before the first sweep and after each.
    """
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    lam = np.zeros(len(b)) if start is None else np.array(start, dtype=float)
    out = [lam.copy()]
    for _ in range(sweeps):
        for i in range(len(b)):
            w_i = b[i] + a[i] @ lam
            lam[i] = max(0.0, lam[i] - w_i / a[i, i])
        out.append(lam.copy())
    return np.array(out)
