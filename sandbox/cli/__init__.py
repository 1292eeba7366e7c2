"""The command line: ``sandbox simulate | compare | lessons | scenes | schema`` (also
``python -m sandbox``).

One module per command (``sandbox/cli/<command>.py``, each with ``add_parser`` and ``run``);
this one assembles the parser and turns every failure into one ``error:`` line.

Bad input exits with status 2 and one line on stderr, ``error: <field path>: <what is wrong>``,
and writes no output file.
"""

from __future__ import annotations

import argparse
import os
import sys

from sandbox.cli import compare, lessons, scenes, schema, simulate
from sandbox.cli.common import CliError, Parser

COMMANDS = (simulate, compare, lessons, scenes, schema)

EXAMPLES = """examples:
  sandbox simulate scenes/drop.json --steps 240 --gif drop.gif
  sandbox compare scenes/stack.json --vary warm_start=false --out stack/
  sandbox lessons 01 07
  sandbox scenes --copy my_scenes/
  sandbox schema > scene.schema.json

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
    """Entry point; returns the exit status (2 for bad input)."""
    from sandbox.scene import SceneError

    parser = build_parser()
    try:
        try:
            args = parser.parse_args(argv)
        except SystemExit as done:  # --help and --version print, then stop here
            return int(done.code or 0)
        return args.func(args)
    except (CliError, SceneError) as err:
        path = err.path or "scene"  # a problem with the whole document
        print(f"error: {path}: {err.message}", file=sys.stderr)
        return 2
    except ValueError as err:  # a setting or value the world itself refused
        print(f"error: {err}", file=sys.stderr)
        return 2
    except BrokenPipeError:  # output piped into e.g. `head`, which stopped reading
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())  # no error at exit
        return 0


if __name__ == "__main__":
    sys.exit(main())
