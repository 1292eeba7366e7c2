"""The first run on a machine where nothing is compiled yet: how long a student waits.

    python benchmarks/bench_first_run.py [--rounds R] [--background] [--kernels]

Each case runs ``sandbox simulate SCENE --steps N --trace t.csv`` in a fresh process with an
empty compile cache of its own (``NUMBA_CACHE_DIR`` in a temporary folder) and times it on the
wall clock, as a new user meets it: a small scene runs uncompiled and says so, a large one
compiles first (``sandbox/cli/first_run.py``). The table gives the median over the rounds, the
path taken and the command's first note. By default the background warmup a cold run starts
is turned off (``SANDBOX_WARMUP=off``), so each case times the command alone;
``--background`` lets it start, as on a student's machine (it then competes for the cores), and
also times how long it takes until the next run is compiled. ``--kernels`` instead counts the
kernels each one-call step compiles from an empty cache: the lengths of the compile notice's
progress bar (``sandbox.jit.CompileNotice.STEP_KERNELS``).

The issue's bounds (issue "First run in seconds"): drop's 240 steps in at most 5 s, the
pyramid's 120 steps in at most 8 s.
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

CASES = [  # (scene, steps)
    ("drop", 240),
    ("pyramid", 120),
    ("pyramid", 300),
    ("rain", 300),
    ("pyramid", 1000),  # 56,000 body-steps: past the bound, compiles
]
WAIT = 600.0  # s: give up waiting for a background warmup after this long


def run_cold(scene: str, steps: int, background: bool) -> tuple[float, str, float | None]:
    """(wall seconds, the first note, seconds until the background warmup finished or None)
    of one cold ``sandbox simulate``."""
    with tempfile.TemporaryDirectory() as folder:
        cache = Path(folder) / "cache"
        cache.mkdir()
        env = {k: v for k, v in os.environ.items() if k not in ("SANDBOX_JIT", "PYTHONPATH")}
        env.update(NUMBA_CACHE_DIR=str(cache), SANDBOX_WARMUP="on" if background else "off")
        command = [sys.executable, "-m", "sandbox", "simulate", scene, "--steps", str(steps)]
        start = time.perf_counter()
        done = subprocess.run(
            [*command, "--trace", str(Path(folder) / "t.csv")],
            env=env,
            cwd=folder,
            capture_output=True,
            text=True,
            check=True,
        )
        seconds = time.perf_counter() - start
        notes = [line for line in done.stderr.splitlines() if line.startswith("note:")]
        warmed = None
        if background:  # the background warmup holds a lock file in the cache while it runs
            while any(cache.rglob("warming")) and time.perf_counter() - start < WAIT:
                time.sleep(0.5)
            warmed = time.perf_counter() - start
        return seconds, (notes[0] if notes else ""), warmed


KERNEL_COUNT = """
import sys
from numba.core import event
import sandbox

STEPS = ("fast_step", "soft_step")
stack, count = [], [0]

class Count(event.Listener):
    def on_start(self, ev):
        stack.append(ev.data["dispatcher"].py_func.__name__)
    def on_end(self, ev):
        name = stack.pop()
        if (stack[0] if stack else name) in STEPS:  # compiled with the step
            count[0] += 1

event.register("numba:compile", Count())
world = sandbox.load_scene(sys.argv[1])
world.settings.solver = sys.argv[2]
world.step()
print(count[0])
"""


def count_kernels(solver: str) -> int:
    """Kernels the one-call step of ``solver`` compiles from an empty cache (the bundled
    pyramid; a world of every shape and joint gave the same count)."""
    with tempfile.TemporaryDirectory() as folder:
        env = {k: v for k, v in os.environ.items() if k not in ("SANDBOX_JIT", "PYTHONPATH")}
        env.update(NUMBA_CACHE_DIR=folder, SANDBOX_WARMUP="off")
        scene = str(Path(__file__).resolve().parents[1] / "scenes" / "pyramid.json")
        done = subprocess.run(
            [sys.executable, "-c", KERNEL_COUNT, scene, solver],
            env=env,
            capture_output=True,
            text=True,
            check=True,
        )
        return int(done.stdout.split()[-1])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=3, help="cold runs per case (median)")
    parser.add_argument(
        "--background", action="store_true", help="let the background warmup run, and time it"
    )
    parser.add_argument(
        "--kernels", action="store_true", help="count the kernels each one-call step compiles"
    )
    args = parser.parse_args()
    if args.kernels:
        for name, solver in (("fast_step", "iterative"), ("soft_step", "soft")):
            print(f"{name}: {count_kernels(solver)} kernels")
        return
    print(
        "| scene | steps | first run (s), median | path | runs (s) | compiled for the next run after (s) |"
    )
    print("|---|---|---|---|---|---|")
    for scene, steps in CASES:
        runs = [run_cold(scene, steps, args.background) for _ in range(args.rounds)]
        seconds = [r[0] for r in runs]
        note = runs[0][1]
        path = "uncompiled" if "plain Python" in note else "compiled"
        warmed = ", ".join(f"{r[2]:.0f}" for r in runs if r[2] is not None) or "-"
        shown = ", ".join(f"{s:.1f}" for s in seconds)
        print(
            f"| {scene} | {steps} | {statistics.median(seconds):.1f} | {path} | {shown} | {warmed} |"
        )


if __name__ == "__main__":
    main()
