"""An array numba does not count references to, for a loop that hands it to an inlined function
at every turn.

numba keeps a compiled array alive with a reference count in its memory record: each new
variable holding the array raises it and lowers it again when the variable goes (an atomic
add each, ``NRT_incref`` and ``NRT_decref``). An array argument of a function numba inlines
(``inline="always"``) is such a variable at every call, and numba does not remove the pair
inside a large loop body with branches. The narrowphase hands the polygons' placed vertices
to the polygon functions at every pair: on the pyramid of base 40 that was 4,760 atomic adds a
step (``benchmarks/count_refs.py``), 15 ns each on the project's machine.

:func:`borrowed` gives the same memory, shape and strides without a memory record: the counts
then test a null pointer and do nothing. The view owns nothing, so it must not outlive the
array it came from: use it inside the function that holds that array, never return or store
it. Uncompiled (``SANDBOX_JIT=0``) it is the array itself.
"""

from __future__ import annotations

from sandbox.jit import JIT_ENABLED

if JIT_ENABLED:
    from numba import types
    from numba.extending import intrinsic
    from numba.np.arrayobj import make_array, populate_array

    @intrinsic
    def borrowed(typingctx, array):
        """``array``'s memory as an array of the same type without a memory record."""
        if not isinstance(array, types.Array):
            return None

        def codegen(context, builder, signature, args):
            held = make_array(array)(context, builder, value=args[0])
            view = make_array(array)(context, builder)
            populate_array(
                view,
                data=held.data,
                shape=held.shape,
                strides=held.strides,
                itemsize=held.itemsize,
                meminfo=None,  # nothing to count: the caller's array keeps the memory
            )
            return view._getvalue()

        return array(array), codegen

else:

    def borrowed(array):
        """Uncompiled: the array itself."""
        return array
