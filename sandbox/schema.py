"""A JSON Schema (draft 2020-12) of scene files, generated from :mod:`sandbox.scene_spec`.

``sandbox schema`` prints it; the package ships it as ``sandbox/scene.schema.json`` (a test keeps
the file equal to :func:`scene_schema`). Point an editor at it with a top-level
``"$schema": "<path or URL of scene.schema.json>"`` for completion and checking as you type.

The schema says what a schema can: types, required keys, unknown keys, choices, ranges, list
lengths. The validator checks more (unique body names, joints naming existing bodies, convex
polygons, ``analytic`` without joints or forces); ``validate_scene`` is the authority.
"""

from __future__ import annotations

import json
from importlib import resources
from typing import Any

from sandbox.fieldspec import Field
from sandbox.scene_spec import OBJECTS, UNIONS, VERSION
from sandbox.settings import SCENE_KEYS

__all__ = ["SCHEMA_FILE", "scene_schema", "schema_text", "shipped_schema_text"]

SCHEMA_FILE = "scene.schema.json"
_IGNORED = {"^_": {}, "^(description|comment)$": {}}  # keys every object accepts and ignores


def _number(field: Field) -> dict:
    out: dict[str, Any] = {"type": "number"}
    if field.lo is not None:
        if field.gt is not None and field.gt >= field.lo:
            out["exclusiveMinimum"] = field.gt
        else:
            out["minimum"] = field.lo
    elif field.gt is not None:
        out["exclusiveMinimum"] = field.gt
    elif field.ge is not None:
        out["minimum"] = field.ge
    if field.hi is not None:
        out["maximum"] = field.hi
    return out


def _pair(item: dict) -> dict:
    return {"type": "array", "items": item, "minItems": 2, "maxItems": 2}


def _value(field: Field) -> dict:
    """The schema of one field's value (without its doc)."""
    kind = field.kind
    if kind == "number":
        out = _number(field)
    elif kind == "integer":
        out = {"type": "integer", "minimum": int(field.lo), "maximum": int(field.hi)}
    elif kind in ("vector", "limits"):
        out = _pair(_number(field))
    elif kind == "vertices":
        out = {"type": "array", "items": _pair(_number(field)), "minItems": 3}
    elif kind == "boolean":
        out = {"type": "boolean"}
    elif kind in ("string", "body"):
        out = {"type": "string", "minLength": 1, "pattern": r"\S"}
    elif kind == "bodies":
        out = {"type": "array", "items": {"type": "string", "minLength": 1}, "uniqueItems": True}
    elif kind == "choice":
        out = {"enum": list(field.choices)}
    elif kind == "version":
        out = {"const": VERSION}
    elif kind == "object":
        out = {"$ref": f"#/$defs/{field.item}"}
    elif kind == "list":
        out = {"type": "array", "items": {"$ref": f"#/$defs/{field.item}"}}
    else:  # pragma: no cover - a new kind must be taught here
        raise ValueError(f"no schema for field kind {kind!r}")
    if field.nullable:
        out = {"anyOf": [out, {"type": "null"}]}
    return out


def _property(field: Field) -> dict:
    unit = f" ({field.unit})" if field.unit else ""
    out = {"description": f"{field.doc}{unit}", **_value(field)}
    if not field.required and field.kind not in ("object", "list") and field.name != "name":
        default = field.default
        out["default"] = list(default) if isinstance(default, tuple) else default
    return out


def _object(name: str, tag: str | None = None) -> dict:
    spec = OBJECTS[name]
    props = {}
    for f in spec.fields:
        props[f.name] = (
            {"const": tag, "description": "the kind"}
            if f.name == "type" and tag
            else (_property(f))
        )
    required = [f.name for f in spec.fields if f.required]
    out = {
        "description": spec.doc,
        "type": "object",
        "properties": props,
        "patternProperties": _IGNORED,
        "additionalProperties": False,
    }
    if required:
        out["required"] = required
    return out


def scene_schema() -> dict:
    """The JSON Schema of a scene file (a dict ready for ``json.dumps``)."""
    defs: dict[str, Any] = {}
    for name in OBJECTS:
        if name == "scene":
            continue
        member_of = [u for u, members in UNIONS.items() if name in members]
        defs[name] = _object(name, tag=name if member_of else None)
    for union, members in UNIONS.items():
        defs[union] = {
            "description": f"one of: {', '.join(members)} (by its type)",
            "oneOf": [{"$ref": f"#/$defs/{m}"} for m in members],
        }
    settings = defs["settings"]
    settings["description"] += f"; always written: {', '.join(SCENE_KEYS)}"
    top = _object("scene")
    top["properties"] = {
        "$schema": {"type": "string", "description": "the schema an editor checks this file with"},
        **top["properties"],
    }
    return {
        "$schema": "https://json-schema.org/draft/2020-12/schema",
        "title": "physics-sandbox scene file (version 1)",
        **top,
        "$defs": defs,
    }


def schema_text() -> str:
    """The schema as the JSON text ``sandbox schema`` prints (2-space indent, newline at end)."""
    return json.dumps(scene_schema(), indent=2, ensure_ascii=False) + "\n"


def shipped_schema_text() -> str:
    """The text of the ``scene.schema.json`` file shipped in the package."""
    return resources.files("sandbox").joinpath(SCHEMA_FILE).read_text(encoding="utf-8")
