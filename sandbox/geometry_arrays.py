"""Shapes flattened into contiguous arrays for the compiled collision code.

Geometry is stored relative to each body's centre of mass, in the body frame (see
``docs/architecture.md``, "Shapes: flattened arrays").
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from sandbox import geometry
from sandbox.body import STATIC, TYPES

CIRCLE, POLYGON = 0, 1


@dataclass
class Geometry:
    """Every shape of the world, flattened (m shapes, V polygon vertices in all)."""

    shapes: list
    shape_body: np.ndarray  # (m,) int64
    shape_kind: np.ndarray  # (m,) int64: 0 circle, 1 polygon
    shape_radius: np.ndarray  # (m,)
    shape_center: np.ndarray  # (m, 2) circle centre about the centre of mass
    shape_vstart: np.ndarray  # (m,) int64
    shape_vcount: np.ndarray  # (m,) int64
    verts: np.ndarray  # (V, 2) about the centre of mass, CCW
    normals: np.ndarray  # (V, 2) outward edge normals
    shape_restitution: np.ndarray
    shape_friction: np.ndarray
    shape_bound: np.ndarray  # (m,) radius about the centre of mass enclosing the shape
    shape_static: np.ndarray  # (m,) bool

    def __len__(self) -> int:
        return len(self.shapes)


def build_geometry(bodies: list, local_com: np.ndarray) -> Geometry:
    """Flatten the shapes of ``bodies`` (in order) into a :class:`Geometry`."""
    shapes, owner = [], []
    for body in bodies:
        for shape in body.shapes:
            shapes.append(shape)
            owner.append(body.index)
    m = len(shapes)
    kind = np.zeros(m, dtype=np.int64)
    radius = np.zeros(m)
    center = np.zeros((m, 2))
    vstart = np.zeros(m, dtype=np.int64)
    vcount = np.zeros(m, dtype=np.int64)
    rest = np.zeros(m)
    fric = np.zeros(m)
    bound = np.zeros(m)
    static = np.zeros(m, dtype=bool)
    verts, normals = [], []
    nv = 0
    for k, shape in enumerate(shapes):
        lc = local_com[owner[k]]
        rest[k], fric[k] = shape.restitution, shape.friction
        static[k] = TYPES[shape.body.type] == STATIC
        if shape.kind == "circle":
            kind[k] = CIRCLE
            radius[k] = shape.radius
            center[k] = shape.offset - lc
            bound[k] = float(np.hypot(*center[k])) + shape.radius
        else:
            kind[k] = POLYGON
            v = shape.vertices - lc
            vstart[k], vcount[k] = nv, len(v)
            nv += len(v)
            verts.append(v)
            normals.append(geometry.edge_normals(v))
            center[k] = v.mean(axis=0)
            bound[k] = float(np.max(np.hypot(v[:, 0], v[:, 1])))
    return Geometry(
        shapes=shapes,
        shape_body=np.array(owner, dtype=np.int64),
        shape_kind=kind,
        shape_radius=radius,
        shape_center=center,
        shape_vstart=vstart,
        shape_vcount=vcount,
        verts=np.concatenate(verts) if verts else np.zeros((0, 2)),
        normals=np.concatenate(normals) if normals else np.zeros((0, 2)),
        shape_restitution=rest,
        shape_friction=fric,
        shape_bound=bound,
        shape_static=static,
    )
