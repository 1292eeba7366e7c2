"""``sandbox lessons [NAME ...]``: run lessons into ``outputs/``."""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import time
from pathlib import Path

from sandbox.cli.common import CliError


def add_parser(sub) -> None:
    """The ``lessons`` command and its options."""
    les = sub.add_parser(
        "lessons",
        help="run lessons into outputs/",
        description="Run lessons (all, or those named) and write their figures into outputs/.",
        epilog="examples:\n  sandbox lessons\n  sandbox lessons 01 07\n  sandbox lessons friction",
    )
    les.add_argument(
        "names", nargs="*", metavar="NAME", help="lesson number or part of its name (default: all)"
    )
    les.set_defaults(func=run)


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


def run(args: argparse.Namespace) -> int:
    """Run each lesson as a script in its own process."""
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
