"""``sandbox schema``: print the JSON Schema of scene files."""

from __future__ import annotations

import argparse
import sys

EXAMPLES = """examples:
  sandbox schema > scene.schema.json
  # then begin a scene with "$schema": "scene.schema.json" for completion in an editor
"""


def add_parser(sub) -> None:
    """The ``schema`` command."""
    cmd = sub.add_parser(
        "schema",
        help="print the JSON Schema of scene files",
        description="Print the JSON Schema (draft 2020-12) of scene files: every field, its\n"
        "type, unit and valid range. Editors use it to complete and check scene files.",
        epilog=EXAMPLES,
    )
    cmd.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    """Write the schema to standard output."""
    from sandbox.schema import schema_text

    sys.stdout.write(schema_text())
    return 0
