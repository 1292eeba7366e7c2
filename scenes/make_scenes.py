"""Write the example scenes in this folder: ``python scenes/make_scenes.py``.

The JSON files are committed; this script only saves doing the arithmetic (positions on a ramp, a
pyramid's rows, a grid of drops) by hand. Each scene is validated before it is written.
"""

from __future__ import annotations

import math
from pathlib import Path

from sandbox.atomic import atomic_write_text
from sandbox.scene import dump_scene, validate_scene

HERE = Path(__file__).resolve().parent


def ground(width: float = 40, friction: float | None = None) -> dict:
    """A static slab whose top face is the line y = 0."""
    shape = {"type": "box", "width": width, "height": 1, "offset": [0, -0.5]}
    if friction is not None:
        shape["friction"] = friction
    return {"name": "ground", "type": "static", "position": [0, 0], "shapes": [shape]}


def box(name: str, x: float, y: float, size: float = 1.0, **extra) -> dict:
    shape = {"type": "box", "width": size, "height": size}
    shape.update(extra.pop("material", {}))
    return {"name": name, "position": [x, y], **extra, "shapes": [shape]}


def drop() -> dict:
    """The example of the design notes, verbatim."""
    return {
        "version": 1,
        "name": "drop",
        "gravity": [0.0, -9.81],
        "dt": 0.016666666666666666,
        "settings": {
            "orientation": "complex",
            "integrator": "semi_implicit_euler",
            "broadphase": "sap",
            "solver": "iterative",
            "iterations": 10,
            "penetration": "impulse",
        },
        "bodies": [
            {
                "name": "ground",
                "type": "static",
                "position": [0, 0],
                "shapes": [
                    {
                        "type": "box",
                        "width": 40,
                        "height": 1,
                        "offset": [0, -0.5],
                        "restitution": 1.0,
                        "friction": 1.0,
                    }
                ],
            },
            {
                "name": "ball",
                "type": "dynamic",
                "position": [0, 10],
                "angle": 0.0,
                "velocity": [0, 0],
                "angular_velocity": 0.0,
                "ccd": False,
                "shapes": [
                    {
                        "type": "circle",
                        "radius": 0.5,
                        "density": 1.0,
                        "restitution": 0.5,
                        "friction": 0.5,
                    }
                ],
            },
        ],
        "joints": [],
        "forces": [],
    }


def projectile() -> dict:
    return {
        "version": 1,
        "name": "projectile",
        "description": "The slides' numeric example: s = (0, 0), u = (3, 4), a = (0, -1), dt = 1.",
        "gravity": [0, -1],
        "dt": 1,
        "settings": {"integrator": "explicit_euler"},
        "bodies": [
            {
                "name": "ball",
                "position": [0, 0],
                "velocity": [3, 4],
                "shapes": [{"type": "circle", "radius": 0.1}],
            }
        ],
    }


def stack() -> dict:
    boxes = [box(f"box{i}", 0, 0.5 + i) for i in range(10)]
    return {
        "version": 1,
        "name": "stack",
        "description": "Ten 1 m boxes stacked with no gap on the ground (y = 0).",
        "bodies": [ground(), *boxes],
    }


def pyramid(base: int = 10) -> dict:
    bodies = [ground(friction=0.6)]
    for row in range(base):
        n = base - row
        for i in range(n):
            x = i - 0.5 * (n - 1)
            bodies.append(box(f"r{row}b{i}", x, 0.5 + row, material={"friction": 0.6}))
    return {
        "version": 1,
        "name": "pyramid",
        "description": f"A pyramid of 1 m boxes, {base} at the base, friction 0.6.",
        "bodies": bodies,
    }


def pendulum(length: float = 2.0, degrees: float = 30.0) -> dict:
    theta = math.radians(degrees)
    pivot = (0.0, 5.0)
    bob = [
        round(pivot[0] + length * math.sin(theta), 12),
        round(pivot[1] - length * math.cos(theta), 12),
    ]
    return {
        "version": 1,
        "name": "pendulum",
        "description": f"A bob on a {length:g} m pin joint, released at rest {degrees:g} degrees out.",
        "bodies": [
            {
                "name": "anchor",
                "type": "static",
                "position": list(pivot),
                "shapes": [{"type": "circle", "radius": 0.05}],
            },
            {"name": "bob", "position": bob, "shapes": [{"type": "circle", "radius": 0.2}]},
        ],
        "joints": [{"type": "pin", "a": "anchor", "b": "bob"}],
    }


def newtons_cradle(count: int = 5, radius: float = 0.5, length: float = 3.0) -> dict:
    top = 5.0
    theta = math.radians(30.0)
    bodies = [
        {
            "name": "frame",
            "type": "static",
            "position": [0, top],
            "shapes": [
                {"type": "box", "width": 2 * radius * count + 1, "height": 0.2, "offset": [0, 0.1]}
            ],
        }
    ]
    joints = []
    for i in range(count):
        x = (i - 0.5 * (count - 1)) * 2 * radius
        position = [x, top - length]
        if i == 0:  # pulled out to the left, string taut
            position = [
                round(x - length * math.sin(theta), 12),
                round(top - length * math.cos(theta), 12),
            ]
        material = {"restitution": 1.0, "friction": 0.0}
        bodies.append(
            {
                "name": f"ball{i}",
                "position": position,
                "shapes": [{"type": "circle", "radius": radius, **material}],
            }
        )
        joints.append({"type": "pin", "a": "frame", "b": f"ball{i}", "anchor_a": [x, 0]})
    return {
        "version": 1,
        "name": "newtons_cradle",
        "description": "Five touching balls (restitution 1) on pin joints; the first pulled out 30 degrees.",
        "bodies": bodies,
        "joints": joints,
    }


def incline(degrees: float = 20.0) -> dict:
    theta = math.radians(degrees)
    c, s = math.cos(theta), math.sin(theta)
    centre, thickness, along = (0.0, 1.9), 0.4, 3.0
    # the box's centre in the ramp's frame: `along` up the slope, resting on the top face
    lx, ly = along, 0.5 * thickness + 0.5
    position = [round(centre[0] + c * lx - s * ly, 12), round(centre[1] + s * lx + c * ly, 12)]
    return {
        "version": 1,
        "name": "incline",
        "description": (
            f"A 1 m box resting on a {degrees:g} degree ramp; both friction 0.5, so the contact "
            "uses 0.25 (the product) and the box slides."
        ),
        "bodies": [
            ground(),
            {
                "name": "ramp",
                "type": "static",
                "position": list(centre),
                "angle": theta,
                "shapes": [{"type": "box", "width": 10, "height": thickness, "friction": 0.5}],
            },
            box("box", *position, angle=theta, material={"friction": 0.5}),
        ],
    }


def rain(rows: int = 10, cols: int = 10, radius: float = 0.2) -> dict:
    bodies = [
        {"name": "floor", "type": "static", "position": [0, 0], "shapes": [{"type": "box", "width": 11, "height": 0.5, "offset": [0, -0.25]}]},
        {"name": "left_wall", "type": "static", "position": [-5.25, 5], "shapes": [{"type": "box", "width": 0.5, "height": 10}]},
        {"name": "right_wall", "type": "static", "position": [5.25, 5], "shapes": [{"type": "box", "width": 0.5, "height": 10}]},
    ]  # fmt: skip
    spacing = 3 * radius
    for r in range(rows):
        for k in range(cols):
            x = (k - 0.5 * (cols - 1)) * spacing + (0.5 * radius if r % 2 else 0.0)
            y = 11.0 + r * spacing
            bodies.append(
                {
                    "name": f"drop{r * cols + k:02d}",
                    "position": [round(x, 9), round(y, 9)],
                    "shapes": [{"type": "circle", "radius": radius}],
                }
            )
    return {
        "version": 1,
        "name": "rain",
        "description": f"{rows * cols} circles in a staggered grid, falling into an open box.",
        "bodies": bodies,
    }


def bullet() -> dict:
    return {
        "version": 1,
        "name": "bullet",
        "description": (
            "A 0.05 m ball at 200 m/s towards a 0.1 m wall: it moves 3.3 m a step and tunnels "
            "through unless ccd is on."
        ),
        "gravity": [0, 0],
        "bodies": [
            {"name": "wall", "type": "static", "position": [5, 0], "shapes": [{"type": "box", "width": 0.1, "height": 4}]},
            {"name": "bullet", "position": [0, 0], "velocity": [200, 0], "ccd": True, "shapes": [{"type": "circle", "radius": 0.05}]},
        ],
    }  # fmt: skip


def spring() -> dict:
    rest = 2.0
    return {
        "version": 1,
        "name": "spring",
        "description": (
            "A 1 kg box hanging from a damped spring (k = 20 N/m, c = 0.5 N s/m), "
            "released at the spring's rest length."
        ),
        "bodies": [
            {"name": "anchor", "type": "static", "position": [0, 5], "shapes": [{"type": "circle", "radius": 0.1}]},
            box("box", 0, 5 - rest - 0.5),
        ],
        "joints": [
            {"type": "spring", "a": "anchor", "b": "box", "anchor_b": [0, 0.5],
             "rest_length": rest, "stiffness": 20, "damping": 0.5}
        ],
    }  # fmt: skip


def buoyancy() -> dict:
    bodies = [
        {"name": "pool_floor", "type": "static", "position": [0, -6], "shapes": [{"type": "box", "width": 20, "height": 1, "offset": [0, -0.5]}]}
    ]  # fmt: skip
    x = -5.0
    for density in (0.3, 0.5, 0.8):
        material = {"density": density}
        bodies.append(box(f"box_{density}", x, 1.5, material=material))
        x += 2
    for density in (0.3, 0.5, 0.8):
        shape = {"type": "circle", "radius": 0.5, "density": density}
        bodies.append({"name": f"disc_{density}", "position": [x, 1.5], "shapes": [shape]})
        x += 2
    return {
        "version": 1,
        "name": "buoyancy",
        "description": "Boxes and discs of density 0.3, 0.5 and 0.8 dropped into water (density 1) below y = 0.",
        "bodies": bodies,
        "forces": [
            {
                "type": "buoyancy",
                "surface_y": 0,
                "fluid_density": 1,
                "linear_drag": 2,
                "angular_drag": 0.5,
            }
        ],
    }


def hinge_motor() -> dict:
    return {
        "version": 1,
        "name": "hinge_motor",
        "description": "A 1 m wheel on a pivot, driven by a motor at 2 rad/s with at most 10 N m.",
        "bodies": [
            {"name": "axle", "type": "static", "position": [0, 2]},
            {"name": "wheel", "position": [0, 2], "shapes": [{"type": "circle", "radius": 1}]},
        ],
        "joints": [
            {"type": "pivot", "a": "axle", "b": "wheel", "motor": {"rate": 2.0, "max_torque": 10.0}}
        ],
    }


SCENES = {
    "drop": drop,
    "projectile": projectile,
    "stack": stack,
    "pyramid": pyramid,
    "pendulum": pendulum,
    "newtons_cradle": newtons_cradle,
    "incline": incline,
    "rain": rain,
    "bullet": bullet,
    "spring": spring,
    "buoyancy": buoyancy,
    "hinge_motor": hinge_motor,
}


def scene_texts() -> dict[str, str]:
    """File name -> the JSON text this script writes (each scene validated first)."""
    texts = {}
    for name, make in SCENES.items():
        scene = make()
        validate_scene(scene)
        texts[f"{name}.json"] = dump_scene(scene, validate=False) + "\n"
    return texts


def main() -> None:
    for filename, text in scene_texts().items():
        atomic_write_text(HERE / filename, text)
        print(f"wrote scenes/{filename}")


if __name__ == "__main__":
    main()
