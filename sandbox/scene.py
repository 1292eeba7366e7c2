"""Scene files (JSON, version 1): read, validate, save.

``validate_scene`` (:mod:`sandbox.scene_validate`, against the format's tables in
:mod:`sandbox.scene_spec`) checks every field of the scene-file contract and returns a new,
normalized dict with every default filled in; ``sandbox.build`` turns that dict into a ``World``. Every problem is a
:class:`SceneError` whose ``path`` names the offending field, e.g. ``bodies[1].shapes[0].radius``.
Units: SI, radians, y up, counter-clockwise positive.
"""

from __future__ import annotations

import json
import os
from typing import TYPE_CHECKING, Any

from sandbox.atomic import atomic_write_text
from sandbox.scene_fields import SceneError, _key, _show
from sandbox.scene_validate import validate_scene

if TYPE_CHECKING:
    from sandbox.world import World

__all__ = [
    "SceneError",
    "dump_scene",
    "load_scene",
    "read_scene_file",
    "save_scene",
    "validate_scene",
]

MAX_DIGITS = 4000  # longer integer literals are refused (Python's own limit is 4300 digits)


# --- reading -------------------------------------------------------------------------------------
class _Constant:
    """Stands in for a NaN / Infinity literal (or an integer of thousands of digits) until its
    field path is known."""

    def __init__(self, text: str, message: str = ""):
        self.text = text
        self.message = message or f"expected a finite number, got {text} (not allowed in JSON)"


def _parse_int(text: str) -> int | _Constant:
    if len(text.lstrip("-")) > MAX_DIGITS:
        return _Constant(text, f"expected a finite number, got an integer of {len(text)} digits")
    return int(text)


def read_scene_file(path: str | os.PathLike) -> dict:
    """Parse a scene file (standard ``json``; NaN and Infinity literals are refused)."""
    name = os.fspath(path)
    try:
        with open(name, encoding="utf-8-sig") as f:
            text = f.read()
    except FileNotFoundError:
        raise SceneError("file", f"cannot read {name!r}: no such file") from None
    except IsADirectoryError:
        raise SceneError("file", f"cannot read {name!r}: it is a folder") from None
    except PermissionError:
        raise SceneError("file", f"cannot read {name!r}: permission denied") from None
    except UnicodeDecodeError as e:
        raise SceneError("file", f"cannot read {name!r}: not UTF-8 text (byte {e.start})") from None
    except OSError as e:
        raise SceneError("file", f"cannot read {name!r}: {e.strerror or e}") from None
    try:
        data = json.loads(text, parse_constant=_Constant, parse_int=_parse_int)
    except json.JSONDecodeError as e:
        where = f"line {e.lineno}, column {e.colno}"
        raise SceneError("file", f"invalid JSON in {name!r} at {where}: {e.msg}") from None
    except RecursionError:
        raise SceneError("file", f"invalid JSON in {name!r}: nested too deeply") from None
    _refuse_constants(data, "")
    if not isinstance(data, dict):
        raise SceneError("", f"expected a JSON object at the top level, got {_show(data)}")
    return data


def _refuse_constants(value: Any, path: str) -> None:
    if isinstance(value, _Constant):
        raise SceneError(path, value.message)
    if isinstance(value, dict):
        for key, item in value.items():
            _refuse_constants(item, _key(path, key))
    elif isinstance(value, list):
        for i, item in enumerate(value):
            _refuse_constants(item, f"{path}[{i}]")


# --- loading and saving --------------------------------------------------------------------------
def load_scene(source: str | os.PathLike | dict) -> World:
    """Build a ``World`` from a scene file path or an already-parsed scene dict."""
    if isinstance(source, dict):
        spec = validate_scene(source)
    elif isinstance(source, str | os.PathLike):
        spec = validate_scene(read_scene_file(source))
    else:
        raise TypeError(f"load_scene: expected a path or a dict, got {type(source).__name__}")
    from sandbox.build import build_world

    return build_world(spec)


def _as_spec(scene: Any) -> dict:
    if hasattr(scene, "to_scene") and not isinstance(scene, dict):
        scene = scene.to_scene()
    return validate_scene(scene)


def dump_scene(spec: Any, *, validate: bool = True) -> str:
    """JSON text of a scene (validated and normalized first unless ``validate=False``).

    ``spec`` is a scene dict or an object with a ``to_scene()`` method (e.g. a ``World``).
    Short lists and objects stay on one line; the text has no trailing newline.
    """
    data = _as_spec(spec) if validate else spec
    return _pretty(data, 0, 0, top=True)


def save_scene(scene: Any, path: str | os.PathLike) -> None:
    """Validate ``scene`` (a dict, or an object with ``to_scene()``) and write it atomically."""
    atomic_write_text(path, dump_scene(scene) + "\n")


_WIDTH = 100


def _pretty(value: Any, indent: int, column: int, top: bool = False) -> str:
    """JSON with one-line containers whenever they fit in ``_WIDTH`` columns."""
    flat = json.dumps(value, allow_nan=False, separators=(", ", ": "))
    if (
        not isinstance(value, dict | list)
        or not value
        or (not top and column + len(flat) <= _WIDTH)
    ):
        return flat
    pad = " " * (indent + 2)
    if isinstance(value, dict):
        items = []
        for key, item in value.items():
            head = f"{pad}{json.dumps(str(key))}: "
            items.append(head + _pretty(item, indent + 2, len(head) + 1))
        return "{\n" + ",\n".join(items) + "\n" + " " * indent + "}"
    items = [pad + _pretty(item, indent + 2, indent + 3) for item in value]
    return "[\n" + ",\n".join(items) + "\n" + " " * indent + "]"
