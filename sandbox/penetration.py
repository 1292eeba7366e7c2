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
to where the bounce at the time of impact would have left them (:func:`rebound`). Joints take a
position pass after each contact pass (:mod:`sandbox.joints.solve`).

The separation of a point is recomputed from the bodies' current poses: the contact point is
kept in each body's frame (``local_a``, ``local_b``) and the normal stays fixed in the world,
so separation = -depth0 + ((c2 + R2 lb) - (c1 + R1 la)) . n. ``slop`` (m) of overlap is allowed,
so resting contacts stay in touch and keep their cached impulses. Turns are applied to each
body's (cos, sin) as the passes go and added up in ``turn``; the stored orientation is turned
by that total at the end (:func:`sandbox.orientation.turn_bodies`).
"""

from __future__ import annotations

from sandbox.jit import njit
from sandbox.joints.solve import solve_joint_positions
from sandbox.math2d import cross, effective_mass, nudge, rotate
from sandbox.orientation import turn_bodies

HALF, MASS_WEIGHTED, IMPULSE = 0, 1, 2
METHODS = ("half", "mass_weighted", "impulse")  # settings.penetration, in code order
MAX_CORRECTION = 0.2  # m: the largest push of one point in one pass (as Box2D)


@njit
def separation(c, p, bodies) -> tuple[float, float, float, float, float]:
    """Current separation of a contact point (m, < 0 overlapping), and its arms r_a, r_b."""
    a, b = bodies[c["a"]], bodies[c["b"]]
    rax, ray = rotate(a["cs"][0], a["cs"][1], p["local_a"][0], p["local_a"][1])
    rbx, rby = rotate(b["cs"][0], b["cs"][1], p["local_b"][0], p["local_b"][1])
    dx = (b["com"][0] + rbx) - (a["com"][0] + rax)
    dy = (b["com"][1] + rby) - (a["com"][1] + ray)
    return -p["depth"] + dx * c["normal"][0] + dy * c["normal"][1], rax, ray, rbx, rby


@njit
def push_apart(contacts, k: int, bodies, weighted: bool, slop: float) -> float:
    """Options 1 and 2, one pass: translate each pair apart by p = deepest overlap - slop.
    Returns the smallest separation seen (m)."""
    worst = 0.0
    for i in range(k):
        c = contacts[i]
        deepest = 0.0
        for j in range(c["count"]):
            sep = separation(c, c["points"][j], bodies)[0]
            worst = min(worst, sep)
            deepest = max(deepest, -sep - slop)
        im_a, im_b = bodies[c["a"]]["inv_mass"], bodies[c["b"]]["inv_mass"]
        if deepest <= 0.0 or im_a + im_b == 0.0:
            continue
        if weighted:  # option 2: m2 / (m1 + m2) = (1/m1) / (1/m1 + 1/m2)
            w_a = im_a / (im_a + im_b)
        elif im_a == 0.0 or im_b == 0.0:  # option 1, one body fixed: the other takes all
            w_a = 0.0 if im_a == 0.0 else 1.0
        else:  # option 1: half each
            w_a = 0.5
        nx, ny = c["normal"][0], c["normal"][1]
        nudge(bodies[c["a"]], -w_a * deepest * nx, -w_a * deepest * ny, 0.0)
        nudge(bodies[c["b"]], (1.0 - w_a) * deepest * nx, (1.0 - w_a) * deepest * ny, 0.0)
    return worst


@njit
def position_impulses(contacts, k: int, bodies, beta: float, slop: float):
    """Option 3, one pass (non-linear Gauss-Seidel), in the velocity sweeps' order
    (:func:`sandbox.solvers.iterative.visit`). Returns (smallest separation seen (m), whether
    anything moved)."""
    worst = 0.0
    moved = False
    half = (k + 1) // 2
    for q in range(k):
        c = contacts[(q >> 1) + (q & 1) * half]
        a, b = bodies[c["a"]], bodies[c["b"]]
        nx, ny = c["normal"][0], c["normal"][1]
        for j in range(c["count"]):
            sep, rax, ray, rbx, rby = separation(c, c["points"][j], bodies)
            worst = min(worst, sep)
            error = min(max(beta * (sep + slop), -MAX_CORRECTION), 0.0)
            if error == 0.0:
                continue  # within the slop: nothing to push
            rn_a, rn_b = cross(rax, ray, nx, ny), cross(rbx, rby, nx, ny)
            k_n = effective_mass(
                a["inv_mass"], a["inv_moment"], b["inv_mass"], b["inv_moment"], rn_a, rn_b
            )
            if k_n <= 0.0:
                continue
            lam = -error / k_n  # slides, "Collision Equation" step 1, on positions
            moved = True
            nudge(
                a,
                -a["inv_mass"] * lam * nx,
                -a["inv_mass"] * lam * ny,
                -a["inv_moment"] * rn_a * lam,
            )
            nudge(
                b, b["inv_mass"] * lam * nx, b["inv_mass"] * lam * ny, b["inv_moment"] * rn_b * lam
            )
    return worst, moved


@njit
def rebound(contacts, k: int, bodies) -> None:
    """Move each pair ``rebound`` closer along the normal, shared by inverse mass (the centre
    of mass of the pair stays): a bounce computed at the start of the step from a gap g is
    moved to its time of impact (see :func:`sandbox.solvers.common.restitution`)."""
    for i in range(k):
        c = contacts[i]
        d = c["rebound"]
        a, b = bodies[c["a"]], bodies[c["b"]]
        im_a, im_b = a["inv_mass"], b["inv_mass"]
        if d <= 0.0 or im_a + im_b == 0.0:
            continue
        w_a, w_b = im_a / (im_a + im_b) * d, im_b / (im_a + im_b) * d
        nudge(a, w_a * c["normal"][0], w_a * c["normal"][1], 0.0)
        nudge(b, -w_b * c["normal"][0], -w_b * c["normal"][1], 0.0)


@njit
def fix_positions(contacts, k: int, joints, bodies, rot, context) -> float:
    """The position stage every rigid solver shares: the rebound, then up to
    ``position_iterations`` passes of the penetration fix, each followed by the joints'
    position pass; then each body's orientation turned by what the passes turned. Nothing at
    all when ``settings.position_correction`` is off. Returns the smallest separation the last
    contact pass saw (m, < 0 overlapping)."""
    ctx = context[0]
    worst = 0.0
    if not ctx["position_correction"]:
        return worst
    rebound(contacts, k, bodies)
    if k == 0 and joints.shape[0] == 0:
        return worst
    for i in range(bodies.shape[0]):
        bodies[i]["turn"] = 0.0
    slop, method = ctx["slop"], ctx["penetration"]
    for _ in range(ctx["position_iterations"]):
        if method == IMPULSE:
            worst, moved = position_impulses(contacts, k, bodies, ctx["baumgarte"], slop)
        else:
            worst, moved = push_apart(contacts, k, bodies, method == MASS_WEIGHTED, slop), True
        if joints.shape[0] == 0:
            if not moved:
                break  # nothing moved: another pass would see the very same separations
            continue
        joint_error = solve_joint_positions(joints, bodies)
        if worst >= -3.0 * slop and joint_error <= slop:
            break
    turn_bodies(bodies, rot, ctx["orientation"], ctx["renormalise"])
    return worst
