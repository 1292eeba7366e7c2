"""``sandbox compare SCENE.json --out DIR``: this engine and pymunk, overlaid."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from sandbox.cli.common import (
    DT,
    STEPS,
    CliError,
    add_settings_options,
    cache_note,
    check_writable,
    field_type,
    input_phase,
    load_spec,
    parse_assignments,
)
from sandbox.fieldspec import Field
from sandbox.settings import CHOICES

# every step of every run is kept to compare them: fewer steps than simulate's streamed runs
COMPARE_STEPS = Field("steps", "integer", "number of steps", STEPS.default, "", lo=0, hi=100_000)

EXAMPLES = """examples:
  sandbox compare scenes/pendulum.json --steps 600 --out compare/
  sandbox compare scenes/stack.json --vary warm_start=false --out stack/   # what warm starting buys
  sandbox compare scenes/drop.json --solver pairwise --vary iterations=2 --no-gif --out drop/
"""


def add_parser(sub) -> None:
    """The ``compare`` command and its options."""
    cmp = sub.add_parser(
        "compare",
        help="this engine and pymunk side by side",
        description="Run a scene in this engine, in pymunk and in variants of this engine;\n"
        "write the traces, an overlaid GIF, deviation and energy plots and a summary.",
        epilog=EXAMPLES,
    )
    cmp.add_argument("scene", metavar="SCENE.json", help="the scene file")
    cmp.add_argument(
        "--steps",
        type=field_type(COMPARE_STEPS, "--steps"),
        default=COMPARE_STEPS.default,
        help=f"number of steps, {COMPARE_STEPS.range_text()} (every step of every run is kept)",
    )
    cmp.add_argument(
        "--dt",
        type=field_type(DT, "--dt"),
        default=None,
        help=f"time step, {DT.range_text()} (default: the scene's dt)",
    )
    cmp.add_argument("--out", required=True, metavar="DIR", help="folder for the outputs")
    for key in ("solver", "orientation", "integrator"):
        cmp.add_argument(
            f"--{key}",
            choices=CHOICES[key],
            action="append",
            help=f"also overlay this engine with settings.{key} set to this (repeatable)",
        )
    cmp.add_argument(
        "--vary",
        action="append",
        default=[],
        metavar="KEY=VALUE",
        help="also overlay this engine with this one setting changed (repeatable), "
        "e.g. --vary warm_start=false",
    )
    add_settings_options(cmp)
    cmp.add_argument("--no-gif", action="store_true", help="skip the animation")
    cmp.set_defaults(func=run)


def variants_of(args: argparse.Namespace) -> dict[str, list]:
    """The overlaid variants: ``--solver/--orientation/--integrator`` and each ``--vary``."""
    variants: dict[str, list] = {k: list(getattr(args, k) or []) for k in CHOICES if k in args}
    for key, value in parse_assignments(args.vary, "--vary"):
        variants.setdefault(key, []).append(value)
    return {k: v for k, v in variants.items() if v}


def run(args: argparse.Namespace) -> int:
    """Run the scene in both engines and write the overlaid figures."""
    from sandbox.cli.simulate import pymunk_note
    from sandbox.compare import compare

    out = Path(args.out)
    if out.exists() and not out.is_dir():
        raise CliError("--out", f"{args.out!r} is not a folder")
    if not out.resolve().parent.is_dir():
        raise CliError("--out", f"folder {str(out.resolve().parent)!r} does not exist")
    check_writable("--out", out if out.is_dir() else out.resolve().parent)
    variants = variants_of(args)
    with input_phase():
        spec = load_spec(args.scene, args)
    cache_note()
    compare(spec, args.steps, out, variants=variants, gif=not args.no_gif)
    note = pymunk_note(spec)  # after the run: a scene pymunk cannot express is one error line
    if note:
        print(note, file=sys.stderr)
    return 0
