"""Free bodies, no collisions: the per-step cost of the world itself (integration and bookkeeping).

    python benchmarks/bench_free.py [--seconds S] [--stages]

Prints steps per second for a single ballistic body and for 1,000 free bodies (no shapes
touching: they are spread far apart and fall under gravity), for each integrator, and each
rate relative to semi-implicit Euler's with the same bodies. The worlds step in alternating
short blocks (about a millisecond each) so all see the same machine load; each figure is the
median over its blocks. Time is the process's CPU time (``time.process_time``), so other
programs sharing the machine's cores do not count; on a quiet machine it is the wall time.

``--stages``: where the time of a 1,000-body step goes, per stage and integrator
(``sandbox.staged_step.StageTimer``: the staged path, each stage called from Python, so each
stage also carries about a microsecond of call overhead that the one-call step does not pay).
"""

from __future__ import annotations

import argparse
import statistics
import time

import sandbox
import scenes  # benchmarks/scenes.py, beside this file

INTEGRATORS = ("explicit_euler", "semi_implicit_euler", "verlet", "rk4")
BODIES = (1, 1000)


def free_world(n: int, integrator: str = "semi_implicit_euler") -> sandbox.World:
    """``n`` discs on a wide grid, far apart, thrown upwards; no two ever touch
    (:func:`scenes.free`, the scene ``ab.py`` times as ``free_1000``)."""
    return sandbox.load_scene(scenes.free(n, integrator))


def block_rate(world: sandbox.World, steps: int) -> float:
    """Steps per second over one block of ``steps`` steps."""
    start = time.process_time()
    for _ in range(steps):
        world.step()
    return steps / (time.process_time() - start)


def measure(seconds: float) -> dict[tuple[str, int], float]:
    """Median steps per second of every (integrator, bodies) world, stepped in alternating
    blocks for about ``seconds`` in all."""
    worlds = {(name, n): free_world(n, name) for name in INTEGRATORS for n in BODIES}
    steps = {}
    for key, world in worlds.items():  # compile, then size a block to about a millisecond
        block_rate(world, 10)
        steps[key] = max(1, int(1e-3 * block_rate(world, 10)))
    rates: dict[tuple[str, int], list[float]] = {key: [] for key in worlds}
    end = time.perf_counter() + seconds
    while time.perf_counter() < end or min(len(r) for r in rates.values()) < 5:
        for key, world in worlds.items():
            rates[key].append(block_rate(world, steps[key]))
    return {key: statistics.median(r) for key, r in rates.items()}


def stage_table(n: int = 1000, steps: int = 300) -> None:
    """Print the microseconds per step of every stage for ``n`` free bodies, per integrator."""
    from sandbox.staged_step import StageTimer
    from sandbox.step import STAGES

    seconds = {}
    for name in INTEGRATORS:
        world = free_world(n, name)
        world.timer = StageTimer()
        for _ in range(10):
            world.step()
        best = None
        for _ in range(5):  # the fastest of five runs of each stage: the least disturbed
            world.timer = StageTimer()
            for _ in range(steps // 5):
                world.step()
            run = {k: v / world.timer.steps for k, v in world.timer.seconds.items()}
            best = run if best is None else {k: min(best[k], run[k]) for k in STAGES}
        seconds[name] = best
    print(
        f"{'stage (us per step, ' + str(n) + ' bodies)':>36}"
        + "".join(f"{s:>20}" for s in INTEGRATORS)
    )
    for stage in (*STAGES, "sum of stages"):
        row = [
            sum(seconds[s].values()) if stage == "sum of stages" else seconds[s][stage]
            for s in INTEGRATORS
        ]
        print(f"{stage:>36}" + "".join(f"{1e6 * v:20.1f}" for v in row))


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=8.0, help="time to measure for (s)")
    parser.add_argument("--stages", action="store_true", help="also time each stage")
    args = parser.parse_args(argv)
    if args.stages:
        stage_table()
    rate = measure(args.seconds)
    head = "".join(f"  {f'{n} bodies (steps/s)':>24}" for n in BODIES)
    print(f"{'integrator':>20}{head}")
    for name in INTEGRATORS:
        cells = ""
        for n in BODIES:
            ratio = rate[name, n] / rate["semi_implicit_euler", n]
            cells += f"  {rate[name, n]:14.0f} ({ratio:4.2f}x)"
        print(f"{name:>20}{cells}")
    print("(x: relative to semi_implicit_euler with the same bodies, in the same run)")


if __name__ == "__main__":
    main()
