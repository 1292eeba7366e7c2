"""A world back to a scene-file dict: its current state as the initial state of a scene."""

from __future__ import annotations

from sandbox.shapes import shape_to_dict


def world_to_scene(world) -> dict:
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
