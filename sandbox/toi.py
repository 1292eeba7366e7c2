"""Continuous collision: distance between convex shapes and time of impact by conservative
advancement (slides, "Conservative Advancement": estimate the time of impact before the
collision happens and move only that far).

Shapes are given as tuples (:func:`shape_of` makes one from a SHAPE record): ``kind`` 0 circle /
1 polygon, ``radius``, ``center`` (circle centre) and ``verts`` (CCW polygon vertices, an empty
(0, 2) array for circles), all relative to the body's centre of mass in the body frame. A pose
is the centre of mass position (m) and the angle (rad). Over a step the pose moves linearly
from its value at t = 0 to its value at t = 1, in position and in angle.

Conservative advancement: at time t the shapes are d apart along the unit direction n. No point
of a body turning by dphi over the step moves faster (per unit t) than |dphi| R, R the largest
distance of the shape from the centre of mass, so along n the gap closes at most at the rate

    bound = |(dp_b - dp_a) . n| + |dphi_a| R_a + |dphi_b| R_b

and t may safely advance by (d - target) / bound. Repeat until d < target + tolerance (impact)
or t >= 1 (no impact this step).
"""

from __future__ import annotations

import math

import numpy as np

from sandbox.jit import njit
from sandbox.narrowphase import joined
from sandbox.records import CIRCLE, POLYGON
from sandbox.solvers.common import first_at_or_after

LINEAR_SLOP = 0.005  # m
MAX_ITERATIONS = 64  # conservative advancement steps before giving up (the last t is used)
# a pair that starts within target + START_BAND x tolerance is already in contact: an advance
# stops within one tolerance of the target, and anything that moves the pair a hair apart
# afterwards (the position stage) would otherwise have it stopped again next step at once, and
# the step after, its velocity growing under gravity while it stands still (a random shock
# scene: 2.56 times its energy within 5 s; tests/test_toi.py)
START_BAND = 2.0


@njit
def _place(kind, center, verts, px, py, angle, wc, wv):
    """World frame of a shape at pose (px, py, angle): wc (2,) circle centre, wv polygon verts."""
    c, s = math.cos(angle), math.sin(angle)
    wc[0] = px + c * center[0] - s * center[1]
    wc[1] = py + s * center[0] + c * center[1]
    if kind == POLYGON:
        for i in range(verts.shape[0]):
            wv[i, 0] = px + c * verts[i, 0] - s * verts[i, 1]
            wv[i, 1] = py + s * verts[i, 0] + c * verts[i, 1]


@njit
def _polygon_point(wv, n, px, py):
    """Signed distance from the polygon wv[:n] (CCW) to the point p and the unit direction from
    the polygon to the point: the nearest edge point when outside, the edge of largest
    separation when inside (negative distance)."""
    best = -math.inf
    bnx, bny = 0.0, 1.0
    for i in range(n):
        j = i + 1 if i + 1 < n else 0
        ex, ey = wv[j, 0] - wv[i, 0], wv[j, 1] - wv[i, 1]
        length = math.sqrt(ex * ex + ey * ey)
        nx, ny = ey / length, -ex / length  # outward normal of a CCW edge
        sep = nx * (px - wv[i, 0]) + ny * (py - wv[i, 1])
        if sep > best:
            best, bnx, bny = sep, nx, ny
    if best <= 0.0:
        return best, bnx, bny
    # outside: distance to the nearest edge point
    d2 = math.inf
    for i in range(n):
        j = i + 1 if i + 1 < n else 0
        ax, ay = wv[i, 0], wv[i, 1]
        ex, ey = wv[j, 0] - ax, wv[j, 1] - ay
        u = ((px - ax) * ex + (py - ay) * ey) / (ex * ex + ey * ey)
        u = 0.0 if u < 0.0 else (1.0 if u > 1.0 else u)
        dx, dy = px - (ax + u * ex), py - (ay + u * ey)
        q2 = dx * dx + dy * dy
        if q2 < d2:
            d2, bnx, bny = q2, dx, dy
    d = math.sqrt(d2)
    if d > 0.0:
        return d, bnx / d, bny / d
    return 0.0, 0.0, 1.0


@njit
def _polygons(wa, na, wb, nb):
    """Signed distance between convex polygons a and b and the unit direction from a to b.

    Overlapping: minus the penetration along the best separating axis (SAT). Apart: the smallest
    vertex-to-edge distance, which for convex polygons is the true distance.
    """
    best = -math.inf
    bnx, bny = 0.0, 1.0
    for side in range(2):
        w1, n1, w2, n2 = (wa, na, wb, nb) if side == 0 else (wb, nb, wa, na)
        flip = 1.0 if side == 0 else -1.0
        for i in range(n1):
            j = i + 1 if i + 1 < n1 else 0
            ex, ey = w1[j, 0] - w1[i, 0], w1[j, 1] - w1[i, 1]
            length = math.sqrt(ex * ex + ey * ey)
            nx, ny = ey / length, -ex / length
            sep = math.inf
            for k in range(n2):
                sep = min(sep, nx * (w2[k, 0] - w1[i, 0]) + ny * (w2[k, 1] - w1[i, 1]))
            if sep > best:
                best, bnx, bny = sep, flip * nx, flip * ny
    if best <= 0.0:
        return best, bnx, bny
    dmin = math.inf
    for k in range(nb):  # vertices of b against the edges of a
        d, nx, ny = _polygon_point(wa, na, wb[k, 0], wb[k, 1])
        if d < dmin:
            dmin, bnx, bny = d, nx, ny
    for k in range(na):  # vertices of a against the edges of b (direction b -> a, flipped)
        d, nx, ny = _polygon_point(wb, nb, wa[k, 0], wa[k, 1])
        if d < dmin:
            dmin, bnx, bny = d, -nx, -ny
    return dmin, bnx, bny


@njit
def _distance_world(ka, ra, wca, wva, na, kb, rb, wcb, wvb, nb):
    """Signed distance and unit direction a -> b of two shapes already in the world frame."""
    if ka == CIRCLE and kb == CIRCLE:
        dx, dy = wcb[0] - wca[0], wcb[1] - wca[1]
        d = math.sqrt(dx * dx + dy * dy)
        if d > 0.0:
            return d - ra - rb, dx / d, dy / d
        return -ra - rb, 0.0, 1.0
    if ka == POLYGON and kb == CIRCLE:
        d, nx, ny = _polygon_point(wva, na, wcb[0], wcb[1])
        return d - rb, nx, ny
    if ka == CIRCLE and kb == POLYGON:
        d, nx, ny = _polygon_point(wvb, nb, wca[0], wca[1])
        return d - ra, -nx, -ny
    return _polygons(wva, na, wvb, nb)


@njit
def distance(shape_a, pose_a, shape_b, pose_b):
    """Signed distance (m) between two convex shapes at the given poses, and the unit direction
    from a to b along which it is measured: ``(d, nx, ny)``, d < 0 when they overlap.

    ``shape = (kind, radius, center, verts)`` (about the centre of mass, body frame; ``verts``
    an empty (0, 2) array for circles), ``pose = (position (2,), angle)``."""
    kind_a, radius_a, center_a, verts_a = shape_a
    kind_b, radius_b, center_b, verts_b = shape_b
    wca, wcb = np.empty(2), np.empty(2)
    wva = np.empty((verts_a.shape[0], 2))
    wvb = np.empty((verts_b.shape[0], 2))
    _place(kind_a, center_a, verts_a, pose_a[0][0], pose_a[0][1], pose_a[1], wca, wva)
    _place(kind_b, center_b, verts_b, pose_b[0][0], pose_b[0][1], pose_b[1], wcb, wvb)
    return _distance_world(
        kind_a, radius_a, wca, wva, verts_a.shape[0], kind_b, radius_b, wcb, wvb, verts_b.shape[0]
    )


@njit
def bound_radius(kind, radius, center, verts):
    """Radius about the centre of mass enclosing the shape (m): |c| + r, or max |v_i|."""
    if kind == CIRCLE:
        return math.sqrt(center[0] ** 2 + center[1] ** 2) + radius
    r = 0.0
    for i in range(verts.shape[0]):
        r = max(r, math.sqrt(verts[i, 0] ** 2 + verts[i, 1] ** 2))
    return r


@njit
def _advance(shape_a, motion_a, shape_b, motion_b, limits, work):
    """Conservative advancement of ``shape = (kind, radius, center, verts, bound)`` along
    ``motion = (x0, y0, angle0, x1, y1, angle1)``; returns t in [0, 1], or -1.0 when the shapes
    are already within ``target + START_BAND * tol`` at t = 0. ``limits = (target, tol,
    max_iterations)``; ``work = (wca, wva, wcb, wvb)`` buffers, (2,) and (n, 2)."""
    target, tol, max_iterations = limits
    wca, wva, wcb, wvb = work
    ka, ra, ca, va, bound_a = shape_a
    kb, rb, cb, vb, bound_b = shape_b
    xa0, ya0, aa0, xa1, ya1, aa1 = motion_a
    xb0, yb0, ab0, xb1, yb1, ab1 = motion_b
    dpx = (xb1 - xb0) - (xa1 - xa0)  # relative displacement over the step
    dpy = (yb1 - yb0) - (ya1 - ya0)
    spin = abs(aa1 - aa0) * bound_a + abs(ab1 - ab0) * bound_b
    t = 0.0
    for it in range(max_iterations):
        # poses interpolated linearly in position and angle
        _place(
            ka,
            ca,
            va,
            xa0 + t * (xa1 - xa0),
            ya0 + t * (ya1 - ya0),
            aa0 + t * (aa1 - aa0),
            wca,
            wva,
        )
        _place(
            kb,
            cb,
            vb,
            xb0 + t * (xb1 - xb0),
            yb0 + t * (yb1 - yb0),
            ab0 + t * (ab1 - ab0),
            wcb,
            wvb,
        )
        d, nx, ny = _distance_world(ka, ra, wca, wva, va.shape[0], kb, rb, wcb, wvb, vb.shape[0])
        if it == 0 and d < target + START_BAND * tol:
            return -1.0  # already in contact
        if d < target + tol:
            return t
        # slides, "Conservative Advancement": advance by distance / (bound on closing speed)
        bound = abs(dpx * nx + dpy * ny) + spin
        if bound <= 1e-15:
            return 1.0
        t += (d - target) / bound
        if t >= 1.0:
            return 1.0
    return t


@njit(python=True)
def time_of_impact(shape_a, motion_a, shape_b, motion_b, target_separation=0.0, tolerance=1e-4):
    """Fraction t in [0, 1] of the step at which shapes a and b first come within
    ``target_separation`` (m, up to ``tolerance``) of each other; 1.0 when they do not this
    step, 0.0 when they already are at t = 0 (up to ``START_BAND`` tolerances).

    ``shape = (kind, radius, center, verts)`` as for :func:`distance`; ``motion = (position at
    t = 0 (2,), angle at t = 0, position at t = 1, angle at t = 1)``, interpolated linearly."""
    wca, wcb = np.empty(2), np.empty(2)
    wva = np.empty((shape_a[3].shape[0], 2))
    wvb = np.empty((shape_b[3].shape[0], 2))
    t = _advance(
        (*shape_a, bound_radius(*shape_a)),
        _flat(motion_a),
        (*shape_b, bound_radius(*shape_b)),
        _flat(motion_b),
        (target_separation, tolerance, MAX_ITERATIONS),
        (wca, wva, wcb, wvb),
    )
    return max(t, 0.0)


@njit
def _flat(motion):
    """(x0, y0, angle0, x1, y1, angle1) of a motion (p0, angle0, p1, angle1)."""
    p0, a0, p1, a1 = motion
    return p0[0], p0[1], a0, p1[0], p1[1], a1


@njit
def shape_of(shape, vertices):
    """A SHAPE record as ``(kind, radius, center, verts)`` for :func:`distance` and
    :func:`time_of_impact` (polygon vertices copied out of the VERTEX records)."""
    n = shape["vertex_count"] if shape["kind"] == POLYGON else 0
    verts = np.empty((n, 2))
    for v in range(n):
        q = vertices[shape["first_vertex"] + v]["point"]
        verts[v, 0], verts[v, 1] = q[0], q[1]
    center = np.array([shape["center"][0], shape["center"][1]])
    return shape["kind"], shape["radius"], center, verts


@njit
def body_motion(b):
    """A body's planned motion this step: from (com, angle) to (com + motion, angle + turn)."""
    p0 = np.array([b["com"][0], b["com"][1]])
    p1 = np.array([b["com"][0] + b["motion"][0], b["com"][1] + b["motion"][1]])
    return p0, b["angle"], p1, b["angle"] + b["motion_turn"]


@njit
def swept_pairs(bodies, shapes):
    """Shape pairs (k, 2), i < j, whose swept discs may meet this step and where at least one
    body has ccd: each shape stays within ``bound`` of its body's centre of mass, which moves
    by ``motion``, so its swept box is that segment's box grown by the bound."""
    m = shapes.shape[0]
    box = np.empty((m, 4))
    for k in range(m):
        b, r = bodies[shapes[k]["body"]], shapes[k]["bound"]
        for a in range(2):
            box[k, a] = min(b["com"][a], b["com"][a] + b["motion"][a]) - r
            box[k, a + 2] = max(b["com"][a], b["com"][a] + b["motion"][a]) + r
    out = np.empty((16, 2), dtype=np.int64)
    n = 0
    for i in range(m):
        bi = shapes[i]["body"]
        if not bodies[bi]["ccd"]:
            continue
        for j in range(m):
            bj = shapes[j]["body"]
            if bj == bi or (bodies[bj]["ccd"] and j < i):
                continue  # same body, or a ccd pair already listed from its other shape
            if box[i, 0] > box[j, 2] or box[j, 0] > box[i, 2]:
                continue
            if box[i, 1] > box[j, 3] or box[j, 1] > box[i, 3]:
                continue
            if n == out.shape[0]:
                grown = np.empty((2 * n, 2), dtype=np.int64)
                # a loop: a slice copy compiles numba's message for mismatched shapes (2.5 s)
                for r in range(n):
                    grown[r, 0], grown[r, 1] = out[r, 0], out[r, 1]
                out = grown
            out[n, 0], out[n, 1] = min(i, j), max(i, j)
            n += 1
    return out[:n]


@njit
def ccd_fractions(bodies, shapes, vertices, pairs, target_separation, tolerance, found):
    """For every body, the fraction of this step's motion (``motion``, ``motion_turn``) it may
    take: the earliest time of impact over the ``pairs`` ((k, 2) shape indices) that involve a
    body with ``ccd`` set, 1.0 for other bodies and when nothing is hit.

    Pairs already within ``target_separation`` at the start (up to ``START_BAND`` tolerances)
    are left to the discrete narrowphase (its contact margin should be at least that), so a
    body resting on the ground is never frozen; but the ccd shape's core (:func:`core_of`) must
    not come that close either (as Box2D v3): the narrowphase's points are the features
    touching at the start, and a long box struck at one corner at speed spins its other corner
    through the ground. ``found`` = (contacts, k, joints, held): with ``held`` (in a substep
    of the soft step, or in the rigid step's position stage) the narrowphase ran once, before
    the moves, so such a pair (unless its bodies share a joint: joined bodies do not collide) is
    left to the solver only when it has a contact among the first ``k``; otherwise (stopped at
    its impact by an earlier move) its ccd body stays where it is (t = 0) until the next step's
    narrowphase finds the contact. Without ``held`` (the rigid step's own motion, which the
    narrowphase before it saw whole) every such pair is left to the narrowphase. A flag, not
    None for the rigid step: one compiled version serves both (1.8 s less compiling). A
    pair whose core began within reach (deep in the other shape) is left to the solver and
    the position stage, in both steps: held still instead, a heavy ball deep in a light body
    stood still while gravity added g dt to its velocity every step (to 17.6 m/s in 2 s).
    """
    contacts, k, joints, held = found
    frac = np.ones(bodies.shape[0])
    for q in range(pairs.shape[0]):
        i, j = pairs[q, 0], pairs[q, 1]
        bi, bj = shapes[i]["body"], shapes[j]["body"]
        if bi == bj or not (bodies[bi]["ccd"] or bodies[bj]["ccd"]):
            continue
        shape_i, shape_j = shape_of(shapes[i], vertices), shape_of(shapes[j], vertices)
        motion_i, motion_j = body_motion(bodies[bi]), body_motion(bodies[bj])
        limits = (target_separation, tolerance)
        t = time_of_impact(shape_i, motion_i, shape_j, motion_j, *limits)
        if t <= 0.0:  # already in contact: the narrowphase handles it, up to the cores
            if held and joined(joints, bodies.shape[0], bi, bj):
                continue  # joined bodies do not collide
            t = 1.0
            if bodies[bi]["ccd"]:
                t = core_impact(core_of(shape_i), motion_i, shape_j, motion_j, limits, t)
            if bodies[bj]["ccd"]:
                t = core_impact(core_of(shape_j), motion_j, shape_i, motion_i, limits, t)
            touching = not held or in_contact(contacts, k, i, j)
            if t <= 0.0 and touching:
                continue  # a core already that close: deep overlap, the position stage's
            if not touching:
                t = 0.0
        for b in (bi, bj):
            if bodies[b]["ccd"] and t < frac[b]:
                frac[b] = t
    return frac


@njit
def core_of(shape):
    """A shape's core: a circle about its centre (its centroid) of a quarter of its smallest
    extent (the radius, or the distance from the centroid to the nearest edge)."""
    kind, radius, center, verts = shape
    extent = radius
    if kind == POLYGON:
        n = verts.shape[0]
        extent = np.inf
        for v in range(n):
            ax, ay = verts[v, 0] - center[0], verts[v, 1] - center[1]
            ex, ey = verts[(v + 1) % n, 0] - verts[v, 0], verts[(v + 1) % n, 1] - verts[v, 1]
            length = math.sqrt(ex * ex + ey * ey)
            if length > 0.0:
                extent = min(extent, abs(ax * ey - ay * ex) / length)
    # an int64 kind, not the constant's literal type: the time of impact's one compiled version
    # serves cores and shapes alike (a literal compiled a second, 0.5 s)
    return np.int64(CIRCLE), 0.25 * extent, center.copy(), np.empty((0, 2))


@njit
def core_impact(core, motion, other, other_motion, limits, t: float) -> float:
    """The earlier of ``t`` and the time the ``core`` comes within ``limits`` = (target,
    tolerance) of ``other``: 0.0 when it already is (the shapes overlap deeply)."""
    return min(t, time_of_impact(core, motion, other, other_motion, limits[0], limits[1]))


@njit
def in_contact(contacts, k: int, i: int, j: int) -> bool:
    """Whether shapes i < j have a contact among the first ``k`` of ``contacts``, which are in
    pair order (sorted by (shape_a, shape_b), as the narrowphase writes them)."""
    q = first_at_or_after(contacts, k, i, j)
    return q < k and contacts[q]["shape_a"] == i and contacts[q]["shape_b"] == j


@njit(python=True)
def limit_ccd_motion(bodies, shapes, vertices, context, found):
    """Conservative advancement for the ``ccd`` bodies: each moves only up to its time of
    impact, a quarter of the contact margin short of touching (``motion`` and ``motion_turn``
    scaled in place); the next step's narrowphase then finds the contact (retroactive detection
    takes over). ``found``: this step's (contacts, k, joints, held), see :func:`ccd_fractions`
    (no default: the staged step passes every argument, as a left-out one sent a call there
    through numba's slow dispatch, tests/test_dispatch.py). Returns each body's fraction."""
    target = impact_target(context)
    pairs = swept_pairs(bodies, shapes)
    if pairs.shape[0] == 0:
        return np.ones(bodies.shape[0])
    frac = ccd_fractions(bodies, shapes, vertices, pairs, target, 0.25 * target, found)
    for i in range(bodies.shape[0]):
        b = bodies[i]
        b["motion"][0] *= frac[i]
        b["motion"][1] *= frac[i]
        b["motion_turn"] *= frac[i]
    return frac


@njit
def impact_target(context) -> float:
    """How far short of touching a ccd body stops (m): a quarter of the contact margin, so
    the next step's narrowphase finds the contact (the slop without a margin)."""
    margin = context[0]["contact_margin"]
    return 0.25 * margin if margin > 0.0 else LINEAR_SLOP


@njit
def hold_stopped(bodies, frac, stopped) -> None:
    """In the soft step's substeps: a body stopped at an impact (``frac`` < 1) stays where
    it stopped for the rest of the step (``stopped``, one flag per body, kept across the
    substeps), as the rigid step moves it only once: no narrowphase runs between substeps to
    find the contact it stopped short of."""
    for i in range(bodies.shape[0]):
        if stopped[i]:
            b = bodies[i]
            b["motion"][0] = b["motion"][1] = b["motion_turn"] = 0.0
        elif frac[i] < 1.0:
            stopped[i] = True
