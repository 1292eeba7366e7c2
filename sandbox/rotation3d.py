"""3D orientation: scaled axis, 3x3 rotation matrix and unit quaternion behind one interface.

Separate from the 2D engine (the slides' "3D Angular Motion" options 1-3). Conventions:

- a quaternion is ``[s, x, y, z]`` (scalar first, as on the slides);
- an orientation maps body-frame vectors to the world frame, ``v_world = R v_body``;
- angular velocity ``omega`` is a world-frame scaled axis (rad/s, right-hand rule), so updates
  multiply on the left: ``R <- R(omega dt) R``, ``q <- q(omega dt) q``.

Every function accepts one item or a stack: arrays of shape ``(..., 3)``, ``(..., 4)`` or
``(..., 3, 3)``, so the same code steps one body or thousands.
"""

from __future__ import annotations

import numpy as np

_CONJ = np.array([1.0, -1.0, -1.0, -1.0])


def _f(a: object) -> np.ndarray:
    return np.asarray(a, dtype=float)


def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``a x b`` over the last axis (written out: cheaper than ``np.cross`` on small arrays)."""
    a, b = _f(a), _f(b)
    if a.shape == (3,) and b.shape == (3,):  # one pair: plain floats are ten times faster
        ax, ay, az = a.tolist()
        bx, by, bz = b.tolist()
        return np.array([ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx])
    ax, ay, az = a[..., 0], a[..., 1], a[..., 2]
    bx, by, bz = b[..., 0], b[..., 1], b[..., 2]
    return np.stack([ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx], axis=-1)


def norm(v: np.ndarray) -> np.ndarray:
    """Euclidean length over the last axis."""
    v = _f(v)
    return np.sqrt(np.sum(v * v, axis=-1))


def matvec(m: np.ndarray, v: np.ndarray) -> np.ndarray:
    """``m @ v`` for stacks of 3x3 matrices and 3-vectors."""
    return np.einsum("...ij,...j->...i", _f(m), _f(v))


# ---------------------------------------------------------------- quaternion algebra


def qnorm(q: np.ndarray) -> np.ndarray:
    """|q| = sqrt(s^2 + v.v)."""
    return norm(q)  # slides, "Quaternions", norm


def qconj(q: np.ndarray) -> np.ndarray:
    """q* = [s, -v]."""
    return _f(q) * _CONJ  # slides, "Quaternions", conjugate


def qmul(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Quaternion product [s1 s2 - v1.v2, s1 v2 + s2 v1 + v1 x v2] (not commutative)."""
    a, b = _f(a), _f(b)
    s1, v1, s2, v2 = a[..., :1], a[..., 1:], b[..., :1], b[..., 1:]
    # slides, "Quaternions", multiplication
    s = s1 * s2 - np.sum(v1 * v2, axis=-1, keepdims=True)
    v = s1 * v2 + s2 * v1 + cross(v1, v2)
    return np.concatenate([s, v], axis=-1)


def qinv(q: np.ndarray) -> np.ndarray:
    """q^-1 = q* / |q|^2, so that q q^-1 = [1, 0, 0, 0] for any non-zero q.

    The slides print q* / |q|; that is only right when |q| = 1.
    """
    q = _f(q)
    return qconj(q) / np.sum(
        q * q, axis=-1, keepdims=True
    )  # slides, "Quaternions", inverse (fixed)


def qcanonical(q: np.ndarray) -> np.ndarray:
    """q / |q| with s >= 0 (q and -q are the same rotation)."""
    q = _f(q)
    q = q / qnorm(q)[..., None]
    return np.where(q[..., :1] < 0.0, -q, q)


def pure(v: np.ndarray) -> np.ndarray:
    """The quaternion [0, v] wrapping a 3-vector."""
    v = _f(v)
    return np.concatenate([np.zeros(v.shape[:-1] + (1,)), v], axis=-1)


def qrotate(q: np.ndarray, v: np.ndarray) -> np.ndarray:
    """v' from [s', v'] = q [0 v] q* (a rotation when |q| = 1; scaled by |q|^2 otherwise)."""
    return qmul(qmul(q, pure(v)), qconj(q))[..., 1:]  # slides, "Rotation Quaternions"


def quat_from_axis_angle(axis: np.ndarray, angle: np.ndarray) -> np.ndarray:
    """q = [cos(theta/2), n sin(theta/2)] with n = axis / |axis| (radians)."""
    axis, angle = _f(axis), _f(angle)[..., None]
    n = axis / norm(axis)[..., None]
    # slides, "Rotation Quaternions"
    return np.concatenate([np.cos(angle / 2), n * np.sin(angle / 2)], axis=-1)


# ---------------------------------------------------------------- conversions


def axis_angle_matrix(axis: np.ndarray, angle: np.ndarray) -> np.ndarray:
    """R_{n, phi}: the slides' 3x3 matrix for a rotation by ``angle`` (rad) about ``axis``."""
    axis, angle = _f(axis), _f(angle)
    n = axis / norm(axis)[..., None]
    x, y, z = n[..., 0], n[..., 1], n[..., 2]
    c, s = np.cos(angle), np.sin(angle)
    t = 1.0 - c
    # slides, "3D Angular Motion", option 2 (filled in place: np.stack costs more than the sums)
    m = np.empty(np.broadcast(x, c).shape + (3, 3))
    m[..., 0, 0], m[..., 0, 1], m[..., 0, 2] = (
        x * x + (1 - x * x) * c,
        x * y * t - z * s,
        x * z * t + y * s,
    )
    m[..., 1, 0], m[..., 1, 1], m[..., 1, 2] = (
        x * y * t + z * s,
        y * y + (1 - y * y) * c,
        y * z * t - x * s,
    )
    m[..., 2, 0], m[..., 2, 1], m[..., 2, 2] = (
        x * z * t - y * s,
        y * z * t + x * s,
        z * z + (1 - z * z) * c,
    )
    return m


def _axis_and_angle(phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Unit axis and angle of a scaled axis (any axis, here x, when the angle is 0)."""
    angle = norm(phi)
    safe = np.where(angle > 0.0, angle, 1.0)[..., None]
    axis = np.where(angle[..., None] > 0.0, phi / safe, np.array([1.0, 0.0, 0.0]))
    return axis, angle


def scaled_axis_to_matrix(phi: np.ndarray) -> np.ndarray:
    """Rotation matrix of the scaled axis ``phi`` (direction = axis, length = angle in rad)."""
    axis, angle = _axis_and_angle(_f(phi))
    return axis_angle_matrix(axis, angle)


def scaled_axis_to_quat(phi: np.ndarray) -> np.ndarray:
    """Unit quaternion [cos(|phi|/2), phi sin(|phi|/2) / |phi|] (exact at phi = 0)."""
    phi = _f(phi)
    angle = norm(phi)[..., None]
    half_sinc = 0.5 * np.sinc(angle / (2 * np.pi))  # sin(angle/2) / angle, 1/2 at angle 0
    return np.concatenate([np.cos(angle / 2), half_sinc * phi], axis=-1)


def quat_to_scaled_axis(q: np.ndarray) -> np.ndarray:
    """Scaled axis of the rotation ``q`` (normalised first), with angle in [0, pi]."""
    q = qcanonical(q)  # q and -q are the same rotation: take s >= 0
    s, v = q[..., 0], q[..., 1:]
    vn = norm(v)
    angle = 2.0 * np.arctan2(vn, s)
    factor = np.where(vn > 0.0, angle / np.where(vn > 0.0, vn, 1.0), 2.0 / s)
    return factor[..., None] * v


def quat_to_matrix(q: np.ndarray) -> np.ndarray:
    """Matrix of v -> q v q*: the rotation matrix for |q| = 1 (|q|^2 times it otherwise)."""
    q = _f(q)
    s, x, y, z = q[..., 0], q[..., 1], q[..., 2], q[..., 3]
    rows = [
        [s * s + x * x - y * y - z * z, 2 * (x * y - s * z), 2 * (x * z + s * y)],
        [2 * (x * y + s * z), s * s - x * x + y * y - z * z, 2 * (y * z - s * x)],
        [2 * (x * z - s * y), 2 * (y * z + s * x), s * s - x * x - y * y + z * z],
    ]
    return np.stack([np.stack(r, axis=-1) for r in rows], axis=-2)


def matrix_to_quat(m: np.ndarray) -> np.ndarray:
    """Unit quaternion (s >= 0) of a rotation matrix (Shepperd: divide by the largest term)."""
    m = _f(m)
    r = [[m[..., i, j] for j in range(3)] for i in range(3)]
    tr = r[0][0] + r[1][1] + r[2][2]
    # 4 |s|^2, 4 x^2, 4 y^2, 4 z^2 from the diagonal; the largest gives a well-conditioned divide
    big = np.stack([1 + tr, 1 + 2 * r[0][0] - tr, 1 + 2 * r[1][1] - tr, 1 + 2 * r[2][2] - tr], -1)
    k = np.argmax(big, axis=-1)
    h = 0.5 * np.sqrt(np.maximum(np.take_along_axis(big, k[..., None], -1)[..., 0], 1e-300))
    d = 0.25 / h
    a, b, c = r[2][1] - r[1][2], r[0][2] - r[2][0], r[1][0] - r[0][1]  # 4 s x, 4 s y, 4 s z
    e, f, g = r[0][1] + r[1][0], r[0][2] + r[2][0], r[1][2] + r[2][1]  # 4 x y, 4 x z, 4 y z
    rows = [[None, a, b, c], [a, None, e, f], [b, e, None, g], [c, f, g, None]]  # None: h
    cands = np.stack([np.stack([h if v is None else v * d for v in row], -1) for row in rows], -2)
    return qcanonical(np.take_along_axis(cands, k[..., None, None], -2)[..., 0, :])


def matrix_to_scaled_axis(m: np.ndarray) -> np.ndarray:
    """Scaled axis (angle in [0, pi]) of a rotation matrix."""
    return quat_to_scaled_axis(matrix_to_quat(m))


def wrap_scaled_axis(phi: np.ndarray) -> np.ndarray:
    """The same rotation with |phi| reduced to [0, pi] by subtracting multiples of 2 pi."""
    phi = _f(phi)
    angle = norm(phi)
    wrapped = angle - 2 * np.pi * np.round(angle / (2 * np.pi))  # in [-pi, pi]
    scale = np.where(angle > np.pi, wrapped / np.where(angle > 0.0, angle, 1.0), 1.0)
    return scale[..., None] * phi  # a negative scale flips the axis: same rotation


def nearest_rotation(m: np.ndarray) -> np.ndarray:
    """The rotation matrix closest to ``m`` in the Frobenius norm (polar decomposition, SVD)."""
    u, _, vt = np.linalg.svd(_f(m))
    det = np.linalg.det(u @ vt)
    u = u.copy()
    u[..., :, 2] *= det[..., None]  # keep det = +1 (no reflection)
    return u @ vt


def orthogonality_error(m: np.ndarray) -> np.ndarray:
    """||M^T M - I||_F: zero for a rotation matrix."""
    m = _f(m)
    e = np.swapaxes(m, -1, -2) @ m - np.eye(3)
    return np.sqrt(np.sum(e * e, axis=(-2, -1)))


def angle_between(qa: np.ndarray, qb: np.ndarray) -> np.ndarray:
    """Angle (rad, in [0, pi]) of the rotation taking orientation ``qa`` to ``qb``."""
    qa, qb = _f(qa), _f(qb)
    d = qmul(qconj(qa / qnorm(qa)[..., None]), qb / qnorm(qb)[..., None])
    return 2.0 * np.arctan2(norm(d[..., 1:]), np.abs(d[..., 0]))


def scaled_axis_rate(phi: np.ndarray, omega: np.ndarray) -> np.ndarray:
    """The true phi' for world angular velocity ``omega``: omega - phi x omega / 2 + c phi x (phi x omega).

    c = (1 - (theta/2) cot(theta/2)) / theta^2 with theta = |phi|. The slides' phi' = omega is
    this only when phi is parallel to omega (both cross products vanish).
    """
    phi, omega = _f(phi), _f(omega)
    th = norm(phi)
    big = th > 1e-4
    t = np.where(big, th, 1.0)
    c = np.where(big, (1.0 - 0.5 * t / np.tan(0.5 * t)) / (t * t), 1 / 12 + th * th / 720)
    pxw = cross(phi, omega)
    return omega - 0.5 * pxw + c[..., None] * cross(phi, pxw)


# ---------------------------------------------------------------- one interface, three structures


class Orientation:
    """An orientation (or a stack of them) in ``data``; subclasses fix the representation.

    ``integrate`` is the slides' update rule, ``integrate_exact`` the update that is exact when
    ``omega`` (world frame, rad/s) is constant over the step. Both change ``data`` in place
    and return ``self``.
    """

    name = "orientation"
    storage = 0  # floats per orientation

    def __init__(self, data: np.ndarray) -> None:
        self.data = np.array(data, dtype=float)

    @classmethod
    def from_quaternion(cls, q: np.ndarray) -> Orientation:
        raise NotImplementedError

    @classmethod
    def from_matrix(cls, m: np.ndarray) -> Orientation:
        return cls.from_quaternion(matrix_to_quat(m))

    @classmethod
    def from_scaled_axis(cls, phi: np.ndarray) -> Orientation:
        return cls.from_quaternion(scaled_axis_to_quat(phi))

    @classmethod
    def identity(cls, shape: tuple[int, ...] = ()) -> Orientation:
        return cls.from_quaternion(np.broadcast_to([1.0, 0.0, 0.0, 0.0], shape + (4,)))

    def copy(self) -> Orientation:
        return type(self)(self.data.copy())

    def integrate(self, omega: np.ndarray, dt: float) -> Orientation:
        raise NotImplementedError

    def integrate_exact(self, omega: np.ndarray, dt: float) -> Orientation:
        raise NotImplementedError

    def matrix(self) -> np.ndarray:
        raise NotImplementedError

    def quaternion(self) -> np.ndarray:
        """Unit quaternion with s >= 0 of the (nearest) rotation."""
        return matrix_to_quat(nearest_rotation(self.matrix()))

    def rotate(self, v: np.ndarray) -> np.ndarray:
        """Body-frame vector(s) ``v`` expressed in the world frame."""
        return matvec(self.matrix(), v)

    def renormalise(self) -> Orientation:
        raise NotImplementedError

    def drift(self) -> np.ndarray:
        """How far ``data`` is from a valid rotation (0 when it is one)."""
        raise NotImplementedError


class ScaledAxis(Orientation):
    """Option 1: phi, a 3-vector; direction = axis, length = angle (rad)."""

    name = "scaled axis"
    storage = 3

    @classmethod
    def from_quaternion(cls, q: np.ndarray) -> ScaledAxis:
        return cls(quat_to_scaled_axis(q))

    def integrate(self, omega: np.ndarray, dt: float) -> ScaledAxis:
        self.data = self.data + _f(omega) * dt  # slides, option 1: phi + omega dt
        return self

    def integrate_exact(self, omega: np.ndarray, dt: float) -> ScaledAxis:
        q = qmul(scaled_axis_to_quat(_f(omega) * dt), scaled_axis_to_quat(self.data))
        self.data = quat_to_scaled_axis(q)  # compose the rotations, then back to phi
        return self

    def matrix(self) -> np.ndarray:
        return scaled_axis_to_matrix(self.data)

    def quaternion(self) -> np.ndarray:
        return qcanonical(scaled_axis_to_quat(self.data))

    def renormalise(self) -> ScaledAxis:
        self.data = wrap_scaled_axis(self.data)  # slides: reduce |phi| to [0, pi]
        return self

    def drift(self) -> np.ndarray:
        return np.zeros(self.data.shape[:-1])  # every 3-vector is a valid rotation


class RotationMatrix(Orientation):
    """Option 2: Phi, a 3x3 rotation matrix (9 floats)."""

    name = "3x3 matrix"
    storage = 9

    @classmethod
    def from_quaternion(cls, q: np.ndarray) -> RotationMatrix:
        q = _f(q)
        return cls(quat_to_matrix(q / qnorm(q)[..., None]))

    @classmethod
    def from_matrix(cls, m: np.ndarray) -> RotationMatrix:
        return cls(m)

    def integrate(self, omega: np.ndarray, dt: float) -> RotationMatrix:
        step = scaled_axis_to_matrix(_f(omega) * dt)
        self.data = step @ self.data  # slides, option 2: R_{w^, |w| dt} Phi
        return self

    def integrate_exact(self, omega: np.ndarray, dt: float) -> RotationMatrix:
        return self.integrate(omega, dt)  # the slides' matrix rule is already exact

    def matrix(self) -> np.ndarray:
        return self.data.copy()

    def renormalise(self) -> RotationMatrix:
        self.data = nearest_rotation(self.data)
        return self

    def drift(self) -> np.ndarray:
        return orthogonality_error(self.data)


class Quaternion(Orientation):
    """Option 3: phi, a quaternion of unit norm [s, x, y, z]."""

    name = "quaternion"
    storage = 4

    @classmethod
    def from_quaternion(cls, q: np.ndarray) -> Quaternion:
        q = _f(q)
        return cls(q / qnorm(q)[..., None])

    def integrate(self, omega: np.ndarray, dt: float) -> Quaternion:
        # slides, "Quaternion-Based Orientation": phi + dt/2 [0 omega] phi
        self.data = self.data + 0.5 * dt * qmul(pure(omega), self.data)
        return self

    def integrate_exact(self, omega: np.ndarray, dt: float) -> Quaternion:
        self.data = qmul(scaled_axis_to_quat(_f(omega) * dt), self.data)
        return self

    def matrix(self) -> np.ndarray:
        return quat_to_matrix(self.data)

    def quaternion(self) -> np.ndarray:
        return qcanonical(self.data)

    def rotate(self, v: np.ndarray) -> np.ndarray:
        return qrotate(self.data, v)

    def renormalise(self) -> Quaternion:
        self.data = self.data / qnorm(self.data)[..., None]  # slides: phi' = phi / |phi|
        return self

    def drift(self) -> np.ndarray:
        return np.abs(qnorm(self.data) - 1.0)


REPRESENTATIONS: tuple[type[Orientation], ...] = (ScaledAxis, RotationMatrix, Quaternion)
