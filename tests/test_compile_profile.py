"""``benchmarks/compile_profile.py``'s clock charges each stage only its own time (a stage that
calls another is not charged for it), and its report adds the stages and counts the functions
as the clock saw them. Compiling itself is not run here (a minute from an empty cache)."""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
import compile_profile  # noqa: E402


class FakeTime:
    """A clock that moves only when told (``pass_time``): the times are exact."""

    def __init__(self) -> None:
        self.now = 0.0

    def perf_counter(self) -> float:
        return self.now

    def pass_time(self, seconds: float) -> None:
        self.now += seconds


def test_clock_charges_each_stage_its_own_time(monkeypatch):
    clock_time = FakeTime()
    monkeypatch.setattr(compile_profile, "time", clock_time)

    class Library:
        """Stands in for a numba code library: ``outer`` spends 0.5 s around ``inner``."""

        def outer(self, inner_seconds: float) -> str:
            clock_time.pass_time(0.25)
            self.inner(inner_seconds)
            clock_time.pass_time(0.25)
            return "done"

        def inner(self, seconds: float) -> None:
            clock_time.pass_time(seconds)

    clock = compile_profile.Clock()
    clock.wrap(Library, "outer", "outer stage")
    clock.wrap(Library, "inner", "inner stage")
    assert Library().outer(2.0) == "done"
    assert Library().outer(1.0) == "done"
    assert clock.calls == {"outer stage": 2, "inner stage": 2}
    assert clock.seconds["inner stage"] == 3.0
    assert clock.seconds["outer stage"] == 1.0  # not 4.0: the inner stage is its own
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
