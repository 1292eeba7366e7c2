"""Less of numba's own Python work while it compiles, for the very same code.

Half of compiling the engine is numba's Python (typing, inlining, lowering), the other half
LLVM. Profiling numba as it compiled the iterative step's family from an empty cache found
three places where its Python does far more work than the result needs; :func:`install`
changes these three and nothing else:

- **Flags compared key by key.** numba keeps the overload templates it has resolved in a
  dictionary keyed by the compile flags, and every lookup hashed and compared the flags by
  building a dictionary of all of their forty-odd options, through a property per option: 100
  thousand comparisons and 73 thousand hashes in the iterative step's family, about 1.9 s.
  :func:`flags_values` builds the same dictionary from the class's defaults at once, a
  comparison of flags that set the same options is decided by those alone, and the hash (of
  the options' names only, numba's own choice) is kept per class.
- **The callee's scope copied once per inlined copy.** Before inlining a function marked
  ``inline="always"``, numba deep-copies its IR block by block, each block with a fresh memo,
  so each block got a copy of the function's whole scope (every variable of the function):
  quadratic in the function's size. Here the blocks of one copy of a function's IR share one
  memo (:func:`shared_block_copy`), as they shared one scope before the copy: 2.4 s -> 0.6 s
  for the lessons' families.
- **Error messages not styled.** Each overload template that does not match records an error
  message whose parts numba styles for a terminal, initialising and tearing down colorama for
  each part (47 thousand times in the iterative step's family). numba's colour scheme is made
  one that leaves text as it is (:func:`plain_text_scheme`), as numba's own setting
  ``NUMBA_DISABLE_ERROR_MESSAGE_HIGHLIGHTING`` would, without that setting in the environment
  (which the course's forked notebook kernels compare with their server's, and which the user's
  own processes would inherit).

The code numba generates is the same to the byte (``tests/test_compile_work.py`` compares the
LLVM IR of a kernel that inlines a function, compiled with and without these; every library of
the iterative step's family was compared so once), so are the results. Each change is made
only if numba's code is as expected; else that part is left as numba's own.
"""

from __future__ import annotations

import copy
import types

_defaults: dict[type, dict] = {}  # each flags class: its options' defaults
_hashes: dict[type, int] = {}  # each flags class: numba's hash of its flags
_block_memo: dict | None = None  # the memo the blocks of one copy of a function's IR share
_original_copy = None  # numba's FunctionIR.copy
ORIGINAL_FLAGS: dict[str, object] = {}  # numba's own values, __hash__ and __eq__ of flags
_made: list[str] | None = None  # the changes made, once installed
_config_class: type | None = None  # numba's TargetConfig, the base class of its flags
_block_class: type | None = None  # numba's IR block


def flags_values(self) -> dict:
    """Every option of the flags ``self`` and its value (numba's ``TargetConfig.values``)."""
    cls = type(self)
    defaults = _defaults.get(cls)
    if defaults is None:
        defaults = _defaults[cls] = {name: o.default for name, o in cls.options.items()}
    return {**defaults, **self._values}


def flags_hash(self) -> int:
    """numba's hash of flags: of the sorted names of its options, the same for every value."""
    cls = type(self)
    value = _hashes.get(cls)
    if value is None:
        value = _hashes[cls] = hash(tuple(sorted(cls.options)))
    return value


def flags_equal(self, other) -> bool:
    """Equal flags have the same value for every option; flags of one class that set the same
    options to the same values are equal without looking at the defaults."""
    if not isinstance(other, _config_class):
        return NotImplemented
    if type(self) is type(other) and self._values == other._values:
        return True
    return flags_values(self) == flags_values(other)


def copy_function_ir(self):
    """numba's ``FunctionIR.copy``; the blocks copied after it (:func:`shared_block_copy`)
    share a fresh memo."""
    global _block_memo
    _block_memo = {}
    return _original_copy(self)


def shared_block_copy(x, memo=None):
    """``copy.deepcopy`` as numba's inlining calls it: a block copied right after its
    function's IR shares the memo of that copy (so its scope is copied once for all blocks); a
    block seen twice, or anything else, is copied as before."""
    if memo is None and type(x) is _block_class and _block_memo is not None:
        if id(x) not in _block_memo:
            return copy.deepcopy(x, _block_memo)
    return copy.deepcopy(x, memo)


def plain_text_scheme():
    """numba's colour scheme that returns every part of a message as it is (numba's own, for
    when colorama is missing or highlighting is turned off)."""
    from numba.core import errors

    class PlainText(errors._DummyColorScheme):
        def code(self, msg):
            return msg

        errmsg = filename = indicate = highlight = reset = code

    return PlainText()


def install() -> list[str]:
    """Make the changes numba's code allows (once); returns the names of those made."""
    global _original_copy, _made, _config_class, _block_class
    if _made is not None:
        return list(_made)
    made = _made = []
    from numba.core import inline_closurecall, ir, targetconfig

    config = _config_class = targetconfig.TargetConfig
    _block_class = ir.Block
    if _flags_as_expected(config):
        ORIGINAL_FLAGS.update(values=config.values, hash=config.__hash__, eq=config.__eq__)
        config.values = flags_values
        config.__hash__ = flags_hash
        config.__eq__ = flags_equal
        made.append("flags")
    if (
        getattr(inline_closurecall, "copy", None) is copy
        and hasattr(inline_closurecall.InlineWorker, "inline_ir")
        and callable(getattr(ir.FunctionIR, "copy", None))
    ):
        _original_copy = ir.FunctionIR.copy
        ir.FunctionIR.copy = copy_function_ir
        names = {name: getattr(copy, name) for name in copy.__all__}
        inline_closurecall.copy = types.SimpleNamespace(**{**names, "deepcopy": shared_block_copy})
        made.append("inlining")
    from numba.core import errors

    if hasattr(errors, "_DummyColorScheme") and hasattr(errors, "_termcolor_inst"):
        errors._termcolor_inst = plain_text_scheme()  # what errors.termcolor() hands out
        made.append("plain errors")
    return made


def _flags_as_expected(config) -> bool:
    """Whether numba's flags are kept as this module's versions assume: options with
    defaults, values set in ``_values``, and these versions give numba's answers."""
    from numba.core.compiler import Flags

    try:
        a, b = Flags(), Flags()
        a.nrt = b.nrt = True
        b.no_cpython_wrapper = True
        return (
            flags_values(a) == config.values(a)
            and flags_hash(a) == config.__hash__(a)
            and flags_equal(a, Flags(a)) is True
            and flags_equal(a, b) == config.__eq__(a, b)
        )
    except (AttributeError, TypeError):
        return False
