"""Collision within the step: detection (broadphase + narrowphase), response (the solver's
impulses), continuous collision and the penetration fix. The world calls these functions.

Slides, "Retroactive Collision Detection": update motion, then for each overlapping pair fix
penetration and handle the collision. Here the overlaps found at the start of a step are
resolved on velocities before the positions move (as box2d-lite does), which keeps resting
contacts quiet.

Two ways through the same kernels:

- step by step (:func:`detect`, :func:`solve_velocities`, :func:`solve_positions`): Python
  calls each phase, so any solver, broadphase, penetration option, joint or force fits in;
- in one compiled call (:func:`step_euler`, :func:`contact_step`): for the usual world (Euler
  integrators, iterative solver, sweep and prune, option 3 of the penetration fix, no joints)
  the whole step runs as one compiled function over preallocated arrays
  (:class:`sandbox.contact.ContactBuffers`), because each compiled call from Python costs
  microseconds, as much as a small world's whole step. It calls the very kernels the first way
  calls, on the same numbers, so both give bit-identical results (it prepares the contacts
  before adding this step's gravity; the first way prepares them afterwards from a copy of the
  velocities before it).

numba caches each compiled function under its own source file only: after editing a kernel in
one module, functions in other modules that call it (the compiled step calls kernels from a
dozen) may load their old compiled code. Delete the cache files (``__pycache__/*.nbi`` and
``*.nbc`` under ``sandbox/``) after such an edit, or run with ``SANDBOX_JIT=0``.
"""

from __future__ import annotations

import numpy as np

from sandbox import integrators, orientation
from sandbox.body import DYNAMIC
from sandbox.broadphase.aabb import shape_aabbs_into, sort_pairs_into
from sandbox.broadphase.sap import gather, sap_kernel, sweep_axis, update_order
from sandbox.contact import I_COUNT, buffers
from sandbox.geometry_arrays import S_BODY
from sandbox.jit import njit
from sandbox.narrowphase import collide_rows
from sandbox.penetration import position_phase
from sandbox.solvers.iterative import prepare_rows, velocity_phase

# ---- step by step --------------------------------------------------------------------------


def detect(world, margin: float = 0.0):
    """Contact manifolds at the current state (``sandbox.contact.Manifolds``)."""
    from sandbox import narrowphase
    from sandbox.broadphase import find_pairs
    from sandbox.contact import Manifolds

    g = world.geometry()
    if len(g) < 2:
        world.stats.update(pair_tests=0, pairs=0, contacts=0, contact_points=0)
        return Manifolds.empty()
    aabb = np.empty((len(g), 4))
    shape_aabbs_into(g.shape_int, g.shape_float, g.poly, world.com, world.cs, margin, aabb)
    # bodies that cannot be pushed (static and kinematic) never collide with each other
    fixed = world.kind[g.shape_body] != DYNAMIC
    pairs, tests = find_pairs(world.settings.broadphase, aabb, fixed, g.shape_body)
    if world.joints:  # bodies sharing a joint do not collide (as in pymunk's bridge)
        from sandbox.joints import drop_joined

        pairs = drop_joined(world, pairs, g.shape_body)
    arrays = narrowphase.collide_packed(
        np.ascontiguousarray(pairs, dtype=np.int64).reshape(-1, 2),
        g.shape_int,
        g.shape_float,
        g.poly,
        world.com,
        world.cs,
        float(margin),
    )
    manifolds = Manifolds(*arrays)
    world.stats.update(
        pair_tests=int(tests),
        pairs=int(len(pairs)),
        contacts=int(len(manifolds)),
        contact_points=int(np.sum(manifolds.count)) if len(manifolds) else 0,
    )
    return manifolds


def solve_velocities(world, dt: float, start=None):
    """Find contacts and let the world's solver change velocities; returns the manifolds.
    ``start`` = (vel, omega) at the start of the step, before this step's gravity and forces
    were added (copies): the approach velocities restitution reflects (default: the current
    velocities)."""
    has_shapes = len(world.geometry()) >= 2
    manifolds = detect(world, world.settings.contact_margin) if has_shapes else None
    if (manifolds is None or len(manifolds) == 0) and not world.joints:
        world.stats.setdefault("contacts", 0)
        if has_shapes:
            buffers(world).forget()  # nothing in contact: nothing to warm start from next step
        return manifolds
    from sandbox import solvers

    solvers.get(world.settings.solver).solve_velocities(world, manifolds, dt, start)
    return manifolds


def solve_positions(world, manifolds, dt: float) -> None:
    """Remove what is left of the overlap after the positions moved (settings.penetration)."""
    if (manifolds is None or len(manifolds) == 0) and not world.joints:
        return
    from sandbox import solvers

    solvers.get(world.settings.solver).solve_positions(world, manifolds, dt)


def limit_ccd_motion(world, dp: np.ndarray, dphi: np.ndarray) -> None:
    """Conservative advancement: a ``ccd`` body moves only up to its time of impact (in place)."""
    from sandbox.toi import limit_motion

    limit_motion(world, dp, dphi)


# ---- the whole step in one compiled call ----------------------------------------------------


def compiled(world) -> bool:
    """Whether :func:`step_euler` can take the world's Euler step (the settings and contents it
    covers; anything else goes step by step)."""
    s = world.settings
    return (
        not world.joints
        and s.solver == "iterative"
        and s.broadphase == "sap"
        and s.penetration == "impulse"
    )


@njit
def free_step(
    kind, com, vel, omega, rot, cs, force, torque, inv_mass, inv_moment, dphi,
    gx, gy, dt, explicit, orientation_kind, renormalise,
) -> None:  # fmt: skip
    """A step with nothing to collide (fewer than two shapes): the Euler velocities, then the
    positions and orientations (``World._step_euler`` without contacts)."""
    integrators.euler_velocities(kind, vel, omega, force, torque, inv_mass, inv_moment, gx, gy, dt)
    integrators.euler_positions(
        kind, com, vel, omega, force, torque, inv_mass, inv_moment, gx, gy, dt, explicit, dphi
    )
    orientation.integrate_rotations(orientation_kind, rot, dphi, renormalise)
    orientation.cos_sin(orientation_kind, rot, cs)


@njit
def contact_step(
    kind, com, vel, omega, rot, cs, force, torque, inv_mass, inv_moment, dphi,
    shape_int, shape_float, poly,
    aabb, order, sweep_box, sweep_int, state, pair_count, pairs_raw, pairs,
    ints, geoms, solver, old_ints, old_solver, k_old,
    gx, gy, dt, explicit, orientation_kind,
    renormalise, margin, slop, warm, accumulate, iterations, threshold, position_correction,
    baumgarte, position_iterations,
):  # fmt: skip
    """One Euler step of a world with contacts (the phases of ``World._step_euler`` and of the
    iterative solver). Returns ``(pairs, pair_tests, manifolds, points,
    warm-started points)``, or ``(-pairs, ...)`` with nothing changed when the pair buffer is too
    small (grow it and call again).

    ``state[0]``: the axis ``order`` (shape indices) is sorted on, -1 for none; the sweep keeps
    it sorted from step to step.
    """
    m = shape_int.shape[0]
    # 1. broadphase at the current positions (no velocity is read: nothing changes before 3.)
    shape_aabbs_into(shape_int, shape_float, poly, com, cs, margin, aabb)
    axis = sweep_axis(aabb)
    update_order(aabb, axis, order, state[0])
    state[0] = axis
    body = np.empty(m, dtype=np.int64)
    static = np.empty(m, dtype=np.bool_)
    for i in range(m):
        body[i] = shape_int[i, S_BODY]
        static[i] = kind[body[i]] != 0  # cannot be pushed: static or kinematic
    gather(aabb, static, body, order, sweep_box, sweep_int)
    npairs, tests = sap_kernel(sweep_box, sweep_int, axis, pairs_raw)
    if npairs > pairs_raw.shape[0]:
        return -npairs, tests, 0, 0, 0
    sort_pairs_into(pairs_raw, npairs, m, pair_count, pairs)
    # 2. narrowphase at the same positions; the contacts are prepared before this step's gravity
    # and forces are added, so restitution reflects the approach velocities the bodies came with
    # (Box2D's order; the step by step path prepares with a copy of these velocities)
    k = collide_rows(pairs, npairs, shape_int, shape_float, poly, com, cs, margin, ints, geoms)
    if k > 0:
        prepare_rows(
            ints, geoms, solver, k, com, cs, vel, omega, inv_mass, inv_moment, 1.0 / dt, 0.0, slop
        )
    # 3. free-motion velocities
    integrators.euler_velocities(kind, vel, omega, force, torque, inv_mass, inv_moment, gx, gy, dt)
    # 4. contact impulses (collision.solve_velocities, iterative.relax)
    found = 0
    if k > 0:
        found = velocity_phase(
            ints, geoms, solver, k, old_ints, old_solver, k_old, vel, omega, warm, accumulate,
            iterations, threshold,
        )  # fmt: skip
    # 5. positions and orientations
    integrators.euler_positions(
        kind, com, vel, omega, force, torque, inv_mass, inv_moment, gx, gy, dt, explicit, dphi
    )
    orientation.integrate_rotations(orientation_kind, rot, dphi, renormalise)
    orientation.cos_sin(orientation_kind, rot, cs)
    # 6. penetration fix (iterative.solve_positions)
    if position_correction and k > 0:
        position_phase(
            ints, geoms, solver, k, com, rot, cs, dphi, inv_mass, orientation_kind, renormalise,
            baumgarte, slop, position_iterations,
        )  # fmt: skip
    points = 0
    for i in range(k):
        points += ints[i, I_COUNT]
    return npairs, tests, k, points, found


def _settings(cache, s) -> tuple:
    """The settings :func:`contact_step` reads, as the types it was compiled for (a float given
    as an int would compile it again); converted again only when a setting changed."""
    raw = (
        s.renormalise, s.contact_margin, s.slop, s.warm_start, s.accumulate_impulses,
        s.iterations, s.restitution_threshold, s.position_correction, s.baumgarte,
        s.position_iterations,
    )  # fmt: skip
    if raw != cache.settings_raw:
        cache.settings_raw = raw
        cache.settings = (
            bool(s.renormalise), float(s.contact_margin), float(s.slop),
            bool(s.warm_start and s.accumulate_impulses), bool(s.accumulate_impulses),
            int(s.iterations), float(s.restitution_threshold), bool(s.position_correction),
            float(s.baumgarte), int(s.position_iterations),
        )  # fmt: skip
    return cache.settings


def step_euler(world, dt: float, explicit: bool) -> None:
    """``World._step_euler`` in one compiled call (see :func:`compiled` for when it applies):
    :func:`free_step` or :func:`contact_step`; fills ``world.manifolds`` and ``world.stats``."""
    g = world.gravity
    kind = world.orientation_kind
    geometry = world.geometry()
    if len(geometry.shapes) < 2:
        free_step(
            world.kind, world.com, world.vel, world.omega, world.rot, world.cs, world.force,
            world.torque, world.inv_mass, world.inv_moment, world._dphi, g[0], g[1], dt,
            explicit, kind, bool(world.settings.renormalise),
        )  # fmt: skip
        world.manifolds = None
        world.stats.setdefault("contacts", 0)
        return
    cache = world._solver_cache.get("buffers")
    if cache is None or cache.geometry is not geometry:
        cache = buffers(world)
    settings = _settings(cache, world.settings)
    old = cache.now
    cur = cache.begin()
    while True:
        result = contact_step(
            world.kind, world.com, world.vel, world.omega, world.rot, world.cs, world.force,
            world.torque, world.inv_mass, world.inv_moment, world._dphi,
            geometry.shape_int, geometry.shape_float, geometry.poly,
            cache.aabb, cache.order, cache.sweep_box, cache.sweep_int, cache.state,
            cache.pair_count, cache.pairs_raw, cache.pairs,
            cache.ints[cur], cache.geoms[cur], cache.solver[cur], cache.ints[old],
            cache.solver[old], cache.k[old], g[0], g[1], dt, explicit, kind, *settings,
        )  # fmt: skip
        if result[0] >= 0:
            break
        cache.reserve(-result[0])  # nothing moved yet: grow the buffers and run again
    npairs, tests, k, points, found = (int(x) for x in result)  # numpy ints without numba
    cache.commit(cur, k)
    cache.source = None
    world.manifolds = cache.manifolds(cur)
    world.stats.update(
        pair_tests=tests, pairs=npairs, contacts=k, contact_points=points, warm_started_points=found
    )
