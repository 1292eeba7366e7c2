"""What every joint shares: two bodies, two anchors, a JOINT record, and the compiled helpers
the joint solvers use on it.

Anchors are given in each body's ORIGIN frame (as in the scene file); the record keeps them
about each body's centre of mass (``local_a``, ``local_b``), so an anchor's lever arm is
r = R(angle) local and its world position com + r (``docs/architecture.md``, "Body state").

A :class:`Joint` object is a view of its row of the world's joint records (``world.joint_table``),
as a :class:`~sandbox.body.Body` is a view of its body record; before it joins a world it keeps a
record of its own.
"""

from __future__ import annotations

import math

import numpy as np

from sandbox.jit import njit
from sandbox.math2d import cross, exchange, nudge, relative_velocity, rotate
from sandbox.records import DYNAMIC, JOINT

# Box2D's tuning of the position pass (b2_linearSlop and b2_maxLinearCorrection); the angular slop
# is smaller than Box2D's 2 degrees so that angle limits hold to about half a degree.
MAX_LINEAR_CORRECTION = 0.2  # m moved per position pass at most
ANGULAR_SLOP = math.radians(0.5)  # rad of limit overlap left alone (keeps the limit active)
MAX_ANGULAR_CORRECTION = math.radians(8.0)  # rad turned per position pass at most
MAX_ARC_TURN = 0.1  # rad per step: the arc correction stops growing past this turn


# --- compiled helpers over the records --------------------------------------------------------
@njit
def arm(body, local) -> tuple[float, float]:
    """World-frame arm r = R(angle) local from the body's centre of mass (m)."""
    return rotate(body["cs"][0], body["cs"][1], local[0], local[1])


@njit
def inverse_masses(j, bodies) -> tuple[float, float, float, float]:
    """(1/m_a, 1/I_a, 1/m_b, 1/I_b) of a joint's two bodies."""
    a, b = bodies[j["a"]], bodies[j["b"]]
    return a["inv_mass"], a["inv_moment"], b["inv_mass"], b["inv_moment"]


@njit
def anchor_velocity(va, ra, vb, rb) -> tuple[float, float]:
    """Relative velocity of the anchors: vb + wb x rb - va - wa x ra (m/s)."""
    return relative_velocity(va, ra[0], ra[1], vb, rb[0], rb[1])


@njit
def apply_joint_impulse(va, vb, mass, ra, rb, px: float, py: float, angular: float):
    """Impulse P on b at rb and -P on a at ra (:func:`sandbox.math2d.exchange`: v += P / m,
    w += (r x P) / I), plus an angular impulse on b (-it on a), w += angular / I (slides,
    "Effects of Force" / "Effects of Torque" as impulses, the change of momentum)."""
    va, vb = exchange(va, vb, mass, ra, rb, px, py)
    if angular != 0.0:
        va = (va[0], va[1], va[2] - mass[1] * angular)
        vb = (vb[0], vb[1], vb[2] + mass[3] * angular)
    return va, vb


@njit
def move_joint_bodies(j, bodies, ra, rb, px: float, py: float, angular: float) -> None:
    """The position-pass twin of :func:`apply_joint_impulse`: a pseudo impulse moves the
    centres of mass and turns the bodies (:func:`sandbox.math2d.nudge`)."""
    mass = inverse_masses(j, bodies)
    a, b = bodies[j["a"]], bodies[j["b"]]
    nudge(a, -mass[0] * px, -mass[0] * py, -mass[1] * (cross(ra[0], ra[1], px, py) + angular))
    nudge(b, mass[2] * px, mass[2] * py, mass[3] * (cross(rb[0], rb[1], px, py) + angular))


@njit
def arc_error(rx: float, ry: float, turn: float) -> tuple[float, float]:
    """How far the linear step r + (w dt) x r misses the arm's true end R(w dt) r (m).

    About -(w dt)^2 r / 2: the centripetal part a velocity-level constraint leaves out. The turn
    is clamped to +-``MAX_ARC_TURN`` so a wildly spinning body cannot feed it back on itself.
    """
    d = min(max(turn, -MAX_ARC_TURN), MAX_ARC_TURN)
    c, s = math.cos(d), math.sin(d)
    return c * rx - s * ry - rx + d * ry, s * rx + c * ry - ry - d * rx


# --- the Python view --------------------------------------------------------------------------
class Joint:
    """Base class: bodies ``a`` and ``b``, anchors in each body's origin frame (m)."""

    type = "joint"
    code = -1  # the JOINT record's kind

    def __init__(self, a, b, anchor_a=(0.0, 0.0), anchor_b=(0.0, 0.0)) -> None:
        if a is b:
            raise ValueError(f"a joint needs two different bodies, got {a.name!r} twice")
        self.a, self.b = a, b
        self.anchor_a = np.array(anchor_a, dtype=float).reshape(2)
        self.anchor_b = np.array(anchor_b, dtype=float).reshape(2)
        for name, value in (("anchor_a", self.anchor_a), ("anchor_b", self.anchor_b)):
            if not np.all(np.isfinite(value)):
                raise ValueError(f"{name}: expected finite numbers, got {value.tolist()}")
        self.world = None
        self.index = -1
        self._own = np.zeros(1, dtype=JOINT)
        self._own[0]["kind"] = self.code

    @property
    def record(self):
        """This joint's JOINT record (in the world's table once attached)."""
        if self.world is None:
            return self._own[0]
        return self.world.joint_table[self.index]

    # --- building -----------------------------------------------------------------------------
    def attach(self, world) -> None:
        """Check the bodies belong to ``world`` and that one of them can move (the world then
        adds the record, see ``World.add_joint``)."""
        for name, body in (("a", self.a), ("b", self.b)):
            if body.world is not world:
                raise ValueError(f"{name}: body {body.name!r} is not in this world")
        if world.kind[self.a.index] != DYNAMIC and world.kind[self.b.index] != DYNAMIC:
            raise ValueError(
                f"a joint needs at least one dynamic body, got {self.a.name!r} ({self.a.type}) "
                f"and {self.b.name!r} ({self.b.type})"
            )

    def place(self, world) -> None:
        """Write the bodies and the anchors about their centres of mass into the record (after
        the joint joined ``world``, and again whenever a body's centre of mass moved)."""
        r = self.record
        r["a"], r["b"] = self.a.index, self.b.index
        r["local_a"] = self.anchor_a - world.local_com[self.a.index]
        r["local_b"] = self.anchor_b - world.local_com[self.b.index]

    def attached(self, world) -> None:
        """Called once the record is in the world's table: fix what depends on the pose."""

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
        r = self.record
        out = []
        for i, local in ((self.ia, r["local_a"]), (self.ib, r["local_b"])):
            c, s = w.cs[i]
            x, y = c * local[0] - s * local[1], s * local[0] + c * local[1]
            out.append(np.array([w.com[i, 0] + x, w.com[i, 1] + y]))
        return out[0], out[1]

    def anchor_distance(self, world=None) -> float:
        """Distance between the two anchors (m)."""
        pa, pb = self.world_anchors(world)
        return float(math.hypot(*(pb - pa)))

    def anchor_error(self, world=None) -> float:
        """How far the joint is from holding (m); 0 when satisfied."""
        raise NotImplementedError

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self.a.name!r}, {self.b.name!r})"
