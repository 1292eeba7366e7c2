"""Python's frame stack kept while the engine compiles: no fresh pages at every deep call.

CPython (3.11 and later) keeps the frames of running Python functions in chunks of 16 KiB. It
takes each chunk from the object arenas' allocator (``mmap`` on Linux) and gives it back as
soon as the first frame in it returns. numba's compiler recurses deep and back, crossing the
same chunk boundary over and over, so every crossing maps 16 KiB of fresh pages and unmaps them
again: compiling half of the lessons' kernels (one share of ``sandbox warmup --lessons``) took
970,000 page faults and 8.3 s of system time (86 % of its page faults were these).

:func:`keep_frame_stack` puts in an arena allocator that keeps up to :data:`KEPT` freed chunks
for the next crossing, and maps and unmaps every other size (the object arenas) as CPython's own
does. :data:`MEASURED` says what it changed. It is put in when this process first compiles
(:mod:`sandbox.jit`), so a run that only loads compiled kernels is left as it was. Set
``SANDBOX_HEAP=system`` to leave the interpreter's own allocator.
"""

from __future__ import annotations

import ctypes
import functools
import mmap
import sys

import numpy as np
from numba import carray, cfunc, types

from sandbox.compile_cache import CACHE_FOLDER
from sandbox.heap import own_settings

CHUNK = 16 * 1024  # bytes: a chunk of CPython's frame stack (DATA_STACK_CHUNK_SIZE)
KEPT = 16  # freed chunks kept for reuse (256 KiB at most)
PROT = mmap.PROT_READ | mmap.PROT_WRITE  # the pages CPython's arena allocator maps
FLAGS = mmap.MAP_PRIVATE | mmap.MAP_ANONYMOUS
MEASURED = (
    "one share of `sandbox warmup --lessons`: 972,530 page faults and 8.26 s of system time "
    "before, 125,504 and 0.82 s after (one run each: 103.8 s against 93.3 s)"
)

# the C library's mmap and munmap, found by name when the compiled code is loaded (pointers as
# integers of their size)
_map = types.ExternalFunction(
    "mmap", types.intp(types.intp, types.uintp, types.intc, types.intc, types.intc, types.intp)
)
_unmap = types.ExternalFunction("munmap", types.intc(types.intp, types.uintp))


def take(kept, size):  # pragma: no cover - compiled (allocator()), called by the interpreter
    """The allocator's ``alloc(ctx, size)``: a kept chunk if there is one, else fresh pages;
    ``kept`` holds how many are kept, then their addresses."""
    shelf = carray(kept, (KEPT + 1,))
    n = shelf[0]
    if size == CHUNK and n > 0:
        shelf[0] = n - 1
        return shelf[n]
    address = _map(0, size, PROT, FLAGS, -1, 0)
    return 0 if address == -1 else address  # MAP_FAILED: NULL, as CPython's own


def give_back(kept, address, size):  # pragma: no cover - compiled, called by the interpreter
    """The allocator's ``free(ctx, address, size)``: a chunk is kept while there is room, every
    other block unmapped."""
    shelf = carray(kept, (KEPT + 1,))
    n = shelf[0]
    if size == CHUNK and n < KEPT:
        shelf[n + 1] = address
        shelf[0] = n + 1
    else:
        _unmap(address, size)


TAKE = types.intp(types.CPointer(types.intp), types.uintp)
GIVE_BACK = types.void(types.CPointer(types.intp), types.intp, types.uintp)


@functools.cache
def allocator() -> tuple:
    """(take, give_back) compiled as C functions (the first call compiles them, or loads them
    from the cache)."""
    cache = CACHE_FOLDER is not None
    return cfunc(TAKE, cache=cache)(take), cfunc(GIVE_BACK, cache=cache)(give_back)


class ArenaAllocator(ctypes.Structure):
    """CPython's ``PyObjectArenaAllocator``."""

    _fields_ = [("ctx", ctypes.c_void_p), ("alloc", ctypes.c_void_p), ("free", ctypes.c_void_p)]


_SHELF = np.zeros(KEPT + 1, dtype=np.intp)  # the kept chunks: how many, then their addresses
_INSTALLED: list[ArenaAllocator] = []  # the allocator put in (kept alive with its functions)
_BUSY: list[bool] = []  # compiling the allocator: its own compile events do not start it again


def applies() -> bool:
    """Whether this interpreter has the frame stack and arena allocator described above: CPython
    3.11 or later on Linux with the global interpreter lock (the allocator is called holding it),
    unless ``SANDBOX_HEAP=system``."""
    return (
        not own_settings()
        and sys.platform.startswith("linux")
        and sys.implementation.name == "cpython"
        and sys.version_info >= (3, 11)
        and getattr(sys, "_is_gil_enabled", lambda: True)()
    )


def keep_frame_stack() -> bool:
    """Put in the allocator that keeps freed frame-stack chunks, once per process, where it
    :func:`applies` and the interpreter's allocator is still its own (no context pointer).
    Returns whether it is in."""
    if _INSTALLED:
        return True
    if _BUSY or not applies():
        return False
    api = ctypes.pythonapi
    own = ArenaAllocator()
    api.PyObject_GetArenaAllocator(ctypes.byref(own))
    if own.ctx is not None:  # someone else's allocator: leave it
        return False
    _BUSY.append(True)
    try:
        alloc, free = allocator()
    finally:
        _BUSY.clear()
    ours = ArenaAllocator(_SHELF.ctypes.data, alloc.address, free.address)
    api.PyObject_SetArenaAllocator(ctypes.byref(ours))
    _INSTALLED.append(ours)
    return True
