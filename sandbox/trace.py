"""CSV traces of a run: ``step,t,body,x,y,angle,vx,vy,omega``, one row per body per step.

Step 0 is the initial state. ``x, y`` are the body origin, ``angle`` is in [-pi, pi], ``vx, vy``
the velocity of the centre of mass, ``omega`` in rad/s. Numbers are written with full precision
(``repr``) so a trace read back gives the same floats. A trace holds finite numbers only: a row
with NaN or infinity raises :class:`sandbox.SimulationError` instead of being written.

Body names are text a spreadsheet must never run as a formula. A name that begins with ``=``,
``+``, ``-``, ``@``, a tab, a carriage return or a line feed (also after leading spaces), or with
an apostrophe, is written with one apostrophe in front: ``=HYPERLINK(...)`` is written
``'=HYPERLINK(...)``, which spreadsheets show as text. Every other name is written as it is.
Reading back, a cell that begins with an apostrophe loses that one apostrophe, so names round-trip
exactly: :func:`read_trace` does it, and so does ``name[1:] if name.startswith("'") else name``
in any other reader (pandas, a script).

:class:`TraceWriter` streams rows to the file as the run goes (memory stays flat however many
steps), whole or not at all (see :mod:`sandbox.atomic`).
"""

from __future__ import annotations

import csv
import math
import os
import sys
from collections.abc import Iterable, Iterator, Sequence

from sandbox.errors import SimulationError

HEADER = ("step", "t", "body", "x", "y", "angle", "vx", "vy", "omega")

Row = tuple[int, float, str, float, float, float, float, float, float]

_FORMULA_START = ("=", "+", "-", "@", "\t", "\r", "\n")


def world_rows(world, step: int) -> list[Row]:
    """The trace rows of a world's current state, labelled ``step``."""
    origins = world.origins()
    angles = world.angles()
    return [
        (
            step,
            float(world.time),
            body.name,
            float(origins[i, 0]),
            float(origins[i, 1]),
            float(angles[i]),
            float(world.vel[i, 0]),
            float(world.vel[i, 1]),
            float(world.omega[i]),
        )
        for i, body in enumerate(world.bodies)
    ]


def run_world(world, steps: int, dt: float | None = None, on_step=None) -> Iterator[Row]:
    """Step ``world`` ``steps`` times, yielding the rows of step 0 (initial state) to ``steps``.

    ``on_step(world)`` is called after each step (e.g. to capture frames for an animation).
    """
    yield from world_rows(world, 0)
    for k in range(1, steps + 1):
        world.step(dt)
        if on_step is not None:
            on_step(world)
        yield from world_rows(world, k)


def check_finite(rows: Sequence[Row]) -> None:
    """Raise :class:`~sandbox.SimulationError` naming the first row whose numbers are not finite."""
    finite = math.isfinite
    for row in rows:
        _, t, _, x, y, angle, vx, vy, omega = row
        ok = finite(x) and finite(y) and finite(angle) and finite(vx) and finite(vy)
        if not (ok and finite(omega) and finite(t)):
            raise SimulationError(
                str(row[2]),
                int(row[0]),
                "its position or velocity is no longer finite (NaN or infinity): "
                "try a smaller dt, softer springs, or numbers in a physical range",
            )


def text_cell(name: str) -> str:
    """A body name as a CSV cell no spreadsheet runs as a formula (see the module notes)."""
    stripped = name.lstrip(" ")
    if name.startswith("'") or stripped.startswith(_FORMULA_START):
        return "'" + name
    return name


def name_from_cell(cell: str) -> str:
    """The body name written as ``cell`` by :func:`text_cell` (its inverse)."""
    return cell[1:] if cell.startswith("'") else cell


def format_row(row: Row) -> list[str]:
    """The CSV cells of one row: full-precision numbers, the name as safe text."""
    step, t, name, *values = row
    return [str(step), repr(float(t)), text_cell(str(name)), *(repr(float(v)) for v in values)]


class TraceWriter:
    """Write trace rows to ``path`` as they come: ``with TraceWriter(p) as w: w.write(rows)``.

    The file is written under a temporary name and renamed when the block ends without error
    (or when the enclosing :func:`sandbox.atomic.output_set` ends). ``rows`` counts the rows
    written. Non-finite rows raise :class:`~sandbox.SimulationError` and are not written.
    """

    def __init__(self, path: str | os.PathLike) -> None:
        from sandbox.atomic import atomic_write

        self.path = path
        self.rows = 0
        self._file = atomic_write(path, "w", newline="")
        self._writer = None

    def __enter__(self) -> TraceWriter:
        self._writer = csv.writer(self._file.__enter__())
        try:
            self._writer.writerow(HEADER)
        except BaseException:
            self._file.__exit__(*sys.exc_info())
            raise
        return self

    def write(self, rows: Sequence[Row]) -> None:
        """Append ``rows`` (one step's rows, or any batch)."""
        check_finite(rows)
        self._writer.writerows(format_row(row) for row in rows)
        self.rows += len(rows)

    def __exit__(self, *exc) -> bool | None:
        return self._file.__exit__(*exc)


def write_trace(rows: Iterable[Row], path: str | os.PathLike) -> int:
    """Write rows to ``path`` as CSV, whole or not at all; returns the number of rows."""
    with TraceWriter(path) as writer:
        batch: list[Row] = []
        for row in rows:
            batch.append(row)
            if len(batch) >= 1024:
                writer.write(batch)
                batch = []
        writer.write(batch)
    return writer.rows


def read_trace(path: str | os.PathLike) -> list[dict]:
    """Read a trace back: a list of dicts with ints, floats and the body name."""
    out = []
    with open(path, newline="", encoding="utf-8") as handle:
        for rec in csv.DictReader(handle):
            row = {k: float(v) for k, v in rec.items() if k not in ("step", "body")}
            row["step"] = int(rec["step"])
            row["body"] = name_from_cell(rec["body"])
            out.append(row)
    return out
