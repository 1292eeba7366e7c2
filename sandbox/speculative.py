"""Speculative contacts that reach as far as the bodies move in one step (``settings.speculative``).

A contact is created for every pair of shapes closer than ``contact_margin`` (2 cm), touching or
not: a point with a gap g > 0 asks the solver only that the pair close no more than g in this step
(its bias is g / dt), so a body arriving at a surface stops on it instead of in it. With a fixed
margin that works for bodies slower than margin / dt (1.2 m/s at 60 Hz). A faster body is still a
margin away at the start of one step and deep in the surface at its end: the contact is found a
step late (a ball landing at 6 m/s ends that step 19 mm deep under the iterative solver, one at
3 m/s 13 mm under the soft step, and bounces from there), and a fast enough one passes a thin
wall entirely (tunnelling, lesson 06).

Speculative contacts with a margin from the speeds (Erin Catto, "Continuous Collision", GDC 2013;
Box2D v3 and Bepu work this way) reach as far as a pair can close within the step. No point of a
shape moves faster than |v| + |omega| r, r the radius about the centre of mass that encloses the
shape (``bound``), so two shapes close by at most

    (|v_b - v_a| + |omega_a| r_a + |omega_b| r_b) dt

in a step of dt, at the speeds the step starts with; ``contact_margin`` covers what gravity adds
within the step (|g| dt^2, 2.7 mm at 60 Hz). The narrowphase keeps points whose gap is within
that plus ``contact_margin`` (:func:`closing_reach`); each shape's box in the broadphase grows
by its own share, (|v| + |omega| r) dt (:func:`box_reach`), so that every such pair is found.
The solver needs nothing new: a point that would not close carries no impulse, one that would
stops at the surface, and the restitution pass bounces it from there (``rebound``), from the
approach speed of the step's start: met up to a step before it lands, a falling ball bounces
without what gravity adds until then (first apex 0.45 m, not 0.50 m, from 2 m at e = 0.5).

The price is the ghost hit: a contact's normal is the one of the closest features now, and a
body flying fast past a corner can be stopped by it though its path would have missed. Lesson 06
shows one. ``settings.speculative`` is off by default, so the classic margin and the tunnelling
it allows stay what the lessons show; continuous collision (``ccd``) has no ghosts but costs a
time of impact per fast body.
"""

from __future__ import annotations

import math

from sandbox.jit import njit


@njit(inline="always")
def moving_speed(body, shape) -> float:
    """The fastest any point of ``shape`` moves with its body (m/s): |v| + |omega| r."""
    v = body["vel"]
    return math.hypot(v[0], v[1]) + abs(body["omega"]) * shape["bound"]


@njit(inline="always")
def box_reach(body, shape, ahead: float) -> float:
    """How far (m) ``shape``'s broadphase box grows for speculative contacts: as far as the
    shape moves in ``ahead`` s (the step; 0 when ``settings.speculative`` is off)."""
    if ahead == 0.0:
        return 0.0
    return moving_speed(body, shape) * ahead


@njit(inline="always")
def closing_reach(body_i, shape_i, body_j, shape_j, ahead: float) -> float:
    """How far (m) the two shapes can close on each other in ``ahead`` s:
    (|v_j - v_i| + |omega_i| r_i + |omega_j| r_j) ahead; 0 when ``ahead`` is 0."""
    if ahead == 0.0:
        return 0.0
    vi, vj = body_i["vel"], body_j["vel"]
    relative = math.hypot(vj[0] - vi[0], vj[1] - vi[1])
    turning = abs(body_i["omega"]) * shape_i["bound"] + abs(body_j["omega"]) * shape_j["bound"]
    return (relative + turning) * ahead
