"""Where a step's time goes: each phase of this engine's step in microseconds, next to pymunk.

    python benchmarks/profile_step.py [--steps N] [--only NAME ...]

For every benchmark scene (``scenes.py``, the same dicts as ``run.py``) three copies run in
lockstep, alternating blocks of 10 steps so all see the same machine load:

- this engine's world stepping normally (``World.step``: for these scenes the whole step is one
  compiled call, ``sandbox.collision.step_euler``): the step's real cost;
- a second world stepping through the same compiled kernels one phase at a time, each call
  timed: the phases below (bit-identical to the first world, checked at the end);
- pymunk's ``Space.step`` on the same scene.

Phases (microseconds per step, averaged):

- ``broadphase``: shape AABBs, the incremental sort and the sweep, sorting the pairs;
- ``narrowphase``: contact manifolds of the pairs;
- ``warm start``: matching last step's contact points (by shapes and feature id);
- ``prepare``: lever arms, effective masses, targets, and re-applying the warm-start impulses;
- ``velocity iterations``: the solver's sweeps;
- ``restitution``: the bounce pass after the sweeps;
- ``integration``: the Euler velocity and position updates, orientations and their (cos, sin);
- ``position pass``: the penetration fix;
- ``Python glue``: everything else in ``World.step`` (the Python around the compiled call and
  the cost of making that call), i.e. the real step minus the compiled phases.

Each phase's time has the cost of its own compiled call (measured with an empty compiled
function taking the same arguments) taken off, so the phases add up to the compiled work.
"""

from __future__ import annotations

import argparse
import gc
import sys
import time

import numba
import numpy as np
from sandbox.collision import compiled
from sandbox.contact_cache import match_rows
from sandbox.geometry_arrays import S_BODY

import scenes  # benchmarks/scenes.py, beside this file
from sandbox import integrators, orientation
from sandbox.broadphase.aabb import shape_aabbs_into, sort_pairs_into
from sandbox.broadphase.sap import gather, sap_kernel, sweep_axis, update_order
from sandbox.build import build_world
from sandbox.contact import I_COUNT, buffers
from sandbox.jit import njit
from sandbox.narrowphase import collide_rows
from sandbox.penetration import position_phase
from sandbox.pymunk_bridge import PymunkScene
from sandbox.scene import validate_scene
from sandbox.solvers.iterative import prepare_rows, restitution_rows, solve_rows, warm_start_rows

BLOCK = 10
PHASES = (
    "broadphase",
    "narrowphase",
    "warm start",
    "prepare",
    "velocity iterations",
    "restitution",
    "integration",
    "position pass",
)
SCENES = {
    "ballistic": (scenes.ballistic, 3000),
    "rain_100": (lambda: scenes.rain(100), 300),
    "rain_1000": (lambda: scenes.rain(1000), 300),
    "rain_5000": (lambda: scenes.rain(5000), 300),
    "pyramid_20": (lambda: scenes.pyramid(20), 300),
    "pyramid_40": (lambda: scenes.pyramid(40), 300),
}


@njit
def _static_and_body(kind, shape_int, static, body) -> None:
    for i in range(shape_int.shape[0]):
        body[i] = shape_int[i, S_BODY]
        static[i] = kind[body[i]] != 0


@njit
def _broadphase(shape_int, shape_float, poly, com, cs, margin, aabb, order, state, kind, box,
                meta, pairs_raw, pair_count, pairs):  # fmt: skip
    """Phase 1 of ``collision.contact_step`` (its first lines, as one call)."""
    m = shape_int.shape[0]
    shape_aabbs_into(shape_int, shape_float, poly, com, cs, margin, aabb)
    axis = sweep_axis(aabb)
    update_order(aabb, axis, order, state[0])
    state[0] = axis
    body = np.empty(m, dtype=np.int64)
    static = np.empty(m, dtype=np.bool_)
    _static_and_body(kind, shape_int, static, body)
    gather(aabb, static, body, order, box, meta)
    npairs, tests = sap_kernel(box, meta, axis, pairs_raw)
    if npairs <= pairs_raw.shape[0]:
        sort_pairs_into(pairs_raw, npairs, m, pair_count, pairs)
    return npairs, tests


@njit
def _integrate_velocities(kind, vel, omega, force, torque, inv_mass, inv_moment, gx, gy, dt):
    integrators.euler_velocities(kind, vel, omega, force, torque, inv_mass, inv_moment, gx, gy, dt)


@njit
def _integrate_positions(kind, com, vel, omega, force, torque, inv_mass, inv_moment, gx, gy, dt,
                         explicit, dphi, orientation_kind, rot, cs, renormalise):  # fmt: skip
    integrators.euler_positions(
        kind, com, vel, omega, force, torque, inv_mass, inv_moment, gx, gy, dt, explicit, dphi
    )
    orientation.integrate_rotations(orientation_kind, rot, dphi, renormalise)
    orientation.cos_sin(orientation_kind, rot, cs)


def _empty(n_args: int):
    """An empty compiled function of ``n_args`` arguments (to measure the cost of a call)."""
    names = ", ".join(f"a{i}" for i in range(n_args))
    namespace: dict = {}
    exec(f"def f({names}):\n    return 0\n", namespace)  # a fixed, local template
    return numba.njit(namespace["f"])  # not cached: it has no source file


class Timer:
    """Accumulates the time of each phase's compiled call, less the cost of an empty call."""

    def __init__(self) -> None:
        self.total = dict.fromkeys(PHASES, 0.0)
        self._overhead: dict[tuple, float] = {}

    def overhead(self, args: tuple) -> float:
        key = tuple(type(a) for a in args)
        if key not in self._overhead:
            f = _empty(len(args))
            f(*args)
            best = np.inf
            for _ in range(7):
                start = time.perf_counter()
                for _ in range(200):
                    f(*args)
                best = min(best, (time.perf_counter() - start) / 200)
            self._overhead[key] = best
        return self._overhead[key]

    def call(self, phase: str, fn, *args):
        start = time.perf_counter()
        out = fn(*args)
        self.total[phase] += max(time.perf_counter() - start - self.overhead(args), 0.0)
        return out


def phased_step(world, timer: Timer) -> None:
    """``collision.step_euler`` with each compiled phase called (and timed) on its own."""
    s = world.settings
    g = world.gravity
    dt = world.dt
    kind = world.orientation_kind
    explicit = s.integrator == "explicit_euler"
    vel_args = (world.kind, world.vel, world.omega, world.force, world.torque, world.inv_mass,
                world.inv_moment, g[0], g[1], dt)  # fmt: skip
    pos_args = (world.kind, world.com, world.vel, world.omega, world.force, world.torque,
                world.inv_mass, world.inv_moment, g[0], g[1], dt, explicit, world._dphi, kind,
                world.rot, world.cs, bool(s.renormalise))  # fmt: skip
    if len(world.geometry()) < 2:
        timer.call("integration", _integrate_velocities, *vel_args)
        timer.call("integration", _integrate_positions, *pos_args)
        world.time += dt
        world.steps += 1
        return
    cache = buffers(world)
    geo = cache.geometry
    old = cache.now
    cur = cache.begin()
    while True:
        npairs, tests = timer.call(
            "broadphase", _broadphase, geo.shape_int, geo.shape_float, geo.poly, world.com,
            world.cs, float(s.contact_margin), cache.aabb, cache.order, cache.state, world.kind,
            cache.sweep_box, cache.sweep_int, cache.pairs_raw, cache.pair_count, cache.pairs,
        )  # fmt: skip
        if npairs <= cache.capacity:
            break
        cache.reserve(npairs)
    ints, geoms, solver = cache.rows(cur)
    old_ints, _, old_solver = cache.rows(old)
    k = timer.call(
        "narrowphase", collide_rows, cache.pairs, npairs, geo.shape_int, geo.shape_float,
        geo.poly, world.com, world.cs, float(s.contact_margin), ints, geoms,
    )  # fmt: skip
    if k > 0:
        timer.call(
            "prepare", prepare_rows, ints, geoms, solver, k, world.com, world.cs, world.vel,
            world.omega, world.inv_mass, world.inv_moment, 1.0 / dt, 0.0, float(s.slop),
        )  # fmt: skip
    # as the compiled step: contacts are prepared on the step's starting velocities, then gravity
    timer.call("integration", _integrate_velocities, *vel_args)
    if k > 0:
        timer.call("warm start", match_rows, ints, solver, k, old_ints, old_solver, cache.k[old])
        timer.call("prepare", warm_start_rows, ints, solver, k, world.vel, world.omega)
        timer.call("velocity iterations", solve_rows, ints, solver, k, world.vel, world.omega,
                   int(s.iterations), True)  # fmt: skip
        timer.call("restitution", restitution_rows, ints, geoms, solver, k, world.vel,
                   world.omega, float(s.restitution_threshold))  # fmt: skip
    timer.call("integration", _integrate_positions, *pos_args)
    if k > 0:
        timer.call(
            "position pass", position_phase, ints, geoms, solver, k, world.com, world.rot,
            world.cs, world._dphi, world.inv_mass, kind, bool(s.renormalise),
            float(s.baumgarte), float(s.slop), int(s.position_iterations),
        )  # fmt: skip
    cache.commit(cur, k)
    cache.source = None
    world.manifolds = cache.manifolds(cur)
    world.stats["contact_points"] = int(np.sum(ints[:k, I_COUNT]))
    world.stats["pairs"] = int(npairs)
    world.time += dt
    world.steps += 1


def profile(name: str, steps: int) -> dict:
    """Per-phase microseconds per step, the real step and pymunk's, for one scene."""
    spec = validate_scene(SCENES[name][0]())
    world = build_world(spec)
    phased = build_world(spec)
    if not compiled(world) or world.settings.integrator not in (
        "semi_implicit_euler",
        "explicit_euler",
    ):
        raise SystemExit(f"{name}: not a world the compiled step covers")
    space = PymunkScene.from_scene(spec).space
    dt = spec["dt"]
    timer = Timer()
    mine = theirs = 0.0
    done = 0
    gc.collect()
    while done < steps:
        n = min(BLOCK, steps - done)
        start = time.perf_counter()
        for _ in range(n):
            world.step()
        middle = time.perf_counter()
        for _ in range(n):
            space.step(dt)
        end = time.perf_counter()
        for _ in range(n):
            phased_step(phased, timer)
        mine += middle - start
        theirs += end - middle
        done += n
    same = np.array_equal(world.com, phased.com) and np.array_equal(world.vel, phased.vel)
    row = {p: 1e6 * t / steps for p, t in timer.total.items()}
    row["compiled phases"] = sum(row[p] for p in PHASES)
    row["step"] = 1e6 * mine / steps
    row["Python glue"] = row["step"] - row["compiled phases"]
    row["pymunk step"] = 1e6 * theirs / steps
    row["ratio"] = mine / theirs
    row["identical"] = same
    row["contact points"] = world.stats.get("contact_points", 0)
    return row


def warm_up() -> None:
    """Compile (or load from the cache) every kernel the scenes use."""
    for spec, steps in ((scenes.ballistic(), 3), (scenes.rain(30), 90), (scenes.pyramid(4), 20)):
        spec = validate_scene(spec)
        world, phased = build_world(spec), build_world(spec)
        timer = Timer()
        for _ in range(steps):
            world.step()
            phased_step(phased, timer)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description="Per-phase cost of a step, next to pymunk.")
    parser.add_argument("--steps", type=int, default=None, help="steps per scene")
    parser.add_argument("--only", nargs="*", metavar="NAME", choices=list(SCENES))
    args = parser.parse_args(argv)
    print("warming up (compiling) ...", flush=True)
    warm_up()
    names = args.only or list(SCENES)
    rows = {}
    for name in names:
        steps = args.steps or SCENES[name][1]
        rows[name] = profile(name, steps)
        print(f"{name}: {rows[name]['step']:.1f} us vs pymunk {rows[name]['pymunk step']:.1f} us",
              flush=True)  # fmt: skip
    keys = (*PHASES, "compiled phases", "Python glue", "step", "pymunk step", "ratio")
    width = max(len(k) for k in keys) + 2
    print()
    print("microseconds per step".ljust(width) + "".join(f"{n:>12}" for n in names))
    for key in keys:
        cells = "".join(
            f"{rows[n][key]:>12.3f}" if key == "ratio" else f"{rows[n][key]:>12.1f}" for n in names
        )
        print(key.ljust(width) + cells)
    print(
        "contact points".ljust(width) + "".join(f"{rows[n]['contact points']:>12}" for n in names)
    )
    if not all(rows[n]["identical"] for n in names):
        print("warning: the phase-by-phase world left the normal one", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
