"""One source, two speeds: hot loops are plain Python compiled by numba.

Set ``SANDBOX_JIT=0`` in the environment to run the very same functions as plain Python, for
stepping through them in a debugger or reading a traceback line by line.

Compiled code is cached on disk (``cache=True``, in :data:`sandbox.compile_cache.CACHE_FOLDER`)
so only the first run compiles; nothing is compiled until a kernel first runs. Compiling takes
tens of seconds the first time: a one-line notice says so, and on a terminal a progress bar
(:class:`CompileNotice`).
"""

from __future__ import annotations

import gc
import os
import sys

import numpy as np

from sandbox.compile_cache import CACHE_FOLDER, COMPILE_LOG, PREBUILT, take_cache_note

JIT_ENABLED: bool = os.environ.get("SANDBOX_JIT", "1") != "0"
# flags for a compiled call to pass as constants. numba compiles a function once for each
# literal True or False it is called with, and once more for a flag known only at run time;
# it takes numpy's bools for the latter, so a call passing ON or OFF shares that version with
# the calls passing a variable (each literal version cost 0.3 to 0.6 s from an empty cache)
ON, OFF = np.bool_(True), np.bool_(False)

__all__ = [
    "CACHE_FOLDER",
    "JIT_ENABLED",
    "OFF",
    "ON",
    "bound",
    "compiling_process",
    "entry",
    "literally",
    "njit",
    "quiet_compiles",
    "take_cache_note",
]


if JIT_ENABLED:
    import numba
    import numba.core.cpu
    import numba.core.event
    from llvmlite import binding as llvm

    from sandbox.vector_width import target_features

    if PREBUILT:  # the kernels shipped in the package: their target (sandbox.prebuilt)
        from sandbox.prebuilt import TARGET

        numba.config.CPU_NAME, numba.config.CPU_FEATURES = TARGET, ""
    else:
        try:  # before anything compiles: the vectors' width (sandbox.vector_width)
            _features = target_features(llvm.get_host_cpu_features().flatten(), os.environ)
        except RuntimeError:  # LLVM cannot tell this processor's features: numba's default
            _features = None
        if _features is not None:
            numba.config.CPU_FEATURES = _features

    from sandbox.heap import keep_heap

    keep_heap()  # the compiled step's work arrays reuse the heap from step to step

    if CACHE_FOLDER is not None:
        numba.config.CACHE_DIR = str(CACHE_FOLDER)
    _CACHE = CACHE_FOLDER is not None

    class CompileNotice(numba.core.event.Listener):
        """While kernels compile (the first runs on a machine), a one-line notice, and on a
        terminal a progress bar, so a wait of tens of seconds is never silent (in a notebook
        either: its stderr is no terminal). Loading compiled kernels from the cache is no
        compile event, so a warm run says nothing. With ``SANDBOX_COMPILE_LOG`` set (a file),
        each compile is a line in that file instead, for the command that started this process
        to report (``sandbox lessons``)."""

        # kernels compiled with each one-call step from an empty cache (the bar's length;
        # measured by `python benchmarks/bench_first_run.py --kernels` on the bundled pyramid;
        # a world of every shape and joint compiles as many)
        STEP_KERNELS = {"fast_step": 235, "soft_step": 232}

        def __init__(self) -> None:
            self.depth = 0
            self.bar = None
            self.told = False
            self.log = os.environ.get(COMPILE_LOG) or None  # set: a line there, no notice

        def on_start(self, event) -> None:
            if self.log is not None:
                with open(self.log, "a", encoding="utf-8") as log:
                    log.write(f"{compiled_name(event) or '?'}\n")
                return
            if self.depth == 0 and not self.told:  # a notebook or a log gets the line too
                print(
                    "note: compiling the engine for this machine, once (later runs load it; "
                    "`sandbox warmup` does it ahead of a class)",
                    file=sys.stderr,
                )
                self.told = True
            if self.depth == 0 and self.bar is None and sys.stderr.isatty():
                from tqdm import tqdm

                # a step: a bar; any other function: how many so far (no length known)
                total = self.STEP_KERNELS.get(compiled_name(event))
                self.bar = tqdm(total=total, unit=" kernels", leave=False, file=sys.stderr)
            self.depth += 1
            if self.bar is not None:
                self.bar.update(1)

        def on_end(self, event) -> None:
            if self.log is not None:
                return
            self.depth -= 1
            if self.depth == 0 and self.bar is not None:
                self.bar.close()
                self.bar = None

    def compiled_name(event) -> str:
        """The name of the function a compile event is about ("" if none)."""
        dispatcher = getattr(event, "data", {}).get("dispatcher")
        return getattr(getattr(dispatcher, "py_func", None), "__name__", "")

    NOTICE = CompileNotice()
    numba.core.event.register("numba:compile", NOTICE)

    class WhileCompiling(numba.core.event.Listener):
        """The interpreter's memory settings while this process compiles, for numba's compiler,
        which builds and drops millions of Python objects deep in recursion:

        - from the first compile on, Python's frame-stack chunks are kept for reuse
          (:mod:`sandbox.frame_stack`), not mapped and unmapped at nearly every deep call;
        - while a compile runs, the garbage collector's full collections come
          :data:`RARER` times less often (its third threshold), and its young collections
          after :data:`YOUNG` new objects rather than 700 (its first), and as before when it
          ends.

        A process that only loads compiled kernels is left as it was; a process that only
        compiles (a warmup) keeps the collector's settings from start to end (:meth:`hold`)."""

        # one share of the lessons' warmup (`sandbox warmup --lessons --part 1/2`, two rounds):
        # 32 full collections and 7.9 to 8.6 s of collecting in all; with this, 4 and 3.4 to
        # 3.8 s (peak memory 594 MB, 638 MB)
        RARER = 10
        # the iterative step's family from an empty cache in one process (as a warmup share
        # compiles it), rounds in turn: with the young collections after 700 new objects,
        # 4,502 collections and 2.0 to 2.6 s of collecting; with this during each compile, 546
        # and 1.9 to 2.1 s; held from the start (a warmup), 444 and 1.35 to 1.42 s, peak memory
        # 485 against 483 to 491 MB. Most of what numba builds is freed by its reference count
        # before a collection would look at it. Between compiles (numba writes each function
        # to the cache after its compile; the warmup steps its worlds) the collector's own
        # settings came back, and with them most of the collecting left
        YOUNG = 10_000

        def __init__(self) -> None:
            self.kept, self.depth, self.thresholds, self.held = False, 0, None, False

        def settings(self, thresholds: tuple[int, int, int]) -> tuple[int, int, int]:
            """The collector's thresholds while compiling, from its ``thresholds``."""
            young, middle, full = thresholds
            return max(young, self.YOUNG), middle, full * self.RARER

        def hold(self) -> None:
            """Keep the settings of a compile from now until the process ends."""
            if not self.held:
                gc.set_threshold(*self.settings(gc.get_threshold()))
                self.held = True

        def on_start(self, event) -> None:
            if not self.kept:
                self.kept = True  # before compiling the allocator, whose compile is nested
                from sandbox.frame_stack import keep_frame_stack

                keep_frame_stack()
            if self.depth == 0 and not self.held:
                self.thresholds = gc.get_threshold()
                gc.set_threshold(*self.settings(self.thresholds))
            self.depth += 1

        def on_end(self, event) -> None:
            self.depth -= 1
            if self.depth == 0 and self.thresholds is not None and not self.held:
                gc.set_threshold(*self.thresholds)

    WHILE_COMPILING = WhileCompiling()
    numba.core.event.register("numba:compile", WHILE_COMPILING)

    class CompileCount(numba.core.event.Listener):
        """How many functions this process compiles from now on (``count``), nested ones
        included: a warmup's progress between two families. ``close()`` stops counting."""

        def __init__(self) -> None:
            self.count = 0
            numba.core.event.register("numba:compile", self)

        def on_start(self, event) -> None:
            self.count += 1

        def on_end(self, event) -> None:
            pass

        def close(self) -> None:
            numba.core.event.unregister("numba:compile", self)

    # numba gives every compiled function a C-callable twin besides its Python entry, for
    # passing it as a first-class function value; the engine never does, and leaving the twins
    # out saves 3 to 5 % of compiling (`sandbox warmup --lessons` from an empty cache, two
    # alternating rounds: 71.6 and 66.4 s against 75.3 and 68.7 s). The option is one of
    # numba's CPU target options; a numba without it compiles the twins as before
    _NO_TWIN = (
        {"no_cfunc_wrapper": True}
        if hasattr(numba.core.cpu.CPUTargetOptions, "no_cfunc_wrapper")
        else {}
    )

    from numba.core.caching import FunctionCache
    from numba.core.compiler import Compiler
    from numba.core.registry import CPUDispatcher

    from sandbox import ir_only

    # the versions without a Python entry make no machine code (sandbox.ir_only); numba's own
    # compiler where this numba's code library lacks what that relies on
    IR_ONLY = ir_only.install()
    _INNER_COMPILER = ir_only.IROnlyCompiler if IR_ONLY else Compiler

    from sandbox import compile_work

    # less of numba's own Python work while compiling, the same code (sandbox.compile_work)
    COMPILE_WORK = compile_work.install()

    class _InnerCache(FunctionCache):
        """The cache of a function's version without a Python entry (:class:`Kernel`): in the
        same index file as the other version's, under keys of its own."""

        def _index_key(self, sig, codegen):
            return (*super()._index_key(sig, codegen), "inner")

    class Kernel(CPUDispatcher):
        """A compiled function: numba's dispatcher, except that the compiled functions that
        call it call a version of it without a Python entry (``inner``, compiled when one
        of them is first compiled).

        numba gives every function it compiles a Python entry (the wrapper that unboxes
        Python's arguments and boxes the result), even one that only compiled code calls: the
        wrapper is generated, optimised and turned into machine code with the function. Most
        of the engine's functions are only called by other compiled functions. A function
        called from Python and from compiled code (a stage of the step that the staged path
        calls one by one) is marked ``@njit(python=True)`` and keeps one version with the
        entry for both, rather than being compiled twice.

        Compiling the lessons' kernels from an empty cache (`sandbox warmup --lessons`, two
        alternating rounds): 62.7 and 58.2 s wall, 116.9 and 107.5 s of CPU, against 70.4 and
        64.8 s, 134.6 and 123.2 s with an entry for every function. The iterative step's
        family alone built 193 entries; it builds 30 now (the staged path's stages)."""

        both = False  # one version, with the Python entry, for Python and compiled callers

        @property
        def inner(self) -> CPUDispatcher:
            version = self.__dict__.get("_inner")
            if version is None:
                options = {**self.targetoptions, "no_cpython_wrapper": True}
                version = CPUDispatcher(self.py_func, self.locals, options, _INNER_COMPILER)
                if isinstance(self._cache, FunctionCache):
                    version._cache = _InnerCache(self.py_func)
                self.__dict__["_inner"] = version
            return version

        @property
        def compiled_both_ways(self) -> bool:
            """Whether this function was compiled for Python and again for compiled callers:
            called both ways, it should be marked ``@njit(python=True)``."""
            version = self.__dict__.get("_inner")
            return bool(self.signatures and version is not None and version.signatures)

        @property
        def _numba_type_(self):  # what numba types a call from compiled code to
            return self._type if self.both else self.inner._type

    def njit(*args, python: bool = False, **kwargs):
        """``numba.njit(cache=True)`` (accepts the same arguments as numba.njit), without the
        C-callable twin of each function, and a :class:`Kernel` (``python``: called from
        Python as well as from compiled code; see there); without a writable cache folder,
        ``cache=False``. A function inlined into its callers (``inline="always"``) is never
        compiled on its own for them: numba's plain dispatcher."""
        kwargs["cache"] = kwargs.get("cache", True) and _CACHE
        kwargs = {**_NO_TWIN, **kwargs}
        if args and callable(args[0]) and len(args) == 1 and not kwargs.get("_signature"):
            return _kernel(args[0], python, kwargs)
        if not args and not kwargs.get("_signature"):
            return lambda function: _kernel(function, python, kwargs)
        return numba.njit(*args, **kwargs)

    def _kernel(function, python: bool, options: dict):
        dispatcher = numba.njit(**options)(function)  # numba's options, numba's dispatcher,
        # made a Kernel (a subclass that adds no fields of its own)
        if options.get("inline", "never") == "never":
            dispatcher.__class__ = Kernel
            dispatcher.both = python
        return dispatcher

    literally = numba.literally  # compile one version of a function per value of an argument

else:
    IR_ONLY = False  # nothing compiles
    COMPILE_WORK: list[str] = []

    def njit(*args, **kwargs):
        """Plain-Python stand-in for ``numba.njit`` (SANDBOX_JIT=0)."""
        if args and callable(args[0]) and len(args) == 1:
            return args[0]
        return lambda f: f

    def literally(value):
        """Plain-Python stand-in for ``numba.literally``: the value itself."""
        return value

    class CompileCount:
        """Plain-Python stand-in: nothing compiles (``count`` stays 0)."""

        count = 0

        def close(self) -> None:
            pass


def compile_noted() -> None:
    """The command has said in its own line that compiling starts (``sandbox.cli.first_run``):
    the compile notice keeps only its bar, so the wait is announced once."""
    if JIT_ENABLED:
        NOTICE.told = True


def quiet_compiles() -> None:
    """No compile notice nor bar in this process (``sandbox warmup --quiet``)."""
    if JIT_ENABLED:
        NOTICE.told = True
        numba.core.event.unregister("numba:compile", NOTICE)


def compiling_process() -> None:
    """This process only compiles (a warmup): the collector's settings of a compile
    (:class:`WhileCompiling`) from now until it ends, not only during each compile."""
    if JIT_ENABLED:
        WHILE_COMPILING.hold()


def entry(function, *args):
    """The compiled machine code of ``function`` for the types of ``args``, callable from Python
    without numba's type dispatch (a call with ten arrays then costs about a microsecond less);
    ``function`` itself when compiling is off. Call it only with arguments of those same types
    (array dtype, dimensions and layout): nothing checks them any more."""
    if not JIT_ENABLED:
        return function
    signature = tuple(function.typeof_pyval(a) for a in args)
    return function.compile(signature)


def bound(function, *args):
    """``function`` with ``args`` bound, to be called with no arguments of its own, step after
    step: compiled, its machine code for those types (:func:`entry`); uncompiled, with its
    record arrays viewed once as :class:`sandbox.plain_records.Records` (the same memory, read
    several times faster in plain Python)."""
    if JIT_ENABLED:
        code = entry(function, *args)
        return lambda: code(*args)
    from sandbox.plain_records import fast_records

    args = fast_records(args)
    return lambda: function(*args)
