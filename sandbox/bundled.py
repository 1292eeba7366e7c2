"""The example scenes and the lessons that ship inside the package.

In the repository they sit at the top (``scenes/``, ``lessons/``); the wheel carries them as the
subpackages ``sandbox.scenes`` and ``sandbox.lessons`` (``setup.py`` maps the two folders), so they
are read with :mod:`importlib.resources` wherever the package is: an editable install, a wheel in a
virtual environment, or a checkout put on ``sys.path`` by hand (then the folders beside the
package are used).
"""

from __future__ import annotations

import importlib.resources
import json
import os
from pathlib import Path

import sandbox


def _folder(package: str, name: str) -> Path:
    """The folder of ``sandbox.<name>``; the checkout's ``<name>/`` when it is not installed."""
    try:
        found = importlib.resources.files(package)
    except ModuleNotFoundError:  # a checkout on sys.path without an install
        return Path(sandbox.__file__).resolve().parent.parent / name
    if not isinstance(found, Path):  # e.g. a zip import: the files are not on disk
        raise RuntimeError(f"{package} is not a folder on disk ({found}); install the package")
    return found


def scenes_folder() -> Path:
    """Folder of the bundled example scenes (``*.json``)."""
    return _folder("sandbox.scenes", "scenes")


def lessons_folder() -> Path:
    """Folder of the bundled lessons (``NN_name.py``)."""
    return _folder("sandbox.lessons", "lessons")


def scene_files() -> list[Path]:
    """The bundled example scenes, sorted by name."""
    return sorted(scenes_folder().glob("*.json"))


def lesson_files() -> list[Path]:
    """The bundled lessons (``NN_name.py``), in course order."""
    return sorted(lessons_folder().glob("[0-9][0-9]_*.py"))


def bundled_scene(name: str) -> Path | None:
    """The bundled scene called ``name`` (``drop`` or ``drop.json``), or None."""
    stem = name[: -len(".json")] if name.endswith(".json") else name
    if not stem or os.sep in stem or "/" in stem or stem.startswith("."):
        return None
    path = scenes_folder() / f"{stem}.json"
    return path if path.is_file() else None


def resolve_scene(source: str | os.PathLike) -> tuple[Path, bool]:
    """A scene file to read for ``source``: the file itself when it exists, else the bundled
    scene of that name. Returns ``(path, bundled)``; a missing file that is no bundled scene
    comes back unchanged (reading it then reports the missing file)."""
    path = Path(source)
    if path.exists():
        return path, False
    found = bundled_scene(os.fspath(source))
    return (found, True) if found is not None else (path, False)


def scene_description(path: Path) -> str:
    """One line about a scene file: its ``description``, or else what it holds (its bodies)."""
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError) as err:
        return f"(unreadable: {err})"
    if not isinstance(data, dict):
        return "(not a scene)"
    text = data.get("description")
    if isinstance(text, str) and text.strip():
        return " ".join(text.split())
    bodies = data.get("bodies") if isinstance(data.get("bodies"), list) else []
    names = [str(b.get("name", "?")) for b in bodies if isinstance(b, dict)]
    shown = ", ".join(names[:4]) + (", ..." if len(names) > 4 else "")
    joints = data.get("joints") if isinstance(data.get("joints"), list) else []
    more = f", {len(joints)} joints" if joints else ""
    return f"{len(names)} bodies ({shown}){more}"
