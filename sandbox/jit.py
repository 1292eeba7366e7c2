"""One source, two speeds: hot loops are plain Python compiled by numba.

Set ``SANDBOX_JIT=0`` in the environment to run the very same functions as plain Python, for
stepping through them in a debugger or reading a traceback line by line.

Compiled code is cached on disk (``cache=True``) so only the first run compiles. numba checks a
cached function only against its own source file, so after editing a kernel, a function in
another module that calls it could load stale machine code. To rule that out the cache lives in
a folder named after a hash of every kernel module's source (``sandbox/__pycache__/numba-<hash>``,
or below ``NUMBA_CACHE_DIR`` when that is set): any edit to a kernel starts a fresh cache.
"""

from __future__ import annotations

import hashlib
import os
import shutil
from pathlib import Path

JIT_ENABLED: bool = os.environ.get("SANDBOX_JIT", "1") != "0"

_PACKAGE = Path(__file__).resolve().parent


def kernel_sources_hash() -> str:
    """A short hash of the source of every module of the package that compiles kernels."""
    digest = hashlib.sha256()
    for path in sorted(_PACKAGE.rglob("*.py")):
        text = path.read_bytes()
        if b"@njit" in text:
            digest.update(path.relative_to(_PACKAGE).as_posix().encode())
            digest.update(text)
    return digest.hexdigest()[:16]


def _use_fresh_cache_dir() -> None:
    """Point numba's cache at a folder keyed by the kernel sources; drop stale sibling folders."""
    import numba

    user_dir = os.environ.get("NUMBA_CACHE_DIR")
    base = Path(user_dir) if user_dir else _PACKAGE / "__pycache__"
    folder = base / f"numba-{kernel_sources_hash()}"
    numba.config.CACHE_DIR = str(folder)
    if not user_dir:  # only tidy the folder we own
        for old in base.glob("numba-*"):
            if old != folder:
                shutil.rmtree(old, ignore_errors=True)


if JIT_ENABLED:
    import numba

    _use_fresh_cache_dir()

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


def entry(function, *args):
    """The compiled machine code of ``function`` for the types of ``args``, callable from Python
    without numba's type dispatch (a call with ten arrays then costs about a microsecond less);
    ``function`` itself when compiling is off. Call it only with arguments of those same types
    (array dtype, dimensions and layout): nothing checks them any more."""
    if not JIT_ENABLED:
        return function
    signature = tuple(function.typeof_pyval(a) for a in args)
    return function.compile(signature)
