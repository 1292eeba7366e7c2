"""Where the first run's compile time goes: numba's stages, and the compiled functions that cost
the most.

    python benchmarks/compile_profile.py [--family "iterative solver" ...] [--top 20] [--list]

It compiles the warmup's families (``sandbox.warmup``: small worlds of every kind, stepped a
few times) afresh, into a temporary cache, and times each stage of numba's compiler without
what it calls (a stage that compiles a callee is not charged for it):

- type inference, inlining of ``inline="always"`` functions, lowering to LLVM IR, the Python
  entry of each function (numba's own Python);
- LLVM: parsing the IR, the passes over each function, the passes over the whole module with
  every callee linked in, and the machine code (LLVM's C++).

Each compiled function is a library of its own, and its machine code is made from its own IR
with the IR of every function it calls linked in, optimized again as one module. A stage that
calls ten functions re-optimizes and compiles all ten once more, and the one-call step all of
its stages. The table of functions lists the costliest libraries with the functions their
final module holds (its own and those linked in) and the libraries linked. The line "each
function through LLVM's module passes and machine code N times" says how often, on the
average, a function's code went through them. The last line names the functions compiled
twice, with numba's Python entry and without (``sandbox.jit.Kernel``): called from Python as
well as from compiled code, each should be marked ``@njit(python=True)``.

Found with it (numba 0.68, the project's 2-core machine, an empty cache): the iterative
solver's family compiles 248 libraries in 48 to 68 s, as the hour goes. LLVM takes about half
(module passes 18 %, machine code 16 %, function passes 9 %, parsing 5 %), numba's own Python
the rest (lowering 18 %, type inference 14 %, its other passes 11 %, inlining 7 %). Each
function's code goes through the module passes and machine code 3.1 times: 1,493 functions in
the final modules, 486 written. The one-call step's library holds 104 of them (2.7 MB of IR,
3.0 s of LLVM), the position stage's 32 (1.0 s). Inlining the single-caller functions that run
once a step (``inline="always"``: the sweep's choice of direction, the position stage's
ordering, the islands' sleep; tried, not kept) took 11 libraries out of 287 (with the soft
step's family) and 2.5 s out of 76 (3 %): numba then typed and lowered what LLVM no longer
compiled twice.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

# (where, method, stage): numba's methods timed, each without the time of the stages it calls
STAGES = (
    ("numba.core.typed_passes:BaseTypeInference", "run_pass", "type inference"),
    ("numba.core.untyped_passes:InlineInlinables", "run_pass", "inlining (numba IR)"),
    ("numba.core.typed_passes:NativeLowering", "run_pass", "lowering to LLVM IR"),
    ("numba.core.lowering:BaseLower", "create_cpython_wrapper", "Python entries"),
    ("numba.core.compiler:CompilerBase", "_compile_core", "numba's other passes"),
    ("numba.core.codegen:CPUCodeLibrary", "add_ir_module", "LLVM: parsing the IR"),
    ("numba.core.codegen:CPUCodeLibrary", "_optimize_functions", "LLVM: function passes"),
    ("numba.core.codegen:CPUCodeLibrary", "_optimize_final_module", "LLVM: module passes"),
    ("numba.core.codegen:JITCodeLibrary", "_finalize_specific", "LLVM: machine code"),
)
PARSING = STAGES[-4][2]
MODULE_PASSES, MACHINE_CODE = STAGES[-2][2], STAGES[-1][2]  # charged to each library too


class Clock:
    """Exclusive times of the wrapped methods (``seconds[stage]``, ``calls[stage]``) and, for
    each code library, the seconds of its module passes and machine code and the size of its
    final module (``libraries[id]``)."""

    def __init__(self) -> None:
        self.seconds, self.calls = Counter(), Counter()
        self.inner: list[float] = []
        self.libraries: dict[int, dict] = {}
        self.own = 0  # functions defined in the libraries' own IR

    def wrap(self, owner, method: str, stage: str) -> None:
        original = getattr(owner, method)

        def timed(this, *args, **kwargs):
            if stage == MODULE_PASSES:  # the final module as it comes, callees linked in
                self.size(this)
            elif stage == PARSING:  # a library's own IR: the functions it defines
                self.own += sum(1 for f in args[0].functions if not f.is_declaration)
            start = time.perf_counter()
            self.inner.append(0.0)
            try:
                return original(this, *args, **kwargs)
            finally:
                spent = time.perf_counter() - start
                own = spent - self.inner.pop()
                self.seconds[stage] += own
                self.calls[stage] += 1
                if self.inner:
                    self.inner[-1] += spent
                if stage in (MODULE_PASSES, MACHINE_CODE):  # `this` is a code library
                    self.entry(this)["s"] += own

        setattr(owner, method, timed)

    def entry(self, library) -> dict:
        return self.libraries.setdefault(id(library), {"name": library.name, "s": 0.0})

    def size(self, library) -> None:
        """The functions defined in ``library``'s final module, its kB of IR, and how many
        libraries were linked into it."""
        entry, module = self.entry(library), library._final_module
        entry["functions"] = sum(1 for f in module.functions if not f.is_declaration)
        entry["kb"] = len(str(module)) // 1000
        entry["linked"] = len({id(linked) for linked in library._linking_libraries})


def install(clock: Clock) -> None:
    """Wrap numba's stages (:data:`STAGES`); a numba without one of them says so in one line."""
    import importlib

    for where, method, stage in STAGES:
        module_name, class_name = where.split(":")
        owner = getattr(importlib.import_module(module_name), class_name, None)
        if owner is None or not hasattr(owner, method):
            raise SystemExit(f"error: this numba has no {where}.{method} to time ({stage})")
        clock.wrap(owner, method, stage)


def owners() -> dict[int, str]:
    """Each compiled library's function, ``module.name``, from the dispatchers in memory."""
    import gc

    from numba.core.registry import CPUDispatcher

    found = {}
    for thing in gc.get_objects():
        if isinstance(thing, CPUDispatcher):
            function = thing.py_func
            for result in thing.overloads.values():
                found[id(result.library)] = f"{function.__module__}.{function.__qualname__}"
    return found


def target(families: list[str], top: int) -> int:
    """In the process with the empty cache: compile ``families`` and print the tables."""
    clock = Clock()
    install(clock)
    from sandbox import warmup

    start = time.perf_counter()  # building the worlds compiles some kernels too
    chosen = [family for family in warmup.every_world() if family[0] in families]
    warmup.warm_families(chosen, report=lambda line: None)
    total = time.perf_counter() - start
    print(report(clock, owners(), families, total, top))
    twice = compiled_both_ways()
    print(f"\ncompiled for Python and again for compiled callers: {', '.join(twice) or 'none'}")
    return 0


def compiled_both_ways() -> list[str]:
    """The functions compiled twice, with numba's Python entry and without
    (:class:`sandbox.jit.Kernel`): each is called both from Python and from compiled code, and
    should be marked ``@njit(python=True)`` to share one version."""
    import gc

    from sandbox.jit import Kernel

    return sorted(
        f"{thing.py_func.__module__}.{thing.py_func.__qualname__}"
        for thing in gc.get_objects()
        if isinstance(thing, Kernel) and thing.compiled_both_ways
    )


def report(clock: Clock, names: dict[int, str], families, total: float, top: int) -> str:
    """The stages' table, the duplication line and the costliest libraries' table."""
    libraries = clock.libraries
    lines = [f"{', '.join(families)}: {total:.1f} s, {len(libraries)} libraries compiled", ""]
    lines.append(f"{'stage':34s} {'s':>7s} {'share':>6s} {'calls':>6s}")
    for stage, seconds in clock.seconds.most_common():
        share = f"{seconds / total:.0%}"
        lines.append(f"{stage:34s} {seconds:7.1f} {share:>6s} {clock.calls[stage]:6d}")
    rest = total - sum(clock.seconds.values())
    lines.append(f"{'(stepping, caching, Python)':34s} {rest:7.1f} {rest / total:6.0%}")
    compiled = sum(entry.get("functions", 0) for entry in libraries.values())
    lines += [
        "",
        f"each function through LLVM's module passes and machine code "
        f"{compiled / max(clock.own, 1):.1f} times on the average",
    ]
    lines += [
        f"({compiled} functions in the libraries' final modules, {clock.own} in their own IR)",
        "",
    ]
    lines.append(f"{'library':56s} {'LLVM s':>7s} {'functions':>9s} {'IR kB':>7s} {'links':>5s}")
    costly = sorted(libraries.items(), key=lambda item: -item[1]["s"])[:top]
    for key, entry in costly:
        name = names.get(key, entry["name"]).removeprefix("sandbox.")
        lines.append(
            f"{name[:56]:56s} {entry['s']:7.2f} {entry.get('functions', 0):9d}"
            f" {entry.get('kb', 0):7d} {entry.get('linked', 0):5d}"
        )
    return "\n".join(lines)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--family",
        action="append",
        help="a family of sandbox.warmup (repeat for more; default: iterative solver)",
    )
    parser.add_argument("--top", type=int, default=20, help="libraries listed")
    parser.add_argument("--list", action="store_true", help="list the families and stop")
    parser.add_argument("--target", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args()
    families = args.family or ["iterative solver"]
    if args.target:
        return target(families, args.top)
    from sandbox.warmup import every_world

    known = [family[0] for family in every_world()]
    if args.list:
        print("\n".join(known))
        return 0
    unknown = [name for name in families if name not in known]
    if unknown:
        print(f"error: --family: no family {unknown[0]!r} (python {__file__} --list)")
        return 2
    with tempfile.TemporaryDirectory() as cache:
        env = dict(os.environ, NUMBA_CACHE_DIR=cache, SANDBOX_WARMUP="off")
        command = [sys.executable, __file__, "--target", "--top", str(args.top)]
        command += [part for name in families for part in ("--family", name)]
        print("compiling afresh into an empty cache (about a minute a family)", flush=True)
        return subprocess.run(command, env=env).returncode


if __name__ == "__main__":
    sys.exit(main())
