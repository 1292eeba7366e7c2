"""Turn trace rows (from this engine or from pymunk) back into a recording to draw."""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence

import numpy as np

from sandbox.energy import does_work, energy_terms
from sandbox.overlays import FROM_TRACE, LayerError, parse_layers
from sandbox.recording import Recording

MAX_FRAMES = 600  # the most frames a recording of a long run keeps (20 s of GIF at 30 fps)


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
        _add_state(rec, world, data[k], times[k], energy, work)
    return rec


def _add_state(rec: Recording, world, state: np.ndarray, t: float, energy: bool, work: float):
    """One frame of ``rec`` from a state (n, 6) ``x, y, angle, vx, vy, omega`` at ``t`` (s)."""
    values: dict[str, float] = {}
    if energy:
        set_state(world, state)
        values = {**energy_terms(world), "energy.work": work}
    rec.add_frame(state[:, :3], t, overlay={"velocities": state[:, 3:5]}, **values)


def frame_stride(steps: int, every: int = 1, max_frames: int = MAX_FRAMES) -> int:
    """The step stride that keeps at most ``max_frames`` frames of steps 0..``steps``.

    At least ``every``; larger when ``steps + 1`` steps every ``every`` would exceed the bound.
    """
    return max(1, int(every), math.ceil((int(steps) + 1) / max(1, int(max_frames))))


class RowSampler:
    """Build a :class:`Recording` from a run's trace rows as they come, every ``every``-th step.

    The streaming form of :func:`recording_from_rows` (same ``draw`` and ``energy``; ``world``
    gives the outlines and, with ``energy``, is put in each kept state): memory is bounded by
    the frames kept, not by the length of the run (pick ``every`` with :func:`frame_stride`).
    ``keep_last`` also keeps the final step (a picture of where the run ended).
    """

    def __init__(
        self,
        world,
        every: int = 1,
        keep_last: bool = False,
        draw: str | Iterable[str] | None = (),
        energy: bool = False,
    ) -> None:
        self.recording = Recording.from_world(world, check_trace_layers(draw))
        self.world, self.every, self.keep_last, self.energy = (
            world,
            max(1, int(every)),
            keep_last,
            energy,
        )
        self.work = math.nan if does_work(world) else 0.0
        self._last: tuple[Sequence[tuple], float] | None = None

    def add(self, step: int, t: float, rows: Sequence[tuple]) -> None:
        """The rows of step ``step`` at time ``t`` (s), all bodies in the world's order."""
        if step % self.every == 0:
            self._add(rows, t)
            self._last = None
        elif self.keep_last:
            self._last = (rows, t)

    def finish(self) -> Recording:
        """The recording (with the final step when ``keep_last``)."""
        if self._last is not None:
            self._add(*self._last)
            self._last = None
        return self.recording

    def _add(self, rows: Sequence[tuple], t: float) -> None:
        state = np.array([r[3:9] for r in rows], dtype=float).reshape(-1, 6)
        _add_state(self.recording, self.world, state, t, self.energy, self.work)
