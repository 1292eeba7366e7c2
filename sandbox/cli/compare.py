"""``sandbox compare SCENE.json --out DIR``: this engine and pymunk, overlaid."""

from __future__ import annotations

import argparse
from pathlib import Path

from sandbox.cli.common import CliError, load_spec, positive_float, positive_int
from sandbox.settings import CHOICES


def add_parser(sub) -> None:
    """The ``compare`` command and its options."""
    cmp = sub.add_parser("compare", help="this engine and pymunk side by side")
    cmp.add_argument("scene", metavar="SCENE.json")
    cmp.add_argument("--steps", type=positive_int, default=300)
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
    spec = load_spec(args.scene, args)
    variants = {k: getattr(args, k) or [] for k in ("solver", "orientation", "integrator")}
    compare(spec, args.steps, out, variants=variants, gif=not args.no_gif)
    return 0
