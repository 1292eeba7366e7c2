"""The JSON Schema of scene files agrees with the validator: every bundled scene is valid, and the
malformed scenes of the test suite are rejected wherever a schema can express the rule."""

from __future__ import annotations

import copy
import json
from pathlib import Path

import jsonschema
import pytest
from test_ranges import FINDINGS
from test_scene import BASE, MALFORMED

from sandbox.cli import main
from sandbox.scene import SceneError, validate_scene
from sandbox.schema import scene_schema

ROOT = Path(__file__).resolve().parent.parent
SCENES = sorted((ROOT / "scenes").glob("*.json"))

# rules a JSON Schema cannot state: they need the other bodies, geometry or a cross-field check
NOT_EXPRESSIBLE = {
    "duplicate name",  # unique body names across objects
    "default name clash",
    "joint unknown body",  # a name must refer to a body of the scene
    "joint a == b",
    "joint both static",
    "force unknown body",
    "concave polygon",  # convexity and area are geometry
    "collinear polygon",
    "repeated vertex",
    "bowtie polygon",
    "dynamic no shapes",  # shapes, or mass and moment, depending on the body type
    "dynamic mass only",
    "analytic with joints",  # a setting against the joints list
    "limits reversed",  # lo <= hi compares two items of one list
}


@pytest.fixture(scope="module")
def validator():
    schema = scene_schema()
    jsonschema.Draft202012Validator.check_schema(schema)
    return jsonschema.Draft202012Validator(schema)


@pytest.fixture(scope="module")
def printed_schema():
    """What ``sandbox schema`` prints, parsed."""
    import contextlib
    import io

    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        assert main(["schema"]) == 0
    return json.loads(out.getvalue())


@pytest.mark.parametrize("path", SCENES, ids=[p.stem for p in SCENES])
def test_every_bundled_scene_is_valid(printed_schema, path):
    scene = json.loads(path.read_text())
    jsonschema.validate(scene, printed_schema, cls=jsonschema.Draft202012Validator)
    # the normalized form (every default filled) and a "$schema" key are valid too
    jsonschema.validate(
        {"$schema": "scene.schema.json", **validate_scene(scene)},
        printed_schema,
        cls=jsonschema.Draft202012Validator,
    )


def test_schema_key_is_accepted_by_the_validator():
    spec = validate_scene({"$schema": "scene.schema.json", **BASE})
    assert "$schema" not in spec
    with pytest.raises(SceneError, match=r"\$schema: expected a string"):
        validate_scene({"$schema": 3, **BASE})


@pytest.mark.parametrize(
    ("name", "change"), [(name, change) for name, change, _, _ in MALFORMED], ids=lambda x: x
)
def test_malformed_scenes_are_rejected(validator, name, change):
    scene = copy.deepcopy(BASE)
    change(scene)
    try:
        json.dumps(scene, allow_nan=False)
    except ValueError:
        pytest.skip("NaN and Infinity cannot be written in JSON: the parser refuses them")
    with pytest.raises(SceneError):
        validate_scene(scene)
    errors = list(validator.iter_errors(scene))
    if name in NOT_EXPRESSIBLE:
        return
    assert errors, f"the schema accepts {name!r}"


@pytest.mark.parametrize(("scene", "path", "fragment"), FINDINGS)
def test_out_of_range_numbers_are_rejected(validator, scene, path, fragment):
    if "vertices" in path or "thin" in fragment:
        pytest.skip("polygon area and box aspect are geometry, not a schema rule")
    assert list(validator.iter_errors(scene))


def test_the_enough_cases_are_expressible():
    expressible = [m for m in MALFORMED if m[0] not in NOT_EXPRESSIBLE]
    assert len(expressible) >= 60  # most of the rules are the schema's too
