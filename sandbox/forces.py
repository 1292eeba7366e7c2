"""Force generators: drag, buoyancy and constant forces (slides, "Force", "Torque", "Further
Topics on Physics Animation": modelling forces).

A generator adds forces (N) and torques (N m) into the world's accumulators through

    accumulate(world, p, v, phi, w, f, tau)

where p (n, 2) are centres of mass, v (n, 2) their velocities, phi (n,) angles and w (n,)
angular velocities: the state the integrator asks about, which for look-ahead integrators (Verlet,
RK4) is not the world's current state. Forces sum as vectors (f_total = sum f_i); a force f at a
point r from the centre of mass adds the torque tau = r x f.

``bodies=None`` means every dynamic body of the world (also ones added later); otherwise a list
of bodies or body names. Springs are joints (:class:`sandbox.joints.SpringJoint`) but use the
same ``accumulate`` interface.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from sandbox.body import DYNAMIC
from sandbox.buoyancy import submerged_by_body


class ForceGenerator:
    """Base class: which bodies the force acts on, and the scene-file form."""

    type = "force"

    def __init__(self, bodies: Sequence | None = None) -> None:
        self._bodies = None if bodies is None else list(bodies)
        self.world = None

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
        self.world = world

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
        raise NotImplementedError


class Drag(ForceGenerator):
    """Air drag at the centre of mass: F = -linear v - quadratic |v| v, tau = -angular omega.

    ``linear`` (N s/m), ``quadratic`` (N s^2/m^2), ``angular`` (N m s).
    """

    type = "drag"

    def __init__(self, linear=0.0, quadratic=0.0, angular=0.0, bodies=None) -> None:
        super().__init__(bodies)
        self.linear, self.quadratic, self.angular = float(linear), float(quadratic), float(angular)
        for name in ("linear", "quadratic", "angular"):
            value = getattr(self, name)
            if not (math.isfinite(value) and value >= 0.0):
                raise ValueError(f"{name}: expected a number >= 0, got {value}")

    def accumulate(self, world, p, v, phi, w, f, tau) -> None:
        on = self.targets(world)
        speed = np.hypot(v[on, 0], v[on, 1])
        f[on] -= (self.linear + self.quadratic * speed)[:, None] * v[on]
        tau[on] -= self.angular * w[on]

    def to_dict(self) -> dict:
        return {
            "type": self.type,
            "linear": self.linear,
            "quadratic": self.quadratic,
            "angular": self.angular,
            "bodies": self._names(),
        }


class Buoyancy(ForceGenerator):
    """Water below ``surface_y`` (m) of density ``fluid_density`` (kg/m^2).

    For each body, A is the area of its shapes below the surface and c that area's centroid
    (:mod:`sandbox.buoyancy`). As Box2D's buoyancy controller (and the pymunk bridge):

    - lift F = -rho_fluid A g at c (Archimedes: the weight of the displaced fluid)
    - drag F = -linear_drag A v(c) at c, with v(c) = v + omega x (c - com)
    - angular drag tau = -angular_drag A (I / m) omega

    The torque about the centre of mass is r x F with r = c - com (slides, "Torque").
    """

    type = "buoyancy"

    def __init__(
        self,
        surface_y: float = 0.0,
        fluid_density: float = 1.0,
        linear_drag: float = 0.0,
        angular_drag: float = 0.0,
        bodies=None,
    ) -> None:
        super().__init__(bodies)
        self.surface_y = float(surface_y)
        self.fluid_density = float(fluid_density)
        self.linear_drag = float(linear_drag)
        self.angular_drag = float(angular_drag)
        if not (math.isfinite(self.fluid_density) and self.fluid_density > 0.0):
            raise ValueError(f"fluid_density: expected a number > 0, got {self.fluid_density}")
        for name in ("linear_drag", "angular_drag"):
            value = getattr(self, name)
            if not (math.isfinite(value) and value >= 0.0):
                raise ValueError(f"{name}: expected a number >= 0, got {value}")

    def submerged(self, world, p=None, phi=None) -> tuple[np.ndarray, np.ndarray]:
        """Submerged area (n,) and its centroid (n, 2) per body (default: the current state)."""
        p = world.com if p is None else p
        phi = world.angles() if phi is None else phi
        return submerged_by_body(world.geometry(), p, phi, self.surface_y, self.targets(world))

    def accumulate(self, world, p, v, phi, w, f, tau) -> None:
        area, centroid = self.submerged(world, p, phi)
        g = world.gravity
        for i in np.flatnonzero(area > 0.0):
            a = area[i]
            rx, ry = centroid[i, 0] - p[i, 0], centroid[i, 1] - p[i, 1]
            vcx, vcy = v[i, 0] - w[i] * ry, v[i, 1] + w[i] * rx  # v(c) = v + omega x r
            fx = -self.fluid_density * a * g[0] - self.linear_drag * a * vcx
            fy = -self.fluid_density * a * g[1] - self.linear_drag * a * vcy
            f[i, 0] += fx
            f[i, 1] += fy
            tau[i] += rx * fy - ry * fx  # tau = r x F
            tau[i] -= self.angular_drag * a * (world.moment[i] / world.mass[i]) * w[i]

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

    def __init__(self, force=(0.0, 0.0), torque: float = 0.0, point=None, bodies=None) -> None:
        super().__init__(bodies)
        self.force = np.array(force, dtype=float).reshape(2)
        self.torque = float(torque)
        self.point = None if point is None else np.array(point, dtype=float).reshape(2)
        if not (np.all(np.isfinite(self.force)) and math.isfinite(self.torque)):
            raise ValueError("force and torque must be finite")

    def accumulate(self, world, p, v, phi, w, f, tau) -> None:
        on = self.targets(world)
        f[on] += self.force
        tau[on] += self.torque
        if self.point is not None:
            idx = np.flatnonzero(on)
            q = self.point - world.local_com[idx]  # arm in the body frame, about the com
            c, s = np.cos(phi[idx]), np.sin(phi[idx])
            rx, ry = c * q[:, 0] - s * q[:, 1], s * q[:, 0] + c * q[:, 1]
            tau[idx] += rx * self.force[1] - ry * self.force[0]

    def to_dict(self) -> dict:
        return {
            "type": self.type,
            "force": self.force.tolist(),
            "torque": self.torque,
            "point": None if self.point is None else self.point.tolist(),
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
