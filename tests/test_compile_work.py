"""numba does less of its own Python work while compiling, for the same code (sandbox.compile_work).

The flags' shortcuts give numba's own answers; the blocks of one copy of a function's IR share
one copy of its scope; and a kernel that inlines a function compiles to the same LLVM IR with
and without the changes."""

from __future__ import annotations

import os
import re
import subprocess
import sys

import pytest
from fresh_process import in_process

from sandbox import jit

pytestmark = pytest.mark.skipif(not jit.JIT_ENABLED, reason="nothing compiles")

KERNELS = """
from sandbox.jit import njit


@njit(inline="always")
def clamp(x, low, high):
    if x < low:
        return low
    for _ in range(2):
        if x > high:
            x = high
    return x


@njit
def clamped_sum(xs):
    total = 0.0
    for x in xs:
        total += clamp(x, -1.0, 1.0)
    return total
"""

# prints the kernel's result, which changes were made, and its LLVM IR without what differs
# from one process to the next anyway (numba's numbering of record types, addresses in names)
RUN = """
import re, numpy as np
{before}
import sandbox.jit as jit
import kernels_inline as k
print(k.clamped_sum(np.array([-3.0, 0.5, 2.0])), jit.COMPILE_WORK)
(result,) = k.clamped_sum.overloads.values()
text = result.library.get_llvm_str()
print(re.sub(r"0x[0-9a-f]{{6,}}", "ADDR", text).replace("\\n", " "))
"""
WITHOUT = "import sandbox.compile_work as w; w.install = lambda: []"


def test_flags_give_numbas_own_answers():
    from numba.core.compiler import Flags

    from sandbox import compile_work

    assert "flags" in jit.COMPILE_WORK
    original = compile_work.ORIGINAL_FLAGS
    plain, nrt, nrt_again, both = Flags(), Flags(), Flags(), Flags()
    nrt.nrt = nrt_again.nrt = both.nrt = True
    both.no_cpython_wrapper = True
    default_set = Flags()
    default_set.nrt = Flags().nrt  # set explicitly to its default: equal to one not set
    every = (plain, nrt, nrt_again, both, default_set)
    for a in every:
        assert a.values() == original["values"](a)
        assert hash(a) == original["hash"](a)
        for b in every:
            assert (a == b) == original["eq"](a, b), (a, b)
    assert nrt == nrt_again and default_set == plain and nrt != both
    assert (plain == "flags") is False
    assert compile_work.install() == jit.COMPILE_WORK  # a second install changes nothing more
    assert original["eq"] is not compile_work.flags_equal  # numba's own, kept


def test_the_blocks_of_one_copy_share_one_scope():
    from numba.core import inline_closurecall
    from numba.core.compiler import run_frontend

    assert "inlining" in jit.COMPILE_WORK

    def branches(x):
        if x > 0:
            x = x + 1
        else:
            x = x - 1
        return x

    ir = run_frontend(branches)
    assert len(ir.blocks) > 2
    deepcopy = inline_closurecall.copy.deepcopy  # as numba's inlining copies each block
    ir.copy()
    blocks = [deepcopy(block) for block in ir.blocks.values()]
    scopes = {id(block.scope) for block in blocks}
    assert len(scopes) == 1  # numba's own copy: one scope per block
    assert blocks[0].scope is not ir.blocks[min(ir.blocks)].scope  # a copy, not the original
    again = deepcopy(next(iter(ir.blocks.values())))  # copied twice: a copy of its own
    assert again is not blocks[0] and again.scope is not blocks[0].scope
    ir.copy()  # the next function's copy starts a fresh memo
    assert deepcopy(next(iter(ir.blocks.values()))).scope is not blocks[0].scope


def compiled(folder, before: str) -> tuple[str, str]:
    """The kernel's result and the changes made, and its LLVM IR, compiled in a new process
    from an empty cache of its own (``before``: code run before the engine is imported)."""
    first, text = in_process(folder, RUN.format(before=before), cache=f"cache{len(before)}")
    return first, re.sub(r"RecordILi\d+EE", "RecordILiNEE", text)


def test_the_same_code_with_and_without_the_changes(tmp_path):
    (tmp_path / "kernels_inline.py").write_text(KERNELS)
    with_changes, ir_with = compiled(tmp_path, "")
    without, ir_without = compiled(tmp_path, WITHOUT)
    assert with_changes == "0.5 ['flags', 'inlining', 'plain errors']"  # -1 + 0.5 + 1
    assert without == "0.5 []"
    assert "5clampB" not in ir_with  # inlined: no call left to it (nor its mangled name)
    assert ir_with == ir_without


def test_error_messages_are_not_styled():
    from numba.core import errors

    assert "plain errors" in jit.COMPILE_WORK
    assert errors.termcolor().errmsg("no match") == "no match"
    assert errors.termcolor().highlight("x") == "x"


def test_importing_the_engine_leaves_the_environment_alone():
    """The course's notebook kernels are forked only when their environment matches their
    server's in what imports read (sandbox.course.prefork): importing the engine must not
    change it."""
    code = (
        "import os; before = dict(os.environ)\n"
        "import sandbox, sandbox.jit, sandbox.world\n"
        "changed = {k for k in set(before) | set(os.environ) if before.get(k) != os.environ.get(k)}\n"
        "print(sorted(changed))\n"
    )
    env = {k: v for k, v in os.environ.items() if not k.startswith("NUMBA_")}
    res = subprocess.run(
        [sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=120
    )
    assert res.returncode == 0, res.stderr
    assert res.stdout.strip() == "[]"
