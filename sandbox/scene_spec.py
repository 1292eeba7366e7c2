"""The scene-file format (JSON, version 1) as data: every object, every field, its type, unit,
default, valid range and a one-line doc.

:mod:`sandbox.scene` validates against these tables, :mod:`sandbox.schema` turns them into a JSON
Schema and the reference docs print them, so the three cannot drift apart. The settings object is
:class:`sandbox.settings.Settings`'s own fields. SI units, radians, y up, counter-clockwise.
"""

from __future__ import annotations

from dataclasses import dataclass

import sandbox.fieldspec as fs
from sandbox.fieldspec import REQUIRED, Field, Range, number, vector
from sandbox.settings import Settings

__all__ = ["OBJECTS", "UNIONS", "ObjectSpec", "every_field"]

VERSION = 1
BODY_TYPES = ("dynamic", "static", "kinematic")


@dataclass(frozen=True)
class ObjectSpec:
    """A JSON object of the format: ``name`` (``body``, ``circle``, ...), how errors call it
    (``what``: "a body"), a one-line ``doc`` and its ``fields`` in the order they are written."""

    name: str
    what: str
    doc: str
    fields: tuple[Field, ...]

    def keys(self) -> tuple[str, ...]:
        """The field names, in order."""
        return tuple(f.name for f in self.fields)

    def field(self, name: str) -> Field:
        """The field called ``name`` (KeyError if none)."""
        for f in self.fields:
            if f.name == name:
                return f
        raise KeyError(name)


def _positive(name: str, doc: str, rng: Range, default=REQUIRED, **kw) -> Field:
    return number(name, doc, rng, default, gt=0.0, **kw)


def _nonneg(name: str, doc: str, rng: Range, default=REQUIRED, **kw) -> Field:
    return number(name, doc, rng, default, ge=0.0, **kw)


def _tag(options: tuple[str, ...], doc: str) -> Field:
    return Field("type", "choice", doc, REQUIRED, choices=options)


SCENE = ObjectSpec(
    "scene",
    "a scene",
    "the whole file; every key but bodies is optional",
    (
        Field("version", "version", "format version; only 1 exists", VERSION),
        Field("name", "string", "the scene's name (titles, file names)", "scene"),
        vector("gravity", "acceleration of gravity", fs.GRAVITY, (0.0, -9.81)),
        _positive("dt", "time step", fs.TIME_STEP, 1.0 / 60.0),
        Field(
            "settings",
            "object",
            "world settings (strategies and solver switches)",
            {},
            item="settings",
        ),
        Field("bodies", "list", "the rigid bodies, in order", REQUIRED, item="body"),
        Field("joints", "list", "joints between two bodies", (), item="joint"),
        Field("forces", "list", "force generators (drag, buoyancy, constant)", (), item="force"),
    ),
)

SETTINGS = ObjectSpec(
    "settings",
    "settings",
    "world settings; the first six always appear in a saved scene, the rest when not default",
    Settings.fields(),
)

BODY = ObjectSpec(
    "body",
    "a body",
    "a rigid body; position and angle place its origin, shapes are in that frame",
    (
        Field("name", "string", "unique name (default body<i>, i its index)", "body<i>"),
        Field("type", "choice", "how it moves", "dynamic", choices=BODY_TYPES),
        vector("position", "world position of the body origin", fs.POSITION, (0.0, 0.0)),
        number("angle", "orientation, counter-clockwise", fs.ANGLE, 0.0),
        vector("velocity", "velocity of the centre of mass", fs.VELOCITY, (0.0, 0.0)),
        number("angular_velocity", "counter-clockwise", fs.ANGULAR_VELOCITY, 0.0),
        Field("ccd", "boolean", "continuous collision for this body (no tunnelling)", False),
        _positive(
            "mass",
            "overrides the shapes' mass (null: from the shapes)",
            fs.MASS,
            None,
            nullable=True,
        ),
        _positive(
            "moment",
            "moment of inertia about the centre of mass (null: from the shapes)",
            fs.MOMENT,
            None,
            nullable=True,
        ),
        vector("force", "constant force at the centre of mass", fs.FORCE, (0.0, 0.0)),
        number("torque", "constant torque", fs.TORQUE, 0.0),
        Field(
            "shapes",
            "list",
            "collision shapes; a dynamic body needs one, or mass and moment",
            (),
            item="shape",
        ),
    ),
)

_MATERIAL = (
    _positive("density", "mass per area (2D)", fs.DENSITY, 1.0),
    _positive(
        "mass",
        "the shape's mass, instead of density (null: from density)",
        fs.MASS,
        None,
        nullable=True,
    ),
    number("restitution", "bounciness; a contact uses the product of the two", fs.RATIO, 0.0),
    _nonneg(
        "friction", "Coulomb friction; a contact uses the product of the two", fs.FRICTION, 0.5
    ),
)
_SHAPE_TYPES = ("circle", "polygon", "box")
_OFFSET = vector("offset", "centre in the body frame", fs.LOCAL, (0.0, 0.0))

CIRCLE = ObjectSpec(
    "circle",
    "a shape",
    "a disc",
    (
        _tag(_SHAPE_TYPES, "circle"),
        _positive("radius", "radius", fs.LENGTH),
        _OFFSET,
        *_MATERIAL,
    ),
)
POLYGON = ObjectSpec(
    "polygon",
    "a shape",
    "a convex polygon",
    (
        _tag(_SHAPE_TYPES, "polygon"),
        Field(
            "vertices",
            "vertices",
            "[x, y] corners in the body frame, convex, either winding",
            REQUIRED,
            fs.LOCAL.unit,
            lo=fs.LOCAL.lo,
            hi=fs.LOCAL.hi,
        ),
        *_MATERIAL,
    ),
)
BOX = ObjectSpec(
    "box",
    "a shape",
    "a rectangle",
    (
        _tag(_SHAPE_TYPES, "box"),
        _positive("width", "size along the box's x axis", fs.LENGTH),
        _positive("height", "size along the box's y axis", fs.LENGTH),
        _OFFSET,
        number("angle", "turn of the box in the body frame", fs.ANGLE, 0.0),
        *_MATERIAL,
    ),
)

_JOINT_TYPES = ("pin", "pivot", "spring")
_ANCHORS = (
    Field("a", "body", "the first body, by name"),
    Field("b", "body", "the second body, by name (another body)"),
    vector("anchor_a", "anchor on a, in a's body frame", fs.LOCAL, (0.0, 0.0)),
    vector("anchor_b", "anchor on b, in b's body frame", fs.LOCAL, (0.0, 0.0)),
)
PIN = ObjectSpec(
    "pin",
    "a joint",
    "a rod keeping the two anchors at their initial distance",
    (_tag(_JOINT_TYPES, "pin"), *_ANCHORS),
)
PIVOT = ObjectSpec(
    "pivot",
    "a joint",
    "a hinge: the two anchors coincide",
    (
        _tag(_JOINT_TYPES, "pivot"),
        *_ANCHORS,
        Field(
            "limits",
            "limits",
            "[lo, hi] on angle_b - angle_a (null: free)",
            None,
            "rad",
            lo=fs.ANGLE.lo,
            hi=fs.ANGLE.hi,
            nullable=True,
        ),
        Field(
            "motor",
            "object",
            "drives angular_velocity_b - angular_velocity_a (null: none)",
            None,
            nullable=True,
            item="motor",
        ),
    ),
)
MOTOR = ObjectSpec(
    "motor",
    "a motor",
    "a pivot's motor",
    (
        number("rate", "target of angular_velocity_b - angular_velocity_a", fs.ANGULAR_VELOCITY),
        number("max_torque", "the most torque it applies", Range(0.0, fs.TORQUE.hi, "N m"), gt=0.0),
    ),
)
SPRING = ObjectSpec(
    "spring",
    "a joint",
    "a damped spring between the anchors",
    (
        _tag(_JOINT_TYPES, "spring"),
        *_ANCHORS,
        _nonneg(
            "rest_length",
            "length without tension (null: the initial distance)",
            Range(0.0, fs.LOCAL.hi, "m"),
            None,
            nullable=True,
        ),
        _nonneg("stiffness", "spring constant k", fs.STIFFNESS),
        _nonneg("damping", "damping constant c (force along the spring per m/s)", fs.DAMPING, 0.0),
    ),
)

_FORCE_TYPES = ("drag", "buoyancy", "constant")
_BODIES = Field(
    "bodies",
    "bodies",
    "the bodies it acts on, by name (null: every dynamic body)",
    None,
    nullable=True,
)
_FLUID_DRAG = Range(0.0, 1e12, "N s/m^3")
DRAG = ObjectSpec(
    "drag",
    "a force",
    "air drag at the centre of mass: F = -linear v - quadratic |v| v, tau = -angular omega",
    (
        _tag(_FORCE_TYPES, "drag"),
        _nonneg("linear", "linear drag coefficient", Range(0.0, 1e12, "N s/m"), 0.0),
        _nonneg("quadratic", "quadratic drag coefficient", Range(0.0, 1e12, "N s^2/m^2"), 0.0),
        _nonneg("angular", "angular drag coefficient", Range(0.0, 1e12, "N m s"), 0.0),
        _BODIES,
    ),
)
BUOYANCY = ObjectSpec(
    "buoyancy",
    "a force",
    "water below surface_y: lift, drag and angular drag on the submerged area",
    (
        _tag(_FORCE_TYPES, "buoyancy"),
        number("surface_y", "height of the water surface", fs.POSITION),
        _positive("fluid_density", "mass per area of the fluid", fs.DENSITY),
        _nonneg("linear_drag", "drag per submerged area and speed", _FLUID_DRAG, 0.0),
        _nonneg("angular_drag", "angular drag per submerged area", _FLUID_DRAG, 0.0),
        _BODIES,
    ),
)
CONSTANT = ObjectSpec(
    "constant",
    "a force",
    "a fixed force at a body-frame point and a fixed torque, every step",
    (
        _tag(_FORCE_TYPES, "constant"),
        vector("force", "the force", fs.FORCE, (0.0, 0.0)),
        number("torque", "the torque", fs.TORQUE, 0.0),
        vector(
            "point",
            "where it acts, body frame (null: the centre of mass)",
            fs.LOCAL,
            None,
            nullable=True,
        ),
        _BODIES,
    ),
)

OBJECTS: dict[str, ObjectSpec] = {
    spec.name: spec
    for spec in (
        SCENE,
        SETTINGS,
        BODY,
        CIRCLE,
        POLYGON,
        BOX,
        PIN,
        PIVOT,
        MOTOR,
        SPRING,
        DRAG,
        BUOYANCY,
        CONSTANT,
    )
}
# lists whose items are one of several objects, told apart by their "type"
UNIONS: dict[str, tuple[str, ...]] = {
    "shape": _SHAPE_TYPES,
    "joint": _JOINT_TYPES,
    "force": _FORCE_TYPES,
}


def every_field() -> list[tuple[str, Field]]:
    """``(object name, field)`` for every field of every object, in reference order."""
    return [(spec.name, f) for spec in OBJECTS.values() for f in spec.fields]
