"""Turn trace rows (from this engine or from pymunk) back into a recording to draw."""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence

import numpy as np

from sandbox.energy import does_work, energy_terms
from sandbox.overlays import FROM_TRACE, LayerError, parse_layers
from sandbox.recording import Recording


def check_trace_layers(draw: str | Iterable[str] | None) -> tuple[str, ...]:
    """The layers ``draw``, refused (:class:`LayerError`) when a trace cannot give their data:
    a trace holds poses and velocities, not contacts, impulses or applied forces."""
    names = parse_layers(draw)
    for name in names:
        if name not in FROM_TRACE:
            raise LayerError(
                f"layer {name!r} is not in a trace: it holds poses and velocities only "
                f"(it draws {', '.join(FROM_TRACE)})"
            )
    return names


def set_state(world, row: np.ndarray) -> None:
    """Put ``world``'s bodies in the state ``row`` (n, 6): ``x, y, angle, vx, vy, omega`` of
    each origin (m, rad) and centre of mass velocity (m/s, rad/s)."""
    for body, (x, y, angle, vx, vy, omega) in zip(world.bodies, row, strict=True):
        body.angle = angle
        body.position = (x, y)
        body.velocity = (vx, vy)
        body.angular_velocity = omega


def recording_from_rows(
    world,
    rows: Sequence[tuple],
    every: int = 1,
    draw: str | Iterable[str] | None = (),
    energy: bool = False,
) -> Recording:
    """A :class:`Recording` with ``world``'s outlines and the poses of ``rows``.

    ``rows`` are trace rows ``(step, t, body, x, y, angle, vx, vy, omega)``, all bodies of a
    step together, in the world's body order; every ``every``-th step is kept. ``draw``: layers
    to draw from the trace (``FROM_TRACE``; velocities come from its rows). ``energy``: the
    energies by part, computed by putting ``world`` in each kept state (``world`` is changed);
    the work done by forces and motors is not in a trace: 0 when nothing but gravity, contacts,
    joints and springs acts (:func:`~sandbox.energy.does_work`), else NaN (the panel says so).
    """
    rec = Recording.from_world(world, check_trace_layers(draw))
    n = len(world.bodies)
    if n == 0:
        return rec
    data = np.array([r[3:9] for r in rows], dtype=float).reshape(-1, n, 6)
    times = [rows[k * n][1] for k in range(len(data))]
    work = math.nan if does_work(world) else 0.0
    for k in range(0, len(data), max(1, int(every))):
        values: dict[str, float] = {}
        if energy:
            set_state(world, data[k])
            values = {**energy_terms(world), "energy.work": work}
        overlay = {"velocities": data[k, :, 3:5]}
        rec.add_frame(data[k, :, :3], times[k], overlay=overlay, **values)
    return rec
