"""Two versions of the engine, step for step: is a change faster or slower?

    python benchmarks/ab.py SCENE [--steps N] [--rounds R] CHECKOUT_A CHECKOUT_B

For example, the code before a change in a second worktree against this one::

    git worktree add ../before HEAD~3
    python benchmarks/ab.py rain_5000 --steps 300 --rounds 7 ../before .

Each round runs SCENE (a name from ``SCENES`` below, built from ``scenes.py``; a name ending
in ``_soft``: that scene under ``solver: soft``; ``free_1000_verlet`` and ``free_1000_rk4``:
``free_1000`` with that integrator; ``chain_20_soft``, ``chain_100_soft``, ``heavy_chain_soft``:
the soft step lesson's chains, 20 and 100 links, 10 links and a ball of 100 link masses;
``rain_100__pairwise``, ``pyramid_20__shock``, ``rain_1000__grid`` and the like: that scene
under another solver or broadphase, which the world steps stage by stage from Python) once
with CHECKOUT_A's ``sandbox`` and once with CHECKOUT_B's, each in its own process (so each
has its own compiled kernels, in its own compile cache under the checkout), alternating, and
times N steps after 5 of warm-up: CPU time of the stepping thread per step. On a shared
machine the time of one run moves by tens of percent; the median of the rounds' ratios B / A
is what to read, with the smallest and the largest.
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent


def scene_named(name: str) -> dict:
    """The benchmark scene ``name`` as a scene dict."""
    import scenes  # benchmarks/scenes.py, beside this file

    makers = {
        "ballistic": scenes.ballistic,
        "rain_100": lambda: scenes.rain(100),
        "rain_1000": lambda: scenes.rain(1000),
        "rain_5000": lambda: scenes.rain(5000),
        "pyramid_20": lambda: scenes.pyramid(20),
        "pyramid_40": lambda: scenes.pyramid(40),
        "free_1000": lambda: scenes.free(1000),
        "free_1000_verlet": lambda: scenes.free(1000, "verlet"),
        "free_1000_rk4": lambda: scenes.free(1000, "rk4"),
        "chain_20": lambda: scenes.chain(20),
        "chain_100": lambda: scenes.chain(100),
        "heavy_chain": lambda: scenes.chain(10, ball=100.0),
    }
    base, _, variant = name.partition("__")
    spec = makers[base.removesuffix("_soft")]()
    settings = spec.setdefault("settings", {})
    if base.endswith("_soft"):  # the same scene under the soft step
        settings["solver"] = "soft"
    if variant in SOLVER_VARIANTS:  # scene__pairwise, scene__shock: under that solver
        settings["solver"] = variant
    elif variant:  # scene__grid and the like: with that broadphase
        settings["broadphase"] = variant
    return spec


SOLVER_VARIANTS = ("pairwise", "shock")
BROADPHASE_VARIANTS = ("brute", "grid", "quadtree", "kdtree")


SCENES = ("ballistic", "rain_100", "rain_1000", "rain_5000", "pyramid_20", "pyramid_40")
SCENES += tuple(f"{name}_soft" for name in SCENES if name != "ballistic")
SCENES += ("free_1000", "free_1000_verlet", "free_1000_rk4")
SCENES += ("chain_20_soft", "chain_100_soft", "heavy_chain_soft")  # the joints of the soft step
# any contact scene under another solver or broadphase (the staged path): rain_100__pairwise
SCENES += tuple(
    f"{name}__{variant}"
    for name in ("rain_100", "rain_1000", "pyramid_20")
    for variant in SOLVER_VARIANTS + BROADPHASE_VARIANTS
)


def time_here(name: str, steps: int) -> float:
    """Milliseconds of thread CPU time per step of scene ``name`` with the ``sandbox`` on the
    path (after 5 steps of warm-up)."""
    from sandbox import load_scene

    world = load_scene(scene_named(name))
    for _ in range(5):
        world.step()
    start = time.thread_time()
    for _ in range(steps):
        world.step()
    return (time.thread_time() - start) / steps * 1e3


def time_in(checkout: Path, name: str, steps: int) -> float:
    """:func:`time_here` in a new process with ``checkout``'s ``sandbox`` first on the path."""
    env = dict(os.environ, PYTHONPATH=str(checkout), NUMBA_CACHE_DIR=str(checkout / ".ab-cache"))
    args = [sys.executable, __file__, "--time-here", name, "--steps", str(steps)]
    done = subprocess.run(args, env=env, cwd=HERE, capture_output=True, text=True, check=True)
    return float(done.stdout)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scene", choices=SCENES)
    parser.add_argument("a", nargs="?", type=Path, help="checkout A (the reference)")
    parser.add_argument("b", nargs="?", type=Path, help="checkout B")
    parser.add_argument("--steps", type=int, default=300, help="steps timed per run")
    parser.add_argument("--rounds", type=int, default=7, help="pairs of runs")
    parser.add_argument("--time-here", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_intermixed_args()
    if args.time_here:
        print(time_here(args.scene, args.steps))
        return
    if args.a is None or args.b is None:
        parser.error("give two checkouts, A and B")
    a, b = args.a.resolve(), args.b.resolve()
    time_in(a, args.scene, 10)  # compile both first: no round pays for it
    time_in(b, args.scene, 10)
    times_a, times_b, ratios = [], [], []
    for _ in range(args.rounds):
        times_a.append(time_in(a, args.scene, args.steps))
        times_b.append(time_in(b, args.scene, args.steps))
        ratios.append(times_b[-1] / times_a[-1])
    print(
        f"{args.scene}: A {statistics.median(times_a):.4f} ms, B {statistics.median(times_b):.4f}"
        f" ms per step (medians); B / A median {statistics.median(ratios):.3f}"
        f" (min {min(ratios):.3f}, max {max(ratios):.3f}, {args.rounds} rounds)"
    )


if __name__ == "__main__":
    main()
