"""Checking the arguments of the Python API with the scene files' rules and messages.

``World(gravity=-9.81)``, ``Body(velocity=(nan, 0))``, ``Box(-1, 1)`` or
``Circle(0.5, elasticity=0.9)`` raise at the call, naming the argument the way a scene file names
its field (``gravity``, ``velocity[0]``, ``width``), instead of failing at the first step. The
ranges are those of :mod:`sandbox.scene_spec`.
"""

from __future__ import annotations

import difflib
from typing import Any

from sandbox.scene_fields import SceneError, _show
from sandbox.scene_spec import OBJECTS, UNIONS
from sandbox.scene_validate import validate_object
from sandbox.settings import FIELDS as SETTING_FIELDS

__all__ = ["ArgumentError", "check_arguments", "check_world_arguments"]

# words other engines (pymunk, Box2D) use for the same thing
SYNONYMS = {
    "elasticity": "restitution",
    "bounciness": "restitution",
    "bounce": "restitution",
    "e": "restitution",
    "mu": "friction",
    "inertia": "moment",
    "moment_of_inertia": "moment",
    "rotation": "angle",
    "omega": "angular_velocity",
    "angular_speed": "angular_velocity",
    "body_type": "type",
    "center": "offset",
    "centre": "offset",
    "points": "vertices",
    "verts": "vertices",
    "size": "width",
    "bullet": "ccd",
    "timestep": "dt",
    "time_step": "dt",
}


class ArgumentError(SceneError, TypeError):
    """An unknown keyword argument (also a ``TypeError``, as Python's own would be)."""


def did_you_mean(key: str, known: tuple[str, ...]) -> str:
    """`` (did you mean 'x'?)`` for the closest known name, or an empty string."""
    if SYNONYMS.get(key) in known:
        return f" (did you mean {SYNONYMS[key]!r}?)"
    close = difflib.get_close_matches(key, known, n=1)
    return f" (did you mean {close[0]!r}?)" if close else ""


def check_arguments(owner: str, obj: str, values: dict[str, Any]) -> dict[str, Any]:
    """Check keyword ``values`` of ``owner(...)`` (e.g. ``"Circle"``) as the scene object
    ``obj`` (``"circle"``); returns them normalized (floats, ``[x, y]`` lists)."""
    known = OBJECTS[obj].keys()
    if any(obj in members for members in UNIONS.values()):
        known = tuple(k for k in known if k != "type")  # the class itself is the type
    for key in values:
        if key not in known:
            hint = did_you_mean(key, known)
            raise ArgumentError(key, f"{owner}() has no argument {key!r}{hint}")
    plain = {k: _plain(v) for k, v in values.items()}
    return validate_object(obj, plain)


def _plain(value: Any) -> Any:
    """numpy scalars (``np.bool_``, ``np.float64``) as Python values."""
    if getattr(value, "ndim", None) == 0 and hasattr(value, "item"):
        return value.item()
    return value


def check_world_arguments(gravity: Any, dt: Any, name: Any, settings: dict[str, Any]) -> None:
    """Raise :class:`SceneError` when ``World(gravity, dt, name, **settings)`` is not valid."""
    validate_object("scene", {"gravity": gravity, "dt": dt})
    if not isinstance(name, str):
        raise SceneError("name", f"expected a string, got {_show(name)}")
    for key, value in settings.items():
        if key not in SETTING_FIELDS:
            hint = did_you_mean(key, tuple(SETTING_FIELDS))
            raise ArgumentError(key, f"World() has no argument or setting {key!r}{hint}")
        validate_object("settings", {key: value}, "settings")


def check_body_name(name: Any, type_: Any) -> None:
    """A body's name is a string; ``Body(1, 10)`` is pymunk's ``Body(mass, moment)``."""
    if isinstance(name, str):
        return
    hint = ""
    if isinstance(name, int | float) and not isinstance(name, bool):
        hint = (
            ": Body's first argument is its name; pymunk's Body(mass, moment) is written "
            f"Body('name', mass={name!r}"
            + (f", moment={type_!r})" if not isinstance(type_, str) else ")")
            + " here, or give the body shapes with a density"
        )
    raise SceneError("name", f"expected a string, got {_show(name)}{hint}")


def not_a_body_hint(value: Any, owner: str) -> None:
    """pymunk's ``Circle(body, radius)``: shapes here are made first, then added to a body."""
    if type(value).__name__ == "Body":
        raise ArgumentError(
            "body",
            f"{owner}() takes no body: make the shape, then body.add_shape({owner}(...))",
        )
