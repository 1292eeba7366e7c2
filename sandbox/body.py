"""Rigid bodies (slides, "State Initialisation (Take 2)"): mass, moment, position, orientation,
linear and angular velocity.

A :class:`Body` added to a :class:`~sandbox.world.World` is a view into the world's arrays (row
``index``): reading ``body.position`` reads the world's state. Before it is added, the body keeps
its own initial values.
"""

from __future__ import annotations

import math

import numpy as np

from sandbox.copying import copy_fields
from sandbox.vec2 import Vec2

DYNAMIC, STATIC, KINEMATIC = 0, 1, 2
TYPES = {"dynamic": DYNAMIC, "static": STATIC, "kinematic": KINEMATIC}
TYPE_NAMES = {v: k for k, v in TYPES.items()}


def _checked(name: str, value):
    """``value`` checked as the body field ``name`` (the scene files' rules; SceneError)."""
    from sandbox.arguments import check_arguments

    return check_arguments("Body", "body", {name: value})[name]


def _rot(c: float, s: float, v) -> np.ndarray:
    return np.array([c * v[0] - s * v[1], s * v[0] + c * v[1]])


class Body:
    """A rigid body. Position and angle place its origin; shapes are in that frame.

    ``mass`` (kg) and ``moment`` (kg m^2, about the centre of mass) default to what the shapes
    give; pass them to override. ``velocity`` is the velocity of the centre of mass (m/s).
    """

    def __init__(
        self,
        name: str = "",
        type: str = "dynamic",
        position=(0.0, 0.0),
        angle: float = 0.0,
        velocity=(0.0, 0.0),
        angular_velocity: float = 0.0,
        mass: float | None = None,
        moment: float | None = None,
        ccd: bool = False,
        force=(0.0, 0.0),
        torque: float = 0.0,
    ) -> None:
        from sandbox.arguments import check_arguments, check_body_name

        check_body_name(name, type)
        check_arguments(
            "Body",
            "body",
            {
                "type": type,
                "position": position,
                "angle": angle,
                "velocity": velocity,
                "angular_velocity": angular_velocity,
                "mass": mass,
                "moment": moment,
                "ccd": ccd,
                "force": force,
                "torque": torque,
            },
        )
        self.name = name
        self.type = type
        self.shapes: list = []
        self.mass_override = mass
        self.moment_override = moment
        self._constant = (np.array(force, dtype=float), float(torque))
        self._controller = None
        self.world = None
        self.index = -1
        self._init = {
            "position": np.array(position, dtype=float),
            "angle": float(angle),
            "velocity": np.array(velocity, dtype=float),
            "angular_velocity": float(angular_velocity),
            "ccd": bool(ccd),
        }

    def __deepcopy__(self, memo: dict) -> Body:
        return copy_fields(self, memo)  # numbers and names shared: see sandbox.copying

    # --- building -----------------------------------------------------------------------------
    def add_shape(self, shape):
        """Attach a shape (returned); mass properties are recomputed."""
        shape.body = self
        self.shapes.append(shape)
        if self.world is not None:
            self.world._shapes_changed(self)
        return shape

    def mass_properties(self):
        """Mass (kg), centre of mass (body frame, m) and moment about it (kg m^2)."""
        from sandbox.mass import MassProperties, combine

        if self.shapes:
            props = combine([s.mass_properties() for s in self.shapes])
        else:
            props = MassProperties(0.0, np.zeros(2), 0.0, 0.0)
        mass = props.mass if self.mass_override is None else float(self.mass_override)
        moment = props.moment
        if self.mass_override is not None and props.mass > 0:
            moment = props.moment * mass / props.mass  # same distribution, scaled
        if self.moment_override is not None:
            moment = float(self.moment_override)
        return mass, np.asarray(props.centroid, dtype=float), moment

    @property
    def controller(self):
        """``controller(body, world)``, called at the start of every step to apply forces."""
        return self._controller

    @controller.setter
    def controller(self, fn) -> None:
        self._controller = fn
        if self.world is not None:
            self.world._controllers_changed()

    @property
    def constant_force(self) -> np.ndarray:
        """A force (N) applied at the centre of mass every step."""
        if self.world is None:
            return self._constant[0]
        return self.world.const_force[self.index]

    @constant_force.setter
    def constant_force(self, value) -> None:
        value = _checked("force", value)
        if self.world is None:
            self._constant = (np.array(value, dtype=float), self._constant[1])
        else:
            self.world.const_force[self.index] = value
            self.world._constants_changed(self.index)

    @property
    def constant_torque(self) -> float:
        """A torque (N m) applied every step."""
        if self.world is None:
            return self._constant[1]
        return float(self.world.const_torque[self.index])

    @constant_torque.setter
    def constant_torque(self, value: float) -> None:
        value = _checked("torque", value)
        if self.world is None:
            self._constant = (self._constant[0], float(value))
        else:
            self.world.const_torque[self.index] = float(value)
            self.world._constants_changed(self.index)

    # --- state (views into the world arrays) -------------------------------------------------
    def _w(self):
        if self.world is None:
            raise RuntimeError(f"body {self.name!r} is not in a world yet")
        return self.world

    @property
    def kind(self) -> int:
        return TYPES[self.type]

    @property
    def position(self) -> Vec2:
        """World position of the body origin (m)."""
        if self.world is None:
            return Vec2(*self._init["position"])
        row = self.world.state[self.index]  # three fields as Python floats: 3.7 us, not 5.8
        (c, s), (lx, ly), (x, y) = (
            row["cs"].tolist(),
            row["local_com"].tolist(),
            row["com"].tolist(),
        )
        return Vec2.of_floats((x - (c * lx - s * ly), y - (s * lx + c * ly)))  # com - R lc

    @position.setter
    def position(self, value) -> None:
        self._place(_checked("position", value))

    def _place(self, value) -> None:
        if self.world is None:
            self._init["position"] = np.array(value, dtype=float)
            return
        w, i = self.world, self.index
        w.com[i] = np.asarray(value, dtype=float) + _rot(*w.cs[i], w.local_com[i])
        w._state_changed(i)

    @property
    def center_of_mass(self) -> Vec2:
        """World position of the centre of mass (m)."""
        return Vec2.of_floats(self._w().state[self.index]["com"].tolist())

    @property
    def angle(self) -> float:
        """Orientation in radians, continuous: turns accumulate (as in pymunk)."""
        if self.world is None:
            return self._init["angle"]
        return float(self.world.state["angle"][self.index])

    @angle.setter
    def angle(self, value: float) -> None:
        value = _checked("angle", value)
        if self.world is None:
            self._init["angle"] = float(value)
            return
        origin = self.position
        self.world._set_angle(self.index, float(value))
        self._place(origin)

    @property
    def velocity(self) -> Vec2:
        """Velocity of the centre of mass (m/s)."""
        if self.world is None:
            return Vec2(*self._init["velocity"])
        return Vec2.of_floats(self.world.state[self.index]["vel"].tolist())

    @velocity.setter
    def velocity(self, value) -> None:
        value = _checked("velocity", value)
        if self.world is None:
            self._init["velocity"] = np.array(value, dtype=float)
        else:
            self.world.vel[self.index] = np.asarray(value, dtype=float)
            self.world._state_changed(self.index)

    @property
    def angular_velocity(self) -> float:
        """rad/s, counter-clockwise positive."""
        if self.world is None:
            return self._init["angular_velocity"]
        return float(self.world.omega[self.index])

    @angular_velocity.setter
    def angular_velocity(self, value: float) -> None:
        value = _checked("angular_velocity", value)
        if self.world is None:
            self._init["angular_velocity"] = float(value)
        else:
            self.world.omega[self.index] = float(value)
            self.world._state_changed(self.index)

    @property
    def mass(self) -> float:
        """kg (inf for static and kinematic bodies in a world)."""
        if self.world is None:
            return self.mass_properties()[0]
        return float(self.world.mass[self.index])

    @property
    def moment(self) -> float:
        """Moment of inertia about the centre of mass (kg m^2)."""
        if self.world is None:
            return self.mass_properties()[2]
        return float(self.world.moment[self.index])

    @property
    def ccd(self) -> bool:
        return self._init["ccd"] if self.world is None else bool(self.world.ccd[self.index])

    # --- frames -------------------------------------------------------------------------------
    def world_point(self, local) -> Vec2:
        """Body-frame point (about the origin) to world coordinates (m)."""
        c, s = math.cos(self.angle), math.sin(self.angle)
        return Vec2(*(np.asarray(self.position) + _rot(c, s, local)))

    def local_point(self, point) -> Vec2:
        """World point to the body frame (about the origin)."""
        c, s = math.cos(self.angle), math.sin(self.angle)
        d = np.asarray(point, dtype=float) - np.asarray(self.position)
        return Vec2(*_rot(c, -s, d))

    def velocity_at(self, point) -> Vec2:
        """Velocity of the material point at world ``point``: v + omega x r (m/s)."""
        w = self._w()
        r = np.asarray(point, dtype=float) - w.com[self.index]
        om = w.omega[self.index]
        return Vec2(*(w.vel[self.index] + om * np.array([-r[1], r[0]])))

    # --- forces -------------------------------------------------------------------------------
    def apply_force(self, force, point=None) -> None:
        """Add a force (N) at a world point (default: the centre of mass); tau = r x f."""
        w = self._w()
        w.wake(self.index)
        f = np.asarray(force, dtype=float)
        w.force[self.index] += f
        if point is not None:
            r = np.asarray(point, dtype=float) - w.com[self.index]
            w.torque[self.index] += r[0] * f[1] - r[1] * f[0]  # slides, "Torque": tau = r x f

    def apply_torque(self, torque: float) -> None:
        """Add a torque (N m) for this step."""
        w = self._w()
        w.wake(self.index)
        w.torque[self.index] += float(torque)

    def apply_impulse(self, impulse, point=None) -> None:
        """Change momentum at once: v += j / m, omega += (r x j) / I."""
        w, i = self._w(), self.index
        w.wake(i)
        j = np.asarray(impulse, dtype=float)
        w.vel[i] += j * w.inv_mass[i]
        if point is not None:
            r = np.asarray(point, dtype=float) - w.com[i]
            w.omega[i] += (r[0] * j[1] - r[1] * j[0]) * w.inv_moment[i]
        w._state_changed(i)

    def kinetic_energy(self) -> float:
        """m |v|^2 / 2 + I omega^2 / 2 (J); 0 for static and kinematic bodies."""
        w, i = self._w(), self.index
        if self.type != "dynamic":
            return 0.0
        v = w.vel[i]
        return 0.5 * w.mass[i] * float(v @ v) + 0.5 * w.moment[i] * w.omega[i] ** 2

    def __repr__(self) -> str:
        return f"Body({self.name!r}, {self.type}, position={self.position}, angle={self.angle:.4f})"
