"""Scene dict -> pymunk Space: run a scene file in pymunk, side by side with this engine.

Accepts a scene dict in the scene-file contract, raw (missing keys take the contract defaults) or
normalised by ``sandbox.scene.validate_scene``. SI units, y up, radians, CCW positive.

Where pymunk and the contract differ, the bridge translates and says so in ``PymunkScene.notes``:

- Body origin vs centre of mass: pymunk's ``body.position`` is the body origin and
  ``body.center_of_gravity`` the centre of mass in the body frame, as in the contract, and
  ``body.velocity`` is the velocity of the centre of mass. Traces report the origin.
- Step order: pymunk (Chipmunk) moves positions with the *previous* step's velocity, then updates
  velocities (gravity, forces, contacts, joints). In free flight after n steps
  p_n = s + u n dt + a dt^2 n(n-1)/2, while this engine's semi-implicit Euler gives
  n(n+1)/2: pymunk's positions lag by one step (a dt^2 n); velocities agree.
- Motor sign: pymunk's ``SimpleMotor(a, b, rate)`` drives w_a - w_b = rate. The contract's
  ``rate`` is the angular velocity of b relative to a (w_b - w_a), so the bridge passes ``-rate``.
- Joints: bodies sharing a joint do not collide with each other (pymunk's default is that they
  do; see ``JOINED_BODIES_COLLIDE``). Pivot limits act on angle_b - angle_a, as pymunk's
  ``RotaryLimitJoint``.
- Settings (orientation, integrator, broadphase, solver, penetration) have no pymunk counterpart;
  only ``iterations`` is used. ``ccd`` is accepted and ignored. pymunk's collision slop is set to
  this engine's (0.005 m; pymunk's default of 0.1 m is sized for pixels, not metres); its bias
  keeps its default (``collision_slop``, ``collision_bias``).
- Buoyancy (pymunk has none) is computed here each step from the submerged area and centroid of
  every shape, with Box2D's buoyancy-controller formulas (see :func:`buoyancy_force`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import pymunk

from sandbox.buoyancy import circle_submerged, polygon_submerged  # also for the tests
from sandbox.geometry import polygon_problem
from sandbox.settings import Settings
from sandbox.sleep import TIME_TO_SLEEP

DEFAULT_DT = 1.0 / 60.0
DEFAULT_GRAVITY = (0.0, -9.81)
DEFAULT_ITERATIONS = 10
DEFAULT_DENSITY = 1.0
DEFAULT_RESTITUTION = 0.0
DEFAULT_FRICTION = 0.5

_BODY_TYPES = {
    "dynamic": pymunk.Body.DYNAMIC,
    "static": pymunk.Body.STATIC,
    "kinematic": pymunk.Body.KINEMATIC,
}

_UNUSED_SETTINGS = ("orientation", "integrator", "broadphase", "solver", "penetration")
JOINED_BODIES_COLLIDE = False  # bodies sharing a joint do not collide with each other

StateRow = tuple[str, float, float, float, float, float, float]
TraceRow = tuple[int, float, str, float, float, float, float, float, float]


class BridgeError(ValueError):
    """A scene the bridge cannot express in pymunk; ``.path`` names the field, e.g. ``forces[0]``."""

    def __init__(self, path: str, message: str) -> None:
        super().__init__(f"{path}: {message}")
        self.path = path
        self.message = message


def wrap_angle(angle: float) -> float:
    """The same angle in [-pi, pi] (radians)."""
    return math.remainder(angle, math.tau)


# ---------------------------------------------------------------- submerged geometry (buoyancy)


def shape_submerged(shape: pymunk.Shape, surface_y: float) -> tuple[float, float, float]:
    """Submerged area and its centroid (world frame) of a pymunk circle or polygon."""
    body = shape.body
    if isinstance(shape, pymunk.Circle):
        c = body.local_to_world(shape.offset)
        return circle_submerged(c.x, c.y, shape.radius, surface_y)
    world = np.array([tuple(body.local_to_world(v)) for v in shape.get_vertices()], dtype=float)
    return polygon_submerged(world, surface_y)


def buoyancy_force(
    body: pymunk.Body, force: Mapping[str, Any], gravity: tuple[float, float]
) -> tuple[float, float, float]:
    """Force (x, y) at the centre of mass and torque on ``body`` from a buoyancy generator.

    Box2D's buoyancy controller, with A the submerged area and c its centroid:
    buoyancy F = -rho_fluid A g at c; drag F = -linear_drag A v(c) at c;
    angular drag tau = -angular_drag A (I/m) omega.
    """
    surface_y = _num(force, "surface_y", 0.0)
    area = sx = sy = 0.0
    for shape in body.shapes:
        a, x, y = shape_submerged(shape, surface_y)
        area += a
        sx += a * x
        sy += a * y
    if area <= 0.0:
        return 0.0, 0.0, 0.0
    c = pymunk.Vec2d(sx / area, sy / area)
    rho = _num(force, "fluid_density", 1.0)
    lin = _num(force, "linear_drag", 0.0)
    ang = _num(force, "angular_drag", 0.0)
    v = body.velocity_at_world_point(c)
    fx = -rho * area * gravity[0] - lin * area * v.x
    fy = -rho * area * gravity[1] - lin * area * v.y
    r = c - body.local_to_world(body.center_of_gravity)
    torque = r.x * fy - r.y * fx
    if math.isfinite(body.moment):  # a body that cannot turn feels no angular drag
        torque -= ang * area * (body.moment / body.mass) * body.angular_velocity
    return fx, fy, torque


def drag_force(body: pymunk.Body, force: Mapping[str, Any]) -> tuple[float, float, float]:
    """Drag at the centre of mass: F = -c v - k |v| v, tau = -c_w omega."""
    c = _num(force, "linear", 0.0)
    k = _num(force, "quadratic", 0.0)
    cw = _num(force, "angular", 0.0)
    vx, vy = body.velocity
    speed = math.hypot(vx, vy)
    return (-(c + k * speed) * vx, -(c + k * speed) * vy, -cw * body.angular_velocity)


# ---------------------------------------------------------------- building the space


def _vec(value: Any, default: Sequence[float] = (0.0, 0.0)) -> tuple[float, float]:
    v = default if value is None else value
    return float(v[0]), float(v[1])


def _num(spec: Mapping[str, Any], key: str, default: float) -> float:
    value = spec.get(key)
    return default if value is None else float(value)


def _positive(spec: Mapping[str, Any], key: str, path: str) -> float:
    if spec.get(key) is None:
        raise BridgeError(f"{path}.{key}", "is required")
    value = float(spec[key])
    if not value > 0.0 or not math.isfinite(value):
        raise BridgeError(f"{path}.{key}", f"must be a positive number, got {value}")
    return value


def _make_shape(body: pymunk.Body, spec: Mapping[str, Any], path: str) -> pymunk.Shape:
    """One pymunk shape with material and mass (density, or a shape ``mass``)."""
    kind = spec.get("type")
    if kind == "circle":
        shape = pymunk.Circle(body, _positive(spec, "radius", path), _vec(spec.get("offset")))
    elif kind == "polygon":
        vertices = spec.get("vertices")
        problem = polygon_problem(vertices) if vertices is not None else "is required"
        if problem:
            raise BridgeError(f"{path}.vertices", problem)
        shape = pymunk.Poly(body, [_vec(v) for v in vertices])  # pymunk keeps the convex hull, CCW
    elif kind == "box":
        hw = 0.5 * _positive(spec, "width", path)
        hh = 0.5 * _positive(spec, "height", path)
        ox, oy = _vec(spec.get("offset"))
        place = pymunk.Transform.translation(ox, oy).rotated(_num(spec, "angle", 0.0))
        corners = [(-hw, -hh), (hw, -hh), (hw, hh), (-hw, hh)]
        shape = pymunk.Poly(body, corners, transform=place)
    else:
        raise BridgeError(f"{path}.type", f"unknown shape type {kind!r}")
    shape.elasticity = _num(spec, "restitution", DEFAULT_RESTITUTION)
    shape.friction = _num(spec, "friction", DEFAULT_FRICTION)
    if spec.get("mass") is not None:
        shape.mass = float(spec["mass"])
    else:
        density = spec.get("density")
        shape.density = DEFAULT_DENSITY if density is None else float(density)
    return shape


class PymunkScene:
    """A scene built in pymunk: ``space``, ``bodies`` in scene order, ``step()``, ``state()``.

    Build with :meth:`from_scene`. ``time`` is the simulated time (s), ``dt`` the scene's step,
    ``notes`` lists what the bridge translated or could not express.
    """

    def __init__(self) -> None:
        self.space = pymunk.Space()
        self.space.collision_slop = Settings().slop  # metres, as this engine allows
        self.dt = DEFAULT_DT
        self.time = 0.0
        self.bodies: list[pymunk.Body] = []
        self.names: list[str] = []
        self.notes: list[str] = []
        self._by_name: dict[str, pymunk.Body] = {}
        self._constant: list[tuple[pymunk.Body, tuple[float, float], float]] = []
        self._generators: list[tuple[Mapping[str, Any], list[pymunk.Body]]] = []

    # -- construction

    @classmethod
    def from_scene(cls, spec: Mapping[str, Any]) -> PymunkScene:
        """Build the pymunk space for a scene dict (raw or normalised); raises BridgeError."""
        if not isinstance(spec, Mapping):
            raise BridgeError("scene", "must be a dict")
        scene = cls()
        space = scene.space
        space.gravity = _vec(spec.get("gravity"), DEFAULT_GRAVITY)
        scene.dt = _num(spec, "dt", DEFAULT_DT)
        if not scene.dt > 0.0:
            raise BridgeError("dt", f"must be > 0, got {scene.dt}")
        settings = spec.get("settings") or {}
        space.iterations = int(_num(settings, "iterations", DEFAULT_ITERATIONS))
        if settings.get("sleep"):  # pymunk's sleeping: idle this long (s), speed from gravity
            space.sleep_time_threshold = TIME_TO_SLEEP
        scene._note_settings(settings)
        for i, body_spec in enumerate(spec.get("bodies") or []):
            scene._add_body(body_spec, f"bodies[{i}]")
        for i, joint_spec in enumerate(spec.get("joints") or []):
            scene._add_joint(joint_spec, f"joints[{i}]")
        for i, force_spec in enumerate(spec.get("forces") or []):
            scene._add_force(force_spec, f"forces[{i}]")
        return scene

    def _note_settings(self, settings: Mapping[str, Any]) -> None:
        self.notes.append(
            "pymunk moves positions with the previous step's velocity, then updates velocities: "
            "free-flight positions lag this engine's semi-implicit Euler by one step"
        )
        unused = [f"{k}={settings[k]!r}" for k in _UNUSED_SETTINGS if k in settings]
        if unused:
            self.notes.append(
                f"settings {', '.join(unused)} have no pymunk counterpart (pymunk: "
                "its own Euler step, bounding-box tree, sequential impulses)"
            )
        self.notes.append(
            f"collision_slop={self.collision_slop} m (this engine's slop), "
            f"collision_bias={self.collision_bias} (pymunk's default)"
        )

    def _add_body(self, spec: Mapping[str, Any], path: str) -> None:
        name = str(spec.get("name", path))
        if name in self._by_name:
            raise BridgeError(f"{path}.name", f"duplicate body name {name!r}")
        kind = spec.get("type", "dynamic")
        if kind not in _BODY_TYPES:
            raise BridgeError(f"{path}.type", f"unknown body type {kind!r}")
        body = pymunk.Body(body_type=_BODY_TYPES[kind])
        body.position = _vec(spec.get("position"))
        body.angle = _num(spec, "angle", 0.0)
        shapes = [
            _make_shape(body, s, f"{path}.shapes[{j}]")
            for j, s in enumerate(spec.get("shapes", []))
        ]
        self.space.add(body, *shapes)  # pymunk sums shape masses here and keeps the origin fixed
        if kind == "dynamic":
            self._set_mass(body, spec, path)
        if kind != "static":
            body.velocity = _vec(spec.get("velocity"))
            body.angular_velocity = _num(spec, "angular_velocity", 0.0)
        if spec.get("ccd"):
            self.notes.append(f"{path}.ccd: pymunk has no continuous collision; ignored")
        force, torque = _vec(spec.get("force")), _num(spec, "torque", 0.0)
        if kind == "dynamic" and (force != (0.0, 0.0) or torque != 0.0):
            self._constant.append((body, force, torque))
        self.bodies.append(body)
        self.names.append(name)
        self._by_name[name] = body

    def _set_mass(self, body: pymunk.Body, spec: Mapping[str, Any], path: str) -> None:
        """Body ``mass``/``moment`` replace the values pymunk computed from the shapes.

        A body mass alone scales the shapes' moment by mass / shape mass (same distribution).
        """
        if spec.get("mass") is not None:
            mass, shape_mass, shape_moment = _positive(spec, "mass", path), body.mass, body.moment
            body.mass = mass
            if shape_mass > 0.0:
                body.moment = shape_moment * mass / shape_mass
        if spec.get("moment") is not None:
            body.moment = _positive(spec, "moment", path)
        if not body.mass > 0.0:
            raise BridgeError(f"{path}.mass", "a dynamic body needs mass (shapes or a body mass)")
        if not body.moment > 0.0:
            body.moment = math.inf
            self.notes.append(f"{path}: no moment of inertia; pymunk gets an infinite one")

    def _lookup(self, name: Any, path: str) -> pymunk.Body:
        if name not in self._by_name:
            raise BridgeError(path, f"no body named {name!r}")
        return self._by_name[name]

    def _add_joint(self, spec: Mapping[str, Any], path: str) -> None:
        kind = spec.get("type")
        a = self._lookup(spec.get("a"), f"{path}.a")
        b = self._lookup(spec.get("b"), f"{path}.b")
        pa, pb = _vec(spec.get("anchor_a")), _vec(spec.get("anchor_b"))
        if kind == "pin":
            parts: list[pymunk.Constraint] = [pymunk.PinJoint(a, b, pa, pb)]
        elif kind == "pivot":
            parts = [pymunk.PivotJoint(a, b, pa, pb)]
            if spec.get("limits") is not None:
                lo, hi = _vec(spec["limits"])  # on angle_b - angle_a, as pymunk
                parts.append(pymunk.RotaryLimitJoint(a, b, lo, hi))
            if spec.get("motor") is not None:
                motor = spec["motor"]
                # contract: rate = w_b - w_a; pymunk's SimpleMotor drives w_a - w_b = rate
                simple = pymunk.SimpleMotor(a, b, -_num(motor, "rate", 0.0))
                simple.max_force = _num(motor, "max_torque", math.inf)
                parts.append(simple)
        elif kind == "spring":
            rest = spec.get("rest_length")
            if rest is None:  # the initial distance between the anchors
                rest = (a.local_to_world(pa) - b.local_to_world(pb)).length
            k, c = _num(spec, "stiffness", 0.0), _num(spec, "damping", 0.0)
            parts = [pymunk.DampedSpring(a, b, pa, pb, float(rest), k, c)]
        else:
            raise BridgeError(f"{path}.type", f"unknown joint type {kind!r}")
        for part in parts:
            part.collide_bodies = JOINED_BODIES_COLLIDE
        self.space.add(*parts)

    def _add_force(self, spec: Mapping[str, Any], path: str) -> None:
        kind = spec.get("type")
        if kind not in ("drag", "buoyancy", "constant"):
            raise BridgeError(f"{path}.type", f"unknown force type {kind!r}")
        names = spec.get("bodies")
        if names is None:
            chosen = self.bodies
        else:
            chosen = [self._lookup(n, f"{path}.bodies[{i}]") for i, n in enumerate(names)]
        targets = [b for b in chosen if b.body_type == pymunk.Body.DYNAMIC]
        if kind == "buoyancy":
            self.notes.append(
                f"{path}: buoyancy computed by the bridge (submerged area and centroid per step)"
            )
        self._generators.append((spec, targets))

    # -- simulation

    @property
    def collision_slop(self) -> float:
        """pymunk's allowed overlap between shapes (m); its default is kept."""
        return self.space.collision_slop

    @property
    def collision_bias(self) -> float:
        """Fraction of overlap pymunk leaves uncorrected after 1 s; its default is kept."""
        return self.space.collision_bias

    def body(self, name: str) -> pymunk.Body:
        """The pymunk body of that name (KeyError if none)."""
        return self._by_name[name]

    def _apply_forces(self) -> None:
        """Constant body forces and force generators, accumulated before ``space.step``."""
        for body, (fx, fy), torque in self._constant:
            body.force += (fx, fy)
            body.torque += torque
        gravity = tuple(self.space.gravity)
        for spec, targets in self._generators:
            for body in targets:
                if spec["type"] == "constant":  # world-frame force at a body-frame point
                    force = tuple(spec.get("force", (0.0, 0.0)))
                    point = spec.get("point")
                    if point is None:
                        body.force += force
                    else:
                        body.apply_force_at_world_point(force, body.local_to_world(tuple(point)))
                    body.torque += spec.get("torque", 0.0)
                    continue
                if spec["type"] == "drag":
                    fx, fy, torque = drag_force(body, spec)
                else:
                    fx, fy, torque = buoyancy_force(body, spec, gravity)
                body.force += (fx, fy)
                body.torque += torque

    def step(self, dt: float | None = None) -> None:
        """Advance by ``dt`` seconds (the scene's dt by default)."""
        h = self.dt if dt is None else float(dt)
        if not h > 0.0:
            raise ValueError(f"dt must be > 0, got {h}")
        self._apply_forces()
        self.space.step(h)
        self.time += h

    def state(self) -> list[StateRow]:
        """(name, x, y, angle, vx, vy, omega) per body: origin, angle in [-pi, pi], COM velocity."""
        rows = []
        for name, b in zip(self.names, self.bodies, strict=True):
            x, y = b.position
            vx, vy = b.velocity
            rows.append((name, x, y, wrap_angle(b.angle), vx, vy, b.angular_velocity))
        return rows


def run_pymunk(spec: Mapping[str, Any], steps: int, dt: float | None = None) -> list[TraceRow]:
    """Trace rows (step, t, name, x, y, angle, vx, vy, omega), steps 0 (initial) to ``steps``."""
    scene = PymunkScene.from_scene(spec)
    rows: list[TraceRow] = []
    for n in range(int(steps) + 1):
        if n > 0:
            scene.step(dt)
        rows.extend((n, scene.time, *row) for row in scene.state())
    return rows
