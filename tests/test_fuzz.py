"""Fuzzing the command line with malformed and extreme scenes and options.

A generator (hypothesis, derandomized like every property test here) starts from a valid scene
with every kind of body, shape, joint and force, then breaks it: a value swapped for an extreme
number (1e-320, 1e308, 10**400, 0, -1, NaN, infinity), a wrong type, a hostile name (mathtext,
a spreadsheet formula, control characters, a lone surrogate), a key removed or unknown, a body
duplicated, or the JSON text itself cut, prefixed or corrupted; and picks the command line:
steps, dt, fps, the engine, settings and the outputs (trace, PNG, GIF).

Whatever it draws, ``sandbox simulate`` keeps the contract:

- exit 2 with one ``error: <field>: <why>`` line on stderr, and no file written; or
- exit 0 with every requested output written and every traced number finite; or
- exit 1 (a run that failed after validation) with one ``error:`` line, and no file written.

Never a traceback, never a half-written or NaN-filled output.
"""

from __future__ import annotations

import contextlib
import copy
import io
import json
import math
import re
import tempfile
from pathlib import Path

from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st

from sandbox.cli import main
from sandbox.trace import read_trace

BASE = {
    "version": 1,
    "name": "fuzz",
    "gravity": [0.0, -9.81],
    "dt": 1 / 60,
    "settings": {"solver": "iterative", "iterations": 8},
    "bodies": [
        {
            "name": "ground",
            "type": "static",
            "shapes": [{"type": "box", "width": 20, "height": 1, "offset": [0, -0.5]}],
        },
        {
            "name": "ball",
            "position": [0.0, 2.0],
            "velocity": [1.0, 0.0],
            "shapes": [{"type": "circle", "radius": 0.5, "density": 1.0, "restitution": 0.5}],
        },
        {
            "name": "box",
            "position": [1.5, 1.0],
            "angle": 0.3,
            "shapes": [{"type": "box", "width": 1.0, "height": 0.5, "friction": 0.8}],
        },
        {
            "name": "tri",
            "position": [-1.5, 1.0],
            "angular_velocity": 1.0,
            "shapes": [{"type": "polygon", "vertices": [[0, 0], [1, 0], [0, 1]]}],
        },
        {"name": "hook", "type": "kinematic", "position": [0, 4], "mass": 1.0, "moment": 1.0},
    ],
    "joints": [
        {
            "type": "spring",
            "a": "hook",
            "b": "ball",
            "anchor_a": [0, 0],
            "anchor_b": [0, 0],
            "rest_length": 1.5,
            "stiffness": 40.0,
            "damping": 0.5,
        },
        {"type": "pin", "a": "box", "b": "tri", "anchor_a": [0.5, 0], "anchor_b": [0, 0]},
    ],
    "forces": [
        {"type": "drag", "linear": 0.1, "quadratic": 0.01},
        {"type": "buoyancy", "surface_y": 0.5, "fluid_density": 1.0, "bodies": ["tri"]},
    ],
}

EXTREMES = [
    0,
    -1,
    0.5,
    3,
    1e-320,
    5e-324,
    1e-200,
    1e-9,
    1e7,
    -1e7,
    1e12,
    1e200,
    1e300,
    1.7e308,
    -1.7e308,
    10**400,
    2**63,
]  # fmt: skip  (finite, and of the right type for most fields: they pass validation or not)
NON_FINITE = [math.nan, math.inf, -math.inf]
NAMES = [
    "$\\frac{$", '=HYPERLINK("http://example.com","x")', "+1", "-1", "@SUM(A1)", "\t=1",
    "a\nb", "\x1b[2J", "x" * 5000, "ball", "", " ", "\ud800", "ünï", "a,b\"c",
]  # fmt: skip
OTHERS = [None, True, "text", [], {}, [1], [1, 2, 3], [[0, 0], [1, 1]], {"x": 1}]


def paths(value, prefix=()):
    """Every path (tuple of keys and indices) inside a JSON value, containers included."""
    out = [prefix]
    if isinstance(value, dict):
        for k, v in value.items():
            out += paths(v, (*prefix, k))
    elif isinstance(value, list):
        for i, v in enumerate(value):
            out += paths(v, (*prefix, i))
    return out


ALL_PATHS = paths(BASE)[1:]


def _at(doc, path):
    for key in path:
        doc = doc[key]
    return doc


def set_at(doc, path, value):
    target = doc
    for key in path[:-1]:
        target = target[key]
    target[path[-1]] = value


def delete_at(doc, path):
    target = doc
    for key in path[:-1]:
        target = target[key]
    del target[path[-1]]


@st.composite
def scenes(draw):
    """A scene document as text: the base scene with one to three mutations."""
    doc = copy.deepcopy(BASE)
    for _ in range(draw(st.integers(1, 3))):
        everything = paths(doc)[1:]
        leaves = [p for p in everything if not isinstance(_at(doc, p), dict | list)]
        path = draw(st.sampled_from(leaves if draw(st.integers(0, 4)) else everything))
        value = _at(doc, path)
        if isinstance(value, dict | list):
            action = draw(st.sampled_from(["delete", "extra", "other"]))
        elif isinstance(value, str):
            action = draw(st.sampled_from(["name"] * 3 + ["other", "delete"]))
        else:  # a number (or a flag): mostly extreme but finite, so the run itself is tried
            action = draw(st.sampled_from(["extreme"] * 7 + ["nan", "other", "delete"]))
        if action == "extreme":
            set_at(doc, path, draw(st.sampled_from(EXTREMES)))
        elif action == "nan":
            set_at(doc, path, draw(st.sampled_from(NON_FINITE)))
        elif action == "name":
            set_at(doc, path, draw(st.sampled_from(NAMES)))
        elif action == "other":
            set_at(doc, path, copy.deepcopy(draw(st.sampled_from(OTHERS))))
        elif action == "delete":
            delete_at(doc, path)
        elif isinstance(value, dict):
            value["unknown_field"] = 1
        elif value:
            value.append(copy.deepcopy(value[-1]))  # one more vertex, body, joint, ...
    text = json.dumps(doc, allow_nan=True)
    how = draw(st.sampled_from(["as is"] * 16 + ["cut", "bom", "corrupt", "nested"]))
    if how == "cut":
        text = text[: draw(st.integers(0, len(text) - 1))]
    elif how == "bom":
        text = "\ufeff" + text
    elif how == "corrupt":
        k = draw(st.integers(0, len(text) - 1))
        text = text[:k] + draw(st.sampled_from(["}", "\x00", "'", "\\", "é", "1e999"])) + text[k:]
    elif how == "nested":
        text = text[:-1] + ', "name": ' + "[" * 5000 + "]" * 5000 + "}"
    return text


@st.composite
def command_lines(draw):
    """Options of ``sandbox simulate`` (after the scene), and the outputs asked for."""
    args = ["--steps", str(draw(st.sampled_from([0, 1, 3, 12, 30])))]
    args += draw(
        st.sampled_from(
            [[]] * 8
            + [["--engine", "pymunk"]] * 3
            + [["--solver", "pairwise"], ["--integrator", "rk4"], ["--broadphase", "grid"]]
            + [["--dt", "1e-320"], ["--dt", "1e-9"], ["--dt", "0.5"], ["--dt", "1e308"]]
        )
    )
    if draw(st.integers(0, 7)) == 0:  # a bad option: the scene is never read
        args += draw(
            st.sampled_from(
                [["--steps", "-1"], ["--steps", str(10**12)], ["--steps", "1e3"]]
                + [["--dt", "nan"], ["--dt", "0"], ["--iterations", "0"], ["--solver", "x"]]
            )
        )
    outputs = ["trace"]
    if draw(st.integers(0, 9)) == 0:
        outputs.append("png")
    if draw(st.integers(0, 19)) == 0:
        outputs.append("gif")
        fps = draw(st.sampled_from([None, None, 1e-320, 0.1, 60, "inf"]))
        if fps is not None:
            args += ["--fps", str(fps)]
    return args, outputs


FIELD = re.compile(r"^error: ([^\s:]+): \S")  # a field path, an option, "file" or "scene"


def simulate(folder: Path, text: str, args: list[str], outputs: list[str]):
    scene = folder / "scene.json"
    scene.write_bytes(text.encode("utf-8", "surrogatepass"))
    files = {"trace": "t.csv", "png": "a.png", "gif": "a.gif"}
    argv = ["simulate", str(scene), *args]
    for kind in outputs:
        argv += [f"--{kind}", str(folder / files[kind])]
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        status = main(argv)
    return status, out.getvalue(), err.getvalue(), [folder / files[k] for k in outputs]


def check_contract(status, out, err, written, folder):
    event(f"exit {status}")  # tallied by pytest --hypothesis-show-statistics
    assert status in (0, 1, 2), (status, err)
    assert "Traceback" not in err and "Traceback" not in out
    if status == 0:
        assert "error:" not in err
        assert len(err.splitlines()) <= 2  # at most a note and a summary of warnings
        for path in written:
            assert path.is_file() and path.stat().st_size > 0
        for row in read_trace(written[0]):
            assert all(math.isfinite(v) for k, v in row.items() if k != "body"), row
        return
    lines = err.splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), err
    if status == 2:
        match = FIELD.match(lines[0])
        assert match, lines[0]
        if match.group(1) == "scene":  # refused while building the world: no field path
            event(f"no field path: {lines[0][:100]}")
    assert sorted(p.name for p in folder.iterdir()) == ["scene.json"]  # nothing written


@settings(max_examples=200, suppress_health_check=[HealthCheck.too_slow])
@given(scenes(), command_lines())
def test_simulate_keeps_the_contract_on_malformed_and_extreme_input(text, command):
    args, outputs = command
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        status, out, err, written = simulate(folder, text, args, outputs)
        check_contract(status, out, err, written, folder)
