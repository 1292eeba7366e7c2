"""How wide the vector instructions of the compiled kernels are.

The wide sweeps visit eight contacts at a time, one in each lane of a block
(:mod:`sandbox.solvers.wide`): eight numbers of a field side by side, 512 bits. On a processor
with AVX-512, LLVM (numba's compiler) still makes 256-bit instructions unless told otherwise:
its tuning for Intel's server processors prefers them (``prefer-256-bit``), as the first of
them (Skylake) slowed their clock for the wider ones. So each block took two passes of four
lanes. Told to use the full width (the feature ``-prefer-256-bit`` added to the host's), it
takes one: on the project's 2-core machine (Intel Emerald Rapids), ten sweeps of the pyramid
of base 40's 2,350 contacts took 225 us against 315 (the visits alone 155 against 250), with
the same numbers to the bit: no instruction changes what it computes, only how many lanes it
works on at once (numba's math is not reordered, and a sum is not split across lanes).

Applied when the processor has AVX-512 (without it there is nothing wider to allow) and
numba's target is not set by hand (``NUMBA_CPU_NAME`` or ``NUMBA_CPU_FEATURES``: those win).
:mod:`sandbox.jit` sets it before anything compiles; the cached machine code is numba's per
target, so code compiled for one width is never loaded for the other.
"""

from __future__ import annotations

from collections.abc import Mapping

WIDE = "-prefer-256-bit"  # LLVM's tuning feature; removed, the vectoriser may use 512 bits


def target_features(host: str, environ: Mapping[str, str]) -> str | None:
    """The features numba's target should get (``numba.config.CPU_FEATURES``): the host's
    (``host``, LLVM's comma-separated ``+feature`` list) and :data:`WIDE`, on a processor with
    AVX-512 when ``environ`` sets no target of its own; else None (numba's default)."""
    if environ.get("NUMBA_CPU_NAME") or environ.get("NUMBA_CPU_FEATURES"):
        return None
    if "+avx512f" not in host.split(","):
        return None
    return f"{host},{WIDE}"
