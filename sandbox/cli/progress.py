"""A progress bar for a long command on a terminal (``sandbox warmup``, ``sandbox lessons``):
moved by the command as its parts finish, and redrawn every second in between with the time so
far and what the command is doing (how many kernels compiled), so that a part that takes a
minute does not look hung. No rate nor time left: the parts take from under a second to a
minute each."""

from __future__ import annotations

import threading
from collections.abc import Callable


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
