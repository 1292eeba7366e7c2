"""Shapes flattened into contiguous arrays for the compiled collision code.

Geometry is stored relative to each body's centre of mass, in the body frame (see
``docs/architecture.md``, "Shapes: flattened arrays").
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from sandbox import geometry
from sandbox.body import STATIC, TYPES

CIRCLE, POLYGON = 0, 1

# Packed copies for the compiled step (fewer, larger arrays: each array handed to a compiled call
# costs about 0.1 us). Columns of ``shape_int`` (m, 4) and ``shape_float`` (m, 8); ``poly`` (V, 4)
# holds each polygon vertex with the outward normal of the edge that starts there.
S_BODY, S_KIND, S_VSTART, S_VCOUNT = 0, 1, 2, 3
S_RADIUS, S_CX, S_CY, S_FRICTION, S_RESTITUTION, S_BOUND = 0, 1, 2, 3, 4, 5
P_X, P_Y, P_NX, P_NY = 0, 1, 2, 3


def pack_shapes(
    shape_body, shape_kind, shape_radius, shape_center, shape_vstart, shape_vcount,
    verts, normals, shape_friction, shape_restitution, shape_bound=None,
):  # fmt: skip
    """The flattened shape arrays packed as ``(shape_int, shape_float, poly)`` (see the column
    names above). ``shape_bound`` defaults to infinity (no bounding-circle test in the
    narrowphase)."""
    m = len(shape_body)
    shape_int = np.zeros((m, 4), dtype=np.int64)
    shape_int[:, S_BODY] = shape_body
    shape_int[:, S_KIND] = shape_kind
    shape_int[:, S_VSTART] = shape_vstart
    shape_int[:, S_VCOUNT] = shape_vcount
    shape_float = np.zeros((m, 8))
    shape_float[:, S_RADIUS] = shape_radius
    shape_float[:, S_CX : S_CY + 1] = np.reshape(shape_center, (-1, 2))
    shape_float[:, S_FRICTION] = shape_friction
    shape_float[:, S_RESTITUTION] = shape_restitution
    shape_float[:, S_BOUND] = np.inf if shape_bound is None else shape_bound
    poly = np.zeros((len(verts), 4))
    poly[:, P_X : P_Y + 1] = np.reshape(verts, (-1, 2))
    poly[:, P_NX : P_NY + 1] = np.reshape(normals, (-1, 2))
    return shape_int, shape_float, poly


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
    # the same, packed for the compiled step (see pack_shapes)
    shape_int: np.ndarray = field(init=False, repr=False)
    shape_float: np.ndarray = field(init=False, repr=False)
    poly: np.ndarray = field(init=False, repr=False)

    def __post_init__(self) -> None:
        self.shape_int, self.shape_float, self.poly = pack_shapes(
            self.shape_body, self.shape_kind, self.shape_radius, self.shape_center,
            self.shape_vstart, self.shape_vcount, self.verts, self.normals,
            self.shape_friction, self.shape_restitution, self.shape_bound,
        )  # fmt: skip

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
