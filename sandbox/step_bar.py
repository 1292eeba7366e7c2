"""A bar of a run's steps on a terminal (``sandbox simulate``, ``sandbox compare``), so that a run
of several seconds (the pyramid as plain Python on a machine where nothing is compiled yet, a
long comparison) does not look hung: drawn once a run has gone on for :data:`DELAY` seconds
after its first step, with the count, the rate and the time left, and cleared when it ends.
Nothing is drawn for a shorter run, nor on a screen that is no terminal (a log, a notebook, a
pipe), so what a run prints and writes is the same either way."""

from __future__ import annotations

import sys

DELAY = 2.0  # s: a run still stepping this long after its first step shows its bar


class StepBar:
    """A bar of ``total`` steps on ``screen`` (default standard error) if it is a terminal and
    not ``quiet`` (see the module). It starts after the first step, whose compile (on a cold
    cache) has a notice and a bar of its own. Use it as a context manager; :meth:`step` once
    each step is made."""

    def __init__(
        self, total: int, screen=None, delay: float | None = None, quiet: bool = False
    ) -> None:
        self.screen = sys.stderr if screen is None else screen
        self.total = total
        self.delay = DELAY if delay is None else delay  # s
        self.shown = not quiet and self.screen.isatty()
        self.bar = None

    def step(self) -> None:
        """One more step is made."""
        if not self.shown:
            return
        if self.bar is None:
            from tqdm import tqdm

            self.bar = tqdm(
                total=self.total,
                initial=1,
                unit="step",
                leave=False,
                delay=self.delay,
                file=self.screen,
            )
        else:
            self.bar.update(1)

    def __enter__(self) -> StepBar:
        return self

    def __exit__(self, *exc: object) -> None:
        if self.bar is not None:
            self.bar.close()
