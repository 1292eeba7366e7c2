"""Scene files (JSON, version 1): read, validate, save.

``validate_scene`` checks every field of the scene-file contract and returns a new, normalized dict
with every default filled in; ``sandbox.build`` turns that dict into a ``World``. Every problem is a
:class:`SceneError` whose ``path`` names the offending field, e.g. ``bodies[1].shapes[0].radius``.
Units: SI, radians, y up, counter-clockwise positive.
"""

from __future__ import annotations

import json
import os
from typing import TYPE_CHECKING, Any

from sandbox.atomic import atomic_write_text
from sandbox.geometry import polygon_problem
from sandbox.scene_fields import (
    SceneError,
    _boolean,
    _choice,
    _get,
    _integer,
    _is_number,
    _key,
    _kind,
    _list,
    _name,
    _number,
    _object,
    _show,
    _vector,
)
from sandbox.settings import CHOICES

if TYPE_CHECKING:
    from sandbox.world import World

__all__ = [
    "SceneError",
    "dump_scene",
    "load_scene",
    "read_scene_file",
    "save_scene",
    "validate_scene",
]

VERSION = 1
DEFAULT_NAME = "scene"
DEFAULT_GRAVITY = (0.0, -9.81)
DEFAULT_DT = 1.0 / 60.0
DEFAULT_SETTINGS = {
    "orientation": "complex",
    "integrator": "semi_implicit_euler",
    "broadphase": "sap",
    "solver": "iterative",
    "iterations": 10,
    "penetration": "impulse",
}
MAX_ITERATIONS = 1000
BODY_TYPES = ("dynamic", "static", "kinematic")
SHAPE_TYPES = ("circle", "polygon", "box")
JOINT_TYPES = ("pin", "pivot", "spring")
FORCE_TYPES = ("drag", "buoyancy", "constant")

_TOP_KEYS = ("version", "name", "gravity", "dt", "settings", "bodies", "joints", "forces")
_BODY_KEYS = (
    "name", "type", "position", "angle", "velocity", "angular_velocity", "ccd",
    "mass", "moment", "force", "torque", "shapes",
)  # fmt: skip
_MATERIAL_KEYS = ("density", "mass", "restitution", "friction")
_SHAPE_KEYS = {
    "circle": ("type", "radius", "offset", *_MATERIAL_KEYS),
    "polygon": ("type", "vertices", *_MATERIAL_KEYS),
    "box": ("type", "width", "height", "offset", "angle", *_MATERIAL_KEYS),
}
_ANCHORS = ("type", "a", "b", "anchor_a", "anchor_b")
_JOINT_KEYS = {
    "pin": _ANCHORS,
    "pivot": (*_ANCHORS, "limits", "motor"),
    "spring": (*_ANCHORS, "rest_length", "stiffness", "damping"),
}
_FORCE_KEYS = {
    "drag": ("type", "linear", "quadratic", "angular", "bodies"),
    "buoyancy": ("type", "surface_y", "fluid_density", "linear_drag", "angular_drag", "bodies"),
    "constant": ("type", "force", "torque", "point", "bodies"),
}


# --- reading -------------------------------------------------------------------------------------
class _Constant:
    """Stands in for a NaN / Infinity literal until its field path is known."""

    def __init__(self, text: str):
        self.text = text


def read_scene_file(path: str | os.PathLike) -> dict:
    """Parse a scene file (standard ``json``; NaN and Infinity literals are refused)."""
    name = os.fspath(path)
    try:
        with open(name, encoding="utf-8-sig") as f:
            text = f.read()
    except FileNotFoundError:
        raise SceneError("file", f"cannot read {name!r}: no such file") from None
    except IsADirectoryError:
        raise SceneError("file", f"cannot read {name!r}: it is a folder") from None
    except PermissionError:
        raise SceneError("file", f"cannot read {name!r}: permission denied") from None
    except UnicodeDecodeError as e:
        raise SceneError("file", f"cannot read {name!r}: not UTF-8 text (byte {e.start})") from None
    except OSError as e:
        raise SceneError("file", f"cannot read {name!r}: {e.strerror or e}") from None
    try:
        data = json.loads(text, parse_constant=_Constant)
    except json.JSONDecodeError as e:
        where = f"line {e.lineno}, column {e.colno}"
        raise SceneError("file", f"invalid JSON in {name!r} at {where}: {e.msg}") from None
    except RecursionError:
        raise SceneError("file", f"invalid JSON in {name!r}: nested too deeply") from None
    _refuse_constants(data, "")
    if not isinstance(data, dict):
        raise SceneError("", f"expected a JSON object at the top level, got {_show(data)}")
    return data


def _refuse_constants(value: Any, path: str) -> None:
    if isinstance(value, _Constant):
        raise SceneError(path, f"expected a finite number, got {value.text} (not allowed in JSON)")
    if isinstance(value, dict):
        for key, item in value.items():
            _refuse_constants(item, _key(path, key))
    elif isinstance(value, list):
        for i, item in enumerate(value):
            _refuse_constants(item, f"{path}[{i}]")


# --- checking the document -----------------------------------------------------------------------
def validate_scene(data: dict) -> dict:
    """Check a parsed scene against the contract; return a new dict with every default filled.

    Never changes ``data``. Raises :class:`SceneError` naming the deepest offending field.
    """
    top = _object(data, "", "a scene", _TOP_KEYS)
    if "version" in top and not (_is_number(top["version"]) and top["version"] == VERSION):
        raise SceneError("version", f"expected {VERSION}, got {_show(top['version'])}")
    scene: dict = {"version": VERSION}
    scene["name"] = _get(top, "", "name", _name, DEFAULT_NAME)
    scene["gravity"] = _get(top, "", "gravity", _vector, DEFAULT_GRAVITY)
    scene["dt"] = _get(top, "", "dt", _number, DEFAULT_DT, gt=0.0)
    scene["settings"] = _settings(top.get("settings", {}))
    raw_bodies = _get(top, "", "bodies", _list, what="bodies")
    scene["bodies"] = [_body(b, f"bodies[{i}]", i) for i, b in enumerate(raw_bodies)]
    kinds: dict[str, str] = {}
    for i, body in enumerate(scene["bodies"]):
        if body["name"] in kinds:
            first = next(j for j, b in enumerate(scene["bodies"]) if b["name"] == body["name"])
            raise SceneError(
                f"bodies[{i}].name", f"duplicate body name {body['name']!r} (also bodies[{first}])"
            )
        kinds[body["name"]] = body["type"]
    joints = _get(top, "", "joints", _list, (), what="joints")
    scene["joints"] = [_joint(j, f"joints[{i}]", kinds) for i, j in enumerate(joints)]
    forces = _get(top, "", "forces", _list, (), what="forces")
    scene["forces"] = [_force(f, f"forces[{i}]", kinds) for i, f in enumerate(forces)]
    if scene["settings"]["integrator"] == "analytic" and (scene["joints"] or scene["forces"]):
        found = f"{len(scene['joints'])} joint(s) and {len(scene['forces'])} force(s)"
        raise SceneError(
            "settings.integrator", f"'analytic' cannot be used with joints or forces, found {found}"
        )
    return scene


def _settings(value: Any) -> dict:
    raw = _object(value, "settings", "settings", tuple(DEFAULT_SETTINGS))
    out = {}
    for key, default in DEFAULT_SETTINGS.items():
        if key == "iterations":
            out[key] = _get(raw, "settings", key, _integer, default, lo=1, hi=MAX_ITERATIONS)
        else:
            out[key] = _get(raw, "settings", key, _choice, default, options=CHOICES[key])
    return out


def _body(value: Any, path: str, index: int) -> dict:
    raw = _object(value, path, "a body", _BODY_KEYS)
    body: dict = {"name": _get(raw, path, "name", _name, f"body{index}")}
    body["type"] = _get(raw, path, "type", _choice, "dynamic", options=BODY_TYPES)
    body["position"] = _get(raw, path, "position", _vector, (0.0, 0.0))
    body["angle"] = _get(raw, path, "angle", _number, 0.0)
    body["velocity"] = _get(raw, path, "velocity", _vector, (0.0, 0.0))
    body["angular_velocity"] = _get(raw, path, "angular_velocity", _number, 0.0)
    body["ccd"] = _get(raw, path, "ccd", _boolean, False)
    body["mass"] = _get(raw, path, "mass", _number, None, nullable=True, gt=0.0)
    body["moment"] = _get(raw, path, "moment", _number, None, nullable=True, gt=0.0)
    body["force"] = _get(raw, path, "force", _vector, (0.0, 0.0))
    body["torque"] = _get(raw, path, "torque", _number, 0.0)
    shapes = _get(raw, path, "shapes", _list, (), what="shapes")
    body["shapes"] = [_shape(s, f"{path}.shapes[{i}]") for i, s in enumerate(shapes)]
    if body["type"] == "dynamic" and not body["shapes"]:
        if body["mass"] is None and body["moment"] is None:
            raise SceneError(
                f"{path}.shapes", "a dynamic body needs at least one shape, or both mass and moment"
            )
        for key in ("mass", "moment"):
            if body[key] is None:
                raise SceneError(f"{path}.{key}", "required for a dynamic body without shapes")
    return body


def _shape(value: Any, path: str) -> dict:
    if not isinstance(value, dict):
        raise SceneError(path, f"expected a shape (a JSON object), got {_show(value)}")
    kind = _kind(value, path, SHAPE_TYPES)
    raw = _object(value, path, "a shape", _SHAPE_KEYS[kind])
    shape: dict = {"type": kind}
    if kind == "circle":
        shape["radius"] = _get(raw, path, "radius", _number, gt=0.0)
        shape["offset"] = _get(raw, path, "offset", _vector, (0.0, 0.0))
    elif kind == "box":
        shape["width"] = _get(raw, path, "width", _number, gt=0.0)
        shape["height"] = _get(raw, path, "height", _number, gt=0.0)
        shape["offset"] = _get(raw, path, "offset", _vector, (0.0, 0.0))
        shape["angle"] = _get(raw, path, "angle", _number, 0.0)
    else:
        shape["vertices"] = _get(raw, path, "vertices", _vertices)
    shape["density"] = _get(raw, path, "density", _number, 1.0, gt=0.0)
    shape["mass"] = _get(raw, path, "mass", _number, None, nullable=True, gt=0.0)
    shape["restitution"] = _get(raw, path, "restitution", _number, 0.0, ge=0.0, le=1.0)
    shape["friction"] = _get(raw, path, "friction", _number, 0.5, ge=0.0)
    return shape


def _vertices(value: Any, path: str) -> list[list[float]]:
    """Body-local vertices of a convex polygon, either winding, kept as given."""
    points = _list(value, path, "[x, y] vertices")
    vertices = [_vector(p, f"{path}[{i}]") for i, p in enumerate(points)]
    problem = (
        polygon_problem(vertices) if vertices else "a polygon needs at least 3 vertices, got 0"
    )
    if problem:
        raise SceneError(path, problem)
    return vertices


def _body_ref(value: Any, path: str, kinds: dict[str, str]) -> str:
    if not isinstance(value, str):
        raise SceneError(path, f"expected a body name, got {_show(value)}")
    if value not in kinds:
        raise SceneError(path, f"unknown body {_show(value)}")
    return value


def _joint(value: Any, path: str, kinds: dict[str, str]) -> dict:
    if not isinstance(value, dict):
        raise SceneError(path, f"expected a joint (a JSON object), got {_show(value)}")
    kind = _kind(value, path, JOINT_TYPES)
    raw = _object(value, path, "a joint", _JOINT_KEYS[kind])
    joint: dict = {"type": kind}
    joint["a"] = _get(raw, path, "a", _body_ref, kinds=kinds)
    joint["b"] = _get(raw, path, "b", _body_ref, kinds=kinds)
    if joint["a"] == joint["b"]:
        raise SceneError(
            f"{path}.b", f"a joint needs two different bodies, got {joint['a']!r} twice"
        )
    if "dynamic" not in (kinds[joint["a"]], kinds[joint["b"]]):
        found = f"{joint['a']!r} is {kinds[joint['a']]}, {joint['b']!r} is {kinds[joint['b']]}"
        raise SceneError(f"{path}.b", f"a joint needs at least one dynamic body, {found}")
    joint["anchor_a"] = _get(raw, path, "anchor_a", _vector, (0.0, 0.0))
    joint["anchor_b"] = _get(raw, path, "anchor_b", _vector, (0.0, 0.0))
    if kind == "pivot":
        joint["limits"] = _get(raw, path, "limits", _limits, None, nullable=True)
        joint["motor"] = _get(raw, path, "motor", _motor, None, nullable=True)
    elif kind == "spring":
        joint["rest_length"] = _get(raw, path, "rest_length", _number, None, nullable=True, ge=0.0)
        joint["stiffness"] = _get(raw, path, "stiffness", _number, ge=0.0)
        joint["damping"] = _get(raw, path, "damping", _number, 0.0, ge=0.0)
    return joint


def _limits(value: Any, path: str) -> list[float]:
    if not isinstance(value, list | tuple) or len(value) != 2:
        raise SceneError(path, f"expected [lo, hi] (radians) or null, got {_show(value)}")
    lo, hi = _number(value[0], f"{path}[0]"), _number(value[1], f"{path}[1]")
    if lo > hi:
        raise SceneError(path, f"expected lo <= hi, got [{lo!r}, {hi!r}]")
    return [lo, hi]


def _motor(value: Any, path: str) -> dict:
    raw = _object(value, path, "a motor", ("rate", "max_torque"))
    return {
        "rate": _get(raw, path, "rate", _number),
        "max_torque": _get(raw, path, "max_torque", _number, gt=0.0),
    }


def _force(value: Any, path: str, kinds: dict[str, str]) -> dict:
    if not isinstance(value, dict):
        raise SceneError(path, f"expected a force (a JSON object), got {_show(value)}")
    kind = _kind(value, path, FORCE_TYPES)
    raw = _object(value, path, "a force", _FORCE_KEYS[kind])
    force: dict = {"type": kind}
    if kind == "drag":
        for key in ("linear", "quadratic", "angular"):
            force[key] = _get(raw, path, key, _number, 0.0, ge=0.0)
    elif kind == "constant":  # extension: a fixed force (N) at a body-frame point, a torque (N m)
        force["force"] = _get(raw, path, "force", _vector, [0.0, 0.0])
        force["torque"] = _get(raw, path, "torque", _number, 0.0)
        force["point"] = _get(raw, path, "point", _vector, None, nullable=True)
    else:
        force["surface_y"] = _get(raw, path, "surface_y", _number)
        force["fluid_density"] = _get(raw, path, "fluid_density", _number, gt=0.0)
        force["linear_drag"] = _get(raw, path, "linear_drag", _number, 0.0, ge=0.0)
        force["angular_drag"] = _get(raw, path, "angular_drag", _number, 0.0, ge=0.0)
    force["bodies"] = _get(raw, path, "bodies", _body_list, None, nullable=True, kinds=kinds)
    return force


def _body_list(value: Any, path: str, kinds: dict[str, str]) -> list[str]:
    names = _list(value, path, "body names")
    out: list[str] = []
    for i, name in enumerate(names):
        name = _body_ref(name, f"{path}[{i}]", kinds)
        if name in out:
            raise SceneError(f"{path}[{i}]", f"body {name!r} is listed twice")
        out.append(name)
    return out


# --- loading and saving --------------------------------------------------------------------------
def load_scene(source: str | os.PathLike | dict) -> World:
    """Build a ``World`` from a scene file path or an already-parsed scene dict.

    A name with no such file in the working folder (``"drop"``) loads the bundled example scene.
    """
    if isinstance(source, dict):
        spec = validate_scene(source)
    elif isinstance(source, str | os.PathLike):
        from sandbox.bundled import resolve_scene

        spec = validate_scene(read_scene_file(resolve_scene(source)[0]))
    else:
        raise TypeError(f"load_scene: expected a path or a dict, got {type(source).__name__}")
    from sandbox.build import build_world

    return build_world(spec)


def _as_spec(scene: Any) -> dict:
    if hasattr(scene, "to_scene") and not isinstance(scene, dict):
        scene = scene.to_scene()
    return validate_scene(scene)


def dump_scene(spec: Any, *, validate: bool = True) -> str:
    """JSON text of a scene (validated and normalized first unless ``validate=False``).

    ``spec`` is a scene dict or an object with a ``to_scene()`` method (e.g. a ``World``).
    Short lists and objects stay on one line; the text has no trailing newline.
    """
    data = _as_spec(spec) if validate else spec
    return _pretty(data, 0, 0, top=True)


def save_scene(scene: Any, path: str | os.PathLike) -> None:
    """Validate ``scene`` (a dict, or an object with ``to_scene()``) and write it atomically."""
    atomic_write_text(path, dump_scene(scene) + "\n")


_WIDTH = 100


def _pretty(value: Any, indent: int, column: int, top: bool = False) -> str:
    """JSON with one-line containers whenever they fit in ``_WIDTH`` columns."""
    flat = json.dumps(value, allow_nan=False, separators=(", ", ": "))
    if (
        not isinstance(value, dict | list)
        or not value
        or (not top and column + len(flat) <= _WIDTH)
    ):
        return flat
    pad = " " * (indent + 2)
    if isinstance(value, dict):
        items = []
        for key, item in value.items():
            head = f"{pad}{json.dumps(str(key))}: "
            items.append(head + _pretty(item, indent + 2, len(head) + 1))
        return "{\n" + ",\n".join(items) + "\n" + " " * indent + "}"
    items = [pad + _pretty(item, indent + 2, indent + 3) for item in value]
    return "[\n" + ",\n".join(items) + "\n" + " " * indent + "]"
