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

import numpy as np

from sandbox.jit import JIT_ENABLED, njit
from sandbox.joints.positions_together import solve_joint_positions_together
from sandbox.joints.solve import solve_joint_positions
from sandbox.math2d import cross, effective_mass, nudge, pose_of, set_pose
from sandbox.orientation import turn_bodies
from sandbox.position_layers import needs_layers, position_masses, position_order
from sandbox.prefetch import AHEAD, prefetch_bodies, prefetch_record, span, where
from sandbox.records import BODY, CONTACT, CONTACT_POINT
from sandbox.solvers.impulses import overlap_left, push_point, separation_of
from sandbox.solvers.wide_positions import allowed_separation, put_poses, take_poses, visit_colour

HALF, MASS_WEIGHTED, IMPULSE = 0, 1, 2
METHODS = ("half", "mass_weighted", "impulse")  # settings.penetration, in code order


@njit
def separation(c, p, bodies) -> tuple[float, float, float, float, float]:
    """Current separation of a contact point (m, < 0 overlapping), and its arms r_a, r_b."""
    return separation_of(
        pose_of(bodies[c["a"]]),
        pose_of(bodies[c["b"]]),
        p["local_a"],
        p["local_b"],
        c["normal"],
        p["anchor_depth"],
    )


@njit
def push_apart(contacts, k: int, bodies, weighted: bool, bounds, layering) -> tuple[float, float]:
    """Options 1 and 2, one pass: translate each pair apart by p = deepest overlap beyond the
    allowed separation. ``bounds`` = (slop, push) (m); ``layering`` = (order, layer) from
    :func:`~sandbox.position_layers.position_order`. Returns (the smallest separation seen
    (m), the overlap beyond what each point may keep, summed (um,
    :func:`~sandbox.solvers.impulses.overlap_left`))."""
    slop, push = bounds
    order, layer = layering
    worst = overlap = 0.0
    for q in range(k):
        c = contacts[order[q]]
        deepest = 0.0
        for j in range(c["count"]):
            p = c["points"][j]
            sep = separation(c, p, bodies)[0]
            allowed = allowed_separation(c, p, slop, push)
            worst = min(worst, sep)
            overlap += overlap_left(sep, allowed)
            deepest = max(deepest, allowed - sep)
        im_a, _, im_b, _ = position_masses(c, bodies, layer)[0]
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
    return worst, overlap


@njit
def push_points(c, bodies, mass, errors, arms) -> None:
    """Position impulses lambda >= 0 at a manifold's points making each point's separation
    change by -error (linearised): K lambda = -error with K_ij = 1/m_a + 1/m_b +
    (r_ai x n)(r_aj x n) / I_a + (r_bi x n)(r_bj x n) / I_b, both points together when both
    push (a box flat on another rises without turning), else the point with the larger error
    alone."""
    im_a, ii_a, im_b, ii_b = mass
    nx, ny = c["normal"][0], c["normal"][1]
    rn_a = (cross(arms[0], arms[1], nx, ny), cross(arms[4], arms[5], nx, ny))
    rn_b = (cross(arms[2], arms[3], nx, ny), cross(arms[6], arms[7], nx, ny))
    k11 = effective_mass(im_a, ii_a, im_b, ii_b, rn_a[0], rn_b[0])
    l1 = l2 = 0.0
    if c["count"] == 2:
        k22 = effective_mass(im_a, ii_a, im_b, ii_b, rn_a[1], rn_b[1])
        k12 = im_a + im_b + ii_a * rn_a[0] * rn_a[1] + ii_b * rn_b[0] * rn_b[1]
        det = k11 * k22 - k12 * k12
        if det > 1e-12 * k11 * k22:
            l1 = -(k22 * errors[0] - k12 * errors[1]) / det
            l2 = -(k11 * errors[1] - k12 * errors[0]) / det
        if not (l1 >= 0.0 and l2 >= 0.0):  # not both: the deeper point alone
            l1 = l2 = 0.0
            if errors[1] < errors[0]:
                l2 = -errors[1] / k22 if k22 > 0.0 else 0.0
            else:
                l1 = -errors[0] / k11 if k11 > 0.0 else 0.0
    elif k11 > 0.0:
        l1 = -errors[0] / k11
    lam = l1 + l2
    a, b = bodies[c["a"]], bodies[c["b"]]
    turn_a, turn_b = rn_a[0] * l1 + rn_a[1] * l2, rn_b[0] * l1 + rn_b[1] * l2
    nudge(a, -im_a * lam * nx, -im_a * lam * ny, -ii_a * turn_a)
    nudge(b, im_b * lam * nx, im_b * lam * ny, ii_b * turn_b)


# what a pass reads of a contact's record (bodies, count, normal; point 0's depth to its depth
# when anchored) and of its bodies' (pose and masses; the turn), asked for ahead
CONTACT_READ = span(CONTACT, "a", "normal")
POINT_READ = tuple(
    CONTACT.fields["points"][1] + at for at in span(CONTACT_POINT, "depth", "anchor_depth")
)
BODY_READ, TURN_READ = span(BODY, "com", "inv_moment"), span(BODY, "turn", "turn")


@njit(inline="always")
def fetch_ahead(contacts, order, q: int, k: int, ahead) -> None:
    """Prefetch (:mod:`sandbox.prefetch`) the record of the contact 2 ``AHEAD`` places on in
    ``order``, and the bodies of the one ``AHEAD`` on (its record asked for before)."""
    contacts_at, bodies_at = ahead
    if q + 2 * AHEAD < k:
        prefetch_record(contacts_at, order[q + 2 * AHEAD], CONTACT_READ)
        prefetch_record(contacts_at, order[q + 2 * AHEAD], POINT_READ)
    if q + AHEAD < k:
        c = contacts[order[q + AHEAD]]
        prefetch_bodies(c, bodies_at, BODY_READ)
        prefetch_bodies(c, bodies_at, TURN_READ)


@njit
def position_impulses(contacts, k: int, bodies, beta: float, bounds, layering):
    """Option 3, one pass (non-linear Gauss-Seidel). Within a layer, point by point, beta of
    each point's error, at most ``MAX_CORRECTION``; between two layers (the lower body held)
    the manifold's points together and entirely (nothing pushes back: :func:`push_points`).
    Returns (smallest separation seen (m), whether anything moved, the overlap beyond what
    each point may keep, summed as the pass met it (um,
    :func:`~sandbox.solvers.impulses.overlap_left`))."""
    slop, push = bounds
    order, layer = layering
    worst = overlap = 0.0
    moved = False
    ahead = ((0, 0), (0, 0))
    if JIT_ENABLED:  # where the records are, to ask for those of the contacts ahead
        ahead = (where(contacts), where(bodies))
    for q in range(k):
        if JIT_ENABLED:
            fetch_ahead(contacts, order, q, k, ahead)
        c = contacts[order[q]]
        a, b = bodies[c["a"]], bodies[c["b"]]
        nx, ny = c["normal"][0], c["normal"][1]
        mass, held = position_masses(c, bodies, layer)
        if held:  # tuples, not lists: a list is allocated and freed each time (a ground contact)
            e0 = e1 = 0.0
            arms0 = arms1 = (0.0, 0.0, 0.0, 0.0)
            for j in range(c["count"]):
                p = c["points"][j]
                sep, rax, ray, rbx, rby = separation(c, p, bodies)
                allowed = allowed_separation(c, p, slop, push)
                worst = min(worst, sep)
                overlap += overlap_left(sep, allowed)
                if j == 0:
                    e0, arms0 = min(sep - allowed, 0.0), (rax, ray, rbx, rby)
                else:
                    e1, arms1 = min(sep - allowed, 0.0), (rax, ray, rbx, rby)
            if e0 < 0.0 or e1 < 0.0:
                push_points(c, bodies, mass, (e0, e1), arms0 + arms1)
                moved = True
            continue
        for j in range(c["count"]):
            p = c["points"][j]
            point = (
                p["local_a"],
                p["local_b"],
                p["anchor_depth"],
                allowed_separation(c, p, slop, push),
            )
            pose_a, pose_b, sep, pushed = push_point(
                pose_of(a), pose_of(b), mass, (nx, ny), point, beta
            )
            worst = min(worst, sep)
            overlap += overlap_left(sep, point[3])
            if pushed:
                moved = True
                set_pose(a, pose_a)
                set_pose(b, pose_b)
    return worst, moved, overlap


@njit
def wide_position_impulses(contacts, bodies, beta: float, bounds, layering, lanes):
    """Option 3, one pass, as :func:`position_impulses` in the order of
    :func:`~sandbox.position_layers.position_order` (not layered): the colours' contacts
    eight at a time (:func:`sandbox.solvers.wide_positions.visit_colour`), then the others
    one by one. The same numbers, faster (:data:`sandbox.solvers.wide_positions.MEASURED`)."""
    lanes, owners, starts, alone = lanes
    worst, moved, overlap = 0.0, False, 0.0
    if len(starts) > 1:
        poses = np.zeros((len(bodies) + 1, 5))
        take_poses(bodies, poses)
        for c in range(len(starts) - 1):
            w, m, o = visit_colour(lanes, owners, starts[c], starts[c + 1], poses, beta)
            worst, moved, overlap = min(worst, w), moved | m, overlap + o
        put_poses(poses, bodies)
    w, m, o = position_impulses(contacts, len(alone), bodies, beta, bounds, layering)
    return min(worst, w), moved | m, overlap + o


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
def first_push(contacts, k: int, bodies, bounds) -> tuple[bool, float]:
    """Whether a pass of option 3 would push anything: some point of the first ``k`` contacts
    overlaps beyond the separation it may keep (:func:`allowed_separation`; ``bounds`` as
    there), looked for at the poses the pass starts from and given up at the first found (or a
    separation that is not a number); and the smallest separation (m) when none does. No
    point pushing, a pass leaves every pose exactly as it was, in any order of the contacts
    and with any masses (:func:`~sandbox.solvers.impulses.push_point`): so this read-only
    look stands for the first pass, and the pass, its order and its lanes need not be made.
    The pyramid of base 20 pushes nothing in 292 of its first 300 steps (all from the 26th
    on), and its position stage then takes a quarter to a third of the time; where a pass
    pushes, the look stops within the first eleven contacts (rain, the pyramid of base 40)."""
    slop, push = bounds
    worst = 0.0
    for i in range(k):
        c = contacts[i]
        for j in range(c["count"]):
            p = c["points"][j]
            sep = separation(c, p, bodies)[0]
            if not sep >= allowed_separation(c, p, slop, push):
                return True, worst
            worst = min(worst, sep)
    return False, worst


@njit(python=True)
def fix_positions(contacts, k: int, joints, bodies, rot, context) -> float:
    """The position stage every solver shares: the rebound, then up to
    ``position_iterations`` passes of the penetration fix, each followed by the joints'
    position pass (swept, or solved together when ``context["joints_together"]`` says so, as
    the soft step does where its plan solves the relax pass together:
    :func:`sandbox.joints.positions_together.solve_joint_positions_together`), until a pass
    finds no point overlapping more than ``position_tolerance`` (and the joints within the
    slop; Box2D 2.x's test: a resting pile takes one pass, a deep overlap all of them), or a
    pass stalls: it met more than 1 - ``position_stall`` of the overlap the pass before met (a
    pile its own load presses together, where the passes push against each other: the rain
    of 5,000 discs, 0.2 % a pass; a spawned pile or a sunk ball, 1.4 % to 40 %); then
    each body's orientation turned by what the passes turned. ``context["position_passes"]``
    gets how many passes ran, ``context["position_progress"]`` the fraction of the overlap
    the pass before the last took out (NaN after one pass, or when it met none). Nothing at
    all when ``settings.position_correction`` is off. Without joints, a first pass that would
    push nothing (:func:`first_push`) is not made: a pile at rest keeps every pose as it is.
    Returns the smallest separation the last contact pass saw (m, < 0 overlapping)."""
    ctx = context[0]
    worst = 0.0
    ctx["position_passes"] = 0
    ctx["position_progress"] = np.nan
    if not ctx["position_correction"]:
        return worst
    rebound(contacts, k, bodies)
    if k == 0 and joints.shape[0] == 0:
        return worst
    for i in range(bodies.shape[0]):
        bodies[i]["turn"] = 0.0
    slop, method = ctx["slop"], ctx["penetration"]
    robust = ctx["robust_positions"]
    push = ctx["max_push_speed"] * ctx["dt"] if robust else np.inf
    bounds = (slop, push)
    if method == IMPULSE and joints.shape[0] == 0 and ctx["position_iterations"] > 0:
        pushes, worst = first_push(contacts, k, bodies, bounds)
        if not pushes:  # the first pass would move nothing, then stop: a pile at rest
            ctx["position_passes"] = 1
            return worst
    gap = ctx["touch_margin"]
    triggers = (ctx["deep_overlap"], ctx["hold_heavier"])
    layered = robust and needs_layers(contacts, k, bodies, triggers, gap)
    wide = JIT_ENABLED and method == IMPULSE and not layered and ctx["position_iterations"] > 0
    layering, lanes = position_order(contacts, k, bodies, layered, gap, bounds, wide)
    stall, met = ctx["position_stall"], np.inf  # met: the overlap the last pass met (um)
    for _ in range(ctx["position_iterations"]):
        if wide:
            worst, moved, overlap = wide_position_impulses(
                contacts, bodies, ctx["baumgarte"], bounds, layering, lanes
            )
        elif method == IMPULSE:
            worst, moved, overlap = position_impulses(
                contacts, k, bodies, ctx["baumgarte"], bounds, layering
            )
        else:
            weighted = method == MASS_WEIGHTED
            worst, overlap = push_apart(contacts, k, bodies, weighted, bounds, layering)
            moved = True
        ctx["position_passes"] += 1
        # Box2D's stop: no point overlaps more than position_tolerance (three slops); or the
        # pass before took out less than position_stall of the overlap (the sums are exact
        # integers of um, so every path stops alike; NaN, never less: nothing to compare);
        # or nothing moved, and another pass would see the very same separations
        progress = 1.0 - overlap / met if 0.0 < met < np.inf else np.nan
        ctx["position_progress"] = progress
        settled = worst >= -ctx["position_tolerance"] or (stall > 0.0 and progress < stall)
        met = overlap
        if joints.shape[0] == 0:
            if settled or not moved:
                break
            continue
        if ctx["joints_together"]:
            joint_error = solve_joint_positions_together(joints, bodies)
        else:
            joint_error = solve_joint_positions(joints, bodies)
        if settled and joint_error <= slop:
            break
    turn_bodies(bodies, rot, ctx["orientation"], ctx["renormalise"])
    return worst
