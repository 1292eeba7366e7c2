"""``sandbox warmup``: compile every kernel ahead of a class (later runs load the machine code)."""

from __future__ import annotations

import argparse

from sandbox.cli.common import field_type
from sandbox.fieldspec import Field

JOBS = Field("jobs", "integer", "processes compiling at a time", None, "", lo=1, hi=64)

EXAMPLES = """examples:
  sandbox warmup            # once after installing, or after an upgrade: one to two minutes
  sandbox warmup --jobs 1   # in one process (the default shares it between two cores)
"""


def add_parser(sub) -> None:
    """The ``warmup`` command."""
    cmd = sub.add_parser(
        "warmup",
        help="compile every kernel ahead of time",
        description="Compile every kernel of the engine for this machine, once, so that later "
        "runs start at once.",
        epilog=EXAMPLES,
    )
    cmd.add_argument("--quiet", action="store_true", help="print nothing (a background warmup)")
    cmd.add_argument(
        "--jobs",
        type=field_type(JOBS, "--jobs"),
        help="processes to share the compiling between (default: 2 on two cores or more)",
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
    """Compile every kernel, saying what is ready."""
    from sandbox.warmup import warm_up, where

    if args.quiet:
        from sandbox.jit import quiet_compiles

        quiet_compiles()

    def report(line: str) -> None:
        if not args.quiet:
            print(line, flush=True)

    if args.part is not None:  # a share of another warmup, which marks the cache warm
        from sandbox.warmup import warm_part

        warm_part(*args.part, report)
        return 0
    report(f"compiling the engine into {where()}")
    seconds = warm_up(report, args.jobs)
    report(f"done in {seconds:.1f} s: every kernel is compiled")
    return 0
