"""Vec2: the 2D vector bodies return (positions, velocities, world points)."""

from __future__ import annotations

import copy
import math
import pickle

import numpy as np
import pytest

import sandbox
from sandbox.vec2 import Vec2


def test_arithmetic_with_vectors_and_scalars():
    v, w = Vec2(3.0, 4.0), Vec2(1.0, -2.0)
    assert v + w == (4.0, 2.0) and type(v + w) is Vec2
    assert v - w == (2.0, 6.0)
    assert v + (1, 0) == (4.0, 4.0)  # a plain tuple is a vector, not concatenated
    assert (1, 0) + v == (4.0, 4.0) and type((1, 0) + v) is Vec2
    assert (0, 0) - v == (-3.0, -4.0)
    assert v * 2 == (6.0, 8.0) and 2 * v == (6.0, 8.0)  # not repetition
    assert v / 2 == (1.5, 2.0) and v // 2 == (1.0, 2.0)
    assert -v == (-3.0, -4.0) and +v == v
    assert v + 1.0 == (4.0, 5.0) and 1.0 - v == (-2.0, -3.0)  # scalars broadcast, as numpy
    with pytest.raises(TypeError):
        v * w  # no implicit dot product: use v.dot(w)


def test_geometry():
    v = Vec2(3.0, 4.0)
    assert v.length == 5.0 and abs(v) == 5.0 and v.length_squared == 25.0
    assert v.dot((1, 2)) == 11.0
    assert v.cross((1, 0)) == -4.0 and Vec2(1, 0).cross((0, 1)) == 1.0  # x cross y = +z
    assert v.normalized() == pytest.approx((0.6, 0.8), abs=1e-15)
    assert Vec2(0, 0).normalized() == (0.0, 0.0)
    turned = Vec2(1, 0).rotated(math.pi / 2)  # counter-clockwise
    assert turned == pytest.approx((0.0, 1.0), abs=1e-15)
    assert Vec2(0, 2).angle == pytest.approx(math.pi / 2, abs=1e-15)
    assert v.perpendicular() == (-4.0, 3.0) and v.distance((0, 0)) == 5.0


def test_tuple_behaviour_is_kept():
    v = Vec2(1, 2)
    x, y = v
    assert (x, y) == (1.0, 2.0) and v.x == 1.0 and v.y == 2.0
    assert isinstance(v, tuple) and v == (1.0, 2.0) and hash(v) == hash((1.0, 2.0))
    assert Vec2((5, 6)) == (5.0, 6.0) and Vec2(np.array([7.0, 8.0])) == (7.0, 8.0)
    assert repr(v) == "Vec2(1.0, 2.0)"
    assert pickle.loads(pickle.dumps(v)) == v and type(copy.deepcopy(v)) is Vec2
    np.testing.assert_array_equal(np.asarray(v), [1.0, 2.0])
    assert isinstance(v + np.array([1.0, 1.0]), np.ndarray)  # numpy keeps numpy semantics
    with pytest.raises(AttributeError):
        v.x = 3.0  # immutable


def test_bodies_return_vectors():
    world = sandbox.World(gravity=(0.0, 0.0))
    body = world.add_body(sandbox.Body("b", position=(1.0, 2.0), velocity=(3.0, 0.0)))
    body.add_shape(sandbox.Box(2.0, 1.0))
    body.angular_velocity = 2.0
    for value in (body.position, body.velocity, body.center_of_mass):
        assert type(value) is Vec2
    p = body.world_point((1.0, 0.0))
    assert type(p) is Vec2 and p == pytest.approx((2.0, 2.0), abs=1e-15)
    assert type(body.local_point(p)) is Vec2
    assert body.local_point(p) == pytest.approx((1.0, 0.0), abs=1e-15)
    # v + omega x r: r = (1, 0) from the centre of mass, omega = 2 -> (3, 0) + (0, 2)
    assert body.velocity_at(p) == pytest.approx((3.0, 2.0), abs=1e-15)
    # what a pymunk user writes
    moved = body.position + body.velocity * 0.5
    assert moved == pytest.approx((2.5, 2.0), abs=1e-15)


def test_a_turned_bodys_vectors_are_its_records_read_exactly():
    """position = com - R(angle) local_com, to the last bit, as Python floats; velocity and
    centre of mass are the records' own values."""
    world = sandbox.World(gravity=(0.0, -9.81))
    body = world.add_body(sandbox.Body("b", position=(1.0, 2.0), angle=0.7, velocity=(3.0, 1.0)))
    body.add_shape(sandbox.Box(2.0, 1.0, offset=(0.3, -0.2)))
    for _ in range(5):
        world.step()
    row = world.state[body.index]
    (c, s), lc, com = row["cs"], row["local_com"], row["com"]
    origin = com - np.array([c * lc[0] - s * lc[1], s * lc[0] + c * lc[1]])
    assert tuple(body.position) == tuple(origin.tolist()) and body.position != (1.0, 2.0)
    assert tuple(body.velocity) == tuple(row["vel"].tolist())
    assert tuple(body.center_of_mass) == tuple(com.tolist())
    values = (*body.position, *body.velocity, *body.center_of_mass)
    assert all(type(x) is float for x in values)
