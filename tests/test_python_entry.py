"""A compiled function gets numba's Python entry only when Python calls it (sandbox.jit.Kernel).

A function that only other compiled functions call is compiled without the wrapper that
unboxes Python's arguments; one that Python calls has it; one marked ``@njit(python=True)``
(called both ways) is compiled once, with it, for both. The two versions are cached under
keys of their own, so a later process never hands Python the version without an entry."""

from __future__ import annotations

import pytest
from fresh_process import in_process

from sandbox import jit

pytestmark = pytest.mark.skipif(not jit.JIT_ENABLED, reason="nothing compiles")

KERNELS = """
from sandbox.jit import njit


@njit
def helper(x):
    return 2.0 * x


@njit(python=True)
def shared(x):
    return x + 1.0


@njit
def outer(x):
    return helper(x) + shared(x)
"""


def entries(function) -> list[bool]:
    """For each compiled version of ``function``: whether its library has a Python entry."""
    return ["cpython" in result.library.get_llvm_str() for result in function.overloads.values()]


def test_only_what_python_calls_has_a_python_entry(tmp_path, monkeypatch):
    (tmp_path / "kernels_entry.py").write_text(KERNELS)
    monkeypatch.syspath_prepend(str(tmp_path))
    monkeypatch.setattr(jit, "_CACHE", False)
    import kernels_entry as k

    assert k.outer(1.5) == 5.5  # 2 * 1.5 + (1.5 + 1)
    assert entries(k.outer) == [True]  # Python called it
    assert entries(k.helper) == []  # no version with an entry: Python never called it
    assert entries(k.helper.inner) == [False]  # the version outer calls
    assert entries(k.shared) == [True]  # one version for both
    assert "_inner" not in k.shared.__dict__ and not k.shared.compiled_both_ways
    assert not k.helper.compiled_both_ways
    assert k.helper(1.5) == 3.0  # called from Python after all: a version with an entry
    assert entries(k.helper) == [True] and entries(k.helper.inner) == [False]
    assert k.helper.compiled_both_ways  # what compile_profile.py reports, to be marked


def test_a_cached_version_without_an_entry_is_never_what_python_gets(tmp_path):
    (tmp_path / "kernels_cached.py").write_text(KERNELS)
    code = (
        "import kernels_cached as k\n"
        "print(k.{call})\n"
        "print(sum(k.{name}.stats.cache_hits.values()), sum(k.{name}.stats.cache_misses.values()))"
    )

    def run(name: str, call: str) -> list[str]:
        # a Python call of a version without an entry crashes the process (numba does not check)
        return in_process(tmp_path, code.format(name=name, call=call))

    assert run("outer", "outer(1.5)")[:2] == ["5.5", "0 1"]  # compiled, helper without entry
    assert run("outer", "outer(1.5)")[:2] == ["5.5", "1 0"]  # loaded
    assert run("helper", "helper(1.5)")[:2] == ["3.0", "0 1"]  # not the cached one: compiled
    assert run("helper", "helper(1.5)")[:2] == ["3.0", "1 0"]  # now loaded, with its entry
    assert run("outer", "outer(1.5)")[:2] == ["5.5", "1 0"]  # and outer's still loads


# --- the versions without an entry keep their IR and make no machine code (sandbox.ir_only) -----
IR_KERNELS = (
    KERNELS
    + """

@njit
def other(x):
    return helper(x) - 1.0
"""
)


def machine_code(function) -> list[bool]:
    """For each compiled version of ``function``: whether the JIT engine holds its code."""
    out = []
    for result in function.overloads.values():
        engine = result.library.codegen._engine
        out.append(engine.is_symbol_defined(result.fndesc.mangled_name))
    return out


@pytest.mark.skipif(not jit.IR_ONLY, reason="this numba's code library lacks what it needs")
def test_a_version_without_an_entry_makes_no_machine_code(tmp_path, monkeypatch):
    (tmp_path / "kernels_ir.py").write_text(IR_KERNELS)
    monkeypatch.syspath_prepend(str(tmp_path))
    monkeypatch.setattr(jit, "_CACHE", False)
    import kernels_ir as k

    assert k.outer(1.5) == 5.5 and k.other(1.5) == 2.0  # both link helper's IR
    assert machine_code(k.helper.inner) == [False]  # made once, for nothing to run it
    assert machine_code(k.outer) == [True] and machine_code(k.shared) == [True]
    assert k.helper(1.5) == 3.0 and machine_code(k.helper) == [True]  # Python's own version


@pytest.mark.skipif(not jit.IR_ONLY, reason="this numba's code library lacks what it needs")
def test_a_cached_version_without_an_entry_links_into_a_new_caller(tmp_path):
    """A later process compiles a new caller of a function whose version without an entry is
    in the cache as IR alone: it loads that IR (no compile, no machine code) and links it."""
    (tmp_path / "kernels_ir_cached.py").write_text(IR_KERNELS)
    code = (
        "import kernels_ir_cached as k\n"
        "print(k.{call})\n"
        "inner = k.helper.__dict__.get('_inner')\n"
        "print(sum(inner.stats.cache_hits.values()) if inner else '-')\n"
    )

    def run(call: str) -> list[str]:
        return in_process(tmp_path, code.format(call=call))

    assert run("outer(1.5)") == ["5.5", "0"]  # compiled, helper's IR written to the cache
    assert run("other(1.5)") == ["2.0", "1"]  # a new caller: helper's IR loaded and linked
    assert run("other(1.5)") == ["2.0", "-"]  # the caller itself loaded: helper not needed
