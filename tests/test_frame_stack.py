"""Python's frame stack keeps its chunks while the engine compiles (sandbox.frame_stack): calls
going deep and back across a chunk boundary fault no page in again, and the allocator gives
the interpreter's arenas mapped and unmapped pages as CPython's own does."""

import ctypes
import os
import subprocess
import sys

import numpy as np
import pytest

from sandbox import jit

pytestmark = pytest.mark.skipif(not jit.JIT_ENABLED, reason="the allocator is compiled")

if jit.JIT_ENABLED:
    from sandbox.frame_stack import CHUNK, KEPT, allocator, applies

# calls 400 deep and back, as numba's compiler makes them, crossing chunk boundaries each time
CALLS = """
import resource
from sandbox.frame_stack import keep_frame_stack
kept = keep_frame_stack()
def deep(n):
    return 0 if n == 0 else deep(n - 1) + 1
deep(400)
before = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
for _ in range(1000):
    deep(400)
print(kept, (resource.getrusage(resource.RUSAGE_SELF).ru_minflt - before) / 1000)
"""

# a process that compiles puts the allocator in on its first compile, and one that does not
# leaves the interpreter's own
FIRST_COMPILE = """
from sandbox import frame_stack, jit
print(bool(frame_stack._INSTALLED))
jit.njit(cache=False)(lambda x: x + 1)(1)
print(bool(frame_stack._INSTALLED))
"""


def run(script: str, heap: str = "keep") -> list[str]:
    env = dict(os.environ, SANDBOX_HEAP=heap)
    return subprocess.run(
        [sys.executable, "-c", script], env=env, capture_output=True, text=True, check=True
    ).stdout.split()


@pytest.mark.skipif(not applies(), reason="CPython 3.11 or later on Linux")
def test_deep_calls_fault_no_page_in_again():
    kept, faults = run(CALLS)
    assert kept == "True"
    assert float(faults) < 0.5  # 0 here
    left, system_faults = run(CALLS, heap="system")
    assert left == "False"
    assert float(system_faults) >= 4  # a 16 KiB chunk mapped afresh each time: 8 here


@pytest.mark.skipif(not applies(), reason="CPython 3.11 or later on Linux")
def test_put_in_by_the_first_compile_only():
    assert run(FIRST_COMPILE) == ["False", "True"]
    assert run(FIRST_COMPILE, heap="system") == ["False", "False"]


def mapped(address: int, size: int) -> bool:
    """Whether all of ``size`` bytes at ``address`` are mapped in this process (msync fails
    with ENOMEM where they are not)."""
    return ctypes.CDLL(None).msync(ctypes.c_void_p(address), ctypes.c_size_t(size), 1) == 0


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="mmap on Linux")
def test_the_allocator_keeps_chunks_and_unmaps_the_rest():
    take, give_back = allocator()
    shelf = np.zeros(KEPT + 1, dtype=np.intp)
    kept = shelf.ctypes.data_as(ctypes.POINTER(ctypes.c_ssize_t))
    chunks = [take.ctypes(kept, CHUNK) for _ in range(KEPT + 1)]
    assert 0 not in chunks and len(set(chunks)) == KEPT + 1
    for address in chunks:
        ctypes.memset(address, 7, CHUNK)  # writable, all of it
        assert mapped(address, CHUNK)
    for address in chunks:
        give_back.ctypes(kept, address, CHUNK)
    assert shelf[0] == KEPT  # the first KEPT kept, in order; the last one unmapped
    assert list(shelf[1:]) == chunks[:KEPT]
    assert not mapped(chunks[-1], CHUNK)
    assert take.ctypes(kept, CHUNK) == chunks[KEPT - 1]  # the last kept is taken first
    assert shelf[0] == KEPT - 1

    arena = take.ctypes(kept, 2**20)  # an object arena: fresh pages, never kept
    ctypes.memset(arena, 1, 2**20)
    give_back.ctypes(kept, arena, 2**20)
    assert shelf[0] == KEPT - 1 and not mapped(arena, 2**20)


def test_system_leaves_the_interpreter_alone(monkeypatch):
    monkeypatch.setenv("SANDBOX_HEAP", "system")
    assert not applies()
