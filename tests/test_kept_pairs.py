"""Sweep and prune keeps its pairs while every shape stays within the box it was swept with
(``sandbox.step.find_pairs``: ``FAT_MARGIN`` to spare, stretched along the velocity by
``settings.box_prediction`` steps): a pile at rest is swept again only when something moves, a
falling crowd every few steps, and both step exactly as with pairs found afresh every step."""

import sys
from pathlib import Path

import numpy as np
import pytest
from step_paths import same_state

from sandbox import Body, Box, Circle, World
from sandbox.build import build_world
from sandbox.scene import validate_scene
from sandbox.step import FAT_MARGIN

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
import scenes  # noqa: E402  (benchmarks/scenes.py: the benchmark scenes as scene dicts)


def pyramid(broadphase: str, solver: str) -> World:
    spec = validate_scene(scenes.pyramid(10))
    spec["settings"].update(broadphase=broadphase, solver=solver)
    return build_world(spec)


def rain(broadphase: str, box_prediction: float = 2.0) -> World:
    spec = validate_scene(scenes.rain(100))
    spec["settings"].update(broadphase=broadphase, box_prediction=box_prediction)
    return build_world(spec)


def swept(w: World) -> bool:
    """Whether the next step's broadphase sweeps (its boxes left their swept boxes)."""
    from sandbox.step import boxes_hold

    a, ctx = w.arrays(), w.context[0]
    reach = (ctx["contact_margin"], ctx["look_ahead"])
    return not (
        ctx["pairs_kept"] and boxes_hold(a.shapes, a.vertices, a.bodies, reach, a.buffers.proxies)
    )


@pytest.mark.parametrize("solver", ["iterative", "soft"])
def test_a_pyramid_keeps_its_pairs_and_steps_as_with_fresh_ones(solver):
    # brute force finds the exact pairs every step; sweep and prune keeps a superset while the
    # boxes stay within their swept boxes, and the narrowphase leaves the extra pairs out: the
    # same contacts in the same order, so the same state to the bit. The pyramid settles in
    # its first second; after that no box moves 2 cm, and sweep and prune sweeps no more
    kept, fresh = pyramid("sap", solver), pyramid("brute", solver)
    swept = []
    for _ in range(240):
        kept.step()
        fresh.step()
        swept.append(kept.stats["pair_tests"] > 0)
        assert kept.stats["contacts"] == fresh.stats["contacts"]
    assert same_state(kept, fresh)
    assert sum(swept[60:]) == 0 and sum(swept) <= 10


def test_a_body_moved_by_hand_is_swept_again_at_once():
    # two boxes at rest 4 m apart: their pairs are kept; a box set down on the other leaves
    # its swept box, so the very next search sweeps again and finds the contact
    w = World(gravity=(0, -9.81))
    w.add_body(Body("ground", type="static", position=(0, -0.5))).add_shape(Box(20, 1))
    a = w.add_body(Body("a", position=(-2, 0.5)))
    a.add_shape(Box(1, 1))
    b = w.add_body(Body("b", position=(2, 0.5)))
    b.add_shape(Box(1, 1))
    for _ in range(30):
        w.step()
    assert w.stats["pair_tests"] == 0  # kept
    b.position = (-2, 1.5 - 0.001)
    touching = {frozenset((c.a.name, c.b.name)) for c in w.find_contacts()}
    assert frozenset(("a", "b")) in touching
    assert w.stats["pair_tests"] > 0


def test_a_move_within_the_spare_margin_keeps_the_pairs():
    # a box nudged by less than the spare margin stays within its swept box: no sweep (with
    # no gravity, on a floor whose box meets theirs: a sweep tests at least those pairs)
    w = World(gravity=(0, 0))
    w.add_body(Body("floor", type="static", position=(0, -1))).add_shape(Box(20, 1))
    w.add_body(Body("a", position=(0, 0))).add_shape(Box(1, 1))
    b = w.add_body(Body("b", position=(3, 0)))
    b.add_shape(Box(1, 1))
    w.step()
    assert w.stats["pair_tests"] > 0  # the first search sweeps
    b.position = (3 + 0.9 * FAT_MARGIN, 0)
    w.step()
    assert w.stats["pair_tests"] == 0
    b.position = (3 + 2.0 * FAT_MARGIN, 0)
    w.step()
    assert w.stats["pair_tests"] > 0
    assert np.isfinite(w.com).all()


def sweeps_and_state(world: World, fresh: World, steps: int) -> int:
    """Step both worlds; assert the same contacts every step and the same state to the bit at
    the end; return how many of ``world``'s steps swept."""
    sweeps = 0
    for _ in range(steps):
        sweeps += swept(world)
        world.step()
        fresh.step()
        assert world.stats["contacts"] == fresh.stats["contacts"]
    assert same_state(world, fresh)
    return sweeps


def test_falling_discs_keep_their_pairs_for_steps_and_step_as_with_fresh_ones():
    # a hundred discs rain onto a floor at up to several metres a second, far more than the
    # spare margin each step: stretched along their velocities, the swept boxes hold them for
    # a few steps, and the kept pairs still hold every pair in reach (same contacts, same state
    # to the bit as brute force, which finds the exact pairs every step)
    stretched = sweeps_and_state(rain("sap"), rain("brute"), 120)
    assert stretched <= 50  # 40 measured
    unstretched = sweeps_and_state(rain("sap", 0.0), rain("brute"), 120)
    assert unstretched >= 65  # 72 measured: the spare margin alone
    further = sweeps_and_state(rain("sap", 8.0), rain("brute"), 120)
    assert further < stretched  # 31 measured


def test_a_box_is_stretched_on_the_side_its_body_moves_to():
    # one disc flying left and up: its swept box reaches box_prediction steps of travel ahead
    # of it (left and up) and only the margins behind it
    w = World(gravity=(0, 0), dt=0.01)
    w.settings.box_prediction = 3.0
    w.add_body(Body("floor", type="static", position=(0, -5))).add_shape(Box(1, 1))
    d = w.add_body(Body("d", position=(0, 0), velocity=(-3.0, 2.0)))
    d.add_shape(Circle(0.5))
    w.step()
    box = w.arrays().buffers.proxies[1]["aabb"]
    ctx = w.context[0]
    spare = ctx["contact_margin"] + FAT_MARGIN + 0.5  # radius, contact margin, spare margin
    assert ctx["look_ahead"] == 0.0  # no speculative reach: the margins are all it grows by
    x, y = 0.0, 0.0  # where the disc was when the step swept
    ahead = 3.0 * 0.01
    assert box[2] == pytest.approx(x + spare) and box[1] == pytest.approx(y - spare)
    assert box[0] == pytest.approx(x - spare - 3.0 * ahead)
    assert box[3] == pytest.approx(y + spare + 2.0 * ahead)
