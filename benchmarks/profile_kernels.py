"""Where the one compiled step spends its time, function by function (Linux ``perf``).

    python benchmarks/profile_kernels.py [--scene rain_5000] [--settle 150] [--steps 300]
                                         [--top 25]

``profile_step.py`` times the stages, each called from Python; inside the one-call step
(``sandbox.step.fast_step``) it cannot see which compiled function the time goes to. This script
samples the process with ``perf record`` while the world steps, and names the samples' machine
code: numba's compiled functions have no symbols a profiler can read, so the script writes the
address of every function of every compiled library into ``/tmp/perf-<pid>.map`` (the map
``perf report`` reads for code made at run time). Loaded from numba's cache, a function's name
is not kept, so the engine is compiled afresh in this process, into a temporary cache: about a
minute before the sampling starts.

``--scene`` is any scene of ``ab.py`` (the benchmark scenes, their soft versions, the
chains). The world steps ``--settle`` steps first, then ``--steps`` under ``perf`` (the garbage
collector frozen, so that it does not run while sampling). Each row gives a function's share of
the samples and that share of the measured time per step. A function numba inlined into its
caller counts as the caller. Samples outside the engine's compiled functions (numba's runtime,
the interpreter, numpy, the operating system) are summed in one row, its largest named below.

Found on the rain of 5,000 discs (steps 150 to 450), the project's 2-core machine: the
position passes (``penetration.position_impulses``) 19 % of the step; the velocity sweeps'
visits (in ``iterative.coloured_sweeps``) 14 %, and their copies of the bodies' velocities into
and out of the lanes (``wide.lanes_in``, ``wide.lanes_out``) 13 % (now each lane takes them
from the lane that last held them: ``handoff.hand_in`` 10 %, ``handoff.plan`` 2 %); the prepare
9 %; the narrowphase 8 %. It also found numba's reference counts (``NRT_incref``, ``NRT_decref``) at 5 %
of the step: the narrowphase's per-pair function reference-counted the polygons' array on
every call; inlined, and two circles kept off that array, they are gone.
"""

from __future__ import annotations

import argparse
import gc
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from ab import SCENES, scene_named  # benchmarks/ab.py, beside this file: its scenes

OTHER = "(numba's runtime, Python, libraries)"


def readable(symbol: str) -> str:
    """``sandbox.solvers.wide.lanes_in`` for numba's mangled
    ``_ZN7sandbox7solvers4wide8lanes_inB4v181B38c8t...E5Array...`` (the name's parts, each
    prefixed by its length, up to the version tag ``B``); any other symbol as it is."""
    if not symbol.startswith("_ZN"):
        return symbol
    parts, at = [], 3
    while at < len(symbol) and symbol[at].isdigit():
        digits = re.match(r"\d+", symbol[at:]).group()
        at += len(digits)
        parts.append(symbol[at : at + int(digits)])
        at += int(digits)
    return ".".join(parts) if parts else symbol


def write_symbol_map(path: Path) -> int:
    """Every function of every compiled library in this process, at its address, as a perf
    map (``start size name``, hex; a function's size taken to the next function's address).
    Returns how many functions were written."""
    from numba.core.dispatcher import Dispatcher

    entries: dict[int, str] = {}
    for obj in gc.get_objects():
        if not isinstance(obj, Dispatcher):
            continue
        for compiled in list(obj.overloads.values()):
            library = compiled.library
            try:
                functions = list(library._final_module.functions)
            except Exception:  # loaded from the cache: no module, no names
                continue
            for fn in functions:
                if fn.is_declaration:
                    continue
                try:
                    address = library.get_pointer_to_function(fn.name)
                except Exception:
                    continue
                if address:
                    entries[address] = fn.name
    addresses = sorted(entries)
    with open(path, "w") as f:
        for i, start in enumerate(addresses):
            size = min(addresses[i + 1] - start if i + 1 < len(addresses) else 4096, 1 << 20)
            if entries[start].startswith("NRT_"):  # the runtime's reference counts: a few
                size = min(size, 256)  # instructions; what follows is not theirs
            f.write(f"{start:x} {size:x} {entries[start]}\n")
    return len(addresses)


def shares(report: str) -> tuple[dict[str, float], list[tuple[str, float]]]:
    """Percent of the samples by function, from ``perf report --sort symbol --stdio`` text
    (numba's functions by :func:`readable` name; every other symbol summed as :data:`OTHER`),
    and the other symbols, largest first."""
    found: dict[str, float] = {}
    other: list[tuple[str, float]] = []
    for line in report.splitlines():
        match = re.match(r"\s*([0-9.]+)%\s+\[([.k])\]\s+(\S+)", line)
        if match is None:
            continue
        percent, symbol = float(match.group(1)), match.group(3)
        if symbol.startswith("_ZN"):
            name = readable(symbol)
        else:
            name = OTHER
            other.append((symbol, percent))
        found[name] = found.get(name, 0.0) + percent
    return found, other


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scene", choices=SCENES, default="rain_5000")
    parser.add_argument("--settle", type=int, default=150, help="steps before the sampling")
    parser.add_argument("--steps", type=int, default=300, help="steps sampled")
    parser.add_argument("--top", type=int, default=25, help="functions listed")
    args = parser.parse_args()
    if shutil.which("perf") is None:
        print("error: perf (Linux's profiler, the linux-perf package) is not installed")
        return 2
    if "NUMBA_CACHE_DIR" not in os.environ:  # compile afresh, so that every function has a name
        with tempfile.TemporaryDirectory() as cache:
            env = dict(os.environ, NUMBA_CACHE_DIR=cache)
            return subprocess.run([sys.executable, *sys.argv], env=env).returncode
    from sandbox.build import build_world
    from sandbox.scene import validate_scene

    world = build_world(validate_scene(scene_named(args.scene)))
    print(f"compiling the engine in this process (about a minute), then {args.settle} steps")
    for _ in range(args.settle):
        world.step()
    symbols = Path(f"/tmp/perf-{os.getpid()}.map")
    count = write_symbol_map(symbols)
    gc.collect()  # before the sampling: the collector then sleeps through it
    gc.freeze()
    gc.disable()
    with tempfile.TemporaryDirectory() as tmp:
        data = Path(tmp) / "perf.data"
        perf = subprocess.Popen(
            ["perf", "record", "-q", "-F", "4000", "-p", str(os.getpid()), "-o", str(data)],
            stdout=subprocess.DEVNULL,
            stderr=subprocess.PIPE,
            text=True,
        )
        time.sleep(1.0)  # perf attached
        if perf.poll() is not None:
            print(f"error: perf record: {perf.stderr.read().strip().splitlines()[-1:]}")
            return 1
        start = time.perf_counter()
        for _ in range(args.steps):
            world.step()
        per_step = (time.perf_counter() - start) / args.steps
        gc.enable()
        perf.send_signal(signal.SIGINT)
        perf.wait()
        report = subprocess.run(
            ["perf", "report", "-i", str(data), "--no-children", "--sort", "symbol", "--stdio"],
            capture_output=True,
            text=True,
        ).stdout
    symbols.unlink(missing_ok=True)
    found, other = shares(report)
    print(
        f"{args.scene}: {1e3 * per_step:.2f} ms a step while sampled (steps {args.settle} to "
        f"{args.settle + args.steps}), {count} compiled functions mapped\n"
    )
    print(f"{'function':58s} {'samples':>8s} {'us/step':>8s}")
    for name, percent in sorted(found.items(), key=lambda kv: -kv[1])[: args.top]:
        print(f"{name:58s} {percent:7.1f}% {10 * percent * per_step * 1e3:8.0f}")
    largest = ", ".join(f"{symbol[:40]} {percent:.1f} %" for symbol, percent in other[:6])
    print(f"\n{OTHER}, largest: {largest}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
