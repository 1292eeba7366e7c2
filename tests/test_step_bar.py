"""A long `sandbox simulate` shows its steps on a terminal; a short one, a log or a pipe get
nothing (``sandbox.cli.progress.StepBar``)."""

import io
import sys
from pathlib import Path

from sandbox.cli import main, progress
from sandbox.cli.progress import StepBar

DROP = Path(__file__).resolve().parent.parent / "scenes" / "drop.json"


class Terminal(io.StringIO):
    """A screen that says it is a terminal (where progress bars are drawn)."""

    def isatty(self):
        return True


def run_steps(bar: StepBar, total: int) -> None:
    with bar:
        for k in range(total + 1):  # 0: the initial state, then each step made
            bar.done(k)


def test_a_run_past_the_delay_shows_its_steps_and_clears_them_at_the_end():
    screen = Terminal()
    run_steps(StepBar(50, screen, delay=0.0), 50)
    text = screen.getvalue()
    assert "/50 [" in text and "step/s" in text  # the count of 50, with the rate
    drawn = text.split("\r")
    assert drawn[-1] == "" and drawn[-2].strip() == ""  # the last line drawn is blank: cleared


def test_a_short_run_and_a_screen_that_is_no_terminal_get_nothing():
    screen = Terminal()
    run_steps(StepBar(50, screen, delay=60.0), 50)  # over long before the delay
    assert screen.getvalue() == ""
    log = io.StringIO()  # a log, a notebook's stream, a pipe
    bar = StepBar(50, log, delay=0.0)
    run_steps(bar, 50)
    assert log.getvalue() == "" and bar.bar is None


def test_the_bar_starts_after_the_first_step_whose_compile_has_its_own():
    bar = StepBar(10, Terminal(), delay=0.0)
    bar.done(0)  # the initial state: no step made yet
    assert bar.bar is None
    bar.done(1)
    assert bar.bar.n == 1 and bar.bar.total == 10
    bar.done(2)
    assert bar.bar.n == 2
    bar.__exit__(None, None, None)


def test_simulate_shows_the_bar_on_a_terminal_and_prints_the_same(tmp_path, monkeypatch, capsys):
    args = ["simulate", str(DROP), "--steps", "30", "--trace", str(tmp_path / "a.csv")]
    assert main(args) == 0
    plain = capsys.readouterr()
    assert plain.err == ""  # not a terminal: no bar
    screen = Terminal()
    monkeypatch.setattr(sys, "stderr", screen)
    monkeypatch.setattr(progress, "STEP_BAR_DELAY", 0.0)
    args[-1] = str(tmp_path / "b.csv")
    assert main(args) == 0
    assert "/30 [" in screen.getvalue()  # drawn (at most every 0.1 s, then cleared)
    shown = capsys.readouterr()
    assert shown.out == plain.out.replace("a.csv", "b.csv")  # the same results, the same lines
    assert (tmp_path / "a.csv").read_bytes() == (tmp_path / "b.csv").read_bytes()
