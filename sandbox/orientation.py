"""2D orientation: the slides' three representations behind one interface.

Slides, "2D Angular Motion":
- option 1, scalar angle phi, wrapped to [-pi, pi]:      phi(t + dt) = phi(t) + omega dt
- option 2, rotation matrix Phi:                         Phi(t + dt) = Phi(t) R(omega dt)
- option 3, unit complex number z = cos phi + i sin phi: z(t + dt) = z(t) e^{i omega dt}

Each representation offers the same operations: integrate by an angle increment, rotate a vector,
convert to a matrix or an angle, renormalise, and measure its drift (how far it has strayed from a
valid rotation). The world keeps every body's orientation in one array of 1, 4 or 2 columns, laid out per
representation (``ANGLE``: [phi]; ``MATRIX``: [m00, m01, m10, m11]; ``COMPLEX``: [c, s]), and the compiled kernels at the bottom of this file work on that array.
"""

from __future__ import annotations

import math

import numpy as np

from sandbox.jit import njit

ANGLE, MATRIX, COMPLEX = 0, 1, 2
NAMES = {"angle": ANGLE, "matrix": MATRIX, "complex": COMPLEX}
FLOATS_STORED = {"angle": 1, "matrix": 4, "complex": 2}


@njit(python=True)
def wrap_angle(phi: float) -> float:
    """Reduce an angle to [-pi, pi] by adding or subtracting 2 pi (slides, option 1)."""
    if -math.pi <= phi <= math.pi:
        return phi
    two_pi = 2.0 * math.pi
    phi = phi - two_pi * math.floor((phi + math.pi) / two_pi)
    return min(max(phi, -math.pi), math.pi)


class AngleOrientation:
    """Option 1: a scalar angle in radians, kept in [-pi, pi]."""

    name = "angle"

    def __init__(self, angle: float = 0.0) -> None:
        self.phi = wrap_angle(float(angle))

    def integrate(self, omega: float, dt: float) -> None:
        """phi(t + dt) = phi(t) + omega dt, then wrapped (slides, option 1)."""
        self.phi = wrap_angle(self.phi + omega * dt)

    def angle(self) -> float:
        return self.phi

    def matrix(self) -> np.ndarray:
        """[[cos, -sin], [sin, cos]]: two trigonometric calls (the slides' 'costly conversion')."""
        c, s = math.cos(self.phi), math.sin(self.phi)
        return np.array([[c, -s], [s, c]])

    def rotate(self, v: np.ndarray) -> np.ndarray:
        return self.matrix() @ np.asarray(v, dtype=float)

    def renormalise(self) -> None:
        self.phi = wrap_angle(self.phi)

    def drift(self) -> float:
        """A scalar angle cannot stray from being a rotation: always 0."""
        return 0.0


class MatrixOrientation:
    """Option 2: a 2x2 rotation matrix (4 floats)."""

    name = "matrix"

    def __init__(self, angle: float = 0.0) -> None:
        c, s = math.cos(angle), math.sin(angle)
        self.m = np.array([[c, -s], [s, c]])

    def integrate(self, omega: float, dt: float) -> None:
        """Phi(t + dt) = Phi(t) [[cos w dt, -sin w dt], [sin w dt, cos w dt]] (slides, option 2)."""
        c, s = math.cos(omega * dt), math.sin(omega * dt)
        self.m = self.m @ np.array([[c, -s], [s, c]])

    def angle(self) -> float:
        return math.atan2(self.m[1, 0], self.m[0, 0])

    def matrix(self) -> np.ndarray:
        return self.m.copy()

    def rotate(self, v: np.ndarray) -> np.ndarray:
        return self.m @ np.asarray(v, dtype=float)

    def renormalise(self) -> None:
        """Gram-Schmidt: normalise the first column, make the second its perpendicular."""
        c0 = self.m[:, 0] / math.hypot(self.m[0, 0], self.m[1, 0])
        self.m = np.array([[c0[0], -c0[1]], [c0[1], c0[0]]])

    def drift(self) -> float:
        """Loss of orthogonality: Frobenius norm of Phi^T Phi - I."""
        return float(np.linalg.norm(self.m.T @ self.m - np.eye(2)))


class ComplexOrientation:
    """Option 3: a unit complex number z = cos phi + i sin phi (2 floats)."""

    name = "complex"

    def __init__(self, angle: float = 0.0) -> None:
        self.z = complex(math.cos(angle), math.sin(angle))

    def integrate(self, omega: float, dt: float) -> None:
        """z(t + dt) = z(t) e^{i omega dt} (slides, option 3)."""
        self.z = self.z * complex(math.cos(omega * dt), math.sin(omega * dt))

    def angle(self) -> float:
        return math.atan2(self.z.imag, self.z.real)

    def matrix(self) -> np.ndarray:
        """[[Re, -Im], [Im, Re]]: no trigonometry needed."""
        return np.array([[self.z.real, -self.z.imag], [self.z.imag, self.z.real]])

    def rotate(self, v: np.ndarray) -> np.ndarray:
        w = self.z * complex(v[0], v[1])
        return np.array([w.real, w.imag])

    def renormalise(self) -> None:
        """z' = z / |z| (slides, option 3)."""
        self.z = self.z / abs(self.z)

    def drift(self) -> float:
        """Departure from unit length: | |z| - 1 |."""
        return abs(abs(self.z) - 1.0)


REPRESENTATIONS = {
    "angle": AngleOrientation,
    "matrix": MatrixOrientation,
    "complex": ComplexOrientation,
}


def make_orientation(
    name: str, angle: float = 0.0
) -> AngleOrientation | MatrixOrientation | ComplexOrientation:
    """A representation by name (``angle`` | ``matrix`` | ``complex``) holding ``angle`` (rad)."""
    return REPRESENTATIONS[name](angle)


# --- the same formulas over the world's orientation array (n, 1 | 4 | 2) --------------------------


@njit
def set_angles(kind: int, rot: np.ndarray, angles: np.ndarray) -> None:
    """Store each angle (rad) in row i of ``rot`` in the layout of representation ``kind``."""
    for i in range(rot.shape[0]):
        set_angle_row(kind, rot, i, angles[i])


@njit(inline="always")
def turn_row(kind: int, rot: np.ndarray, i: int, d: float, renormalise: bool) -> None:
    """Turn row i of ``rot`` by the angle increment d = omega dt in the layout of ``kind``."""
    if kind == ANGLE:
        rot[i, 0] = wrap_angle(rot[i, 0] + d)  # option 1
        return
    c, s = math.cos(d), math.sin(d)
    if kind == COMPLEX:
        zr, zi = rot[i, 0], rot[i, 1]  # option 3: z e^{i d}
        zr, zi = zr * c - zi * s, zr * s + zi * c
        if renormalise:
            inv = 1.0 / math.sqrt(zr * zr + zi * zi)
            zr *= inv
            zi *= inv
        rot[i, 0] = zr
        rot[i, 1] = zi
    else:
        m00, m01, m10, m11 = rot[i, 0], rot[i, 1], rot[i, 2], rot[i, 3]  # option 2: Phi R(d)
        n00, n01 = m00 * c + m01 * s, -m00 * s + m01 * c
        n10, n11 = m10 * c + m11 * s, -m10 * s + m11 * c
        if renormalise:  # Gram-Schmidt on the first column
            inv = 1.0 / math.sqrt(n00 * n00 + n10 * n10)
            n00 *= inv
            n10 *= inv
            n01, n11 = -n10, n00
        rot[i, 0], rot[i, 1], rot[i, 2], rot[i, 3] = n00, n01, n10, n11


@njit(inline="always")
def cos_sin_row(kind: int, rot: np.ndarray, i: int) -> tuple[float, float]:
    """(cos, sin) of the orientation in row i, as collision code reads it."""
    if kind == ANGLE:
        return math.cos(rot[i, 0]), math.sin(rot[i, 0])
    if kind == COMPLEX:
        return rot[i, 0], rot[i, 1]
    return rot[i, 0], rot[i, 2]


@njit
def integrate_rotations(kind: int, rot: np.ndarray, dphi: np.ndarray, renormalise: bool) -> None:
    """Turn every body by its increment dphi = omega dt in the layout of ``kind`` (in place)."""
    for i in range(rot.shape[0]):
        if dphi[i] != 0.0 or renormalise:
            turn_row(kind, rot, i, dphi[i], renormalise)


@njit
def cos_sin(kind: int, rot: np.ndarray, cs: np.ndarray) -> None:
    """Fill ``cs`` (n, 2) with (cos, sin) of each orientation, as collision code reads them."""
    for i in range(rot.shape[0]):
        cs[i, 0], cs[i, 1] = cos_sin_row(kind, rot, i)


@njit(inline="always")
def turn_body(bodies, rot: np.ndarray, i: int, kind: int, d: float, renormalise: bool) -> None:
    """Turn body i by d radians: its stored orientation, its (cos, sin) read back from it, and
    its continuous angle, the sum of every turn (so turns accumulate whatever the
    representation; it differs from the stored orientation's angle by that representation's
    rounding only)."""
    b = bodies[i]
    turn_row(kind, rot, i, d, renormalise)
    b["cs"][0], b["cs"][1] = cos_sin_row(kind, rot, i)
    b["angle"] += d


@njit
def turn_bodies(bodies, rot: np.ndarray, kind: int, renormalise: bool) -> None:
    """Turn every body by its ``turn`` (what the position passes turned it by), then zero it."""
    for i in range(bodies.shape[0]):
        d = bodies[i]["turn"]
        if d != 0.0:
            turn_body(bodies, rot, i, kind, d, renormalise)
            bodies[i]["turn"] = 0.0


@njit
def place_bodies(bodies, rot: np.ndarray, kind: int) -> None:
    """Store every body's continuous ``angle`` in ``rot`` (layout ``kind``) and set its
    (cos, sin) from it: a fresh orientation, after a switch of representation or a reset."""
    for i in range(bodies.shape[0]):
        b = bodies[i]
        set_angle_row(kind, rot, i, b["angle"])
        b["cs"][0], b["cs"][1] = cos_sin_row(kind, rot, i)


@njit
def set_angle_row(kind: int, rot: np.ndarray, i: int, angle: float) -> None:
    """Store ``angle`` (rad) in row i of ``rot`` in the layout of representation ``kind``."""
    c, s = math.cos(angle), math.sin(angle)
    if kind == ANGLE:
        rot[i, 0] = wrap_angle(angle)
    elif kind == COMPLEX:
        rot[i, 0] = c
        rot[i, 1] = s
    else:
        rot[i, 0] = c
        rot[i, 1] = -s
        rot[i, 2] = s
        rot[i, 3] = c


def angles_of(kind: int, rot: np.ndarray) -> np.ndarray:
    """Angles (rad, in [-pi, pi]) of every row of ``rot``."""
    if kind == ANGLE:
        return rot[:, 0].copy()
    if kind == COMPLEX:
        return np.arctan2(rot[:, 1], rot[:, 0])
    return np.arctan2(rot[:, 2], rot[:, 0])


def drift_of(kind: int, rot: np.ndarray) -> np.ndarray:
    """Per-body drift: | |z| - 1 | for complex, ||Phi^T Phi - I||_F for matrices, 0 for angles."""
    if kind == ANGLE:
        return np.zeros(len(rot))
    if kind == COMPLEX:
        return np.abs(np.hypot(rot[:, 0], rot[:, 1]) - 1.0)
    m = rot.reshape(-1, 2, 2)
    g = np.einsum("nki,nkj->nij", m, m) - np.eye(2)
    return np.sqrt(np.sum(g * g, axis=(1, 2)))
