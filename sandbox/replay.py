"""Turn trace rows (from this engine or from pymunk) back into a recording to draw."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from sandbox.recording import Recording

MAX_FRAMES = 600  # the most frames a recording of a long run keeps (20 s of GIF at 30 fps)


def recording_from_rows(world, rows: Sequence[tuple], every: int = 1) -> Recording:
    """A :class:`Recording` with ``world``'s outlines and the poses of ``rows``.

    ``rows`` are trace rows ``(step, t, body, x, y, angle, vx, vy, omega)``, all bodies of a
    step together, in the world's body order; every ``every``-th step is kept.
    """
    rec = Recording.from_world(world)
    n = len(world.bodies)
    if n == 0:
        return rec
    data = np.array([r[3:6] for r in rows], dtype=float).reshape(-1, n, 3)
    times = [rows[k * n][1] for k in range(len(data))]
    for k in range(0, len(data), max(1, int(every))):
        rec.add_frame(data[k], times[k])
    return rec


def frame_stride(steps: int, every: int = 1, max_frames: int = MAX_FRAMES) -> int:
    """The step stride that keeps at most ``max_frames`` frames of steps 0..``steps``.

    At least ``every``; larger when ``steps + 1`` steps every ``every`` would exceed the bound.
    """
    return max(1, int(every), math.ceil((int(steps) + 1) / max(1, int(max_frames))))


class RowSampler:
    """Build a :class:`Recording` from a run's rows as they come, keeping every ``every``-th step.

    Memory is bounded by the number of frames kept, not by the length of the run: pick
    ``every`` with :func:`frame_stride`. ``keep_last`` also keeps the final step (for a picture
    of where the run ended).
    """

    def __init__(self, world, every: int = 1, keep_last: bool = False) -> None:
        self.recording = Recording.from_world(world)
        self.every = max(1, int(every))
        self.keep_last = keep_last
        self._last: tuple[Sequence[tuple], float] | None = None
        self._n = len(world.bodies)

    def add(self, step: int, t: float, rows: Sequence[tuple]) -> None:
        """The rows of step ``step`` at time ``t`` (s), all bodies in the world's order."""
        if step % self.every == 0:
            self.recording.add_frame(self._poses(rows), t)
            self._last = None
        elif self.keep_last:
            self._last = (rows, t)

    def finish(self) -> Recording:
        """The recording (with the final step when ``keep_last``)."""
        if self._last is not None:
            rows, t = self._last
            self.recording.add_frame(self._poses(rows), t)
            self._last = None
        return self.recording

    def _poses(self, rows: Sequence[tuple]) -> np.ndarray:
        return np.array([r[3:6] for r in rows], dtype=float).reshape(self._n, 3)
