"""One source, two speeds: hot loops are plain Python compiled by numba.

Set ``SANDBOX_JIT=0`` in the environment to run the very same functions as plain Python, for
stepping through them in a debugger or reading a traceback line by line.
"""

from __future__ import annotations

import os

JIT_ENABLED: bool = os.environ.get("SANDBOX_JIT", "1") != "0"

if JIT_ENABLED:
    import numba

    def njit(*args, **kwargs):
        """``numba.njit(cache=True)`` (accepts the same arguments as numba.njit)."""
        kwargs.setdefault("cache", True)
        if args and callable(args[0]) and len(args) == 1 and not kwargs.get("_signature"):
            return numba.njit(cache=True)(args[0])
        return numba.njit(*args, **kwargs)

else:

    def njit(*args, **kwargs):
        """Plain-Python stand-in for ``numba.njit`` (SANDBOX_JIT=0)."""
        if args and callable(args[0]) and len(args) == 1:
            return args[0]
        return lambda f: f
