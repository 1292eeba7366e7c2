"""This engine against pymunk and Box2D 2.3, step for step, in one process (``DESIGN.md``,
"Performance").

    python benchmarks/run.py [--quick] [--only NAME ...] [--clock cpu|wall]

For every scene of :mod:`scenes` (rain of 100, 1,000 and 5,000 circles, pyramids of base 20 and
40, a single ballistic body) every engine of :mod:`engines` is built from the same scene dict
(same dt = 1/60 s, 10 velocity iterations, gravity, shapes, materials): this engine with its
iterative solver and with the soft step (``solver: soft``, 4 substeps; contact scenes only),
pymunk, and Box2D 2.3 when the ``box2d`` package is installed (the ``bench`` extra; without it
one line says so and the column is left out). After a warm-up that compiles every numba kernel
the scenes use, all are stepped N times from the initial state, in turns of blocks of 10 steps
(the first engine of a turn rotates) so that all see the same machine load. The result is
milliseconds per step for each engine, the ratios of this engine's columns to pymunk and to
Box2D (below 1: this engine is faster), and each engine's mean height of the dynamic bodies at
the end (a check that all simulated the same thing).

Time is measured twice: CPU time of the stepping thread (``time.thread_time``, what the table
shows by default: time spent waiting for a core under load does not count) and wall time
(``time.perf_counter``, ``--clock wall``). The engines step on one thread; if one ever uses
more, the table must show wall time.

Then: frames per second of GIF output for 500 bodies at 480 px (``bench_render.py``), and the
wall time of every lesson (``sandbox lessons`` in a subprocess; skipped with ``--quick``), and
with ``--cold-lessons`` of all lessons from an empty compile cache.

Writes ``benchmarks/results.csv`` (both clocks) and ``benchmarks/results.png`` (ratios per
scene, a line at 1), prints the table, and puts it into ``benchmarks/README.md`` between the
``results`` markers.
"""

from __future__ import annotations

import argparse
import csv
import gc
import io
import os
import platform
import re
import subprocess
import sys
import tempfile
import time
import traceback
from dataclasses import dataclass
from pathlib import Path

# the engine compiled for this very processor, not kernels compiled ahead to ship in a wheel
# (sandbox/prebuilt.py), which a checkout holds after `python -m sandbox.prebuilt`
os.environ.setdefault("SANDBOX_PREBUILT", "off")

import pymunk  # noqa: E402
from engines import (  # benchmarks/engines.py
    ALL_NAMES,
    BOX2D_MISSING,
    BOX2D_VERSION,
    ENGINES,
    SANDBOX_ENGINES,
    SOFT_SUBSTEPS,
    Engine,
)

import scenes  # benchmarks/scenes.py, beside this file
from sandbox.atomic import atomic_write, atomic_write_text
from sandbox.scene import validate_scene

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
BLOCK = 10  # steps per timed block; the engines take turns block by block
CLOCKS = {"cpu": "CPU time of the stepping thread", "wall": "wall time"}
SANDBOX_NAMES = [e.name for e in SANDBOX_ENGINES]
PEER_NAMES = [n for n in ALL_NAMES if n not in SANDBOX_NAMES]
RATIOS = [(s, p) for p in PEER_NAMES for s in SANDBOX_NAMES]  # (this engine's column, peer)
FIELDS = (
    ["benchmark", "bodies", "steps", "clock"]
    + [f"{n}_{c}_ms_per_step" for n in ALL_NAMES for c in CLOCKS]
    + [f"{n}_first_step_{c}_ms" for n in ALL_NAMES for c in CLOCKS]
    + [f"{s}_per_{p}" for s, p in RATIOS]
    + [f"{n}_mean_y" for n in ALL_NAMES]
    + ["value", "unit", "status"]
)


@dataclass
class Case:
    """One step benchmark: a scene builder, how many steps to time (full, quick), and whether
    anything in it touches (the soft step is timed on contact scenes only)."""

    name: str
    build: object
    steps: int
    quick_steps: int
    contacts: bool = True


CASES = [
    Case("ballistic", scenes.ballistic, 3000, 600, contacts=False),
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
    """Compile (or load from numba's cache) every kernel the scenes use, under every solver:
    circles against circles and boxes, boxes against boxes, free flight. Small scenes, run until
    they touch."""
    for spec, steps in (
        (scenes.ballistic(), 5),
        (scenes.rain(30), 90),
        (scenes.pyramid(4), 30),
    ):
        spec = validate_scene(spec)
        for engine in ENGINES:
            engine.build(spec).run(steps)


@dataclass
class Timing:
    """Seconds per step of one engine on both clocks, its first step's (s), and its mean height
    at the end (m)."""

    cpu: float
    wall: float
    first_cpu: float
    first_wall: float
    mean_y: float


def _idle(n: int) -> None:
    """The timed loop with no engine in it: what the clocks and the loop cost by themselves."""
    for _ in range(n):
        pass


def time_steps(spec: dict, steps: int, engines: list[Engine]) -> dict[str, Timing]:
    """Every engine stepped ``steps`` times from the initial state of ``spec``: seconds per step
    and the mean height of the dynamic bodies at the end (m: a check that all did the same).

    Each engine's first step is timed on its own and kept apart: this engine sets up its
    arrays there (about 1 ms for one body, 8 ms for 210 boxes), a cost of building the world, not
    of stepping it. The other ``steps - 1`` are timed in turns of ``BLOCK`` steps; the engine that
    starts a turn rotates, so none always follows the same one (whose memory traffic it would
    inherit). Each turn also times an empty block; its time (reading the CPU clock is a system
    call of about 1-2 us here, as long as a few of pymunk's free-flight steps) is taken off every
    engine's.
    """
    spec = validate_scene(spec)
    steppers = {e.name: e.build(spec) for e in engines}
    runs = {name: stepper.run for name, stepper in steppers.items()}
    runs[""] = _idle
    names = list(runs)
    cpu = dict.fromkeys(names, 0.0)
    wall = dict.fromkeys(names, 0.0)
    first = {}
    gc.collect()
    for name in names:
        wall_0, cpu_0 = time.perf_counter(), time.thread_time()
        runs[name](1)
        cpu_1, wall_1 = time.thread_time(), time.perf_counter()
        first[name] = (cpu_1 - cpu_0, wall_1 - wall_0)
    done, turn = 1, 0
    while done < steps:
        n = min(BLOCK, steps - done)
        k = turn % len(names)
        for name in names[k:] + names[:k]:
            run = runs[name]
            wall_0, cpu_0 = time.perf_counter(), time.thread_time()
            run(n)
            cpu_1, wall_1 = time.thread_time(), time.perf_counter()
            cpu[name] += cpu_1 - cpu_0
            wall[name] += wall_1 - wall_0
        done += n
        turn += 1
    dynamic = [i for i, b in enumerate(spec["bodies"]) if b["type"] == "dynamic"]
    timed = max(1, steps - 1)
    return {
        name: Timing(
            cpu=(cpu[name] - cpu[""]) / timed,
            wall=(wall[name] - wall[""]) / timed,
            first_cpu=first[name][0] - first[""][0],
            first_wall=first[name][1] - first[""][1],
            mean_y=stepper.mean_y(dynamic),
        )
        for name, stepper in steppers.items()
    }


def case_engines(case: Case) -> list[Engine]:
    """The engines a case steps: all, but those for contact scenes only where nothing touches."""
    return [e for e in ENGINES if case.contacts or not e.contacts_only]


def bench_case(case: Case, quick: bool, clock: str) -> dict:
    spec = case.build()
    steps = case.quick_steps if quick else case.steps
    engines = case_engines(case)
    base = {"bodies": scenes.body_count(spec), "steps": steps, "clock": clock}
    try:
        timings = time_steps(spec, steps, engines)
    except Exception as err:  # a scene an engine cannot run: report it, go on
        traceback.print_exc(limit=3)
        return row(case.name, **base, status=f"error: {err}")
    values = {}
    for name, t in timings.items():
        values[f"{name}_cpu_ms_per_step"] = f"{1e3 * t.cpu:.4g}"
        values[f"{name}_wall_ms_per_step"] = f"{1e3 * t.wall:.4g}"
        values[f"{name}_first_step_cpu_ms"] = f"{1e3 * t.first_cpu:.4g}"
        values[f"{name}_first_step_wall_ms"] = f"{1e3 * t.first_wall:.4g}"
        values[f"{name}_mean_y"] = f"{t.mean_y:.3f}"
    for mine, peer in RATIOS:
        if mine in timings and peer in timings:
            ratio = getattr(timings[mine], clock) / getattr(timings[peer], clock)
            values[f"{mine}_per_{peer}"] = f"{ratio:.3g}"
    return row(case.name, **base, **values)


# ---------------------------------------------------------------- rendering and lessons


def bench_gif() -> dict:
    try:
        from bench_render import bench_render
    except ImportError as err:
        return row("render_gif_500", bodies=500, status=f"skipped: {err}")
    fps = max(bench_render(n_bodies=500, frames=120, size_px=480) for _ in range(2))
    return row("render_gif_500", bodies=500, steps=120, value=f"{fps:.1f}", unit="frames/s")


def bench_lessons(cold: bool = False) -> list[dict]:
    """Wall time of ``sandbox lessons`` (all of them, one subprocess), total and per lesson,
    with the compile cache as it is (warm after the warm-up); ``cold``: only the total, from an
    empty compile cache (a temporary ``NUMBA_CACHE_DIR``), the first run of a class, and the
    part of it the warmup took."""
    env = dict(os.environ)
    with tempfile.TemporaryDirectory() as cache:
        if cold:
            env["NUMBA_CACHE_DIR"] = cache
            # no background warmup after the lessons: it would go on compiling into the cache
            # while it is removed (and beside whatever is timed next)
            env["SANDBOX_WARMUP"] = "off"
        proc, total = time_lessons(env)
    rows = []
    for match in re.finditer(r"^== (\S+): (.+?) in ([0-9.]+) s$", proc.stdout, re.MULTILINE):
        name, status, seconds = match.groups()
        status = "ok" if status == "ok" else f"error: {status}"
        if not cold:
            rows.append(row(f"lesson {name}", value=seconds, unit="s", status=status))
    status = "ok" if proc.returncode == 0 else f"error: exit {proc.returncode}"
    if proc.returncode:
        print("\n".join(proc.stderr.splitlines()[-20:]), file=sys.stderr)
    if cold:
        warmup = re.search(r"^done in ([0-9.]+) s: .* compiled$", proc.stdout, re.M)
        if warmup:  # the warmup the command runs first, on a machine where nothing is compiled
            rows.append(row("warmup_cold_cache", value=warmup.group(1), unit="s", status=status))
        rows.append(row("lessons_total_cold_cache", value=f"{total:.1f}", unit="s", status=status))
        return rows
    rows.append(row("lessons_total", value=f"{total:.1f}", unit="s", status=status))
    return rows


def time_lessons(env: dict[str, str]) -> tuple[subprocess.CompletedProcess, float]:
    """``sandbox lessons`` (all of them, from the checkout) in ``env``: the finished process and
    its wall time (s)."""
    start = time.perf_counter()
    proc = subprocess.run(
        [sys.executable, "-m", "sandbox", "lessons"],
        cwd=ROOT,
        capture_output=True,
        text=True,
        env=env,
    )
    return proc, time.perf_counter() - start


def bench_lessons_shipped() -> list[dict]:
    """Wall time of ``sandbox lessons`` from an empty compile cache with the kernels compiled
    ahead in the package (``python -m sandbox.prebuilt``), as a class's first run from
    that wheel; no row unless the checkout holds them and they run here."""
    from sandbox import prebuilt
    from sandbox.compile_cache import kernel_sources_hash

    if not prebuilt.matches(kernel_sources_hash()):
        return []
    with tempfile.TemporaryDirectory() as cache:
        env = {**os.environ, prebuilt.SWITCH: "on", "NUMBA_CACHE_DIR": cache}
        env["SANDBOX_WARMUP"] = "off"  # as bench_lessons(cold=True)
        proc, total = time_lessons(env)
    status = "ok" if proc.returncode == 0 else f"error: exit {proc.returncode}"
    name = "lessons_total_cold_cache_shipped_kernels"
    return [row(name, value=f"{total:.1f}", unit="s", status=status)]


# ---------------------------------------------------------------- output


def _joined(r: dict, names: list[str], key: str) -> str:
    """One cell holding every engine's ``{name}_{key}`` value, ``-`` where it did not run."""
    if not any(r[f"{n}_{key}"] for n in names):
        return ""
    return " / ".join(r[f"{n}_{key}"] or "-" for n in names)


def format_table(rows: list[dict], clock: str) -> str:
    """A Markdown table of the results: ms per step on ``clock`` for every engine that ran, the
    ratios of this engine's columns to each peer, every engine's mean height at the end, and
    every engine's first step (ms, kept out of the time per step)."""
    names = [e.name for e in ENGINES]
    ratios = [(m, p) for m, p in RATIOS if m in names and p in names]
    head = (
        ["benchmark", "bodies", "steps"]
        + [f"{n} ms/step" for n in names]
        + [f"{m} / {p}" for m, p in ratios]
        + [f"mean y at end (m): {' / '.join(names)}", "first step (ms)", "other"]
    )
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for r in rows:
        other = f"{r['value']} {r['unit']}".strip()
        if r["status"] != "ok":
            other = f"{other} ({r['status']})".strip()
        cells = (
            [r["benchmark"], r["bodies"], r["steps"]]
            + [r[f"{n}_{clock}_ms_per_step"] for n in names]
            + [r[f"{m}_per_{p}"] for m, p in ratios]
            + [_joined(r, names, "mean_y"), _joined(r, names, f"first_step_{clock}_ms"), other]
        )
        lines.append("| " + " | ".join(str(c) for c in cells) + " |")
    return "\n".join(lines)


def write_csv(rows: list[dict], path: Path) -> None:
    with atomic_write(path, "w", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=FIELDS)
        writer.writeheader()
        writer.writerows(rows)


def write_plot(rows: list[dict], path: Path, title: str) -> None:
    """Grouped bars: for each scene, every ratio of this engine's columns to a peer."""
    from matplotlib.figure import Figure

    series = [(m, p) for m, p in RATIOS if any(r[f"{m}_per_{p}"] for r in rows)]
    scenes_ = [r["benchmark"] for r in rows if any(r[f"{m}_per_{p}"] for m, p in series)]
    by_name = {r["benchmark"]: r for r in rows}
    fig = Figure(figsize=(10, 4.8))
    ax = fig.subplots()
    width = 0.8 / max(1, len(series))
    values = []
    for j, (mine, peer) in enumerate(series):
        xs, ys = [], []
        for i, name in enumerate(scenes_):
            cell = by_name[name][f"{mine}_per_{peer}"]
            if cell:
                xs.append(i + (j - 0.5 * (len(series) - 1)) * width)
                ys.append(float(cell))
        values += ys
        bars = ax.bar(xs, ys, width=width, color=f"C{j}", label=f"{mine} / {peer}")
        ax.bar_label(bars, labels=[f"{v:.2f}" for v in ys], fontsize=7)  # 1.04, not 1
    if values and max(values) / min(values) > 8:  # log scale when the ratios span a wide range
        ax.set_yscale("log")
    ax.axhline(1.0, color="k", linewidth=1.0, label="as fast as the peer")
    ax.set_xticks(range(len(scenes_)), scenes_, fontsize=8)
    ax.set_xlabel("scene")
    ax.set_ylabel("time per step, this engine / peer (1)")
    ax.set_title(title, fontsize=8, wrap=True)
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))
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


def make_title(mode: str, clock: str) -> str:
    """What ran (``mode``: "full run", "quick run (--only)", ...) where, and what the table's
    times are."""
    box2d = f"Box2D {BOX2D_VERSION}" if BOX2D_VERSION else "Box2D not installed"
    positions = " (Box2D also 3 position iterations)" if BOX2D_VERSION else ""
    return (
        f"{time.strftime('%Y-%m-%d')}, {mode}: "
        f"Python {platform.python_version()}, pymunk {pymunk.version}, {box2d}, "
        f"{platform.machine()}; dt = 1/60 s, 10 velocity iterations{positions}, "
        f"soft: {SOFT_SUBSTEPS} substeps; times: {CLOCKS[clock]}"
    )


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        description="This engine against pymunk and Box2D 2.3, step for step."
    )
    parser.add_argument("--quick", action="store_true", help="fewer steps, no lesson timing")
    parser.add_argument(
        "--only",
        nargs="*",
        metavar="NAME",
        help="only these step benchmarks, or with no NAME every one, without the render and "
        "lesson timings (print, write nothing)",
    )
    parser.add_argument(
        "--clock",
        choices=sorted(CLOCKS),
        default="cpu",
        help="the time the table shows: cpu (the stepping thread's, default) or wall",
    )
    parser.add_argument("--no-readme", action="store_true", help="leave README.md as it is")
    parser.add_argument(
        "--cold-lessons",
        action="store_true",
        help="also time all lessons from an empty compile cache (about three minutes more), "
        "and again with the kernels compiled ahead if the checkout holds them (sandbox.prebuilt)",
    )
    args = parser.parse_args(argv)

    known = [c.name for c in CASES]
    unknown = [name for name in args.only or [] if name not in known]
    if unknown:
        parser.error(f"--only: unknown benchmark {', '.join(unknown)} (one of {', '.join(known)})")
    if os.environ.get("SANDBOX_JIT") == "0":
        print("SANDBOX_JIT=0: this engine runs uncompiled (plain Python) in this benchmark")
    if BOX2D_MISSING:
        print(f"Box2D skipped: {BOX2D_MISSING} (pip install -e '.[bench]' adds the box2d package)")
    partial = args.only is not None  # --only, even with no name: print, keep the last results
    cases = [c for c in CASES if not args.only or c.name in args.only]
    print("warming up (compiling) ...", flush=True)
    start = time.perf_counter()
    warm_up()
    print(f"warm-up {time.perf_counter() - start:.1f} s", flush=True)
    rows = []
    for case in cases:
        rows.append(bench_case(case, args.quick, args.clock))
        r = rows[-1]
        times = ", ".join(
            f"{e.name} {r[f'{e.name}_{args.clock}_ms_per_step'] or '-'}" for e in ENGINES
        )
        print(f"{case.name}: {times} ms per step ({r['status']})", flush=True)
    if not partial:
        rows.append(bench_gif())
        if not args.quick:
            rows.extend(bench_lessons())
        if args.cold_lessons:
            rows.extend(bench_lessons(cold=True))
            rows.extend(bench_lessons_shipped())

    mode = f"{'quick' if args.quick else 'full'} run{' (--only)' if partial else ''}"
    title = make_title(mode, args.clock)
    table = format_table(rows, args.clock)
    print()
    print(title)
    print(table)
    if not partial:  # a partial run prints only, keeping the last full results
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
