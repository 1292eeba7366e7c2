"""Settings changed between steps: the world adapts, nothing corrupts (a switch of orientation
representation converts every body's stored orientation), and a run that switches matches one
that does not."""

import math

import numpy as np
import pytest

from sandbox import Body, Box, Circle, World
from sandbox.joints import PivotJoint

REPRESENTATIONS = ("angle", "matrix", "complex")


def scene(**settings) -> World:
    """A spinning wheel on a hinge, a box resting on the ground and a disc rolling down to it."""
    w = World(gravity=(0, -9.81), **settings)
    w.add_body(Body("ground", type="static", position=(0, -0.5))).add_shape(Box(20, 1))
    w.add_body(Body("box", position=(0, 0.5), angle=0.2)).add_shape(Box(1, 1, friction=0.6))
    w.add_body(Body("disc", position=(-3, 2), angular_velocity=-4)).add_shape(Circle(0.4))
    axle = w.add_body(Body("axle", type="static", position=(4, 3)))
    wheel = w.add_body(Body("wheel", position=(4, 3), angular_velocity=7.0))
    wheel.add_shape(Box(1.5, 0.2))
    w.add_joint(PivotJoint(axle, wheel))
    return w


def state(w: World) -> np.ndarray:
    return np.concatenate([w.com.ravel(), w.vel.ravel(), w.omega, w.angles()])


def test_switching_representation_every_30_steps_matches_never_switching():
    # the same run, once in complex numbers throughout and once switching angle -> matrix ->
    # complex every 30 steps: positions, velocities and angles agree to 1e-9 after 300 steps
    plain, switching = scene(orientation="complex"), scene(orientation="complex")
    for step in range(300):
        if step % 30 == 0:
            switching.settings.orientation = REPRESENTATIONS[(step // 30) % 3]
            assert (
                switching.rot.shape[1]
                == {"angle": 1, "matrix": 4, "complex": 2}[switching.settings.orientation]
            )
        plain.step()
        switching.step()
    assert np.max(np.abs(state(plain) - state(switching))) < 1e-9
    assert abs(plain.body("wheel").angle) > 2 * math.pi  # the wheel turned more than once


def test_a_switch_keeps_every_angle_and_the_stored_numbers_follow():
    w = scene()
    for _ in range(50):
        w.step()
    for name in REPRESENTATIONS:
        before = w.angles()
        w.settings.orientation = name
        assert np.array_equal(w.angles(), before)  # the continuous angles are kept exactly
        c, s = np.cos(before), np.sin(before)
        # the stored numbers are those of each body's angle (rad), in the new layout
        assert np.allclose(w.cs, np.stack([c, s], axis=1), atol=1e-12)
        w.step()


@pytest.mark.parametrize(
    "key, values",
    [
        ("solver", ("pairwise", "shock", "iterative")),
        ("broadphase", ("brute", "grid", "quadtree", "kdtree", "sap")),
        ("integrator", ("explicit_euler", "verlet", "rk4", "semi_implicit_euler")),
        ("penetration", ("half", "mass_weighted", "impulse")),
        ("iterations", (1, 30, 10)),
        ("warm_start", (False, True)),
        ("accumulate_impulses", (False, True)),
        ("position_correction", (False, True)),
    ],
)
def test_every_setting_can_change_between_steps(key, values):
    # each value for 20 steps, mid-run: the run goes on, finite, the box still on the ground
    w = scene()
    for value in values:
        setattr(w.settings, key, value)
        for _ in range(20):
            w.step()
        assert np.all(np.isfinite(state(w)))
    assert abs(w.body("box").position[1] - 0.5) < 0.05  # resting, give or take 5 cm
