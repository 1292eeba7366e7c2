"""A small immutable 2D vector, in the spirit of pymunk's ``Vec2d``.

:class:`Vec2` is a ``tuple`` subclass, so code that unpacks (``x, y = body.position``), indexes
or compares with plain tuples keeps working, and ``np.asarray(v)`` gives a length-2 array. Unlike
a plain tuple it does vector arithmetic::

    >>> v = Vec2(3.0, 4.0)
    >>> v + (1, 0), 2 * v, v / 2, -v
    (Vec2(4.0, 4.0), Vec2(6.0, 8.0), Vec2(1.5, 2.0), Vec2(-3.0, -4.0))
    >>> v.length, v.dot((1, 0)), v.cross((1, 0))
    (5.0, 3.0, -4.0)

Adding or subtracting a scalar applies it to both components, as numpy does. An operation with a
numpy array is left to numpy (the result is an array). Units are whatever the vector holds (m for
positions, m/s for velocities); angles are radians, counter-clockwise positive.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Iterable
from typing import Any

__all__ = ["Vec2"]


def _pair(other: Any) -> tuple[float, float] | None:
    """``other`` as two floats when it is a vector-like of length 2 (not an ndarray), else None."""
    if isinstance(other, tuple | list) and len(other) == 2:
        return other[0], other[1]
    return None


class Vec2(tuple):
    """An immutable 2D vector ``(x, y)``: a tuple with vector arithmetic."""

    __slots__ = ()

    def __new__(cls, x: float | Iterable[float] = 0.0, y: float | None = None) -> Vec2:
        if y is None and not isinstance(x, numbers.Real):
            x, y = x  # Vec2((1, 2)) and Vec2(array) as well as Vec2(1, 2)
        return tuple.__new__(cls, (float(x), float(0.0 if y is None else y)))

    @classmethod
    def of_floats(cls, xy: Iterable[float]) -> Vec2:
        """A vector of two Python floats as they are (``array.tolist()`` gives them), nothing
        converted or checked: for code that reads many vectors from the engine's records."""
        return tuple.__new__(cls, xy)

    # --- components ---------------------------------------------------------------------------
    @property
    def x(self) -> float:
        """First component."""
        return self[0]

    @property
    def y(self) -> float:
        """Second component."""
        return self[1]

    # --- arithmetic ---------------------------------------------------------------------------
    def __add__(self, other: Any) -> Vec2:
        p = _pair(other)
        if p is not None:
            return Vec2(self[0] + p[0], self[1] + p[1])
        if isinstance(other, numbers.Real):
            return Vec2(self[0] + other, self[1] + other)
        return NotImplemented

    __radd__ = __add__

    def __sub__(self, other: Any) -> Vec2:
        p = _pair(other)
        if p is not None:
            return Vec2(self[0] - p[0], self[1] - p[1])
        if isinstance(other, numbers.Real):
            return Vec2(self[0] - other, self[1] - other)
        return NotImplemented

    def __rsub__(self, other: Any) -> Vec2:
        p = _pair(other)
        if p is not None:
            return Vec2(p[0] - self[0], p[1] - self[1])
        if isinstance(other, numbers.Real):
            return Vec2(other - self[0], other - self[1])
        return NotImplemented

    def __mul__(self, other: Any) -> Vec2:
        if isinstance(other, numbers.Real):
            return Vec2(self[0] * other, self[1] * other)
        return NotImplemented  # not tuple repetition; for a dot product use .dot

    __rmul__ = __mul__

    def __truediv__(self, other: Any) -> Vec2:
        if isinstance(other, numbers.Real):
            return Vec2(self[0] / other, self[1] / other)
        return NotImplemented

    def __floordiv__(self, other: Any) -> Vec2:
        if isinstance(other, numbers.Real):
            return Vec2(self[0] // other, self[1] // other)
        return NotImplemented

    def __neg__(self) -> Vec2:
        return Vec2(-self[0], -self[1])

    def __pos__(self) -> Vec2:
        return self

    def __abs__(self) -> float:
        """The length, as ``abs`` of a complex number."""
        return math.hypot(self[0], self[1])

    # --- geometry -----------------------------------------------------------------------------
    @property
    def length(self) -> float:
        """|v|."""
        return math.hypot(self[0], self[1])

    @property
    def length_squared(self) -> float:
        """|v|^2."""
        return self[0] * self[0] + self[1] * self[1]

    @property
    def angle(self) -> float:
        """Direction of the vector from the +x axis (rad, in [-pi, pi], CCW positive)."""
        return math.atan2(self[1], self[0])

    def dot(self, other: Iterable[float]) -> float:
        """a . b = ax bx + ay by."""
        ox, oy = other
        return self[0] * ox + self[1] * oy

    def cross(self, other: Iterable[float]) -> float:
        """The 2D cross product a x b = ax by - ay bx (a scalar: the z of the 3D cross product)."""
        ox, oy = other
        return self[0] * oy - self[1] * ox

    def normalized(self) -> Vec2:
        """The unit vector along v (the zero vector stays zero)."""
        n = math.hypot(self[0], self[1])
        return Vec2(self[0] / n, self[1] / n) if n > 0.0 else Vec2(0.0, 0.0)

    def rotated(self, angle: float) -> Vec2:
        """v turned by ``angle`` (rad, counter-clockwise)."""
        c, s = math.cos(angle), math.sin(angle)
        return Vec2(c * self[0] - s * self[1], s * self[0] + c * self[1])

    def perpendicular(self) -> Vec2:
        """v turned by +90 degrees: (-y, x)."""
        return Vec2(-self[1], self[0])

    def distance(self, other: Iterable[float]) -> float:
        """|v - other|."""
        ox, oy = other
        return math.hypot(self[0] - ox, self[1] - oy)

    # --- display ------------------------------------------------------------------------------
    def __repr__(self) -> str:
        return f"Vec2({self[0]!r}, {self[1]!r})"

    def __getnewargs__(self) -> tuple[float, float]:  # pickling and copy
        return (self[0], self[1])
