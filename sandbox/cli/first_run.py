"""How the engine runs a command on a machine where it was never compiled.

Compiling the kernels a scene needs takes 40 to 50 s the first time (every kernel, ``sandbox
warmup``, one to two minutes; numba caches the machine code for later runs). For a small scene,
running the same functions uncompiled (plain Python, ``SANDBOX_JIT=0``, on the record view of
:mod:`sandbox.plain_records`) finishes long before that: drop's 240 steps take 0.4 s and the
pyramid's 120 steps 6 to 7 s. So when the compile cache is not warm (``sandbox warmup`` has
not run) and the scene is small, the command runs uncompiled, says so in one line, and starts
``sandbox warmup`` in the background (at a low priority, one at a time) so that the next runs are
compiled. A larger scene compiles in the foreground, with a notice and a progress bar on a
terminal.

``SANDBOX_JIT=0`` or ``1`` set by the user decides alone; ``SANDBOX_WARMUP=off`` keeps the
background warmup from starting.
"""

from __future__ import annotations

import os
import subprocess
import sys
import time

from sandbox.cli.common import note

# bodies x steps up to which an uncompiled run is done sooner than compiling. Measured on the
# project's 2-core machine: uncompiled, the bundled pyramid (56 boxes) takes 6 to 7 s for 120
# steps and 13 s for 300 (0.8 ms per body and step), rain (103 circles) 10 s for 300 (0.3 ms),
# drop (2 bodies) 0.4 s for 240; compiling and running takes 50 to 54 s. At the bound, boxes
# take about 30 s uncompiled, still well under the compile; every bundled scene at the default
# 300 steps runs uncompiled
PLAIN_BODY_STEPS = 40_000
LOCK = "warming"  # file in the cache folder while a background warmup runs
STALE = 600.0  # s: a lock older than this is from a warmup that died


def choose_engine_speed(spec: dict, steps: int) -> None:
    """Before the engine is imported: run uncompiled if that is sooner (see the module)."""
    if "SANDBOX_JIT" in os.environ or engine_imported():
        return
    from sandbox.compile_cache import has_kernel, is_warm

    if is_warm():
        return
    if len(spec["bodies"]) * steps <= PLAIN_BODY_STEPS:
        later = "; it compiles in the background for the next runs" if run_uncompiled() else ""
        note(f"the engine is not compiled for this machine yet: this run is plain Python{later}")
    elif not has_kernel(scene_kernel(spec)):
        note("compiling the engine for this machine, once: about a minute; later runs load it")
        from sandbox.jit import compile_noted  # imports numba: this run compiles anyway

        compile_noted()


def run_uncompiled() -> bool:
    """Run this process, and the processes it starts, uncompiled (``SANDBOX_JIT=0``, before the
    engine is imported), while ``sandbox warmup`` compiles the engine in the background for the
    next runs (:func:`start_background_warmup`). Returns whether that warmup runs."""
    from sandbox.compile_cache import CACHE_FOLDER

    os.environ["SANDBOX_JIT"] = "0"
    return start_background_warmup(CACHE_FOLDER)


def scene_kernel(spec: dict) -> str:
    """The compiled step a validated scene runs, by the world's own rule
    (:func:`sandbox.compile_cache.step_kernel`)."""
    from sandbox.compile_cache import step_kernel

    shapes = sum(len(body.get("shapes", [])) for body in spec["bodies"])
    solver = spec.get("settings", {}).get("solver", "")
    return step_kernel(shapes, len(spec.get("joints", [])), solver)


def engine_imported() -> bool:
    """Whether the engine (and so numba's choice) was imported already in this process."""
    return "sandbox.jit" in sys.modules


def start_background_warmup(folder) -> bool:
    """Start ``sandbox warmup --quiet`` detached at low priority, unless one already runs or
    there is no cache to fill. Returns whether one runs now."""
    if folder is None or os.environ.get("SANDBOX_WARMUP") == "off":
        return False
    lock = folder / LOCK
    try:
        if os.name == "posix":  # one at a time; a lock whose warmup was killed holds nothing
            busy = running_warmup(folder) is not None
        else:  # no asking whether a process lives there: a fresh lock is a running warmup
            busy = lock.exists() and time.time() - lock.stat().st_mtime < STALE
        if busy:
            return True
        lock.write_text(str(os.getpid()))
    except OSError:
        return False
    env = {**os.environ, "SANDBOX_JIT": "1"}  # (the warmup compiles for this very processor)
    try:
        warmup = subprocess.Popen(
            [sys.executable, "-m", "sandbox", "warmup", "--quiet"],
            stdin=subprocess.DEVNULL,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
            env=env,
            start_new_session=True,
            preexec_fn=_lower_priority if hasattr(os, "nice") else None,
        )
        lock.write_text(str(warmup.pid))  # whose lock: running_warmup() asks if it still runs
    except OSError:
        return False
    return True


def running_warmup(folder) -> int | None:
    """The process id of a background warmup compiling into ``folder`` now (its lock is
    there, younger than :data:`STALE`, and its process alive), or None. (None on Windows,
    where asking whether a process lives would end it: nothing waits for a warmup there.)"""
    if folder is None or os.name != "posix":
        return None
    lock = folder / LOCK
    try:
        if time.time() - lock.stat().st_mtime >= STALE:
            return None
        pid = int(lock.read_text())
    except (OSError, ValueError):
        return None
    try:
        if os.waitpid(pid, os.WNOHANG)[0] == pid:  # this process started it, and it ended
            return None
    except OSError:  # not a child of this process (ChildProcessError): os.kill tells
        pass
    try:
        os.kill(pid, 0)  # no signal: whether the process exists
    except ProcessLookupError:
        return None
    except PermissionError:  # it exists, another user's
        pass
    return pid


def wait_for_warmup(folder, poll: float = 0.5) -> bool:
    """If a background warmup (started by an earlier run) is compiling into ``folder``, wait
    for it to end rather than compile the same kernels beside it, saying so in one line (on
    a terminal with the time so far, redrawn every second). Returns whether it waited."""
    if running_warmup(folder) is None:
        return False
    print(
        "the engine is compiling in the background (an earlier run started it): waiting for it",
        flush=True,
    )
    from contextlib import nullcontext

    from sandbox.cli.progress import TickingBar

    waiting = "waiting for the background warmup"
    screen = sys.stdout
    clock = TickingBar(screen, 1, "", str, line=waiting) if screen.isatty() else nullcontext()
    with clock:
        while running_warmup(folder) is not None:
            time.sleep(poll)
    return True


def _lower_priority() -> None:
    os.nice(10)
