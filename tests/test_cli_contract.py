"""The command line as a user meets it: --version, --help, did-you-mean, --vary, notes, schema."""

from __future__ import annotations

import json
import subprocess
import sys
from importlib.metadata import version
from pathlib import Path

import pytest

import sandbox
from sandbox.cli import build_parser, main
from sandbox.trace import read_trace

ROOT = Path(__file__).resolve().parent.parent
DROP = ROOT / "scenes" / "drop.json"
STACK = ROOT / "scenes" / "stack.json"


def test_version_prints_the_installed_version(capsys):
    assert main(["--version"]) == 0
    assert capsys.readouterr().out.strip() == f"sandbox {version('physics-sandbox')}"
    assert sandbox.__version__ == version("physics-sandbox")
    res = subprocess.run(
        [sys.executable, "-m", "sandbox", "--version"], capture_output=True, text=True
    )
    assert res.returncode == 0 and res.stdout.split() == ["sandbox", sandbox.__version__]


@pytest.mark.parametrize("command", ["simulate", "compare", "lessons", "schema"])
def test_help_shows_defaults_and_an_example(capsys, command):
    assert main([command, "--help"]) == 0
    text = capsys.readouterr().out
    assert f"examples:\n  sandbox {command}" in text
    if command in ("simulate", "compare"):
        assert "(default: 300)" in text and "--set KEY=VALUE" in text


def test_every_option_has_help():
    parser = build_parser()
    for name, sub in parser._subparsers._group_actions[0].choices.items():
        for action in sub._actions:
            assert action.help, f"{name} {action.option_strings or action.dest}"


@pytest.mark.parametrize(
    ("args", "line"),
    [
        (["simulate", str(DROP), "--stesp", "10"], "error: --stesp: unknown option (did you mean --steps?)"),
        (["simulate", str(DROP), "--tarce=x.csv"], "error: --tarce: unknown option (did you mean --trace?)"),
        (["simulat", str(DROP)], "(did you mean simulate?)"),
        (["simulate", str(DROP), "--engine", "pymonk"], "(did you mean pymunk?)"),
        # another command's option: said so, never "did you mean" the option itself
        (["simulate", str(DROP), "--out", "x"], "error: --out: unknown option for `sandbox simulate` (an option of `sandbox compare` and `sandbox lessons`; see `sandbox simulate -h`)"),
        (["lessons", "--outt", "x"], "error: --outt: unknown option (did you mean --out?)"),
    ],
)  # fmt: skip
def test_mistyped_flags_get_one_line_with_a_suggestion(capsys, args, line):
    assert main(args) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("error: ") and line in err, err


def test_engine_pymunk_notes_each_setting_it_cannot_honour(capsys, tmp_path):
    out = tmp_path / "p.csv"
    args = ["simulate", str(DROP), "--steps", "3", "--engine", "pymunk", "--trace", str(out)]
    assert main([*args, "--set", "warm_start=false", "--set", "iterations=4"]) == 0
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("note: pymunk cannot honour warm_start=false")
    assert "iterations=4" not in err  # pymunk honours the iteration count
    assert main(args) == 0
    assert capsys.readouterr().err == ""  # nothing to say about the defaults
    assert len(read_trace(out)) == 4 * 2


def test_compare_vary_adds_an_overlaid_run(tmp_path, capsys):
    out = tmp_path / "cmp"
    args = ["compare", str(STACK), "--steps", "60", "--out", str(out), "--no-gif"]
    assert main([*args, "--vary", "warm_start=false", "--solver", "pairwise"]) == 0
    names = sorted(p.name for p in out.iterdir())
    assert "trace_warm_start_false.csv" in names and "trace_solver_pairwise.csv" in names
    summary = (out / "summary.txt").read_text()
    assert "sandbox warm_start=false" in summary and "sandbox solver=pairwise" in summary
    top = {
        run: [r["y"] for r in read_trace(out / f"trace_{run}.csv") if r["body"] == "box9"]
        for run in ("sandbox", "warm_start_false")
    }
    # the variant really ran without warm starting: its top box sank more (see test_settings)
    assert (
        top["sandbox"][0] - top["sandbox"][-1]
        < top["warm_start_false"][0] - top["warm_start_false"][-1]
    )


def test_compare_vary_bad_key_exits_2_and_writes_nothing(tmp_path, capsys):
    out = tmp_path / "cmp"
    assert main(["compare", str(DROP), "--out", str(out), "--vary", "warmstart=false"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("error: --vary warmstart: unknown setting (did you mean 'warm_start'?)")
    assert not out.exists()


@pytest.mark.parametrize(
    "key, where",
    [
        ("gravity=0,-1.62", 'gravity is the scene\'s own, beside its settings: "gravity": '),
        ("dt=0.01", "dt is the scene's own, beside its settings; on the command line, --dt"),
    ],
)
def test_set_of_a_scene_field_says_where_it_is_set(tmp_path, capsys, key, where):
    # a teacher's --set gravity=... names the field and where it belongs, not a did-you-mean
    out = tmp_path / "t.csv"
    assert main(["simulate", str(DROP), "--steps", "3", "--set", key, "--trace", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"error: --set {key.split('=')[0]}: unknown setting ({where}")
    assert err.count("\n") == 1 and not out.exists()


def test_schema_command_prints_the_shipped_schema(capsys):
    from sandbox.schema import scene_schema, shipped_schema_text

    assert main(["schema"]) == 0
    printed = capsys.readouterr().out
    assert json.loads(printed) == scene_schema()
    assert printed == shipped_schema_text()  # the packaged file is the generated one


def test_a_refused_pymunk_run_is_one_error_line_without_the_note(tmp_path, monkeypatch, capsys):
    from sandbox import pymunk_bridge

    def refuse(spec):  # where the bridge refuses a scene it cannot express
        raise pymunk_bridge.BridgeError("forces[0]", "pymunk has no such force")

    monkeypatch.setattr(pymunk_bridge.PymunkScene, "from_scene", staticmethod(refuse))
    out = tmp_path / "p.csv"
    args = ["simulate", str(DROP), "--engine", "pymunk", "--set", "warm_start=false"]
    assert main([*args, "--trace", str(out)]) == 2
    assert capsys.readouterr().err == "error: forces[0]: pymunk has no such force\n"
    assert not out.exists()
