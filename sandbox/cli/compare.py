"""``sandbox compare SCENE.json --out DIR``: this engine and pymunk, overlaid."""

from __future__ import annotations

import argparse
from pathlib import Path

from sandbox.cli.common import (
    CliError,
    cache_note,
    check_writable,
    input_phase,
    load_spec,
    positive_float,
    steps_count,
)
from sandbox.settings import CHOICES

MAX_COMPARE_STEPS = 100_000


def add_parser(sub) -> None:
    """The ``compare`` command and its options."""
    cmp = sub.add_parser("compare", help="this engine and pymunk side by side")
    cmp.add_argument("scene", metavar="SCENE.json")
    cmp.add_argument(
        "--steps",
        type=steps_count(MAX_COMPARE_STEPS),
        default=300,
        help=f"0 to {MAX_COMPARE_STEPS:,} (every step of every run is kept to compare them)",
    )
    cmp.add_argument("--dt", type=positive_float, default=None)
    cmp.add_argument("--out", required=True, metavar="DIR")
    for key in ("solver", "orientation", "integrator"):
        cmp.add_argument(
            f"--{key}",
            choices=CHOICES[key],
            action="append",
            help=f"also overlay this engine with settings.{key} set to this (repeatable)",
        )
    cmp.add_argument("--no-gif", action="store_true", help="skip the animation")
    cmp.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    """Run the scene in both engines and write the overlaid figures."""
    from sandbox.compare import compare

    out = Path(args.out)
    if out.exists() and not out.is_dir():
        raise CliError("--out", f"{args.out!r} is not a folder")
    if not out.resolve().parent.is_dir():
        raise CliError("--out", f"folder {str(out.resolve().parent)!r} does not exist")
    check_writable("--out", out if out.is_dir() else out.resolve().parent)
    with input_phase():
        spec = load_spec(args.scene, args)
    cache_note()
    variants = {k: getattr(args, k) or [] for k in ("solver", "orientation", "integrator")}
    compare(spec, args.steps, out, variants=variants, gif=not args.no_gif)
    return 0
