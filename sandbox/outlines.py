"""Outlines of shapes for drawing, and the geometry that places them in the world.

A circle is a :class:`CircleOutline` ``(center (2,), radius)`` in its body's ORIGIN frame (the
frame of ``body.position`` and ``body.angle``); a polygon an ``(V, 2)`` array of vertices in that
frame. :class:`OutlineArrays` turns every shape of a recording into polygons of one vertex count
so that one numpy expression (:func:`place`) puts all of them in the world for a frame.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np

if TYPE_CHECKING:
    from sandbox.recording import Recording


class CircleOutline(NamedTuple):
    """A circle in a body's origin frame: ``center`` (2,) in metres, ``radius`` in metres."""

    center: np.ndarray
    radius: float


Outline = CircleOutline | np.ndarray


def shape_outline(shape: Any) -> Outline:
    """The outline of one shape of the engine (``.kind`` "circle" or "polygon")."""
    if shape.kind == "circle":
        center = np.asarray(getattr(shape, "offset", (0.0, 0.0)), dtype=float).reshape(2).copy()
        return CircleOutline(center, float(shape.radius))
    if shape.kind == "polygon":
        vertices = np.array(shape.vertices, dtype=float).reshape(-1, 2)
        return vertices
    raise ValueError(f"cannot draw a shape of kind {shape.kind!r}")


@dataclass
class OutlineArrays:
    """Every shape of a recording as a polygon with the same vertex count, in array form.

    A circle becomes a regular ``circle_sides``-gon; shorter polygons are padded by repeating
    their last vertex, so all shapes are placed in the world with one numpy expression.
    """

    body: np.ndarray  # (P,) int64: the body owning each shape
    local: np.ndarray  # (P, V, 2) vertices in the body's origin frame
    marker: np.ndarray  # (P, 3, 2) orientation marker: centre, rim / first-edge midpoint, NaN
    static: np.ndarray  # (P,) bool: the owning body is static
    # (P,) circle radius (m), 0 for polygons: a circle's AABB is its centre (marker[:, 0]) +- r
    radius: np.ndarray = field(default_factory=lambda: np.zeros(0))

    @classmethod
    def of(cls, rec: Recording, circle_sides: int = 20) -> OutlineArrays:
        angles = 2.0 * math.pi * np.arange(circle_sides) / circle_sides
        unit = np.stack([np.cos(angles), np.sin(angles)], axis=1)
        gap = (math.nan, math.nan)  # breaks the marker polyline between shapes
        body, polys, markers, radius = [], [], [], []
        for i, outlines in enumerate(rec.outlines):
            for outline in outlines:
                if isinstance(outline, CircleOutline):
                    c, r = outline.center, outline.radius
                    polys.append(c + r * unit)
                    markers.append((c, c + (r, 0.0), gap))
                    radius.append(r)
                else:
                    polys.append(outline)
                    markers.append((outline.mean(axis=0), 0.5 * (outline[0] + outline[1]), gap))
                    radius.append(0.0)
                body.append(i)
        width = max([circle_sides] + [len(p) for p in polys])
        local = np.zeros((len(polys), width, 2))
        for j, p in enumerate(polys):
            local[j, : len(p)] = p
            local[j, len(p) :] = p[-1]
        return cls(
            body=np.array(body, dtype=np.int64),
            local=local,
            marker=np.array(markers, dtype=float).reshape(-1, 3, 2),
            static=np.array([rec.types[b] == "static" for b in body], dtype=bool),
            radius=np.array(radius, dtype=float),
        )


def place(local: np.ndarray, body: np.ndarray, poses: np.ndarray) -> np.ndarray:
    """World coordinates of body-frame points ``local`` (P, V, 2): x = p + R(angle) q.

    ``body`` (P,) picks each row's pose from ``poses`` (..., n, 3); leading frame axes broadcast,
    so one call places every shape of one frame, or of a block of frames.
    """
    pose = poses[..., body, :]
    c = np.cos(pose[..., 2])[..., None]
    s = np.sin(pose[..., 2])[..., None]
    qx, qy = local[..., 0], local[..., 1]
    out = np.empty(pose.shape[:-1] + local.shape[-2:])
    out[..., 0] = c * qx - s * qy + pose[..., 0, None]
    out[..., 1] = s * qx + c * qy + pose[..., 1, None]
    return out


# a spring's zig-zag: straight leads at both ends, then ZIGZAG_PEAKS alternating peaks between
_LEAD = 0.15
ZIGZAG_PEAKS = 10
_ZIG_T = np.concatenate(
    [[0.0, _LEAD], _LEAD + (1 - 2 * _LEAD) * (np.arange(ZIGZAG_PEAKS) + 0.5) / ZIGZAG_PEAKS]
    + [[1 - _LEAD, 1.0]]
)
_ZIG_SIDE = np.concatenate([[0.0, 0.0], (-1.0) ** np.arange(ZIGZAG_PEAKS), [0.0, 0.0]])


def zigzag(ends: np.ndarray, half_width: float) -> np.ndarray:
    """Zig-zag polylines ``(S, Z, 2)`` between the two points of each row of ``ends`` (S, 2, 2).

    The peaks stand ``half_width`` (m) off the line from end 0 to end 1; a spring of length 0
    is drawn as a point.
    """
    pa, d = ends[:, 0], ends[:, 1] - ends[:, 0]
    length = np.hypot(d[:, 0], d[:, 1])
    scale = np.divide(half_width, length, out=np.zeros_like(length), where=length > 0)
    normal = np.stack([-d[:, 1], d[:, 0]], axis=1) * scale[:, None]  # |normal| = half_width
    return (
        pa[:, None, :]
        + _ZIG_T[None, :, None] * d[:, None, :]
        + _ZIG_SIDE[None, :, None] * normal[:, None, :]
    )


def bounds(
    shapes: OutlineArrays, poses: np.ndarray, points: np.ndarray | None = None
) -> np.ndarray | None:
    """``[xmin, xmax, ymin, ymax]`` of all shapes in all frames ``poses`` (F, n, 3), in metres,
    and of the extra ``points`` (..., 2) (e.g. joint anchors).

    Non-finite coordinates are ignored; None when there is nothing finite to bound.
    """
    lo, hi = np.full(2, np.inf), np.full(2, -np.inf)
    if points is not None and points.size:
        pts = points.reshape(-1, 2)
        pts = pts[np.isfinite(pts).all(axis=1)]
        if len(pts):
            lo, hi = pts.min(axis=0), pts.max(axis=0)
    chunk = max(1, 2_000_000 // max(1, shapes.local.size))  # frames per block, bounded memory
    for k in range(0, len(poses), chunk):
        block = poses[k : k + chunk]
        if len(shapes.body):
            pts = place(shapes.local, shapes.body, block).reshape(-1, 2)
        else:
            pts = block[..., :2].reshape(-1, 2)
        pts = pts[np.isfinite(pts).all(axis=1)]
        if len(pts):
            lo = np.minimum(lo, pts.min(axis=0))
            hi = np.maximum(hi, pts.max(axis=0))
    if not np.isfinite(lo).all():
        return None
    return np.array([lo[0], hi[0], lo[1], hi[1]])
