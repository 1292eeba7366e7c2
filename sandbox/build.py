"""Scene dict (validated, see :mod:`sandbox.scene`) to :class:`~sandbox.world.World`, and back."""

from __future__ import annotations

from sandbox.body import Body
from sandbox.shapes import shape_from_dict, shape_to_dict
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


def world_to_scene(world: World) -> dict:
    """The scene-file dict of a world, its current state taken as the initial state."""
    bodies = []
    for body in world.bodies:
        entry = {
            "name": body.name,
            "type": body.type,
            "position": list(body.position),
            "angle": body.angle,
            "velocity": list(body.velocity),
            "angular_velocity": body.angular_velocity,
            "ccd": body.ccd,
            "shapes": [shape_to_dict(s) for s in body.shapes],
        }
        if body.mass_override is not None:
            entry["mass"] = float(body.mass_override)
        if body.moment_override is not None:
            entry["moment"] = float(body.moment_override)
        if body.constant_force.any():
            entry["force"] = body.constant_force.tolist()
        if body.constant_torque:
            entry["torque"] = body.constant_torque
        bodies.append(entry)
    return {
        "version": 1,
        "name": world.name,
        "gravity": world.gravity.tolist(),
        "dt": world.dt,
        "settings": world.settings.scene_dict(),  # contract keys + settings not at default
        "bodies": bodies,
        "joints": [j.to_dict() for j in world.joints],
        "forces": [f.to_dict() for f in world.forces],
    }
