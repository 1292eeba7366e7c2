"""Continuous collision for the position stage (:mod:`sandbox.ccd_positions`): a ccd body the
position passes push out of one shape is not pushed through another.

Tolerances: the impact target and tolerance of :func:`sandbox.toi.ccd_fractions` (a quarter
of the contact margin, and a quarter of that), stated next to each assertion."""

from __future__ import annotations

import numpy as np
import pytest

from sandbox.ccd_positions import poses, sweep_position_moves
from sandbox.records import CONTACT

DT = 1.0 / 60.0


def wall_and_two_balls():
    """A thin static wall at x = 0 (its face at x = -0.01), a ccd ball and a plain ball of
    radius 0.05 m half a metre to its left."""
    from sandbox import Body, Box, Circle, World

    world = World(contact_margin=0.02)  # target separation 0.005, tolerance 0.00125
    world.add_body(Body("wall", type="static")).add_shape(Box(0.02, 2.0))
    world.add_body(Body("caught", position=(-0.5, 0.0), ccd=True)).add_shape(Circle(0.05))
    world.add_body(Body("plain", position=(-0.5, 0.5))).add_shape(Circle(0.05))
    world._prepare(DT)
    return world


def sweep(world, before) -> None:
    g = world.geometry()
    found = (np.zeros(0, dtype=CONTACT), 0, world.joint_table, True)
    sweep_position_moves(world.state, world.rot, g.table, g.vertices, world.context, before, found)


def test_a_position_move_through_a_wall_stops_at_its_face():
    # both balls are moved a metre right, through the wall, as a position pass might: the ccd
    # ball stops the impact target short of the face, the plain one keeps its whole move
    world = wall_and_two_balls()
    bodies = world.state
    before = poses(bodies)
    bodies["com"][1:, 0] += 1.0
    sweep(world, before)
    gap = -0.01 - (bodies["com"][1, 0] + 0.05)
    assert 0.005 - 1e-12 <= gap < 0.00625 + 1e-12  # target 0.005, tolerance 0.00125; round-off
    assert bodies["com"][1, 1] == 0.0
    assert bodies["com"][2, 0] == 0.5  # not ccd: as the stage left it


def test_a_move_shorter_than_the_target_is_left_exactly_as_it_is():
    # a move of 4 mm (under the 5 mm target) cannot cross a face the next narrowphase would
    # miss: nothing is swept and the stage's result stays bit for bit
    world = wall_and_two_balls()
    bodies = world.state
    before = poses(bodies)
    bodies["com"][1, 0] += 0.004
    after = bodies["com"].copy()
    sweep(world, before)
    assert np.array_equal(bodies["com"], after)


def square_driven_into_the_ceiling(solver: str) -> dict:
    """From a random scene: a 16 kg ball (ccd) at 58 m/s drives into a 0.16 kg square (ccd)
    below a ceiling at y = 8 m; the square ends deep in the ball, whose core was already deep
    in it, so continuous collision leaves that pair to the solver and the position stage."""

    def box(width, height, x, y):
        return {"type": "box", "width": width, "height": height, "offset": [x, y]}

    square = [[0.59, 0.52], [-0.52, 0.59], [-0.59, -0.52], [0.52, -0.59]]
    return {
        "version": 1, "name": "sandwich", "dt": 1 / 30,
        "settings": {"solver": solver, "substeps": 5, "penetration": "mass_weighted", "iterations": 6},
        "bodies": [
            {"name": "walls", "type": "static", "position": [0, 0],
             "shapes": [box(12, 1, 0, -0.5), box(1, 10, -5.5, 4), box(1, 10, 5.5, 4), box(12, 1, 0, 8.5)]},
            {"name": "ball", "position": [1.28, 4.07], "velocity": [30.6, 49.0], "ccd": True,
             "shapes": [{"type": "circle", "radius": 0.44, "density": 27.0, "friction": 0.07,
                         "restitution": 0.57}]},
            {"name": "square", "position": [2.67, 6.2], "angle": -0.9, "velocity": [2.2, 6.0],
             "angular_velocity": 1.2, "ccd": True,
             "shapes": [{"type": "polygon", "vertices": square, "density": 0.127, "friction": 0.42,
                         "restitution": 0.87}]},
        ],
    }  # fmt: skip


@pytest.mark.parametrize("solver", ["soft", "iterative", "shock"])
def test_a_light_body_squeezed_out_of_a_heavy_one_stays_below_the_ceiling(solver):
    # without the sweep the position stage took the square out of the ball in one pass, a
    # metre up and through the ceiling (its centre rose to 10.8 m under soft, 9.8 m under
    # iterative and shock, and it fell on the world's roof). With it, the square's core (a
    # circle of a quarter of its half side, 0.14 m) never passes the ceiling's face, and the
    # square comes to rest on the floor (half side 0.556 m) within 2 cm
    from sandbox import load_scene

    world = load_scene(square_driven_into_the_ceiling(solver))
    highest = -np.inf
    for _ in range(120):
        world.step()
        highest = max(highest, world.body("square").position[1])
    assert highest < 8.0 - 0.139
    assert abs(world.body("square").position[1] - 0.556) < 0.02
