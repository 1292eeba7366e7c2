"""Running a few lines of Python in a new process with a compile cache of its own, for tests of
what a later process loads from the cache or compiles afresh."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path


def in_process(folder: Path, code: str, cache: str = "cache") -> list[str]:
    """The first two lines ``code`` prints, run in a new process with ``folder`` on its path,
    working in ``folder``, and its compile cache in ``folder``/``cache`` (numba's settings of
    this process left out; a crash fails the test)."""
    env = {k: v for k, v in os.environ.items() if not k.startswith("NUMBA_")}
    env.update(PYTHONPATH=os.pathsep.join([str(folder), *sys.path]))
    env["NUMBA_CACHE_DIR"] = str(folder / cache)
    res = subprocess.run(
        [sys.executable, "-c", code],
        cwd=folder, env=env, capture_output=True, text=True, timeout=120,
    )  # fmt: skip
    assert res.returncode == 0, res.stderr
    return res.stdout.split("\n")[:2]
