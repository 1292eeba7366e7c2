"""Scene files: the contract's validation rules, defaults, round trips, example scenes, atomic writes."""

from __future__ import annotations

import copy
import importlib.util
import json
import math
import pickle
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from sandbox.atomic import atomic_write, atomic_write_bytes, atomic_write_text
from sandbox.fieldspec import LENGTH, POSITION
from sandbox.geometry import box_vertices, rotation, signed_area
from sandbox.scene import (
    SceneError,
    dump_scene,
    load_scene,
    read_scene_file,
    save_scene,
    validate_scene,
)

ROOT = Path(__file__).resolve().parents[1]
SCENES = ROOT / "scenes"
SCENE_NAMES = (
    "drop", "projectile", "stack", "pyramid", "pendulum", "newtons_cradle",
    "incline", "rain", "bullet", "spring", "buoyancy", "hinge_motor",
)  # fmt: skip

# the example of the design notes, verbatim
DESIGN_EXAMPLE = {
    "version": 1,
    "name": "drop",
    "gravity": [0.0, -9.81],
    "dt": 0.016666666666666666,
    "settings": {
        "orientation": "complex",
        "integrator": "semi_implicit_euler",
        "broadphase": "sap",
        "solver": "iterative",
        "iterations": 10,
        "penetration": "impulse",
    },
    "bodies": [
        {
            "name": "ground", "type": "static", "position": [0, 0],
            "shapes": [{"type": "box", "width": 40, "height": 1, "offset": [0, -0.5],
                        "restitution": 1.0, "friction": 1.0}],
        },
        {
            "name": "ball", "type": "dynamic",
            "position": [0, 10], "angle": 0.0, "velocity": [0, 0], "angular_velocity": 0.0,
            "ccd": False,
            "shapes": [{"type": "circle", "radius": 0.5, "density": 1.0,
                        "restitution": 0.5, "friction": 0.5}],
        },
    ],
    "joints": [],
    "forces": [],
}  # fmt: skip

# a small valid scene touching every kind of object; the malformed cases each break one field
BASE = {
    "version": 1,
    "name": "base",
    "bodies": [
        {"name": "ground", "type": "static", "shapes": [{"type": "box", "width": 10, "height": 1}]},
        {"name": "ball", "position": [0, 2], "shapes": [{"type": "circle", "radius": 0.5}]},
        {
            "name": "tri",
            "position": [2, 2],
            "shapes": [{"type": "polygon", "vertices": [[0, 0], [1, 0], [0, 1]]}],
        },
    ],
    "joints": [
        {"type": "pin", "a": "ground", "b": "ball"},
        {"type": "pivot", "a": "ball", "b": "tri"},
        {"type": "spring", "a": "ground", "b": "tri", "stiffness": 10},
    ],
    "forces": [
        {"type": "drag", "linear": 0.1},
        {"type": "buoyancy", "surface_y": 0, "fluid_density": 1},
    ],
}


def load_example(name: str) -> dict:
    return json.loads((SCENES / f"{name}.json").read_text())


# --- the example scenes ----------------------------------------------------------------------------
@pytest.mark.parametrize("name", SCENE_NAMES)
def test_example_scene_is_valid_and_round_trips(name):
    spec = validate_scene(read_scene_file(SCENES / f"{name}.json"))
    assert spec["name"] == name
    # dump -> parse -> validate gives the same normalized dict, bit for bit
    assert validate_scene(json.loads(dump_scene(spec))) == spec
    assert dump_scene(validate_scene(json.loads(dump_scene(spec)))) == dump_scene(spec)


def test_drop_is_the_design_example():
    assert load_example("drop") == DESIGN_EXAMPLE


def test_example_files_match_their_generator():
    spec = importlib.util.spec_from_file_location("make_scenes", SCENES / "make_scenes.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    texts = module.scene_texts()
    assert sorted(texts) == sorted(f"{n}.json" for n in SCENE_NAMES)
    for filename, text in texts.items():
        assert (SCENES / filename).read_text() == text, filename


def test_projectile_is_the_slides_example():
    spec = validate_scene(load_example("projectile"))
    (ball,) = spec["bodies"]
    assert spec["gravity"] == [0.0, -1.0] and spec["dt"] == 1.0
    assert spec["settings"]["integrator"] == "explicit_euler"
    assert ball["position"] == [0.0, 0.0] and ball["velocity"] == [3.0, 4.0]
    assert ball["shapes"][0]["type"] == "circle"


def test_stack_pyramid_and_rain_layouts():
    stack = validate_scene(load_example("stack"))["bodies"][1:]
    assert [b["position"] for b in stack] == [[0.0, 0.5 + i] for i in range(10)]
    pyramid = validate_scene(load_example("pyramid"))
    boxes = pyramid["bodies"][1:]
    assert len(boxes) == 55  # 10 + 9 + ... + 1
    assert all(b["shapes"][0]["friction"] == 0.6 for b in pyramid["bodies"])
    assert sorted({b["position"][1] for b in boxes}) == [0.5 + r for r in range(10)]
    rain = validate_scene(load_example("rain"))
    drops = [b for b in rain["bodies"] if b["type"] == "dynamic"]
    assert len(drops) == 100
    # every drop starts above the walls (top y = 10) and inside them (|x| < 5)
    assert all(d["position"][1] - d["shapes"][0]["radius"] > 10.0 for d in drops)
    assert all(abs(d["position"][0]) + d["shapes"][0]["radius"] < 5.0 for d in drops)


def test_pendulum_and_cradle_geometry():
    spec = validate_scene(load_example("pendulum"))
    anchor, bob = spec["bodies"]
    d = np.subtract(bob["position"], anchor["position"])
    assert math.hypot(*d) == pytest.approx(2.0, abs=1e-12)  # 2 m string, rounding 1e-12
    assert math.atan2(d[0], -d[1]) == pytest.approx(math.radians(30), abs=1e-12)
    cradle = validate_scene(load_example("newtons_cradle"))
    frame, *balls = cradle["bodies"]
    assert len(balls) == 5 and all(b["shapes"][0]["restitution"] == 1.0 for b in balls)
    for joint, ball in zip(cradle["joints"], balls, strict=True):
        top = np.add(frame["position"], joint["anchor_a"])
        assert math.hypot(*(np.subtract(ball["position"], top))) == pytest.approx(3.0, abs=1e-11)
    assert balls[0]["position"][0] < -3.0  # the first one pulled out


def test_bullet_incline_spring_buoyancy_hinge():
    bullet = validate_scene(load_example("bullet"))
    wall, ball = bullet["bodies"]
    assert bullet["gravity"] == [0.0, 0.0] and ball["ccd"] is True
    assert wall["shapes"][0]["width"] == 0.1 and ball["shapes"][0]["radius"] == 0.05
    assert ball["velocity"] == [200.0, 0.0]
    incline = validate_scene(load_example("incline"))
    assert incline["bodies"][1]["angle"] == pytest.approx(math.radians(20), abs=1e-15)
    spring = validate_scene(load_example("spring"))
    assert spring["joints"][0]["type"] == "spring"
    buoy = validate_scene(load_example("buoyancy"))
    assert buoy["forces"][0]["fluid_density"] == 1.0 and buoy["forces"][0]["surface_y"] == 0.0
    densities = sorted(s["density"] for b in buoy["bodies"][1:] for s in b["shapes"])
    assert densities == [0.3, 0.3, 0.5, 0.5, 0.8, 0.8]
    hinge = validate_scene(load_example("hinge_motor"))
    assert hinge["joints"][0]["type"] == "pivot" and hinge["joints"][0]["motor"]["max_torque"] > 0


def _world_shapes(spec: dict):
    """(body index, is_static, 'circle', centre, r) or (..., 'poly', vertices) in world frame."""
    out = []
    for i, body in enumerate(spec["bodies"]):
        rot, pos = rotation(body["angle"]), np.array(body["position"])
        for s in body["shapes"]:
            static = body["type"] == "static"
            if s["type"] == "circle":
                out.append((i, static, "circle", pos + rot @ s["offset"], s["radius"]))
            else:
                local = (
                    box_vertices(s["width"], s["height"], s["offset"], s["angle"])
                    if s["type"] == "box"
                    else np.array(s["vertices"])
                )
                out.append((i, static, "poly", local @ rot.T + pos, None))
    return out


def _overlap(a, b) -> float:
    """Penetration depth of two shapes (<= 0: apart or touching): SAT / circle distance."""
    if a[2] == "circle" and b[2] == "circle":
        return a[4] + b[4] - float(np.linalg.norm(a[3] - b[3]))
    if a[2] == "circle":
        a, b = b, a
    if b[2] == "circle":
        v, c, r = a[3], b[3], b[4]
        edges = np.roll(v, -1, axis=0) - v
        # outward normals (e_y, -e_x) for counter-clockwise winding, flipped for clockwise
        normals = np.stack([edges[:, 1], -edges[:, 0]], axis=1) * np.sign(signed_area(v))
        normals /= np.linalg.norm(normals, axis=1)[:, None]
        side = np.einsum("ij,ij->i", c - v, normals)
        if np.all(side <= 0):
            return r - float(np.max(side))
        t = np.clip(np.einsum("ij,ij->i", c - v, edges) / np.einsum("ij,ij->i", edges, edges), 0, 1)
        return r - float(np.min(np.linalg.norm(v + t[:, None] * edges - c, axis=1)))
    depth = np.inf
    for poly in (a[3], b[3]):
        edges = np.roll(poly, -1, axis=0) - poly
        for n in np.stack([edges[:, 1], -edges[:, 0]], axis=1):
            pa, pb = a[3] @ n, b[3] @ n
            depth = min(
                depth, (min(pa.max(), pb.max()) - max(pa.min(), pb.min())) / np.linalg.norm(n)
            )
    return depth


@pytest.mark.parametrize("name", SCENE_NAMES)
def test_example_scene_has_no_initial_overlap(name):
    shapes = _world_shapes(validate_scene(load_example(name)))
    for k, a in enumerate(shapes):
        for b in shapes[k + 1 :]:
            if a[0] == b[0] or (a[1] and b[1]):
                continue  # same body, or two static bodies: never tested for contact
            assert _overlap(a, b) <= 1e-9, (name, a[0], b[0])  # touching allowed, 1e-9 m


def test_overlap_helper_detects_overlap():
    ball = (0, False, "circle", np.array([0.0, 0.45]), 0.5)
    slab = (1, True, "poly", box_vertices(4, 1, (0, -0.5)), None)
    assert _overlap(ball, slab) == pytest.approx(0.05)  # 0.5 - 0.45
    cube = (2, False, "poly", box_vertices(1, 1, (0, 0.4)), None)
    assert _overlap(cube, slab) == pytest.approx(0.1)  # bottom at -0.1


# --- defaults ----------------------------------------------------------------------------------------
def test_defaults_are_filled():
    spec = validate_scene({"bodies": [{"shapes": [{"type": "circle", "radius": 1}]}]})
    assert spec == {
        "version": 1,
        "name": "scene",
        "gravity": [0.0, -9.81],
        "dt": 1.0 / 60.0,
        "settings": {
            "orientation": "complex",
            "integrator": "semi_implicit_euler",
            "broadphase": "sap",
            "solver": "iterative",
            "iterations": 10,
            "penetration": "impulse",
        },
        "bodies": [
            {
                "name": "body0",
                "type": "dynamic",
                "position": [0.0, 0.0],
                "angle": 0.0,
                "velocity": [0.0, 0.0],
                "angular_velocity": 0.0,
                "ccd": False,
                "mass": None,
                "moment": None,
                "force": [0.0, 0.0],
                "torque": 0.0,
                "shapes": [
                    {
                        "type": "circle",
                        "radius": 1.0,
                        "offset": [0.0, 0.0],
                        "density": 1.0,
                        "mass": None,
                        "restitution": 0.0,
                        "friction": 0.5,
                    }
                ],
            }
        ],
        "joints": [],
        "forces": [],
    }
    assert all(isinstance(x, float) for x in spec["gravity"] + [spec["dt"]])


def test_defaults_of_every_joint_force_and_shape():
    spec = validate_scene(BASE)
    pin, pivot, spring = spec["joints"]
    assert pin == {
        "type": "pin",
        "a": "ground",
        "b": "ball",
        "anchor_a": [0.0, 0.0],
        "anchor_b": [0.0, 0.0],
    }
    assert pivot["limits"] is None and pivot["motor"] is None
    assert (
        spring["rest_length"] is None and spring["stiffness"] == 10.0 and spring["damping"] == 0.0
    )
    drag, buoy = spec["forces"]
    assert drag == {"type": "drag", "linear": 0.1, "quadratic": 0.0, "angular": 0.0, "bodies": None}
    assert buoy == {
        "type": "buoyancy", "surface_y": 0.0, "fluid_density": 1.0,
        "linear_drag": 0.0, "angular_drag": 0.0, "bodies": None,
    }  # fmt: skip
    box = spec["bodies"][0]["shapes"][0]
    assert box["offset"] == [0.0, 0.0] and box["angle"] == 0.0 and box["density"] == 1.0
    poly = spec["bodies"][2]["shapes"][0]
    assert poly["vertices"] == [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]
    assert set(poly) == {"type", "vertices", "density", "mass", "restitution", "friction"}


def test_accepted_variants():
    scene = copy.deepcopy(BASE)
    scene["_note"] = "ignored"
    scene["description"] = "ignored too"
    scene["bodies"][1]["comment"] = "ignored"
    scene["bodies"][1]["shapes"][0]["_colour"] = "red"
    scene["bodies"][2]["shapes"][0]["vertices"] = [[0, 0], [0, 1], [1, 0]]  # clockwise is fine
    scene["bodies"].append({"name": "crate", "mass": 2, "moment": 0.5})  # no shapes, mass given
    scene["bodies"].append({"name": "lift", "type": "kinematic"})
    scene["joints"][1].update(limits=[-1, 1], motor={"rate": -2, "max_torque": 5})
    scene["joints"][2].update(rest_length=None, damping=0)
    scene["forces"][0]["bodies"] = ["ball", "tri"]
    scene["bodies"][1]["shapes"][0]["radius"] = np.float64(0.25)  # numpy numbers are numbers
    spec = validate_scene(scene)
    assert "_note" not in spec and "description" not in spec and "comment" not in spec["bodies"][1]
    assert spec["bodies"][2]["shapes"][0]["vertices"] == [[0.0, 0.0], [0.0, 1.0], [1.0, 0.0]]
    assert spec["bodies"][3]["mass"] == 2.0 and spec["bodies"][4]["shapes"] == []
    assert spec["joints"][1]["limits"] == [-1.0, 1.0] and spec["joints"][1]["motor"]["rate"] == -2.0
    assert spec["forces"][0]["bodies"] == ["ball", "tri"]
    assert type(spec["bodies"][1]["shapes"][0]["radius"]) is float


def test_validation_never_mutates_and_shares_nothing():
    scene = copy.deepcopy(BASE)
    scene["bodies"][1]["_private"] = [1, 2]
    before = copy.deepcopy(scene)
    spec = validate_scene(scene)
    assert scene == before
    spec["bodies"][2]["shapes"][0]["vertices"][0][0] = 99.0
    spec["bodies"][1]["position"][0] = 99.0
    assert scene == before


@settings(max_examples=50, deadline=None, derandomize=True)
@given(
    # every number in the documented ranges (positions, radii) survives, bit for bit
    st.floats(min_value=POSITION.lo, max_value=POSITION.hi),
    st.floats(min_value=LENGTH.lo, max_value=LENGTH.hi),
)
def test_numbers_round_trip_bit_identical(x, r):
    scene = {"bodies": [{"position": [x, -x], "shapes": [{"type": "circle", "radius": r}]}]}
    spec = validate_scene(scene)
    again = validate_scene(json.loads(dump_scene(spec)))
    assert again == spec and again["bodies"][0]["position"] == [x, -x]


# --- malformed scenes ------------------------------------------------------------------------------
def _set(*keys_and_value):
    *keys, value = keys_and_value

    def change(scene):
        target = scene
        for key in keys[:-1]:
            target = target[key]
        target[keys[-1]] = value

    return change


def _delete(*keys):
    def change(scene):
        target = scene
        for key in keys[:-1]:
            target = target[key]
        del target[keys[-1]]

    return change


def _both(*changes):
    def change(scene):
        for c in changes:
            c(scene)

    return change


B, J, F = "bodies", "joints", "forces"
NAN, INF = float("nan"), float("inf")
MALFORMED = [
    ("version 2", _set("version", 2), "version", "expected 1, got 2"),
    ("version string", _set("version", "1"), "version", "got '1'"),
    ("version bool", _set("version", True), "version", "got true"),
    ("empty name", _set("name", ""), "name", "non-empty string"),
    ("name number", _set("name", 3), "name", "got 3"),
    ("gravity 1 item", _set("gravity", [0]), "gravity", "got a list of 1 item"),
    ("gravity not list", _set("gravity", 9.81), "gravity", "expected [x, y]"),
    ("gravity string", _set("gravity", [0, "down"]), "gravity[1]", "expected a number, got 'down'"),
    ("gravity bool", _set("gravity", [0, True]), "gravity[1]", "got true"),
    ("gravity NaN", _set("gravity", [NAN, 0]), "gravity[0]", "finite number, got NaN"),
    ("dt zero", _set("dt", 0), "dt", "expected a number > 0, got 0"),
    ("dt negative", _set("dt", -0.01), "dt", "got -0.01"),
    ("dt inf", _set("dt", INF), "dt", "finite number, got Infinity"),
    ("dt null", _set("dt", None), "dt", "got null"),
    ("orientation", _set("settings", {"orientation": "quaternion"}), "settings.orientation",
     "expected one of angle, matrix, complex, got 'quaternion'"),
    ("integrator", _set("settings", {"integrator": "euler"}), "settings.integrator", "got 'euler'"),
    ("broadphase", _set("settings", {"broadphase": "octree"}), "settings.broadphase", "sap"),
    ("solver", _set("settings", {"solver": "pgs"}), "settings.solver", "pairwise, shock, iterative"),
    ("penetration", _set("settings", {"penetration": 3}), "settings.penetration", "got 3"),
    ("iterations 0", _set("settings", {"iterations": 0}), "settings.iterations", "integer in [1, 1000], got 0"),
    ("iterations 1001", _set("settings", {"iterations": 1001}), "settings.iterations", "got 1001"),
    ("iterations float", _set("settings", {"iterations": 2.5}), "settings.iterations", "got 2.5"),
    ("iterations bool", _set("settings", {"iterations": True}), "settings.iterations", "got true"),
    ("unknown setting", _set("settings", {"speed": 2}), "settings.speed", "unknown field"),
    ("settings list", _set("settings", []), "settings", "JSON object"),
    ("unknown top field", _set("gravty", [0, 0]), "gravty", "unknown field (did you mean 'gravity'?)"),
    ("no bodies", _delete(B), "bodies", "required field is missing"),
    ("bodies object", _set(B, {}), "bodies", "expected a list of bodies, got an object"),
    ("body not object", _set(B, 1, 5), "bodies[1]", "expected a body"),
    ("unknown body field", _set(B, 1, "positon", [0, 0]), "bodies[1].positon", "unknown field"),
    ("body type", _set(B, 1, "type", "ghost"), "bodies[1].type", "dynamic, static, kinematic"),
    ("duplicate name", _set(B, 1, "name", "ground"), "bodies[1].name", "duplicate body name 'ground'"),
    ("default name clash", _both(_delete(B, 1, "name"), _set(B, 2, "name", "body1")),
     "bodies[2].name", "duplicate"),
    ("blank name", _set(B, 1, "name", "  "), "bodies[1].name", "non-empty string"),
    ("position 3 items", _set(B, 1, "position", [1, 2, 3]), "bodies[1].position", "got a list of 3 items"),
    ("angle NaN", _set(B, 1, "angle", NAN), "bodies[1].angle", "finite"),
    ("velocity inf", _set(B, 1, "velocity", [0, -INF]), "bodies[1].velocity[1]", "got -Infinity"),
    ("omega string", _set(B, 1, "angular_velocity", "1"), "bodies[1].angular_velocity", "got '1'"),
    ("ccd int", _set(B, 1, "ccd", 1), "bodies[1].ccd", "expected true or false, got 1"),
    ("body mass 0", _set(B, 1, "mass", 0), "bodies[1].mass", "> 0"),
    ("body moment < 0", _set(B, 1, "moment", -1), "bodies[1].moment", "got -1"),
    ("force 1 item", _set(B, 1, "force", [0]), "bodies[1].force", "[x, y]"),
    ("torque bool", _set(B, 1, "torque", False), "bodies[1].torque", "got false"),
    ("dynamic no shapes", _set(B, 1, "shapes", []), "bodies[1].shapes", "at least one shape"),
    ("dynamic mass only", _both(_set(B, 1, "shapes", []), _set(B, 1, "mass", 1)),
     "bodies[1].moment", "required"),
    ("shapes string", _set(B, 1, "shapes", "circle"), "bodies[1].shapes", "expected a list of shapes"),
    ("shape type", _set(B, 1, "shapes", 0, "type", "triangle"), "bodies[1].shapes[0].type", "circle, polygon, box"),
    ("shape no type", _delete(B, 1, "shapes", 0, "type"), "bodies[1].shapes[0].type", "missing"),
    ("radius negative", _set(B, 1, "shapes", 0, "radius", -1), "bodies[1].shapes[0].radius", "> 0, got -1"),
    ("radius zero", _set(B, 1, "shapes", 0, "radius", 0), "bodies[1].shapes[0].radius", "got 0"),
    ("radius missing", _delete(B, 1, "shapes", 0, "radius"), "bodies[1].shapes[0].radius", "missing"),
    ("radius bool", _set(B, 1, "shapes", 0, "radius", True), "bodies[1].shapes[0].radius", "got true"),
    ("radius NaN", _set(B, 1, "shapes", 0, "radius", NAN), "bodies[1].shapes[0].radius", "NaN"),
    ("radius huge int", _set(B, 1, "shapes", 0, "radius", 10**400), "bodies[1].shapes[0].radius", "finite"),
    ("circle width", _set(B, 1, "shapes", 0, "width", 1), "bodies[1].shapes[0].width", "unknown field"),
    ("box width 0", _set(B, 0, "shapes", 0, "width", 0), "bodies[0].shapes[0].width", "> 0"),
    ("box height < 0", _set(B, 0, "shapes", 0, "height", -2), "bodies[0].shapes[0].height", "got -2"),
    ("box angle inf", _set(B, 0, "shapes", 0, "angle", INF), "bodies[0].shapes[0].angle", "finite"),
    ("box radius", _set(B, 0, "shapes", 0, "radius", 1), "bodies[0].shapes[0].radius", "unknown field"),
    ("density 0", _set(B, 1, "shapes", 0, "density", 0), "bodies[1].shapes[0].density", "> 0"),
    ("shape mass < 0", _set(B, 1, "shapes", 0, "mass", -1), "bodies[1].shapes[0].mass", "> 0"),
    ("restitution > 1", _set(B, 1, "shapes", 0, "restitution", 1.5), "bodies[1].shapes[0].restitution", "in [0, 1], got 1.5"),
    ("restitution < 0", _set(B, 1, "shapes", 0, "restitution", -0.1), "bodies[1].shapes[0].restitution", "[0, 1]"),
    ("friction < 0", _set(B, 1, "shapes", 0, "friction", -0.5), "bodies[1].shapes[0].friction", ">= 0, got -0.5"),
    ("offset 1 item", _set(B, 1, "shapes", 0, "offset", [0]), "bodies[1].shapes[0].offset", "[x, y]"),
    ("concave polygon", _set(B, 2, "shapes", 0, "vertices", [[0, 0], [2, 0], [2, 2], [1, 0.5]]),
     "bodies[2].shapes[0].vertices", "not strictly convex"),
    ("collinear polygon", _set(B, 2, "shapes", 0, "vertices", [[0, 0], [1, 0], [2, 0]]),
     "bodies[2].shapes[0].vertices", "degenerate"),
    ("2 vertices", _set(B, 2, "shapes", 0, "vertices", [[0, 0], [1, 0]]),
     "bodies[2].shapes[0].vertices", "at least 3 vertices, got 2"),
    ("no vertices", _set(B, 2, "shapes", 0, "vertices", []), "bodies[2].shapes[0].vertices", "got 0"),
    ("repeated vertex", _set(B, 2, "shapes", 0, "vertices", [[0, 0], [0, 0], [1, 0], [0, 1]]),
     "bodies[2].shapes[0].vertices", "coincide"),
    ("bowtie polygon", _set(B, 2, "shapes", 0, "vertices", [[0, 0], [1, 1], [1, 0], [0, 1]]),
     "bodies[2].shapes[0].vertices", "polygon"),
    ("vertex 1 item", _set(B, 2, "shapes", 0, "vertices", [[0, 0], [1], [0, 1]]),
     "bodies[2].shapes[0].vertices[1]", "[x, y]"),
    ("vertex NaN", _set(B, 2, "shapes", 0, "vertices", [[0, 0], [NAN, 0], [0, 1]]),
     "bodies[2].shapes[0].vertices[1][0]", "NaN"),
    ("vertices missing", _delete(B, 2, "shapes", 0, "vertices"), "bodies[2].shapes[0].vertices", "missing"),
    ("joints string", _set(J, "x"), "joints", "expected a list of joints"),
    ("joint unknown body", _set(J, 0, "b", "x"), "joints[0].b", "unknown body 'x'"),
    ("joint a missing", _delete(J, 0, "a"), "joints[0].a", "required field is missing"),
    ("joint a not string", _set(J, 0, "a", 0), "joints[0].a", "expected a body name, got 0"),
    ("joint a == b", _set(J, 0, "a", "ball"), "joints[0].b", "two different bodies"),
    ("joint both static", _set(B, 1, "type", "static"), "joints[0].b", "at least one dynamic body"),
    ("joint type", _set(J, 0, "type", "weld"), "joints[0].type", "pin, pivot, spring"),
    ("anchor NaN", _set(J, 0, "anchor_a", [0, NAN]), "joints[0].anchor_a[1]", "finite"),
    ("pin limits", _set(J, 0, "limits", [0, 1]), "joints[0].limits", "unknown field"),
    ("limits reversed", _set(J, 1, "limits", [1, -1]), "joints[1].limits", "lo <= hi"),
    ("limits 1 item", _set(J, 1, "limits", [0]), "joints[1].limits", "[lo, hi]"),
    ("motor no torque", _set(J, 1, "motor", {"rate": 1}), "joints[1].motor.max_torque", "missing"),
    ("motor torque 0", _set(J, 1, "motor", {"rate": 1, "max_torque": 0}), "joints[1].motor.max_torque", "> 0"),
    ("motor unknown", _set(J, 1, "motor", {"rate": 1, "max_torque": 1, "speed": 2}), "joints[1].motor.speed", "unknown field"),
    ("stiffness < 0", _set(J, 2, "stiffness", -1), "joints[2].stiffness", ">= 0"),
    ("stiffness missing", _delete(J, 2, "stiffness"), "joints[2].stiffness", "missing"),
    ("damping < 0", _set(J, 2, "damping", -0.1), "joints[2].damping", ">= 0"),
    ("rest length < 0", _set(J, 2, "rest_length", -1), "joints[2].rest_length", ">= 0"),
    ("force type", _set(F, 0, "type", "wind"), "forces[0].type", "drag, buoyancy"),
    ("drag negative", _set(F, 0, "linear", -1), "forces[0].linear", ">= 0"),
    ("force unknown body", _set(F, 0, "bodies", ["ghost"]), "forces[0].bodies[0]", "unknown body 'ghost'"),
    ("force body twice", _set(F, 0, "bodies", ["ball", "ball"]), "forces[0].bodies[1]", "twice"),
    ("fluid density 0", _set(F, 1, "fluid_density", 0), "forces[1].fluid_density", "> 0"),
    ("surface missing", _delete(F, 1, "surface_y"), "forces[1].surface_y", "missing"),
    ("buoyancy quadratic", _set(F, 1, "quadratic", 1), "forces[1].quadratic", "unknown field"),
    ("analytic with joints", _set("settings", {"integrator": "analytic"}), "settings.integrator",
     "'analytic' cannot be used with joints or forces"),
]  # fmt: skip


@pytest.mark.parametrize(
    ("change", "path", "fragment"),
    [pytest.param(c, p, f, id=name) for name, c, p, f in MALFORMED],
)
def test_malformed_scene(change, path, fragment):
    scene = copy.deepcopy(BASE)
    change(scene)
    with pytest.raises(SceneError) as info:
        validate_scene(scene)
    assert info.value.path == path
    assert fragment in info.value.message
    assert str(info.value) == f"{path}: {info.value.message}"
    assert "\n" not in str(info.value)


def test_enough_malformed_cases():
    assert len(MALFORMED) >= 40


def test_analytic_without_joints_or_forces_is_fine():
    scene = {"settings": {"integrator": "analytic"}, "bodies": copy.deepcopy(BASE["bodies"])}
    assert validate_scene(scene)["settings"]["integrator"] == "analytic"
    with pytest.raises(SceneError) as info:
        validate_scene({**scene, "forces": [{"type": "drag"}]})
    assert info.value.path == "settings.integrator"


@pytest.mark.parametrize("document", [[], "scene", 3, None])
def test_top_level_must_be_an_object(document):
    with pytest.raises(SceneError) as info:
        validate_scene(document)
    assert info.value.path == "" and "JSON object" in info.value.message


def test_scene_error_is_a_value_error_and_pickles():
    err = SceneError("bodies[1].shapes[0].radius", "expected a number > 0, got -1")
    assert isinstance(err, ValueError)
    assert str(err) == "bodies[1].shapes[0].radius: expected a number > 0, got -1"
    back = pickle.loads(pickle.dumps(err))
    assert (back.path, back.message) == (err.path, err.message)


# --- files -------------------------------------------------------------------------------------------
def _file_error(tmp_path, content: str | bytes, name: str = "scene.json") -> SceneError:
    path = tmp_path / name
    if isinstance(content, bytes):
        path.write_bytes(content)
    else:
        path.write_text(content)
    with pytest.raises(SceneError) as info:
        read_scene_file(path)
    return info.value


def test_missing_file(tmp_path):
    with pytest.raises(SceneError) as info:
        read_scene_file(tmp_path / "nope.json")
    assert info.value.path == "file" and "no such file" in info.value.message
    with pytest.raises(SceneError) as info:
        read_scene_file(tmp_path)  # a folder
    assert info.value.path == "file" and "folder" in info.value.message


def test_invalid_json_names_line_and_column(tmp_path):
    err = _file_error(tmp_path, '{\n  "bodies": [\n    {"name": "a",}\n  ]\n}')
    assert err.path == "file" and "line 3, column 18" in err.message
    assert _file_error(tmp_path, "").path == "file"
    assert "UTF-8" in _file_error(tmp_path, b'{"name": "\xff"}').message


@pytest.mark.parametrize("literal", ["NaN", "Infinity", "-Infinity"])
def test_nan_and_infinity_literals_are_refused(tmp_path, literal):
    text = '{"bodies": [{"shapes": [{"type": "circle", "radius": RADIUS}]}]}'.replace(
        "RADIUS", literal
    )
    err = _file_error(tmp_path, text)
    assert err.path == "bodies[0].shapes[0].radius"
    assert literal in err.message and "finite" in err.message


def test_top_level_list_in_file(tmp_path):
    err = _file_error(tmp_path, "[1, 2]")
    assert err.path == "" and "got a list of 2 items" in err.message


def test_read_accepts_byte_order_mark(tmp_path):
    path = tmp_path / "bom.json"
    path.write_bytes(b"\xef\xbb\xbf" + json.dumps(BASE).encode())
    assert read_scene_file(path) == BASE


def test_save_scene_round_trip_and_failure(tmp_path):
    out = tmp_path / "saved.json"
    save_scene(BASE, out)
    assert validate_scene(read_scene_file(out)) == validate_scene(BASE)
    assert out.read_text().endswith("}\n")

    class FakeWorld:
        def to_scene(self):
            return copy.deepcopy(BASE)

    save_scene(FakeWorld(), tmp_path / "from_world.json")
    assert read_scene_file(tmp_path / "from_world.json") == read_scene_file(out)
    bad = copy.deepcopy(BASE)
    bad["dt"] = -1
    with pytest.raises(SceneError):
        save_scene(bad, tmp_path / "bad.json")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["from_world.json", "saved.json"]


def test_load_scene_rejects_other_types_and_bad_scenes(tmp_path):
    with pytest.raises(TypeError):
        load_scene(42)
    with pytest.raises(SceneError) as info:
        load_scene({"bodies": [{"positon": [0, 0]}]})
    assert info.value.path == "bodies[0].positon"
    with pytest.raises(SceneError) as info:
        load_scene(tmp_path / "missing.json")
    assert info.value.path == "file"


def test_load_scene_builds_a_world():
    pytest.importorskip("sandbox.build")
    world = load_scene(SCENES / "drop.json")
    assert [b.name for b in world.bodies] == ["ground", "ball"]
    assert world.body("ball").position[1] == pytest.approx(10.0, abs=1e-12)  # placed exactly


# --- atomic writes -----------------------------------------------------------------------------------
def test_atomic_write_leaves_no_file_when_the_block_raises(tmp_path):
    target = tmp_path / "out.csv"
    with pytest.raises(RuntimeError), atomic_write(target) as f:
        f.write("half a file")
        raise RuntimeError("boom")
    assert list(tmp_path.iterdir()) == []


def test_atomic_write_keeps_the_old_file_when_the_block_raises(tmp_path):
    target = tmp_path / "out.txt"
    atomic_write_text(target, "old")
    with pytest.raises(KeyboardInterrupt), atomic_write(target, "wb") as f:
        f.write(b"new")
        raise KeyboardInterrupt
    assert target.read_text() == "old" and list(tmp_path.iterdir()) == [target]


def test_atomic_write_replaces_whole(tmp_path):
    target = tmp_path / "out.bin"
    atomic_write_bytes(target, b"\x00\x01" * 1000)
    atomic_write_bytes(target, b"xyz")
    assert target.read_bytes() == b"xyz"
    with atomic_write(tmp_path / "t.csv", newline="") as f:
        f.write("a,b\r\n")
    assert (tmp_path / "t.csv").read_bytes() == b"a,b\r\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out.bin", "t.csv"]
    with pytest.raises(ValueError):
        with atomic_write(tmp_path / "x", "a"):
            pass
    assert not (tmp_path / "x").exists()
