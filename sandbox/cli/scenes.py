"""``sandbox scenes [--copy DIR]``: the bundled example scenes, listed or copied out to edit."""

from __future__ import annotations

import argparse
import os
from pathlib import Path

from sandbox.cli.common import CliError


def add_parser(sub) -> None:
    """The ``scenes`` command and its options."""
    sc = sub.add_parser(
        "scenes",
        help="list the bundled example scenes, or copy them out",
        description="List the example scenes that come with the package, one line each. Any\n"
        "command that takes a SCENE.json also takes one of these names when no such file\n"
        "exists in the working folder.",
        epilog="examples:\n  sandbox scenes\n  sandbox scenes --copy my_scenes/\n"
        "  sandbox simulate drop --gif drop.gif",
    )
    sc.add_argument("--copy", metavar="DIR", help="copy every bundled scene into DIR (created)")
    sc.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    """List the scenes with one line each, or copy them (all or none) into ``--copy DIR``."""
    from sandbox.bundled import scene_description, scene_files, scenes_folder

    files = scene_files()
    if not files:
        raise CliError("scenes", f"no bundled scene found in {scenes_folder()}")
    if args.copy is not None:
        return copy_scenes(files, Path(args.copy))
    width = max(len(f.stem) for f in files)
    print(f"{len(files)} bundled example scenes:")
    for f in files:
        print(f"  {f.stem.ljust(width)}  {scene_description(f)}")
    print("run one by name (sandbox simulate drop); edit copies: sandbox scenes --copy DIR")
    return 0


def copy_scenes(files: list[Path], folder: Path) -> int:
    """Copy ``files`` into ``folder``; an existing file of the same name stops it before any copy."""
    from sandbox.atomic import atomic_write_bytes

    if folder.exists() and not folder.is_dir():
        raise CliError("--copy", f"{str(folder)!r} is not a folder")
    taken = [f.name for f in files if (folder / f.name).exists()]
    if taken:
        raise CliError(
            "--copy",
            f"{', '.join(taken)} already in {str(folder)!r} (nothing copied; not replaced)",
        )
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as err:
        raise CliError("--copy", f"cannot create {str(folder)!r}: {err.strerror or err}") from None
    if not os.access(folder, os.W_OK):
        raise CliError("--copy", f"folder {str(folder)!r} is not writable")
    written = []
    try:
        for f in files:
            atomic_write_bytes(folder / f.name, f.read_bytes())
            written.append(folder / f.name)
    except BaseException:  # all or none: take back what was copied
        for path in written:
            path.unlink(missing_ok=True)
        raise
    print(f"copied {len(files)} scenes to {folder}: {', '.join(f.name for f in files)}")
    return 0
