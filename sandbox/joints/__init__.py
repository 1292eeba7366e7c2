"""Joints (slides, "Further Topics on Physics Animation": ball-and-socket, hinges, motors, springs).

- :class:`PinJoint`: a rod keeping two anchors at a fixed distance (``pin``)
- :class:`PivotJoint`: a hinge, anchors held together, optional angle limits and motor (``pivot``)
- :class:`SpringJoint`: a damped spring, a force generator (``spring``)

Anchors are in each body's origin frame (as in scene files). Each joint object is a view of
its JOINT record in the world (``world.joint_table``); the step's joint stages
(:mod:`sandbox.joints.solve`) work on the records. Pin and pivot joints are velocity
constraints solved with sequential impulses, accumulated and warm-started across steps, plus a
position pass (non-linear Gauss-Seidel, as Box2D) that removes the drift. A spring is a force
(:func:`sandbox.joints.spring.spring_force`). Bodies sharing a joint do not collide with each
other (as in the pymunk bridge): see :func:`sandbox.narrowphase.joined`.
"""

from __future__ import annotations

from sandbox.joints.base import Joint
from sandbox.joints.pin import PinJoint
from sandbox.joints.pivot import PivotJoint
from sandbox.joints.spring import SpringJoint

__all__ = ["Joint", "PinJoint", "PivotJoint", "SpringJoint", "joined_pairs", "joint_from_dict"]

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
