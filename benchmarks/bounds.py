"""The step's speed bounds, measured several times: how often each holds, and by how much.

    python benchmarks/bounds.py [--runs N] [--clock cpu|wall]

The bounds of the issue "First run in seconds, and a step that costs no more than pymunk's"
are ratios of this engine's time per step (its iterative solver) to a peer's, each measured
in one run: the two stepped in turns in one process (``run.py``'s :func:`run.time_steps`,
every engine of ``run.py`` as there, so the conditions are the same). On a shared machine one
run's ratio moves by several percent from one minute to the next, so a single run says little
about a bound with a small margin. This script makes ``--runs`` runs (default 5) of the five
scenes the bounds name, one after another, and prints one row per bound: its limit, every
run's ratio, the median, the largest, and in how many runs it held. Box2D's rows need the
``box2d`` package (the ``bench`` extra); without it they are left out and one line says so.

Exits 0 when every bound held in every run, 1 when one did not (the table says which).
"""

from __future__ import annotations

import argparse
import statistics
import sys
from dataclasses import dataclass

import run  # benchmarks/run.py, beside this file
from engines import BOX2D_MISSING

MINE = "iterative"  # the column the bounds are about: this engine's default solver


@dataclass(frozen=True)
class Bound:
    """At most ``limit`` for this engine's time per step on ``scene`` over ``peer``'s."""

    scene: str
    peer: str
    limit: float

    @property
    def label(self) -> str:
        return f"{self.scene}, {MINE} / {self.peer}"


BOUNDS = (
    Bound("ballistic", "pymunk", 1.0),
    Bound("rain_100", "pymunk", 0.7),
    Bound("pyramid_20", "pymunk", 0.7),
    Bound("rain_5000", "pymunk", 0.4),
    Bound("pyramid_40", "pymunk", 0.6),
    Bound("rain_100", "Box2D", 1.0),  # no slower than Box2D 2.3
    Bound("pyramid_20", "Box2D", 1.0),
)


def measure(scene: str, clock: str) -> dict[str, float]:
    """One run of ``scene`` as ``run.py`` times it: seconds per step of every engine on
    ``clock`` (``cpu`` or ``wall``)."""
    case = next(c for c in run.CASES if c.name == scene)
    timings = run.time_steps(case.build(), case.steps, run.case_engines(case))
    return {name: getattr(t, clock) for name, t in timings.items()}


def ratios(bounds, runs: int, clock: str, report=print) -> dict[Bound, list[float]]:
    """Every bound's ratio in each of ``runs`` runs; each run times each scene once."""
    scenes = list(dict.fromkeys(b.scene for b in bounds))
    found: dict[Bound, list[float]] = {b: [] for b in bounds}
    for r in range(runs):
        for scene in scenes:
            seconds = measure(scene, clock)
            for b in bounds:
                if b.scene == scene:
                    found[b].append(seconds[MINE] / seconds[b.peer])
        report(f"run {r + 1} of {runs} done", flush=True)
    return found


def table(found: dict[Bound, list[float]]) -> str:
    """A Markdown table: one row per bound, every run's ratio, the median, the largest, and in
    how many runs the ratio was at most the limit."""
    runs = max(len(v) for v in found.values())
    head = ["bound", "limit", *(f"run {i + 1}" for i in range(runs)), "median", "largest"]
    lines = ["| " + " | ".join(head + ["held"]) + " |", "|" + "---|" * (len(head) + 1)]
    for b, values in found.items():
        cells = [b.label, f"{b.limit:.2f}", *(f"{v:.3f}" for v in values)]
        cells += [f"{statistics.median(values):.3f}", f"{max(values):.3f}"]
        held = sum(v <= b.limit for v in values)
        cells.append(f"{held} of {len(values)}")
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description="The step's speed bounds, measured N times.")
    parser.add_argument(
        "--runs", type=int, default=5, help="how many times to measure every bound (default 5)"
    )
    parser.add_argument(
        "--clock",
        choices=sorted(run.CLOCKS),
        default="cpu",
        help="cpu (the stepping thread's time, as run.py's table, default) or wall",
    )
    args = parser.parse_args(argv)
    if args.runs < 1:
        parser.error("--runs: at least 1")
    bounds = [b for b in BOUNDS if b.peer != "Box2D" or not BOX2D_MISSING]
    if len(bounds) < len(BOUNDS):
        print(f"Box2D's bounds skipped: {BOX2D_MISSING}")
    print("warming up (compiling) ...", flush=True)
    run.warm_up()
    found = ratios(bounds, args.runs, args.clock)
    print()
    print(f"{run.CLOCKS[args.clock]}, {args.runs} runs")
    print(table(found))
    broken = [b.label for b, values in found.items() if max(values) > b.limit]
    if broken:
        print(f"over the limit in some run: {'; '.join(broken)}")
        return 1
    print("every bound held in every run")
    return 0


if __name__ == "__main__":
    sys.exit(main())
