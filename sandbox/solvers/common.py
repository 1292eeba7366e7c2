"""What every contact solver shares (as Solver2D's ``solve_common.c``): prepare the contacts,
warm start them from the last step, bounce, and report.

Per contact point (:data:`sandbox.records.CONTACT_POINT`), as box2d-lite and Box2D keep them:

- ``rn_a``, ``rn_b``, ``rt_a``, ``rt_b``: r x n and r x t for the arms r_a, r_b from each centre
  of mass to the point (world frame), all the sweeps need of the arms: the point's speed along
  n is (v_b - v_a) . n + w_b (r_b x n) - w_a (r_a x n), and an impulse lambda n turns a body by
  lambda (r x n) / I (:func:`normal_speed`, :func:`apply_normal`); ``local_a``, ``local_b``
  the points the position passes follow, in each body's frame (:func:`anchor`), and
  ``anchor_depth`` the depth between them;
- ``normal_mass``, ``tangent_mass``: 1 / k along the normal and the tangent t = (n_y, -n_x),
  with the collision equation's k (slides, "Collision Equation", step 1);
- ``bias``: the normal velocity the constraint asks for, v_r . n >= bias (m/s): the gap closed
  in this step for speculative contacts (depth < 0), else an optional Baumgarte push;
- ``approach_speed``: v_r . n when the step began, before this step's gravity and forces (the
  prepare stage runs before the velocities are integrated, as in Box2D), for restitution;
- ``normal_impulse``, ``tangent_impulse``: the accumulated impulses (N s),
  ``max_normal_impulse`` the largest normal impulse of the step, ``bounce_impulse`` the
  restitution pass's (and the shock pass's pushes), ``bounce_tangent`` the shock pass's
  friction: neither is warm-started.

Conventions: the normal n points from body a to body b; v_r is b's contact point's velocity
seen from a's, so v_r . n < 0 means approaching.
"""

from __future__ import annotations

import numpy as np

from sandbox.jit import njit
from sandbox.math2d import (
    cross,
    effective_mass,
    inverse_or_zero,
    push_along,
    rotate,
    set_velocity,
    speed_along,
    take_velocities,
    unrotate,
    velocity_of,
)
from sandbox.records import CIRCLE

BLOCK_CONDITION = 1000.0  # the block solver is used while k11^2 < 1000 det K (Box2D's limit)


@njit
def masses(c) -> tuple[float, float, float, float]:
    """(1/m_a, 1/I_a, 1/m_b, 1/I_b) of a contact, as its prepare stage copied them."""
    return c["inv_mass_a"], c["inv_moment_a"], c["inv_mass_b"], c["inv_moment_b"]


@njit
def normal_speed(va, vb, p, nx: float, ny: float) -> float:
    """v_r . n at a contact point for the velocities va, vb (slides, "Collision Effects"),
    from the point's r x n: (w x r) . n = w (r x n)."""
    return speed_along(va, vb, nx, ny, p["rn_a"], p["rn_b"])


@njit
def tangent_speed(va, vb, p, nx: float, ny: float) -> float:
    """v_r . t at a contact point, t = (n_y, -n_x)."""
    return speed_along(va, vb, ny, -nx, p["rt_a"], p["rt_b"])


@njit
def apply_normal(va, vb, mass, p, nx: float, ny: float, impulse: float):
    """-P on body a and +P on body b at the point, P = impulse n (N s): v += P / m and
    w += (r x P) / I = impulse (r x n) / I (slides, "Collision Equation", steps 3a and 3b)."""
    return push_along(va, vb, mass, nx, ny, p["rn_a"], p["rn_b"], impulse)


@njit
def apply_tangent(va, vb, mass, p, nx: float, ny: float, impulse: float):
    """The same for P = impulse t, t = (n_y, -n_x) (friction)."""
    return push_along(va, vb, mass, ny, -nx, p["rt_a"], p["rt_b"], impulse)


@njit
def point_masses(c, p) -> None:
    """A used point's effective masses along the normal and the tangent, from the contact's
    (1/m_a, 1/I_a, 1/m_b, 1/I_b) and the point's lever arms."""
    im_a, ii_a, im_b, ii_b = masses(c)
    # slides, "Collision Equation", step 1: k = 1/m_a + 1/m_b + (r_a x n)^2/I_a + (r_b x n)^2/I_b
    kn = effective_mass(im_a, ii_a, im_b, ii_b, p["rn_a"], p["rn_b"])
    kt = effective_mass(im_a, ii_a, im_b, ii_b, p["rt_a"], p["rt_b"])
    p["normal_mass"], p["tangent_mass"] = inverse_or_zero(kn), inverse_or_zero(kt)


@njit(inline="always")
def anchor(shape, cs, local, rx: float, ry: float, nx: float, ny: float) -> float:
    """Write into ``local`` the point a contact point's separation follows on one body, in its
    frame about its centre of mass (m), given the contact point's arm (rx, ry) (m, world frame)
    and the body's (cos, sin): on a polygon the contact point itself, fixed to the body; on a
    circle the circle's centre, whose facing point is the centre plus a fixed reach along the
    normal however the circle turns, where a spinning ball's material point would swing off the
    contact by r (1 - cos dphi) (a 5 cm bullet sliding down a wall at 330 rad/s: 3 cm into the
    wall), and the position passes would turn the ball for nothing. Returns that reach (m)."""
    # both worked out and one kept (selects, not branches: discs against discs and against
    # walls alternate unpredictably)
    round_ = shape["kind"] == CIRCLE
    centre = shape["center"]
    ux, uy = unrotate(cs[0], cs[1], rx, ry)
    cx, cy = rotate(cs[0], cs[1], centre[0], centre[1])
    local[0] = centre[0] if round_ else ux
    local[1] = centre[1] if round_ else uy
    return (rx - cx) * nx + (ry - cy) * ny if round_ else 0.0


@njit(inline="always")
def arrived_velocities(bodies) -> np.ndarray:
    """(n, 3): every body's (vx, vy, w) (m/s, rad/s) as the step began, before this step's
    gravity and forces (:func:`sandbox.math2d.take_velocities`): the velocities the approach
    speeds are measured at."""
    arrived = np.empty((bodies.shape[0], 3))
    take_velocities(bodies, arrived)
    return arrived


@njit(inline="always")
def arrived_at(arrived, i: int) -> tuple[float, float, float]:
    """Body i's (vx, vy, w) as it arrived (:func:`arrived_velocities`)."""
    return arrived[i, 0], arrived[i, 1], arrived[i, 2]


@njit(inline="always")  # in the loop over contacts: as a call per point, a fifth of the prepare
def prepare_point(c, p, shapes, moving, inv_dt: float, beta: float, slop: float) -> None:
    """Lever arms, anchors (:func:`anchor`), effective masses, velocity target and approach
    speed of one used point; ``moving`` = (the BODY records, their velocities as they
    arrived: :func:`arrived_velocities`)."""
    bodies, arrived = moving
    a, b = bodies[c["a"]], bodies[c["b"]]
    nx, ny = c["normal"][0], c["normal"][1]
    point = p["point"]
    x, y = point[0], point[1]
    com_a, com_b = a["com"], b["com"]
    rax, ray = x - com_a[0], y - com_a[1]
    rbx, rby = x - com_b[0], y - com_b[1]
    reach_a = anchor(shapes[c["shape_a"]], a["cs"], p["local_a"], rax, ray, nx, ny)
    reach_b = anchor(shapes[c["shape_b"]], b["cs"], p["local_b"], rbx, rby, nx, ny)
    p["anchor_depth"] = p["depth"] + reach_a - reach_b  # separation = -depth at detection
    rn_a, rn_b = cross(rax, ray, nx, ny), cross(rbx, rby, nx, ny)
    rt_a, rt_b = cross(rax, ray, ny, -nx), cross(rbx, rby, ny, -nx)
    p["rn_a"], p["rn_b"], p["rt_a"], p["rt_b"] = rn_a, rn_b, rt_a, rt_b
    point_masses(c, p)
    # not the velocities with this step's gravity and warm start: those the bodies arrived with
    va, vb = arrived_at(arrived, c["a"]), arrived_at(arrived, c["b"])
    p["approach_speed"] = speed_along(va, vb, nx, ny, rn_a, rn_b)  # v_r . n
    d = p["depth"]
    p["bias"] = d * inv_dt if d < 0.0 else beta * inv_dt * max(d - slop, 0.0)


@njit
def prepare_block(c) -> None:
    """The 2x2 effective mass matrix K of a two-point manifold, kept as its inverse when it is
    well conditioned (Box2D's block solver, see :func:`sandbox.solvers.iterative.block_normal`)."""
    c["use_block"] = False
    if c["count"] != 2:
        return
    im_a, ii_a, im_b, ii_b = masses(c)
    p0, p1 = c["points"][0], c["points"][1]
    a1, a2 = p0["rn_a"], p1["rn_a"]  # r_a x n at points 0 and 1
    b1, b2 = p0["rn_b"], p1["rn_b"]
    k11 = effective_mass(im_a, ii_a, im_b, ii_b, a1, b1)
    k22 = effective_mass(im_a, ii_a, im_b, ii_b, a2, b2)
    k12 = im_a + im_b + ii_a * a1 * a2 + ii_b * b1 * b2
    det = k11 * k22 - k12 * k12
    if k11 * k11 < BLOCK_CONDITION * det:
        c["use_block"] = True
        # the diagonal as the sweeps would find it from normal_mass, worked out once a step
        c["block_k"][0], c["block_k"][1], c["block_k"][2] = (
            1.0 / p0["normal_mass"],
            k12,
            1.0 / p1["normal_mass"],
        )
        c["block_mass"][0], c["block_mass"][1], c["block_mass"][2] = (
            k22 / det,
            -k12 / det,
            k11 / det,
        )


@njit
def prepare_contacts(
    contacts, k: int, shapes, moving, beta: float, context, block: bool, last
) -> int:
    """Prepare the first ``k`` contacts: copy the bodies' inverse masses, zero the impulses,
    then :func:`prepare_point` and, for a solver that has a block solver (``block``),
    :func:`prepare_block`; then give each the last step's impulses (:func:`match_previous`'s walk)
    and, when asked, apply them at once (:func:`warm_start_contact`). ``moving`` = (the BODY
    records, their velocities as the step began: :func:`arrived_velocities`, which the approach
    speeds are measured at); ``last`` = (the last step's contacts, how many of them: 0 for
    none, whether to warm start here). ``beta``: the Baumgarte factor of the velocity bias (the
    rigid solvers pass 0 and fix overlap on positions instead). Returns the number of points
    warm started; counts the contacts' points into ``context["contact_points"]`` (a pass of
    its own read a line of every record again: 85 to 106 us on the rain of 5,000).

    The warm start's merge and the warm start itself run in this loop, while the contact's
    record is at hand: each as a pass of its own read every record again. On the rain of
    5,000 discs (12,637 contacts, step 200, in one process, in turn): 1,133 us with the warm
    start as a pass of its own, 817 in this loop (the merge: 390 us as its own pass, 340 to
    365 in the loop)."""
    ctx = context[0]
    inv_dt, slop = ctx["inv_dt"], ctx["slop"]
    bodies = moving[0]
    previous, k_old, warm_now = last
    found = q = points_in_all = 0
    for i in range(k):
        c = contacts[i]
        a, b = bodies[c["a"]], bodies[c["b"]]
        c["inv_mass_a"], c["inv_moment_a"] = a["inv_mass"], a["inv_moment"]
        c["inv_mass_b"], c["inv_moment_b"] = b["inv_mass"], b["inv_moment"]
        c["rebound"] = 0.0
        c["soft_impulse_scale"] = 0.0  # a rigid contact: no load sag (the soft step sets it)
        points, count = c["points"], c["count"]
        points_in_all += count
        for j in range(2):
            p = points[j]
            p["normal_impulse"] = p["tangent_impulse"] = 0.0
            p["max_normal_impulse"] = p["bounce_impulse"] = p["bounce_tangent"] = 0.0
            p["held_sag"] = 0.0
            if j < count:
                prepare_point(c, p, shapes, moving, inv_dt, beta, slop)
        if block:
            prepare_block(c)
        else:
            c["use_block"] = False
        if k_old > 0:  # the walk of match_previous, written out here: an inlined function
            # that takes the array and loops had it reference-counted each time
            sa, sb = c["shape_a"], c["shape_b"]
            if q > 0 and not before(previous[q - 1]["shape_a"], previous[q - 1]["shape_b"], sa, sb):
                q = first_at_or_after(previous, q, sa, sb)
            while q < k_old and before(previous[q]["shape_a"], previous[q]["shape_b"], sa, sb):
                q += 1
            if q < k_old and previous[q]["shape_a"] == sa and previous[q]["shape_b"] == sb:
                found += carry_points(c, previous[q])
        if warm_now:
            warm_start_contact(c, bodies)
    ctx["contact_points"] = points_in_all
    return found


@njit
def before(sa0: int, sb0: int, sa: int, sb: int) -> bool:
    """The shape pair (sa0, sb0) comes before (sa, sb)."""
    return sa0 < sa or (sa0 == sa and sb0 < sb)


@njit
def first_at_or_after(contacts, k: int, sa: int, sb: int) -> int:
    """The first of the first ``k`` ``contacts`` (in pair order) whose shape pair is not
    before (sa, sb): a binary search; ``k`` when there is none."""
    lo, hi = 0, k
    while lo < hi:
        mid = (lo + hi) // 2
        if before(contacts[mid]["shape_a"], contacts[mid]["shape_b"], sa, sb):
            lo = mid + 1
        else:
            hi = mid
    return lo


@njit
def match_previous(contacts, k: int, previous, k_old: int) -> int:
    """Warm starting (box2d-lite's ``Arbiter::Update``): give each point of this step the
    impulses of the last step's point with the same shapes and feature id
    (:func:`carry_points`). Both lists are in pair order, sorted by (shape a, shape b), so one
    forward walk finds every match (a merge). Returns the number of points matched."""
    found = q = 0
    for i in range(k):
        c = contacts[i]
        sa, sb = c["shape_a"], c["shape_b"]
        if q > 0 and not before(previous[q - 1]["shape_a"], previous[q - 1]["shape_b"], sa, sb):
            q = first_at_or_after(previous, q, sa, sb)  # not in pair order (hand-made contacts)
        while q < k_old and before(previous[q]["shape_a"], previous[q]["shape_b"], sa, sb):
            q += 1
        if q < k_old and previous[q]["shape_a"] == sa and previous[q]["shape_b"] == sb:
            found += carry_points(c, previous[q])
    return found


@njit(inline="always")
def carry_points(c, old) -> int:
    """Each point of contact ``c`` gets the impulses of the point of ``old`` (the same shapes'
    contact in the last step) with the same feature id. Returns how many matched."""
    found = 0
    old_points, old_count, points = old["points"], old["count"], c["points"]
    for j in range(c["count"]):
        p = points[j]
        for jj in range(old_count):
            o = old_points[jj]
            if o["feature"] == p["feature"]:
                p["normal_impulse"] = o["normal_impulse"]
                p["tangent_impulse"] = o["tangent_impulse"]
                p["held_sag"] = o["held_sag"]
                found += 1
                break
    return found


@njit(inline="always")
def warm_start_contact(c, bodies) -> None:
    """Apply a contact's accumulated impulses of the last step, p_n n and p_t t, again
    (box2d-lite's PreStep)."""
    a, b, points, n = c["a"], c["b"], c["points"], c["normal"]
    nx, ny = n[0], n[1]
    mass = masses(c)
    va, vb = velocity_of(bodies, a), velocity_of(bodies, b)
    for j in range(c["count"]):
        p = points[j]
        va, vb = apply_normal(va, vb, mass, p, nx, ny, p["normal_impulse"])
        va, vb = apply_tangent(va, vb, mass, p, nx, ny, p["tangent_impulse"])
    set_velocity(bodies, a, va)
    set_velocity(bodies, b, vb)


@njit
def warm_start(contacts, k: int, bodies) -> None:
    """Warm start the first ``k`` contacts (:func:`warm_start_contact`), in their order."""
    for i in range(k):
        warm_start_contact(contacts[i], bodies)


@njit(python=True)
def restitution(contacts, k: int, bodies, threshold: float) -> None:
    """Bounce: v_r . n = -e v_r0 . n, with the approach speed v_r0 . n of the start of the step.

    As Box2D's restitution: only points that approached faster than ``threshold`` (m/s) and
    carried an impulse bounce; slower contacts rest. The total impulse stays >= 0. Measured
    after gravity, the approach speed would be g dt too fast and every bounce would gain height.

    A speculative point (a gap g = -depth > 0 at the start of the step) bounces here, before it
    touched; had it bounced at its time of impact, the bodies would end the step (1 + e) g
    closer. ``rebound`` records that distance for the position stage
    (:func:`sandbox.penetration.rebound`), so the bounce starts from the surface.
    """
    for i in range(k):  # rebound is 0 from the prepare stage: a resting contact's record is
        c = contacts[i]  # only read here (writing it made every record's line dirty)
        e = c["restitution"]
        if e == 0.0:
            continue
        nx, ny = c["normal"][0], c["normal"][1]
        mass = masses(c)
        va, vb = velocity_of(bodies, c["a"]), velocity_of(bodies, c["b"])
        for j in range(c["count"]):
            p = c["points"][j]
            if p["approach_speed"] > -threshold or p["max_normal_impulse"] == 0.0:
                continue
            vn = normal_speed(va, vb, p, nx, ny)
            old = p["normal_impulse"] + p["bounce_impulse"]
            new = max(old - p["normal_mass"] * (vn + e * p["approach_speed"]), 0.0)  # -e vn0
            p["bounce_impulse"] += new - old
            va, vb = apply_normal(va, vb, mass, p, nx, ny, new - old)
            c["rebound"] = max(c["rebound"], (1.0 + e) * -p["depth"])
        set_velocity(bodies, c["a"], va)
        set_velocity(bodies, c["b"], vb)
