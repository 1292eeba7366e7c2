"""Scene dict (validated, see :mod:`sandbox.scene`) to :class:`~sandbox.world.World`; the way
back is :func:`sandbox.scene_export.world_to_scene`."""

from __future__ import annotations

from sandbox.body import Body
from sandbox.scene_export import world_to_scene
from sandbox.shapes import shape_from_dict
from sandbox.world import World


def build_world(spec: dict) -> World:
    """A world holding the scene ``spec`` (a normalized dict from ``validate_scene``)."""
    world = World(
        gravity=spec["gravity"],
        dt=spec["dt"],
        name=spec.get("name", "scene"),
        **spec["settings"],  # the contract keys and any other setting the scene gives
    )
    for b in spec["bodies"]:
        body = Body(
            name=b["name"],
            type=b["type"],
            position=b["position"],
            angle=b["angle"],
            velocity=b["velocity"],
            angular_velocity=b["angular_velocity"],
            mass=b.get("mass"),
            moment=b.get("moment"),
            ccd=b.get("ccd", False),
            force=b.get("force", (0.0, 0.0)),
            torque=b.get("torque", 0.0),
        )
        for s in b["shapes"]:
            body.shapes.append(shape_from_dict(s))
            body.shapes[-1].body = body
        world.add_body(body)
    if spec.get("joints"):
        from sandbox.joints import joint_from_dict

        for j in spec["joints"]:
            world.add_joint(joint_from_dict(j, world))
    if spec.get("forces"):
        from sandbox.forces import force_from_dict

        for f in spec["forces"]:
            world.add_force(force_from_dict(f, world))
    return world


__all__ = ["build_world", "world_to_scene"]
