"""Force generators: drag, buoyancy and constant forces (slides, "Force", "Torque", "Further
Topics on Physics Animation": modelling forces).

Each generator is a GENERATOR record in the world (``world.generator_table``); the objects here
are views of their records, as bodies and joints are. The step evaluates every force at the
state the integrator asks about (:func:`accumulate_forces`), which for look-ahead integrators
(Verlet, RK4) is not the world's current state. Forces sum as vectors (f_total = sum f_i); a
force f at a point r from the centre of mass adds the torque tau = r x f.

``bodies=None`` means every dynamic body of the world (also ones added later); otherwise a list
of bodies or body names. Springs are joints (:class:`sandbox.joints.SpringJoint`) whose force
is added here too. Any other object with an ``accumulate(world, p, v, phi, w, f, tau)`` method
can be added as a force as well; it is evaluated once per step, at the state the step starts
from.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from sandbox.buoyancy import submerged_by_body
from sandbox.jit import njit
from sandbox.joints.spring import spring_force
from sandbox.math2d import cross, rotate
from sandbox.records import BUOYANCY, CONSTANT, DRAG, DYNAMIC, GENERATOR, MOTION, SPRING

MAX_GENERATORS = 64  # one bit per generator in BODY["generators"]


# --- compiled: every force at a state ----------------------------------------------------------
@njit
def drag_force(g, bit, bodies, state, out) -> None:
    """Air drag at the centre of mass: F = -linear v - quadratic |v| v, tau = -angular omega."""
    for i in range(bodies.shape[0]):
        if bodies[i]["kind"] != DYNAMIC or not (bodies[i]["generators"] & bit):
            continue
        v = state[i]["v"]
        k = g["linear"] + g["quadratic"] * math.sqrt(v[0] * v[0] + v[1] * v[1])
        out[i]["v"][0] -= k * v[0]
        out[i]["v"][1] -= k * v[1]
        out[i]["w"] -= g["angular"] * state[i]["w"]


@njit
def buoyancy_force(g, bit, bodies, shapes, vertices, state, gravity, out) -> None:
    """Box2D's buoyancy controller, with A the submerged area and c its centroid
    (:mod:`sandbox.buoyancy`): lift F = -rho_fluid A g at c (Archimedes: the weight of the
    displaced fluid); drag F = -linear_drag A v(c) at c, v(c) = v + omega x (c - com); angular
    drag tau = -angular_drag A (I / m) omega; the torque about the centre of mass is r x F."""
    area, centroid = submerged_by_body(bodies, shapes, vertices, state, g["surface_y"], bit)
    for i in range(bodies.shape[0]):
        a = area[i]
        if a <= 0.0:
            continue
        s = state[i]
        rx, ry = centroid[i, 0] - s["p"][0], centroid[i, 1] - s["p"][1]
        vcx, vcy = s["v"][0] - s["w"] * ry, s["v"][1] + s["w"] * rx  # v(c) = v + omega x r
        fx = -g["fluid_density"] * a * gravity[0] - g["linear_drag"] * a * vcx
        fy = -g["fluid_density"] * a * gravity[1] - g["linear_drag"] * a * vcy
        out[i]["v"][0] += fx
        out[i]["v"][1] += fy
        out[i]["w"] += cross(rx, ry, fx, fy)  # tau = r x F
        out[i]["w"] -= g["angular_drag"] * a * (bodies[i]["moment"] / bodies[i]["mass"]) * s["w"]


@njit
def constant_force(g, bit, bodies, state, out) -> None:
    """A fixed world-frame force at a body point (origin frame) or the centre of mass, plus a
    torque: wind, a thruster held on."""
    for i in range(bodies.shape[0]):
        if bodies[i]["kind"] != DYNAMIC or not (bodies[i]["generators"] & bit):
            continue
        fx, fy = g["force"][0], g["force"][1]
        out[i]["v"][0] += fx
        out[i]["v"][1] += fy
        out[i]["w"] += g["torque"]
        if g["at_point"]:
            qx = g["point"][0] - bodies[i]["local_com"][0]  # the arm in the body frame
            qy = g["point"][1] - bodies[i]["local_com"][1]
            phi = state[i]["phi"]
            rx, ry = rotate(math.cos(phi), math.sin(phi), qx, qy)
            out[i]["w"] += cross(rx, ry, fx, fy)


@njit(python=True)
def generator_force(generators, k: int, geometry, state, gravity, out) -> None:
    """Generator k's forces at ``state`` added into ``out`` (see :func:`accumulate_forces`);
    ``geometry`` = (bodies, shapes, vertices) records."""
    bodies, shapes, vertices = geometry
    g = generators[k]
    bit = np.uint64(1) << np.uint64(k)
    if g["kind"] == DRAG:
        drag_force(g, bit, bodies, state, out)
    elif g["kind"] == BUOYANCY:
        buoyancy_force(g, bit, bodies, shapes, vertices, state, gravity, out)
    elif g["kind"] == CONSTANT:
        constant_force(g, bit, bodies, state, out)


@njit
def accumulate_forces(bodies, shapes, vertices, joints, generators, state, gravity, out) -> None:
    """Every force and torque at the integrator's ``state`` (MOTION records) into ``out``
    (MOTION records used as forces: ``v`` holds F (N), ``w`` holds tau (N m)): each body's
    accumulated force and torque of the step, every generator, every spring. Gravity is not
    included (see :func:`sandbox.integrators.accelerations`)."""
    for i in range(bodies.shape[0]):
        out[i]["v"][0], out[i]["v"][1] = bodies[i]["force"][0], bodies[i]["force"][1]
        out[i]["w"] = bodies[i]["torque"]
    for k in range(generators.shape[0]):
        generator_force(generators, k, (bodies, shapes, vertices), state, gravity, out)
    for k in range(joints.shape[0]):
        j = joints[k]
        if j["kind"] != SPRING:
            continue
        fx, fy, ra, rb = spring_force(j, bodies, state)
        a, b = out[j["a"]], out[j["b"]]
        b["v"][0] += fx
        b["v"][1] += fy
        b["w"] += cross(rb[0], rb[1], fx, fy)
        a["v"][0] -= fx
        a["v"][1] -= fy
        a["w"] -= cross(ra[0], ra[1], fx, fy)


# --- the Python views --------------------------------------------------------------------------
class ForceGenerator:
    """Base class: which bodies the force acts on, its record, and the scene-file form."""

    type = "force"
    code = -1

    def __init__(self, bodies: Sequence | None = None) -> None:
        self._bodies = None if bodies is None else list(bodies)
        self.world = None
        self.index = -1
        self._own = np.zeros(1, dtype=GENERATOR)
        self._own[0]["kind"] = self.code

    @property
    def record(self):
        """This generator's GENERATOR record (in the world's table once attached)."""
        if self.world is None:
            return self._own[0]
        return self.world.generator_table[self.index]

    def _set(self, field: str, value: float, positive: bool = False) -> None:
        value = float(value)
        ok = value > 0.0 if positive else value >= 0.0
        if not (math.isfinite(value) and ok):
            raise ValueError(
                f"{field}: expected a number {'>' if positive else '>='} 0, got {value}"
            )
        self.record[field] = value

    def attach(self, world) -> None:
        """Resolve body names against ``world`` (called by ``world.add_force``)."""
        if self._bodies is not None:
            resolved = []
            for body in self._bodies:
                if isinstance(body, str):
                    body = world.body(body)
                if body.world is not world:
                    raise ValueError(f"bodies: body {body.name!r} is not in this world")
                resolved.append(body)
            self._bodies = resolved

    @property
    def bodies(self) -> list | None:
        """The bodies acted on, or None for every dynamic body."""
        return self._bodies

    def targets(self, world) -> np.ndarray:
        """(n,) bool: the dynamic bodies this generator acts on."""
        mask = world.kind == DYNAMIC
        if self._bodies is None:
            return mask
        chosen = np.zeros(len(mask), dtype=bool)
        chosen[[b.index for b in self._bodies]] = True
        return mask & chosen

    def _names(self) -> list[str] | None:
        return None if self._bodies is None else [getattr(b, "name", b) for b in self._bodies]

    def accumulate(self, world, p, v, phi, w, f, tau) -> None:
        """Add this generator's forces (N) and torques (N m) at the state p (n, 2) centres of
        mass, v (n, 2), phi (n,) angles, w (n,) into f (n, 2) and tau (n,): what the step adds
        (:func:`generator_force`), for a look at one force on its own."""
        if world._dirty:
            world._prepare(world.dt)
        state = np.zeros(len(world.bodies), dtype=MOTION)
        state["p"], state["v"], state["phi"], state["w"] = p, v, phi, w
        out = np.zeros(len(world.bodies), dtype=MOTION)
        g = world.geometry()
        geometry = (world.state, g.table, g.vertices)
        generator_force(world.generator_table, self.index, geometry, state, world.gravity, out)
        f += out["v"]
        tau += out["w"]

    def __repr__(self) -> str:
        """``Drag(linear=0.1, quadratic=0, angular=0, bodies=None)``: the scene-file fields."""
        fields = {k: v for k, v in self.to_dict().items() if k != "type"}
        return f"{type(self).__name__}({', '.join(f'{k}={_show(v)}' for k, v in fields.items())})"


def _show(value) -> str:
    """A field value as a repr shows it: floats short (0.1, 0), lists of them likewise."""
    if isinstance(value, float):
        return f"{value:g}"
    if isinstance(value, list | tuple):
        return "[" + ", ".join(_show(v) for v in value) + "]"
    return repr(value)


class Drag(ForceGenerator):
    """Air drag at the centre of mass: F = -linear v - quadratic |v| v, tau = -angular omega.

    ``linear`` (N s/m), ``quadratic`` (N s^2/m^2), ``angular`` (N m s).
    """

    type = "drag"
    code = DRAG

    def __init__(self, linear=0.0, quadratic=0.0, angular=0.0, bodies=None) -> None:
        super().__init__(bodies)
        self.linear, self.quadratic, self.angular = linear, quadratic, angular

    linear = property(
        lambda self: float(self.record["linear"]), lambda self, v: self._set("linear", v)
    )
    quadratic = property(
        lambda self: float(self.record["quadratic"]), lambda self, v: self._set("quadratic", v)
    )
    angular = property(
        lambda self: float(self.record["angular"]), lambda self, v: self._set("angular", v)
    )

    def to_dict(self) -> dict:
        return {
            "type": self.type,
            "linear": self.linear,
            "quadratic": self.quadratic,
            "angular": self.angular,
            "bodies": self._names(),
        }


class Buoyancy(ForceGenerator):
    """Water below ``surface_y`` (m) of density ``fluid_density`` (kg/m^2), with drag per unit
    submerged area (``linear_drag``, ``angular_drag``): see :func:`buoyancy_force`."""

    type = "buoyancy"
    code = BUOYANCY

    def __init__(
        self,
        surface_y: float = 0.0,
        fluid_density: float = 1.0,
        linear_drag: float = 0.0,
        angular_drag: float = 0.0,
        bodies=None,
    ) -> None:
        super().__init__(bodies)
        value = float(surface_y)
        if not math.isfinite(value):
            raise ValueError(f"surface_y: expected a finite number, got {value}")
        self.record["surface_y"] = value
        self._set("fluid_density", fluid_density, positive=True)
        self.linear_drag, self.angular_drag = linear_drag, angular_drag

    surface_y = property(lambda self: float(self.record["surface_y"]))
    fluid_density = property(lambda self: float(self.record["fluid_density"]))
    linear_drag = property(
        lambda self: float(self.record["linear_drag"]), lambda self, v: self._set("linear_drag", v)
    )
    angular_drag = property(
        lambda self: float(self.record["angular_drag"]),
        lambda self, v: self._set("angular_drag", v),
    )

    def submerged(self, world, p=None, phi=None) -> tuple[np.ndarray, np.ndarray]:
        """Submerged area (n,) and its centroid (n, 2) per body (default: the current state;
        ``p`` (n, 2) centres of mass and ``phi`` (n,) angles otherwise)."""
        state = np.zeros(len(world.bodies), dtype=MOTION)
        state["p"] = world.com if p is None else p
        state["phi"] = world.state["angle"] if phi is None else phi
        g = world.geometry()
        bit = np.uint64(1) << np.uint64(self.index)
        return submerged_by_body(world.state, g.table, g.vertices, state, self.surface_y, bit)

    def to_dict(self) -> dict:
        return {
            "type": self.type,
            "surface_y": self.surface_y,
            "fluid_density": self.fluid_density,
            "linear_drag": self.linear_drag,
            "angular_drag": self.angular_drag,
            "bodies": self._names(),
        }


class ConstantForce(ForceGenerator):
    """A fixed world-frame ``force`` (N) at a body-frame ``point`` (m, origin frame; default: the
    centre of mass), plus a ``torque`` (N m), on each chosen body: wind, a thruster held on."""

    type = "constant"
    code = CONSTANT

    def __init__(self, force=(0.0, 0.0), torque: float = 0.0, point=None, bodies=None) -> None:
        super().__init__(bodies)
        force = np.array(force, dtype=float).reshape(2)
        if not (np.all(np.isfinite(force)) and math.isfinite(float(torque))):
            raise ValueError("force and torque must be finite")
        r = self.record
        r["force"], r["torque"] = force, float(torque)
        if point is not None:
            r["point"], r["at_point"] = np.array(point, dtype=float).reshape(2), True

    @property
    def force(self) -> np.ndarray:
        return self.record["force"].copy()

    @property
    def torque(self) -> float:
        return float(self.record["torque"])

    @property
    def point(self) -> np.ndarray | None:
        r = self.record
        return r["point"].copy() if r["at_point"] else None

    def to_dict(self) -> dict:
        point = self.point
        return {
            "type": self.type,
            "force": self.force.tolist(),
            "torque": self.torque,
            "point": None if point is None else point.tolist(),
            "bodies": self._names(),
        }


TYPES = {"drag": Drag, "buoyancy": Buoyancy, "constant": ConstantForce}


def force_from_dict(spec: dict, world) -> ForceGenerator:
    """A force generator from its scene-file form (normalized by ``validate_scene``)."""
    kind = spec["type"]
    if kind not in TYPES:
        raise ValueError(f"type: expected one of {', '.join(TYPES)}, got {kind!r}")
    bodies = spec.get("bodies")
    if kind == "drag":
        return Drag(
            spec.get("linear", 0.0), spec.get("quadratic", 0.0), spec.get("angular", 0.0), bodies
        )
    if kind == "buoyancy":
        return Buoyancy(
            spec["surface_y"],
            spec["fluid_density"],
            spec.get("linear_drag", 0.0),
            spec.get("angular_drag", 0.0),
            bodies,
        )
    return ConstantForce(
        spec.get("force", (0.0, 0.0)), spec.get("torque", 0.0), spec.get("point"), bodies
    )
