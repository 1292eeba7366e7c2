"""What every command shares: the one-line error, the argument parser (defaults in ``--help``,
a did-you-mean for a mistyped option), checked numbers, ``--set KEY=VALUE``, reading a scene."""

from __future__ import annotations

import argparse
import contextlib
import difflib
import os
import sys
import tempfile
from collections.abc import Iterator
from pathlib import Path

from sandbox.fieldspec import TIME_STEP, Field, check_value
from sandbox.scene_fields import SceneError
from sandbox.settings import CHOICES


class CliError(ValueError):
    """Bad command-line input; ``path`` names the option or field."""

    def __init__(self, path: str, message: str) -> None:
        super().__init__(f"{path}: {message}")
        self.path, self.message = path, message


class HelpFormatter(argparse.RawDescriptionHelpFormatter):
    """``--help`` shows each option's default and keeps the examples' line breaks."""

    def _get_help_string(self, action: argparse.Action) -> str:
        text = action.help or ""
        default = action.default
        shown = default not in (None, False, [], argparse.SUPPRESS) and action.option_strings
        if shown and "%(default)" not in text and "default:" not in text:
            text += " (default: %(default)s)"
        return text


class Parser(argparse.ArgumentParser):
    """An argument parser whose errors are one :class:`CliError` instead of usage + message,
    with a did-you-mean for a mistyped option or command."""

    def __init__(self, *args, **kwargs) -> None:
        kwargs.setdefault("formatter_class", HelpFormatter)
        super().__init__(*args, **kwargs)

    def parse_known_args(self, args=None, namespace=None):
        self._argv = list(sys.argv[1:] if args is None else args)  # for error(): the command
        return super().parse_known_args(args, namespace)

    def error(self, message: str):
        if message.startswith("unrecognized arguments: "):
            unknown = message[len("unrecognized arguments: ") :].split()
            flag = next((u for u in unknown if u.startswith("-")), unknown[0])
            option = flag.split("=", 1)[0]
            raise CliError(option, f"unknown option{self._hint(option)}")
        if message.startswith("argument "):
            message = message[len("argument ") :]
            name, _, rest = message.partition(": ")
            if rest.startswith("invalid choice: "):
                given = rest[len("invalid choice: ") :].split(" (choose", 1)[0].strip("'")
                choices = rest.partition("(choose from ")[2].rstrip(")").replace("'", "")
                rest += _close(given, [c.strip() for c in choices.split(",")])
            raise CliError(name.split("/")[-1], rest)
        raise CliError("arguments", message)

    def _commands(self) -> dict[str, Parser]:
        """This parser's commands by name (none for a command's own parser)."""
        for action in self._actions:
            if isinstance(action, argparse._SubParsersAction):
                return dict(action.choices)
        return {}

    def _hint(self, option: str) -> str:
        """What to say about an unknown ``option``: the closest option of the command given
        (``sandbox simulate --stesp``: did you mean --steps?), or, when it is another
        command's option (``sandbox simulate --out``), which commands have it."""
        commands = self._commands()
        given = next((word for word in getattr(self, "_argv", []) if word in commands), None)
        if given is None:
            return _close(option, self._known_options())
        own = commands[given]._known_options()
        elsewhere = [name for name, sub in commands.items() if option in sub._known_options()]
        if elsewhere:
            where = " and ".join(f"`sandbox {name}`" for name in elsewhere)
            return f" for `sandbox {given}` (an option of {where}; see `sandbox {given} -h`)"
        return _close(option, own)

    def _known_options(self) -> list[str]:
        """Every option string of this parser and of its commands."""
        options: list[str] = []
        for action in self._actions:
            options += [o for o in action.option_strings if o.startswith("--")]
            if isinstance(action, argparse._SubParsersAction):
                for sub in action.choices.values():
                    options += sub._known_options()
        return options


def _close(word: str, options: list[str]) -> str:
    """`` (did you mean --steps?)`` for the closest option, or nothing."""
    match = difflib.get_close_matches(word, options, n=1, cutoff=0.6)
    return f" (did you mean {match[0]}?)" if match else ""


def field_type(field: Field, option: str):
    """An argparse ``type`` that checks command-line text against ``field`` (range, unit)."""

    def convert(text: str):
        try:
            value: object = int(text) if field.kind == "integer" else float(text)
        except ValueError:
            value = text  # the check says what was expected
        try:
            return check_value(field, value, option)
        except SceneError as err:
            raise argparse.ArgumentTypeError(err.message) from None

    convert.__name__ = field.name  # argparse names the type in some messages
    return convert


# the command line's own numbers, with their ranges (the scene's dt is the scene field's)
STEPS = Field("steps", "integer", "number of steps", 300, "", lo=0, hi=10_000_000)
FPS = Field("fps", "number", "GIF frames per second", 30.0, "frames/s", gt=0.0, lo=0.1, hi=100)
DT = Field(
    "dt",
    "number",
    "time step (default: the scene's)",
    None,
    "s",
    gt=0.0,
    lo=TIME_STEP.lo,
    hi=TIME_STEP.hi,
)


def add_settings_options(parser: argparse.ArgumentParser) -> None:
    """``--set KEY=VALUE`` (repeatable): any world setting, checked like a scene file's."""
    parser.add_argument(
        "--set",
        action="append",
        default=[],
        metavar="KEY=VALUE",
        help="change one world setting (repeatable), e.g. --set warm_start=false; "
        "see the scene reference for every setting",
    )


def parse_assignments(items: list[str] | None, option: str) -> list[tuple[str, object]]:
    """``KEY=VALUE`` texts as (setting, checked value) pairs; CliError naming the bad one."""
    from sandbox.settings import parse_setting

    out = []
    for item in items or ():
        key, sep, text = item.partition("=")
        key = key.strip()
        if not sep or not key:
            raise CliError(option, f"expected KEY=VALUE, got {item!r}")
        try:
            out.append((key, parse_setting(key, text, f"{option} {key}")))
        except SceneError as err:
            raise CliError(err.path, err.message) from None
    return out


def _scene_hint(path: str) -> str:
    """For a scene file that is not there: the bundled scene of the closest name, if any, and
    where the bundled scenes are listed."""
    from sandbox.bundled import scene_files

    stem = Path(path).name.removesuffix(".json")
    match = difflib.get_close_matches(stem, [f.stem for f in scene_files()], n=1, cutoff=0.6)
    listed = "`sandbox scenes` lists the bundled example scenes"
    return f" (did you mean the bundled scene {match[0]}? {listed})" if match else f" ({listed})"


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
    elif not found.exists() and Path(path).parent == Path("."):  # a name, as of a bundled one
        raise SceneError("file", f"cannot read {path!r}: no such file{_scene_hint(path)}")
    spec = validate_scene(read_scene_file(found))
    if args is not None:
        for key, value in parse_assignments(getattr(args, "set", None), "--set"):
            spec["settings"][key] = value
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
    from sandbox.compile_cache import private_temp_folder, writable_folder

    root = os.environ.get("XDG_CONFIG_HOME") or os.path.join(os.path.expanduser("~"), ".config")
    if writable_folder(Path(root) / "matplotlib"):
        return
    base = private_temp_folder()
    if base is not None and writable_folder(base / "matplotlib"):
        os.environ["MPLCONFIGDIR"] = str(base / "matplotlib")


def cache_note() -> None:
    """Print the compile cache's note (where it fell back to), if any, once."""
    from sandbox.compile_cache import take_cache_note

    text = take_cache_note()
    if text:
        note(text)
