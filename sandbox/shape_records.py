"""The world's shapes as records (:data:`sandbox.records.SHAPE` and ``VERTEX``), built again
whenever shapes or mass properties change.

Geometry is stored about each body's centre of mass, in the body frame, so the collision code
places a shape point ``q`` of body ``i`` at ``com_i + R(angle_i) q`` without another offset.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from sandbox.geometry import edge_normals
from sandbox.records import CIRCLE, POLYGON, SHAPE, VERTEX


@dataclass
class Geometry:
    """Every shape of the world: the shape objects (``shapes``, in body order) and their
    records (``table``, one per shape; ``vertices``, every polygon's vertices in turn)."""

    shapes: list
    table: np.ndarray  # SHAPE records
    vertices: np.ndarray  # VERTEX records

    def __len__(self) -> int:
        return len(self.shapes)


def shape_table(
    owners: list[int], shapes: list, local_com: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """SHAPE and VERTEX records for ``shapes`` (objects with ``kind``, ``radius``/``offset`` or
    ``vertices`` about the body origin, ``friction``, ``restitution``); ``owners[k]`` is shape
    k's body and ``local_com[b]`` body b's centre of mass in its frame (m)."""
    table = np.zeros(len(shapes), dtype=SHAPE)
    polygons = []
    first = 0
    for k, shape in enumerate(shapes):
        row = table[k]
        lc = np.asarray(local_com[owners[k]], dtype=float)
        row["body"] = owners[k]
        row["friction"], row["restitution"] = shape.friction, shape.restitution
        if shape.kind == "circle":
            row["kind"] = CIRCLE
            row["radius"] = shape.radius
            row["center"] = np.asarray(shape.offset, dtype=float) - lc
            row["bound"] = float(np.hypot(*row["center"])) + shape.radius
        else:
            v = np.asarray(shape.vertices, dtype=float) - lc
            row["kind"] = POLYGON
            row["first_vertex"], row["vertex_count"] = first, len(v)
            row["center"] = v.mean(axis=0)
            row["bound"] = float(np.max(np.hypot(v[:, 0], v[:, 1])))
            polygons.append(v)
            first += len(v)
    vertices = np.zeros(first, dtype=VERTEX)
    if polygons:
        points = np.concatenate(polygons)
        vertices["point"] = points
        vertices["normal"] = np.concatenate([edge_normals(v) for v in polygons])
    return table, vertices


def build_geometry(bodies: list, local_com: np.ndarray) -> Geometry:
    """The :class:`Geometry` of ``bodies`` (in order; each ``body.index`` set)."""
    shapes, owners = [], []
    for body in bodies:
        for shape in body.shapes:
            shapes.append(shape)
            owners.append(body.index)
    table, vertices = shape_table(owners, shapes, local_com)
    return Geometry(shapes, table, vertices)
