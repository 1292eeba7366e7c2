"""The world: every body's state in contiguous arrays, and the step (slides, "State Update").

Per step (``docs/architecture.md`` has the details):

1. forces: gravity, constant forces, controllers, force generators -> accelerations
2. the integrator's free-motion increments (dp, dv, dphi, domega)
3. v += dv; contacts found at the current positions (retroactive detection)
4. the solver's impulses change v and omega (contacts and joints); bounces reflect the
   approach velocities from before step 3 (before this step's gravity and forces)
5. p += dp + (impulse velocity change) dt; orientation turned likewise
6. continuous collision for ``ccd`` bodies, then the penetration fix
"""

from __future__ import annotations

import numpy as np

from sandbox import collision, integrators, orientation
from sandbox.body import DYNAMIC, KINEMATIC, STATIC, TYPES, Body
from sandbox.geometry_arrays import Geometry, build_geometry
from sandbox.settings import Settings

_EULERS = ("semi_implicit_euler", "explicit_euler")


class World:
    """A 2D rigid-body world. SI units, y up, radians counter-clockwise.

    ``World(gravity=(0, -9.81), dt=1/60, orientation="complex", solver="iterative", ...)``: any
    field of :class:`~sandbox.settings.Settings` may be passed by name.
    """

    def __init__(
        self, gravity=(0.0, -9.81), dt: float = 1.0 / 60.0, name: str = "world", **settings
    ):
        from sandbox.arguments import check_world_arguments  # the API's checks (SceneError)

        check_world_arguments(gravity, dt, name, settings)
        if not dt > 0:
            raise ValueError("dt: must be > 0")
        self.name = name
        self.gravity = np.array(gravity, dtype=float)
        self.dt = float(dt)
        self.settings = Settings(**settings)
        self.time = 0.0
        self.steps = 0
        self.bodies: list[Body] = []
        self.joints: list = []
        self.forces: list = []
        self.stats: dict = {}
        self.manifolds = None  # contacts of the last step (sandbox.contact.Manifolds)
        self._by_name: dict[str, Body] = {}
        self._geometry: Geometry | None = None
        self._analytic_ref = None
        self._solver_cache: dict = {}
        self._controlled: list[Body] = []
        self._checked = False  # masses checked and ccd flag known
        self._has_ccd = False
        self._has_constant = False
        self._alloc(0)

    # --- arrays -------------------------------------------------------------------------------
    def _alloc(self, n: int) -> None:
        self.kind = np.zeros(n, dtype=np.int64)
        self.com = np.zeros((n, 2))
        self.local_com = np.zeros((n, 2))
        self.vel = np.zeros((n, 2))
        self.omega = np.zeros(n)
        # orientation in the settings' representation: 1, 4 or 2 floats per body
        self.rot = np.zeros((n, orientation.FLOATS_STORED[self.settings.orientation]))
        self.cs = np.zeros((n, 2))
        self.mass = np.zeros(n)
        self.inv_mass = np.zeros(n)
        self.moment = np.zeros(n)
        self.inv_moment = np.zeros(n)
        self.force = np.zeros((n, 2))
        self.torque = np.zeros(n)
        self.const_force = np.zeros((n, 2))
        self.const_torque = np.zeros(n)
        self.ccd = np.zeros(n, dtype=bool)
        # what controllers, constant forces and apply_force/apply_torque applied in the last
        # step (N, N m), for drawing force arrows; gravity and contact impulses not included
        self.applied_force = np.zeros((n, 2))
        self.applied_torque = np.zeros(n)
        self._dphi = np.zeros(n)  # scratch: each body's turn this step

    def _grow(self) -> int:
        n = len(self.kind)
        for key, value in list(vars(self).items()):
            if (
                isinstance(value, np.ndarray)
                and value.shape[:1] == (n,)
                and key not in ("gravity",)
            ):
                pad = np.zeros((1, *value.shape[1:]), dtype=value.dtype)
                setattr(self, key, np.concatenate([value, pad]))
        return n

    @property
    def orientation_kind(self) -> int:
        return orientation.NAMES[self.settings.orientation]

    # --- building -----------------------------------------------------------------------------
    def add_body(self, body: Body) -> Body:
        """Add a body (returned). Names must be unique; an empty name becomes ``body<i>``."""
        if body.world is not None:
            raise ValueError(f"body {body.name!r} is already in a world")
        if not body.name:
            body.name = f"body{len(self.bodies)}"
        if body.name in self._by_name:
            raise ValueError(f"duplicate body name {body.name!r}")
        i = self._grow()
        body.world, body.index = self, i
        self.bodies.append(body)
        self._by_name[body.name] = body
        init = body._init
        self.kind[i] = TYPES[body.type]
        self.vel[i] = init["velocity"]
        self.omega[i] = init["angular_velocity"]
        self.ccd[i] = init["ccd"]
        self.const_force[i], self.const_torque[i] = body._constant
        self._controllers_changed()
        self._constants_changed()
        self._set_angle(i, init["angle"])
        self._update_mass(body, origin=init["position"])
        return body

    def add_joint(self, joint):
        """Add a joint (see :mod:`sandbox.joints`); returned."""
        joint.attach(self)
        self.joints.append(joint)
        return joint

    def add_force(self, generator):
        """Add a force generator (see :mod:`sandbox.forces`); returned."""
        if hasattr(generator, "attach"):
            generator.attach(self)
        self.forces.append(generator)
        return generator

    def body(self, name: str) -> Body:
        """The body called ``name`` (KeyError if none)."""
        try:
            return self._by_name[name]
        except KeyError:
            raise KeyError(f"no body named {name!r}") from None

    def _update_mass(self, body: Body, origin=None) -> None:
        i = body.index
        if origin is None:
            origin = np.asarray(body.position)
        mass, local_com, moment = body.mass_properties()
        self.local_com[i] = local_com
        c, s = self.cs[i]
        self.com[i] = np.asarray(origin) + [
            c * local_com[0] - s * local_com[1],
            s * local_com[0] + c * local_com[1],
        ]
        if body.type == "dynamic":
            if not (mass > 0 and moment > 0):  # no shapes yet: checked again when stepping
                self.mass[i] = self.moment[i] = self.inv_mass[i] = self.inv_moment[i] = 0.0
                self._geometry = None
                self._checked = False
                return
            self.mass[i], self.moment[i] = mass, moment
            self.inv_mass[i], self.inv_moment[i] = 1.0 / mass, 1.0 / moment
        else:
            self.mass[i] = self.moment[i] = np.inf
            self.inv_mass[i] = self.inv_moment[i] = 0.0
        self._geometry = None
        self._checked = False
        self._state_changed()

    def _controllers_changed(self) -> None:
        self._controlled = [b for b in self.bodies if b.controller is not None]

    def _shapes_changed(self, body: Body) -> None:
        self._update_mass(body)

    def _set_angle(self, i: int, angle: float) -> None:
        row = self.rot[i : i + 1]
        orientation.set_angles(self.orientation_kind, row, np.array([angle]))
        orientation.cos_sin(self.orientation_kind, row, self.cs[i : i + 1])
        self._state_changed()

    def _state_changed(self) -> None:
        self._analytic_ref = None

    def angles(self) -> np.ndarray:
        """Every body's angle (rad, in [-pi, pi])."""
        return orientation.angles_of(self.orientation_kind, self.rot)

    def origins(self) -> np.ndarray:
        """Every body's origin (n, 2): com - R local_com."""
        c, s = self.cs[:, 0], self.cs[:, 1]
        lc = self.local_com
        return self.com - np.stack(
            [c * lc[:, 0] - s * lc[:, 1], s * lc[:, 0] + c * lc[:, 1]], axis=1
        )

    def geometry(self) -> Geometry:
        """Flattened shape arrays (rebuilt after shapes change)."""
        if self._geometry is None:
            self._geometry = build_geometry(self.bodies, self.local_com)
        return self._geometry

    # --- forces -------------------------------------------------------------------------------
    def _accelerations(self, extra_force: np.ndarray, extra_torque: np.ndarray):
        """accel(p, v, phi, omega) for the integrators: gravity + forces / m, torques / I."""
        dyn = self.kind == DYNAMIC
        inv_m, inv_i = self.inv_mass, self.inv_moment
        gravity = np.where(dyn[:, None], self.gravity, 0.0)
        generators = self._force_generators()

        def accel(p, v, phi, w):
            f = extra_force.copy()
            tau = extra_torque.copy()
            for g in generators:
                g.accumulate(self, p, v, phi, w, f, tau)
            return gravity + f * inv_m[:, None], tau * inv_i

        return accel

    # --- the step -----------------------------------------------------------------------------
    def step(self, dt: float | None = None) -> None:
        """Advance the world by ``dt`` seconds (default: the world's dt)."""
        dt = self.dt if dt is None else float(dt)
        if not dt > 0:
            raise ValueError("dt: must be > 0")
        if not self._checked:
            self._check_masses()
        for body in self._controlled:
            body.controller(body, self)
        if self._has_constant:
            self.force += self.const_force
            self.torque += self.const_torque
        self.applied_force[:] = self.force
        self.applied_torque[:] = self.torque
        integrator = self.settings.integrator
        if integrator == "analytic":
            self._step_analytic(dt)
        elif integrator in _EULERS and not self._has_ccd and not self._has_force_generators():
            self._step_euler(dt, explicit=integrator == "explicit_euler")
        else:
            self._step_numeric(dt)
        self.time += dt
        self.steps += 1

    def _force_generators(self) -> list:
        """Force generators, and joints that act as forces (springs: ``accumulate``)."""
        return [*self.forces, *(j for j in self.joints if hasattr(j, "accumulate"))]

    def _has_force_generators(self) -> bool:
        """Whether :meth:`_force_generators` has any (without building the list each step)."""
        return bool(self.forces) or any(hasattr(j, "accumulate") for j in self.joints)

    def _check_masses(self) -> None:
        massless = (self.kind == DYNAMIC) & (self.mass <= 0)
        if massless.any():
            name = self.bodies[int(np.argmax(massless))].name
            raise ValueError(f"body {name!r}: a dynamic body needs shapes or a mass and moment")
        self._has_ccd = bool(self.ccd.any())
        self._checked = True

    def _constants_changed(self) -> None:
        self._has_constant = bool(self.const_force.any() or self.const_torque.any())

    def _step_euler(self, dt: float, explicit: bool) -> None:
        """Fast path: both Euler methods as two compiled passes around the solver (the whole
        step in one compiled call when the settings allow, ``collision.step_euler``)."""
        if collision.compiled(self):
            collision.step_euler(self, dt, explicit)
            return
        g = self.gravity
        args = (self.force, self.torque, self.inv_mass, self.inv_moment, g[0], g[1], dt)
        # the velocities before this step's gravity and forces: restitution reflects the
        # approach velocities measured with them (Box2D's prepare step)
        start = (self.vel.copy(), self.omega.copy())
        integrators.euler_velocities(self.kind, self.vel, self.omega, *args)
        self.manifolds = collision.solve_velocities(self, dt, start)
        dphi = self._dphi
        integrators.euler_positions(
            self.kind, self.com, self.vel, self.omega, *args, explicit, dphi
        )
        kind = self.orientation_kind
        orientation.integrate_rotations(kind, self.rot, dphi, self.settings.renormalise)
        orientation.cos_sin(kind, self.rot, self.cs)
        if self.manifolds is not None or self.joints:
            collision.solve_positions(self, self.manifolds, dt)

    def _step_numeric(self, dt: float) -> None:
        """Any integrator: free-motion increments, impulses in between (docs/architecture.md)."""
        s = self.settings
        moving = self.kind != STATIC
        dyn = self.kind == DYNAMIC
        phi = self.angles()
        accel = self._accelerations(self.force, self.torque)
        dp, dv, dphi, dw = integrators.INTEGRATORS[s.integrator](
            self.com, self.vel, phi, self.omega, accel, dt
        )
        kin = self.kind == KINEMATIC  # kinematic bodies move at their own velocity
        dp = np.where(kin[:, None], self.vel * dt, dp)
        dphi = np.where(kin, self.omega * dt, dphi)
        # the velocities before this step's gravity and forces: restitution reflects the
        # approach velocities measured with them (Box2D's prepare step)
        start = (self.vel.copy(), self.omega.copy())
        self.vel += np.where(dyn[:, None], dv, 0.0)
        self.omega += np.where(dyn, dw, 0.0)
        v_free, w_free = self.vel.copy(), self.omega.copy()

        self.manifolds = collision.solve_velocities(self, dt, start)

        dp = dp + (self.vel - v_free) * dt
        dphi = dphi + (self.omega - w_free) * dt
        dp[~moving] = 0.0
        dphi[~moving] = 0.0
        if self._has_ccd:
            collision.limit_ccd_motion(self, dp, dphi)
        self.com += dp
        orientation.integrate_rotations(self.orientation_kind, self.rot, dphi, s.renormalise)
        orientation.cos_sin(self.orientation_kind, self.rot, self.cs)
        self.force[:] = 0.0
        self.torque[:] = 0.0
        collision.solve_positions(self, self.manifolds, dt)

    def _step_analytic(self, dt: float) -> None:
        """p(t) = s + u t + a t^2 / 2, theta(t) = theta0 + omega0 t + alpha t^2 / 2 (slides)."""
        if self.joints or self.forces:
            raise ValueError("settings.integrator: analytic motion cannot have joints or forces")
        if self._analytic_ref is None:
            dyn = (self.kind == DYNAMIC)[:, None]
            a = np.where(dyn, self.gravity + self.force * self.inv_mass[:, None], 0.0)
            alpha = self.torque * self.inv_moment
            self._analytic_ref = (
                self.time,
                self.com.copy(),
                self.vel.copy(),
                a,
                self.angles(),
                self.omega.copy(),
                alpha,
            )
        t0, s0, u, a, th0, w0, alpha = self._analytic_ref
        t = self.time + dt - t0
        moving = self.kind != STATIC
        self.com[moving] = (s0 + u * t + 0.5 * a * t * t)[moving]
        self.vel[moving] = (u + a * t)[moving]
        self.omega[moving] = (w0 + alpha * t)[moving]
        theta = th0 + w0 * t + 0.5 * alpha * t * t
        orientation.set_angles(self.orientation_kind, self.rot, np.where(moving, theta, th0))
        orientation.cos_sin(self.orientation_kind, self.rot, self.cs)
        self.manifolds = None
        self.force[:] = 0.0
        self.torque[:] = 0.0

    # --- observation --------------------------------------------------------------------------
    def find_contacts(self) -> list:
        """Broadphase + narrowphase at the current state, without stepping (list of Contact)."""
        from sandbox import collision
        from sandbox.contact import contacts_from_manifolds

        manifolds = collision.detect(self, margin=0.0)
        return contacts_from_manifolds(manifolds, self.bodies)

    def kinetic_energy(self) -> float:
        """Sum of m |v|^2 / 2 + I omega^2 / 2 over dynamic bodies (J)."""
        dyn = self.kind == DYNAMIC
        v2 = np.sum(self.vel[dyn] ** 2, axis=1)
        return float(
            np.sum(0.5 * self.mass[dyn] * v2 + 0.5 * self.moment[dyn] * self.omega[dyn] ** 2)
        )

    def potential_energy(self) -> float:
        """Gravitational -m g . c over dynamic bodies, plus springs' k x^2 / 2 (J)."""
        dyn = self.kind == DYNAMIC
        pe = -float(np.sum(self.mass[dyn] * (self.com[dyn] @ self.gravity)))
        for item in (*self.joints, *self.forces):
            if hasattr(item, "potential_energy"):
                pe += item.potential_energy(self)
        return pe

    def energy(self) -> float:
        """Kinetic + potential (J)."""
        return self.kinetic_energy() + self.potential_energy()

    def momentum(self) -> np.ndarray:
        """Linear momentum sum m v of dynamic bodies (kg m/s)."""
        dyn = self.kind == DYNAMIC
        return np.sum(self.mass[dyn, None] * self.vel[dyn], axis=0)

    def angular_momentum(self, about=(0.0, 0.0)) -> float:
        """L = sum (r x m v + I omega) about a world point (default the origin) (kg m^2/s)."""
        dyn = self.kind == DYNAMIC
        r = self.com[dyn] - np.asarray(about, dtype=float)
        v = self.vel[dyn]
        m = self.mass[dyn]
        return float(
            np.sum(m * (r[:, 0] * v[:, 1] - r[:, 1] * v[:, 0]) + self.moment[dyn] * self.omega[dyn])
        )

    def orientation_drift(self) -> np.ndarray:
        """Per-body drift of the stored orientations (0 for scalar angles)."""
        return orientation.drift_of(self.orientation_kind, self.rot)

    def to_scene(self) -> dict:
        """The world as a scene-file dict (current state as the initial state)."""
        from sandbox.build import world_to_scene

        return world_to_scene(self)

    def __repr__(self) -> str:
        return f"World({self.name!r}, {len(self.bodies)} bodies, t={self.time:.4f})"
