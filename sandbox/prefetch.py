"""Asking the processor for memory ahead of its use (``llvm.prefetch``).

The position passes visit the contacts in an order that jumps about the records (a layer at a
time), so that each contact waits for its record and its bodies' to come from memory. A
prefetch asks for them some contacts ahead and does not wait: by the time the pass reaches
the contact they are in the cache. Uncompiled (``SANDBOX_JIT=0``) it does nothing.

Measured on the rain of 5,000 discs (step 150, 12,761 contacts in layers): a layered pass
after the caches were flushed, 851 and 1,279 us against 1,530 and 2,446 us without (two runs);
the position passes' share of a step (``benchmarks/profile_kernels.py``) 11.5 to 13.5 %
against 18 to 22 %. The same asked for the bodies in the prepare stage, the warm start and
the narrowphase, whose loops go through the records in order, gained nothing there: the
processor's own prefetcher already follows them. A loop that goes through the records in
order but reads two of a record's ten lines gains: the layering's two passes over the
contacts (:func:`sandbox.solvers.shock.contact_layers`), caches flushed, 264 and 243 us
against 321 and 299 us.
"""

from __future__ import annotations

from sandbox.jit import JIT_ENABLED, njit

if JIT_ENABLED:
    import numba
    from llvmlite import ir
    from numba.extending import intrinsic

    @intrinsic
    def prefetch_address(typingctx, address):
        """Prefetch the cache line holding byte ``address`` (an integer) for reading."""
        if not isinstance(address, numba.types.Integer):
            return None

        def codegen(context, builder, signature, args):
            i32, i8p = ir.IntType(32), ir.IntType(8).as_pointer()
            kind = ir.FunctionType(ir.VoidType(), (i8p, i32, i32, i32))
            fn = builder.module.declare_intrinsic("llvm.prefetch", fnty=kind)
            # (address, read, locality 3: keep in every cache level, data cache)
            where = builder.inttoptr(args[0], i8p)
            builder.call(fn, (where, ir.Constant(i32, 0), ir.Constant(i32, 3), ir.Constant(i32, 1)))
            return context.get_dummy_value()

        return numba.types.void(address), codegen

else:

    def prefetch_address(address: int) -> None:
        """Uncompiled: nothing to ask for."""


LINE = 64  # bytes in a cache line
AHEAD = 8  # how many contacts ahead a loop asks for their bodies (their records: twice as far)


@njit(inline="always")
def prefetch_span(first: int, last: int) -> None:
    """Prefetch every cache line from byte address ``first`` to ``last``."""
    for at in range(first, last, LINE):
        prefetch_address(at)
    prefetch_address(last)


@njit(inline="always")
def where(records) -> tuple[int, int]:
    """(address of the first record, bytes a record) of a record array."""
    return records.ctypes.data, records.itemsize


@njit(inline="always")
def prefetch_record(records_at, index: int, span) -> None:
    """Prefetch bytes ``span`` = (first, last) of record ``index`` (``records_at`` from
    :func:`where`)."""
    base, size = records_at
    prefetch_span(base + size * index + span[0], base + size * index + span[1])


@njit(inline="always")
def prefetch_bodies(c, bodies_at, span) -> None:
    """Prefetch bytes ``span`` = (first, last) of the records of contact ``c``'s bodies
    (``bodies_at`` from :func:`where`)."""
    prefetch_record(bodies_at, c["a"], span)
    prefetch_record(bodies_at, c["b"], span)


def span(dtype, first: str, last: str) -> tuple[int, int]:
    """The bytes of a record from field ``first`` to the end of field ``last``."""
    end = dtype.fields[last][1] + dtype.fields[last][0].itemsize - 1
    return dtype.fields[first][1], end
