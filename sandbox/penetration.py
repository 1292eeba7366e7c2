"""Solving interpenetration after the positions moved (slides, "Solving Interpenetration").

``settings.penetration`` picks the option:

- ``half`` (option 1): each body moves away by half the penetration p along the normal,
  p1' = p1 - p/2 n, p2' = p2 + p/2 n; a body that cannot move (static, kinematic) stays and
  the other takes all of it.
- ``mass_weighted`` (option 2): p1' = p1 - m2 / (m1 + m2) p n, p2' = p2 + m1 / (m1 + m2) p n
  (written with inverse masses, 1/m1 / (1/m1 + 1/m2), so an infinite mass does not move).
- ``impulse`` (option 3): "apply the impulse equation at positional level" -- for each contact
  point a pseudo-impulse lambda = -C / k with the collision equation's k and
  C = beta (separation + slop), clamped to [-max_correction, 0], changes positions *and* angles:
  p1 -= lambda n / m1, phi1 -= (r1 x lambda n) / I1, and the opposite for body 2 (Box2D's
  non-linear Gauss-Seidel position solver). beta is ``settings.baumgarte``.

Before these passes, pairs that bounced before they touched (a speculative contact) are moved
to where the bounce at the time of impact would have left them (:func:`rebound`).

The separation of a point is recomputed from the bodies' current poses: the contact point is
kept in each body's frame (``la``, ``lb``) and the normal stays fixed in the world, so
separation = -depth0 + ((c2 + R2 lb) - (c1 + R1 la)) . n. ``slop`` (m) of overlap is allowed,
so resting contacts stay in touch and keep their cached impulses.
"""

from __future__ import annotations

import math

import numpy as np

from sandbox import orientation
from sandbox.contact import (
    DEPTH,
    G_NX,
    G_NY,
    G_POINT,
    G_REBOUND,
    G_STRIDE,
    I_A,
    I_B,
    I_COUNT,
    LAX,
    LAY,
    LBX,
    LBY,
    S_II1,
    S_II2,
    S_IM1,
    S_IM2,
)
from sandbox.jit import njit
from sandbox.solvers.impulse import cross, effective_mass

METHODS = ("half", "mass_weighted", "impulse")
MAX_CORRECTION = 0.2  # m: the largest push of one point in one pass (as Box2D)


@njit
def separation(i, j, ia, ib, nx, ny, la, lb, sep0, com, cs):
    """Current separation of point j of manifold i (m, < 0 overlapping), and its lever arms."""
    c1, s1, c2, s2 = cs[ia, 0], cs[ia, 1], cs[ib, 0], cs[ib, 1]
    r1x = c1 * la[i, j, 0] - s1 * la[i, j, 1]
    r1y = s1 * la[i, j, 0] + c1 * la[i, j, 1]
    r2x = c2 * lb[i, j, 0] - s2 * lb[i, j, 1]
    r2y = s2 * lb[i, j, 0] + c2 * lb[i, j, 1]
    dx = (com[ib, 0] + r2x) - (com[ia, 0] + r1x)
    dy = (com[ib, 1] + r2y) - (com[ia, 1] + r1y)
    return sep0[i, j] + dx * nx + dy * ny, r1x, r1y, r2x, r2y


@njit
def _turn(cs, dphi, i, d) -> None:
    """Rotate body i by d radians: (c, s) turned by d, and d added to its total dphi."""
    if d == 0.0:
        return
    dphi[i] += d
    cd, sd = math.cos(d), math.sin(d)
    c, s = cs[i, 0], cs[i, 1]
    cs[i, 0] = c * cd - s * sd
    cs[i, 1] = s * cd + c * sd


@njit
def push_apart(a, b, normal, count, la, lb, sep0, com, cs, inv_mass, weighted, slop, passes):
    """Options 1 and 2: translate the two bodies apart by p = deepest overlap - slop.

    Returns the smallest separation seen in the last pass (m).
    """
    worst = 0.0
    for _ in range(passes):
        worst = 0.0
        for i in range(len(a)):
            ia, ib = a[i], b[i]
            nx, ny = normal[i, 0], normal[i, 1]
            deepest = 0.0
            for j in range(count[i]):
                sep = separation(i, j, ia, ib, nx, ny, la, lb, sep0, com, cs)[0]
                worst = min(worst, sep)
                deepest = max(deepest, -sep - slop)
            im1, im2 = inv_mass[ia], inv_mass[ib]
            if deepest <= 0.0 or im1 + im2 == 0.0:
                continue
            if weighted:  # option 2: m2 / (m1 + m2) = (1/m1) / (1/m1 + 1/m2)
                w1 = im1 / (im1 + im2)
            elif im1 == 0.0 or im2 == 0.0:  # option 1, one body fixed: the other takes all
                w1 = 0.0 if im1 == 0.0 else 1.0
            else:  # option 1: half each
                w1 = 0.5
            w2 = 1.0 - w1
            com[ia, 0] -= w1 * deepest * nx
            com[ia, 1] -= w1 * deepest * ny
            com[ib, 0] += w2 * deepest * nx
            com[ib, 1] += w2 * deepest * ny
    return worst


@njit
def position_impulses(
    a, b, normal, count, la, lb, sep0, com, cs, dphi, inv_mass, inv_moment,
    beta, slop, max_correction, passes,
):  # fmt: skip
    """Option 3: the impulse equation at positional level (non-linear Gauss-Seidel).

    Returns the smallest separation seen in the last pass (m).
    """
    worst = 0.0
    for _ in range(passes):
        worst = 0.0
        for i in range(len(a)):
            ia, ib = a[i], b[i]
            nx, ny = normal[i, 0], normal[i, 1]
            im1, im2, ii1, ii2 = inv_mass[ia], inv_mass[ib], inv_moment[ia], inv_moment[ib]
            for j in range(count[i]):
                sep, r1x, r1y, r2x, r2y = separation(i, j, ia, ib, nx, ny, la, lb, sep0, com, cs)
                worst = min(worst, sep)
                c = min(max(beta * (sep + slop), -max_correction), 0.0)
                k = effective_mass(im1, ii1, im2, ii2, r1x, r1y, r2x, r2y, nx, ny)
                if c == 0.0 or k <= 0.0:
                    continue
                lam = -c / k  # slides, "Collision Equation" step 1, on positions
                px, py = lam * nx, lam * ny
                com[ia, 0] -= im1 * px
                com[ia, 1] -= im1 * py
                _turn(cs, dphi, ia, -ii1 * cross(r1x, r1y, px, py))
                com[ib, 0] += im2 * px
                com[ib, 1] += im2 * py
                _turn(cs, dphi, ib, ii2 * cross(r2x, r2y, px, py))
    return worst


@njit
def rebound(a, b, normal, distance, com, inv_mass) -> None:
    """Move each pair ``distance[i]`` closer along the normal, shared by inverse mass (the
    centre of mass of the pair stays): a bounce computed at the start of the step from a gap
    g is moved to its time of impact (see :func:`sandbox.solvers.impulse.restitution`)."""
    for i in range(len(a)):
        d = distance[i]
        ia, ib = a[i], b[i]
        im1, im2 = inv_mass[ia], inv_mass[ib]
        if d <= 0.0 or im1 + im2 == 0.0:
            continue
        w1, w2 = im1 / (im1 + im2) * d, im2 / (im1 + im2) * d
        com[ia, 0] += w1 * normal[i, 0]
        com[ia, 1] += w1 * normal[i, 1]
        com[ib, 0] -= w2 * normal[i, 0]
        com[ib, 1] -= w2 * normal[i, 1]


# --- option 3 and the rebound on contact rows (what the world's step runs) ---------------------


@njit
def turn_small(c, s, d):
    """(c, s) turned by about d radians, for the small turns within the position passes: by
    atan(d), ((c, s) + d (-s, c)) / sqrt(1 + d^2), which is d to within d^3 / 3, without a
    cosine and a sine. The passes add up the exact d of every turn, and the orientation is
    turned by that total afterwards, so the step's result keeps no error."""
    scale = 1.0 / math.sqrt(1.0 + d * d)
    return (c - s * d) * scale, (s + c * d) * scale


@njit
def position_rows(ints, geoms, solver, k, com, cs, dphi, beta, slop, max_correction, passes):
    """:func:`position_impulses` for contact rows (``sandbox.contact``), visiting the manifolds
    in the velocity sweeps' order (``sandbox.solvers.iterative.visit``). Returns the smallest
    separation seen in the last pass (m)."""
    worst = 0.0
    half = (k + 1) // 2
    for _ in range(passes):
        worst = 0.0
        moved = False
        for q in range(k):
            i = (q >> 1) + (q & 1) * half
            ia, ib = ints[i, I_A], ints[i, I_B]
            nx, ny = geoms[i, G_NX], geoms[i, G_NY]
            for j in range(ints[i, I_COUNT]):
                g = G_POINT + G_STRIDE * j
                c1, s1, c2, s2 = cs[ia, 0], cs[ia, 1], cs[ib, 0], cs[ib, 1]
                lax, lay = geoms[i, g + LAX], geoms[i, g + LAY]
                lbx, lby = geoms[i, g + LBX], geoms[i, g + LBY]
                r1x, r1y = c1 * lax - s1 * lay, s1 * lax + c1 * lay
                r2x, r2y = c2 * lbx - s2 * lby, s2 * lbx + c2 * lby
                dx = (com[ib, 0] + r2x) - (com[ia, 0] + r1x)
                dy = (com[ib, 1] + r2y) - (com[ia, 1] + r1y)
                sep = -geoms[i, g + DEPTH] + dx * nx + dy * ny
                worst = min(worst, sep)
                c = min(max(beta * (sep + slop), -max_correction), 0.0)
                if c == 0.0:
                    continue  # within the slop: nothing to push
                im1, ii1 = solver[i, S_IM1], solver[i, S_II1]
                im2, ii2 = solver[i, S_IM2], solver[i, S_II2]
                rn1, rn2 = cross(r1x, r1y, nx, ny), cross(r2x, r2y, nx, ny)
                kn = im1 + im2 + ii1 * rn1 * rn1 + ii2 * rn2 * rn2
                if kn <= 0.0:
                    continue
                lam = -c / kn  # slides, "Collision Equation" step 1, on positions
                moved = True
                com[ia, 0] -= im1 * lam * nx
                com[ia, 1] -= im1 * lam * ny
                com[ib, 0] += im2 * lam * nx
                com[ib, 1] += im2 * lam * ny
                d1, d2 = -ii1 * rn1 * lam, ii2 * rn2 * lam
                if d1 != 0.0:
                    dphi[ia] += d1
                    cs[ia, 0], cs[ia, 1] = turn_small(c1, s1, d1)
                if d2 != 0.0:
                    dphi[ib] += d2
                    cs[ib, 0], cs[ib, 1] = turn_small(c2, s2, d2)
        if not moved:
            break  # nothing moved: another pass would see the very same separations
    return worst


@njit
def rebound_rows(ints, geoms, k, com, inv_mass) -> None:
    """:func:`rebound` for contact rows (distance in ``G_REBOUND``)."""
    for i in range(k):
        d = geoms[i, G_REBOUND]
        ia, ib = ints[i, I_A], ints[i, I_B]
        im1, im2 = inv_mass[ia], inv_mass[ib]
        if d <= 0.0 or im1 + im2 == 0.0:
            continue
        w1, w2 = im1 / (im1 + im2) * d, im2 / (im1 + im2) * d
        com[ia, 0] += w1 * geoms[i, G_NX]
        com[ia, 1] += w1 * geoms[i, G_NY]
        com[ib, 0] -= w2 * geoms[i, G_NX]
        com[ib, 1] -= w2 * geoms[i, G_NY]


@njit
def position_phase(
    ints, geoms, solver, k, com, rot, cs, dphi, inv_mass, orientation_kind, renormalise,
    beta, slop, passes,
) -> float:  # fmt: skip
    """The position phase on contact rows without joints, option 3: the rebound, ``passes``
    passes of :func:`position_rows`, then the orientations turned by what the passes turned
    (``dphi`` is scratch, one per body). Returns the smallest separation left (m)."""
    rebound_rows(ints, geoms, k, com, inv_mass)
    if k == 0 or passes <= 0:
        return 0.0
    dphi[:] = 0.0
    worst = position_rows(ints, geoms, solver, k, com, cs, dphi, beta, slop, MAX_CORRECTION, passes)
    orientation.integrate_rotations(orientation_kind, rot, dphi, renormalise)
    orientation.cos_sin(orientation_kind, rot, cs)
    return worst


def constraints_of_rows(cache, s: int, k: int):
    """The position data of set ``s`` of contact rows as a
    :class:`~sandbox.solvers.impulse.Constraints` (``la``, ``lb``, ``sep0``, ``rebound``), for
    the options and the joint loop that work on those."""
    from sandbox.solvers.impulse import Constraints

    geoms = cache.geoms[s][:k]
    cons = Constraints(k)
    for j in range(2):
        g = G_POINT + G_STRIDE * j
        cons.la[:, j] = geoms[:, [g + LAX, g + LAY]]
        cons.lb[:, j] = geoms[:, [g + LBX, g + LBY]]
        cons.sep0[:, j] = -geoms[:, g + DEPTH]
    cons.rebound[:] = geoms[:, G_REBOUND]
    return cons


def correct(world, manifolds, cons, passes: int) -> float:
    """Run ``passes`` passes of ``world.settings.penetration`` over the contacts (in place on
    ``world.com`` and the orientations). Returns the smallest separation left (m)."""
    s = world.settings
    if manifolds is None or len(manifolds) == 0 or passes <= 0:
        return 0.0
    m = manifolds
    if s.penetration == "impulse":
        dphi = np.zeros(len(world.kind))
        worst = position_impulses(
            m.a, m.b, m.normal, m.count, cons.la, cons.lb, cons.sep0, world.com, world.cs,
            dphi, world.inv_mass, world.inv_moment, float(s.baumgarte), float(s.slop),
            MAX_CORRECTION, int(passes),
        )  # fmt: skip
        # the orientations proper follow the angle changes; cs is recomputed from them
        orientation.integrate_rotations(world.orientation_kind, world.rot, dphi, s.renormalise)
        orientation.cos_sin(world.orientation_kind, world.rot, world.cs)
        return float(worst)
    return float(
        push_apart(
            m.a,
            m.b,
            m.normal,
            m.count,
            cons.la,
            cons.lb,
            cons.sep0,
            world.com,
            world.cs,
            world.inv_mass,
            s.penetration == "mass_weighted",
            float(s.slop),
            int(passes),
        )  # fmt: skip
    )


def solve_positions(world, manifolds, cons, passes: int) -> None:
    """The position phase every solver shares: ``passes`` passes of the penetration fix,
    interleaved with the joints' ``solve_position`` when there are joints. Nothing at all
    when ``settings.position_correction`` is off."""
    if not world.settings.position_correction:
        return
    m = manifolds
    if len(m) and np.any(cons.rebound > 0.0):
        rebound(m.a, m.b, m.normal, cons.rebound, world.com, world.inv_mass)
    if not world.joints:
        correct(world, manifolds, cons, passes)
        return
    for _ in range(passes):
        worst = correct(world, manifolds, cons, 1)
        joint_error = 0.0
        for joint in world.joints:
            joint_error = max(joint_error, float(joint.solve_position(world)))
        if worst >= -3.0 * world.settings.slop and joint_error <= world.settings.slop:
            break
