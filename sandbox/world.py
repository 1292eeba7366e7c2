"""The world: every body's state in records, and the step (slides, "State Update").

The bodies are one array of BODY records (``world.state``), the orientations one array in the
settings' representation (``world.rot``), the shapes, joints and force generators arrays of
their records (:mod:`sandbox.records`); :class:`~sandbox.body.Body`, the joints and the force
generators are views of their rows. ``world.com``, ``world.vel`` and the other per-body arrays
are views of the record fields. A step runs the stages of :mod:`sandbox.step`.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

import sandbox.orientation as orientation
from sandbox.body import DYNAMIC, Body
from sandbox.compile_cache import step_kernel
from sandbox.contact import ContactBuffers, Manifolds, find_contacts
from sandbox.context import fill_context
from sandbox.copying import copy_fields
from sandbox.energy_growth import energy_limit
from sandbox.errors import SimulationError
from sandbox.forces import ForceGenerator
from sandbox.integrators import has_fields, work_arrays
from sandbox.jit import bound
from sandbox.projectile import advance_analytic
from sandbox.records import BODY, CONTEXT, GENERATOR, JOINT, SLEEPING
from sandbox.settings import Settings
from sandbox.shape_records import Geometry, build_geometry
from sandbox.sleep import wake_island
from sandbox.sleeping_contacts import keep_sleeping_contacts
from sandbox.staged_step import staged_step
from sandbox.step import fast_step, free_step, soft_step
from sandbox.world_building import Building
from sandbox.world_measures import Measures


class WorldArrays(NamedTuple):
    """Everything a step reads and writes, for :mod:`sandbox.step`."""

    bodies: np.ndarray
    rot: np.ndarray
    shapes: np.ndarray
    vertices: np.ndarray
    joints: np.ndarray
    generators: np.ndarray
    buffers: ContactBuffers
    context: np.ndarray
    work: np.ndarray | None  # the integrator's work arrays (None: no state-dependent force)


def _field(name: str) -> property:
    def get(self):
        return self.state[name]

    def put(self, value):
        self.state[name] = value

    return property(get, put, doc=f"Every body's ``{name}`` (a view of the BODY records).")


class World(Building, Measures):
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
        self._gravity = np.array(gravity, dtype=float)
        self.dt = float(dt)
        self.settings = Settings(**settings)
        self.time = 0.0
        self.steps = 0
        self.bodies: list[Body] = []
        self.joints: list = []
        self.forces: list = []
        self._timer = None  # a sandbox.staged_step.StageTimer: time every stage (the staged path)
        self._by_name: dict[str, Body] = {}
        self._python_forces: list = []  # force objects without a record: evaluated per step
        self._controlled: list[Body] = []
        self.state = self._state_store = np.zeros(0, dtype=BODY)
        self.rot = self._rot_store = np.zeros(
            (0, orientation.FLOATS_STORED[self.settings.orientation])
        )
        self.joint_table = np.zeros(0, dtype=JOINT)
        self.generator_table = np.zeros(0, dtype=GENERATOR)
        self.context = np.zeros(1, dtype=CONTEXT)
        self.context[0]["sweep_direction"] = -1
        self._geometry: Geometry | None = None
        self._buffers: ContactBuffers | None = None
        self._found_stats: dict | None = None
        self._analytic_ref = None
        self._dirty = True  # shapes, masses, joints, forces or settings changed: _prepare()
        self._energy_stale = True  # the closed-system energy bound must be taken again
        self._sleep = False
        self._fast = False
        self._work = None  # the integrator's work arrays (sandbox.integrators.work_arrays)
        self._step_dt = 0.0  # the dt the step context holds
        self._held = False  # a Manifolds view of the contact buffers was handed out
        self._run = None  # the way a step runs (see _choose_path)
        self.has_ccd = False
        self._watch_settings()

    # --- arrays -------------------------------------------------------------------------------
    kind = _field("kind")  # DYNAMIC, STATIC, KINEMATIC or SLEEPING
    com = _field("com")  # centre of mass (m)
    local_com = _field("local_com")  # centre of mass in the body frame (m)
    vel = _field("vel")  # m/s
    omega = _field("omega")  # rad/s
    cs = _field("cs")  # (cos, sin) of the angle
    mass = _field("mass")  # kg
    inv_mass = _field("inv_mass")
    moment = _field("moment")  # kg m^2
    inv_moment = _field("inv_moment")
    force = _field("force")  # N, accumulated for the coming step
    torque = _field("torque")  # N m
    const_force = _field("const_force")
    const_torque = _field("const_torque")
    applied_force = _field("applied_force")  # what the last step applied (N)
    applied_torque = _field("applied_torque")
    ccd = _field("ccd")

    @property
    def gravity(self) -> np.ndarray:
        """m/s^2; assign a new vector to change it (the step context is filled again)."""
        return self._gravity

    @gravity.setter
    def gravity(self, value) -> None:
        self._gravity = np.array(value, dtype=float)
        self._dirty = True

    @property
    def orientation_kind(self) -> int:
        return orientation.NAMES[self.settings.orientation]

    def arrays(self) -> WorldArrays:
        """The records a step works on (after :meth:`_prepare`)."""
        g = self.geometry()
        return WorldArrays(
            self.state,
            self.rot,
            g.table,
            g.vertices,
            self.joint_table,
            self.generator_table,
            self._buffers_for(g),
            self.context,
            self._work,
        )

    def geometry(self) -> Geometry:
        """Every shape as records (rebuilt after shapes or masses change)."""
        if self._geometry is None:
            self._geometry = build_geometry(self.bodies, self.local_com)
        return self._geometry

    def _buffers_for(self, g: Geometry) -> ContactBuffers:
        b = self._buffers
        if b is None or len(b.proxies) != len(g):
            b = self._buffers = ContactBuffers(len(g))
            ctx = self.context[0]
            ctx["sweep_direction"] = -1
            ctx["pairs_kept"] = False
            ctx["contact_count"][:] = 0  # the last step's sets and the sleeping islands' store
        return b

    def _constants_changed(self, i: int | None = None) -> None:
        """Constant forces are applied by the step itself: only wake the body."""
        self.wake(i)

    def _set_angle(self, i: int, angle: float) -> None:
        self.state[i]["angle"] = float(angle)
        orientation.place_bodies(self.state[i : i + 1], self.rot[i : i + 1], self.orientation_kind)
        self._state_changed(i)

    def _state_changed(self, i: int | None = None) -> None:
        """Body i (or any body, None) was moved or pushed by the program: wake it."""
        self._analytic_ref = None
        self.wake(i)

    def wake(self, body=None) -> None:
        """Wake a sleeping body's island (a Body, its index or its name), or every sleeping
        body (None). The world does this itself whenever the program moves or pushes a body,
        or changes a joint, a force, gravity or a setting (:mod:`sandbox.sleep`). The energy
        bound of a closed system is taken again (:mod:`sandbox.energy_growth`)."""
        self._energy_stale = True
        if not len(self.state):
            return
        if body is None:
            asleep = np.flatnonzero(self.sleeping)
        else:
            i = self.body(body).index if isinstance(body, str) else getattr(body, "index", body)
            asleep = [i] if self.kind[i] == SLEEPING else []
        for i in asleep:
            if self.kind[i] == SLEEPING:
                wake_island(self.state, int(self.state[i]["island"]))
        self.context[0]["awake"] = -1  # not known (a kinematic body may move): step again

    def angles(self) -> np.ndarray:
        """Every body's angle (rad), continuous: turns accumulate."""
        return self.state["angle"].copy()

    def origins(self) -> np.ndarray:
        """Every body's origin (n, 2): com - R local_com."""
        c, s = self.cs[:, 0], self.cs[:, 1]
        lc = self.local_com
        return self.com - np.stack(
            [c * lc[:, 0] - s * lc[:, 1], s * lc[:, 0] + c * lc[:, 1]], axis=1
        )

    # --- settings -----------------------------------------------------------------------------
    def _watch_settings(self) -> None:
        """Be told when a setting changes (the world adapts before the next step)."""
        try:
            self.settings._observer = self._setting_changed
        except AttributeError:  # pragma: no cover - a Settings without the hook
            pass

    def _setting_changed(self, name: str, old, new) -> None:
        if name == "orientation" and old != new:
            self._switch_orientation(new)
        self._dirty = True

    def _switch_orientation(self, name: str) -> None:
        """Store every body's orientation in representation ``name`` (from its angle)."""
        self.rot = self._rot_store = np.zeros((len(self.state), orientation.FLOATS_STORED[name]))
        orientation.place_bodies(self.state, self.rot, orientation.NAMES[name])

    def _prepare(self, dt: float) -> None:
        """Bring the records up to date after shapes, masses, joints, forces or settings
        changed (not every step)."""
        if self._dirty:
            self.wake()  # a joint, a force, gravity or a setting changed
        if self.rot.shape[1] != orientation.FLOATS_STORED[self.settings.orientation]:
            self._switch_orientation(self.settings.orientation)  # changed without being told
        massless = (self.kind == DYNAMIC) & (self.mass <= 0)
        if massless.any():
            name = self.bodies[int(np.argmax(massless))].name
            raise ValueError(f"body {name!r}: a dynamic body needs shapes or a mass and moment")
        self.arrays()  # geometry and buffers for the current shapes
        n = len(self.bodies)
        for joint in self.joints:
            joint.place(self)
        if len(self.joint_table):
            keys = np.minimum(self.joint_table["a"], self.joint_table["b"]) * n + np.maximum(
                self.joint_table["a"], self.joint_table["b"]
            )
            self.joint_table["pair_key"] = keys
            self.joint_table["sorted_key"] = np.sort(keys)
        masks = np.zeros(n, dtype=np.uint64)
        for g in self.forces:
            if isinstance(g, ForceGenerator):
                masks[g.targets(self)] |= np.uint64(1) << np.uint64(g.index)
        self.state["generators"] = masks
        self.has_ccd = bool(self.ccd.any())
        s = self.settings
        fields = has_fields(self.joint_table, self.generator_table)  # the step's own test
        self._fast = (
            s.broadphase == "sap" and s.solver in ("iterative", "soft") and not self.has_ccd
        )
        if not fields:
            self._work = None  # a constant a wherever a method looks: worked out body by body
        elif self._work is None or self._work.shape[1] != n:
            self._work = work_arrays(n)
        fill_context(self.context[0], self.settings, self.gravity, dt)
        self._step_dt = dt
        self._dirty = False
        self._energy_stale = True
        self._sleep = bool(self.settings.sleep)  # a plain bool: read every step
        self._choose_path()

    @property
    def timer(self):
        """A :class:`sandbox.staged_step.StageTimer` that times every stage of each step (the world
        then takes the staged path), or None (the default: the fastest path)."""
        return self._timer

    @timer.setter
    def timer(self, value) -> None:
        self._timer = value
        if not self._dirty:  # already prepared: take the path the timer asks for now
            self._choose_path()

    # --- the step -----------------------------------------------------------------------------
    def step(self, dt: float | None = None) -> None:
        """Advance the world by ``dt`` seconds (default: the world's dt)."""
        if dt is None:
            dt = self.dt
        else:
            dt = float(dt)
            if not dt > 0:
                raise ValueError("dt: must be > 0")
        if self._dirty or dt != self._step_dt:
            self._prepare(dt)
        for body in self._controlled:
            body.controller(body, self)
        if self._python_forces:
            self._python_force_step()
        if self._sleep and self.context[0]["awake"] == 0:
            self.time += dt  # everything sleeps and nothing kinematic moves: nothing to do
            self.steps += 1
            self.force[:], self.torque[:] = 0.0, 0.0
            return
        if self._held:
            self._held = self._buffers.release(1 - int(self.context[0]["contact_set"]))
        if self._energy_stale:  # a state the program set: the closed system's energy bound
            self.context[0]["energy_limit"] = energy_limit(self)
            self._energy_stale = bool(np.any(self.force) or np.any(self.torque))
        status = self._run()
        while status < 0:  # the pair buffer was too small: nothing moved yet
            self._buffers.reserve(-status)
            self._choose_path()
            status = self._run()
        self.time += dt
        self.steps += 1
        self._found_stats = None
        if status > 0:
            raise self._divergence(status - 1)
        if self._sleep and self.context[0]["fell_asleep"] and self.context[0]["warm_start"]:
            keep_sleeping_contacts(self.context[0], self._buffers.sets, self.state["kind"])

    def _choose_path(self) -> None:
        """How :meth:`step` runs the stages (after :meth:`_prepare` or a buffer grew): one
        compiled call for the usual world (:func:`sandbox.step.fast_step`, or ``free_step``
        when nothing can touch), the stages one by one otherwise, the closed form for
        ``integrator: analytic``."""
        s, g, b = self.settings, self._geometry, self._buffers
        if s.integrator == "analytic":
            self._run = lambda: advance_analytic(self, self._step_dt) or 0
            return
        fast = self._fast and self.timer is None
        model = (self.state, self.rot, g.table, g.vertices, self.joint_table, self.generator_table)
        kernel = step_kernel(len(g), len(self.joint_table), s.solver)
        if fast and kernel == "free_step":
            # the arrays the forces need, only if one depends on the state (free_step)
            fields = None if self._work is None else (*model[2:], self._work)
            self._run = bound(free_step, self.state, self.rot, self.context, fields)
        elif fast:
            args = (*model, b.sets, b.proxies, b.pairs, self.context, self._work)
            one_call = soft_step if kernel == "soft_step" else fast_step
            self._run = bound(one_call, *args)
        else:
            self._run = lambda: staged_step(self, self.timer)

    def _python_force_step(self) -> None:
        """Force objects without a record add their force at the step's starting state."""
        for g in self._python_forces:
            g.accumulate(
                self, self.com, self.vel, self.angles(), self.omega, self.force, self.torque
            )

    def _divergence(self, i: int) -> SimulationError:
        """The error for body i, whose state stopped being finite or which moves fastest in a
        closed system whose energy grew by orders of magnitude, with a likely cause."""
        from sandbox.divergence import likely_cause

        self._energy_stale = True  # a program that catches the error may set a new state
        return SimulationError(self.bodies[i].name, self.steps, likely_cause(self, i))

    # --- observation --------------------------------------------------------------------------
    @property
    def manifolds(self) -> Manifolds | None:
        """The contacts of the last step (a view of its CONTACT records), or None before the
        first step."""
        if self._buffers is None or self.steps == 0:
            return None
        self._held = True
        return self._buffers.manifolds(self.context[0])

    @property
    def stats(self) -> dict:
        """Counters from the last step or :meth:`find_contacts`: ``pair_tests``, ``pairs``,
        ``contacts``, ``contact_points``, ``warm_started_points`` (sweep and prune keeps its
        pairs while no shape leaves the box it was swept with, 2 cm larger than the contact
        margin needs: ``pair_tests`` is 0 in such a step, and ``pairs`` counts the kept ones,
        those within that spare margin too; and ``shock_layers``; and
        ``sweeps``, the velocity sweeps of the iterative and shock solvers: ``iterations``,
        more at a large dt, where they go on until the contacts hold; and ``position_passes``,
        the passes of the overlap fix: up to ``position_iterations``, fewer once no point
        overlaps more than ``position_tolerance`` or a pass stalls; and ``position_progress``,
        the fraction of the overlap the pass before the last took out, None after one pass)."""
        if self._found_stats is not None:
            return dict(self._found_stats)
        if self.steps == 0:
            return {}
        ctx = self.context[0]
        keys = ["pair_tests", "pairs", "contacts", "contact_points", "warm_started_points"]
        keys.append("position_passes")
        if self.settings.solver == "shock":
            keys.append("shock_layers")
        if self.settings.solver in ("iterative", "shock"):
            keys.append("sweeps")
        stats: dict = {key: int(ctx[key]) for key in keys}
        progress = float(ctx["position_progress"])  # NaN: one pass, nothing to compare
        stats["position_progress"] = None if math.isnan(progress) else progress
        return stats

    def find_contacts(self) -> list:
        """Broadphase + narrowphase at the current state, without stepping (list of Contact);
        also fills :attr:`stats` (see :func:`sandbox.contact.find_contacts`)."""
        if self._dirty:
            self._prepare(self.dt)
        contacts, self._found_stats = find_contacts(self)
        return contacts

    def to_scene(self) -> dict:
        """The world as a scene-file dict (current state as the initial state)."""
        from sandbox.scene_export import world_to_scene

        return world_to_scene(self)

    def __deepcopy__(self, memo: dict) -> World:
        """``copy.deepcopy(world)``: every part copied (:mod:`sandbox.copying`); the copy
        watches its own settings (a copied Settings carries no observer), and the way a step
        runs is chosen again for its own arrays (the original's is bound to the original's:
        stepping the copy moved the original's bodies)."""
        new = copy_fields(self, memo)
        new._watch_settings()
        if new._run is not None:
            new._choose_path()
        return new

    def __repr__(self) -> str:
        return f"World({self.name!r}, {len(self.bodies)} bodies, t={self.time:.4f})"
