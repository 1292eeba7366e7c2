"""Numerical integration of linear and angular motion (slides, "Numerical Integration").

Each integrator turns the state (p, v, phi, omega) and an acceleration function into the
*increments* of one step, for free motion (no contacts or joints):

    dp, dv, dphi, domega

The world applies the increments, letting contact and joint impulses add to the velocity in
between (see ``docs/architecture.md``), so in free flight a body follows its integrator exactly.

``accel(p, v, phi, omega) -> (a, alpha)`` returns linear (n, 2) and angular (n,) accelerations for
all bodies at the given state; integrators that look ahead (Verlet, RK4) call it more than once.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from sandbox.forces import accumulate_forces
from sandbox.jit import njit
from sandbox.orientation import turn_body
from sandbox.records import DYNAMIC, MOTION, SPRING, STATIC

Accel = Callable[[np.ndarray, np.ndarray, np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]]
Increments = tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]

NAMES = ("explicit_euler", "semi_implicit_euler", "verlet", "rk4", "analytic")
ORDER = {"explicit_euler": 1, "semi_implicit_euler": 1, "verlet": 2, "rk4": 4}


def explicit_euler(p, v, phi, w, accel: Accel, dt: float) -> Increments:
    """The slides' first-order step: p' = p + v dt, v' = v + a dt (both from the old state)."""
    a, alpha = accel(p, v, phi, w)
    return v * dt, a * dt, w * dt, alpha * dt


def semi_implicit_euler(p, v, phi, w, accel: Accel, dt: float) -> Increments:
    """Symplectic Euler: v' = v + a dt first, then p' = p + v' dt (what pymunk and Box2D use)."""
    a, alpha = accel(p, v, phi, w)
    dv, dw = a * dt, alpha * dt
    return (v + dv) * dt, dv, (w + dw) * dt, dw


def verlet(p, v, phi, w, accel: Accel, dt: float) -> Increments:
    """Velocity Verlet: p' = p + v dt + a dt^2 / 2, v' = v + (a + a') dt / 2, a' = a(p', v*)."""
    a, alpha = accel(p, v, phi, w)
    dp = v * dt + 0.5 * a * dt * dt
    dphi = w * dt + 0.5 * alpha * dt * dt
    # the velocity at the new position is not known yet: predict it with Euler for a(p', v)
    a1, alpha1 = accel(p + dp, v + a * dt, phi + dphi, w + alpha * dt)
    return dp, 0.5 * (a + a1) * dt, dphi, 0.5 * (alpha + alpha1) * dt


def rk4(p, v, phi, w, accel: Accel, dt: float) -> Increments:
    """Classical fourth-order Runge-Kutta on the first-order system (p, v)' = (v, a(p, v))."""
    a1, b1 = accel(p, v, phi, w)
    p2, v2, f2, w2 = p + 0.5 * dt * v, v + 0.5 * dt * a1, phi + 0.5 * dt * w, w + 0.5 * dt * b1
    a2, b2 = accel(p2, v2, f2, w2)
    p3, v3, f3, w3 = p + 0.5 * dt * v2, v + 0.5 * dt * a2, phi + 0.5 * dt * w2, w + 0.5 * dt * b2
    a3, b3 = accel(p3, v3, f3, w3)
    p4, v4, f4, w4 = p + dt * v3, v + dt * a3, phi + dt * w3, w + dt * b3
    a4, b4 = accel(p4, v4, f4, w4)
    dp = dt / 6.0 * (v + 2.0 * v2 + 2.0 * v3 + v4)
    dv = dt / 6.0 * (a1 + 2.0 * a2 + 2.0 * a3 + a4)
    dphi = dt / 6.0 * (w + 2.0 * w2 + 2.0 * w3 + w4)
    dw = dt / 6.0 * (b1 + 2.0 * b2 + 2.0 * b3 + b4)
    return dp, dv, dphi, dw


INTEGRATORS: dict[str, Callable[..., Increments]] = {
    "explicit_euler": explicit_euler,
    "semi_implicit_euler": semi_implicit_euler,
    "verlet": verlet,
    "rk4": rk4,
}


def integrate(
    name: str,
    p: np.ndarray,
    v: np.ndarray,
    phi: np.ndarray,
    w: np.ndarray,
    accel: Accel,
    dt: float,
    steps: int = 1,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Advance a free state ``steps`` times with integrator ``name``; returns (p, v, phi, omega).

    A small stand-alone driver for lessons and tests (the world has its own loop).
    """
    step = INTEGRATORS[name]
    p, v = np.array(p, dtype=float), np.array(v, dtype=float)
    phi, w = np.array(phi, dtype=float), np.array(w, dtype=float)
    for _ in range(steps):
        dp, dv, dphi, dw = step(p, v, phi, w, accel, dt)
        p, v, phi, w = p + dp, v + dv, phi + dphi, w + dw
    return p, v, phi, w


def constant_acceleration(a: np.ndarray, alpha: np.ndarray | float = 0.0) -> Accel:
    """An ``accel`` function returning the same (a, alpha) everywhere (e.g. gravity)."""
    a = np.asarray(a, dtype=float)

    def accel(p, v, phi, w):
        return np.broadcast_to(a, np.shape(p)), np.broadcast_to(alpha, np.shape(w))

    return accel


# --- the world's integration stages (compiled, over the body records) --------------------------
# The same formulas as above, for every body at once. The velocity stage applies the
# integrator's velocity increment and remembers its free-motion move; contact and joint impulses
# then change the velocity, and the position stage moves each body by the free move plus what
# the impulses changed: p += dp + (v - v_free) dt (so a body in free flight follows its
# integrator exactly, e.g. the slides' explicit Euler table).

EXPLICIT_EULER, SEMI_IMPLICIT_EULER, VERLET, RK4, ANALYTIC = range(5)
CODES = {name: code for code, name in enumerate(NAMES)}


@njit
def accelerations(model, gravity, state, out) -> None:
    """The time derivative of ``state`` (MOTION records) into ``out``: (v, a, w, alpha) with
    a = g + F / m and alpha = tau / I for dynamic bodies (zero for the others), F and tau every
    force at that state (:func:`sandbox.forces.accumulate_forces`). ``model``: the world's
    (bodies, shapes, vertices, joints, generators) records."""
    bodies, shapes, vertices, joints, generators = model
    accumulate_forces(bodies, shapes, vertices, joints, generators, state, gravity, out)
    for i in range(bodies.shape[0]):
        b, d = bodies[i], out[i]
        d["p"][0], d["p"][1], d["phi"] = state[i]["v"][0], state[i]["v"][1], state[i]["w"]
        if b["kind"] == DYNAMIC:
            d["v"][0] = gravity[0] + d["v"][0] * b["inv_mass"]
            d["v"][1] = gravity[1] + d["v"][1] * b["inv_mass"]
            d["w"] = d["w"] * b["inv_moment"]
        else:
            d["v"][0] = d["v"][1] = d["w"] = 0.0


@njit
def advanced(y, d, h: float, out) -> None:
    """out = y + h d, field by field (a state moved along a derivative for a time h)."""
    for i in range(y.shape[0]):
        for k in range(2):
            out[i]["p"][k] = y[i]["p"][k] + h * d[i]["p"][k]
            out[i]["v"][k] = y[i]["v"][k] + h * d[i]["v"][k]
        out[i]["phi"] = y[i]["phi"] + h * d[i]["phi"]
        out[i]["w"] = y[i]["w"] + h * d[i]["w"]


@njit
def look_ahead(model, gravity, start, y1, out) -> None:
    """The time derivative where RK4 looks, at y + h d, into ``out``; ``start`` = (y, d, h):
    the state y1 = y + h d (:func:`advanced`), then :func:`accelerations` there."""
    y, d, h = start
    advanced(y, d, h, y1)
    accelerations(model, gravity, y1, out)


# the rows of the work arrays of :func:`free_increments` (one MOTION record per body in each),
# kept by the world from step to step (:func:`work_arrays`): the state y the step starts from,
# the derivatives k1 ... k4 where the method looks, the state y1 it looks at, the increments
STATE, K1, K2, K3, K4, AHEAD, INCREMENTS = range(7)


def work_arrays(n: int) -> np.ndarray:
    """The work arrays of :func:`free_increments` for ``n`` bodies: (7, n) MOTION records."""
    return np.zeros((INCREMENTS + 1, n), dtype=MOTION)


@njit
def free_increments(model, gravity, method: int, dt: float, work) -> None:
    """The integrator's increments of one step of free motion for every body, into
    ``work[INCREMENTS]`` (MOTION records holding dp, dv, dphi, dw), with every force evaluated
    where the method looks (the slides' formulas, as :func:`explicit_euler` ... :func:`rk4`
    above), for a world where some force depends on the state (without, every method takes
    :func:`integrate_constant`); ``work``: :func:`work_arrays` (nothing is allocated)."""
    bodies = model[0]
    n = bodies.shape[0]
    y, k1, k2, k3, k4 = work[STATE], work[K1], work[K2], work[K3], work[K4]
    y1, inc = work[AHEAD], work[INCREMENTS]
    for i in range(n):
        b = bodies[i]
        y[i]["p"][0], y[i]["p"][1], y[i]["phi"] = b["com"][0], b["com"][1], b["angle"]
        y[i]["v"][0], y[i]["v"][1], y[i]["w"] = b["vel"][0], b["vel"][1], b["omega"]
    accelerations(model, gravity, y, k1)
    if method == EXPLICIT_EULER:  # p' = p + v dt, v' = v + a dt, both from the old state
        for i in range(n):
            for k in range(2):
                inc[i]["p"][k] = k1[i]["p"][k] * dt
                inc[i]["v"][k] = k1[i]["v"][k] * dt
            inc[i]["phi"] = k1[i]["phi"] * dt
            inc[i]["w"] = k1[i]["w"] * dt
        return
    if method == SEMI_IMPLICIT_EULER:  # v' = v + a dt first, then p' = p + v' dt
        for i in range(n):
            for k in range(2):
                inc[i]["v"][k] = k1[i]["v"][k] * dt
                inc[i]["p"][k] = (y[i]["v"][k] + inc[i]["v"][k]) * dt
            inc[i]["w"] = k1[i]["w"] * dt
            inc[i]["phi"] = (y[i]["w"] + inc[i]["w"]) * dt
        return
    if method == VERLET:  # p' = p + v dt + a dt^2/2, v' = v + (a + a') dt / 2
        for i in range(n):  # p' (the new position), v + a dt (Euler's guess of v')
            for k in range(2):
                y1[i]["p"][k] = y[i]["p"][k] + dt * k1[i]["p"][k] + 0.5 * k1[i]["v"][k] * dt * dt
                y1[i]["v"][k] = y[i]["v"][k] + dt * k1[i]["v"][k]
            y1[i]["phi"] = y[i]["phi"] + dt * k1[i]["phi"] + 0.5 * k1[i]["w"] * dt * dt
            y1[i]["w"] = y[i]["w"] + dt * k1[i]["w"]
        accelerations(model, gravity, y1, k2)  # a' = a(p', v + a dt)
        for i in range(n):
            for k in range(2):
                inc[i]["p"][k] = y1[i]["p"][k] - y[i]["p"][k]
                inc[i]["v"][k] = 0.5 * (k1[i]["v"][k] + k2[i]["v"][k]) * dt
            inc[i]["phi"] = y1[i]["phi"] - y[i]["phi"]
            inc[i]["w"] = 0.5 * (k1[i]["w"] + k2[i]["w"]) * dt
        return
    # RK4: k1 = f(y), k2 = f(y + dt/2 k1), k3 = f(y + dt/2 k2), k4 = f(y + dt k3)
    look_ahead(model, gravity, (y, k1, 0.5 * dt), y1, k2)
    look_ahead(model, gravity, (y, k2, 0.5 * dt), y1, k3)
    look_ahead(model, gravity, (y, k3, dt), y1, k4)
    for i in range(n):  # y' - y = dt/6 (k1 + 2 k2 + 2 k3 + k4)
        for k in range(2):
            inc[i]["p"][k] = (
                dt
                / 6.0
                * (k1[i]["p"][k] + 2.0 * k2[i]["p"][k] + 2.0 * k3[i]["p"][k] + k4[i]["p"][k])
            )
            inc[i]["v"][k] = (
                dt
                / 6.0
                * (k1[i]["v"][k] + 2.0 * k2[i]["v"][k] + 2.0 * k3[i]["v"][k] + k4[i]["v"][k])
            )
        inc[i]["phi"] = (
            dt / 6.0 * (k1[i]["phi"] + 2.0 * k2[i]["phi"] + 2.0 * k3[i]["phi"] + k4[i]["phi"])
        )
        inc[i]["w"] = dt / 6.0 * (k1[i]["w"] + 2.0 * k2[i]["w"] + 2.0 * k3[i]["w"] + k4[i]["w"])


@njit
def has_fields(joints, generators) -> bool:
    """Whether any force depends on the state (a generator or a spring)."""
    if generators.shape[0] > 0:
        return True
    for k in range(joints.shape[0]):
        if joints[k]["kind"] == SPRING:
            return True
    return False


@njit(inline="always")
def constant_increments(method: int, v: float, a: float, dt: float) -> tuple[float, float]:
    """(dx, dv) of one coordinate over a step under a constant acceleration ``a``: the slides'
    formulas of :func:`explicit_euler` ... :func:`rk4` above, with a(p, v) = a wherever the
    method looks (RK4: k2 and k3 look at v + a dt / 2, k4 at v + a dt)."""
    if method == SEMI_IMPLICIT_EULER:  # the default first
        dv = a * dt
        return (v + dv) * dt, dv
    if method == EXPLICIT_EULER:
        return v * dt, a * dt
    if method == VERLET:
        return v * dt + 0.5 * a * dt * dt, 0.5 * (a + a) * dt
    v2, v3, v4 = v + 0.5 * dt * a, v + 0.5 * dt * a, v + dt * a
    return dt / 6.0 * (v + 2.0 * v2 + 2.0 * v3 + v4), dt / 6.0 * (a + 2.0 * a + 2.0 * a + a)


@njit(inline="always")
def constant_velocity(b, gravity, dt: float, method: int) -> None:
    """One body's step under its constant acceleration a = g + F / m, alpha = tau / I
    (:func:`constant_increments`): v' = v + dv, and the free move dx."""
    for k in range(2):
        v, a = b["vel"][k], gravity[k] + b["force"][k] * b["inv_mass"]
        dx, dv = constant_increments(method, v, a, dt)
        b["vel"][k], b["free_move"][k] = v + dv, dx
    w, alpha = b["omega"], b["torque"] * b["inv_moment"]
    dphi, dw = constant_increments(method, w, alpha, dt)
    b["omega"], b["free_turn"] = w + dw, dphi


@njit(python=True)
def gather_forces(bodies) -> None:
    """Add each body's constant force and torque to what was applied for this step, and keep
    the total as ``applied_force``, ``applied_torque`` (what the step applies besides gravity,
    force generators and contacts; cleared again by :func:`clear_forces`)."""
    for i in range(bodies.shape[0]):
        b = bodies[i]
        for k in range(2):
            b["force"][k] += b["const_force"][k]
            b["applied_force"][k] = b["force"][k]
        b["torque"] += b["const_torque"]
        b["applied_torque"] = b["torque"]


@njit
def clear_forces(bodies) -> None:
    """Empty the force and torque accumulators after the step."""
    for i in range(bodies.shape[0]):
        b = bodies[i]
        b["force"][0] = b["force"][1] = b["torque"] = 0.0


@njit
def integrate_constant(bodies, context, dt: float) -> None:
    """The velocity stage when no force depends on the state: the acceleration is the same
    wherever a method looks, so every method is worked out body by body in one pass
    (:func:`constant_velocity`), without the work arrays (one-call steps of such a world do
    not compile the force fields)."""
    ctx = context[0]
    gravity, method = ctx["gravity"], ctx["integrator"]
    for i in range(bodies.shape[0]):
        b = bodies[i]
        if b["kind"] == DYNAMIC:
            constant_velocity(b, gravity, dt, method)
        else:
            still_or_kinematic(b, dt)
        b["free_vel"][0], b["free_vel"][1], b["free_omega"] = b["vel"][0], b["vel"][1], b["omega"]


@njit
def still_or_kinematic(b, dt: float) -> None:
    """A body that forces do not move: a kinematic one moves at its own velocity, a static one
    not at all."""
    moving = b["kind"] != STATIC
    for k in range(2):
        b["free_move"][k] = b["vel"][k] * dt if moving else 0.0
    b["free_turn"] = b["omega"] * dt if moving else 0.0


@njit(python=True)
def integrate_velocities(model, context, dt: float, work) -> None:
    """The velocity stage over a time ``dt`` (the step, or a substep of it): each dynamic
    body's velocity gets the integrator's increment, every force evaluated where the method
    looks (:func:`free_increments`, in the :func:`work_arrays` ``work``); its free-motion move
    is remembered for :func:`plan_motion`. Without state-dependent forces every method takes
    :func:`integrate_constant`: the world then passes ``work=None`` (it keeps work arrays only
    when :func:`has_fields`), and a compiled step leaves the passes over the work arrays and the
    force fields out (numba drops the branch)."""
    ctx, bodies = context[0], model[0]
    if work is None:
        integrate_constant(bodies, context, dt)
        return
    free_increments(model, ctx["gravity"], ctx["integrator"], dt, work)
    inc = work[INCREMENTS]
    for i in range(bodies.shape[0]):
        b = bodies[i]
        if b["kind"] == DYNAMIC:
            for k in range(2):
                b["vel"][k] += inc[i]["v"][k]
                b["free_move"][k] = inc[i]["p"][k]
            b["omega"] += inc[i]["w"]
            b["free_turn"] = inc[i]["phi"]
        else:
            still_or_kinematic(b, dt)
        b["free_vel"][0], b["free_vel"][1], b["free_omega"] = b["vel"][0], b["vel"][1], b["omega"]


@njit(python=True)
def plan_motion(bodies, dt: float) -> None:
    """Each body's move this step: the free move plus what the impulses changed,
    dp = dp_free + (v - v_free) dt (and likewise for the turn)."""
    for i in range(bodies.shape[0]):
        b = bodies[i]
        if b["kind"] == STATIC:
            b["motion"][0] = b["motion"][1] = b["motion_turn"] = 0.0
            continue
        for k in range(2):
            b["motion"][k] = b["free_move"][k] + (b["vel"][k] - b["free_vel"][k]) * dt
        b["motion_turn"] = b["free_turn"] + (b["omega"] - b["free_omega"]) * dt


@njit(python=True)
def move_bodies(bodies, rot, context) -> None:
    """Apply each body's planned move and turn (orientation in the world's representation)."""
    ctx = context[0]
    for i in range(bodies.shape[0]):
        b = bodies[i]
        if b["kind"] != STATIC:
            for k in range(2):
                b["com"][k] += b["motion"][k]
                b["delta_position"][k] += b["motion"][k]
            if b["motion_turn"] != 0.0 or ctx["renormalise"]:
                turn_body(bodies, rot, i, ctx["orientation"], b["motion_turn"], ctx["renormalise"])
