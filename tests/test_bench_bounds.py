"""``benchmarks/bounds.py``: every bound's ratio in every run, and the count of runs it held in,
from stand-in timings (no engine steps)."""

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
import bounds  # noqa: E402  (benchmarks/bounds.py, beside run.py)


@pytest.fixture
def timed(monkeypatch):
    """Seconds per step by scene and run: this engine's time goes up by 10 % each run."""
    calls = []

    def measure(scene, clock):
        calls.append((scene, clock))
        run = sum(1 for s, _ in calls if s == scene) - 1
        mine = {"rain_5000": 0.38, "pyramid_40": 0.55}.get(scene, 0.5) * 1.1**run
        return {"iterative": mine, "soft": 9.0, "pymunk": 1.0, "Box2D": 2.0}

    monkeypatch.setattr(bounds, "measure", measure)
    monkeypatch.setattr(bounds.run, "warm_up", lambda: None)
    return calls


def test_each_scene_is_timed_once_a_run_and_feeds_its_bounds(timed):
    chosen = [bounds.Bound("rain_100", "pymunk", 0.7), bounds.Bound("rain_100", "Box2D", 1.0)]
    found = bounds.ratios(chosen, 2, "wall", report=lambda *a, **k: None)
    assert timed == [("rain_100", "wall"), ("rain_100", "wall")]
    assert found[chosen[0]] == pytest.approx([0.5, 0.55])
    assert found[chosen[1]] == pytest.approx([0.25, 0.275])


def test_the_table_counts_the_runs_each_bound_held_in():
    found = {
        bounds.Bound("rain_5000", "pymunk", 0.4): [0.38, 0.418, 0.4],
        bounds.Bound("pyramid_40", "pymunk", 0.6): [0.55, 0.605, 0.6655],
    }
    rows = bounds.table(found).splitlines()
    assert rows[0] == "| bound | limit | run 1 | run 2 | run 3 | median | largest | held |"
    assert rows[2] == (
        "| rain_5000, iterative / pymunk | 0.40 | 0.380 | 0.418 | 0.400 | 0.400 | 0.418 | 2 of 3 |"
    )
    assert rows[3].endswith("| 0.605 | 0.665 | 1 of 3 |")


def test_exit_status_says_whether_every_bound_held_in_every_run(timed, capsys):
    assert bounds.main(["--runs", "1"]) == 0
    assert "every bound held in every run" in capsys.readouterr().out
    assert bounds.main(["--runs", "2"]) == 1  # the second run is 10 % slower: 0.418 > 0.4
    out = capsys.readouterr().out
    assert out.splitlines()[-1] == (  # 0.605 > 0.6 as well; 0.55 <= 0.7 on the others
        "over the limit in some run: rain_5000, iterative / pymunk; pyramid_40, iterative / pymunk"
    )
