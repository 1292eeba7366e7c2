"""The compiled kernels' vector width (``sandbox/vector_width.py``): on a processor with AVX-512,
numba's target gets LLVM's ``-prefer-256-bit``, so the eight-lane loops run 512 bits wide;
a target set by hand, or a processor without AVX-512, keeps numba's default."""

import os
import re

import numpy as np
import pytest

from sandbox.jit import JIT_ENABLED
from sandbox.vector_width import WIDE, target_features

HOST = "+sse2,+avx,+avx2,+avx512f,+avx512dq,-amx-tile"


def test_a_processor_with_avx512_gets_the_full_width():
    assert target_features(HOST, {}) == HOST + ",-prefer-256-bit"
    assert WIDE == "-prefer-256-bit"


@pytest.mark.parametrize(
    "host", ["+sse2,+avx,+avx2,-avx512f", "+sse2,+avx,+avx2", "+avx512fp16,-avx512f"]
)
def test_without_avx512_nothing_changes(host):
    assert target_features(host, {}) is None


@pytest.mark.parametrize("name", ["NUMBA_CPU_NAME", "NUMBA_CPU_FEATURES"])
def test_a_target_set_by_hand_wins(name):
    assert target_features(HOST, {name: "skylake"}) is None
    assert target_features(HOST, {name: ""}) == HOST + ",-prefer-256-bit"  # set but empty


def _host_features() -> str:
    from llvmlite import binding

    return binding.get_host_cpu_features().flatten()


@pytest.mark.skipif(not JIT_ENABLED, reason="compiled kernels only")
def test_the_compiled_loops_use_512_bit_registers_where_the_processor_has_them():
    import numba

    expected = target_features(_host_features(), os.environ)
    if expected is None:
        pytest.skip("no AVX-512 here, or numba's target set by hand")
    assert numba.config.CPU_FEATURES == expected  # set by sandbox.jit, before any compile

    @numba.njit  # not cached: its machine code is made here
    def scale(a, b):
        for i in range(a.shape[0]):
            a[i] = a[i] * b[i] + 1.0

    a = np.ones(64)
    scale(a, a)
    assert a[0] == 2.0
    machine_code = next(iter(scale.inspect_asm().values()))
    assert re.search(r"\bzmm\d+\b", machine_code), "the loop was not vectorised 512 bits wide"
