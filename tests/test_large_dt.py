"""A resting stack at a large dt (the reliability issue: "a resting 5-box stack at dt = 0.5 s
falls through the ground"; "a resting stack stays resting at large dt").

At dt = 0.5 s the contact margin is |g| dt^2 = 2.45 m, so every box of a 5-box stack has
speculative contacts with the boxes two and three above it. The stack is exactly symmetric
about x = 0, so with symmetric contacts and symmetric solves every box must stay at x = 0 with
angle 0 (to rounding).
"""

from __future__ import annotations

import numpy as np
import pytest

from sandbox import Body, Box, World

G = 9.81
BOXES = 5


def stack(dt: float, **settings) -> World:
    """Five unit boxes (default density and friction) resting on a static ground box whose top
    is y = 0, gravity 9.81 m/s^2."""
    w = World(dt=dt, **settings)
    w.add_body(Body("ground", type="static", position=(0.0, -0.5))).add_shape(Box(40.0, 1.0))
    for i in range(BOXES):
        w.add_body(Body(f"box{i}", position=(0.0, 0.5 + i))).add_shape(Box(1.0, 1.0))
    return w


def worst_over(w: World, steps: int) -> tuple[float, float, float]:
    """Run ``steps`` steps; the largest |x| (m), |y - resting height| (m) and |angle| (deg) of
    any box at the end of any step."""
    rest = 0.5 + np.arange(BOXES)
    worst = np.zeros(3)
    for _ in range(steps):
        w.step()
        dx = np.abs(w.com[1:, 0]).max()
        dy = np.abs(w.com[1:, 1] - rest).max()
        da = np.degrees(np.abs(w.state["angle"][1:])).max()
        worst = np.maximum(worst, (dx, dy, da))
    return tuple(worst)


def test_boxes_apart_face_to_face_give_two_points():
    # the first and third box are 1 m apart, inside the 2.45 m margin: their faces are equally
    # close all along, so the step's speculative contact is a face contact with both corners
    # (not one corner, which held the stack unevenly), each 1 m apart (depth -1) at detection
    w = stack(0.5)
    w.step()
    m = w.manifolds
    first, third = 1, 3  # body indices (the ground is 0)
    rows = [i for i in range(len(m)) if {int(m.a[i]), int(m.b[i])} == {first, third}]
    assert len(rows) == 1
    i = rows[0]
    assert m.count[i] == 2
    np.testing.assert_allclose(sorted(m.point[i, :, 0]), [-0.5, 0.5], atol=1e-12)
    np.testing.assert_allclose(m.depth[i], [-1.0, -1.0], atol=1e-12)


@pytest.mark.xfail(
    strict=True,
    reason="shock propagation pushes a manifold's two points one after the other, and the "
    "first push turns the box; solving the two pushes together holds this stack exactly, but "
    "made the pyramid of 40 rise 17 mm and walk 17 cm in 2 s (lesson 16), so it was not kept",
)
def test_shock_solver_holds_the_stack_at_half_a_second():
    # the bar over 20 s (40 steps): every box within 5 cm of x = 0 and of its resting
    # height, angles under 2 degrees
    dx, dy, da = worst_over(stack(0.5, solver="shock"), 40)
    assert dx < 0.05 and dy < 0.05 and da < 2.0, (dx, dy, da)


@pytest.mark.xfail(
    strict=True,
    reason="10 sweeps of sequential impulses leave about 0.921^10 = 44% of the first step's "
    "g dt (no warm start yet; Gauss-Seidel on a chain of 5 converges by cos^2(pi/11) per "
    "sweep), so the boxes sink up to 1.9 m into one another in the first steps; the position "
    "pass, one point after the other, tilts the deeply overlapping boxes and the stack "
    "topples (also with robust_positions and with solver: shock, test above)",
)
def test_default_solver_holds_the_stack_at_half_a_second():
    dx, dy, da = worst_over(stack(0.5), 40)
    assert dx < 0.05 and dy < 0.05 and da < 2.0, (dx, dy, da)


# the resting stack at dt = 1/60 after 300 steps as the code before the large-dt fixes gave it
# (bit-identical with and without robust_positions; x and angles exactly 0): the fixes act
# only on large overlaps and speculative contacts across a gap, which a 60 Hz stack never has
BEFORE_60HZ = (
    0.49936925332409665,
    1.4988589980743012,
    2.4988589980742995,
    3.4981538609126597,
    4.498153860912658,
)


@pytest.mark.parametrize("settings", [{}, {"robust_positions": True}])
def test_resting_stack_at_60_hz_is_unchanged(settings):
    w = stack(1 / 60, **settings)
    for _ in range(300):
        w.step()
    np.testing.assert_allclose(w.com[1:, 1], BEFORE_60HZ, rtol=0, atol=1e-9)
    np.testing.assert_allclose(w.com[1:, 0], 0.0, rtol=0, atol=1e-9)
    np.testing.assert_allclose(w.state["angle"][1:], 0.0, rtol=0, atol=1e-9)
