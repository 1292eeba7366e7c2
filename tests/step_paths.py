"""The two ways a world steps, side by side: one compiled call (``sandbox.step.fast_step``,
``free_step``, ``soft_step``) and the same stages called one by one from Python
(``sandbox.staged_step.staged_step``, which a stage timer selects). Both run the same functions
in the same order, so the tests compare them with exact equality."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from sandbox import World
from sandbox.staged_step import StageTimer


def fast_and_staged(make: Callable[[], World], steps: int) -> tuple[World, World]:
    """Two worlds from ``make``, the second with a stage timer (the staged path), each stepped
    ``steps`` times in turn."""
    fast, staged = make(), make()
    staged.timer = StageTimer()  # a timer makes the world take the staged path
    for _ in range(steps):
        fast.step()
        staged.step()
    return fast, staged


def same_state(a: World, b: World) -> bool:
    """Bit-identical positions, velocities and orientations."""
    return all(np.array_equal(getattr(a, k), getattr(b, k)) for k in ("com", "vel", "omega", "rot"))
