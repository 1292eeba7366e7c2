"""``benchmarks/run.py``'s command line: a partial run (``--only``, with names or without)
prints its table and keeps the last full results (the README's table, results.csv and the
plot), which come from a full run in one hour."""

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
import run  # noqa: E402  (benchmarks/run.py, beside the scenes)


@pytest.fixture
def stubbed(monkeypatch):
    """run.py with every timing and every writer replaced: records what was called."""
    calls = []
    monkeypatch.setattr(run, "warm_up", lambda: None)
    ok = {"benchmark": "-", "status": "ok"}
    monkeypatch.setattr(run, "bench_case", lambda case, quick, clock: calls.append(case.name) or ok)
    monkeypatch.setattr(run, "bench_gif", lambda: calls.append("bench_gif") or ok)
    monkeypatch.setattr(run, "bench_lessons", lambda cold=False: calls.append("lessons") or [])
    monkeypatch.setattr(run, "bench_lessons_shipped", lambda: calls.append("shipped") or [])
    monkeypatch.setattr(run, "format_table", lambda rows, clock: "table")
    for name in ("write_csv", "write_plot", "update_readme"):
        monkeypatch.setattr(run, name, lambda *a, _n=name: calls.append(_n))
    monkeypatch.setattr(run, "ENGINES", [])
    return calls


@pytest.mark.parametrize(
    ("only", "cases"),
    [([], [c.name for c in run.CASES]), (["rain_100"], ["rain_100"])],
)
def test_only_with_or_without_names_writes_nothing(stubbed, capsys, only, cases):
    run.main(["--only", *only])
    assert stubbed == cases  # the step benchmarks only: no GIF, no lessons, nothing written
    assert "(--only)" in capsys.readouterr().out


def test_a_full_run_writes_its_results(stubbed):
    run.main(["--quick", "--no-readme"])
    assert stubbed[-3:] == ["bench_gif", "write_csv", "write_plot"]


def test_the_lessons_with_shipped_kernels_are_timed_only_where_there_are_some(monkeypatch):
    from sandbox import prebuilt

    monkeypatch.setattr(prebuilt, "matches", lambda kernels: False)
    monkeypatch.setattr(run.subprocess, "run", lambda *a, **k: pytest.fail("ran the lessons"))
    assert run.bench_lessons_shipped() == []


def test_cold_lessons_time_both_ways(stubbed):
    run.main(["--quick", "--no-readme", "--cold-lessons"])
    assert stubbed[-4:] == ["lessons", "shipped", "write_csv", "write_plot"]
