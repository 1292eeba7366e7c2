"""Prefetching ahead in the position passes (sandbox.prefetch): the byte spans it asks for,
and that it compiles to prefetch instructions (results: the bit-for-bit checks of
the passes in test_wide_positions.py and test_penetration*.py)."""

import numpy as np
import pytest

from sandbox.jit import JIT_ENABLED
from sandbox.prefetch import span
from sandbox.records import BODY, CONTACT


def test_span_runs_from_the_first_field_to_the_last_byte_of_the_last():
    # BODY: kind (8 bytes), com (16), vel (16), omega (8): vel..omega is bytes 24 to 47
    assert span(BODY, "vel", "omega") == (24, 47)
    assert span(CONTACT, "a", "a") == (0, 7)
    first, last = span(BODY, "com", "inv_moment")
    assert first == BODY.fields["com"][1] and last == BODY.fields["inv_moment"][1] + 7


@pytest.mark.skipif(not JIT_ENABLED, reason="uncompiled, nothing is prefetched")
def test_prefetch_span_compiles_to_a_prefetch_per_line_and_changes_nothing():
    from sandbox.jit import njit
    from sandbox.prefetch import prefetch_span, where

    @njit
    def summed_after_prefetching(values):
        base, size = where(values)
        prefetch_span(base, base + size * (len(values) - 1))
        return values.sum()

    values = np.arange(100.0)
    assert summed_after_prefetching(values) == 4950.0
    asm = summed_after_prefetching.inspect_asm(summed_after_prefetching.signatures[0])
    assert "prefetch" in asm
