"""The command line: ``sandbox simulate | compare | lessons | scenes | schema | warmup`` (also
``python -m sandbox``).

One module per command (``sandbox/cli/<command>.py``, each with ``add_parser`` and ``run``);
this one assembles the parser, and :mod:`sandbox.cli.exits` turns every way a command can end
into an exit status and at most one line on stderr.

Bad input exits with status 2 and one line on stderr, ``error: <field path>: <what is wrong>``,
and writes no output file. A run that fails after validation (divergence, disk full, out of
memory, ...) exits 1 with one ``error:`` line and writes nothing either: the outputs of one
command are written as a set (:func:`sandbox.atomic.output_set`). Ctrl-C exits 130 and SIGTERM
143, quietly, removing temporary files. ``SANDBOX_DEBUG=1`` adds the traceback.
"""

from __future__ import annotations

import argparse
import sys

from sandbox.cli import compare, lessons, scenes, schema, simulate, warmup
from sandbox.cli.common import CliError, Parser, settle_matplotlib_config
from sandbox.cli.exits import run_command

COMMANDS = (simulate, compare, lessons, scenes, schema, warmup)

EXAMPLES = """examples:
  sandbox simulate scenes/drop.json --steps 240 --gif drop.gif
  sandbox compare scenes/stack.json --vary warm_start=false --out stack/
  sandbox lessons 01 07
  sandbox scenes --copy my_scenes/
  sandbox schema > scene.schema.json
  sandbox warmup                       # compile the engine once, ahead of a class

sandbox COMMAND --help shows each command's options and examples."""

__all__ = ["CliError", "build_parser", "main"]


def build_parser() -> argparse.ArgumentParser:
    """The ``sandbox`` parser with every command."""
    from sandbox import __version__

    parser = Parser(
        prog="sandbox",
        description="A 2D physics sandbox for teaching.",
        epilog=EXAMPLES,
    )
    parser.add_argument("--version", action="version", version=f"sandbox {__version__}")
    sub = parser.add_subparsers(
        dest="command", required=True, parser_class=Parser, metavar="COMMAND"
    )
    for command in COMMANDS:
        command.add_parser(sub)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Entry point; returns the exit status (0 done, 1 run failed, 2 bad input, 130 Ctrl-C)."""

    def command() -> int:
        try:
            args = build_parser().parse_args(argv)
        except SystemExit as done:  # --help and --version print, then stop here
            return int(done.code or 0)
        settle_matplotlib_config()
        return args.func(args)

    return run_command(command)


if __name__ == "__main__":
    sys.exit(main())
