"""A clean copy of the project's sources, for tests that build the wheel: building in the
checkout itself would leave ``build/`` and an egg-info behind (and a later build would pick up
what they hold)."""

from __future__ import annotations

import shutil
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SOURCES = ("pyproject.toml", "setup.py", "README.md", "LICENSE", "sandbox", "lessons", "scenes")


def clean_copy(dest: Path) -> Path:
    """Copy what the wheel is built from into ``dest`` (created), without caches; returns it."""
    dest.mkdir(parents=True)
    for name in SOURCES:
        if (ROOT / name).is_dir():
            ignore = shutil.ignore_patterns("__pycache__", "*.pyc", "*.nbi", "*.nbc")
            shutil.copytree(ROOT / name, dest / name, ignore=ignore)
        else:
            shutil.copy2(ROOT / name, dest / name)
    return dest
