"""Collision shapes: geometry in the body's frame (about the body origin) plus material.

``restitution`` (e, default 0) and ``friction`` (mu, default 0.5) combine by product in a contact,
as in pymunk. Mass comes from ``density`` (kg/m^2) or an explicit ``mass`` (kg).
"""

from __future__ import annotations

import numpy as np

import sandbox.geometry as geometry


class Shape:
    """Common material and mass parameters of every shape."""

    kind = "shape"

    def __init__(
        self,
        density: float = 1.0,
        mass: float | None = None,
        restitution: float = 0.0,
        friction: float = 0.5,
    ) -> None:
        self.density = float(density)
        self.mass = None if mass is None else float(mass)
        self.restitution = float(restitution)
        self.friction = float(friction)
        self.body = None  # set by Body.add_shape

    def mass_properties(self):
        """:class:`sandbox.mass.MassProperties` in the body-origin frame."""
        raise NotImplementedError

    def _material(self) -> dict:
        return {
            "density": self.density,
            "mass": self.mass,
            "restitution": self.restitution,
            "friction": self.friction,
        }


class Circle(Shape):
    """A disc of ``radius`` (m) centred at ``offset`` (m, body frame)."""

    kind = "circle"

    def __init__(self, radius: float, offset=(0.0, 0.0), **material) -> None:
        super().__init__(**material)
        self.radius = float(radius)
        self.offset = np.array(offset, dtype=float)

    def mass_properties(self):
        from sandbox.mass import circle_mass_properties

        return circle_mass_properties(self.radius, self.density, self.offset, mass=self.mass)

    def to_dict(self) -> dict:
        return {"type": "circle", "radius": self.radius, "offset": self.offset.tolist()}


class Polygon(Shape):
    """A convex polygon; ``vertices`` (m, body frame) in either winding, stored CCW."""

    kind = "polygon"

    def __init__(self, vertices, **material) -> None:
        super().__init__(**material)
        problem = geometry.polygon_problem(vertices)
        if problem:
            raise ValueError(f"vertices: {problem}")
        self.vertices = geometry.make_ccw(np.asarray(vertices, dtype=float))

    def mass_properties(self):
        from sandbox.mass import polygon_mass_properties

        return polygon_mass_properties(self.vertices, self.density, mass=self.mass)

    def to_dict(self) -> dict:
        return {"type": "polygon", "vertices": self.vertices.tolist()}


class Box(Polygon):
    """A ``width`` x ``height`` rectangle (m) centred at ``offset``, turned by ``angle`` (rad)."""

    def __init__(self, width: float, height: float, offset=(0.0, 0.0), angle: float = 0.0, **mat):
        self.width, self.height = float(width), float(height)
        self.offset = np.array(offset, dtype=float)
        self.angle = float(angle)
        super().__init__(geometry.box_vertices(width, height, offset, angle), **mat)

    def to_dict(self) -> dict:
        return {
            "type": "box",
            "width": self.width,
            "height": self.height,
            "offset": self.offset.tolist(),
            "angle": self.angle,
        }


def shape_to_dict(shape: Shape) -> dict:
    """The scene-file form of a shape (material included)."""
    return {**shape.to_dict(), **shape._material()}


def shape_from_dict(spec: dict) -> Shape:
    """Build a shape from its (validated) scene-file form."""
    material = {k: spec[k] for k in ("density", "mass", "restitution", "friction") if k in spec}
    kind = spec["type"]
    if kind == "circle":
        return Circle(spec["radius"], spec.get("offset", (0.0, 0.0)), **material)
    if kind == "box":
        return Box(
            spec["width"],
            spec["height"],
            spec.get("offset", (0.0, 0.0)),
            spec.get("angle", 0.0),
            **material,
        )
    return Polygon(spec["vertices"], **material)
