"""Checking a parsed scene against the format of :mod:`sandbox.scene_spec`.

``validate_scene`` walks the tables of :mod:`sandbox.scene_spec` field by field (type, sign,
range, default) and adds what a table cannot say: body names are unique, joints name two
different bodies of which one moves, a polygon is convex, a dynamic body has shapes or a mass and
moment, ``analytic`` motion has no joints or forces. Every problem is a :class:`SceneError` whose
``path`` names the deepest offending field, e.g. ``bodies[1].shapes[0].radius``.
"""

from __future__ import annotations

from typing import Any

from sandbox.fieldspec import MIN_AREA, Field, check_value, format_bound
from sandbox.geometry import polygon_problem, signed_area
from sandbox.scene_fields import (
    SceneError,
    _get,
    _is_number,
    _kind,
    _list,
    _number,
    _object,
    _show,
    _vector,
)
from sandbox.scene_spec import OBJECTS, SETTINGS, UNIONS, VERSION
from sandbox.settings import SCENE_KEYS

__all__ = ["validate_scene", "validate_object"]

_SCHEMA_KEY = "$schema"  # accepted at the top level (editors use it), not kept


def validate_scene(data: dict) -> dict:
    """Check a parsed scene against the contract; return a new dict with every default filled.

    Never changes ``data``. Raises :class:`SceneError` naming the deepest offending field.
    """
    spec = OBJECTS["scene"]
    top = _object(data, "", spec.what, (*spec.keys(), _SCHEMA_KEY))
    if _SCHEMA_KEY in top and not isinstance(top[_SCHEMA_KEY], str):
        raise SceneError(_SCHEMA_KEY, f"expected a string (a URI), got {_show(top[_SCHEMA_KEY])}")
    ctx: dict = {}
    scene = {}
    for f in spec.fields:
        scene[f.name] = _field(top, "", f, ctx)
        if f.name == "bodies":
            ctx["kinds"] = _body_kinds(scene["bodies"])
    if scene["settings"]["integrator"] == "analytic" and (scene["joints"] or scene["forces"]):
        found = f"{len(scene['joints'])} joint(s) and {len(scene['forces'])} force(s)"
        raise SceneError(
            "settings.integrator", f"'analytic' cannot be used with joints or forces, found {found}"
        )
    return scene


def validate_object(name: str, values: dict, path: str = "") -> dict:
    """Check ``values`` as the object ``name`` of the format (``"body"``, ``"circle"``, ...):
    the same checks and messages as in a scene file, for the Python API. Returns them normalized.
    """
    spec = OBJECTS[name]
    raw = _object(values, path, spec.what, spec.keys())
    out = {f.name: _field(raw, path, f, {}) for f in spec.fields if f.name in raw}
    if name in _CROSS:
        _CROSS[name](out, path)
    return out


# --- one field -----------------------------------------------------------------------------------
def _field(raw: dict, path: str, field: Field, ctx: dict) -> Any:
    if field.kind == "object" and field.name not in raw and field.default == {}:
        raw = {**raw, field.name: {}}  # a missing object is an empty one: its own defaults
    return _get(
        raw, path, field.name, _check, field.default, nullable=field.nullable, field=field, ctx=ctx
    )


def _check(value: Any, path: str, field: Field, ctx: dict) -> Any:
    kind = field.kind
    if kind == "list":
        items = _list(value, path, field.name)
        return [_ITEMS[field.item](item, f"{path}[{i}]", ctx, i) for i, item in enumerate(items)]
    if kind == "object":
        return _OBJECTS[field.item](value, path, ctx)
    if kind in _SPECIAL:
        return _SPECIAL[kind](value, path, field, ctx)
    return check_value(field, value, path)


def _version(value: Any, path: str, field: Field, ctx: dict) -> int:
    if not (_is_number(value) and value == VERSION):
        raise SceneError(path, f"expected {VERSION}, got {_show(value)}")
    return VERSION


def _vertices(value: Any, path: str, field: Field, ctx: dict) -> list[list[float]]:
    """Body-local vertices of a convex polygon, either winding, kept as given."""
    points = _list(value, path, "[x, y] vertices")
    bounds = {"lo": field.lo, "hi": field.hi, "unit": field.unit}
    vertices = [_vector(p, f"{path}[{i}]", **bounds) for i, p in enumerate(points)]
    problem = (
        polygon_problem(vertices) if vertices else "a polygon needs at least 3 vertices, got 0"
    )
    if problem:
        raise SceneError(path, problem)
    area = abs(signed_area(vertices))
    if area < MIN_AREA:
        raise SceneError(
            path, f"expected a polygon of area >= {format_bound(MIN_AREA)} m^2, got {area:.3g}"
        )
    return vertices


def _limits(value: Any, path: str, field: Field, ctx: dict) -> list[float]:
    if not isinstance(value, list | tuple) or len(value) != 2:
        raise SceneError(path, f"expected [lo, hi] (radians) or null, got {_show(value)}")
    bounds = {"lo": field.lo, "hi": field.hi, "unit": field.unit}
    lo, hi = _number(value[0], f"{path}[0]", **bounds), _number(value[1], f"{path}[1]", **bounds)
    if lo > hi:
        raise SceneError(path, f"expected lo <= hi, got [{lo!r}, {hi!r}]")
    return [lo, hi]


def _body_ref(value: Any, path: str, field: Field | None, ctx: dict) -> str:
    if not isinstance(value, str):
        raise SceneError(path, f"expected a body name, got {_show(value)}")
    if value not in ctx["kinds"]:
        raise SceneError(path, f"unknown body {_show(value)}")
    return value


def _body_list(value: Any, path: str, field: Field, ctx: dict) -> list[str]:
    names = _list(value, path, "body names")
    out: list[str] = []
    for i, name in enumerate(names):
        name = _body_ref(name, f"{path}[{i}]", None, ctx)
        if name in out:
            raise SceneError(f"{path}[{i}]", f"body {name!r} is listed twice")
        out.append(name)
    return out


_SPECIAL = {
    "version": _version,
    "vertices": _vertices,
    "limits": _limits,
    "body": _body_ref,
    "bodies": _body_list,
}


# --- objects -------------------------------------------------------------------------------------
def _settings(value: Any, path: str, ctx: dict) -> dict:
    """The six contract keys (defaults filled), then any other setting given, each checked."""
    raw = _object(value, path, SETTINGS.what, SETTINGS.keys())
    out = {}
    for f in SETTINGS.fields:
        if f.name in SCENE_KEYS or f.name in raw:
            out[f.name] = _field(raw, path, f, ctx)
    return out


def _motor(value: Any, path: str, ctx: dict) -> dict:
    spec = OBJECTS["motor"]
    raw = _object(value, path, spec.what, spec.keys())
    return {f.name: _field(raw, path, f, ctx) for f in spec.fields}


def _tagged(value: Any, path: str, ctx: dict, union: str) -> tuple[dict, dict]:
    """(the checked fields, the raw object) of one member of a union (shape, joint, force)."""
    what = OBJECTS[UNIONS[union][0]].what
    if not isinstance(value, dict):
        raise SceneError(path, f"expected {what} (a JSON object), got {_show(value)}")
    spec = OBJECTS[_kind(value, path, UNIONS[union])]
    raw = _object(value, path, what, spec.keys())
    out = {f.name: _field(raw, path, f, ctx) for f in spec.fields}
    if spec.name in _CROSS:
        _CROSS[spec.name](out, path)
    return out, raw


MAX_ASPECT = 1e9  # a box's longer side over its shorter: thinner boxes have no usable area


def _box(box: dict, path: str) -> None:
    if "width" not in box or "height" not in box:
        return
    w, h = box["width"], box["height"]
    if max(w, h) > MAX_ASPECT * min(w, h):
        thin = "width" if w < h else "height"
        other = "height" if thin == "width" else "width"
        raise SceneError(
            f"{path}.{thin}" if path else thin,
            f"expected at least {other} / {format_bound(MAX_ASPECT)}, got {_show(box[thin])} "
            f"({other} {_show(box[other])}): a box this thin has no usable area",
        )


_CROSS = {"box": _box}


def _body(value: Any, path: str, ctx: dict, index: int) -> dict:
    spec = OBJECTS["body"]
    raw = _object(value, path, spec.what, spec.keys())
    body = {}
    for f in spec.fields:
        if f.name == "name" and "name" not in raw:
            body["name"] = f"body{index}"
        else:
            body[f.name] = _field(raw, path, f, ctx)
    if body["type"] == "dynamic" and not body["shapes"]:
        if body["mass"] is None and body["moment"] is None:
            raise SceneError(
                f"{path}.shapes", "a dynamic body needs at least one shape, or both mass and moment"
            )
        for key in ("mass", "moment"):
            if body[key] is None:
                raise SceneError(f"{path}.{key}", "required for a dynamic body without shapes")
    return body


def _shape(value: Any, path: str, ctx: dict, index: int) -> dict:
    return _tagged(value, path, ctx, "shape")[0]


def _joint(value: Any, path: str, ctx: dict, index: int) -> dict:
    joint, _ = _tagged(value, path, ctx, "joint")
    kinds = ctx["kinds"]
    a, b = joint["a"], joint["b"]
    if a == b:
        raise SceneError(f"{path}.b", f"a joint needs two different bodies, got {a!r} twice")
    if "dynamic" not in (kinds[a], kinds[b]):
        found = f"{a!r} is {kinds[a]}, {b!r} is {kinds[b]}"
        raise SceneError(f"{path}.b", f"a joint needs at least one dynamic body, {found}")
    return joint


def _force(value: Any, path: str, ctx: dict, index: int) -> dict:
    return _tagged(value, path, ctx, "force")[0]


def _body_kinds(bodies: list[dict]) -> dict[str, str]:
    kinds: dict[str, str] = {}
    for i, body in enumerate(bodies):
        if body["name"] in kinds:
            first = next(j for j, b in enumerate(bodies) if b["name"] == body["name"])
            raise SceneError(
                f"bodies[{i}].name", f"duplicate body name {body['name']!r} (also bodies[{first}])"
            )
        kinds[body["name"]] = body["type"]
    return kinds


_ITEMS = {"body": _body, "shape": _shape, "joint": _joint, "force": _force}
_OBJECTS = {"settings": _settings, "motor": _motor}
