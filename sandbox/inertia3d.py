"""3D inertia tensors: the slides' solids, point masses, the parallel axis theorem (SI units).

Tensors are 3x3 ``float64`` arrays in kg m^2, about the centre of mass and in the body frame
unless said otherwise. The slides' axes: a cuboid is ``w`` along x, ``h`` along y, ``d`` along z;
a cylinder's axis is y.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np


def sphere(mass: float, radius: float) -> np.ndarray:
    """Solid sphere: I = 2/5 m r^2 on the diagonal, no products of inertia."""
    return np.eye(3) * (2.0 / 5.0 * mass * radius**2)  # slides, "Inertia Tensor Example: Sphere"


def cuboid(mass: float, w: float, h: float, d: float) -> np.ndarray:
    """Solid cuboid w x h x d: diag(m/12 (h^2 + d^2), m/12 (w^2 + d^2), m/12 (w^2 + h^2))."""
    k = mass / 12.0
    # slides, "Inertia Tensor Example: Cuboid"
    return np.diag([k * (h * h + d * d), k * (w * w + d * d), k * (w * w + h * h)])


def cylinder(mass: float, radius: float, height: float) -> np.ndarray:
    """Solid cylinder, axis y: diag(m/12 (3 r^2 + h^2), m r^2 / 2, m/12 (3 r^2 + h^2))."""
    side = mass / 12.0 * (3 * radius**2 + height**2)
    # slides, "Inertia Tensor Example: Cylinder"
    return np.diag([side, mass * radius**2 / 2.0, side])


def point_masses(masses: np.ndarray, positions: np.ndarray) -> np.ndarray:
    """Tensor of point masses about the origin: sum m (|r|^2 E - r r^T).

    Diagonal: I_xx = sum m (r_y^2 + r_z^2) ...; off-diagonal: I_xy = -sum m r_x r_y ... (the
    slides' "Moment of Inertia Tensor" integrals with the density replaced by point masses).
    """
    m = np.asarray(masses, dtype=float)
    r = np.asarray(positions, dtype=float).reshape(-1, 3)
    m = np.broadcast_to(m, r.shape[:1])
    outer = np.einsum("k,ki,kj->ij", m, r, r)  # sum m r r^T
    return np.eye(3) * np.trace(outer) - outer


def centre_of_mass(masses: np.ndarray, positions: np.ndarray) -> np.ndarray:
    """c = sum m r / sum m (m)."""
    m = np.asarray(masses, dtype=float)
    r = np.asarray(positions, dtype=float).reshape(-1, 3)
    m = np.broadcast_to(m, r.shape[:1])
    return m @ r / m.sum()  # slides, "Centre of Mass"


def parallel_axis(inertia_com: np.ndarray, mass: float, offset: np.ndarray) -> np.ndarray:
    """Tensor about a point ``offset`` away from the centre of mass: I_c + m (|d|^2 E - d d^T)."""
    d = np.asarray(offset, dtype=float)
    return np.asarray(inertia_com, dtype=float) + mass * (np.dot(d, d) * np.eye(3) - np.outer(d, d))


def rotate_tensor(inertia: np.ndarray, rotation: np.ndarray) -> np.ndarray:
    """The tensor in the frame reached by ``rotation``: R I R^T (e.g. body -> world)."""
    r = np.asarray(rotation, dtype=float)
    return r @ np.asarray(inertia, dtype=float) @ r.T


def principal_axes(inertia: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Principal moments (ascending, kg m^2) and axes (columns, unit) of a symmetric tensor."""
    moments, axes = np.linalg.eigh(np.asarray(inertia, dtype=float))
    return moments, axes


def lattice_point_masses(
    mass: float,
    half_extents: tuple[float, float, float],
    n: int,
    inside: Callable[[np.ndarray], np.ndarray] | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """Equal point masses at the centres of an n x n x n lattice of cells filling a box.

    The box is [-a, a] x [-b, b] x [-c, c] for ``half_extents = (a, b, c)``; cells whose centre
    fails ``inside(points) -> bool array`` are dropped; ``mass`` is shared by the cells kept.
    Returns ``(masses (k,), positions (k, 3))``.
    """
    axes = [((np.arange(n) + 0.5) / n * 2.0 - 1.0) * e for e in half_extents]
    pts = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
    if inside is not None:
        pts = pts[inside(pts)]
    return np.full(len(pts), mass / len(pts)), pts


def box_of_point_masses(
    mass: float, w: float, h: float, d: float, n: int
) -> tuple[np.ndarray, np.ndarray]:
    """A cuboid w x h x d as n^3 equal point masses (cell centres), centred on the origin.

    Its tensor is the cuboid's times (1 - 1/n^2) exactly (the mean of x^2 over n cell centres
    of [-w/2, w/2] is w^2 (1 - 1/n^2) / 12), so it tends to :func:`cuboid` as n grows.
    """
    return lattice_point_masses(mass, (w / 2, h / 2, d / 2), n)
