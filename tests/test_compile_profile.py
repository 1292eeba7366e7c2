"""``benchmarks/compile_profile.py``'s clock charges each stage only its own time (a stage that
calls another is not charged for it), and its report adds the stages and counts the functions
as the clock saw them. Compiling itself is not run here (a minute from an empty cache)."""

from __future__ import annotations

import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
import compile_profile  # noqa: E402


def test_clock_charges_each_stage_its_own_time():
    class Library:
        """Stands in for a numba code library: ``outer`` sleeps around ``inner``."""

        def outer(self, inner_seconds: float) -> str:
            time.sleep(0.05)
            self.inner(inner_seconds)
            return "done"

        def inner(self, seconds: float) -> None:
            time.sleep(seconds)

    clock = compile_profile.Clock()
    clock.wrap(Library, "outer", "outer stage")
    clock.wrap(Library, "inner", "inner stage")
    assert Library().outer(0.2) == "done"
    assert clock.calls == {"outer stage": 1, "inner stage": 1}
    assert 0.2 <= clock.seconds["inner stage"] < 0.3
    assert 0.05 <= clock.seconds["outer stage"] < 0.15  # not 0.25: the inner stage is its own
    assert clock.inner == []


def test_report_adds_the_stages_and_counts_the_functions():
    clock = compile_profile.Clock()
    clock.seconds.update({"LLVM: module passes": 3.0, "type inference": 1.0})
    clock.calls.update({"LLVM: module passes": 2, "type inference": 2})
    clock.libraries = {
        1: {"name": "step", "s": 2.5, "functions": 6, "kb": 120, "linked": 2},
        2: {"name": "stage", "s": 0.5, "functions": 3, "kb": 40, "linked": 0},
    }
    clock.own = 3  # 9 functions in the final modules, 3 written: 3 times each
    text = compile_profile.report(clock, {1: "sandbox.step.fast_step"}, ["a family"], 5.0, 10)
    lines = text.splitlines()
    assert lines[0] == "a family: 5.0 s, 2 libraries compiled"
    assert "LLVM: module passes" in lines[3] and "3.0" in lines[3] and "60%" in lines[3]
    assert "1.0" in lines[5] and "20%" in lines[5]  # (stepping, caching, Python): 5 - 3 - 1
    assert "machine code 3.0 times on the average" in text
    assert "(9 functions in the libraries' final modules, 3 in their own IR)" in text
    step = next(line for line in lines if line.startswith("step.fast_step"))
    assert step.split()[1:] == ["2.50", "6", "120", "2"]
    assert lines[-1].split() == ["stage", "0.50", "3", "40", "0"]  # the costliest first
