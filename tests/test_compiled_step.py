"""The whole step in one compiled call (``sandbox.collision.step_euler``) against the same
step taken phase by phase from Python, the reused contact buffers, and the manifolds it hands
out."""

import numpy as np
import pytest

from sandbox import Body, Box, Circle, World
from sandbox.collision import compiled
from sandbox.contact import ContactBuffers


def pile(broadphase="sap", **settings):
    """Boxes and discs dropped on a floor, falling over each other: every contact kind."""
    w = World(gravity=(0, -9.81), broadphase=broadphase, **settings)
    w.add_body(Body("floor", type="static", position=(0, -0.5))).add_shape(Box(12, 1))
    for i in range(24):
        x, y = -3.0 + 0.55 * (i % 12), 0.6 + 0.9 * (i // 12) + 0.05 * np.sin(7.0 * i)
        b = w.add_body(Body(f"b{i}", position=(x, y), angle=0.2 * np.sin(3.0 * i)))
        b.add_shape(Box(0.5, 0.4, restitution=0.3) if i % 2 else Circle(0.25, friction=0.4))
    return w


def run(w, steps=90):
    for _ in range(steps):
        w.step()
    return w


def test_compiled_step_equals_the_phase_by_phase_step():
    # sweep and prune takes the compiled step, brute force the Python one through the same
    # kernels: identical pairs, so bit-identical bodies, impulses and statistics
    fast, slow = pile("sap"), pile("brute")
    assert compiled(fast) and not compiled(slow)
    run(fast), run(slow)
    assert np.array_equal(fast.com, slow.com) and np.array_equal(fast.vel, slow.vel)
    assert np.array_equal(fast.omega, slow.omega) and np.array_equal(fast.rot, slow.rot)
    assert np.array_equal(fast.manifolds.normal_impulse, slow.manifolds.normal_impulse)
    assert np.array_equal(fast.manifolds.point, slow.manifolds.point)
    assert fast.stats["contacts"] == slow.stats["contacts"] > 10
    assert fast.stats["warm_started_points"] == slow.stats["warm_started_points"] > 0


def test_buffers_grow_without_changing_the_result():
    # room for 2 pairs at first: the step grows its buffers and runs again from where it
    # started, so the result is the same to the bit
    small, normal = pile(), pile()
    small._solver_cache["buffers"] = ContactBuffers(small.geometry(), capacity=2)
    run(small), run(normal)
    assert small._solver_cache["buffers"].capacity >= small.stats["pairs"]
    assert np.array_equal(small.com, normal.com) and np.array_equal(small.omega, normal.omega)


def test_held_manifolds_keep_their_step():
    # the buffers are reused every other step; manifolds someone still holds are copied out
    # first, so they keep showing the step they came from (exactly)
    w = run(pile(), 60)
    held = w.manifolds
    w.step()
    copy = w._solver_cache["buffers"].copy_out(1 - w._solver_cache["buffers"].now, len(held))
    for _ in range(3):
        w.step()
    assert len(held) == len(copy) > 0
    assert np.array_equal(held.normal_impulse, copy.normal_impulse)
    assert np.array_equal(held.depth, copy.depth) and np.array_equal(held.sb, copy.sb)


@pytest.mark.parametrize("switches", [{"warm_start": False}, {"position_correction": False}])
def test_switches_take_the_compiled_step_too(switches):
    # the teaching switches are arguments of the compiled step: same result as step by step
    fast, slow = run(pile("sap", **switches), 40), run(pile("grid", **switches), 40)
    assert np.array_equal(fast.com, slow.com) and np.array_equal(fast.omega, slow.omega)


def test_row_kernels_compute_the_readable_sweeps():
    # a sliding, turning box on two corners (one two-point manifold, block solver and friction):
    # sequential_impulses on Constraints and solve_rows on contact rows give the same velocities
    # and impulses, to rounding (1e-12)
    from sandbox import collision
    from sandbox.solvers import get, impulse, iterative

    def world():
        w = World(gravity=(0, -9.81), warm_start=False)
        w.add_body(Body("g", type="static", position=(0, -0.5))).add_shape(Box(10, 1))
        box = w.add_body(Body("box", position=(0, 0.499), velocity=(1.5, -0.5)))
        box.add_shape(Box(1, 1, friction=0.5))
        box.angular_velocity = 0.3
        return w

    readable, rows = world(), world()
    m1 = collision.detect(readable, readable.settings.contact_margin)
    m2 = collision.detect(rows, rows.settings.contact_margin)
    assert len(m1) == 1 and m1.count[0] == 2
    cons = impulse.build(readable, m1, readable.dt)
    iterative.sweep(readable, m1, cons, readable.settings.iterations)
    get("iterative").solve_velocities(rows, m2, rows.dt)
    assert np.allclose(readable.vel, rows.vel, atol=1e-12, rtol=0)
    assert np.allclose(readable.omega, rows.omega, atol=1e-12, rtol=0)
    assert np.allclose(m1.normal_impulse, m2.normal_impulse, atol=1e-12, rtol=0)
    assert np.allclose(m1.tangent_impulse, m2.tangent_impulse, atol=1e-12, rtol=0)
    assert m2.normal_impulse.min() > 0 and abs(m2.tangent_impulse).max() > 0
