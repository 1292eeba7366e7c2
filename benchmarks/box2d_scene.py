"""Scene dict -> Box2D 2.3 world (the ``box2d`` package, also known as pybox2d), for the benchmarks.

Builds the bodies and shapes of a scene-file dict (raw or normalised by
``sandbox.scene.validate_scene``) in Box2D 2.3, so that ``run.py`` can step it beside this engine
and pymunk. SI units, y up, radians, CCW positive; a body's ``position`` is its origin in both.

What is kept the same, and how:

- dt, gravity, and the velocity iterations (the scene's ``settings.iterations``); Box2D also runs
  ``POSITION_ITERATIONS`` = 3 position iterations, its recommended default.
- Masses: each fixture gets the shape's density (or its ``mass`` divided by its area) and Box2D
  computes mass, centre of mass and moment itself; a body's ``mass`` and ``moment`` overrides are
  applied as this engine does (an overridden mass scales the moment unless it is also given).
- Friction: a contact uses the **product** of the two shapes' friction (the scene contract, as in
  pymunk). Box2D 2.3 mixes with the geometric mean sqrt(f_a f_b), so each fixture is given f^2:
  sqrt(f_a^2 f_b^2) = f_a f_b exactly.
- Restitution: also the product; Box2D 2.3 takes the larger of the two. When every shape has
  restitution 0 (all the benchmark scenes) both give 0 and nothing more is done; otherwise a
  contact listener sets each contact's restitution to the product before it is solved (a Python
  call per touching contact per step, so timings of such a scene include it). Box2D's threshold
  below which impacts do not bounce (1 m/s) equals this engine's default.
- Sleeping is off (this engine's ``sleep`` defaults to off, pymunk's spaces never sleep unless
  told); continuous collision is off unless a body asks for ``ccd`` (then that body is a
  "bullet" and the world's continuous physics is on).

What differs and cannot be changed without rebuilding Box2D (its compile-time constants):

- Polygons carry a skin of ``b2_polygonRadius`` = 0.01 m: boxes rest 1 cm apart, so a pyramid of
  base 40 stands a few centimetres taller on average.
- A body moves at most ``b2_maxTranslation`` = 2 m per step (120 m/s at dt = 1/60 s): the
  ballistic body falls slower than free fall after about 14 s.
- Box2D computes in single precision (float32).

Joints and force generators are not built (the benchmark scenes have none): such a scene raises
:class:`Box2DSceneError` naming the field, as does a body with a constant ``force`` or ``torque``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import Box2D

POSITION_ITERATIONS = 3  # Box2D 2.3's recommended position iterations per step
DEFAULT_DT = 1.0 / 60.0
DEFAULT_GRAVITY = (0.0, -9.81)
DEFAULT_ITERATIONS = 10
DEFAULT_DENSITY = 1.0
DEFAULT_FRICTION = 0.5
DEFAULT_RESTITUTION = 0.0


class Box2DSceneError(ValueError):
    """A scene the Box2D builder cannot express; ``.path`` names the field, e.g. ``joints``."""

    def __init__(self, path: str, message: str) -> None:
        super().__init__(f"{path}: {message}")
        self.path = path


class ProductRestitution(Box2D.b2ContactListener):
    """Sets each contact's restitution to the product of its two shapes' (kept in the fixtures'
    ``userData``) just before Box2D solves it."""

    def PreSolve(self, contact, old_manifold) -> None:  # noqa: N802 (Box2D's callback name)
        contact.restitution = contact.fixtureA.userData * contact.fixtureB.userData


@dataclass
class Box2DScene:
    """A scene built in Box2D 2.3: ``world``, ``bodies`` in scene order, and how to step it."""

    world: Any
    bodies: list = field(default_factory=list)
    dt: float = DEFAULT_DT
    velocity_iterations: int = DEFAULT_ITERATIONS
    position_iterations: int = POSITION_ITERATIONS
    listener: Any = None  # kept alive here: Box2D holds only a borrowed reference

    def step(self) -> None:
        """One step of ``dt`` seconds."""
        self.world.Step(self.dt, self.velocity_iterations, self.position_iterations)


def _vec(value: Any, default: Sequence[float] = (0.0, 0.0)) -> tuple[float, float]:
    v = default if value is None else value
    return float(v[0]), float(v[1])


def _num(spec: Mapping[str, Any], key: str, default: float) -> float:
    value = spec.get(key)
    return default if value is None else float(value)


def _polygon_area(vertices: Sequence[Sequence[float]]) -> float:
    """Area (m^2) of a simple polygon, either winding (shoelace formula)."""
    twice = 0.0
    for i, (x0, y0) in enumerate(vertices):
        x1, y1 = vertices[(i + 1) % len(vertices)]
        twice += x0 * y1 - x1 * y0
    return 0.5 * abs(twice)


def _shape(spec: Mapping[str, Any], path: str) -> tuple[Any, float]:
    """The Box2D shape of a scene shape, and its area (m^2)."""
    kind = spec.get("type")
    if kind == "circle":
        radius = float(spec["radius"])
        return Box2D.b2CircleShape(radius=radius, pos=_vec(spec.get("offset"))), math.pi * radius**2
    if kind == "box":
        w, h = float(spec["width"]), float(spec["height"])
        box = (0.5 * w, 0.5 * h, _vec(spec.get("offset")), _num(spec, "angle", 0.0))
        return Box2D.b2PolygonShape(box=box), w * h
    if kind == "polygon":
        vertices = [_vec(v) for v in spec["vertices"]]
        if len(vertices) > Box2D.b2_maxPolygonVertices:
            raise Box2DSceneError(
                f"{path}.vertices", f"Box2D takes at most {Box2D.b2_maxPolygonVertices} vertices"
            )
        return Box2D.b2PolygonShape(vertices=vertices), _polygon_area(vertices)
    raise Box2DSceneError(f"{path}.type", f"unknown shape type {kind!r}")


def _add_body(scene: Box2DScene, spec: Mapping[str, Any], path: str) -> None:
    kind = spec.get("type", "dynamic")
    if kind not in ("dynamic", "static", "kinematic"):
        raise Box2DSceneError(f"{path}.type", f"unknown body type {kind!r}")
    if _vec(spec.get("force")) != (0.0, 0.0) or _num(spec, "torque", 0.0) != 0.0:
        key = "torque" if _vec(spec.get("force")) == (0.0, 0.0) else "force"
        raise Box2DSceneError(f"{path}.{key}", "constant forces are not built in Box2D here")
    bullet = bool(spec.get("ccd", False))
    body = scene.world.CreateBody(
        type={
            "dynamic": Box2D.b2_dynamicBody,
            "static": Box2D.b2_staticBody,
            "kinematic": Box2D.b2_kinematicBody,
        }[kind],
        position=_vec(spec.get("position")),
        angle=_num(spec, "angle", 0.0),
        linearVelocity=_vec(spec.get("velocity")),
        angularVelocity=_num(spec, "angular_velocity", 0.0),
        allowSleep=False,
        bullet=bullet,
    )
    if bullet:
        scene.world.continuousPhysics = True
    for j, shape_spec in enumerate(spec.get("shapes") or []):
        shape, area = _shape(shape_spec, f"{path}.shapes[{j}]")
        if shape_spec.get("mass") is not None:
            density = float(shape_spec["mass"]) / area
        else:
            density = _num(shape_spec, "density", DEFAULT_DENSITY)
        friction = _num(shape_spec, "friction", DEFAULT_FRICTION)
        restitution = _num(shape_spec, "restitution", DEFAULT_RESTITUTION)
        fixture = body.CreateFixture(
            shape=shape,
            density=density,
            friction=friction**2,  # Box2D mixes sqrt(f_a f_b): this gives the product f_a f_b
            restitution=restitution,
        )
        fixture.userData = restitution  # the listener's factor, when one is needed
    if kind == "dynamic" and (spec.get("mass") is not None or spec.get("moment") is not None):
        _override_mass(body, spec)
    # the contract's velocity is the centre of mass's, and so is Box2D's once the body has its
    # fixtures; but adding them moved the centre and Box2D kept the origin's velocity: set it again
    body.linearVelocity = _vec(spec.get("velocity"))
    scene.bodies.append(body)


def _override_mass(body: Any, spec: Mapping[str, Any]) -> None:
    """A body's ``mass`` and ``moment`` (about the centre of mass) as this engine applies them."""
    data = body.massData
    cx, cy = data.center
    shapes_mass = data.mass
    shapes_moment = data.I - shapes_mass * (cx * cx + cy * cy)  # Box2D's I is about the origin
    mass = _num(spec, "mass", shapes_mass)
    moment = shapes_moment * mass / shapes_mass if shapes_mass > 0.0 else shapes_moment
    moment = _num(spec, "moment", moment)
    data.mass = mass
    data.I = moment + mass * (cx * cx + cy * cy)
    body.massData = data


def box2d_scene(spec: Mapping[str, Any]) -> Box2DScene:
    """Build the Box2D 2.3 world of a scene dict (raw or normalised); raises Box2DSceneError."""
    for key in ("joints", "forces"):
        if spec.get(key):
            raise Box2DSceneError(key, "not built in Box2D by the benchmark builder")
    settings = spec.get("settings") or {}
    world = Box2D.b2World(gravity=_vec(spec.get("gravity"), DEFAULT_GRAVITY), doSleep=False)
    world.continuousPhysics = False
    scene = Box2DScene(
        world=world,
        dt=_num(spec, "dt", DEFAULT_DT),
        velocity_iterations=int(_num(settings, "iterations", DEFAULT_ITERATIONS)),
    )
    for i, body_spec in enumerate(spec.get("bodies") or []):
        _add_body(scene, body_spec, f"bodies[{i}]")
    restitutions = {f.userData for b in scene.bodies for f in b.fixtures}
    if restitutions - {0.0}:  # the larger of two (Box2D) differs from their product
        scene.listener = ProductRestitution()
        world.contactListener = scene.listener
    return scene
