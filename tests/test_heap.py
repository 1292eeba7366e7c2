"""The C heap keeps what a compiled step frees (sandbox.heap): arrays of megabytes allocated
and freed as a step does it fault no page in again the next time."""

import os
import subprocess
import sys

import pytest

from sandbox.heap import keep_heap

GLIBC = sys.platform.startswith("linux") and os.confstr("CS_GNU_LIBC_VERSION") is not None

# a step's pattern: five arrays of 0.8 to 4 MB, each written, all freed at its end
STEPS = """
import resource, sys
import numpy as np
from sandbox.heap import keep_heap
print(keep_heap())
def step():
    arrays = [np.ones(n) for n in (300_000, 200_000, 500_000, 100_000, 250_000)]
    return sum(a[0] for a in arrays)
for _ in range(3):
    step()
before = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
for _ in range(20):
    step()
print((resource.getrusage(resource.RUSAGE_SELF).ru_minflt - before) / 20)
"""


def faults_a_step(heap: str) -> tuple[bool, float]:
    """(whether keep_heap set the heap, page faults a step) in a new process."""
    env = dict(os.environ, SANDBOX_HEAP=heap)
    out = subprocess.run(
        [sys.executable, "-c", STEPS], env=env, capture_output=True, text=True, check=True
    ).stdout.split()
    return out[0] == "True", float(out[1])


@pytest.mark.skipif(not GLIBC, reason="the heap's settings are glibc's")
def test_freed_arrays_are_reused_without_faulting_pages_in_again():
    kept, faults = faults_a_step("keep")
    assert kept
    assert faults < 10  # 0 here
    left, system_faults = faults_a_step("system")
    assert not left
    assert system_faults > 500  # glibc's own settings give the top of its heap back: 2,019


def test_system_leaves_the_c_library_alone(monkeypatch):
    monkeypatch.setenv("SANDBOX_HEAP", "system")
    assert keep_heap() is False
