"""Sleeping islands (``settings.sleep``; as Box2D and pymunk do): bodies at rest cost nothing.

Bodies joined by contacts (touching or about to, within the contact margin) and joints form
*islands* (found with a union-find over this step's contacts and the joints; static and kinematic bodies do not join islands). A body slower than
``LINEAR_TOLERANCE`` (m/s) and ``ANGULAR_TOLERANCE`` (rad/s) counts up its ``sleep_time``;
when every body of an island has been that slow for ``TIME_TO_SLEEP`` (s), the whole island
sleeps: its velocities are set to zero and it becomes immovable (kind ``SLEEPING``, its inverse
mass and moment put aside), so the step neither moves nor solves it, and the broadphase leaves
out pairs of sleeping and static bodies, as it does for two static bodies.

An island wakes when an awake body touches one of its bodies (checked right after the
narrowphase, before anything is solved), and when the program pushes, moves or changes one of
its bodies (``World.wake``). When nothing is awake and nothing kinematic moves, the world
skips the step altogether.

A sleeping island keeps its contacts, as in Box2D: when it falls asleep, its contacts (with
their impulses) go to a third contact set, the *store*, and when it wakes its contacts are warm
started from there (:mod:`sandbox.sleeping_contacts`). Without that, a pile that woke began
from zero impulses, sagged and slid for a few steps, and a box dropped on it left it up to 15 mm
from where the same box left the pile kept awake (0.45 mm with the store).
"""

from __future__ import annotations

import numpy as np

from sandbox.jit import njit
from sandbox.records import DYNAMIC, KINEMATIC, SLEEPING

LINEAR_TOLERANCE = 0.05  # m/s (Box2D's b2_linearSleepTolerance)
ANGULAR_TOLERANCE = np.radians(2.0)  # rad/s (Box2D's b2_angularSleepTolerance)
TIME_TO_SLEEP = 0.5  # s (Box2D's b2_timeToSleep)


@njit
def root(parent, i: int) -> int:
    """The representative of i's island (union-find with path halving)."""
    while parent[i] != i:
        parent[i] = parent[parent[i]]
        i = parent[i]
    return i


@njit
def join(parent, bodies, a: int, b: int) -> None:
    """Put bodies a and b in one island, if both can move."""
    if bodies[a]["kind"] == DYNAMIC and bodies[b]["kind"] == DYNAMIC:
        ra, rb = root(parent, a), root(parent, b)
        if ra != rb:
            parent[max(ra, rb)] = min(ra, rb)


@njit
def find_islands(contacts, k: int, joints, bodies) -> None:
    """Every awake body's island (``BODY["island"]``: the smallest index of its island)."""
    n = bodies.shape[0]
    parent = np.arange(n)
    for i in range(k):
        join(parent, bodies, contacts[i]["a"], contacts[i]["b"])
    for j in range(joints.shape[0]):
        join(parent, bodies, joints[j]["a"], joints[j]["b"])
    for i in range(n):
        if bodies[i]["kind"] == DYNAMIC:  # a sleeping body keeps the island it fell asleep in
            bodies[i]["island"] = root(parent, i)


@njit
def wake_body(b) -> None:
    """A sleeping body moves again: its inverse mass and moment back, kind dynamic."""
    if b["kind"] == SLEEPING:
        b["kind"] = DYNAMIC
        b["inv_mass"], b["inv_moment"] = b["sleep_inv_mass"], b["sleep_inv_moment"]
    b["sleep_time"] = 0.0


@njit(python=True)
def wake_island(bodies, island: int) -> int:
    """Wake every body of an island; returns how many were asleep."""
    woken = 0
    for i in range(bodies.shape[0]):
        if bodies[i]["island"] == island:
            woken += bodies[i]["kind"] == SLEEPING
            wake_body(bodies[i])
    return woken


@njit
def wake_touched(contacts, k: int, bodies) -> int:
    """Wake the islands of sleeping bodies an awake body touches (right after the
    narrowphase). Returns how many bodies woke."""
    woken = 0
    for i in range(k):
        a, b = bodies[contacts[i]["a"]], bodies[contacts[i]["b"]]
        for sleeper, other in ((a, b), (b, a)):
            if sleeper["kind"] == SLEEPING and (
                other["kind"] == DYNAMIC or moving_kinematic(other)
            ):
                woken += wake_island(bodies, sleeper["island"])
    return woken


@njit
def moving_kinematic(b) -> bool:
    """A kinematic body that moves (it keeps what it touches awake)."""
    return b["kind"] == KINEMATIC and (
        b["vel"][0] != 0.0 or b["vel"][1] != 0.0 or b["omega"] != 0.0
    )


@njit
def fall_asleep(contacts, k: int, joints, bodies, dt: float) -> tuple[int, int]:
    """After a step: count each slow body's time at rest, find the islands, and put to sleep
    every island whose bodies have all been at rest for ``TIME_TO_SLEEP``. Returns the number
    of bodies that will move next step (awake dynamic ones and moving kinematic ones) and the
    number that fell asleep now."""
    n = bodies.shape[0]
    for i in range(n):
        b = bodies[i]
        if b["kind"] != DYNAMIC:
            continue
        v2 = b["vel"][0] ** 2 + b["vel"][1] ** 2
        slow = v2 < LINEAR_TOLERANCE**2 and b["omega"] ** 2 < ANGULAR_TOLERANCE**2
        b["sleep_time"] = b["sleep_time"] + dt if slow else 0.0
    find_islands(contacts, k, joints, bodies)
    rested = np.full(n, np.inf)  # per island root: the shortest time at rest of its bodies
    for i in range(k):  # an island touching a moving kinematic body stays awake
        a, b = bodies[contacts[i]["a"]], bodies[contacts[i]["b"]]
        if moving_kinematic(a):
            rested[b["island"]] = 0.0
        if moving_kinematic(b):
            rested[a["island"]] = 0.0
    for i in range(n):
        if bodies[i]["kind"] == DYNAMIC:
            island = bodies[i]["island"]
            rested[island] = min(rested[island], bodies[i]["sleep_time"])
    awake = fell = 0
    for i in range(n):
        b = bodies[i]
        if b["kind"] != DYNAMIC:
            awake += moving_kinematic(b)
            continue
        if rested[b["island"]] >= TIME_TO_SLEEP:
            fell += 1
            b["kind"] = SLEEPING
            b["sleep_inv_mass"], b["sleep_inv_moment"] = b["inv_mass"], b["inv_moment"]
            b["inv_mass"] = b["inv_moment"] = 0.0
            b["vel"][0] = b["vel"][1] = b["omega"] = 0.0
        else:
            awake += 1
    return awake, fell


@njit
def anything_moves(bodies) -> bool:
    """Whether a step would change anything: an awake dynamic body or a moving kinematic one."""
    for i in range(bodies.shape[0]):
        if bodies[i]["kind"] == DYNAMIC or moving_kinematic(bodies[i]):
            return True
    return False
