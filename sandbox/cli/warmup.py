"""``sandbox warmup``: compile every kernel ahead of a class (later runs load the machine code)."""

from __future__ import annotations

import argparse

EXAMPLES = """examples:
  sandbox warmup            # once after installing, or after an upgrade: about a minute
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
    cmd.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    """Compile every kernel, saying what is ready."""
    from sandbox.warmup import warm_up, where

    def report(line: str) -> None:
        if not args.quiet:
            print(line, flush=True)

    report(f"compiling the engine into {where()}")
    seconds = warm_up(report)
    report(f"done in {seconds:.1f} s: every kernel is compiled")
    return 0
