"""The narrowphase on two threads (``settings.threads``) against one: wall time per step.

    python benchmarks/bench_threads.py [--rounds R] [--steps N] [--stages]

For every scene (pyramids of base 20 and 40, rain of 1,000 and 5,000 circles; ``scenes.py``) two
worlds are built from the same dict, one with ``threads: 1`` and one with ``threads: 2``, and
stepped in alternating blocks of ``--steps`` steps, ``--rounds`` times, the one that starts a
round alternating. Per world the table gives the median over the blocks of the wall time per
step (``time.perf_counter``) and of the process's CPU time per step (``time.process_time``: all
threads, the workers' included, unlike ``run.py``'s thread time). After the last round it checks
that both worlds' bodies are bit-identical (``==``). A 1-body world is timed the same way (the
parallel kernel is never called for it: the cost of the switch itself).

``--stages``: the share of each stage in a one-thread step (``sandbox.step.StageTimer``, the
staged path), for the narrowphase's ("collide") share.
"""

from __future__ import annotations

import argparse
import statistics
import time

import numpy as np

import scenes
from sandbox.build import build_world
from sandbox.scene import validate_scene
from sandbox.step import STAGES, StageTimer

CASES = {
    "pyramid_20": lambda: scenes.pyramid(20),
    "pyramid_40": lambda: scenes.pyramid(40),
    "rain_1000": lambda: scenes.rain(1000),
    "rain_5000": lambda: scenes.rain(5000),
}


def one_body() -> dict:
    """A single falling disc: the fixed cost of a step."""
    spec = scenes.rain(1)
    spec["bodies"] = [b for b in spec["bodies"] if b.get("type", "dynamic") == "dynamic"]
    return spec


def build(spec: dict, threads: int):
    spec = dict(spec, settings=dict(spec["settings"], threads=threads))
    return build_world(validate_scene(spec))


def block(world, steps: int) -> tuple[float, float]:
    """(wall s, process CPU s) per step over ``steps`` steps."""
    w0, c0 = time.perf_counter(), time.process_time()
    for _ in range(steps):
        world.step()
    c1, w1 = time.process_time(), time.perf_counter()
    return (w1 - w0) / steps, (c1 - c0) / steps


def identical(a, b) -> bool:
    """Whether two worlds' body states are bit-identical."""
    x, y = a.arrays().bodies, b.arrays().bodies
    return all(np.array_equal(x[f], y[f]) for f in ("com", "vel", "omega", "angle"))


def compare(spec: dict, rounds: int, steps: int, settle: int) -> dict:
    """Median wall and CPU time per step (s) of a 1-thread and a 2-thread world, after
    ``settle`` steps (the rain lands: most pairs come once it lies in the box)."""
    worlds = {1: build(spec, 1), 2: build(spec, 2)}
    for w in worlds.values():
        block(w, settle)
    times = {t: [] for t in worlds}
    for r in range(rounds):
        order = (1, 2) if r % 2 == 0 else (2, 1)
        for t in order:
            times[t].append(block(worlds[t], steps))
    out = {"identical": identical(worlds[1], worlds[2]), "pairs": worlds[1].stats["pairs"]}
    for t, runs in times.items():
        out[t] = (statistics.median(r[0] for r in runs), statistics.median(r[1] for r in runs))
    return out


def stage_shares(spec: dict, steps: int = 60) -> dict[str, float]:
    """Seconds per step of every stage on one thread (staged path)."""
    world = build(spec, 1)
    for _ in range(steps):
        world.step()
    world.timer = StageTimer()
    for _ in range(steps):
        world.step()
    return {k: v / world.timer.steps for k, v in world.timer.seconds.items()}


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=21, help="blocks per world")
    parser.add_argument("--steps", type=int, default=10, help="steps per block")
    parser.add_argument("--settle", type=int, default=90, help="steps before timing")
    parser.add_argument("--cases", default=",".join([*CASES, "one_body"]), help="which scenes")
    parser.add_argument("--stages", action="store_true", help="also give the stage shares")
    args = parser.parse_args(argv)
    if args.stages:
        for name, make in CASES.items():
            s = stage_shares(make())
            total = sum(s.values())
            print(f"{name}: {1e6 * total:.0f} us per step (staged)")
            for k in STAGES:
                print(f"  {k:>22} {1e6 * s[k]:8.1f} us {100 * s[k] / total:5.1f} %")
    print(
        f"{'scene':>12} {'pairs':>6}  {'wall 1t':>9} {'wall 2t':>9} {'ratio':>6}"
        f"  {'cpu 1t':>9} {'cpu 2t':>9}  identical"
    )
    cases = dict(CASES, one_body=one_body)
    for name in args.cases.split(","):
        make = cases[name]
        steps = args.steps if name != "one_body" else 1000
        r = compare(make(), args.rounds, steps, args.settle)
        (w1, c1), (w2, c2) = r[1], r[2]
        print(
            f"{name:>12} {r['pairs']:>6}  {1e3 * w1:7.3f}ms {1e3 * w2:7.3f}ms {w2 / w1:6.3f}"
            f"  {1e3 * c1:7.3f}ms {1e3 * c2:7.3f}ms  {r['identical']}"
        )


if __name__ == "__main__":
    main()
