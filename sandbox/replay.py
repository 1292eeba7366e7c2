"""Turn trace rows (from this engine or from pymunk) back into a recording to draw."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from sandbox.recording import Recording


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
