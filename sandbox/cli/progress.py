"""Progress bars for long commands on a terminal.

:class:`TickingBar` (``sandbox warmup``, ``sandbox lessons``): moved by the command as its parts
finish, and redrawn every second in between with the time so far and what the command is doing
(how many kernels compiled), so that a part that takes a minute does not look hung. No rate nor
time left: the parts take from under a second to a minute each.

:class:`StepBar` (``sandbox simulate``): the steps of a run, with their rate and the time left,
for a run that goes on for more than a couple of seconds.
"""

from __future__ import annotations

import sys
import threading
from collections.abc import Callable

STEP_BAR_DELAY = 2.0  # s: a run still stepping this long after its first step shows its bar


class TickingBar:
    """A tqdm bar on ``screen`` over ``total`` parts called ``unit``, whose postfix is
    ``postfix()``, redrawn every ``tick`` seconds by a thread until the bar is closed. Use it as
    a context manager; ``advance()`` when a part is done, ``write(line)`` to print above it.
    With ``line``, that text stands in for the bar (a wait with no parts to count)."""

    def __init__(
        self,
        screen,
        total: int,
        unit: str,
        postfix: Callable[[], str],
        tick: float = 1.0,
        line: str | None = None,
    ) -> None:
        from tqdm import tqdm

        if line is None:
            line = "{desc}{percentage:3.0f}%|{bar}| {n_fmt}/{total_fmt} " + unit
        self.postfix = postfix
        fmt = line + " [{elapsed}{postfix}]"
        self.bar = tqdm(total=total, bar_format=fmt, leave=False, file=screen)
        self.stop = threading.Event()
        self.lock = threading.Lock()  # the ticker and the command draw one at a time
        self.ticker = threading.Thread(target=self._tick, args=(tick,), daemon=True)
        self.ticker.start()

    def _tick(self, tick: float) -> None:
        while not self.stop.wait(tick):
            with self.lock:
                self.bar.set_postfix_str(self.postfix(), refresh=True)

    def advance(self) -> None:
        """One more part done."""
        with self.lock:
            self.bar.set_postfix_str(self.postfix(), refresh=False)
            self.bar.update(1)

    def write(self, line: str) -> None:
        """Print ``line`` above the bar."""
        with self.lock:
            self.bar.write(line, file=self.bar.fp)

    def __enter__(self) -> TickingBar:
        return self

    def __exit__(self, *exc: object) -> None:
        self.stop.set()
        self.ticker.join()
        self.bar.close()


class StepBar:
    """A bar of a run's ``total`` steps on ``screen`` (default standard error), if it is a
    terminal: nothing for a run done within :data:`STEP_BAR_DELAY` seconds of its first step,
    else drawn from then on, with the rate and the time left, and gone when the run ends. It
    starts after the first step, whose compile (on a cold cache) has a notice and a bar of its
    own. Use it as a context manager; ``done(k)`` once step ``k`` (1 to ``total``) is made."""

    def __init__(self, total: int, screen=None, delay: float | None = None) -> None:
        self.screen = sys.stderr if screen is None else screen
        self.total = total
        self.delay = STEP_BAR_DELAY if delay is None else delay  # s
        self.shown = self.screen.isatty()  # a log, a notebook or a pipe gets no bar
        self.bar = None

    def done(self, k: int) -> None:
        """Step ``k`` is made (0: the initial state, not a step)."""
        if not self.shown or k < 1:
            return
        if self.bar is None:
            from tqdm import tqdm

            self.bar = tqdm(
                total=self.total,
                initial=k,
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
