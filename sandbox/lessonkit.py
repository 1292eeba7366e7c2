"""Small helpers shared by the lesson scripts: where to write, how to show a figure, a table.

A lesson runs the same way as a script and as a notebook. As a script, figures and animations go
to files and tables print; in a notebook kernel, every figure and animation is also shown inline
in the cell that made it, and a table shows once (printed, never echoed again as the cell's
value). Either way each printed table is also saved to ``tables.md`` in the lesson's folder.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

_current: Path | None = None  # the folder output_dir last gave: where tables.md goes
_tables = 0  # tables written to it so far by this process


def repo_root(start: Path | None = None) -> Path:
    """The folder holding ``pyproject.toml`` above ``start`` (default: the working directory)."""
    here = (start or Path.cwd()).resolve()
    for folder in (here, *here.parents):
        if (folder / "pyproject.toml").exists() and (folder / "sandbox").is_dir():
            return folder
    return here


def output_dir(lesson: str) -> Path:
    """``outputs/<lesson>/`` (created) where the lesson writes its figures and tables.

    ``SANDBOX_OUTPUTS`` names the ``outputs`` folder (``sandbox lessons`` sets it); otherwise it
    is the checkout's ``outputs/`` when run inside one, else ``./outputs``. A notebook opened in
    its own output folder (the working folder is called ``<lesson>``) writes beside itself.
    """
    global _current, _tables
    base = os.environ.get("SANDBOX_OUTPUTS")
    if base:
        out = Path(base) / lesson
    elif Path.cwd().name == lesson:
        out = Path.cwd()
    else:
        out = repo_root() / "outputs" / lesson
    out.mkdir(parents=True, exist_ok=True)
    _current, _tables = out, 0
    return out


def scene_path(name: str) -> Path:
    """Path of a bundled example scene (``name`` with or without ``.json``), found next to the
    package wherever the lesson runs from."""
    from sandbox.bundled import scenes_folder

    name = name if name.endswith(".json") else name + ".json"
    return scenes_folder() / name


def save_figure(fig, path: str | os.PathLike, **savefig_kwargs) -> Path:
    """Save a lesson's matplotlib figure to ``path`` (PNG) and close it; returns the path.

    Every lesson figure goes through here: in a notebook kernel the saved file is also shown
    inline, in the cell that made it; with ``SANDBOX_CHECK_FIGURES`` set, a figure that breaks
    the figure standard (:mod:`sandbox.figure_standard`) raises instead of being saved.
    """
    import matplotlib.pyplot as plt

    from sandbox.figure_standard import enforce

    path = Path(path)
    enforce(fig, path.name)
    fig.savefig(path, **savefig_kwargs)
    plt.close(fig)
    return show_image(path)


def show_gif(path: str | os.PathLike) -> Path:
    """Show an animation written by :func:`sandbox.render.render_gif` inline (it plays) when
    running in a notebook kernel; nothing happens in a script. Returns the path."""
    return show_image(path)


class ShownPath(type(Path())):
    """The path of a figure already shown: a notebook shows nothing more for it as a cell's
    value (a cell ending in ``save_figure(...)`` would otherwise also print the path)."""

    def _ipython_display_(self) -> None:
        return None


def show_image(path: str | os.PathLike) -> Path:
    """Show a PNG or GIF file inline when running in a notebook kernel. Returns the path."""
    from sandbox.notebook import show_file

    show_file(path, _current)
    return ShownPath(path)


def format_table(headers: Sequence[str], rows: Sequence[Sequence[object]], digits: int = 4) -> str:
    """A plain-text table with right-aligned columns; floats printed with ``digits`` decimals."""
    text = _cells(headers, rows, digits)
    widths = [max(len(r[i]) for r in text) for i in range(len(headers))]
    lines = ["  ".join(c.rjust(w) for c, w in zip(r, widths, strict=True)) for r in text]
    lines.insert(1, "  ".join("-" * w for w in widths))
    return "\n".join(lines)


def markdown_table(
    headers: Sequence[str], rows: Sequence[Sequence[object]], digits: int = 4
) -> str:
    """The same table as Markdown (right-aligned columns, ``|`` in a cell escaped)."""
    text = [
        [" ".join(c.split()).replace("|", "\\|") for c in r] for r in _cells(headers, rows, digits)
    ]
    lines = ["| " + " | ".join(r) + " |" for r in text]
    lines.insert(1, "|" + "|".join("---:" for _ in headers) + "|")
    return "\n".join(lines)


class Table(str):
    """A printed table's text. A notebook shows nothing for it as a cell's value: it was
    printed already, and would otherwise appear twice."""

    def _ipython_display_(self) -> None:
        return None


def print_table(headers: Sequence[str], rows: Sequence[Sequence[object]], digits: int = 4) -> Table:
    """Print :func:`format_table`, add it to the lesson's ``tables.md`` and return its text."""
    text = Table(format_table(headers, rows, digits))
    print(text)
    _save_table(markdown_table(headers, rows, digits))
    return text


def _cells(headers: Sequence[str], rows: Sequence[Sequence[object]], digits: int) -> list[list]:
    def cell(v: object) -> str:
        if isinstance(v, float):
            return f"{v:.{digits}f}"
        return str(v)

    return [[str(h) for h in headers]] + [[cell(v) for v in row] for row in rows]


def _save_table(markdown: str) -> None:
    """Append a table to ``tables.md`` of the current lesson (started afresh by each run)."""
    global _tables
    if _current is None:
        return
    _tables += 1
    head = f"# {_current.name}: printed tables\n\n" if _tables == 1 else "\n"
    mode = "w" if _tables == 1 else "a"
    with open(_current / "tables.md", mode, encoding="utf-8") as f:
        f.write(f"{head}Table {_tables}\n\n{markdown}\n")
