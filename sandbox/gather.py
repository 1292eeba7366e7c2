"""Eight numbers gathered from anywhere in an array into eight side by side, in one instruction
(``llvm.masked.gather``: ``vgatherqpd`` with AVX-512).

Before each group of a sweep, every lane of the wide sweeps takes its bodies' velocities from
the lanes that last held them (:func:`sandbox.solvers.handoff.hand_in`): for each of a block's
six velocity fields, eight numbers from eight places in the lanes go to eight numbers side by
side. numba cannot prove that the places read are not the ones written (both are in the same
array), so its loop loads and stores the numbers one at a time; with :func:`gather_lanes` the
eight sources are read as one vector from their eight indices, and the eight numbers written
with one store. The numbers copied are the same. Measured on the rain of 5,000 discs (13,625
contacts, 8 colours, step 300), ten sweeps' hand-ins in one process: 409 to 416 us one at a
time, 292 to 297 us gathered.

A processor without a gather instruction (AVX2 has four-wide ones, ARM's NEON none) gets
LLVM's own sequence of loads for it, the same numbers. With numba's bounds checks on
(``NUMBA_BOUNDSCHECK=1``) it is :func:`gather_plain`, compiled with each index checked;
uncompiled (``SANDBOX_JIT=0``) the same function in Python.
"""

from __future__ import annotations

import numpy as np

from sandbox.jit import JIT_ENABLED

WIDTH = 8  # numbers gathered at once (the wide sweeps' LANES)


def gather_plain(numbers, to: int, indices, first: int, add: int) -> None:
    """:func:`gather_lanes` one number at a time: in Python (``SANDBOX_JIT=0``), and compiled
    by numba with each index checked (``NUMBA_BOUNDSCHECK=1``). Every number is read before any
    is written."""
    flat, shift, got = indices.reshape(-1), np.int64(add), np.empty(WIDTH)
    for lane in range(WIDTH):
        got[lane] = numbers[flat[first + lane] + shift]
    for lane in range(WIDTH):
        numbers[np.int64(to) + lane] = got[lane]


if JIT_ENABLED:
    import numba
    from llvmlite import ir
    from numba.extending import intrinsic

    def _splat(builder, value, kind: ir.VectorType):
        # the scalar ``value`` in every element of a vector
        one = builder.insert_element(ir.Constant(kind, ir.Undefined), value, ir.IntType(32)(0))
        lanes = ir.Constant(ir.VectorType(ir.IntType(32), WIDTH), [0] * WIDTH)
        return builder.shuffle_vector(one, ir.Constant(kind, ir.Undefined), lanes)

    @intrinsic
    def gather_lanes(typingctx, numbers, to, indices, first, add):
        """``numbers[to + l] = numbers[indices.flat[first + l] + add]`` for l = 0 to 7:
        ``numbers`` a C-contiguous float64 array, ``indices`` a C-contiguous int64 array (read
        as flat), the indices (plus ``add``) within ``numbers`` and the eight written not among
        the eight read but where a number is copied onto itself (all are read before any is
        written)."""
        float_array = isinstance(numbers, numba.types.Array) and numbers.dtype == numba.float64
        int_array = isinstance(indices, numba.types.Array) and indices.dtype == numba.int64
        if not (float_array and int_array and numbers.layout == indices.layout == "C"):
            return None

        def codegen(context, builder, signature, args):
            if context.enable_boundscheck:  # NUMBA_BOUNDSCHECK: numba's checked indexing
                return context.compile_internal(builder, gather_plain, signature, args)
            kinds = signature.args
            i64, f64 = ir.IntType(64), ir.DoubleType()
            ints, doubles = ir.VectorType(i64, WIDTH), ir.VectorType(f64, WIDTH)
            data = context.make_array(kinds[0])(context, builder, args[0]).data
            index_data = context.make_array(kinds[2])(context, builder, args[2]).data
            first_at = context.cast(builder, args[3], kinds[3], numba.int64)
            added = context.cast(builder, args[4], kinds[4], numba.int64)
            to_at = context.cast(builder, args[1], kinds[1], numba.int64)
            # the eight indices, plus add, as byte offsets from the numbers' first
            at = builder.gep(index_data, [first_at])
            index = builder.load(builder.bitcast(at, ints.as_pointer()), align=8)
            index = builder.add(index, _splat(builder, added, ints))
            offsets = builder.shl(index, ir.Constant(ints, [3] * WIDTH))  # 8 bytes a number
            base = _splat(builder, builder.ptrtoint(data, i64), ints)
            places = builder.inttoptr(
                builder.add(base, offsets), ir.VectorType(f64.as_pointer(), WIDTH)
            )
            every = ir.Constant(ir.VectorType(ir.IntType(1), WIDTH), [1] * WIDTH)
            kind = ir.FunctionType(doubles, (places.type, ir.IntType(32), every.type, doubles))
            # named after its types (llvm.masked.gather.v8f64.v8p0f64, or .v8p0 where LLVM's
            # pointers carry no type)
            pointer = f64.as_pointer().intrinsic_name
            name = f"llvm.masked.gather.v{WIDTH}f64.v{WIDTH}{pointer}"
            fn = builder.module.declare_intrinsic(name, fnty=kind)
            # (places, alignment of each number, all lanes, what a masked-off lane would get)
            gathered = builder.call(
                fn, (places, ir.IntType(32)(8), every, ir.Constant(doubles, ir.Undefined))
            )
            out = builder.gep(data, [to_at])
            builder.store(gathered, builder.bitcast(out, doubles.as_pointer()), align=8)
            return context.get_dummy_value()

        return numba.types.void(numbers, to, indices, first, add), codegen

else:
    gather_lanes = gather_plain
