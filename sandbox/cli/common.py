"""What every command shares: the one-line error, the argument parser, reading a scene."""

from __future__ import annotations

import argparse
import contextlib
import math
import os
import sys
import tempfile
from collections.abc import Iterator
from pathlib import Path

from sandbox.settings import CHOICES

MAX_STEPS = 10_000_000  # simulate: a trace of this many steps of one body is about 1 GB
FPS_RANGE = (0.1, 50.0)  # GIF frames per second: a GIF's delay is in 1/100 s, and browsers
# show frames shorter than 2/100 s at 1/10 s instead


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
        shown = text if len(text) <= 30 else text[:27] + "..."
        raise argparse.ArgumentTypeError(f"expected a whole number, got {shown!r}") from None
    if value < 0:
        raise argparse.ArgumentTypeError(f"must be >= 0, got {value}")
    return value


def steps_count(limit: int):
    """An argument type: a whole number of steps from 0 to ``limit``."""

    def steps(text: str) -> int:
        value = positive_int(text)
        if value > limit:
            raise argparse.ArgumentTypeError(f"must be at most {limit:,}, got {value:,}")
        return value

    steps.__name__ = "steps"
    return steps


def positive_float(text: str) -> float:
    """A finite number > 0."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number, got {text!r}") from None
    if not math.isfinite(value) or value <= 0:
        raise argparse.ArgumentTypeError(f"must be a finite number > 0, got {text}")
    return value


def fps_value(text: str) -> float:
    """GIF frames per second, within :data:`FPS_RANGE`."""
    value = positive_float(text)
    lo, hi = FPS_RANGE
    if not lo <= value <= hi:
        raise argparse.ArgumentTypeError(
            f"must be from {lo:g} to {hi:g} frames per second, got {text}"
        )
    return value


@contextlib.contextmanager
def input_phase() -> Iterator[None]:
    """Reading, validating and building the scene: whatever fails here is bad input (exit 2).

    A ``ValueError`` or arithmetic error without a field path (the world refusing a value while
    it is built) becomes a :class:`CliError` on ``scene``.
    """
    try:
        yield
    except (ValueError, ArithmeticError) as err:
        if isinstance(err, ValueError) and isinstance(getattr(err, "path", None), str):
            raise
        raise CliError("scene", str(err) or type(err).__name__) from err


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
    """An output path must end in ``suffix`` and sit in an existing, writable folder.

    Writable is tried, not assumed from permission bits (which say yes to root on a read-only
    file system): a temporary file is created in the folder and removed.
    """
    if path is None:
        return
    if not path.lower().endswith(suffix):
        raise CliError(option, f"expected a {suffix} file name, got {path!r}")
    folder = Path(path).resolve().parent
    if not folder.is_dir():
        raise CliError(option, f"folder {str(folder)!r} does not exist")
    check_writable(option, folder)
    if Path(path).is_dir():
        raise CliError(option, f"{path!r} is a folder")


def check_writable(option: str, folder: Path) -> None:
    """Raise :class:`CliError` on ``option`` unless a file can be created in ``folder``."""
    try:
        with tempfile.TemporaryFile(dir=folder):
            pass
    except OSError as err:
        why = err.strerror or "cannot create a file there"
        raise CliError(option, f"folder {str(folder)!r} is not writable ({why})") from None


def note(text: str) -> None:
    """One ``note:`` line on stderr (something the user should know; not an error)."""
    print(f"note: {text}", file=sys.stderr)


def shown(name: str) -> str:
    """A body or scene name safe to print on one terminal line (control characters escaped)."""
    return "".join(c if c.isprintable() else repr(c)[1:-1] for c in str(name))


def settle_matplotlib_config() -> None:
    """On a machine where matplotlib's config folder is not writable, give it a private
    temporary one (``MPLCONFIGDIR``) before it is imported, instead of its two warning lines."""
    if os.environ.get("MPLCONFIGDIR") or "matplotlib" in sys.modules:
        return
    from sandbox.jit import private_temp_folder, writable_folder

    root = os.environ.get("XDG_CONFIG_HOME") or os.path.join(os.path.expanduser("~"), ".config")
    if writable_folder(Path(root) / "matplotlib"):
        return
    base = private_temp_folder()
    if base is not None and writable_folder(base / "matplotlib"):
        os.environ["MPLCONFIGDIR"] = str(base / "matplotlib")


def cache_note() -> None:
    """Print the compile cache's note (where it fell back to), if any, once."""
    from sandbox import jit

    text = jit.take_cache_note()
    if text:
        note(text)
