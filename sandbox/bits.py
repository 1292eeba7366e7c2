"""The index of the lowest set bit of an integer, in one instruction (``llvm.cttz``: count
trailing zeros, ``tzcnt`` on x86).

The colouring of the wide sweeps (:func:`sandbox.solvers.wide.colour`) keeps a body's colours
as the bits of one integer and gives a contact the lowest colour free at both its bodies: the
lowest bit of a mask. Found by shifting the mask until it is 1, that took one to eight turns
of a loop whose end the processor mispredicted; on the rain of 5,000 discs (13,625 contacts,
8 colours) the colouring took 175 us, against 139 us with this (in one process, in turn; the
same colours). Uncompiled (``SANDBOX_JIT=0``) it is Python's ``int.bit_length``.
"""

from __future__ import annotations

from sandbox.jit import JIT_ENABLED

if JIT_ENABLED:
    import numba
    from llvmlite import ir
    from numba.extending import intrinsic

    @intrinsic
    def lowest_bit(typingctx, x):
        """The index of the lowest set bit of ``x`` (an integer, not 0)."""
        if not isinstance(x, numba.types.Integer):
            return None

        def codegen(context, builder, signature, args):
            i64, i1 = ir.IntType(64), ir.IntType(1)
            kind = ir.FunctionType(i64, (i64, i1))
            fn = builder.module.declare_intrinsic("llvm.cttz", (i64,), kind)
            value = context.cast(builder, args[0], signature.args[0], numba.types.int64)
            # (value, poison for 0: the callers never pass 0)
            return builder.call(fn, (value, ir.Constant(i1, 1)))

        return numba.types.int64(x), codegen

else:

    def lowest_bit(x: int) -> int:
        """The index of the lowest set bit of ``x`` (an integer, not 0)."""
        x = int(x)
        return (x & -x).bit_length() - 1
