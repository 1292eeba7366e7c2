"""The wide position passes (sandbox.solvers.wide_positions): the penetration fix's position
impulses, eight contacts at a time, give bit for bit what the record pass gives in the same
order (colour by colour, then the contacts no colour could take)."""

from __future__ import annotations

import numpy as np
import pytest
from test_wide_sweeps import CASES, instructions, scenes

from sandbox.build import build_world
from sandbox.penetration import (
    first_push,
    fix_positions,
    position_impulses,
    wide_position_impulses,
)
from sandbox.position_layers import position_order
from sandbox.records import CONTACT
from sandbox.scene import validate_scene
from sandbox.solvers.iterative import visit
from sandbox.solvers.wide import COLOURS, colour

BOUNDS = (0.005, np.inf)  # slop (m), and no bound on the push (robust_positions off)
BETA = 0.2
GAP = 0.02  # m: contacts closer than this touch (only used by layered passes)


def sunk(contacts, bodies):
    """The same contacts 2 cm deeper than they were found, so that the passes push."""
    contacts = contacts.copy()
    contacts["points"]["depth"] += 0.02
    contacts["points"]["anchor_depth"] += 0.02
    return contacts, bodies


DEPTHS = ("as found", "2 cm deeper")


def case_at(case: str, depth: str):
    """The contacts and bodies of ``case``, as found or :func:`sunk`."""
    contacts, bodies, *_ = CASES[case]()
    return (contacts, bodies) if depth == "as found" else sunk(contacts, bodies)


@pytest.mark.parametrize("case", CASES)
@pytest.mark.parametrize("depth", DEPTHS)
def test_wide_passes_equal_the_record_passes_bit_for_bit(case, depth):
    contacts, bodies = case_at(case, depth)
    k = len(contacts)
    layering, lanes = position_order(contacts, k, bodies, False, GAP, BOUNDS, True)
    records = position_order(contacts, k, bodies, False, GAP, BOUNDS, False)[0]
    wide_b, record_b = bodies.copy(), bodies.copy()
    for _ in range(3):
        got = wide_position_impulses(contacts, wide_b, BETA, BOUNDS, layering, lanes)
        want = position_impulses(contacts, k, record_b, BETA, BOUNDS, records)
        assert got == want
    for field in ("com", "cs", "turn"):
        assert np.array_equal(wide_b[field], record_b[field]), field
    moved = np.abs(wide_b["com"] - bodies["com"]).max()
    if depth != "as found":  # they pushed, and turned the boxes; a disc follows its centre
        turned = np.abs(wide_b["turn"]).max()
        assert moved > 1e-3 and (turned > 0.0 if (contacts["count"] == 2).any() else turned == 0)


@pytest.mark.parametrize("case", CASES)
def test_the_order_is_colour_by_colour_then_the_rest_interleaved(case):
    contacts, bodies, *_ = CASES[case]()
    k = len(contacts)
    (order, _), (_, owners, starts, alone) = position_order(
        contacts, k, bodies, False, GAP, BOUNDS, False
    )
    assert sorted(order) == list(range(k))
    colours = np.empty(k, dtype=np.int64)
    count = colour(contacts, k, bodies, colours, True)
    assert len(starts) == count + 1
    coloured = [i for c in range(count) for i in np.flatnonzero(colours == c)]
    rest = np.flatnonzero(colours == COLOURS)
    rest = [rest[visit(q, (len(rest) + 1) // 2)] for q in range(len(rest))]
    assert list(order) == coloured + rest
    assert list(alone) == list(np.flatnonzero(colours == COLOURS))
    if not np.any(contacts["count"] == 2):  # discs: the old order of the passes, unchanged
        assert list(order) == [visit(q, (k + 1) // 2) for q in range(k)]


def test_a_held_contact_still_counts_its_bodies_as_moving():
    # the soft step zeroes a contact's copies of a held body's masses; the position passes
    # push that body all the same (with its own masses), so the colouring must see it move
    contacts, bodies = CASES["pyramid of base 20, boxes (two-point manifolds, block solver)"]()
    held = contacts.copy()
    held["inv_mass_a"] = held["inv_moment_a"] = 0.0
    k = len(held)
    colours = np.empty(k, dtype=np.int64)
    count = colour(held, k, bodies, colours, True)
    for c in range(count):
        moving = []
        for i in np.flatnonzero(colours == c):
            for side in ("a", "b"):
                if bodies["inv_mass"][held[side][i]] > 0.0:
                    moving.append(held[side][i])
        assert len(moving) == len(set(moving))
    sunk_held, _ = sunk(held, bodies)
    layering, lanes = position_order(sunk_held, k, bodies, False, GAP, BOUNDS, True)
    records = position_order(sunk_held, k, bodies, False, GAP, BOUNDS, False)[0]
    wide_b, record_b = bodies.copy(), bodies.copy()
    got = wide_position_impulses(sunk_held, wide_b, BETA, BOUNDS, layering, lanes)
    assert got == position_impulses(sunk_held, k, record_b, BETA, BOUNDS, records)
    assert np.array_equal(wide_b["com"], record_b["com"])


@pytest.mark.parametrize("case", CASES)
@pytest.mark.parametrize("depth", DEPTHS)
def test_first_push_says_whether_a_pass_would_move_anything(case, depth):
    # the look that lets the position stage skip a pass that would move nothing: it must find
    # a push exactly when the first pass moves something, and else the pass's smallest
    # separation, to the bit (the settled piles and planks as found push nothing, the rain
    # and everything 2 cm deeper do)
    contacts, bodies = case_at(case, depth)
    k = len(contacts)
    pushes, worst = first_push(contacts, k, bodies, BOUNDS)
    records = position_order(contacts, k, bodies, False, GAP, BOUNDS, False)[0]
    after = bodies.copy()
    pass_worst, moved, _ = position_impulses(contacts, k, after, BETA, BOUNDS, records)
    assert pushes == moved
    assert pushes == (depth != "as found" or case.startswith("rain"))
    if not pushes:
        assert worst == pass_worst
        assert np.array_equal(after, bodies)


def test_a_resting_pile_leaves_the_position_stage_as_one_pass_that_moved_nothing():
    # the whole stage, as a step runs it, on the pyramid at rest: the look stands for the
    # first pass (no pose, turn or angle changes; one pass counted; no progress to compare)
    world = build_world(validate_scene(scenes.pyramid(20)))
    for _ in range(60):
        world.step()
    a = world.arrays()
    ctx = a.context[0]
    s = int(ctx["contact_set"])
    k = int(ctx["contact_count"][s])
    contacts, before, rot = a.buffers.sets[s], a.bodies.copy(), a.rot.copy()
    worst = fix_positions(contacts, k, a.joints, a.bodies, a.rot, a.context)
    assert np.array_equal(a.bodies, before) and np.array_equal(a.rot, rot)
    assert ctx["position_passes"] == 1 and np.isnan(ctx["position_progress"])
    bounds = (ctx["slop"], ctx["max_push_speed"] * ctx["dt"])  # robust_positions is on
    records = position_order(contacts, k, before, False, GAP, bounds, False)[0]
    beta = ctx["baumgarte"]
    assert worst == position_impulses(contacts, k, before.copy(), beta, bounds, records)[0] < 0


def test_empty_contact_list():
    bodies = np.zeros(
        2, dtype=CASES["a plank under 80 boxes (contacts no colour takes)"]()[1].dtype
    )
    contacts = np.zeros(0, dtype=CONTACT)
    layering, lanes = position_order(contacts, 0, bodies, False, GAP, BOUNDS, True)
    assert wide_position_impulses(contacts, bodies, BETA, BOUNDS, layering, lanes) == (
        0.0,
        False,
        0.0,
    )


def test_the_lane_loop_compiles_to_vector_instructions():
    from sandbox.solvers import wide_positions

    args = (np.zeros(wide_positions.BLOCK), np.uint64(0), 0.2)
    packed, single = instructions(
        wide_positions.visit_block, args, "mul|div|sqrt", error_model="numpy"
    )
    assert packed > 20 and single < packed, (packed, single)
