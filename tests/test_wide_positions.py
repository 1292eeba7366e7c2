"""The wide position passes (sandbox.solvers.wide_positions): the penetration fix's position
impulses, eight contacts at a time, give bit for bit what the record pass gives in the same
order (colour by colour, then the contacts no colour could take)."""

from __future__ import annotations

import numpy as np
import pytest
from test_wide_sweeps import CASES, instructions

from sandbox.penetration import position_impulses, position_order, wide_position_impulses
from sandbox.records import CONTACT
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


@pytest.mark.parametrize("case", CASES)
@pytest.mark.parametrize("depth", ["as found", "2 cm deeper"])
def test_wide_passes_equal_the_record_passes_bit_for_bit(case, depth):
    contacts, bodies = CASES[case]()
    if depth != "as found":
        contacts, bodies = sunk(contacts, bodies)
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
    contacts, bodies = CASES[case]()
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
