"""The command line: ``sandbox simulate | compare | lessons`` (also ``python -m sandbox``).

Bad input exits with status 2 and one line on stderr, ``error: <field path>: <what is wrong>``,
and writes no output file.
"""

from __future__ import annotations

import argparse
import math
import os
import subprocess
import sys
import time
from pathlib import Path

from sandbox.settings import CHOICES


class CliError(ValueError):
    """Bad command-line input; ``path`` names the option or field."""

    def __init__(self, path: str, message: str) -> None:
        super().__init__(f"{path}: {message}")
        self.path, self.message = path, message


class _Parser(argparse.ArgumentParser):
    def error(self, message: str):  # one line instead of usage + message
        if message.startswith("argument "):
            message = message[len("argument ") :]
            name, _, rest = message.partition(": ")
            raise CliError(name.split("/")[-1], rest)
        raise CliError("arguments", message)


def _positive_int(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a whole number, got {text!r}") from None
    if value < 0:
        raise argparse.ArgumentTypeError(f"must be >= 0, got {value}")
    return value


def _positive_float(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number, got {text!r}") from None
    if not math.isfinite(value) or value <= 0:
        raise argparse.ArgumentTypeError(f"must be a finite number > 0, got {text}")
    return value


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="sandbox", description="A 2D physics sandbox for teaching.")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)

    sim = sub.add_parser("simulate", help="run a scene file")
    sim.add_argument("scene", metavar="SCENE.json")
    sim.add_argument("--steps", type=_positive_int, default=300)
    sim.add_argument("--dt", type=_positive_float, default=None)
    sim.add_argument("--engine", choices=("sandbox", "pymunk"), default="sandbox")
    sim.add_argument("--trace", metavar="OUT.csv")
    sim.add_argument("--gif", metavar="OUT.gif")
    sim.add_argument("--png", metavar="OUT.png")
    sim.add_argument("--fps", type=_positive_float, default=30.0, help="GIF frames per second")
    for key, choices in CHOICES.items():
        sim.add_argument(f"--{key}", choices=choices, help=f"override settings.{key}")
    sim.add_argument("--iterations", type=_positive_int, default=None)
    sim.set_defaults(func=cmd_simulate)

    cmp = sub.add_parser("compare", help="this engine and pymunk side by side")
    cmp.add_argument("scene", metavar="SCENE.json")
    cmp.add_argument("--steps", type=_positive_int, default=300)
    cmp.add_argument("--dt", type=_positive_float, default=None)
    cmp.add_argument("--out", required=True, metavar="DIR")
    for key in ("solver", "orientation", "integrator"):
        cmp.add_argument(
            f"--{key}",
            choices=CHOICES[key],
            action="append",
            help=f"also overlay this engine with settings.{key} set to this (repeatable)",
        )
    cmp.add_argument("--no-gif", action="store_true", help="skip the animation")
    cmp.set_defaults(func=cmd_compare)

    les = sub.add_parser("lessons", help="run lessons into outputs/")
    les.add_argument("names", nargs="*", metavar="NAME")
    les.set_defaults(func=cmd_lessons)
    return parser


# --- helpers ----------------------------------------------------------------------------------


def load_spec(path: str, args: argparse.Namespace | None = None) -> dict:
    """Read and validate a scene file, applying command-line setting overrides."""
    from sandbox.scene import read_scene_file, validate_scene

    spec = validate_scene(read_scene_file(path))
    if args is not None:
        for key in (*CHOICES, "iterations"):
            value = getattr(args, key, None)
            if value is not None and not isinstance(value, list):
                spec["settings"][key] = value
        if getattr(args, "dt", None) is not None:
            spec["dt"] = args.dt
        spec = validate_scene(spec)
    return spec


def check_output(option: str, path: str | None, suffix: str) -> None:
    """An output path must end in ``suffix`` and sit in an existing, writable folder."""
    if path is None:
        return
    if not path.lower().endswith(suffix):
        raise CliError(option, f"expected a {suffix} file name, got {path!r}")
    folder = Path(path).resolve().parent
    if not folder.is_dir():
        raise CliError(option, f"folder {str(folder)!r} does not exist")
    if not os.access(folder, os.W_OK):
        raise CliError(option, f"folder {str(folder)!r} is not writable")
    if Path(path).is_dir():
        raise CliError(option, f"{path!r} is a folder")


# --- commands ---------------------------------------------------------------------------------


def cmd_simulate(args: argparse.Namespace) -> int:
    from sandbox.build import build_world
    from sandbox.trace import write_trace

    for option, path, suffix in (
        ("--trace", args.trace, ".csv"),
        ("--gif", args.gif, ".gif"),
        ("--png", args.png, ".png"),
    ):
        check_output(option, path, suffix)
    spec = load_spec(args.scene, args)
    world = build_world(spec)
    want_frames = args.gif or args.png
    if args.engine == "pymunk":
        from sandbox.pymunk_bridge import run_pymunk

        rows = run_pymunk(spec, args.steps, spec["dt"])
    else:
        from sandbox.trace import run_world

        rows = list(run_world(world, args.steps))
    if want_frames:
        from sandbox.render import render_gif, render_png
        from sandbox.replay import recording_from_rows

        label = f"{args.engine}: {spec['name']}"
        if args.gif:
            every = max(1, round(1.0 / (spec["dt"] * args.fps)))
            rec = recording_from_rows(build_world(spec), rows, every=every)
            render_gif(rec, args.gif, fps=args.fps, labels=[label])
        if args.png:
            render_png(recording_from_rows(build_world(spec), rows), args.png)
    if args.trace:
        write_trace(rows, args.trace)
    last = rows[-len(world.bodies) :] if world.bodies else []
    print(f"{spec['name']}: {args.steps} steps of {spec['dt']:.6g} s with {args.engine}")
    for row in last:
        print(f"  {row[2]}: x={row[3]:.6g} y={row[4]:.6g} angle={row[5]:.6g}")
    return 0


def cmd_compare(args: argparse.Namespace) -> int:
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


def lesson_files(names: list[str] | None = None) -> list[Path]:
    """Lesson scripts (``lessons/NN_*.py``) matching any of ``names`` (number or name)."""
    from sandbox.lessonkit import repo_root

    folder = repo_root(Path(__file__).resolve().parent) / "lessons"
    files = sorted(folder.glob("[0-9][0-9]_*.py"))
    if not names:
        return files
    picked = []
    for name in names:
        match = [
            f for f in files if f.stem == name or f.stem.split("_", 1)[0] == name or name in f.stem
        ]
        if not match:
            raise CliError("NAME", f"no lesson matches {name!r}")
        picked += [f for f in match if f not in picked]
    return picked


def cmd_lessons(args: argparse.Namespace) -> int:
    files = lesson_files(args.names)
    root = files[0].parent.parent if files else Path.cwd()
    failed = []
    for f in files:
        start = time.perf_counter()
        print(f"== {f.stem}", flush=True)
        env = {**os.environ, "MPLBACKEND": "Agg"}
        result = subprocess.run([sys.executable, str(f)], cwd=root, env=env)
        status = "ok" if result.returncode == 0 else f"FAILED ({result.returncode})"
        print(f"== {f.stem}: {status} in {time.perf_counter() - start:.1f} s", flush=True)
        if result.returncode:
            failed.append(f.stem)
    if failed:
        print(f"error: lessons: {len(failed)} failed: {', '.join(failed)}", file=sys.stderr)
        return 1
    print(f"{len(files)} lessons written to {root / 'outputs'}")
    return 0


def main(argv: list[str] | None = None) -> int:
    """Entry point; returns the exit status (2 for bad input)."""
    from sandbox.scene import SceneError

    parser = build_parser()
    try:
        args = parser.parse_args(argv)
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
