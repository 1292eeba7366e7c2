"""The collision equation as small compiled functions (slides, "Collision Response" to
"Collision Equation"), and the contact kernels the solvers share.

Conventions: the normal n points from body 1 (``a``) to body 2 (``b``); the tangent is
t = n x 1 = (n_y, -n_x); r1, r2 run from each centre of mass to the contact point; the relative
velocity is body 2's contact point seen from body 1's, so v_r . n < 0 means approaching.

Per contact point the solvers keep, as box2d-lite and Box2D do:

- ``kn``, ``kt``: the effective masses 1 / k along the normal and the tangent;
- ``bias``: the normal velocity the constraint asks for, v_r . n >= bias (m/s): the gap
  closed in this step for speculative contacts (depth < 0), else an optional Baumgarte push;
- ``vn0``: the approach velocity v_r . n at the start of the step, before the iterations and
  before this step's gravity and forces were added (as Box2D measures it), for restitution:
  a bounce reflects the speed the bodies arrived with, not gravity's pull during the step;
- ``dvn``: what this step's free motion (gravity, forces) added to v_r . n before the solve;
- ``pn``, ``pt``: the impulses applied (accumulated), ``pmax`` the largest normal impulse seen;
- ``rebound`` (per manifold): how much closer the bodies should end the step after a bounce
  that happened before they touched (see :func:`restitution`).

Everything here works on whole arrays, so one call covers every contact of the world.
"""

from __future__ import annotations

import numpy as np

from sandbox.jit import njit


# --- the collision equation, one formula per function --------------------------------------
@njit
def cross(ax: float, ay: float, bx: float, by: float) -> float:
    """z-component of the 2D cross product a x b."""
    return ax * by - ay * bx


@njit
def point_velocity(vx, vy, w, rx, ry):
    """Velocity of a body's material point at r from its centre of mass: v + w x r (m/s).

    slides, "Collision Effects": v_contact = v_body + r x w. In 2D w x r = (-w r_y, w r_x);
    the slide's r x w is the same vector with the opposite sign, so we write w x r.
    """
    return vx - w * ry, vy + w * rx


@njit
def relative_velocity(v1x, v1y, w1, r1x, r1y, v2x, v2y, w2, r2x, r2y):
    """v_r = (v2 + w2 x r2) - (v1 + w1 x r1) (slides, "Collision Effects")."""
    ax, ay = point_velocity(v1x, v1y, w1, r1x, r1y)
    bx, by = point_velocity(v2x, v2y, w2, r2x, r2y)
    return bx - ax, by - ay


@njit
def effective_mass(im1, ii1, im2, ii2, r1x, r1y, r2x, r2y, nx, ny) -> float:
    """k = 1/m1 + 1/m2 + (r1 x n)^2 / I1 + (r2 x n)^2 / I2 (slides, "Collision Equation",
    step 1 denominator: in 2D ((I^-1 (r x n)) x r) . n = (r x n)^2 / I)."""
    rn1 = cross(r1x, r1y, nx, ny)
    rn2 = cross(r2x, r2y, nx, ny)
    return im1 + im2 + ii1 * rn1 * rn1 + ii2 * rn2 * rn2


@njit
def collision_impulse(e: float, vn: float, k: float) -> float:
    """j = -(1 + e) v_r . n / k (slides, "Collision Equation", step 1)."""
    return -(1.0 + e) * vn / k


@njit
def receive(vx, vy, w, im, ii, rx, ry, px, py):
    """A body's velocities after an impulse P at r: v + P / m, w + (r x P) / I (steps 3a, 3b).

    Body 2 receives +P = +j n and body 1 receives -P. (The slide's step 2 gives j1 = +j n to
    body 1; with n pointing from body 1 to body 2 that pushes body 1 *into* body 2.)
    """
    return vx + im * px, vy + im * py, w + ii * cross(rx, ry, px, py)


# --- kernels over all contact points ---------------------------------------------------------
class Constraints:
    """Per-point solver data for ``k`` manifolds (2 slots each; see the module docstring).

    ``la``, ``lb``: the contact point in each body's frame (about the centre of mass), and
    ``sep0`` = -depth: together they give the separation again after the bodies moved
    (used by :mod:`sandbox.penetration`).
    """

    def __init__(self, k: int) -> None:
        self.r1 = np.zeros((k, 2, 2))
        self.r2 = np.zeros((k, 2, 2))
        self.la = np.zeros((k, 2, 2))
        self.lb = np.zeros((k, 2, 2))
        self.kn = np.zeros((k, 2))
        self.kt = np.zeros((k, 2))
        self.kblock = np.zeros((k, 4))
        self.bias = np.zeros((k, 2))
        self.vn0 = np.zeros((k, 2))
        self.dvn = np.zeros((k, 2))
        self.sep0 = np.zeros((k, 2))
        self.pmax = np.zeros((k, 2))
        self.rebound = np.zeros(k)


@njit
def prepare(
    a, b, normal, count, point, depth, com, cs, vel, omega, vel0, omega0, inv_mass, inv_moment,
    inv_dt, beta, slop, r1, r2, la, lb, kn, kt, kblock, bias, vn0, dvn, sep0,
):  # fmt: skip
    """Lever arms, effective masses, velocity targets and approach velocities of every point.

    vn0: v_r . n for the velocities at the start of the step (``vel0``, ``omega0``, before this
    step's gravity and forces); dvn: v_r . n now (``vel``, ``omega``) minus vn0.

    bias: depth < 0 (a speculative contact, a gap of -depth): the bodies may still approach
    by the gap in this step, v_r . n >= depth / dt; depth > 0: beta / dt (depth - slop), the
    Baumgarte push (beta = 0 leaves the overlap to the position pass).
    """
    for i in range(len(a)):
        ia, ib = a[i], b[i]
        nx, ny = normal[i, 0], normal[i, 1]
        im1, im2, ii1, ii2 = inv_mass[ia], inv_mass[ib], inv_moment[ia], inv_moment[ib]
        c1, s1, c2, s2 = cs[ia, 0], cs[ia, 1], cs[ib, 0], cs[ib, 1]
        for j in range(count[i]):
            r1x, r1y = point[i, j, 0] - com[ia, 0], point[i, j, 1] - com[ia, 1]
            r2x, r2y = point[i, j, 0] - com[ib, 0], point[i, j, 1] - com[ib, 1]
            r1[i, j, 0], r1[i, j, 1], r2[i, j, 0], r2[i, j, 1] = r1x, r1y, r2x, r2y
            la[i, j, 0], la[i, j, 1] = c1 * r1x + s1 * r1y, -s1 * r1x + c1 * r1y  # R1^T r1
            lb[i, j, 0], lb[i, j, 1] = c2 * r2x + s2 * r2y, -s2 * r2x + c2 * r2y  # R2^T r2
            k = effective_mass(im1, ii1, im2, ii2, r1x, r1y, r2x, r2y, nx, ny)
            kn[i, j] = 1.0 / k if k > 0.0 else 0.0
            k = effective_mass(im1, ii1, im2, ii2, r1x, r1y, r2x, r2y, ny, -nx)
            kt[i, j] = 1.0 / k if k > 0.0 else 0.0
            vx, vy = relative_velocity(
                vel0[ia, 0], vel0[ia, 1], omega0[ia], r1x, r1y,
                vel0[ib, 0], vel0[ib, 1], omega0[ib], r2x, r2y,
            )  # fmt: skip
            vn0[i, j] = vx * nx + vy * ny
            vx, vy = relative_velocity(
                vel[ia, 0], vel[ia, 1], omega[ia], r1x, r1y,
                vel[ib, 0], vel[ib, 1], omega[ib], r2x, r2y,
            )  # fmt: skip
            dvn[i, j] = vx * nx + vy * ny - vn0[i, j]
            d = depth[i, j]
            sep0[i, j] = -d
            bias[i, j] = d * inv_dt if d < 0.0 else beta * inv_dt * max(d - slop, 0.0)
        kblock[i, 3] = 0.0
        if count[i] == 2:  # the 2x2 matrix K of the block solver, if well conditioned
            a1 = cross(r1[i, 0, 0], r1[i, 0, 1], nx, ny)  # r1 x n at point 0
            a2 = cross(r1[i, 1, 0], r1[i, 1, 1], nx, ny)  # r1 x n at point 1
            b1 = cross(r2[i, 0, 0], r2[i, 0, 1], nx, ny)
            b2 = cross(r2[i, 1, 0], r2[i, 1, 1], nx, ny)
            k11, k22 = 1.0 / kn[i, 0], 1.0 / kn[i, 1]
            k12 = im1 + im2 + ii1 * a1 * a2 + ii2 * b1 * b2
            det = k11 * k22 - k12 * k12
            if k11 * k11 < 1000.0 * det:
                kblock[i, 0], kblock[i, 1], kblock[i, 2], kblock[i, 3] = k11, k12, k22, det


@njit
def warm_start(a, b, normal, count, r1, r2, pn, pt, vel, omega, inv_mass, inv_moment) -> None:
    """Apply last step's accumulated impulses P = pn n + pt t again (box2d-lite PreStep)."""
    v = np.empty(6)
    for i in range(len(a)):
        ia, ib = a[i], b[i]
        nx, ny = normal[i, 0], normal[i, 1]
        mass = (inv_mass[ia], inv_moment[ia], inv_mass[ib], inv_moment[ib])
        load(v, vel, omega, ia, ib)
        for j in range(count[i]):
            px = pn[i, j] * nx + pt[i, j] * ny
            py = pn[i, j] * ny - pt[i, j] * nx
            apply(i, j, px, py, r1, r2, mass, v)
        store(v, vel, omega, ia, ib)


@njit
def load(v, vel, omega, ia, ib) -> None:
    """Copy the two bodies' velocities into the scratch row v = (v1x, v1y, w1, v2x, v2y, w2)."""
    v[0], v[1], v[2] = vel[ia, 0], vel[ia, 1], omega[ia]
    v[3], v[4], v[5] = vel[ib, 0], vel[ib, 1], omega[ib]


@njit
def store(v, vel, omega, ia, ib) -> None:
    """Write the scratch row back to the two bodies."""
    vel[ia, 0], vel[ia, 1], omega[ia] = v[0], v[1], v[2]
    vel[ib, 0], vel[ib, 1], omega[ib] = v[3], v[4], v[5]


@njit
def along(i, j, tx, ty, r1, r2, v) -> float:
    """v_r . t at point j of manifold i, for the velocities in the scratch row v."""
    vx, vy = relative_velocity(
        v[0], v[1], v[2], r1[i, j, 0], r1[i, j, 1], v[3], v[4], v[5], r2[i, j, 0], r2[i, j, 1]
    )
    return vx * tx + vy * ty


@njit
def apply(i, j, px, py, r1, r2, mass, v) -> None:
    """-P to body 1 and +P to body 2 at point j of manifold i (in the scratch row v);
    mass = (1/m1, 1/I1, 1/m2, 1/I2)."""
    im1, ii1, im2, ii2 = mass
    v[0], v[1], v[2] = receive(v[0], v[1], v[2], im1, ii1, r1[i, j, 0], r1[i, j, 1], -px, -py)
    v[3], v[4], v[5] = receive(v[3], v[4], v[5], im2, ii2, r2[i, j, 0], r2[i, j, 1], px, py)


@njit
def restitution(
    a, b, normal, count, rest, r1, r2, kn, vn0, sep0, pn, pmax, rebound,
    vel, omega, inv_mass, inv_moment, threshold,
) -> None:  # fmt: skip
    """Bounce: v_r . n = -e v_r0 . n with the approach velocity v_r0 . n from the start of the
    step, before the iterations and before this step's gravity and forces (``vn0``).

    As Box2D's restitution: only points that approached faster than ``threshold`` (m/s) and
    carried an impulse bounce; slower contacts rest. The total impulse stays >= 0. Measured
    after gravity, the approach speed would be g dt too fast and every bounce would gain height.

    A speculative point (a gap g = sep0 > 0 at the start of the step) bounces here, before it
    touched; had it bounced at its time of impact, the bodies would end the step (1 + e) g
    closer. ``rebound[i]`` records that distance for the position phase
    (:func:`sandbox.penetration.rebound`), so the bounce starts from the surface.
    """
    v = np.empty(6)
    for i in range(len(a)):
        rebound[i] = 0.0
        e = rest[i]
        if e == 0.0:
            continue
        ia, ib = a[i], b[i]
        nx, ny = normal[i, 0], normal[i, 1]
        mass = (inv_mass[ia], inv_moment[ia], inv_mass[ib], inv_moment[ib])
        load(v, vel, omega, ia, ib)
        for j in range(count[i]):
            if vn0[i, j] > -threshold or pmax[i, j] == 0.0:
                continue
            vn = along(i, j, nx, ny, r1, r2, v)
            old = pn[i, j]
            pn[i, j] = max(old - kn[i, j] * (vn + e * vn0[i, j]), 0.0)  # target -e vn0
            dp = pn[i, j] - old
            apply(i, j, dp * nx, dp * ny, r1, r2, mass, v)
            rebound[i] = max(rebound[i], (1.0 + e) * sep0[i, j])
        store(v, vel, omega, ia, ib)


# --- glue the solvers share (Python, once per step) ------------------------------------------
def empty_manifolds(manifolds):
    """``manifolds`` or, when None, an empty set."""
    if manifolds is None:
        from sandbox.contact import Manifolds

        return Manifolds.empty()
    return manifolds


def start_velocities(world, start=None) -> tuple[np.ndarray, np.ndarray]:
    """``start`` = (vel, omega) at the start of the step, before this step's gravity and forces
    were added (what the world's step passes), or, without it, the current velocities."""
    return (world.vel, world.omega) if start is None else start


def build(world, manifolds, dt: float, beta: float = 0.0, start=None) -> Constraints:
    """Prepare every contact point (see :func:`prepare`) and keep the result for this step's
    position phase (``world._solver_cache["constraints"]``). ``beta`` is a Baumgarte velocity
    bias factor; the solvers use 0 and remove overlap on positions (:mod:`sandbox.penetration`)
    instead, so no velocity is added to push bodies apart. ``start``: see
    :func:`start_velocities`."""
    m = manifolds
    cons = Constraints(len(m))
    if len(m):
        vel0, omega0 = start_velocities(world, start)
        prepare(
            m.a, m.b, m.normal, m.count, m.point, m.depth, world.com, world.cs, world.vel,
            world.omega, vel0, omega0, world.inv_mass, world.inv_moment, 1.0 / dt, float(beta),
            float(world.settings.slop), cons.r1, cons.r2, cons.la, cons.lb, cons.kn, cons.kt,
            cons.kblock, cons.bias, cons.vn0, cons.dvn, cons.sep0,
        )  # fmt: skip
    world._solver_cache["constraints"] = (m, cons)
    return cons


def built(world, manifolds) -> Constraints | None:
    """The constraints :func:`build` made for ``manifolds`` in this step, if any."""
    m, cons = world._solver_cache.get("constraints", (None, None))
    return cons if m is manifolds and manifolds is not None else None


def start(world, m, cons, warm: bool) -> None:
    """With ``warm``: last step's impulses of the matching points (:mod:`sandbox.contact_cache`)
    are applied again (warm starting); otherwise the impulses start from zero."""
    from sandbox import contact_cache

    if warm and len(m):
        world.stats["warm_started_points"] = contact_cache.load(world, m)
        warm_start(
            m.a, m.b, m.normal, m.count, cons.r1, cons.r2, m.normal_impulse, m.tangent_impulse,
            world.vel, world.omega, world.inv_mass, world.inv_moment,
        )  # fmt: skip
    else:
        world.stats["warm_started_points"] = 0
        m.normal_impulse[:] = 0.0
        m.tangent_impulse[:] = 0.0


def bounce(world, m, cons) -> None:
    """The restitution pass (see :func:`restitution`)."""
    if len(m):
        restitution(
            m.a, m.b, m.normal, m.count, m.restitution, cons.r1, cons.r2, cons.kn, cons.vn0,
            cons.sep0, m.normal_impulse, cons.pmax, cons.rebound, world.vel, world.omega,
            world.inv_mass, world.inv_moment, float(world.settings.restitution_threshold),
        )  # fmt: skip


def prepare_joints(world, dt: float) -> None:
    """Every joint's ``prepare`` then ``warm_start`` (joints read the settings themselves)."""
    for joint in world.joints:
        joint.prepare(world, dt)
    for joint in world.joints:
        joint.warm_start(world)


def solve_joints(world) -> None:
    """One velocity pass over the joints."""
    for joint in world.joints:
        joint.solve_velocity(world)
