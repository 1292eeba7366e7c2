"""What every joint shares: two bodies, two anchors, and small helpers on the world's arrays.

Anchors are given in each body's ORIGIN frame (as in the scene file); the world keeps body state
about the centre of mass, so an anchor's lever arm is r = R(angle) (anchor - local_com) and its
world position com + r (``docs/architecture.md``, "Body state").
"""

from __future__ import annotations

import math

import numpy as np

from sandbox import orientation
from sandbox.body import DYNAMIC, Body

# Box2D's tuning of the position pass (b2_linearSlop and b2_maxLinearCorrection); the angular slop
# is smaller than Box2D's 2 degrees so that angle limits hold to about half a degree.
MAX_LINEAR_CORRECTION = 0.2  # m moved per position pass at most
ANGULAR_SLOP = math.radians(0.5)  # rad of limit overlap left alone (keeps the limit active)
MAX_ANGULAR_CORRECTION = math.radians(8.0)  # rad turned per position pass at most
MAX_ARC_TURN = 0.1  # rad per step: the arc correction stops growing past this turn


_TURN = np.zeros(1)  # scratch for turn()


def cross(ax: float, ay: float, bx: float, by: float) -> float:
    """2D cross product a x b (a scalar): slides, "Torque", tau = r x f."""
    return ax * by - ay * bx


def lever(world, i: int, anchor) -> tuple[float, float]:
    """World-frame arm r = R(angle_i) (anchor - local_com_i) from body i's centre of mass (m)."""
    cs, lc = world.cs, world.local_com
    c, s = cs.item(i, 0), cs.item(i, 1)
    qx = anchor[0] - lc.item(i, 0)
    qy = anchor[1] - lc.item(i, 1)
    return c * qx - s * qy, s * qx + c * qy


def arc_error(r: tuple[float, float], turn: float) -> tuple[float, float]:
    """How far the linear step r + (w dt) x r misses the arm's true end R(w dt) r (m).

    About -(w dt)^2 r / 2: the centripetal part a velocity-level constraint leaves out. The turn
    is clamped to +-``MAX_ARC_TURN`` so a wildly spinning body cannot feed it back on itself.
    """
    d = min(max(turn, -MAX_ARC_TURN), MAX_ARC_TURN)
    c, s = math.cos(d), math.sin(d)
    return c * r[0] - s * r[1] - r[0] + d * r[1], s * r[0] + c * r[1] - r[1] - d * r[0]


def turn(world, i: int, dphi: float) -> None:
    """Turn body i by ``dphi`` radians in the world's orientation representation (position pass)."""
    if dphi == 0.0:
        return
    kind = world.orientation_kind
    row = world.rot[i : i + 1]
    _TURN[0] = dphi
    orientation.integrate_rotations(kind, row, _TURN, world.settings.renormalise)
    orientation.cos_sin(kind, row, world.cs[i : i + 1])


def body_angle(world, i: int) -> float:
    """Angle of body i (rad, in [-pi, pi]) from its (cos, sin)."""
    return math.atan2(world.cs.item(i, 1), world.cs.item(i, 0))


def unwrap(angle: float, near: float) -> float:
    """The value of ``angle`` (mod 2 pi) closest to ``near``: keeps a relative angle continuous."""
    return near + math.remainder(angle - near, math.tau)


class Joint:
    """Base class: bodies ``a`` and ``b``, anchors in each body's origin frame (m).

    Subclasses implement the solver interface (called by ``sandbox.solvers``): ``prepare(world,
    dt)`` once per step, ``warm_start(world)``, ``solve_velocity(world)`` once per velocity
    iteration and ``solve_position(world) -> float`` once per position iteration.
    """

    type = "joint"

    def __init__(self, a: Body, b: Body, anchor_a=(0.0, 0.0), anchor_b=(0.0, 0.0)) -> None:
        if a is b:
            raise ValueError(f"a joint needs two different bodies, got {a.name!r} twice")
        self.a, self.b = a, b
        self.anchor_a = np.array(anchor_a, dtype=float).reshape(2)
        self.anchor_b = np.array(anchor_b, dtype=float).reshape(2)
        self._qa = (float(self.anchor_a[0]), float(self.anchor_a[1]))  # plain floats for speed
        self._qb = (float(self.anchor_b[0]), float(self.anchor_b[1]))
        self.world = None
        self._i = self._j = -1
        self._ma = self._mb = self._ja = self._jb = 0.0
        for name, value in (("anchor_a", self.anchor_a), ("anchor_b", self.anchor_b)):
            if not np.all(np.isfinite(value)):
                raise ValueError(f"{name}: expected finite numbers, got {value.tolist()}")

    # --- building -----------------------------------------------------------------------------
    def attach(self, world) -> None:
        """Check the bodies belong to ``world`` and that one of them can move."""
        for name, body in (("a", self.a), ("b", self.b)):
            if body.world is not world:
                raise ValueError(f"{name}: body {body.name!r} is not in this world")
        if world.kind[self.a.index] != DYNAMIC and world.kind[self.b.index] != DYNAMIC:
            raise ValueError(
                f"a joint needs at least one dynamic body, got {self.a.name!r} ({self.a.type}) "
                f"and {self.b.name!r} ({self.b.type})"
            )
        self.world = world

    @property
    def ia(self) -> int:
        return self.a.index

    @property
    def ib(self) -> int:
        return self.b.index

    def bodies(self) -> tuple[int, int]:
        """The joined pair of body indices, smaller first."""
        i, j = self.a.index, self.b.index
        return (i, j) if i < j else (j, i)

    def _anchors_dict(self) -> dict:
        return {
            "type": self.type,
            "a": self.a.name,
            "b": self.b.name,
            "anchor_a": self.anchor_a.tolist(),
            "anchor_b": self.anchor_b.tolist(),
        }

    # --- geometry -----------------------------------------------------------------------------
    def world_anchors(self, world=None) -> tuple[np.ndarray, np.ndarray]:
        """World positions of the two anchors (m)."""
        w = world if world is not None else self.world
        ra, rb = lever(w, self.ia, self._qa), lever(w, self.ib, self._qb)
        return w.com[self.ia] + ra, w.com[self.ib] + rb

    def anchor_error(self, world=None) -> float:
        """How far the joint is from holding (m); 0 when satisfied."""
        raise NotImplementedError

    # --- solver interface (no-ops here; force-like joints keep them) ---------------------------
    def prepare(self, world, dt: float) -> None:
        """Once per step, before the velocity iterations: arms, effective masses."""

    def warm_start(self, world) -> None:
        """Apply last step's accumulated impulses (``settings.warm_start``)."""

    def solve_velocity(self, world) -> None:
        """One velocity iteration: an impulse that makes the velocity constraint hold."""

    def solve_position(self, world) -> float:
        """One position iteration (after positions moved); returns the error found (m)."""
        return 0.0

    # --- applying impulses --------------------------------------------------------------------
    def _load_masses(self, world) -> None:
        """Cache indices and inverse masses as plain floats for this step's solver calls."""
        self._i, self._j = self.a.index, self.b.index
        self._ma, self._mb = float(world.inv_mass[self._i]), float(world.inv_mass[self._j])
        self._ja, self._jb = float(world.inv_moment[self._i]), float(world.inv_moment[self._j])

    def _apply(self, world, px: float, py: float, ra, rb, ang: float = 0.0) -> None:
        """Impulse P on b at rb and -P on a at ra, plus an angular impulse ``ang`` on b (-ang on a).

        v += P / m, omega += (r x P) / I (slides, "Effects of Force" / "Effects of Torque" as
        impulses: the change of momentum).
        """
        i, j, vel, om = self._i, self._j, world.vel, world.omega
        vel[i, 0] = vel.item(i, 0) - self._ma * px
        vel[i, 1] = vel.item(i, 1) - self._ma * py
        om[i] = om.item(i) - self._ja * (ra[0] * py - ra[1] * px + ang)
        vel[j, 0] = vel.item(j, 0) + self._mb * px
        vel[j, 1] = vel.item(j, 1) + self._mb * py
        om[j] = om.item(j) + self._jb * (rb[0] * py - rb[1] * px + ang)

    def _move(self, world, px: float, py: float, ra, rb, ang: float = 0.0) -> None:
        """The position-pass twin of :meth:`_apply`: a pseudo impulse moves com and angle."""
        i, j, com = self._i, self._j, world.com
        com[i, 0] = com.item(i, 0) - self._ma * px
        com[i, 1] = com.item(i, 1) - self._ma * py
        turn(world, i, -self._ja * (ra[0] * py - ra[1] * px + ang))
        com[j, 0] = com.item(j, 0) + self._mb * px
        com[j, 1] = com.item(j, 1) + self._mb * py
        turn(world, j, self._jb * (rb[0] * py - rb[1] * px + ang))

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self.a.name!r}, {self.b.name!r})"
