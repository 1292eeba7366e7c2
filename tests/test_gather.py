"""``sandbox.gather.gather_lanes``: eight numbers from eight places of an array into eight side
by side, compiled (one gather instruction where the processor has one) and in Python alike, as
the wide sweeps' hand-in uses it."""

import os
import platform
import re
import subprocess
import sys

import numpy as np
import pytest

from sandbox.gather import WIDTH, gather_lanes, gather_plain
from sandbox.jit import JIT_ENABLED, njit


@njit
def gather_blocks(numbers, indices, to) -> None:
    # each row of ``indices`` gathered into the eight numbers from to[row] on, plus 3 places
    for row in range(indices.shape[0]):
        gather_lanes(numbers, to[row], indices, row * WIDTH, np.uint64(3))


def case(seed: int = 7):
    """Numbers, rows of eight indices (some copying a number onto itself) and where each row's
    eight go, and what numpy makes of it."""
    rng = np.random.default_rng(seed)
    numbers = rng.standard_normal(200)
    to = np.array([0, 40, 96, 160], dtype=np.uint64)
    indices = rng.integers(0, 190, size=(4, WIDTH)).astype(np.int64)
    indices[1, 2] = 40 + 2 - 3  # lane 2 of row 1 reads the number it writes
    expected = numbers.copy()
    for row in range(4):  # each row reads before it writes, rows one after another
        got = expected[indices[row] + 3].copy()
        expected[int(to[row]) : int(to[row]) + WIDTH] = got
    return numbers, indices, to, expected


def test_gathered_as_numpy_indexes():
    numbers, indices, to, expected = case()
    gather_blocks(numbers, indices, to)
    assert np.array_equal(numbers, expected)


def test_the_python_version_gathers_the_same():
    numbers, indices, to, expected = case(11)
    for row in range(indices.shape[0]):
        gather_plain(numbers, int(to[row]), indices, row * WIDTH, 3)
    assert np.array_equal(numbers, expected)


@pytest.mark.skipif(not JIT_ENABLED, reason="compiled kernels only")
def test_one_gather_instruction_where_the_processor_has_avx512():
    import numba
    from llvmlite import binding

    if "+avx512f" not in binding.get_host_cpu_features().flatten().split(","):
        pytest.skip("no AVX-512 here")

    @numba.njit  # not cached: its machine code is made here
    def one(numbers, indices):
        gather_lanes(numbers, 0, indices, 0, 0)

    numbers, indices = np.arange(16.0), np.arange(8, 16, dtype=np.int64)
    one(numbers, indices)
    assert numbers[:8].tolist() == list(range(8, 16))
    machine_code = next(iter(one.inspect_asm().values()))
    assert re.search(r"\bvgatherqpd\b", machine_code), "no gather instruction"


@pytest.mark.skipif(not JIT_ENABLED, reason="compiled kernels only")
@pytest.mark.skipif(platform.machine() not in ("x86_64", "AMD64"), reason="an x86 target")
@pytest.mark.parametrize("cpu", ["x86-64", "haswell"])
def test_a_processor_without_avx512_gets_the_same_numbers(tmp_path, cpu):
    # numba's target set to plain x86-64 (SSE2, no gather instruction: LLVM loads the numbers
    # one by one) or to AVX2 (four-wide gathers, two for eight)
    code = (
        "import numpy as np; from tests.test_gather import case, gather_blocks\n"
        "numbers, indices, to, expected = case(5)\n"
        "gather_blocks(numbers, indices, to)\n"
        "assert np.array_equal(numbers, expected)\n"
    )
    env = dict(os.environ, NUMBA_CPU_NAME=cpu, NUMBA_CACHE_DIR=str(tmp_path))
    env.pop("NUMBA_CPU_FEATURES", None)
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    done = subprocess.run(
        [sys.executable, "-c", code], cwd=root, env=env, capture_output=True, text=True
    )
    assert done.returncode == 0, done.stderr[-2000:]


@pytest.mark.skipif(not JIT_ENABLED, reason="compiled kernels only")
def test_with_bounds_checks_an_index_past_the_end_is_an_index_error():
    import numba

    @numba.njit(boundscheck=True)
    def checked(numbers, indices):
        gather_lanes(numbers, 0, indices, 0, 0)

    numbers, indices = np.arange(16.0), np.arange(8, 16, dtype=np.int64)
    checked(numbers, indices)
    assert numbers[:8].tolist() == list(range(8, 16))
    indices[3] = 16
    with pytest.raises(IndexError):
        checked(numbers, indices)
