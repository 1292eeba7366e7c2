"""The command line: slide tables through --trace, exit status 2 on bad input, nothing written."""

import json
import subprocess
import sys
from pathlib import Path

import pytest

from sandbox.cli import main
from sandbox.trace import read_trace

ROOT = Path(__file__).resolve().parent.parent
PROJECTILE = ROOT / "scenes" / "projectile.json"

EULER = [(0, 0), (3, 4), (6, 7), (9, 9), (12, 10), (15, 10), (18, 9), (21, 7), (24, 4), (27, 0)]
ANALYTIC = [(0, 0), (3, 3.5), (6, 6), (9, 7.5), (12, 8), (15, 7.5), (18, 6), (21, 3.5), (24, 0)]


def run(*args):
    return main([str(a) for a in args])


def test_explicit_euler_trace_is_the_slides_numeric_table(tmp_path):
    out = tmp_path / "t.csv"
    assert run("simulate", PROJECTILE, "--steps", 9, "--trace", out) == 0
    header = out.read_text().splitlines()[0]
    assert header == "step,t,body,x,y,angle,vx,vy,omega"
    rows = read_trace(out)
    assert [(r["x"], r["y"]) for r in rows] == EULER  # exact, not approximate
    assert [r["step"] for r in rows] == list(range(10))


def test_analytic_trace_is_the_slides_analytic_table(tmp_path):
    out = tmp_path / "a.csv"
    assert (
        run("simulate", PROJECTILE, "--steps", 8, "--integrator", "analytic", "--trace", out) == 0
    )
    assert [(r["x"], r["y"]) for r in read_trace(out)] == ANALYTIC


def test_png_and_gif_are_written(tmp_path):
    png, gif = tmp_path / "a.png", tmp_path / "a.gif"
    assert run("simulate", PROJECTILE, "--steps", 9, "--png", png, "--gif", gif, "--fps", 2) == 0
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert gif.read_bytes()[:6] == b"GIF89a"


def write(tmp_path, data, name="s.json"):
    p = tmp_path / name
    p.write_text(data if isinstance(data, str) else json.dumps(data))
    return p


BAD = [
    ("{not json", "file"),
    (
        json.dumps({"bodies": [{"name": "a", "shapes": [{"type": "circle", "radius": -1}]}]}),
        "bodies[0].shapes[0].radius",
    ),
    (json.dumps({"dt": 0, "bodies": []}), "dt"),
    (json.dumps({"settings": {"solver": "magic"}, "bodies": []}), "settings.solver"),
    (
        json.dumps(
            {
                "bodies": [
                    {"name": "a", "mass": 1, "moment": 1},
                    {"name": "a", "mass": 1, "moment": 1},
                ]
            }
        ),
        "bodies[1].name",
    ),
]


@pytest.mark.parametrize("text,path", BAD)
def test_bad_scene_exits_2_with_one_line_and_writes_nothing(tmp_path, capsys, text, path):
    scene = write(tmp_path, text)
    out = tmp_path / "trace.csv"
    assert run("simulate", scene, "--trace", out, "--gif", tmp_path / "g.gif") == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith(f"error: {path}")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.json"]


@pytest.mark.parametrize(
    "args,path",
    [
        (["--steps", "-3"], "--steps"),
        (["--steps", "many"], "--steps"),
        (["--dt", "nan"], "--dt"),
        (["--dt", "0"], "--dt"),
        (["--engine", "box2d"], "--engine"),
        (["--trace", "no/such/folder/t.csv"], "--trace"),
        (["--gif", "out.png"], "--gif"),
    ],
)
def test_bad_options_exit_2(capsys, args, path):
    assert run("simulate", PROJECTILE, *args) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith(f"error: {path}")


def test_missing_file_and_unknown_lesson(capsys):
    assert run("simulate", "no-such-scene.json") == 2
    assert run("lessons", "no-such-lesson") == 2
    lines = capsys.readouterr().err.splitlines()
    assert lines[0].startswith("error: file:") and lines[1].startswith("error: NAME:")


def test_python_dash_m_and_console_script_are_the_same_program(tmp_path):
    out = tmp_path / "t.csv"
    res = subprocess.run(
        [
            sys.executable,
            "-m",
            "sandbox",
            "simulate",
            str(PROJECTILE),
            "--steps",
            "9",
            "--trace",
            str(out),
        ],
        capture_output=True,
        text=True,
    )
    assert res.returncode == 0, res.stderr
    assert [(r["x"], r["y"]) for r in read_trace(out)] == EULER
    bad = subprocess.run(
        [sys.executable, "-m", "sandbox", "simulate", str(tmp_path / "x.json")],
        capture_output=True,
        text=True,
    )
    assert bad.returncode == 2 and "Traceback" not in bad.stderr


def test_pymunk_engine_writes_the_same_trace_format(tmp_path):
    out = tmp_path / "p.csv"
    assert run("simulate", PROJECTILE, "--steps", 9, "--engine", "pymunk", "--trace", out) == 0
    rows = read_trace(out)
    assert len(rows) == 10
    # pymunk moves positions with the previous velocity: p_n = s + u n dt + a dt^2 n (n-1)/2,
    # the same positions as the slides' explicit Euler table (within 1e-9)
    for r, (x, y) in zip(rows, EULER, strict=True):
        assert r["x"] == pytest.approx(x, abs=1e-9) and r["y"] == pytest.approx(y, abs=1e-9)
