"""CSV traces of a run: ``step,t,body,x,y,angle,vx,vy,omega``, one row per body per step.

Step 0 is the initial state. ``x, y`` are the body origin, ``angle`` is in [-pi, pi], ``vx, vy``
the velocity of the centre of mass, ``omega`` in rad/s. Numbers are written with full precision
(``repr``) so a trace read back gives the same floats.
"""

from __future__ import annotations

import csv
import os
from collections.abc import Iterable, Iterator

HEADER = ("step", "t", "body", "x", "y", "angle", "vx", "vy", "omega")

Row = tuple[int, float, str, float, float, float, float, float, float]


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


def format_row(row: Row) -> list[str]:
    step, t, name, *values = row
    return [str(step), repr(float(t)), name, *(repr(float(v)) for v in values)]


def write_trace(rows: Iterable[Row], path: str | os.PathLike) -> None:
    """Write rows to ``path`` as CSV, whole or not at all."""
    from sandbox.atomic import atomic_write

    with atomic_write(path, "w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(HEADER)
        for row in rows:
            writer.writerow(format_row(row))


def read_trace(path: str | os.PathLike) -> list[dict]:
    """Read a trace back: a list of dicts with ints, floats and the body name."""
    out = []
    with open(path, newline="", encoding="utf-8") as handle:
        for rec in csv.DictReader(handle):
            row = {k: float(v) for k, v in rec.items() if k not in ("step", "body")}
            row["step"] = int(rec["step"])
            row["body"] = rec["body"]
            out.append(row)
    return out
