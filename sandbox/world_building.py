"""Building a world: adding bodies, joints and force generators (a mixin of
:class:`~sandbox.world.World`).

The bodies' records grow by doubling a store (``World._grow``), so a scene of thousands of
bodies is built in linear time; joints and force generators are few and are appended.
"""

from __future__ import annotations

import numpy as np

from sandbox.body import TYPES, Body
from sandbox.forces import MAX_GENERATORS, ForceGenerator
from sandbox.records import BODY


class Building:
    """``add_body``, ``add_joint``, ``add_force``, ``body``; the mass of a body's shapes."""

    def _controllers_changed(self) -> None:
        self._controlled = [b for b in self.bodies if b.controller is not None]

    def _shapes_changed(self, body: Body) -> None:
        self._update_mass(body)

    def add_body(self, body: Body) -> Body:
        """Add a body (returned). Names must be unique; an empty name becomes ``body<i>``."""
        if body.world is not None:
            raise ValueError(f"body {body.name!r} is already in a world")
        if not body.name:
            body.name = f"body{len(self.bodies)}"
        if body.name in self._by_name:
            raise ValueError(f"duplicate body name {body.name!r}")
        i = len(self.state)
        self._grow()
        body.world, body.index = self, i
        self.bodies.append(body)
        self._by_name[body.name] = body
        init, row = body._init, self.state[i]
        row["kind"] = TYPES[body.type]
        row["vel"] = init["velocity"]
        row["omega"] = init["angular_velocity"]
        row["ccd"] = init["ccd"]
        row["const_force"], row["const_torque"] = body._constant
        if body.controller is not None:
            self._controlled.append(body)
        self._set_angle(i, init["angle"])
        self._update_mass(body, origin=init["position"])
        return body

    def add_joint(self, joint):
        """Add a joint (see :mod:`sandbox.joints`); returned."""
        self.wake()
        joint.attach(self)
        self.joint_table = np.concatenate([self.joint_table, joint._own])
        joint.world, joint.index = self, len(self.joint_table) - 1
        joint.place(self)
        joint.attached(self)
        self.joints.append(joint)
        self._dirty = True
        return joint

    def add_force(self, generator):
        """Add a force generator (see :mod:`sandbox.forces`); returned. An object of another
        kind with ``accumulate(world, p, v, phi, w, f, tau)`` is evaluated once per step."""
        if hasattr(generator, "attach"):
            generator.attach(self)
        if isinstance(generator, ForceGenerator):
            if len(self.generator_table) >= MAX_GENERATORS:
                raise ValueError(f"forces: at most {MAX_GENERATORS} force generators")
            self.generator_table = np.concatenate([self.generator_table, generator._own])
            generator.world, generator.index = self, len(self.generator_table) - 1
        else:
            self._python_forces.append(generator)
        self.forces.append(generator)
        self._dirty = True
        return generator

    def body(self, name: str) -> Body:
        """The body called ``name`` (KeyError if none)."""
        try:
            return self._by_name[name]
        except KeyError:
            raise KeyError(f"no body named {name!r}") from None

    def _grow(self) -> None:
        """One more row in ``state`` and ``rot``: views of the first rows of stores that
        double when full, so adding n bodies copies O(n) rows, not O(n^2)."""
        n = len(self.state)
        if n == len(self._state_store) or len(self._rot_store) != len(self._state_store):
            capacity = max(8, 2 * n)
            self._state_store = np.zeros(capacity, dtype=BODY)
            self._state_store[:n] = self.state
            self._rot_store = np.zeros((capacity, self.rot.shape[1]))
            self._rot_store[:n] = self.rot
        self.state = self._state_store[: n + 1]
        self.rot = self._rot_store[: n + 1]

    def _update_mass(self, body: Body, origin=None) -> None:
        i = body.index
        row = self.state[i]
        if origin is None:
            origin = np.asarray(body.position, dtype=float)
        mass, local_com, moment = body.mass_properties()
        row["local_com"] = local_com
        c, s = row["cs"]
        row["com"] = np.asarray(origin, dtype=float) + [
            c * local_com[0] - s * local_com[1],
            s * local_com[0] + c * local_com[1],
        ]
        if body.type == "dynamic" and not (mass > 0 and moment > 0):
            # no shapes yet: checked again when stepping
            row["mass"] = row["moment"] = row["inv_mass"] = row["inv_moment"] = 0.0
        elif body.type == "dynamic":
            row["mass"], row["moment"] = mass, moment
            row["inv_mass"], row["inv_moment"] = 1.0 / mass, 1.0 / moment
        else:
            row["mass"] = row["moment"] = np.inf
            row["inv_mass"] = row["inv_moment"] = 0.0
        self._geometry = None
        self._dirty = True
        self._state_changed(i)  # this body's island wakes

    def _controllers_changed(self) -> None:
        self._controlled = [b for b in self.bodies if b.controller is not None]
