"""This engine against pymunk, step for step, in one process (``DESIGN.md``, "Performance").

    python benchmarks/run.py [--quick] [--only NAME ...]

For every scene of :mod:`scenes` (rain of 100, 1,000 and 5,000 circles, pyramids of base 20 and
40, a single ballistic body) this engine's world and pymunk's space are built from the same scene
dict (same dt = 1/60 s, 10 iterations, gravity). After a warm-up that compiles every numba kernel
the scenes use, both are stepped N times from the initial state, alternating blocks of 10 steps
so that both see the same machine load; the result is milliseconds per step for each and the
ratio sandbox / pymunk (below 1: this engine is faster).

Then: frames per second of GIF output for 500 bodies at 480 px (``bench_render.py``), and the
wall time of every lesson (``sandbox lessons`` in a subprocess; skipped with ``--quick``).

Writes ``benchmarks/results.csv`` and ``benchmarks/results.png`` (ratio per scene, a line at 1),
prints the table, and puts it into ``benchmarks/README.md`` between the ``results`` markers.
"""

from __future__ import annotations

import argparse
import csv
import gc
import io
import platform
import re
import subprocess
import sys
import time
import traceback
from dataclasses import dataclass
from pathlib import Path

import pymunk

import scenes  # benchmarks/scenes.py, beside this file
from sandbox.atomic import atomic_write, atomic_write_text
from sandbox.build import build_world
from sandbox.pymunk_bridge import PymunkScene
from sandbox.scene import validate_scene

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
BLOCK = 10  # steps per timed block; the engines alternate block by block
FIELDS = (
    "benchmark",
    "bodies",
    "steps",
    "sandbox_ms_per_step",
    "pymunk_ms_per_step",
    "ratio",
    "sandbox_mean_y",
    "pymunk_mean_y",
    "value",
    "unit",
    "status",
)


@dataclass
class Case:
    """One step benchmark: a scene builder, and how many steps to time (full, quick)."""

    name: str
    build: object
    steps: int
    quick_steps: int


CASES = [
    Case("ballistic", scenes.ballistic, 3000, 600),
    Case("rain_100", lambda: scenes.rain(100), 300, 120),
    Case("rain_1000", lambda: scenes.rain(1000), 300, 120),
    Case("rain_5000", lambda: scenes.rain(5000), 300, 60),
    Case("pyramid_20", lambda: scenes.pyramid(20), 300, 120),
    Case("pyramid_40", lambda: scenes.pyramid(40), 300, 60),
]


def row(benchmark: str, **values) -> dict:
    out = dict.fromkeys(FIELDS, "")
    out.update({"benchmark": benchmark, "status": "ok", **values})
    return out


# ---------------------------------------------------------------- stepping


def warm_up() -> None:
    """Compile (or load from numba's cache) every kernel the scenes use: circles against circles
    and boxes, boxes against boxes, free flight. Small scenes, run until they touch."""
    for spec, steps in (
        (scenes.ballistic(), 5),
        (scenes.rain(30), 90),
        (scenes.pyramid(4), 30),
    ):
        spec = validate_scene(spec)
        world = build_world(spec)
        space = PymunkScene.from_scene(spec).space
        for _ in range(steps):
            world.step()
            space.step(spec["dt"])


def time_steps(spec: dict, steps: int) -> tuple[float, float, float, float]:
    """Seconds per step (this engine, pymunk), both from the initial state of ``spec``, and the
    mean height of the dynamic bodies at the end in each (m: a check that both did the same).

    The engines alternate blocks of ``BLOCK`` steps; pymunk's own ``Space.step`` is timed (no
    bridge code runs inside the timed part: these scenes have no forces to add).
    """
    spec = validate_scene(spec)
    world = build_world(spec)
    bridge = PymunkScene.from_scene(spec)
    space: pymunk.Space = bridge.space
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
        mine += middle - start
        theirs += end - middle
        done += n
    dynamic = [i for i, b in enumerate(spec["bodies"]) if b["type"] == "dynamic"]
    mine_y = sum(world.bodies[i].position[1] for i in dynamic) / max(1, len(dynamic))
    theirs_y = sum(bridge.bodies[i].position.y for i in dynamic) / max(1, len(dynamic))
    return mine / steps, theirs / steps, mine_y, theirs_y


def bench_case(case: Case, quick: bool) -> dict:
    spec = case.build()
    steps = case.quick_steps if quick else case.steps
    try:
        mine, theirs, mine_y, theirs_y = time_steps(spec, steps)
    except Exception as err:  # a scene this engine cannot run yet: report it, go on
        traceback.print_exc(limit=3)
        return row(case.name, bodies=scenes.body_count(spec), steps=steps, status=f"error: {err}")
    return row(
        case.name,
        bodies=scenes.body_count(spec),
        steps=steps,
        sandbox_ms_per_step=f"{1e3 * mine:.4g}",
        pymunk_ms_per_step=f"{1e3 * theirs:.4g}",
        ratio=f"{mine / theirs:.3g}",
        sandbox_mean_y=f"{mine_y:.3f}",
        pymunk_mean_y=f"{theirs_y:.3f}",
    )


# ---------------------------------------------------------------- rendering and lessons


def bench_gif() -> dict:
    try:
        from bench_render import bench_render
    except ImportError as err:
        return row("render_gif_500", bodies=500, status=f"skipped: {err}")
    fps = max(bench_render(n_bodies=500, frames=120, size_px=480) for _ in range(2))
    return row("render_gif_500", bodies=500, steps=120, value=f"{fps:.1f}", unit="frames/s")


def bench_lessons() -> list[dict]:
    """Wall time of ``sandbox lessons`` (all of them, one subprocess), total and per lesson."""
    start = time.perf_counter()
    proc = subprocess.run(
        [sys.executable, "-m", "sandbox", "lessons"],
        cwd=ROOT,
        capture_output=True,
        text=True,
    )
    total = time.perf_counter() - start
    rows = []
    for match in re.finditer(r"^== (\S+): (.+?) in ([0-9.]+) s$", proc.stdout, re.MULTILINE):
        name, status, seconds = match.groups()
        status = "ok" if status == "ok" else f"error: {status}"
        rows.append(row(f"lesson {name}", value=seconds, unit="s", status=status))
    status = "ok" if proc.returncode == 0 else f"error: exit {proc.returncode}"
    if proc.returncode:
        print("\n".join(proc.stderr.splitlines()[-20:]), file=sys.stderr)
    rows.append(row("lessons_total", value=f"{total:.1f}", unit="s", status=status))
    return rows


# ---------------------------------------------------------------- output


def format_table(rows: list[dict]) -> str:
    """A Markdown table of the results."""
    head = [
        "benchmark",
        "bodies",
        "steps",
        "sandbox ms/step",
        "pymunk ms/step",
        "ratio",
        "mean y at end (m)",
        "other",
    ]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for r in rows:
        other = f"{r['value']} {r['unit']}".strip()
        if r["status"] != "ok":
            other = f"{other} ({r['status']})".strip()
        cells = [
            r["benchmark"],
            r["bodies"],
            r["steps"],
            r["sandbox_ms_per_step"],
            r["pymunk_ms_per_step"],
            r["ratio"],
            f"{r['sandbox_mean_y']} / {r['pymunk_mean_y']}" if r["sandbox_mean_y"] else "",
            other,
        ]
        lines.append("| " + " | ".join(str(c) for c in cells) + " |")
    return "\n".join(lines)


def write_csv(rows: list[dict], path: Path) -> None:
    with atomic_write(path, "w", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=FIELDS)
        writer.writeheader()
        writer.writerows(rows)


def write_plot(rows: list[dict], path: Path, title: str) -> None:
    from matplotlib.figure import Figure

    ratios = [(r["benchmark"], float(r["ratio"])) for r in rows if r["ratio"]]
    fig = Figure(figsize=(8, 4.5))
    ax = fig.subplots()
    if ratios:
        names, values = zip(*ratios, strict=True)
        colors = ["C2" if v <= 1.0 else "C3" for v in values]
        bars = ax.bar(names, values, color=colors)
        ax.bar_label(bars, labels=[f"{v:.2g}" for v in values], fontsize=8)
        if max(values) / min(values) > 8:  # log scale when the ratios span a wide range
            ax.set_yscale("log")
    ax.axhline(1.0, color="k", linewidth=1.0, label="as fast as pymunk")
    ax.set_ylabel("time per step, sandbox / pymunk")
    ax.set_title(title, fontsize=9)
    ax.legend(fontsize=8)
    ax.tick_params(axis="x", labelsize=8)
    fig.tight_layout()
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", dpi=100)
    with atomic_write(path, "wb") as f:
        f.write(buffer.getvalue())


def update_readme(path: Path, table: str, title: str) -> None:
    """Replace the text between the ``results`` markers of the README with the new table."""
    if not path.exists():
        return
    text = path.read_text(encoding="utf-8")
    start, end = "<!-- results -->", "<!-- /results -->"
    if start not in text or end not in text:
        return
    before, rest = text.split(start, 1)
    after = rest.split(end, 1)[1]
    atomic_write_text(path, f"{before}{start}\n{title}\n\n{table}\n{end}{after}")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description="This engine against pymunk, step for step.")
    parser.add_argument("--quick", action="store_true", help="fewer steps, no lesson timing")
    parser.add_argument(
        "--only",
        nargs="*",
        metavar="NAME",
        help="only these step benchmarks (print, write nothing)",
    )
    parser.add_argument("--no-readme", action="store_true", help="leave README.md as it is")
    args = parser.parse_args(argv)

    cases = [c for c in CASES if not args.only or c.name in args.only]
    print("warming up (compiling) ...", flush=True)
    start = time.perf_counter()
    warm_up()
    print(f"warm-up {time.perf_counter() - start:.1f} s", flush=True)
    rows = []
    for case in cases:
        rows.append(bench_case(case, args.quick))
        r = rows[-1]
        print(f"{case.name}: {r['sandbox_ms_per_step'] or '-'} ms vs", end=" ")
        print(f"{r['pymunk_ms_per_step'] or '-'} ms per step ({r['status']})", flush=True)
    if not args.only:
        rows.append(bench_gif())
        if not args.quick:
            rows.extend(bench_lessons())

    mode = "quick" if args.quick else "full"
    title = (
        f"{time.strftime('%Y-%m-%d')}, {mode} run: Python {platform.python_version()}, "
        f"pymunk {pymunk.version}, {platform.machine()}, dt = 1/60 s, 10 iterations"
    )
    table = format_table(rows)
    print()
    print(title)
    print(table)
    if not args.only:  # a partial run prints only, keeping the last full results
        write_csv(rows, HERE / "results.csv")
        write_plot(rows, HERE / "results.png", title)
        if not args.no_readme:
            update_readme(HERE / "README.md", table, title)
    failed = [r["benchmark"] for r in rows if r["status"].startswith("error")]
    if failed:
        print(f"could not run: {', '.join(failed)}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
