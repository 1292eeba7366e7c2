"""How a command ends: exit statuses, the one ``error:`` line, interrupts and termination.

Every failure becomes one line on stderr, ``error: <what>: <why>``, and no traceback
(``SANDBOX_DEBUG=1`` prints the traceback too):

- exit 2, bad input: a :class:`~sandbox.cli.common.CliError` or
  :class:`~sandbox.scene_fields.SceneError` (a ``ValueError`` whose ``path`` names the field), or
  anything the scene's world refused while it was being built (see :func:`input_phase`);
- exit 1, a run that failed after its input was accepted: :class:`~sandbox.SimulationError`
  (divergence), ``OSError`` (disk full, a folder gone), ``MemoryError``, ``OverflowError``,
  numba errors, anything else;
- exit 130 on Ctrl-C (SIGINT), 143 on SIGTERM and 129 on SIGHUP, quietly: 128 + the signal
  number, the status a shell reports for a process killed by that signal, so a caller's ``$?``
  reads the same whether the signal came before or after the handler was installed, and a script
  can tell a user's Ctrl-C (130) from a supervisor's stop (143).

Signals are turned into exceptions, so ``finally`` blocks run and the command's temporary files
are removed (:mod:`sandbox.atomic`). Warnings (numpy overflow and the like) are counted and
summarised in one ``warning:`` line after a run that succeeded, instead of one line each.
"""

from __future__ import annotations

import _thread
import contextlib
import os
import signal
import sys
import threading
import traceback
import warnings
from collections.abc import Callable, Iterator

EXIT_FAILED = 1
EXIT_BAD_INPUT = 2
_HANDLED = {"SIGTERM": 143, "SIGHUP": 129}
_MAX_LINE = 1000  # characters of an error message shown on its one line (a list of lessons fits)


class Stopped(BaseException):
    """A signal asking the command to stop (SIGTERM, SIGHUP); ``status`` is its exit status."""

    def __init__(self, signum: int, status: int) -> None:
        super().__init__(f"stopped by signal {signum}")
        self.signum, self.status = signum, status


def debug() -> bool:
    """True when ``SANDBOX_DEBUG`` asks for tracebacks."""
    return os.environ.get("SANDBOX_DEBUG", "") not in ("", "0")


def one_line(text: str) -> str:
    """``text`` on one line: whitespace runs (newlines too) collapsed, control characters
    escaped, at most a few hundred characters."""
    text = " ".join(str(text).split())
    text = "".join(c if c.isprintable() else repr(c)[1:-1] for c in text)
    return text if len(text) <= _MAX_LINE else text[: _MAX_LINE - 3] + "..."


def is_bad_input(err: BaseException) -> bool:
    """Bad input: a ``ValueError`` that names the offending field in ``path``."""
    return isinstance(err, ValueError) and isinstance(getattr(err, "path", None), str)


def describe(err: BaseException) -> tuple[int, str]:
    """The exit status and the ``error:`` line for a failure."""
    from sandbox.errors import SimulationError

    if is_bad_input(err):
        message = getattr(err, "message", None) or str(err)
        return EXIT_BAD_INPUT, f"error: {err.path or 'scene'}: {one_line(message)}"
    if isinstance(err, SimulationError):
        return EXIT_FAILED, f"error: {one_line(str(err))}"
    if isinstance(err, OSError):
        where = f"{err.filename}: " if err.filename else ""
        why = err.strerror or str(err) or type(err).__name__
        return EXIT_FAILED, f"error: {one_line(where + why)}"
    if isinstance(err, MemoryError):
        return EXIT_FAILED, "error: out of memory: try fewer steps, fewer bodies or no GIF"
    kind = type(err).__name__
    module = type(err).__module__.split(".")[0]
    if module == "numba":
        kind = f"compiled kernel failed ({kind})"
    message = str(err) or "no message"
    hint = " (SANDBOX_DEBUG=1 shows the traceback)"
    return EXIT_FAILED, f"error: {one_line(f'{kind}: {message}')}{hint}"


class Again:
    """A signal sent to the main thread again a moment from now: the signal whose exception a
    finaliser dropped (:func:`signals_as_exceptions`). ``dropped``: the next delivery raises
    again (a second signal is otherwise ignored); ``hooked``: the unraisable hook is running."""

    DELAY = 0.01  # s: long after the finaliser and the hook have returned

    def __init__(self) -> None:
        self.dropped = self.hooked = False
        self.timers: list[threading.Timer] = []

    def later(self, signum: int) -> None:
        """Deliver ``signum`` to the main thread's handler after :data:`DELAY`."""
        timer = threading.Timer(self.DELAY, _thread.interrupt_main, args=(signum,))
        timer.daemon = True
        self.timers.append(timer)
        timer.start()

    def cancel(self) -> None:
        """No more deliveries (the block has ended)."""
        for timer in self.timers:
            timer.cancel()


@contextlib.contextmanager
def signals_as_exceptions() -> Iterator[list[int]]:
    """SIGTERM and SIGHUP raise :class:`Stopped` while the block runs, SIGINT
    ``KeyboardInterrupt``; a second signal while stopping is ignored, so cleanup finishes.

    Yields the list of exit statuses (128 + the signal number) of the signals received, so a
    caller can tell an error that an interrupt caused inside a library (which may swallow the
    interrupt and fail otherwise: matplotlib once reported an invalid affine matrix) from a
    real failure. Signals the caller ignores (``nohup``, a background job) stay ignored. Only in
    the main thread (elsewhere signals cannot be handled): there the block runs unchanged.

    A signal that arrives while a finaliser runs (an object's ``__del__``, a weak reference's
    callback: llvmlite frees LLVM's objects so, thousands of times while numba compiles) raises
    inside the finaliser, and Python drops what a finaliser raises: the command went on as if
    nothing had come (a stopped warmup compiled on for a minute and exited 0). Python hands
    what it dropped to ``sys.unraisablehook``; here the hook has the signal come again a moment
    later (:class:`Again`), and the handler raises once more, in the code the finaliser
    interrupted.
    """
    received: list[int] = []
    if threading.current_thread() is not threading.main_thread():
        yield received
        return
    again = Again()

    def handler(signum, frame):
        if again.hooked:  # inside the hook: what it raised here would be dropped as well
            again.later(signum)
            return
        if received and not again.dropped:
            return
        again.dropped = False
        if not received:
            received.append(128 + signum)
        if signum == signal.SIGINT:
            raise KeyboardInterrupt
        raise Stopped(signum, 128 + signum)

    previous_hook = sys.unraisablehook

    def unraisable(info) -> None:
        if not (received and isinstance(info.exc_value, (Stopped, KeyboardInterrupt))):
            previous_hook(info)
            return
        again.hooked, again.dropped = True, True
        try:
            again.later(received[0] - 128)
        finally:
            again.hooked = False

    saved = {}
    names = list(_HANDLED)
    if signal.getsignal(signal.SIGINT) is signal.default_int_handler:
        names.append("SIGINT")
    for name in names:
        signum = getattr(signal, name, None)
        if signum is None or signal.getsignal(signum) is signal.SIG_IGN:
            continue
        saved[signum] = signal.signal(signum, handler)
    sys.unraisablehook = unraisable
    try:
        yield received
    finally:
        again.cancel()
        sys.unraisablehook = previous_hook
        for signum, old in saved.items():
            signal.signal(signum, old)


@contextlib.contextmanager
def warnings_summarised(summary: list[str]) -> Iterator[None]:
    """Count warnings instead of printing them; ``summary`` gets one line describing them."""
    if debug():
        yield
        return
    seen: list[str] = []

    def collect(message, category, filename, lineno, file=None, line=None):
        seen.append(f"{category.__name__}: {message}")

    with warnings.catch_warnings():
        warnings.showwarning = collect
        yield
    if seen:
        many = f"{len(seen)} warnings" if len(seen) > 1 else "1 warning"
        summary.append(
            f"warning: {many} during the run, first {one_line(seen[0])} "
            "(SANDBOX_DEBUG=1 shows each)"
        )


def run_command(command: Callable[[], int]) -> int:
    """Run ``command`` and turn every way it can end into an exit status and at most a line."""
    summary: list[str] = []
    received: list[int] = []
    try:
        with signals_as_exceptions() as received, warnings_summarised(summary):
            status = command()
    except KeyboardInterrupt:
        _traceback_if_debug()
        return 130
    except Stopped as stop:
        _traceback_if_debug()
        return stop.status
    except BrokenPipeError:  # output piped into e.g. `head`, which stopped reading
        with contextlib.suppress(OSError):
            os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())  # no error at exit
        return 0
    except Exception as err:
        _traceback_if_debug()
        stop = interrupt_behind(err)
        if stop is not None:
            return stop
        if received:  # an interrupt a library swallowed and failed over
            return received[0]
        status, line = describe(err)
        print(line, file=sys.stderr)
        return status
    if received:  # an interrupt a library swallowed, and the command finished all the same
        return received[0]
    for line in summary:
        print(line, file=sys.stderr)
    return status


def interrupt_behind(err: BaseException) -> int | None:
    """The exit status of a Ctrl-C or a stop signal that ``err`` was raised over, if any: an
    interrupt arriving inside a C extension's callback (a GIF encoder writing through Python)
    comes back out as another error, with the interrupt as its cause or context."""
    seen: set[int] = set()
    link: BaseException | None = err
    while link is not None and id(link) not in seen:
        seen.add(id(link))
        if isinstance(link, KeyboardInterrupt):
            return 130
        if isinstance(link, Stopped):
            return link.status
        link = link.__cause__ or link.__context__
    return None


def _traceback_if_debug() -> None:
    if debug():
        traceback.print_exc()
