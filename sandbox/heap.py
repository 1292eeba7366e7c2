"""Freed memory kept for the next step: the C heap's settings while the engine is compiled.

A compiled step allocates its work arrays as it goes (the velocity lanes, the colours, the
pass orders, the layers: megabytes in a pile of thousands of bodies) and frees them at its
end. glibc's ``malloc`` serves an array over its mmap threshold with pages fresh from the
system and, once the free space at the top of its heap passes its trim threshold, gives that
back. Its thresholds adapt to the largest array freed so far, but the step's arrays still
came out of, and went back to, the system every step: in the rain of 5,000 discs 45 page
faults a step, 0.07 to 0.2 ms of system time, and every fresh page read first from memory.

:func:`keep_heap` sets both thresholds (``mallopt``, where the C library is glibc), so that
such arrays come from the heap and stay there for the next step. Freed memory is then kept
by the process up to :data:`TRIM` at the heap's top (arrays of :data:`MMAP` and more are
still mapped and unmapped alone). :data:`MEASURED` says what it changed.
Set ``SANDBOX_HEAP=system`` to leave the C library's own settings.
"""

from __future__ import annotations

import ctypes
import os
import sys

M_TRIM_THRESHOLD, M_MMAP_THRESHOLD = -1, -3  # glibc's <malloc.h>
MMAP = 32 * 2**20  # bytes: smaller arrays come from the heap
TRIM = 128 * 2**20  # bytes: free space at the heap's top kept for the next step
MEASURED = "rain of 5,000 discs: 45 to 46 page faults a step before, 3.4 after"


def own_settings() -> bool:
    """Whether ``SANDBOX_HEAP=system`` asks to leave the C library's and the interpreter's own
    memory settings (this module's heap, :mod:`sandbox.frame_stack`'s frame stack)."""
    return os.environ.get("SANDBOX_HEAP", "keep") == "system"


def keep_heap() -> bool:
    """Set the heap's thresholds (:data:`MMAP`, :data:`TRIM`) for the whole process, once,
    unless ``SANDBOX_HEAP=system`` or the C library is not glibc (then nothing changes).
    Returns whether they were set."""
    if own_settings() or not sys.platform.startswith("linux"):
        return False
    try:
        libc = ctypes.CDLL(None)  # the symbols the process has loaded: the C library's
        libc.gnu_get_libc_version  # noqa: B018 - glibc only: musl has mallopt, and ignores it
        mallopt = libc.mallopt
    except (OSError, AttributeError):
        return False
    mallopt.argtypes, mallopt.restype = (ctypes.c_int, ctypes.c_int), ctypes.c_int
    return bool(mallopt(M_MMAP_THRESHOLD, MMAP)) and bool(mallopt(M_TRIM_THRESHOLD, TRIM))
