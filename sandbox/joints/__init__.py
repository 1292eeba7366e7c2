"""Joints (slides, "Further Topics on Physics Animation": ball-and-socket, hinges, motors, springs).

- :class:`PinJoint`: a rod keeping two anchors at a fixed distance (``pin``)
- :class:`PivotJoint`: a hinge, anchors held together, optional angle limits and motor (``pivot``)
- :class:`SpringJoint`: a damped spring, a force generator (``spring``)

Anchors are in each body's origin frame (as in scene files). Pin and pivot joints are velocity
constraints solved by the world's solver with sequential impulses, accumulated and warm-started
across steps, plus a position pass (non-linear Gauss-Seidel, as Box2D) that removes the drift.
The solver interface, per step::

    for joint in world.joints: joint.prepare(world, dt)
    for joint in world.joints: joint.warm_start(world)
    for _ in range(settings.iterations):           # interleaved with contacts
        for joint in world.joints: joint.solve_velocity(world)
    ... positions move ...
    for _ in range(settings.position_iterations):
        error = max(joint.solve_position(world) for joint in world.joints)

A spring's solver methods do nothing: it acts through ``accumulate`` like a force generator.
Bodies sharing a joint do not collide with each other (as in the pymunk bridge): see
:func:`joined_pairs` and :func:`drop_joined`.
"""

from __future__ import annotations

import numpy as np

from sandbox.joints.base import Joint
from sandbox.joints.pin import PinJoint
from sandbox.joints.pivot import PivotJoint
from sandbox.joints.spring import SpringJoint

__all__ = [
    "Joint",
    "PinJoint",
    "PivotJoint",
    "SpringJoint",
    "drop_joined",
    "joined_pairs",
    "joint_from_dict",
]

TYPES = {"pin": PinJoint, "pivot": PivotJoint, "spring": SpringJoint}


def joint_from_dict(spec: dict, world) -> Joint:
    """A joint from its scene-file form (normalized by ``validate_scene``); bodies by name."""
    kind = spec["type"]
    if kind not in TYPES:
        raise ValueError(f"type: expected one of {', '.join(TYPES)}, got {kind!r}")
    a, b = world.body(spec["a"]), world.body(spec["b"])
    anchors = (spec.get("anchor_a", (0.0, 0.0)), spec.get("anchor_b", (0.0, 0.0)))
    if kind == "pin":
        return PinJoint(a, b, *anchors)
    if kind == "pivot":
        return PivotJoint(a, b, *anchors, limits=spec.get("limits"), motor=spec.get("motor"))
    return SpringJoint(
        a,
        b,
        *anchors,
        rest_length=spec.get("rest_length"),
        stiffness=spec["stiffness"],
        damping=spec.get("damping", 0.0),
    )


def joined_pairs(world) -> set[tuple[int, int]]:
    """Every pair of body indices (i, j), i < j, that shares a joint (springs included)."""
    return {joint.bodies() for joint in world.joints}


def drop_joined(world, pairs: np.ndarray, shape_body: np.ndarray) -> np.ndarray:
    """The rows of a broadphase pair list ``pairs`` (k, 2) of shape indices whose two bodies do
    not share a joint: what the collision code keeps before the narrowphase."""
    if not world.joints or len(pairs) == 0:
        return pairs
    joined = joined_pairs(world)
    ba, bb = shape_body[pairs[:, 0]], shape_body[pairs[:, 1]]
    keep = np.array(
        [
            (min(i, j), max(i, j)) not in joined
            for i, j in zip(ba.tolist(), bb.tolist(), strict=True)
        ],
        dtype=bool,
    )
    return pairs[keep] if not keep.all() else pairs
