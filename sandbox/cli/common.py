"""What every command shares: the one-line error, the argument parser, reading a scene."""

from __future__ import annotations

import argparse
import math
import os
from pathlib import Path

from sandbox.settings import CHOICES


class CliError(ValueError):
    """Bad command-line input; ``path`` names the option or field."""

    def __init__(self, path: str, message: str) -> None:
        super().__init__(f"{path}: {message}")
        self.path, self.message = path, message


class Parser(argparse.ArgumentParser):
    """An argument parser whose errors are one :class:`CliError` instead of usage + message."""

    def error(self, message: str):
        if message.startswith("argument "):
            message = message[len("argument ") :]
            name, _, rest = message.partition(": ")
            raise CliError(name.split("/")[-1], rest)
        raise CliError("arguments", message)


def positive_int(text: str) -> int:
    """A whole number >= 0."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a whole number, got {text!r}") from None
    if value < 0:
        raise argparse.ArgumentTypeError(f"must be >= 0, got {value}")
    return value


def positive_float(text: str) -> float:
    """A finite number > 0."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number, got {text!r}") from None
    if not math.isfinite(value) or value <= 0:
        raise argparse.ArgumentTypeError(f"must be a finite number > 0, got {text}")
    return value


def load_spec(path: str, args: argparse.Namespace | None = None) -> dict:
    """Read and validate a scene file, applying command-line setting overrides.

    ``path`` may name a bundled example scene (``drop``) when no such file exists here; a line
    says so.
    """
    from sandbox.bundled import resolve_scene
    from sandbox.scene import read_scene_file, validate_scene

    found, bundled = resolve_scene(path)
    if bundled:
        print(f"{path}: no such file here; using the bundled example scene {found.name}")
    spec = validate_scene(read_scene_file(found))
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
