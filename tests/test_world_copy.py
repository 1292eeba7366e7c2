"""copy.deepcopy of a world (sandbox.copying): the same graph, independent of the original."""

import copy

import numpy as np

from sandbox import Body, Box, Circle, World


def small_pile() -> World:
    w = World(gravity=(0, -9.81))
    w.add_body(Body("floor", type="static", position=(0, -0.5))).add_shape(Box(10, 1))
    for i in range(4):
        b = w.add_body(Body(f"b{i}", position=(0.3 * i - 0.4, 0.5 + 1.05 * i), angle=0.05 * i))
        b.add_shape(Box(1, 1) if i % 2 else Circle(0.5))
    return w


def test_a_copied_world_steps_as_the_original_to_the_bit():
    w = small_pile()
    c = copy.deepcopy(w)
    for _ in range(60):
        w.step()
        c.step()
    assert w.com.tobytes() == c.com.tobytes() and w.vel.tobytes() == c.vel.tobytes()
    assert w.omega.tobytes() == c.omega.tobytes()


def test_a_copy_is_the_same_graph_and_owns_its_parts():
    w = small_pile()
    c = copy.deepcopy(w)
    for body, twin in zip(w.bodies, c.bodies, strict=True):
        assert twin is not body and twin.world is c and twin.name == body.name
        for shape, copied in zip(body.shapes, twin.shapes, strict=True):
            assert copied is not shape and copied.body is twin and type(copied) is type(shape)
            assert copied.friction == shape.friction and copied.density == shape.density
            if isinstance(shape, Box):
                assert copied.vertices is not shape.vertices
                assert np.array_equal(copied.vertices, shape.vertices)
    c.body("b2").velocity = (3.0, 0.0)
    c.add_body(Body("late", position=(4.0, 2.0))).add_shape(Circle(0.2))
    c.step()
    assert tuple(w.body("b2").velocity) == (0.0, 0.0) and len(w.bodies) == 5
    assert w.steps == 0 and c.steps == 1


def test_a_copy_of_a_stepped_world_steps_on_its_own():
    # the way a step runs is bound to a world's arrays: the copy chooses its own (before, a
    # stepped copy stepped the original's bodies), so original and copy go on alike, apart
    w = small_pile()
    for _ in range(20):
        w.step()
    c = copy.deepcopy(w)
    before = w.com.copy()
    c.step()
    assert np.array_equal(w.com, before) and w.steps == 20 and c.steps == 21
    w.step()
    for _ in range(30):
        w.step()
        c.step()
    assert w.com.tobytes() == c.com.tobytes() and w.vel.tobytes() == c.vel.tobytes()
    c.settings.iterations = 3  # the copy's settings tell the copy, not the original
    assert c._dirty and not w._dirty and w.settings.iterations != 3
