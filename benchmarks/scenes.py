"""Benchmark scenes as scene-file dicts (``DESIGN.md``, "Performance").

Both engines are built from the very same dict: this engine with ``sandbox.build.build_world``,
pymunk with ``sandbox.pymunk_bridge.PymunkScene.from_scene``. Every scene uses dt = 1/60 s, 10
solver iterations and gravity (0, -9.81) unless told otherwise. Nothing is random: where a
little irregularity is wanted (so that rain does not stack in perfect columns), it comes from a
fixed formula.
"""

from __future__ import annotations

import math

DT = 1.0 / 60.0
ITERATIONS = 10


def _scene(name: str, bodies: list[dict], iterations: int = ITERATIONS) -> dict:
    return {
        "version": 1,
        "name": name,
        "gravity": [0.0, -9.81],
        "dt": DT,
        "settings": {"iterations": iterations},
        "bodies": bodies,
    }


def _static_box(name: str, x: float, y: float, width: float, height: float) -> dict:
    return {
        "name": name,
        "type": "static",
        "position": [x, y],
        "shapes": [{"type": "box", "width": width, "height": height, "friction": 0.6}],
    }


def rain(n: int, radius: float = 0.2, iterations: int = ITERATIONS) -> dict:
    """``n`` circles in a staggered grid falling into an open box whose floor is at y = 0.

    About sqrt(n) circles a row, 0.1 m apart, the lowest row 1 m above the floor; odd rows are
    shifted by half a spacing and every circle by up to 2 cm (a fixed sine pattern). The walls
    are as tall as the grid, so nothing leaves the box.
    """
    spacing = 2.0 * radius + 0.1
    cols = max(10, round(math.sqrt(n)))
    rows = math.ceil(n / cols)
    inner = (cols + 0.5) * spacing + 0.1  # room for the half-shifted rows
    height = 1.0 + rows * spacing + 1.0
    bodies = [
        _static_box("floor", 0.0, -0.25, inner + 1.0, 0.5),
        _static_box("left_wall", -0.5 * inner - 0.25, 0.5 * height, 0.5, height),
        _static_box("right_wall", 0.5 * inner + 0.25, 0.5 * height, 0.5, height),
    ]
    x0 = -0.5 * inner + 0.05 + radius
    for i in range(n):
        row, col = divmod(i, cols)
        jitter = 0.02 * math.sin(12.9898 * i)
        x = x0 + (col + 0.5 * (row % 2)) * spacing + jitter
        y = 1.0 + radius + row * spacing
        bodies.append(
            {
                "name": f"drop{i}",
                "position": [x, y],
                "shapes": [{"type": "circle", "radius": radius, "friction": 0.5}],
            }
        )
    return _scene(f"rain_{n}", bodies, iterations)


def pyramid(base: int, size: float = 1.0, iterations: int = ITERATIONS) -> dict:
    """A pyramid of ``base * (base + 1) / 2`` boxes (``size`` m) resting on the ground (y = 0).

    Row r holds ``base - r`` boxes, centred, touching; friction 0.6 everywhere.
    """
    width = max(40.0, 2.0 * base * size)
    bodies = [_static_box("ground", 0.0, -0.5, width, 1.0)]
    for row in range(base):
        count = base - row
        for k in range(count):
            x = (k - 0.5 * (count - 1)) * size
            y = (row + 0.5) * size
            bodies.append(
                {
                    "name": f"r{row}b{k}",
                    "position": [x, y],
                    "shapes": [{"type": "box", "width": size, "height": size, "friction": 0.6}],
                }
            )
    return _scene(f"pyramid_{base}", bodies, iterations)


def ballistic(iterations: int = ITERATIONS) -> dict:
    """One disc thrown upwards with spin, nothing to hit: the per-step overhead of an engine."""
    body = {
        "name": "ball",
        "position": [0.0, 0.0],
        "velocity": [3.0, 20.0],
        "angular_velocity": 1.0,
        "shapes": [{"type": "circle", "radius": 0.2}],
    }
    return _scene("ballistic", [body], iterations)


def free(n: int, integrator: str = "semi_implicit_euler") -> dict:
    """``n`` discs on a wide square grid, 10 m apart, thrown upwards with spin; no two ever
    touch (``bench_free.py``'s world): the cost of integration and bookkeeping."""
    side = max(1, int(n**0.5))
    bodies = [
        {
            "name": f"b{i}",
            "position": [10.0 * (i % side), 10.0 * (i // side)],
            "velocity": [1.0, 5.0],
            "angular_velocity": 1.0,
            "shapes": [{"type": "circle", "radius": 0.2}],
        }
        for i in range(n)
    ]
    spec = _scene(f"free_{n}", bodies)
    spec["settings"]["integrator"] = integrator
    return spec


def chain(links: int, ball: float = 0.0) -> dict:
    """Boxes 0.5 m x 0.1 m of 1 kg hinged end to end from a static hook at (0, 10), released
    horizontally; ``ball`` > 0 hangs a disc of that many link masses at the free end (the soft
    step lesson's chains): the cost of the joints."""
    link = {"type": "box", "width": 0.5, "height": 0.1, "density": 20.0}
    bodies = [{"name": "hook", "type": "static", "position": [0.0, 10.0], "shapes": []}]
    joints, prev = [], "hook"
    for i in range(links):
        bodies.append({"name": f"link{i}", "position": [(i + 0.5) * 0.5, 10.0], "shapes": [link]})
        anchor_a = [0.0, 0.0] if i == 0 else [0.25, 0.0]
        joints.append(
            {"type": "pivot", "a": prev, "b": f"link{i}", "anchor_a": anchor_a,
             "anchor_b": [-0.25, 0.0]}
        )  # fmt: skip
        prev = f"link{i}"
    if ball:
        disc = {"type": "circle", "radius": 0.25, "mass": ball}
        bodies.append({"name": "ball", "position": [(links + 0.5) * 0.5, 10.0], "shapes": [disc]})
        joints.append(
            {"type": "pivot", "a": prev, "b": "ball", "anchor_a": [0.25, 0.0],
             "anchor_b": [-0.25, 0.0]}
        )  # fmt: skip
    spec = _scene(f"chain_{links}", bodies)
    spec["joints"] = joints
    return spec


def body_count(spec: dict) -> int:
    """Number of dynamic bodies in a scene dict."""
    return sum(1 for b in spec["bodies"] if b.get("type", "dynamic") == "dynamic")
