"""Collision shapes: geometry in the body's frame (about the body origin) plus material.

``restitution`` (e, default 0) and ``friction`` (mu, default 0.5) combine by product in a contact,
as in pymunk. Mass comes from ``density`` (kg/m^2) or an explicit ``mass`` (kg).
"""

from __future__ import annotations

import numpy as np

import sandbox.geometry as geometry
from sandbox.copying import copy_fields


def _check(owner: str, kind: str, values: dict) -> dict:
    """The arguments of a shape, checked as the scene object ``kind`` (SceneError, at the call)."""
    from sandbox.arguments import check_arguments

    return check_arguments(owner, kind, values)


class Shape:
    """Common material and mass parameters of every shape.

    ``density`` (kg/m^2, default 1), ``mass`` (kg, instead of density), ``restitution`` (0..1,
    default 0) and ``friction`` (>= 0, default 0.5); checked at the call with the scene files'
    ranges, and an unknown keyword gets a did-you-mean (``elasticity`` -> ``restitution``).
    """

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

    def __deepcopy__(self, memo: dict) -> Shape:
        return copy_fields(self, memo)  # numbers shared: see sandbox.copying

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

    def _material_repr(self) -> str:
        parts = [] if self.mass is not None else [f"density={self.density:g}"]
        if self.mass is not None:
            parts.append(f"mass={self.mass:g}")
        parts += [f"restitution={self.restitution:g}", f"friction={self.friction:g}"]
        return ", ".join(parts)


def _material_of(values: dict) -> dict:
    return {k: values[k] for k in ("density", "mass", "restitution", "friction") if k in values}


class Circle(Shape):
    """A disc of ``radius`` (m) centred at ``offset`` (m, body frame)."""

    kind = "circle"

    def __init__(self, radius: float, offset=(0.0, 0.0), **material) -> None:
        from sandbox.arguments import not_a_body_hint

        not_a_body_hint(radius, "Circle")
        values = _check("Circle", "circle", {"radius": radius, "offset": offset, **material})
        super().__init__(**_material_of(values))
        self.radius = values["radius"]
        self.offset = np.array(values["offset"], dtype=float)

    def mass_properties(self):
        from sandbox.mass import circle_mass_properties

        return circle_mass_properties(self.radius, self.density, self.offset, mass=self.mass)

    def to_dict(self) -> dict:
        return {"type": "circle", "radius": self.radius, "offset": self.offset.tolist()}

    def __repr__(self) -> str:
        x, y = self.offset
        where = f", offset=({x:g}, {y:g})" if (x, y) != (0.0, 0.0) else ""
        return f"Circle({self.radius:g}{where}, {self._material_repr()})"


class Polygon(Shape):
    """A convex polygon; ``vertices`` (m, body frame) in either winding, stored CCW."""

    kind = "polygon"

    def __init__(self, vertices, **material) -> None:
        from sandbox.arguments import not_a_body_hint

        not_a_body_hint(vertices, "Polygon")
        if isinstance(vertices, np.ndarray):
            vertices = vertices.tolist()
        values = _check("Polygon", "polygon", {"vertices": vertices, **material})
        super().__init__(**_material_of(values))
        self.vertices = geometry.make_ccw(np.asarray(values["vertices"], dtype=float))

    def mass_properties(self):
        from sandbox.mass import polygon_mass_properties

        return polygon_mass_properties(self.vertices, self.density, mass=self.mass)

    def to_dict(self) -> dict:
        return {"type": "polygon", "vertices": self.vertices.tolist()}

    def __repr__(self) -> str:
        points = ", ".join(f"({x:g}, {y:g})" for x, y in self.vertices)
        return f"Polygon([{points}], {self._material_repr()})"


class Box(Polygon):
    """A ``width`` x ``height`` rectangle (m) centred at ``offset``, turned by ``angle`` (rad)."""

    def __init__(self, width: float, height: float, offset=(0.0, 0.0), angle: float = 0.0, **mat):
        from sandbox.arguments import not_a_body_hint

        not_a_body_hint(width, "Box")
        given = {"width": width, "height": height, "offset": offset, "angle": angle, **mat}
        values = _check("Box", "box", given)
        self.width, self.height = values["width"], values["height"]
        self.offset = np.array(values["offset"], dtype=float)
        self.angle = values["angle"]
        Shape.__init__(self, **_material_of(values))  # the corners need no convexity check
        self.vertices = geometry.box_vertices(self.width, self.height, self.offset, self.angle)

    def mass_properties(self):
        from sandbox.mass import box_mass_properties

        return box_mass_properties(
            self.width, self.height, self.density, self.offset, self.angle, mass=self.mass
        )

    def to_dict(self) -> dict:
        return {
            "type": "box",
            "width": self.width,
            "height": self.height,
            "offset": self.offset.tolist(),
            "angle": self.angle,
        }

    def __repr__(self) -> str:
        x, y = self.offset
        where = f", offset=({x:g}, {y:g})" if (x, y) != (0.0, 0.0) else ""
        turn = f", angle={self.angle:g}" if self.angle else ""
        return f"Box({self.width:g}, {self.height:g}{where}{turn}, {self._material_repr()})"


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
