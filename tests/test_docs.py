"""The user reference agrees with the code: the scene reference documents every field the
validator knows (and only those), the command-line page every option, and the Python API guide's
code runs."""

from __future__ import annotations

import argparse
import copy
import os
import re
from pathlib import Path

import pytest

from sandbox.cli import build_parser
from sandbox.reference import cli_reference, lesson_list, scene_reference
from sandbox.scene import SceneError, validate_scene
from sandbox.settings import Settings

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs"

# a scene touching every object and every optional field, written out in full
RICH = {
    "version": 1,
    "name": "rich",
    "gravity": [0, -9.81],
    "dt": 0.01,
    "settings": Settings().scene_dict(full=True),
    "bodies": [
        {"name": "ground", "type": "static", "shapes": [{"type": "box", "width": 10, "height": 1,
                                                          "offset": [0, -0.5], "angle": 0.1, "density": 1,
                                                          "mass": None, "restitution": 0,
                                                          "friction": 1}]},
        {"name": "ball", "type": "dynamic", "position": [0, 2], "angle": 0.2, "velocity": [1, 0],
         "angular_velocity": 0.5, "ccd": True, "mass": 2, "moment": 0.3, "force": [0, 1],
         "torque": 0.1,
         "shapes": [{"type": "circle", "radius": 0.5, "offset": [0, 0], "density": 2, "mass": 1,
                     "restitution": 0.5, "friction": 0.4}]},
        {"name": "tri", "position": [2, 2],
         "shapes": [{"type": "polygon", "vertices": [[0, 0], [1, 0], [0, 1]], "density": 1,
                     "mass": None, "restitution": 0.1, "friction": 0.5}]},
        {"name": "lift", "type": "kinematic"},
    ],
    "joints": [
        {"type": "pin", "a": "ground", "b": "ball", "anchor_a": [0, 0], "anchor_b": [0, 0]},
        {"type": "pivot", "a": "ball", "b": "tri", "anchor_a": [0, 0], "anchor_b": [0, 0],
         "limits": [-1, 1],
         "motor": {"rate": 1, "max_torque": 5}},
        {"type": "spring", "a": "ground", "b": "tri", "anchor_a": [0, 0], "anchor_b": [0, 0],
         "rest_length": 1, "stiffness": 10,
         "damping": 0.5},
    ],
    "forces": [
        {"type": "drag", "linear": 0.1, "quadratic": 0.01, "angular": 0.1, "bodies": ["ball"]},
        {"type": "buoyancy", "surface_y": 0, "fluid_density": 1, "linear_drag": 1,
         "angular_drag": 1, "bodies": None},
        {"type": "constant", "force": [1, 0], "torque": 0, "point": [0, 0.5], "bodies": None},
    ],
}  # fmt: skip


def documented() -> dict[str, set[str]]:
    """{object name: documented field names}, parsed from the generated scene reference."""
    out: dict[str, set[str]] = {}
    current = None
    section_objects = {"The file": "scene", "Settings": "settings", "Bodies": "body"}
    for line in scene_reference().splitlines():
        if line.startswith("## "):
            current = section_objects.get(line[3:].strip())
        elif line.startswith("### "):
            current = line[4:].strip().strip("`")
        elif line.startswith("| `") and current:
            out.setdefault(current, set()).add(line.split("`")[1])
    return out


def validated() -> dict[str, set[str]]:
    """{object name: field names} of what the validator returns for the rich scene."""
    spec = validate_scene(RICH)
    out = {"scene": set(spec), "settings": set(spec["settings"]), "body": set()}
    for body in spec["bodies"]:
        out["body"] |= set(body)
        for shape in body["shapes"]:
            out.setdefault(shape["type"], set()).update(shape)
    for item in (*spec["joints"], *spec["forces"]):
        out.setdefault(item["type"], set()).update(item)
        if item.get("motor"):
            out.setdefault("motor", set()).update(item["motor"])
    return out


def test_scene_reference_covers_every_field_the_validator_knows():
    docs, known = documented(), validated()
    assert set(docs) == set(known)
    for name in known:
        assert docs[name] == known[name], name
    assert docs["settings"] == set(Settings.names())


def test_every_documented_field_is_accepted_and_an_undocumented_one_is_not():
    docs = documented()
    paths = {  # where each object sits in RICH
        "scene": lambda s: s,
        "settings": lambda s: s["settings"],
        "body": lambda s: s["bodies"][1],
        "circle": lambda s: s["bodies"][1]["shapes"][0],
        "box": lambda s: s["bodies"][0]["shapes"][0],
        "polygon": lambda s: s["bodies"][2]["shapes"][0],
        "pin": lambda s: s["joints"][0],
        "pivot": lambda s: s["joints"][1],
        "motor": lambda s: s["joints"][1]["motor"],
        "spring": lambda s: s["joints"][2],
        "drag": lambda s: s["forces"][0],
        "buoyancy": lambda s: s["forces"][1],
        "constant": lambda s: s["forces"][2],
    }
    assert set(paths) == set(docs)
    for name, where in paths.items():
        assert docs[name] <= set(where(RICH)), f"{name}: RICH should set every field"
        scene = copy.deepcopy(RICH)
        where(scene)["undocumented_field"] = 1
        with pytest.raises(SceneError, match="unknown"):
            validate_scene(scene)


def test_the_reference_states_units_defaults_and_ranges():
    text = scene_reference()
    assert "| `radius` | number | m | required | [1e-06, 1e+06] m |" in text
    assert "| `warm_start` | boolean | - | `true` | true \\| false |" in text
    assert "| `position` | [x, y] | m | `[0.0, 0.0]` | [-1e+09, 1e+09] m |" in text


def test_command_line_page_lists_every_command_and_option():
    # every option a user may give; the hidden ones (the warmup's --part, for its own helper
    # process) not at all: they showed as "==SUPPRESS==" in the reference
    text = cli_reference()
    parser = build_parser()
    hidden = 0
    for name, sub in parser._subparsers._group_actions[0].choices.items():
        assert f"## `sandbox {name}`" in text
        for action in sub._actions:
            for option in action.option_strings:
                if option in ("-h", "--help"):
                    continue
                if action.help == argparse.SUPPRESS:
                    hidden += 1
                    assert f"`{option}" not in text, f"{name} {option}"
                else:
                    assert f"`{option}" in text, f"{name} {option}"
    assert hidden and "SUPPRESS" not in text


def test_lesson_list_has_one_line_per_lesson():
    lines = lesson_list(ROOT / "lessons").splitlines()
    assert len(lines) == len(list((ROOT / "lessons").glob("[0-9][0-9]_*.py")))
    assert all(re.match(r"- \*\*\d\d .+\*\* \(`lessons/\d\d_\w+\.py`\): .+", x) for x in lines)


def test_pages_hold_their_generated_parts():
    for page, marker in (
        ("scene-format.md", "scene-reference"),
        ("command-line.md", "cli-reference"),
        ("lessons.md", "lesson-list"),
    ):
        assert f"<!-- generated: {marker} -->" in (DOCS / page).read_text()


def test_python_api_guide_runs(tmp_path, monkeypatch):
    """Every ```python block of the guide, in order, in a folder with the example scenes."""
    text = (DOCS / "python-api.md").read_text()
    blocks = re.findall(r"```python\n(.*?)```", text, re.S)
    assert len(blocks) >= 8
    os.symlink(ROOT / "scenes", tmp_path / "scenes")
    monkeypatch.chdir(tmp_path)
    namespace: dict = {}
    for block in blocks:
        exec(compile(block, "python-api.md", "exec"), namespace)  # noqa: S102 (our own docs)
    for name in ("pendulum.gif", "pendulum.png", "stack.gif", "stack_after.json"):
        assert (tmp_path / name).stat().st_size > 0, name


def test_api_reference_names_each_object_where_it_is_defined():
    """The site builder reads the source without importing it, so it cannot follow the lazy
    top-level names of ``sandbox``: each ``::: target`` must name the module that defines it
    (or re-exports it by a plain import)."""
    import ast
    import importlib.util

    targets = re.findall(r"^::: ([\w.]+)$", (DOCS / "api.md").read_text(), flags=re.M)
    assert len(targets) > 20
    for target in targets:
        module, _, name = target.rpartition(".")
        spec = importlib.util.find_spec(module)
        assert spec is not None and spec.origin, target
        tree = ast.parse(open(spec.origin, encoding="utf-8").read())
        defined = {n.name for n in tree.body if isinstance(n, (ast.ClassDef, ast.FunctionDef))} | {
            a.asname or a.name for n in tree.body if isinstance(n, ast.ImportFrom) for a in n.names
        }
        assert name in defined, f"{target}: not defined in {spec.origin}"
