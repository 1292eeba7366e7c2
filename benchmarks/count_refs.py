"""How often numba's runtime counts references while the world steps, function by function
(Linux, with ``gdb``).

    python benchmarks/count_refs.py [--scene pyramid_40] [--settle 200] [--steps 4] [--top 15]

numba keeps every array alive with a reference count in its memory record, raised
(``NRT_incref``) and lowered (``NRT_decref``) by an atomic add: a few nanoseconds each, so
nothing to see once a step, and a tenth of the step when it happens at every contact. A
compiled function counts a reference when an array becomes a new variable: an array argument
of a function numba inlines (``inline="always"``) at every call, an array picked from a tuple
by a number, and often an array argument of a function called in a loop. numba removes most
of the pairs again, but not those inside a large loop body with branches. Records (one row of
a record array) are not counted: the per-contact and per-pair functions take their bodies'
and shapes' records, not the arrays.

``perf`` (``profile_kernels.py``) shows the counting as time in ``NRT_incref`` and
``NRT_decref``; this script says who calls them. It compiles the engine afresh (into a
temporary cache, about a minute, so that every function has a name), steps ``--settle`` steps,
then has ``gdb`` stop at both functions for ``--steps`` steps and note each call's return
address, which the compiled functions' addresses (``profile_kernels.write_symbol_map``) name.
The caller is the compiled function the call is written in: a function numba inlined counts as
its caller. ``--scene``: any scene of ``ab.py``.

Found with it (numba 0.68): the pyramid of base 40 counted 9,532 references a step, the
narrowphase's two arrays at each of its 2,380 pairs of boxes; the soft pyramid of 20 4,768
more in its passes over the contacts; the rain of 100, 455 of its 770 in the hand-off of
velocities between lanes (a tuple of arrays picked by a number at every group). Each is gone:
records instead of the arrays, one array instead of the tuple, and for the polygons' placed
vertices, which the polygon functions need whole, a view numba does not count
(``sandbox/borrowed.py``). Left: the counts once a call of each stage.
"""

from __future__ import annotations

import argparse
import bisect
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from collections import Counter
from pathlib import Path

from ab import SCENES, scene_named  # benchmarks/ab.py, beside this file: its scenes
from profile_kernels import readable, write_symbol_map

# run by gdb inside itself: a breakpoint at each counting function that notes the return
# address (the word at the stack pointer, on entry) and goes on
GDB_SCRIPT = """
import gdb, json
calls = {}
class Count(gdb.Breakpoint):
    def stop(self):
        sp = int(gdb.parse_and_eval("$sp"))
        back = int(gdb.parse_and_eval(f"*(unsigned long *) {sp}"))
        key = f"{self.kind} {back}"
        calls[key] = calls.get(key, 0) + 1
        return False
for line in open(MAP):
    start, size, name = line.split(" ", 2)
    name = name.strip()
    if name in ("NRT_incref", "NRT_decref"):
        Count(f"*0x{start}", internal=True).kind = name
def report(event):
    json.dump(calls, open(OUT, "w"))
gdb.events.exited.connect(report)
open(GO, "w").close()
"""


def target(scene: str, settle: int, steps: int, folder: Path) -> int:
    """The stepping process: compile, settle, map the functions, wait for gdb, step."""
    from sandbox.build import build_world
    from sandbox.scene import validate_scene

    world = build_world(validate_scene(scene_named(scene)))
    for _ in range(settle):
        world.step()
    write_symbol_map(folder / "functions.map")
    print(f"ready {os.getpid()}", flush=True)
    while not (folder / "go").exists():  # gdb has set its breakpoints
        time.sleep(0.1)
    for _ in range(steps):
        world.step()
    return 0


def callers(calls: dict[str, int], functions: Path) -> Counter:
    """(kind, function) -> calls, each return address named by the function it lies in."""
    rows = []
    for line in functions.read_text().splitlines():
        start, size, name = line.split(" ", 2)
        rows.append((int(start, 16), int(size, 16), name.strip()))
    rows.sort()
    starts = [row[0] for row in rows]
    found: Counter = Counter()
    for key, count in calls.items():
        kind, back = key.split()
        address = int(back)
        i = bisect.bisect_right(starts, address) - 1
        inside = i >= 0 and address < rows[i][0] + rows[i][1]
        found[(kind, readable(rows[i][2]) if inside else hex(address))] += count
    return found


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scene", choices=SCENES, default="pyramid_40")
    parser.add_argument("--settle", type=int, default=200, help="steps before the counting")
    parser.add_argument("--steps", type=int, default=4, help="steps counted")
    parser.add_argument("--top", type=int, default=15, help="functions listed")
    parser.add_argument("--target", type=Path, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.target is not None:
        return target(args.scene, args.settle, args.steps, args.target)
    if shutil.which("gdb") is None:
        print("error: gdb (the GNU debugger, the gdb package) is not installed")
        return 2
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        env = dict(os.environ, NUMBA_CACHE_DIR=str(folder / "cache"))
        command = [sys.executable, __file__, "--scene", args.scene, "--settle", str(args.settle)]
        command += ["--steps", str(args.steps), "--target", str(folder)]
        print(f"compiling the engine afresh (about a minute), then {args.settle} steps")
        stepping = subprocess.Popen(command, env=env, stdout=subprocess.PIPE, text=True)
        line = stepping.stdout.readline()
        if not line.startswith("ready"):
            stepping.wait()
            print("error: the stepping process stopped before it was ready")
            return 1
        names = {"MAP": folder / "functions.map", "OUT": folder / "calls.json"}
        names["GO"] = folder / "go"
        script = folder / "count.py"
        script.write_text(
            "".join(f"{key} = {str(value)!r}\n" for key, value in names.items()) + GDB_SCRIPT
        )
        pid = line.split()[1]
        gdb = ["gdb", "-q", "-batch", "-p", pid, "-ex", f"source {script}", "-ex", "continue"]
        subprocess.run(gdb, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        stepping.wait()
        if not names["OUT"].exists():
            print("error: gdb could not attach (ptrace not allowed?)")
            return 1
        found = callers(json.loads(names["OUT"].read_text()), names["MAP"])
    per_step = {key: count / args.steps for key, count in found.items()}
    total = sum(per_step.values())
    print(f"{args.scene}: {total:,.0f} reference counts a step (steps {args.settle} on)\n")
    print(f"{'function':58s} {'raised':>9s} {'lowered':>9s}")
    functions = Counter()
    for (_kind, name), count in per_step.items():
        functions[name] += count
    for name, _ in functions.most_common(args.top):
        up, down = per_step.get(("NRT_incref", name), 0), per_step.get(("NRT_decref", name), 0)
        print(f"{name[:58]:58s} {up:9,.0f} {down:9,.0f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
