"""A long `sandbox simulate` or `sandbox compare` shows its steps on a terminal; a short run, a
log, a notebook or a pipe get nothing (``sandbox.step_bar.StepBar``)."""

import io
import sys
from pathlib import Path

from sandbox import step_bar
from sandbox.cli import main
from sandbox.compare import compare
from sandbox.scene import read_scene_file
from sandbox.step_bar import StepBar

SCENES = Path(__file__).resolve().parent.parent / "scenes"


class Terminal(io.StringIO):
    """A screen that says it is a terminal (where progress bars are drawn)."""

    def isatty(self):
        return True


def run_steps(bar: StepBar, total: int) -> None:
    with bar:
        for _ in range(total):
            bar.step()


def test_a_run_past_the_delay_shows_its_steps_and_clears_them_at_the_end():
    screen = Terminal()
    run_steps(StepBar(50, screen, delay=0.0), 50)
    text = screen.getvalue()
    assert "/50 [" in text and "step/s" in text  # the count of 50, with the rate
    drawn = text.split("\r")
    assert drawn[-1] == "" and drawn[-2].strip() == ""  # the last line drawn is blank: cleared


def test_a_short_run_a_quiet_one_and_a_screen_that_is_no_terminal_get_nothing():
    screen = Terminal()
    run_steps(StepBar(50, screen, delay=60.0), 50)  # over long before the delay
    assert screen.getvalue() == ""
    run_steps(StepBar(50, screen, delay=0.0, quiet=True), 50)
    assert screen.getvalue() == ""
    log = io.StringIO()  # a log, a notebook's stream, a pipe
    bar = StepBar(50, log, delay=0.0)
    run_steps(bar, 50)
    assert log.getvalue() == "" and bar.bar is None


def test_the_bar_starts_with_the_first_step_made():
    # made after the first step, whose compile (on a cold cache) has a notice and bar of its own
    bar = StepBar(10, Terminal(), delay=0.0)
    assert bar.bar is None
    bar.step()
    assert bar.bar.n == 1 and bar.bar.total == 10
    bar.step()
    assert bar.bar.n == 2
    bar.__exit__(None, None, None)


def test_simulate_shows_the_bar_on_a_terminal_and_prints_the_same(tmp_path, monkeypatch, capsys):
    args = ["simulate", str(SCENES / "drop.json"), "--steps", "30", "--trace", ""]
    args[-1] = str(tmp_path / "a.csv")
    assert main(args) == 0
    plain = capsys.readouterr()
    assert plain.err == ""  # not a terminal: no bar
    screen = Terminal()
    monkeypatch.setattr(sys, "stderr", screen)
    monkeypatch.setattr(step_bar, "DELAY", 0.0)
    args[-1] = str(tmp_path / "b.csv")
    assert main(args) == 0
    assert "/30 [" in screen.getvalue()  # drawn (at most every 0.1 s, then cleared)
    shown = capsys.readouterr()
    assert shown.out == plain.out.replace("a.csv", "b.csv")  # the same results, the same lines
    assert (tmp_path / "a.csv").read_bytes() == (tmp_path / "b.csv").read_bytes()


def test_compare_counts_every_run_s_steps_in_one_bar(monkeypatch, capsys):
    spec = read_scene_file(SCENES / "drop.json")
    screen = Terminal()
    monkeypatch.setattr(sys, "stderr", screen)
    monkeypatch.setattr(step_bar, "DELAY", 0.0)
    made = []
    original = StepBar.step
    monkeypatch.setattr(StepBar, "step", lambda self: made.append(1) or original(self))
    compare(spec, 20, None, variants={"warm_start": [False]}, gif=False)
    assert len(made) == 60  # this engine, pymunk and the variant, 20 steps each
    assert "/60 [" in screen.getvalue()
    assert "deviation from pymunk" in capsys.readouterr().out  # the table, as before
    screen.seek(0)
    screen.truncate()
    compare(spec, 20, None, gif=False, quiet=True)  # quiet: no table, no bar
    assert screen.getvalue() == "" and capsys.readouterr().out == ""
