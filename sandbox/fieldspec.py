"""What one field of the contract is: its type, unit, default, valid range and a one-line doc.

A :class:`Field` is the single description of a value a user gives, in a scene file, on the
command line or through the Python API. The scene-file validator, the JSON Schema
(:mod:`sandbox.schema`), the scene-format reference in the docs, ``--set KEY=VALUE`` and the
checks of :class:`~sandbox.settings.Settings` all read these, so they cannot disagree.

Numbers have two rules, checked in turn, each with its own message:

- a sign rule (``gt=0``: "expected a number > 0"; ``ge=0``: "expected a number >= 0"), the
  physical meaning (a length is positive);
- a range ``[lo, hi]`` in ``unit``: what the engine can simulate with float64 numbers without
  overflowing (positions up to 1e9 m, lengths from 1e-6 m to 1e6 m, ...), so that an absurd value
  is refused with its field path instead of overflowing later.

The named ranges below are shared by every field of the same quantity.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from sandbox.scene_fields import (
    _REQUIRED,
    SceneError,
    _boolean,
    _bound,
    _choice,
    _integer,
    _name,
    _number,
    _show,
    _vector,
)

__all__ = ["REQUIRED", "Field", "Range", "check_value", "format_bound"]


REQUIRED: Any = _REQUIRED  # the default of a field that must be given


@dataclass(frozen=True)
class Range:
    """A closed interval ``[lo, hi]`` of a physical quantity in ``unit``."""

    lo: float
    hi: float
    unit: str = ""


# --- the physical ranges (SI units) ----------------------------------------------------------------
POSITION = Range(-1e9, 1e9, "m")  # world coordinates
LOCAL = Range(-1e6, 1e6, "m")  # body-frame coordinates: offsets, vertices, anchors
LENGTH = Range(1e-6, 1e6, "m")  # radius, width, height
ANGLE = Range(-1e6, 1e6, "rad")
VELOCITY = Range(-1e6, 1e6, "m/s")
ANGULAR_VELOCITY = Range(-1e6, 1e6, "rad/s")
MASS = Range(1e-12, 1e15, "kg")
MOMENT = Range(1e-24, 1e30, "kg m^2")
DENSITY = Range(1e-9, 1e9, "kg/m^2")  # 2D: mass per area
FORCE = Range(-1e15, 1e15, "N")
TORQUE = Range(-1e15, 1e15, "N m")
GRAVITY = Range(-1e4, 1e4, "m/s^2")
TIME_STEP = Range(1e-6, 10.0, "s")
STIFFNESS = Range(0.0, 1e12, "N/m")
DAMPING = Range(0.0, 1e12, "N s/m")
RATIO = Range(0.0, 1.0)
FRICTION = Range(0.0, 100.0)
MIN_AREA = LENGTH.lo**2  # m^2: the smallest polygon area (a LENGTH.lo square)


format_bound = _bound  # ``1``, ``0.005``, ``1e+09``, ``1e-06``


@dataclass(frozen=True)
class Field:
    """One field: ``kind`` is how it is checked, the rest is what users are told.

    ``kind``: ``number`` | ``integer`` | ``vector`` (``[x, y]``, the range applies to each
    component) | ``boolean`` | ``string`` | ``choice`` (one of ``choices``) | a structural kind
    the scene validator knows (``object``, ``list``, ``vertices``, ``limits``, ``body``,
    ``bodies``, ``version``, ``uri``), with ``item`` naming what it holds.
    """

    name: str
    kind: str
    doc: str
    default: Any = REQUIRED
    unit: str = ""
    gt: float | None = None  # sign rule: value > gt
    ge: float | None = None  # sign rule: value >= ge
    lo: float | None = None  # range [lo, hi]
    hi: float | None = None
    nullable: bool = False
    choices: tuple[str, ...] = ()
    item: str = ""

    @property
    def required(self) -> bool:
        return self.default is REQUIRED

    def range_text(self) -> str:
        """The valid values in words, e.g. ``[1e-06, 1e+06] m`` or ``(0, 1e+15] N m``."""
        if self.kind == "choice":
            return " | ".join(self.choices)
        if self.kind == "boolean":
            return "true | false"
        unit = f" {self.unit}" if self.unit else ""
        if self.lo is not None and self.hi is not None:
            left = "(" if self.gt is not None and self.gt >= self.lo else "["
            return f"{left}{format_bound(self.lo)}, {format_bound(self.hi)}]{unit}"
        if self.gt is not None:
            return f"> {format_bound(self.gt)}{unit}"
        if self.ge is not None:
            return f">= {format_bound(self.ge)}{unit}"
        return ""

    def describe_default(self) -> str:
        """The default as JSON text (``required`` when there is none)."""
        import json

        if self.required:
            return "required"
        default = list(self.default) if isinstance(self.default, tuple) else self.default
        return json.dumps(default)


def number(name: str, doc: str, rng: Range, default: Any = REQUIRED, **kw) -> Field:
    """A number field in the range ``rng`` (its unit included)."""
    return Field(name, "number", doc, default, rng.unit, lo=rng.lo, hi=rng.hi, **kw)


def vector(name: str, doc: str, rng: Range, default: Any = REQUIRED, **kw) -> Field:
    """An ``[x, y]`` field, each component in ``rng``."""
    return Field(name, "vector", doc, default, rng.unit, lo=rng.lo, hi=rng.hi, **kw)


def check_value(field: Field, value: Any, path: str) -> Any:
    """Check one value of a simple kind against ``field``; return it normalized.

    Raises :class:`SceneError` naming ``path`` (``None`` is accepted when ``field.nullable``).
    """
    if value is None and field.nullable:
        return None
    kind = field.kind
    if kind == "number":
        return _number(
            value, path, gt=field.gt, ge=field.ge, lo=field.lo, hi=field.hi, unit=field.unit
        )
    if kind == "integer":
        return _integer(value, path, int(field.lo), int(field.hi))
    if kind == "vector":
        return _vector(value, path, lo=field.lo, hi=field.hi, unit=field.unit)
    if kind == "boolean":
        return _boolean(value, path)
    if kind == "string":
        return _name(value, path)
    if kind == "choice":
        return _choice(value, path, field.choices)
    raise SceneError(path, f"cannot check a {kind} field here (got {_show(value)})")
