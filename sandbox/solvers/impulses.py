"""The formulas of one visit of the iterative solver, on numbers alone (slides, "Collision
Equation" and "Iterative Solver"; box2d-lite's ``Arbiter::ApplyImpulse``; Box2D's block
solver), and of one point of the penetration fix's position impulses (slides, "Solving
Interpenetration", option 3; Box2D's non-linear Gauss-Seidel). The sweeps and passes over
contact records (:mod:`sandbox.solvers.iterative`, :mod:`sandbox.penetration`) and the wide
ones over eight contacts at a time (:mod:`sandbox.solvers.wide`,
:mod:`sandbox.solvers.wide_positions`) both use these, so each formula has one source."""

from __future__ import annotations

import numpy as np

from sandbox.jit import njit
from sandbox.math2d import cross, effective_mass, nudged, push_along, rotate, speed_along

MAX_CORRECTION = 0.2  # m: the largest push of one point in one position pass (as Box2D)


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
def friction_step(va, vb, mass, t, rt, old: float, tangent_mass: float, limit: float):
    """One point's friction visit: the new running total (:func:`friction_total`, from v_r . t
    at the arms' ``rt`` = (r_a x t, r_b x t)) and the velocities after its change
    P = (new - old) t. Returns ``(new, va, vb)``."""
    v_t = speed_along(va, vb, t[0], t[1], rt[0], rt[1])  # v_r . t
    new = friction_total(old, tangent_mass, v_t, limit)
    va, vb = push_along(va, vb, mass, t[0], t[1], rt[0], rt[1], new - old)
    return new, va, vb


@njit(inline="always")
def normal_step(va, vb, mass, n, rn, old: float, normal_mass: float, bias: float):
    """One point's normal visit: the new running total (:func:`normal_total`, from v_r . n at
    the arms' ``rn``) and the velocities after its change P = (new - old) n. Returns
    ``(new, va, vb)``."""
    v_n = speed_along(va, vb, n[0], n[1], rn[0], rn[1])  # v_r . n
    new = normal_total(old, normal_mass, bias, v_n)
    va, vb = push_along(va, vb, mass, n[0], n[1], rn[0], rn[1], new - old)
    return new, va, vb


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


@njit(inline="always")
def separation_of(pose_a, pose_b, local_a, local_b, n, depth: float):
    """A contact point's current separation (m, < 0 overlapping) and its arms (r_a, r_b), from
    the bodies' poses (:func:`sandbox.math2d.pose_of`): the point is kept in each body's
    frame (``local_a``, ``local_b``) and the normal ``n`` fixed in the world, so separation =
    -depth0 + ((c_b + R_b l_b) - (c_a + R_a l_a)) . n."""
    rax, ray = rotate(pose_a[2], pose_a[3], local_a[0], local_a[1])
    rbx, rby = rotate(pose_b[2], pose_b[3], local_b[0], local_b[1])
    dx = (pose_b[0] + rbx) - (pose_a[0] + rax)
    dy = (pose_b[1] + rby) - (pose_a[1] + ray)
    return -depth + dx * n[0] + dy * n[1], rax, ray, rbx, rby


@njit(inline="always")
def push_point(pose_a, pose_b, mass, n, point, beta: float):
    """One point's position impulse: lambda = -C / k with C = beta (separation - allowed),
    clamped to [-``MAX_CORRECTION``, 0], moves and turns both bodies (p_a -= lambda n / m_a,
    phi_a -= (r_a x lambda n) / I_a, the opposite for b). ``point`` = (local_a, local_b,
    depth0 (m), allowed separation (m)); ``mass`` = (1/m_a, 1/I_a, 1/m_b, 1/I_b). Returns the
    new poses, the separation before the push (m) and whether it pushed; no push (within
    the allowed separation, or nothing can move) leaves the poses exactly as they were."""
    local_a, local_b, depth, allowed = point
    im_a, ii_a, im_b, ii_b = mass
    nx, ny = n
    sep, rax, ray, rbx, rby = separation_of(pose_a, pose_b, local_a, local_b, n, depth)
    error = min(max(beta * (sep - allowed), -MAX_CORRECTION), 0.0)
    rn_a, rn_b = cross(rax, ray, nx, ny), cross(rbx, rby, nx, ny)
    k_n = effective_mass(im_a, ii_a, im_b, ii_b, rn_a, rn_b)
    pushed = (error != 0.0) & (k_n > 0.0)
    lam = -error / k_n if pushed else 0.0  # slides, "Collision Equation" step 1, on positions
    pose_a = nudged(pose_a, -im_a * lam * nx, -im_a * lam * ny, -ii_a * rn_a * lam)
    pose_b = nudged(pose_b, im_b * lam * nx, im_b * lam * ny, ii_b * rn_b * lam)
    return pose_a, pose_b, sep, pushed


@njit(inline="always")
def overlap_left(sep: float, allowed: float) -> float:
    """How far a point overlaps beyond the separation it may keep (``allowed``, m), in whole
    micrometres: a float that holds an integer, so that a pass's sum of them is exact and the
    same in any order, and the passes over lanes and over records stop alike (the stall test
    of :func:`sandbox.penetration.fix_positions`)."""
    return np.floor(max(allowed - sep, 0.0) * 1e6)
