"""Small helpers shared by the lesson scripts: where to write, how to print a table."""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path

import matplotlib

matplotlib.use("Agg")


def repo_root(start: Path | None = None) -> Path:
    """The folder holding ``pyproject.toml`` above ``start`` (default: the working directory)."""
    here = (start or Path.cwd()).resolve()
    for folder in (here, *here.parents):
        if (folder / "pyproject.toml").exists() and (folder / "sandbox").is_dir():
            return folder
    return here


def output_dir(lesson: str) -> Path:
    """``outputs/<lesson>/`` (created). ``SANDBOX_OUTPUTS`` overrides the ``outputs`` folder."""
    base = os.environ.get("SANDBOX_OUTPUTS")
    root = Path(base) if base else repo_root() / "outputs"
    out = root / lesson
    out.mkdir(parents=True, exist_ok=True)
    return out


def scene_path(name: str) -> Path:
    """Path of an example scene in ``scenes/`` (``name`` with or without ``.json``)."""
    name = name if name.endswith(".json") else name + ".json"
    return repo_root() / "scenes" / name


def save_figure(fig, path: str | os.PathLike, **savefig_kwargs) -> Path:
    """Save a lesson's matplotlib figure to ``path`` (PNG) and close it; returns the path.

    Every lesson figure goes through here, so that one place decides how a figure is shown
    (a file for a script run) and checked: with ``SANDBOX_CHECK_FIGURES`` set, a figure that
    breaks the figure standard (:mod:`sandbox.figure_standard`) raises instead of being saved.
    """
    import matplotlib.pyplot as plt

    from sandbox.figure_standard import enforce

    path = Path(path)
    enforce(fig, path.name)
    fig.savefig(path, **savefig_kwargs)
    plt.close(fig)
    return path


def format_table(headers: Sequence[str], rows: Sequence[Sequence[object]], digits: int = 4) -> str:
    """A plain-text table with right-aligned columns; floats printed with ``digits`` decimals."""

    def cell(v: object) -> str:
        if isinstance(v, float):
            return f"{v:.{digits}f}"
        return str(v)

    text = [[str(h) for h in headers]] + [[cell(v) for v in row] for row in rows]
    widths = [max(len(r[i]) for r in text) for i in range(len(headers))]
    lines = ["  ".join(c.rjust(w) for c, w in zip(r, widths, strict=True)) for r in text]
    lines.insert(1, "  ".join("-" * w for w in widths))
    return "\n".join(lines)


def print_table(headers: Sequence[str], rows: Sequence[Sequence[object]], digits: int = 4) -> str:
    """Print :func:`format_table` and return it (so a lesson can also save it)."""
    text = format_table(headers, rows, digits)
    print(text)
    return text
