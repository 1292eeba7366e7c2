"""The narrowphase on two threads against one: does the second core pay? (It did not, here.)

    python benchmarks/bench_threads.py [--rounds R] [--steps N] [--cases a,b] [--stages]
                                       [--kernel] [--compile]

The two-thread narrowphase measured here lives in this file, not in the engine:
:func:`collide_two_threads` works out pair q's manifold into contact record q in a numba
``prange`` loop (``parallel=True``), then one thread moves the manifolds found to the front in
pair order, so the contact list, and every step after it, is bit-identical to the one-thread
:func:`sandbox.narrowphase.collide_into` (``tests/test_threads.py`` checks it with ``==``).

- default: for pyramids of base 20 and 40 and rain of 1,000 and 5,000 circles (``scenes.py``,
  after ``--settle`` steps, when the rain lies in the box), two worlds from the same dict step in
  alternating blocks, one with each narrowphase; the table gives the median over the blocks of
  the wall time per step (``time.perf_counter``) and the process's CPU time per step
  (``time.process_time``: every thread, unlike ``run.py``'s thread time), and checks that the
  bodies came out bit-identical. Both worlds take the staged path (``world.timer``), which calls
  the narrowphase from Python through ``sandbox.staged_step.collide_into``: the script swaps
  that name.
- ``--stages``: each stage's share of a one-thread step (``sandbox.staged_step.StageTimer``).
- ``--kernel``: the narrowphase alone on a settled scene's pairs, one against two threads.
- ``--compile``: in a fresh process with an empty compile cache, the time to compile the engine
  and step a small pyramid once, then the extra time of the two-thread kernel's first call.

Found (2 cores shared with other users' processes, numba 0.68.1; OpenMP threading layer unless
said; medians; 2t/1t is the two-thread step's wall time over the one-thread step's):

- The narrowphase ("collide") is 21-23 % of a staged step on the pyramids (78 of 340 us at base
  20, 312 of 1,518 us at base 40) and 10-14 % on the rain (88 of 885 us at 1,000, 846 of 5,890
  us at 5,000): two threads can save at most half of that.
- The narrowphase alone, called back to back: up to 2.0x faster on two threads for boxes
  (polygon pairs are costly) and 1.0-1.3x for circles when the second core is free; 0.5-0.9x
  as soon as another process uses it, and always 0.45-0.86x with the ``workqueue`` layer.
- Whole steps, 2t/1t in five OpenMP runs: pyramid_20 0.97-1.03, pyramid_40 0.96-1.23,
  rain_1000 0.96-1.16, rain_5000 1.10-1.17; but 2.4-5x (6 of the 17 figures) while other
  processes were busy (the step waits for a worker the OS has not scheduled yet: 8 ms where one
  thread takes 1.7). With ``OMP_WAIT_POLICY=passive`` 0.99-1.14, with ``workqueue``
  0.98-1.25. OpenMP's workers also spin on after each region: on pyramid_40 the
  process's CPU time per step was 2.9-3.7 ms with two threads against 2.2-2.5 ms with one.
- Compiling: the parallel kernel adds about 3 s to an empty cache (the engine with its first
  step: 32 s, same run). Built into the engine's step (a ``threads`` setting, tried in commit
  cba776a and taken out again), it made a cold ``sandbox simulate scenes/pyramid.json --steps
  120`` 2.7-4.6 s longer even with one thread: the compiled step contains the parallel kernel.
- Bit-identical every time (bodies ``==``), as designed. A 1-body step did not change (1.0 us).

So the engine stays on one thread: the gain is a few percent at best, the loss on a busy
machine several-fold, and every first run would compile longer.
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time

import numba
import numpy as np

import sandbox.staged_step
import scenes
from sandbox.build import build_world
from sandbox.jit import njit
from sandbox.narrowphase import (
    collide_into,
    collide_pair,
    joined,
    place_polygons,
    within_reach,
    write_manifold,
)
from sandbox.scene import validate_scene
from sandbox.speculative import closing_reach
from sandbox.staged_step import StageTimer
from sandbox.step import STAGES

CASES = {
    "pyramid_20": lambda: scenes.pyramid(20),
    "pyramid_40": lambda: scenes.pyramid(40),
    "rain_1000": lambda: scenes.rain(1000),
    "rain_5000": lambda: scenes.rain(5000),
}
STATE = ("com", "vel", "omega", "angle")


# --- the two-thread narrowphase --------------------------------------------------------------
@njit(parallel=True)
def collide_slots(pairs, npairs, shapes, wp, bodies, joints, reach, contacts) -> None:
    """Pair q's manifold into ``contacts[q]`` (count 0 when none), the pairs shared among
    numba's threads: each record is written by one thread only."""
    base, ahead = reach
    for q in numba.prange(npairs):
        contacts[q]["count"] = 0
        i, j = pairs[q, 0], pairs[q, 1]  # the skips and the writing of collide_into
        shape_i, shape_j = shapes[i], shapes[j]
        a, b = shape_i["body"], shape_j["body"]
        body_a, body_b = bodies[a], bodies[b]
        margin = base + closing_reach(body_a, shape_i, body_b, shape_j, ahead)
        if a == b or not within_reach(shape_i, shape_j, body_a, body_b, margin):
            continue
        if joints.shape[0] > 0 and joined(joints, bodies.shape[0], a, b):
            continue
        shape_pair, body_pair = (shape_i, shape_j), (body_a, body_b)
        manifold = collide_pair(i, j, shape_pair, body_pair, wp, margin)
        if manifold[0] > 0:
            write_manifold(contacts[q], i, j, shapes, manifold)


@njit
def move_manifold(contacts, q: int, k: int) -> None:
    """Copy what the narrowphase writes of record q into record k."""
    c, d = contacts[q], contacts[k]
    d["a"], d["b"], d["shape_a"], d["shape_b"] = c["a"], c["b"], c["shape_a"], c["shape_b"]
    d["count"] = c["count"]
    d["normal"][0], d["normal"][1] = c["normal"][0], c["normal"][1]
    d["friction"], d["restitution"] = c["friction"], c["restitution"]
    for m in range(2):
        p, r = c["points"][m], d["points"][m]
        r["point"][0], r["point"][1] = p["point"][0], p["point"][1]
        r["depth"], r["feature"] = p["depth"], p["feature"]


@njit
def collide_two_threads(pairs, npairs, shapes, vertices, bodies, joints, reach, contacts) -> int:
    """:func:`sandbox.narrowphase.collide_into` with the pairs shared among threads, then put
    in pair order on one thread (``contacts`` needs a row per pair). Returns how many."""
    wp = place_polygons(shapes, vertices, bodies)
    collide_slots(pairs, npairs, shapes, wp, bodies, joints, reach, contacts)
    k = 0
    for q in range(npairs):
        if contacts[q]["count"] > 0:
            if k != q:
                move_manifold(contacts, q, k)
            k += 1
    return k


# --- stepping with either narrowphase --------------------------------------------------------
NARROWPHASES = {1: collide_into, 2: collide_two_threads}


def build(spec: dict):
    """A world on the staged path (``world.timer``), which calls the narrowphase from Python."""
    world = build_world(validate_scene(spec))
    world.timer = StageTimer()
    return world


def step(world, threads: int, steps: int) -> tuple[float, float]:
    """``steps`` steps with the ``threads``-thread narrowphase: (wall s, process CPU s) per step."""
    sandbox.staged_step.collide_into = NARROWPHASES[threads]
    try:
        w0, c0 = time.perf_counter(), time.process_time()
        for _ in range(steps):
            world.step()
        c1, w1 = time.process_time(), time.perf_counter()
    finally:
        sandbox.staged_step.collide_into = collide_into
    return (w1 - w0) / steps, (c1 - c0) / steps


def identical(a, b) -> bool:
    """Whether two worlds' body states are bit-identical."""
    x, y = a.arrays().bodies, b.arrays().bodies
    return all(np.array_equal(x[f], y[f]) for f in STATE)


def compare(spec: dict, rounds: int, steps: int, settle: int) -> dict:
    """Median wall and CPU time per step (s) with one and with two threads, after ``settle``
    steps; the worlds take turns, the one that starts a round alternating."""
    worlds = {1: build(spec), 2: build(spec)}
    for t, w in worlds.items():
        step(w, t, settle)
    times = {1: [], 2: []}
    for r in range(rounds):
        for t in (1, 2) if r % 2 == 0 else (2, 1):
            times[t].append(step(worlds[t], t, steps))
    out = {"identical": identical(worlds[1], worlds[2]), "pairs": worlds[1].stats["pairs"]}
    for t, runs in times.items():
        out[t] = (statistics.median(r[0] for r in runs), statistics.median(r[1] for r in runs))
    return out


def stage_shares(spec: dict, steps: int = 60) -> dict[str, float]:
    """Seconds per step of every stage, one thread, after ``steps`` steps."""
    world = build(spec)
    step(world, 1, steps)
    world.timer = StageTimer()
    step(world, 1, steps)
    return {k: v / world.timer.steps for k, v in world.timer.seconds.items()}


def kernel_times(spec: dict, settle: int, calls: int = 200) -> tuple[int, float, float]:
    """(pairs, one-thread s, two-thread s): the narrowphase alone, median of ``calls`` calls
    each on the pairs of the settled scene, alternating."""
    world = build(spec)
    step(world, 1, settle)
    a = world.arrays()
    ctx = a.context[0]
    n, pairs = int(ctx["pairs"]), a.buffers.pairs[1]
    geometry = (a.shapes, a.vertices, a.bodies, a.joints, float(ctx["contact_margin"]))
    out = {t: np.zeros(len(pairs), a.buffers.sets.dtype) for t in NARROWPHASES}
    times = {t: [] for t in NARROWPHASES}
    for r in range(calls):
        for t in (1, 2) if r % 2 == 0 else (2, 1):
            w0 = time.perf_counter()
            NARROWPHASES[t](pairs, n, *geometry, out[t])
            times[t].append(time.perf_counter() - w0)
    return n, statistics.median(times[1]), statistics.median(times[2])


COLD = """
import sys, time
sys.path.insert(0, {here!r})
t0 = time.perf_counter()
import scenes
from sandbox.build import build_world
from sandbox.scene import validate_scene
world = build_world(validate_scene(scenes.pyramid(4)))
world.timer = __import__("sandbox.staged_step").staged_step.StageTimer()
world.step()
t1 = time.perf_counter()
import bench_threads
a = world.arrays()
c = a.buffers.sets[0].copy()
bench_threads.collide_two_threads(a.buffers.pairs[1], 1, a.shapes, a.vertices, a.bodies,
                                  a.joints, 0.0, c)
t2 = time.perf_counter()
print(t1 - t0, t2 - t1)
"""


def cold_compile() -> tuple[float, float]:
    """In a fresh process with an empty compile cache: (s to import, compile and take a first
    staged step of a small pyramid, s more for the two-thread kernel's first call)."""
    here = os.path.dirname(os.path.abspath(__file__))
    with tempfile.TemporaryDirectory() as cache:
        env = dict(os.environ, NUMBA_CACHE_DIR=cache)
        code = COLD.format(here=here)
        done = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True)
    engine, kernel = (float(x) for x in done.stdout.split())
    return engine, kernel


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=21, help="blocks per world")
    parser.add_argument("--steps", type=int, default=10, help="steps per block")
    parser.add_argument("--settle", type=int, default=90, help="steps before timing")
    parser.add_argument("--cases", default=",".join(CASES), help="which scenes, comma-separated")
    parser.add_argument("--stages", action="store_true", help="the stage shares, one thread")
    parser.add_argument("--kernel", action="store_true", help="the narrowphase alone")
    parser.add_argument("--compile", action="store_true", help="cold compile times")
    args = parser.parse_args(argv)
    cases = args.cases.split(",")
    if args.compile:
        engine, kernel = cold_compile()
        print(f"empty cache: engine + first step {engine:.1f} s, two-thread kernel +{kernel:.1f} s")
    if args.stages:
        for name in cases:
            s = stage_shares(CASES[name]())
            total = sum(s.values())
            print(f"{name}: {1e6 * total:.0f} us per step (staged, one thread)")
            for k in STAGES:
                print(f"  {k:>22} {1e6 * s[k]:8.1f} us {100 * s[k] / total:5.1f} %")
    if args.kernel:
        print(f"{'scene':>12} {'pairs':>6} {'1 thread':>10} {'2 threads':>10} {'speedup':>8}")
        for name in cases:
            n, one, two = kernel_times(CASES[name](), args.settle)
            print(f"{name:>12} {n:>6} {1e6 * one:8.0f}us {1e6 * two:8.0f}us {one / two:8.2f}")
    print(
        f"{'scene':>12} {'pairs':>6}  {'wall 1t':>9} {'wall 2t':>9} {'2t/1t':>6}"
        f"  {'cpu 1t':>9} {'cpu 2t':>9}  identical"
    )
    for name in cases:
        r = compare(CASES[name](), args.rounds, args.steps, args.settle)
        (w1, c1), (w2, c2) = r[1], r[2]
        print(
            f"{name:>12} {r['pairs']:>6}  {1e3 * w1:7.3f}ms {1e3 * w2:7.3f}ms {w2 / w1:6.3f}"
            f"  {1e3 * c1:7.3f}ms {1e3 * c2:7.3f}ms  {r['identical']}"
        )
    print(f"(numba {numba.__version__}, threading layer {numba.threading_layer()})")


if __name__ == "__main__":
    main()
