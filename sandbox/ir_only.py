"""Versions of compiled functions that only compiled code calls keep their IR, no machine code.

numba makes every function it compiles a library of its own: its LLVM IR, with the IR of every
function it calls linked in, optimised and turned into machine code. A caller never runs a
callee's machine code: it links the callee's IR into its own module. The versions of the
engine's functions without a Python entry (:attr:`sandbox.jit.Kernel.inner`) are only ever
used that way, so their machine code was made for nothing: 5.0 s of the 80.7 s that compiling
the lessons' families took in one process (the versions with an entry, 8.9 s).

:class:`IROnlyCompiler` is numba's compiler with one pass more before the lowering: the
function's library is marked IR-only, and this module's additions to numba's code library
(:func:`install`) then

- finish such a library without handing it to the JIT engine (no machine code, no symbols);
- write it to the cache as its linkable IR alone (kind :data:`KIND`) and read it back so;
- give 0 for the address of any of its functions (nothing calls one from Python: a call from
  Python goes to the version with an entry, :class:`sandbox.jit.Kernel`).

Every other library (the versions with an entry, numba's own helpers, its runtime) is
numba's as before. Results are the same to the bit: callers link the same IR as before.
"""

from __future__ import annotations

from llvmlite import binding as ll
from numba.core import codegen as numba_codegen
from numba.core.compiler import Compiler, DefaultPassBuilder
from numba.core.compiler_machinery import LoweringPass, register_pass
from numba.core.typed_passes import AnnotateTypes

KIND = "sandbox-ir-only"  # the cache's kind of serialised library: linkable IR, no machine code


@register_pass(mutates_CFG=False, analysis_only=False)
class MarkIROnly(LoweringPass):
    """Create the function's code library (as numba's lowering would) and mark it IR-only."""

    _name = "sandbox_mark_ir_only"

    def __init__(self) -> None:
        LoweringPass.__init__(self)

    def run_pass(self, state) -> bool:
        if state.library is None:
            state.library = state.targetctx.codegen().create_library(state.func_id.func_qualname)
            state.library.enable_object_caching()  # as numba's lowering does, for the cache
        state.library._ir_only = True
        return True


class IROnlyCompiler(Compiler):
    """numba's nopython compiler, the library it lowers into marked IR-only (:class:`MarkIROnly`)."""

    def define_pipelines(self):
        if self.state.flags.force_pyobject:  # object mode: numba's own pipeline
            return super().define_pipelines()
        pm = DefaultPassBuilder.define_nopython_pipeline(self.state)
        pm.add_pass_after(MarkIROnly, AnnotateTypes)
        pm.finalize()
        return [pm]


def _ir_only(library) -> bool:
    return getattr(library, "_ir_only", False)


def install() -> bool:
    """Teach numba's JIT code library IR-only libraries (once); False, changing nothing, when
    this numba's code library lacks a method it relies on."""
    library_class = numba_codegen.JITCodeLibrary
    codegen_class = numba_codegen.JITCPUCodegen
    needed = (
        (library_class, "_finalize_final_module"),
        (library_class, "_finalize_dynamic_globals"),
        (library_class, "_verify_declare_only_symbols"),
        (library_class, "get_pointer_to_function"),
        (library_class, "serialize_using_object_code"),
        (library_class, "_get_module_for_linking"),
        (library_class, "_unserialize"),
        (codegen_class, "set_env"),
    )
    if not all(hasattr(owner, name) for owner, name in needed):
        return False
    if getattr(library_class, "_sandbox_ir_only", False):
        return True

    finalize = library_class._finalize_final_module
    pointer = library_class.get_pointer_to_function
    serialize = library_class.serialize_using_object_code
    unserialize = library_class._unserialize.__func__
    set_env = codegen_class.set_env

    def _finalize_final_module(self) -> None:
        if not _ir_only(self):
            return finalize(self)
        self._finalize_dynamic_globals()
        self._verify_declare_only_symbols()
        self._finalized = True  # its IR is final; the JIT engine never sees it
        return None

    def get_pointer_to_function(self, name: str) -> int:
        if not _ir_only(self):
            return pointer(self, name)
        self._ensure_finalized()  # as numba's does: the library is final once this is asked
        return 0

    def serialize_using_object_code(self):
        if not _ir_only(self):
            return serialize(self)
        self._ensure_finalized()
        return (self.name, KIND, self._get_module_for_linking().as_bitcode())

    def _unserialize(cls, codegen, state):
        name, kind, data = state
        if kind != KIND:
            return unserialize(cls, codegen, state)
        library = codegen.create_library(name)
        library._ir_only = True
        library._final_module = library._shared_module = ll.parse_bitcode(data)
        library._finalized = True
        return library

    def codegen_set_env(self, env_name: str, env) -> None:
        # the environment of an IR-only library's function is in no module of the engine
        if self._engine.get_global_value_address(env_name):
            set_env(self, env_name, env)

    library_class._finalize_final_module = _finalize_final_module
    library_class.get_pointer_to_function = get_pointer_to_function
    library_class.serialize_using_object_code = serialize_using_object_code
    library_class._unserialize = classmethod(_unserialize)
    codegen_class.set_env = codegen_set_env
    library_class._sandbox_ir_only = True
    return True
