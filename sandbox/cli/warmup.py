"""``sandbox warmup``: compile every kernel ahead of a class (later runs load the machine code)."""

from __future__ import annotations

import argparse

from sandbox.cli.common import field_type
from sandbox.fieldspec import Field

JOBS = Field("jobs", "integer", "processes compiling at a time", None, "", lo=1, hi=64)

EXAMPLES = """examples:
  sandbox warmup            # once after installing, or after an upgrade: one to two minutes
  sandbox warmup --jobs 1   # in one process (the default shares it between two cores)
  sandbox warmup --lessons  # only what the bundled lessons need (about a minute)
"""


def add_parser(sub) -> None:
    """The ``warmup`` command."""
    cmd = sub.add_parser(
        "warmup",
        help="compile every kernel ahead of time",
        description="Compile every kernel of the engine for this machine, once, so that later "
        "runs start at once. On a terminal, a progress bar over the families of kernels; "
        "otherwise one line per family ready.",
        epilog=EXAMPLES,
    )
    cmd.add_argument("--quiet", action="store_true", help="print nothing (a background warmup)")
    cmd.add_argument(
        "--jobs",
        type=field_type(JOBS, "--jobs"),
        help="processes to share the compiling between (default: 2 on two cores or more)",
    )
    cmd.add_argument(
        "--lessons",
        action="store_true",
        help="compile only what the bundled lessons need (a first `sandbox lessons` does this, "
        "then the rest in the background); the cache is not marked warm",
    )
    cmd.add_argument("--part", type=_part, help=argparse.SUPPRESS)  # I/N: one share, unmarked
    cmd.set_defaults(func=run)


def _part(text: str) -> tuple[int, int]:
    """``I/N`` (0 <= I < N): the share a helper process of a warmup compiles."""
    try:
        index, parts = (int(x) for x in text.split("/"))
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected I/N, got {text!r}") from None
    if not 0 <= index < parts:
        raise argparse.ArgumentTypeError(f"expected 0 <= I < N, got {text!r}")
    return index, parts


def run(args: argparse.Namespace) -> int:
    """Compile every kernel, saying what is ready: on a terminal one progress bar over the
    families, else one line per family (and never the compile notice of a first run: this
    says what it compiles itself)."""
    import sys

    from sandbox.compile_cache import own_processor

    own_processor()  # for this very processor, not the kernels shipped in the package
    from sandbox.jit import compiling_process, quiet_compiles
    from sandbox.warmup import warm_part, warm_up, where

    quiet_compiles()
    compiling_process()
    if args.part is not None:  # a share of another warmup, which marks the cache warm
        warm_part(*args.part, (lambda line: None) if args.quiet else _print, args.lessons)
        return 0
    if args.quiet:
        warm_up(lambda line: None, args.jobs, args.lessons)
        return 0
    from sandbox.cli.first_run import wait_for_warmup
    from sandbox.compile_cache import CACHE_FOLDER

    wait_for_warmup(CACHE_FOLDER)  # then this one loads what it compiled
    print(f"compiling the engine into {where()}", flush=True)
    if sys.stderr.isatty():
        with FamilyBar(sys.stderr, lessons=args.lessons) as bar:
            seconds = warm_up(bar.ready, args.jobs, args.lessons)
    else:
        seconds = warm_up(_print, args.jobs, args.lessons)
    what = "the lessons' kernels are" if args.lessons else "every kernel is"
    print(f"done in {seconds:.1f} s: {what} compiled", flush=True)
    return 0


def _print(line: str) -> None:
    print(line, flush=True)


class FamilyBar:
    """A progress bar on ``screen`` (a terminal) over the families the warmup steps
    (:class:`sandbox.cli.progress.TickingBar`), moved by each ``"  <family>: ready"`` line
    (:func:`sandbox.warmup.warm_up`'s report), showing the last family ready and how many
    kernels this process has compiled: the first family alone compiles for most of a minute."""

    def __init__(self, screen, tick: float = 1.0, lessons: bool = False) -> None:
        from sandbox.cli.progress import TickingBar
        from sandbox.jit import CompileCount
        from sandbox.warmup import worlds

        self.kernels = CompileCount()
        self.last = ""
        total = sum(1 for _ in worlds(lessons))
        self.bar = TickingBar(screen, total, "families", self._postfix, tick)

    def _postfix(self) -> str:
        compiled = f"{self.kernels.count} kernels compiled"
        return f"{self.last} ready, {compiled}" if self.last else compiled

    def ready(self, line: str) -> None:
        self.last = line.strip().removesuffix(": ready")
        self.bar.advance()

    def __enter__(self) -> FamilyBar:
        return self

    def __exit__(self, *exc: object) -> None:
        self.bar.__exit__(*exc)
        self.kernels.close()
