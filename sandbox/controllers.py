"""User and agent input (slides, "User / Agent Input": a user or an AI steering a simulated
vehicle; the input ends up as applied forces, and forces are the source of linear and angular
acceleration).

A controller is any callable ``controller(body, world)``; set ``body.controller = ...`` and the
world calls it at the start of every step, before the forces are integrated. It steers by
applying forces at points and torques for that step::

    body.apply_force(f, point)   # N at a world point: a = f / m, and tau = r x f (slides, "Torque")
    body.apply_torque(t)         # N m: alpha = tau / I

This module offers a :class:`Thruster` (a bounded push at a fixed point of the body, along a fixed
body direction), a PD "go to target" autopilot for a lander with two thrusters
(:class:`LanderController`), and :class:`Scripted`, which replays a time-stamped list of
commands (what a recorded user, or the autopilot's own log, did).
"""

from __future__ import annotations

import bisect
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np


def _rotate(angle: float, v) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([c * v[0] - s * v[1], s * v[0] + c * v[1]])


@dataclass
class Thruster:
    """A push of 0..``max_thrust`` N at ``point`` (body origin frame, m) along ``direction``
    (body frame, unit vector; default the body's +y axis, "up" when the body is level)."""

    point: tuple[float, float]
    direction: tuple[float, float] = (0.0, 1.0)
    max_thrust: float = 10.0

    def fire(self, body, thrust: float) -> float:
        """Apply ``thrust`` (clamped to 0..max_thrust) for this step; returns the thrust used."""
        thrust = min(max(float(thrust), 0.0), self.max_thrust)
        if thrust > 0.0:
            angle = body.angle
            d = np.asarray(self.direction, dtype=float)
            force = _rotate(angle, d / np.hypot(*d)) * thrust
            body.apply_force(force, point=body.world_point(self.point))  # tau = r x f
        return thrust


def lander_thrusters(width: float, height: float, max_thrust: float) -> list[Thruster]:
    """Two thrusters under the bottom corners of a ``width`` x ``height`` box, pushing up."""
    return [
        Thruster((-0.5 * width, -0.5 * height), (0.0, 1.0), max_thrust),
        Thruster((0.5 * width, -0.5 * height), (0.0, 1.0), max_thrust),
    ]


@dataclass
class LanderController:
    """PD autopilot flying a two-thruster lander to ``target`` (m, world position of its origin).

    Each step (slides, "Force": f = m a; "Torque": tau = I alpha):

    1. desired acceleration a* = kp (target - p) - kd v - g (hover plus a spring-damper pull);
    2. tilt the thrust towards a*: desired angle theta* = atan2(-a*_x, a*_y), within
       +-``max_tilt``; desired torque tau* = I (kp_angle (theta* - theta) - kd_angle omega);
    3. total thrust T = m (a* . up), split between the left and right thrusters so that
       (T_right - T_left) * arm = tau*, each clamped to 0..max_thrust (the bound can win).

    ``log`` keeps one row per step: (t, left thrust, right thrust), the commands :class:`Scripted`
    can replay.
    """

    target: tuple[float, float]
    thrusters: Sequence[Thruster]
    kp: float = 3.0  # 1/s^2
    kd: float = 3.5  # 1/s (about critical damping: kd^2 ~ 4 kp)
    kp_angle: float = 40.0  # 1/s^2
    kd_angle: float = 12.0  # 1/s
    max_tilt: float = 0.5  # rad
    log: list[tuple[float, float, float]] = field(default_factory=list)

    def commands(self, body, world) -> tuple[float, float]:
        """(left, right) thrust (N) the autopilot asks for now, before clamping."""
        p = np.asarray(body.position)
        v = np.asarray(body.velocity)
        a = self.kp * (np.asarray(self.target, dtype=float) - p) - self.kd * v - world.gravity
        tilt = math.atan2(-a[0], a[1]) if a[1] > 0.0 else 0.0
        tilt = min(max(tilt, -self.max_tilt), self.max_tilt)
        theta, omega = body.angle, body.angular_velocity
        torque = body.moment * (self.kp_angle * (tilt - theta) - self.kd_angle * omega)
        up = _rotate(theta, (0.0, 1.0))
        total = max(body.mass * float(a @ up), 0.0)
        left, right = self.thrusters
        arm = 0.5 * abs(right.point[0] - left.point[0])
        diff = torque / arm if arm > 0 else 0.0
        return 0.5 * (total - diff), 0.5 * (total + diff)

    def __call__(self, body, world) -> None:
        left, right = self.commands(body, world)
        used = (self.thrusters[0].fire(body, left), self.thrusters[1].fire(body, right))
        self.log.append((world.time, *used))


class Scripted:
    """Replay time-stamped commands: ``[(t0, command0), (t1, command1), ...]`` (t in s).

    The command whose time is the latest not after ``world.time`` is held until the next one
    (zero-order hold); before the first, nothing is applied. A command is either

    - a sequence of thrusts, one per thruster in ``thrusters``, or
    - a dict with any of ``force`` (N, world frame), ``point`` (body origin frame, m, where the
      force acts; default the centre of mass), ``torque`` (N m).

    ``log`` keeps (t, *values applied) per step, like :class:`LanderController`.
    """

    def __init__(self, commands: Sequence, thrusters: Sequence[Thruster] | None = None) -> None:
        pairs = sorted(((float(t), c) for t, c in commands), key=lambda tc: tc[0])
        self.times = [t for t, _ in pairs]
        self.commands = [c for _, c in pairs]
        self.thrusters = list(thrusters) if thrusters is not None else None
        self.log: list[tuple] = []

    @classmethod
    def from_log(cls, log: Sequence[Sequence[float]], thrusters: Sequence[Thruster]) -> Scripted:
        """A replay of a controller's ``log`` rows (t, thrust 1, thrust 2, ...)."""
        return cls([(row[0], tuple(row[1:])) for row in log], thrusters)

    def current(self, time: float):
        """The command in force at ``time`` (s), or None."""
        k = bisect.bisect_right(self.times, time + 1e-9) - 1
        return self.commands[k] if k >= 0 else None

    def __call__(self, body, world) -> None:
        command = self.current(world.time)
        if command is None:
            self.log.append((world.time,))
            return
        if self.thrusters is not None:
            used = [t.fire(body, x) for t, x in zip(self.thrusters, command, strict=True)]
            self.log.append((world.time, *used))
            return
        force = np.asarray(command.get("force", (0.0, 0.0)), dtype=float)
        point = command.get("point")
        body.apply_force(force, None if point is None else body.world_point(point))
        torque = float(command.get("torque", 0.0))
        if torque:
            body.apply_torque(torque)
        self.log.append((world.time, *force.tolist(), torque))


def chain(*controllers: Callable) -> Callable:
    """One controller running several in turn (e.g. an autopilot plus a scripted gust)."""

    def run(body, world) -> None:
        for c in controllers:
            c(body, world)

    return run
