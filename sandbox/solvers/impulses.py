"""The formulas of one visit of the iterative solver, on numbers alone (slides, "Collision
Equation" and "Iterative Solver"; box2d-lite's ``Arbiter::ApplyImpulse``; Box2D's block
solver). The sweeps over contact records (:mod:`sandbox.solvers.iterative`) and the wide
sweeps over eight contacts at a time (:mod:`sandbox.solvers.wide`) both use these, so each
formula has one source."""

from __future__ import annotations

from sandbox.jit import njit


@njit(inline="always")
def friction_total(old: float, tangent_mass: float, v_t: float, limit: float) -> float:
    """Coulomb friction: the running total of the impulse along t that stops sliding,
    old - (v_r . t) / k_t, clamped to |p_t| <= limit = mu p_n (N s)."""
    return min(max(old - tangent_mass * v_t, -limit), limit)


@njit(inline="always")
def normal_total(old: float, normal_mass: float, bias: float, v_n: float) -> float:
    """The running total of the normal impulse that makes v_r . n = bias, kept >= 0 (N s)
    (slides, "Collision Equation", step 1, with the target bias instead of -e v_r . n)."""
    return max(old + normal_mass * (bias - v_n), 0.0)


@njit(inline="always")
def block_totals(
    a1: float,
    a2: float,
    b1: float,
    b2: float,
    k12: float,
    m: tuple[float, float, float],
    normal_mass_1: float,
    normal_mass_2: float,
) -> tuple[float, float]:
    """Both normal impulses of a two-point manifold at once (Box2D's block solver).

    Find the totals x = (p_n1, p_n2) >= 0 with normal speeds v_n = K x + b >= 0 and
    x_j v_n,j = 0, given the totals so far (a1, a2), b (each point's normal speed without
    them, minus its bias, m/s), K's off-diagonal k12 and K^-1 as m = (m11, m12, m22). Tried in
    turn: both points push, only the first, only the second, neither; where none fits
    (degenerate), the totals stay as they were.
    """
    m11, m12, m22 = m
    x1, x2 = -(m11 * b1 + m12 * b2), -(m12 * b1 + m22 * b2)  # both push: x = -K^-1 b
    if x1 < 0.0 or x2 < 0.0:
        x1, x2 = -b1 * normal_mass_1, 0.0  # only the first pushes
        if x1 < 0.0 or k12 * x1 + b2 < 0.0:
            x1, x2 = 0.0, -b2 * normal_mass_2  # only the second
            if x2 < 0.0 or k12 * x2 + b1 < 0.0:
                x1, x2 = 0.0, 0.0  # neither
                if b1 < 0.0 or b2 < 0.0:
                    x1, x2 = a1, a2  # no solution: leave as is
    return x1, x2
