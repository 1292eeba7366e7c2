"""Soft step: substeps, soft contacts, a relax pass and restitution (Box2D v3's solver;
Erin Catto, "Solver2D", 2024).

A rigid constraint asks the velocities to remove the whole error at once; sequential impulses
never quite converge, and the error they leave (a box sunk into the one below, a chain link
stretched) must be fought again every step. A *soft* constraint behaves like a stiff damped
spring instead: the error C pulls back with a stiffness set as a frequency f (Hz) and a damping
ratio zeta, the mass-spring-damper m x'' + c x' + k x = 0 with k = m omega^2, c = 2 m zeta omega,
omega = 2 pi f. Integrated implicitly over a substep h, the impulse that does that is

    lambda = -m_eff (mass_scale (Cdot) + bias_rate mass_scale C) - impulse_scale lambda_total

with (:func:`softness`)

    bias_rate = omega / (2 zeta + h omega),   mass_scale = h omega (2 zeta + h omega) / (1 + h omega (2 zeta + h omega)),
    impulse_scale = 1 / (1 + h omega (2 zeta + h omega)).

Per step (``sandbox.step``): prepare the contacts and joints once (effective masses, the
softness for this substep length, each point's separation at the start); then ``substeps``
times: integrate the velocities over h, warm start (the accumulated impulses again), solve
with the soft bias, integrate the positions, and *relax*: solve again without bias, so the
velocities the next substep starts from carry no push-out speed; after the substeps, the
position stage every solver shares (``sandbox.penetration.fix_positions``: only what sank
beyond the slop) and the restitution pass. Contacts with a static body are twice as stiff, as
in Box2D (bodies are not pushed through the ground). Overlap is pushed out at most at
``max_push_speed`` (m/s); a point that began the step deeper than its load's sag explains
(:func:`load_sag`) by more than the slop plus one step of that push gets no push from the bias
at all and is left to the position stage, which takes it out at that bounded speed (the
pushes of a pile's many overlapping pairs would otherwise add up to tens of m/s).

Sag recovery (this engine's, past Box2D): at rest a soft contact sinks until its spring carries
its load, by the static error g / omega^2 per load it carries (:func:`load_sag`), and a pile's
rows add theirs up (a pyramid of 40: 122 mm). Each contact keeps a *held sag* (:func:`hold_sag`,
stored at each of its points), carried from step to step like its impulses, and the bias pulls
towards s = -held_sag instead of 0: every biased pass adds h / T of its points' mean overlap to
it (T = ``settings.sag_recovery_time``), up to the sag their loads explain, so after a few T
the spring rests where the load is carried at s = 0 (the same pyramid: a few mm after 5 s). It
is integral action on the spring, the I of a PI controller; the spring and damper still take
every change of load, and alone answer a tilt. ``sag_recovery_time`` 0 turns it off.

Mass ratios: a soft contact is a spring of stiffness m_eff omega^2, and between a light body and
a heavy one m_eff is about the light body's, so the heavy body's weight sinks it by
(m_heavy / m_light) g / omega^2 (11 cm at 400:1 and 30 Hz), and sweeps share the load out
slowly. A body resting on one more than ``settings.hold_ratio`` times lighter treats it as
immovable (:func:`hold_under_heavy_loads`, shock propagation where the masses differ that much).

Why substeps can beat iterations at equal arithmetic: an iteration shares one velocity error
out among the constraints; a substep also moves the bodies, so each constraint then sees its
real, current error (the separation is recomputed from the bodies' moves), and the gravity a
stack must carry arrives in small pieces. (At equal time they do not on this engine yet: the
iterative sweeps visit eight contacts at once, :mod:`sandbox.solvers.wide`, these passes one.)
"""

from __future__ import annotations

import math

import numpy as np

from sandbox.jit import njit
from sandbox.math2d import put_velocity, rotate, velocity
from sandbox.solvers.common import (
    apply_normal,
    apply_tangent,
    masses,
    normal_speed,
    point_masses,
    tangent_speed,
)
from sandbox.solvers.iterative import visit
from sandbox.solvers.shock import contact_layers, touching

STATIC_STIFFNESS = 2.0  # contacts with a body that cannot move are this many times stiffer
MAX_CONTACT_HERTZ_PER_RATE = 0.125  # contact_hertz is capped at this times the substep rate
HOLD_SLOPE = 0.5  # settings.hold_ratio: resting on: the normal within 60 degrees of upright


@njit(python=True)
def softness(hertz: float, zeta: float, h: float) -> tuple[float, float, float]:
    """(bias_rate (1/s), mass_scale, impulse_scale) of a soft constraint of frequency
    ``hertz`` and damping ratio ``zeta`` over a substep ``h`` (s); rigid (0, 1, 0) at 0 Hz."""
    if hertz == 0.0:
        return 0.0, 1.0, 0.0
    omega = 2.0 * math.pi * hertz
    a1 = 2.0 * zeta + h * omega
    a2 = h * omega * a1
    a3 = 1.0 / (1.0 + a2)
    return omega / a1, a2 * a3, a3


@njit
def with_fixed(c) -> bool:
    """Whether contact ``c`` is with a body that cannot move (the ground, or one held still by
    :func:`hold_under_heavy_loads`): its 1/m in the record is 0."""
    return c["inv_mass_a"] == 0.0 or c["inv_mass_b"] == 0.0


@njit
def prepare_soft(contacts, k: int, bodies, context) -> None:
    """The soft step's additions to :func:`sandbox.solvers.common.prepare_contacts`: each
    point's base separation, what :func:`separation_now` adds the bodies' moves to, and each
    contact's softness (twice the stiffness against a body that cannot move). No
    stiffer than an eighth of the substep rate
    (MAX_CONTACT_HERTZ_PER_RATE, as Box2D since v3.1): at a quarter (Box2D v3.0) a pyramid of 40
    boxes rings forever, its top box swinging between 15 mm up and 69 mm down (Box2D's own solver
    with the quarter cap rings too); at an eighth it rests."""
    ctx = context[0]
    h = ctx["dt"] / ctx["substeps"]
    hertz = min(ctx["contact_hertz"], MAX_CONTACT_HERTZ_PER_RATE / h)
    zeta = ctx["contact_damping_ratio"]
    moving, static = softness(hertz, zeta, h), softness(STATIC_STIFFNESS * hertz, zeta, h)
    for i in range(k):
        c = contacts[i]
        rate, mass_scale, impulse_scale = static if with_fixed(c) else moving
        c["soft_bias_rate"], c["soft_mass_scale"] = rate, mass_scale
        c["soft_impulse_scale"] = impulse_scale
        nx, ny = c["normal"][0], c["normal"][1]
        com_a, com_b = bodies[c["a"]]["com"], bodies[c["b"]]["com"]
        for j in range(c["count"]):
            p = c["points"][j]
            point = p["point"]
            # s0 - (R_b l_b - R_a l_a) . n, l the anchors: the contact point's arms r less
            # each circle's reach along n (anchor_depth has them), -anchor_depth - (r_b - r_a) . n
            rax, ray = point[0] - com_a[0], point[1] - com_a[1]
            rbx, rby = point[0] - com_b[0], point[1] - com_b[1]
            p["base_separation"] = -p["anchor_depth"] - ((rbx - rax) * nx + (rby - ray) * ny)
            pair = bodies[c["a"]], bodies[c["b"]]
            p["separation"] = separation_now(c, p, pair)  # what the first solve pass needs


@njit
def heavy_on_light(contacts, k: int, ratio: float, gap: float) -> bool:
    """Whether two bodies in touch (closer than ``gap``, m) differ in mass more than ``ratio``
    times."""
    for i in range(k):
        c = contacts[i]
        im_a, im_b = c["inv_mass_a"], c["inv_mass_b"]
        if im_a > 0.0 and im_b > 0.0 and max(im_a, im_b) > ratio * min(im_a, im_b):
            if touching(c, gap):
                return True
    return False


@njit
def hold_under_heavy_loads(contacts, k: int, bodies, context) -> int:
    """Hold still the lower body of each contact where a body more than ``ratio`` times
    heavier rests on it (``settings.hold_ratio``), for the whole step: its 1/m and 1/I in the
    contact record become 0 and the point masses are worked out again (shock propagation, only
    where the masses differ that much). Layers from the ground up
    (:func:`sandbox.solvers.shock.contact_layers`, over contacts closer than the touch margin)
    say which body is lower; the heavy one rests on it when the normal from the lower body to
    the upper points within 60 degrees of straight up, against gravity (``HOLD_SLOPE``), so a
    heavy body that strikes a light one from the side still pushes it, and when the light one
    began the step moving up into the heavy one no faster than
    ``settings.restitution_threshold`` (m/s): a held body keeps its velocity, and a light one
    striking fast from below would hit the heavy one as an immovable ram (a 0.2 kg triangle
    at 32 m/s launched a 30 kg block at 25 m/s). Returns how many contacts hold a body.

    Why: sequential impulses share a heavy load out between a light body's contacts slowly
    (each pass moves the heavy body by about m_light/m_heavy of its error), and a soft contact
    sags by its load over its effective mass, which is the light body's: 1 kg under 400 kg sank
    17 cm and was squeezed out. Held, the contact's effective mass is the heavy body's and its
    sag g / omega^2, as for a box on the ground. The light body no longer feels the load through
    this contact (the ground under it carries its own weight only)."""
    ctx = context[0]
    gravity, ratio, gap = ctx["gravity"], ctx["hold_ratio"], ctx["touch_margin"]
    g = math.hypot(gravity[0], gravity[1])
    if g == 0.0 or not heavy_on_light(contacts, k, ratio, gap):
        return 0
    layer = contact_layers(contacts, k, bodies, gap)
    held = 0
    for i in range(k):
        c = contacts[i]
        la, lb = layer[c["a"]], layer[c["b"]]
        if la == lb or not touching(c, gap):
            continue
        im_a, im_b = c["inv_mass_a"], c["inv_mass_b"]
        lower, upper = (im_a, im_b) if la < lb else (im_b, im_a)
        up = -(c["normal"][0] * gravity[0] + c["normal"][1] * gravity[1]) / g  # n . up, a to b
        if la > lb:
            up = -up
        if lower == 0.0 or upper * ratio >= lower or up < HOLD_SLOPE:
            continue
        lower_body = bodies[c["a"]] if la < lb else bodies[c["b"]]
        if rising(lower_body, c["normal"], la < lb) > ctx["restitution_threshold"]:
            continue
        if la < lb:
            c["inv_mass_a"] = c["inv_moment_a"] = 0.0
        else:
            c["inv_mass_b"] = c["inv_moment_b"] = 0.0
        for j in range(c["count"]):
            point_masses(c, c["points"][j])
        held += 1
    return held


@njit
def rising(lower, normal, lower_is_a: bool) -> float:
    """How fast (m/s) the lower body of a contact moves towards the upper one along the normal
    (``normal`` points from a to b)."""
    speed = lower["vel"][0] * normal[0] + lower["vel"][1] * normal[1]
    return speed if lower_is_a else -speed


@njit
def separation_now(c, p, pair) -> float:
    """The point's separation after the bodies' moves this step (m, < 0 overlapping):
    s = s_base + ((dp_b - dp_a) + R_b l_b - R_a l_a) . n, the normal held fixed, l the
    anchors (``local_a``, ``local_b``: :func:`sandbox.solvers.common.anchor`); ``pair``: the
    BODY records of the contact's bodies a and b."""
    a, b = pair
    rax, ray = rotate(a["cs"][0], a["cs"][1], p["local_a"][0], p["local_a"][1])
    rbx, rby = rotate(b["cs"][0], b["cs"][1], p["local_b"][0], p["local_b"][1])
    dx = b["delta_position"][0] - a["delta_position"][0] + rbx - rax
    dy = b["delta_position"][1] - a["delta_position"][1] + rby - ray
    return p["base_separation"] + dx * c["normal"][0] + dy * c["normal"][1]


@njit
def load_sag(c, p) -> float:
    """How far (m) a soft contact point sinks under the load it carries: at rest the impulse
    of a substep, lambda, holds it where the bias and the leak of the accumulated impulse
    balance, mass_scale bias_rate C m_eff = -impulse_scale lambda, so
    -C = impulse_scale lambda / (mass_scale bias_rate m_eff) = lambda / (m_eff h omega^2)
    (the g / omega^2 per load of the soft step lesson)."""
    rate = c["soft_mass_scale"] * c["soft_bias_rate"] * p["normal_mass"]
    return c["soft_impulse_scale"] * p["normal_impulse"] / rate if rate > 0.0 else 0.0


@njit
def excess_depth(c, p) -> float:
    """How deep (m) a contact point began the step, less what its load explains
    (:func:`load_sag`): a loaded soft contact sinks by design, and only overlap beyond that
    counts as deep; the rigid solvers keep no such sag (0)."""
    return p["depth"] - load_sag(c, p)


@njit
def hold_sag(c, recovery: float) -> float:
    """A contact's held sag after one biased pass (m), the same at its points: what they held,
    plus ``recovery`` (h / T, T = ``settings.sag_recovery_time``) times their mean overlap -s
    (less, where they are apart), never below 0 and never more than the mean sag their loads
    explain (:func:`load_sag`). Integral action on the spring: the bias pulls towards
    -held_sag, so a contact held at s < 0 gains held_sag at |s| / T a second until the load's
    sag is all held and s = 0. Without the bound a contact that is deep for another reason (a
    box tipping over an edge) would hold ever more and push its pile apart. Per contact, not
    per point: a point's own held sag would also answer a tilt (the loaded corner of a
    rocking box pushed up a second later, the other let down), and a column of ten boxes
    rocked further every swing, its top box 0.5 m to either side within 25 s."""
    n = c["count"]
    held = overlap = sag = 0.0
    for j in range(n):
        p = c["points"][j]
        held += p["held_sag"]
        overlap -= p["separation"]
        sag += load_sag(c, p)
    return min(max((held + recovery * overlap) / n, 0.0), sag / n)


@njit(inline="always")  # compiled into solve_soft itself, as the iterative sweep's visits
def solve_soft_contact(c, pair, inv_h: float, use_bias: bool, push) -> None:
    """One contact: the normal impulses (soft, or rigid without bias in the relax pass), then
    friction within the cone of the current normal impulse (Box2D v3's order). ``push`` =
    (max_push_speed (m/s), deep (m), recovery): a point that began the step more than ``deep``
    into overlap beyond the sag its load explains (:func:`load_sag`) gets no push from the bias;
    the position stage takes it out at a bounded speed (``settings.robust_positions``), where
    the pushes of many overlapping neighbours would add up to tens of m/s here. ``recovery``
    (h / sag_recovery_time, 0: off): how much of its overlap each biased pass adds to the
    contact's held sag (:func:`hold_sag`). ``pair``: the BODY records of the contact's bodies
    a and b (records, not the array: inlined, an array is reference-counted at every contact)."""
    max_push, deep, recovery = push
    nx, ny = c["normal"][0], c["normal"][1]
    mass = masses(c)
    recover = use_bias and recovery > 0.0  # sag recovery off: held_sag stays 0, as prepared
    held = hold_sag(c, recovery) if recover else 0.0  # from the separations the pass reads
    va, vb = velocity(pair[0]), velocity(pair[1])
    for j in range(c["count"]):
        p = c["points"][j]
        if use_bias:  # the bodies have not moved since the last pass measured s
            s = p["separation"]
        else:  # the relax pass comes right after the move: measure s again
            s = separation_now(c, p, pair)
            p["separation"] = s
        bias, mass_scale, impulse_scale = 0.0, 1.0, 0.0
        if s > 0.0:
            bias = s * inv_h  # speculative: the gap may close within this substep
        elif use_bias and (p["depth"] <= deep or excess_depth(c, p) <= deep):
            # the spring pulls towards s = -held_sag below its rest, what the load presses in
            bias = max(c["soft_mass_scale"] * c["soft_bias_rate"] * (s - held), -max_push)
            mass_scale, impulse_scale = c["soft_mass_scale"], c["soft_impulse_scale"]
        vn = normal_speed(va, vb, p, nx, ny)
        old = p["normal_impulse"]
        change = -p["normal_mass"] * (mass_scale * vn + bias) - impulse_scale * old
        new = max(old + change, 0.0)
        p["normal_impulse"] = new
        p["max_normal_impulse"] = max(p["max_normal_impulse"], new)
        va, vb = apply_normal(va, vb, mass, p, nx, ny, new - old)
        if recover:
            p["held_sag"] = held
    for j in range(c["count"]):
        p = c["points"][j]
        old = p["tangent_impulse"]
        limit = c["friction"] * p["normal_impulse"]
        vt = tangent_speed(va, vb, p, nx, ny)
        new = min(max(old - p["tangent_mass"] * vt, -limit), limit)
        p["tangent_impulse"] = new
        va, vb = apply_tangent(va, vb, mass, p, nx, ny, new - old)
    put_velocity(pair[0], va)
    put_velocity(pair[1], vb)


@njit
def soft_order(contacts, k: int):
    """The order every pass of this step visits the first ``k`` contacts: those between moving
    bodies first, then those with a body that cannot move (the ground has the last word in
    each pass, so what rests on it is not pushed into it); within each group alternately from
    its two halves (:func:`sandbox.solvers.iterative.visit`, so the processor overlaps two
    visits that rarely share a body)."""
    order = np.empty(k, dtype=np.int64)
    start = 0
    for fixed in (False, True):
        end = start
        for i in range(k):
            if with_fixed(contacts[i]) == fixed:
                order[end] = i
                end += 1
        group = order[start:end].copy()
        half = (group.shape[0] + 1) // 2
        for q in range(group.shape[0]):
            order[start + q] = group[visit(q, half)]
        start = end
    return order


@njit
def solve_soft(contacts, order, bodies, context, use_bias: bool) -> None:
    """One pass over the contacts in ``order`` (:func:`soft_order`): with the soft bias
    (solve) or without (relax). The relax pass follows the bodies' move and measures each
    point's separation at their new poses (:func:`separation_now`); the solve pass follows a
    pass that did (the last substep's relax, or :func:`prepare_soft` for the first) with only
    velocities changed in between, so it reads the separation stored then: the same number,
    measured once instead of twice."""
    ctx = context[0]
    inv_h = ctx["substeps"] / ctx["dt"]
    t = ctx["sag_recovery_time"]
    recovery = 1.0 / (inv_h * t) if t > 0.0 else 0.0  # h / T
    push = (ctx["max_push_speed"], ctx["deep_overlap"], recovery)
    if use_bias:  # the visit compiled for each pass, its flag a constant (the hot loop)
        for q in range(order.shape[0]):
            c = contacts[order[q]]
            solve_soft_contact(c, (bodies[c["a"]], bodies[c["b"]]), inv_h, True, push)
    else:
        for q in range(order.shape[0]):
            c = contacts[order[q]]
            solve_soft_contact(c, (bodies[c["a"]], bodies[c["b"]]), inv_h, False, push)
