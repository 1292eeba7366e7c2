"""Physical ranges: absurd numbers are refused with their field path, from scene files, the
command line and the Python API alike (issue 15, findings 1-3; issue 16, the API cases)."""

from __future__ import annotations

import copy
import json
import math

import pytest

import sandbox
from sandbox.cli import main
from sandbox.fieldspec import LENGTH, POSITION
from sandbox.scene import SceneError, read_scene_file, validate_scene

BASE = {
    "bodies": [
        {"name": "ground", "type": "static", "shapes": [{"type": "box", "width": 10, "height": 1}]},
        {"name": "ball", "position": [0, 2], "shapes": [{"type": "circle", "radius": 0.5}]},
        {"name": "crate", "position": [2, 2], "shapes": [{"type": "box", "width": 1, "height": 1}]},
    ],
    "joints": [{"type": "pin", "a": "ball", "b": "crate"}],
}


def changed(*keys_and_value):
    *keys, value = keys_and_value
    scene = copy.deepcopy(BASE)
    target = scene
    for key in keys[:-1]:
        target = target[key]
    target[keys[-1]] = value
    return scene


B = "bodies"
# (scene, field path, part of the message): each one used to pass validation or fail elsewhere
FINDINGS = [
    (changed(B, 1, "position", [0, 1e200]), "bodies[1].position[1]", "[-1e+09, 1e+09] m"),
    (changed("joints", 0, "anchor_a", [1e200, 0]), "joints[0].anchor_a[0]", "[-1e+06, 1e+06] m"),
    (changed(B, 0, "shapes", 0, "width", 1e300), "bodies[0].shapes[0].width", "got 1e+300"),
    (changed(B, 1, "shapes", 0, "radius", 1e-200), "bodies[1].shapes[0].radius", "got 1e-200"),
    (changed(B, 1, "shapes", 0, "radius", 1e308), "bodies[1].shapes[0].radius", "got 1e+308"),
    (changed(B, 1, "mass", 1e-320), "bodies[1].mass", "[1e-12, 1e+15] kg"),
    (changed(B, 1, "moment", 1e-320), "bodies[1].moment", "kg m^2"),
    (changed(B, 1, "shapes", 0, "density", 1e-320), "bodies[1].shapes[0].density", "kg/m^2"),
    (changed(B, 1, "shapes", 0, "mass", 1e-320), "bodies[1].shapes[0].mass", "got 1e-320"),
    (changed("gravity", [0, 1e308]), "gravity[1]", "m/s^2, got 1e+308"),
    (changed("dt", 1e308), "dt", "[1e-06, 10] s"),
    (changed(B, 1, "velocity", [1e300, 0]), "bodies[1].velocity[0]", "m/s"),
    (changed(B, 0, "shapes", 0, "height", 1e-12), "bodies[0].shapes[0].height", "[1e-06, 1e+06]"),
    (
        changed(B, 0, "shapes", 0, {"type": "box", "width": 1e6, "height": 1e-5}),
        "bodies[0].shapes[0].height",
        "a box this thin",
    ),
    (
        changed(B, 1, "shapes", 0, {"type": "polygon", "vertices": [[0, 0], [1e-7, 0], [0, 1e-7]]}),
        "bodies[1].shapes[0].vertices",
        "area >= 1e-12 m^2",
    ),
]


@pytest.mark.parametrize(("scene", "path", "fragment"), FINDINGS)
def test_absurd_numbers_exit_2_naming_the_field_and_write_nothing(
    tmp_path, capsys, scene, path, fragment
):
    file = tmp_path / "s.json"
    file.write_text(json.dumps(scene))
    outputs = [tmp_path / "t.csv", tmp_path / "a.gif", tmp_path / "a.png"]
    args = ["simulate", str(file), "--steps", "5"]
    args += ["--trace", str(outputs[0]), "--gif", str(outputs[1]), "--png", str(outputs[2])]
    assert main(args) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith(f"error: {path}: "), err
    assert fragment in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.json"]


def test_a_5001_digit_integer_is_refused_with_its_path(tmp_path, capsys):
    file = tmp_path / "s.json"
    text = json.dumps(BASE).replace('"radius": 0.5', '"radius": ' + "9" * 5001)
    file.write_text(text)
    with pytest.raises(SceneError) as info:
        read_scene_file(file)
    assert info.value.path == "bodies[1].shapes[0].radius"
    assert "integer of 5001 digits" in info.value.message
    assert main(["simulate", str(file), "--trace", str(tmp_path / "t.csv")]) == 2
    assert capsys.readouterr().err.startswith("error: bodies[1].shapes[0].radius: ")
    with pytest.raises(SceneError, match="radius"):  # the same integer from Python
        sandbox.Circle(10**5000)


@pytest.mark.parametrize(
    ("option", "value"),
    [("--dt", "1e308"), ("--dt", "1e-320"), ("--fps", "1e-320"), ("--steps", "1000000000000")],
)
def test_absurd_command_line_numbers_exit_2(tmp_path, capsys, option, value):
    scene = tmp_path / "s.json"
    scene.write_text(json.dumps(BASE))
    gif = tmp_path / "a.gif"
    assert main(["simulate", str(scene), option, value, "--gif", str(gif)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith(f"error: {option}: expected"), err
    assert not gif.exists()


def test_the_ranges_are_wide_enough_for_real_use():
    # positions to 1e7 m and beyond, lessons' one-second steps, millimetre and kilometre shapes
    scene = changed(B, 1, "position", [1e7, -1e7])
    scene["dt"] = 1.0
    scene["bodies"][2]["shapes"][0].update(width=1e-3, height=1e3)
    spec = validate_scene(scene)
    assert spec["bodies"][1]["position"] == [1e7, -1e7]
    assert POSITION.hi >= 1e7 and LENGTH.lo <= 1e-3 and LENGTH.hi >= 1e3
    world = sandbox.load_scene(scene)
    world.step()
    assert all(math.isfinite(c) for b in world.bodies for c in (*b.position, *b.velocity))


# --- the Python API: the same checks, at the call -----------------------------------------------
def test_bad_gravity_raises_at_the_call():
    with pytest.raises(SceneError) as info:
        sandbox.World(gravity=-9.81)
    assert info.value.path == "gravity" and "expected [x, y]" in info.value.message
    with pytest.raises(SceneError, match=r"gravity\[1\]: expected a finite number, got NaN"):
        sandbox.World(gravity=(0, math.nan))
    with pytest.raises(SceneError, match=r"gravity\[1\]"):
        sandbox.World(gravity=(0, 1e308))
    with pytest.raises(SceneError, match="dt: expected a number in"):
        sandbox.World(dt=1e308)


def test_nan_velocity_raises_at_the_call():
    with pytest.raises(SceneError) as info:
        sandbox.Body("b", velocity=(math.nan, 0.0))
    assert info.value.path == "velocity[0]" and "got NaN" in info.value.message
    world = sandbox.World()
    body = world.add_body(sandbox.Body("b"))
    body.add_shape(sandbox.Circle(0.5))
    with pytest.raises(SceneError, match=r"velocity\[1\]"):
        body.velocity = (0.0, math.inf)
    with pytest.raises(SceneError, match="angular_velocity"):
        body.angular_velocity = math.nan
    with pytest.raises(SceneError, match=r"position\[0\]"):
        body.position = (1e200, 0.0)
    assert body.velocity == (0.0, 0.0) and body.position == (0.0, 0.0)  # nothing changed


def test_sizes_must_be_positive_at_the_call():
    with pytest.raises(SceneError) as info:
        sandbox.Box(-1, 1)
    assert info.value.path == "width" and "expected a number > 0, got -1" in info.value.message
    with pytest.raises(SceneError, match="height"):
        sandbox.Box(1, 0)
    with pytest.raises(SceneError, match="radius: expected a number > 0"):
        sandbox.Circle(-0.5)
    with pytest.raises(SceneError, match="not strictly convex"):
        sandbox.Polygon([(0, 0), (2, 0), (2, 2), (1, 0.5)])
    with pytest.raises(SceneError, match=r"restitution: expected a number in \[0, 1\]"):
        sandbox.Circle(0.5, restitution=1.5)


def test_unknown_keywords_get_a_did_you_mean():
    with pytest.raises(TypeError) as info:  # a TypeError, as Python's own, and a SceneError
        sandbox.Circle(0.5, elasticity=0.9)
    assert "did you mean 'restitution'?" in str(info.value)
    assert isinstance(info.value, SceneError) and info.value.path == "elasticity"
    with pytest.raises(TypeError, match="did you mean 'friction'"):
        sandbox.Box(1, 1, frction=0.3)
    with pytest.raises(TypeError, match="did you mean 'warm_start'"):
        sandbox.World(warmstart=False)


def test_pymunk_habits_get_a_hint():
    with pytest.raises(SceneError) as info:
        sandbox.Body(1, 10)  # pymunk's Body(mass, moment)
    message = str(info.value)
    assert info.value.path == "name" and "mass=1" in message and "moment=10" in message
    body = sandbox.Body("b")
    with pytest.raises(TypeError, match=r"body.add_shape\(Circle"):
        sandbox.Circle(body, 0.5)  # pymunk's Circle(body, radius)


def test_reprs_of_shapes_joints_and_forces():
    assert repr(sandbox.Circle(0.5, restitution=0.2)) == (
        "Circle(0.5, density=1, restitution=0.2, friction=0.5)"
    )
    assert repr(sandbox.Box(2, 1, offset=(0, -0.5))).startswith("Box(2, 1, offset=(0, -0.5)")
    assert repr(sandbox.Polygon([(0, 0), (1, 0), (0, 1)])).startswith("Polygon([(0, 0), (1, 0)")
    assert repr(sandbox.Drag(linear=0.1)) == (
        "Drag(linear=0.1, quadratic=0, angular=0, bodies=None)"
    )
    world = sandbox.World()
    a = world.add_body(sandbox.Body("a", mass=1, moment=1))
    b = world.add_body(sandbox.Body("b", mass=1, moment=1))
    assert "'a'" in repr(sandbox.PinJoint(a, b)) and "'b'" in repr(sandbox.PinJoint(a, b))
