"""Mass properties: centre of mass, moment of inertia, parallel axis theorem, shapes.

Slides "Centre of Mass", "Moment of Inertia" and their worked examples. SI units throughout:
masses in kg, positions in m, areas in m^2, densities in kg/m^2 (2D: mass per unit area),
moments of inertia in kg m^2 about an axis perpendicular to the plane. Angles in radians, CCW
positive, y up.

Point masses:

- :func:`center_of_mass`      c = sum m_i r_i / sum m_i
- :func:`moment_of_inertia`   I = sum m_i r_i^2 (r_i = perpendicular distance to the axis)
- :func:`parallel_axis`       I = I_cm + m d^2, and :func:`parallel_axis_to_centroid` (its inverse)

Solid shapes (uniform density), each returning a :class:`MassProperties`:

- :func:`circle_mass_properties`   I = m r^2 / 2
- :func:`box_mass_properties`      I = m (w^2 + h^2) / 12
- :func:`polygon_mass_properties`  shoelace area, centroid and moment by triangle decomposition
- :func:`combine`                  several shapes -> one body, by the parallel axis theorem
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass

import numpy as np

from sandbox.geometry import make_ccw, signed_area


@dataclass(frozen=True, eq=False)
class MassProperties:
    """Mass properties of a shape or body, in that shape's (or body's) frame.

    mass: kg. centroid: (2,) m, the centre of mass. moment: kg m^2 about the axis through the
    centroid, perpendicular to the plane. area: m^2.
    """

    mass: float
    centroid: np.ndarray
    moment: float
    area: float

    def __post_init__(self) -> None:
        c = np.array(self.centroid, dtype=float).reshape(2)
        c.setflags(write=False)
        object.__setattr__(self, "centroid", c)
        object.__setattr__(self, "mass", float(self.mass))
        object.__setattr__(self, "moment", float(self.moment))
        object.__setattr__(self, "area", float(self.area))

    @property
    def density(self) -> float:
        """Mass per unit area (kg/m^2)."""
        return self.mass / self.area

    def moment_about(self, point: Iterable[float] = (0.0, 0.0)) -> float:
        """Moment of inertia about the axis through ``point`` (same frame), kg m^2."""
        # slides, "Moment of Inertia", moved off the centre of mass: I = I_cm + m d^2
        return parallel_axis(self.moment, self.mass, self.centroid - _point(point))

    def __repr__(self) -> str:
        cx, cy = (float(x) for x in self.centroid)
        return (
            f"MassProperties(mass={self.mass!r}, centroid=({cx!r}, {cy!r}), "
            f"moment={self.moment!r}, area={self.area!r})"
        )


# ---------------------------------------------------------------- input checks


def _point(p: object) -> np.ndarray:
    """A 2D point from ``(x, y)``, or from a scalar x (a point on the x axis)."""
    a = np.asarray(p, dtype=float)
    if a.ndim == 0:
        a = np.array([float(a), 0.0])
    if a.shape != (2,) or not np.all(np.isfinite(a)):
        raise ValueError(f"expected a finite point (x, y), got {p!r}")
    return a


def _points(masses: object, positions: object) -> tuple[np.ndarray, np.ndarray]:
    """Masses (n,) and positions (n, 2); scalar positions are points on the x axis."""
    m = np.asarray(masses, dtype=float).reshape(-1)
    r = np.asarray(positions, dtype=float)
    if r.ndim == 1:
        r = np.stack([r, np.zeros_like(r)], axis=1)
    if r.ndim != 2 or r.shape[1] != 2 or len(r) != len(m):
        raise ValueError(f"need one position per mass: {len(m)} masses, positions {r.shape}")
    if len(m) == 0:
        raise ValueError("need at least one point mass")
    if not (np.all(np.isfinite(m)) and np.all(np.isfinite(r))):
        raise ValueError("masses and positions must be finite")
    if np.any(m < 0) or not np.sum(m) > 0:
        raise ValueError("masses must be >= 0 with a positive total")
    return m, r


def _positive(name: str, value: float) -> float:
    v = float(value)
    if not (math.isfinite(v) and v > 0):
        raise ValueError(f"{name} must be a finite number > 0, got {value!r}")
    return v


def _mass_from(area: float, density: float, mass: float | None) -> float:
    """m = rho A, unless ``mass`` is given (then rho = m / A)."""
    if mass is not None:
        return _positive("mass", mass)
    return _positive("density", density) * area


# ---------------------------------------------------------------- point masses


def center_of_mass(masses: Iterable[float], positions: object) -> np.ndarray | float:
    """Centre of mass of point masses ``masses`` (kg) at ``positions`` (m).

    ``positions`` is (n, 2), or (n,) for masses on a line (then a float is returned).
    """
    scalar = np.ndim(positions) == 1
    m, r = _points(masses, positions)
    # slides, "Centre of Mass": c = sum_i m_i r_i / sum_i m_i
    c = (m[:, None] * r).sum(axis=0) / m.sum()
    return float(c[0]) if scalar else c


def moment_of_inertia(
    masses: Iterable[float], positions: object, axis: object = (0.0, 0.0)
) -> float:
    """Moment of inertia (kg m^2) of point masses about the axis through ``axis``.

    The axis is perpendicular to the plane, so r_i is the distance from ``axis`` to mass i.
    ``positions`` is (n, 2) or (n,) on a line; ``axis`` is (x, y) or a scalar x.
    """
    m, r = _points(masses, positions)
    d = r - _point(axis)
    # slides, "Moment of Inertia": I = sum_i m_i r_i^2, r_i perpendicular distance to the axis
    return float(np.sum(m * np.sum(d * d, axis=1)))


def parallel_axis(moment_cm: float, mass: float, offset: object) -> float:
    """Moment about an axis ``offset`` (vector (2,) or distance d, m) from the centre of mass."""
    d = _point(offset)
    # parallel axis theorem: I = I_cm + m d^2
    return float(moment_cm + mass * float(d @ d))


def parallel_axis_to_centroid(moment_axis: float, mass: float, offset: object) -> float:
    """Inverse of :func:`parallel_axis`: moment about the centre of mass, ``offset`` away."""
    d = _point(offset)
    # parallel axis theorem solved for the centroid: I_cm = I - m d^2
    moment_cm = float(moment_axis - mass * float(d @ d))
    if moment_cm < -1e-12 * max(abs(moment_axis), 1e-300):
        raise ValueError(
            f"I - m d^2 = {moment_cm} < 0: no axis through the centre of mass has a smaller moment"
        )
    return max(moment_cm, 0.0)


# ---------------------------------------------------------------- solid shapes


def circle_mass_properties(
    radius: float,
    density: float = 1.0,
    offset: object = (0.0, 0.0),
    mass: float | None = None,
) -> MassProperties:
    """Solid disc of ``radius`` (m) centred at ``offset``: A = pi r^2, I = m r^2 / 2."""
    r = _positive("radius", radius)
    area = math.pi * r * r
    m = _mass_from(area, density, mass)
    # slides, "Moment of Inertia" for a solid body, evaluated for a disc: I = m r^2 / 2
    return MassProperties(m, _point(offset), 0.5 * m * r * r, area)


def box_mass_properties(
    width: float,
    height: float,
    density: float = 1.0,
    offset: object = (0.0, 0.0),
    angle: float = 0.0,
    mass: float | None = None,
) -> MassProperties:
    """Solid ``width`` x ``height`` box (m) centred at ``offset``, turned by ``angle``.

    A = w h, I = m (w^2 + h^2) / 12 about its centre, whatever the angle.
    """
    w, h = _positive("width", width), _positive("height", height)
    if not math.isfinite(angle):
        raise ValueError(f"angle must be finite, got {angle!r}")
    area = w * h
    m = _mass_from(area, density, mass)
    # slides, "Moment of Inertia" for a solid body, evaluated for a rectangle: I = m (w^2 + h^2) / 12
    return MassProperties(m, _point(offset), m * (w * w + h * h) / 12.0, area)


def polygon_mass_properties(
    vertices: object, density: float = 1.0, mass: float | None = None
) -> MassProperties:
    """Solid simple polygon (either winding, convex or not): area, centroid, moment (SI).

    Fan of triangles (o, p_i, p_{i+1}) from a point o; with a = p_i - o, b = p_{i+1} - o and
    k_i = a x b (twice the signed triangle area):

    - A = sum k_i / 2 (shoelace)
    - c = o + sum k_i (a + b) / (6 A)
    - I_c = rho sum k_i (a.a + a.b + b.b) / 12, with o moved to c (no I - m d^2 cancellation).
    """
    v = np.asarray(vertices, dtype=float)
    if v.ndim != 2 or v.shape[1] != 2 or len(v) < 3:
        raise ValueError("a polygon needs at least 3 vertices given as [x, y] pairs")
    if not np.all(np.isfinite(v)):
        raise ValueError("polygon vertices must be finite")
    v = make_ccw(v)
    # shoelace formula: A = 1/2 sum (x_i y_{i+1} - x_{i+1} y_i)
    area = signed_area(v)
    size = float(np.max(np.ptp(v, axis=0)))
    if not area > 1e-12 * size * size:
        raise ValueError("degenerate polygon (zero area)")
    m = _mass_from(area, density, mass)

    # centroid of the fan: area-weighted mean of the triangles' centroids (a + b) / 3
    o = v.mean(axis=0)
    a = v - o
    b = np.roll(a, -1, axis=0)
    k = a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]
    c = o + (k[:, None] * (a + b)).sum(axis=0) / (6.0 * area)

    # slides, "Moment of Inertia" for a solid body: I = integral rho r^2 dA, summed per triangle
    a = v - c
    b = np.roll(a, -1, axis=0)
    k = a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]
    second = np.sum(k * (np.sum(a * a, axis=1) + np.sum(a * b, axis=1) + np.sum(b * b, axis=1)))
    moment = (m / area) * second / 12.0
    return MassProperties(m, c, moment, area)


def combine(parts: Iterable[MassProperties]) -> MassProperties:
    """Several shapes (in one frame) as one body: total mass, centroid, moment about it."""
    parts = list(parts)
    if not parts:
        raise ValueError("combine needs at least one part")
    if len(parts) == 1:  # one part is the body: its centroid exactly, not m c / m rounded
        return parts[0]
    masses = np.array([p.mass for p in parts])
    centroids = np.array([p.centroid for p in parts])
    # slides, "Centre of Mass": c = sum m_k c_k / sum m_k
    c = center_of_mass(masses, centroids)
    # parallel axis theorem per part: I = sum_k (I_k + m_k |c_k - c|^2)
    moment = sum(parallel_axis(p.moment, p.mass, p.centroid - c) for p in parts)
    return MassProperties(float(masses.sum()), c, moment, sum(p.area for p in parts))
