"""Where a step's time goes: each stage of this engine's step in microseconds, next to pymunk.

    python benchmarks/profile_step.py [--steps N] [--only NAME ...]

For every benchmark scene (``scenes.py``, the same dicts as ``run.py``) three copies run in
lockstep, alternating blocks of 10 steps so all see the same machine load:

- this engine's world stepping normally (``World.step``: for these scenes the whole step is one
  compiled call, ``sandbox.step.fast_step``): the step's real cost;
- a second world with a stage timer (``world.timer = sandbox.staged_step.StageTimer()``), which
  makes it take the staged path: the very same stage functions called one by one from Python,
  each timed (``sandbox.step.STAGES``); it stays bit-identical to the first world (checked);
- pymunk's ``Space.step`` on the same scene.

A staged stage's time includes the cost of its own compiled call from Python (about a
microsecond), which the one-call step does not pay: the row ``calls and glue`` is the staged
step's total minus the real step.
"""

from __future__ import annotations

import argparse
import gc
import sys
import time

import numpy as np

import scenes  # benchmarks/scenes.py, beside this file
from sandbox.build import build_world
from sandbox.pymunk_bridge import PymunkScene
from sandbox.scene import validate_scene
from sandbox.staged_step import StageTimer
from sandbox.step import STAGES

BLOCK = 10
SCENES = {
    "ballistic": (scenes.ballistic, 3000),
    "rain_100": (lambda: scenes.rain(100), 300),
    "rain_1000": (lambda: scenes.rain(1000), 300),
    "pyramid_20": (lambda: scenes.pyramid(20), 300),
    "pyramid_40": (lambda: scenes.pyramid(40), 200),
    "rain_5000": (lambda: scenes.rain(5000), 120),
}


def profile(name: str, steps: int) -> dict:
    """Per-stage microseconds per step, the real step and pymunk's, for one scene."""
    spec = validate_scene(SCENES[name][0]())
    world, staged = build_world(spec), build_world(spec)
    staged.timer = StageTimer()
    space = PymunkScene.from_scene(spec).space
    dt = spec["dt"]
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
            staged.step()
        mine += middle - start
        theirs += end - middle
        done += n
    row = {stage: 1e6 * t / steps for stage, t in staged.timer.seconds.items()}
    row["staged total"] = sum(row[stage] for stage in STAGES)
    row["step"] = 1e6 * mine / steps
    row["calls and glue"] = row["staged total"] - row["step"]
    row["pymunk step"] = 1e6 * theirs / steps
    row["ratio"] = mine / theirs
    row["identical"] = np.array_equal(world.com, staged.com) and np.array_equal(
        world.vel, staged.vel
    )
    row["contact points"] = world.stats.get("contact_points", 0)
    return row


def warm_up() -> None:
    """Compile (or load from the cache) every stage the scenes use, both ways."""
    for spec, steps in ((scenes.ballistic(), 3), (scenes.rain(30), 90), (scenes.pyramid(4), 20)):
        spec = validate_scene(spec)
        world, staged = build_world(spec), build_world(spec)
        staged.timer = StageTimer()
        for _ in range(steps):
            world.step()
            staged.step()


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description="Per-stage cost of a step, next to pymunk.")
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
        row = rows[name]
        print(f"{name}: {row['step']:.1f} us vs pymunk {row['pymunk step']:.1f} us", flush=True)
    keys = (*STAGES, "staged total", "calls and glue", "step", "pymunk step", "ratio")
    width = max(len(k) for k in keys) + 2
    print()
    print("microseconds per step".ljust(width) + "".join(f"{n:>12}" for n in names))
    for key in keys:
        cells = "".join(
            f"{rows[n][key]:>12.3f}" if key == "ratio" else f"{rows[n][key]:>12.1f}" for n in names
        )
        print(key.ljust(width) + cells)
    points = "".join(f"{rows[n]['contact points']:>12}" for n in names)
    print("contact points".ljust(width) + points)
    if not all(rows[n]["identical"] for n in names):
        print("warning: the staged world left the one-call world", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
