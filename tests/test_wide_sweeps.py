"""The wide sweeps (sandbox.solvers.wide): contacts coloured so that no two of a colour share a
moving body, visited eight at a time, give bit for bit what the one-by-one visits give in the
same order (colour by colour, then the contacts no colour could take), whether the lanes hand
the velocities on from sweep to sweep or, with joints or contacts no colour takes, through the
bodies' rows (sandbox.solvers.handoff)."""

from __future__ import annotations

import platform
import re
import sys
from pathlib import Path

import numpy as np
import pytest

from sandbox import Body, Box, Circle, PinJoint, World
from sandbox.build import build_world
from sandbox.jit import ON
from sandbox.joints.solve import solve_joint_velocities
from sandbox.records import CONTACT, JOINT
from sandbox.scene import validate_scene
from sandbox.solvers.iterative import coloured_sweeps, visit, visit_contact
from sandbox.solvers.wide import COLOURS, LANES, colour

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
import scenes  # noqa: E402


def settled(spec: dict, steps: int):
    """A world's last contacts (warm-started impulses and all) and bodies after ``steps``."""
    world = build_world(validate_scene(spec))
    for _ in range(steps):
        world.step()
    ctx = world.context[0]
    s = int(ctx["contact_set"])
    k = int(ctx["contact_count"][s])
    return world._buffers.sets[s][:k].copy(), world.state.copy()


NO_JOINTS = np.zeros(0, dtype=JOINT)


def one_by_one(contacts, bodies, n: int, joints=NO_JOINTS) -> None:
    """``n`` sweeps visiting the joints, then the contacts one at a time in the wide sweeps'
    order: colour by colour (in each, the two-point contacts, then the one-point ones), then
    the rest in the interleaved order of the one-by-one sweeps."""
    colours = np.empty(len(contacts), dtype=np.int64)
    count = colour(contacts, len(contacts), bodies, colours, False, True)
    order = [
        i
        for c in range(count)
        for points in (2, 1)
        for i in np.flatnonzero((colours == c) & (contacts["count"] == points))
    ]
    alone = np.flatnonzero(colours == COLOURS)
    order += [alone[visit(q, (len(alone) + 1) // 2)] for q in range(len(alone))]
    for _ in range(n):
        solve_joint_velocities(joints, bodies, ON)
        for i in order:
            visit_contact(contacts[i], bodies, True)


def fan(spokes: int, disc_every: int = 0):
    """A plank on the ground with ``spokes`` small boxes resting on it (every ``disc_every``-th
    a disc instead): more two-point contacts on one body than there are colours when
    spokes > 63."""
    w = World(gravity=(0.0, -9.81))
    w.add_body(Body("ground", type="static", position=(0.0, -0.5))).add_shape(Box(400.0, 1.0))
    w.add_body(Body("plank", position=(0.0, 0.25))).add_shape(Box(2.0 * spokes, 0.5))
    for i in range(spokes):
        small = Body(f"s{i}", position=(i - spokes / 2 + 0.5, 0.75), velocity=(0.0, -1.0))
        disc = disc_every and i % disc_every == 0
        w.add_body(small).add_shape(Circle(0.25) if disc else Box(0.5, 0.5))
    w.step()
    ctx = w.context[0]
    s = int(ctx["contact_set"])
    return w._buffers.sets[s][: int(ctx["contact_count"][s])].copy(), w.state.copy()


def tied_pile():
    """Boxes and discs piled on the ground, three of them tied by pins to their neighbours and
    one to a static hook: joints between the sweeps' colours."""
    w = World(gravity=(0.0, -9.81))
    ground = w.add_body(Body("ground", type="static", position=(0.0, -0.5)))
    ground.add_shape(Box(40.0, 1.0))
    hook = w.add_body(Body("hook", type="static", position=(0.0, 8.0)))
    pile = []
    for row in range(4):
        for i in range(6 - row):
            body = Body(f"b{row}_{i}", position=(i - 2.5 + 0.5 * row, 0.5 + 0.98 * row))
            pile.append(w.add_body(body))
            body.add_shape(Circle(0.45) if (row + i) % 3 == 0 else Box(0.95, 0.95))
    for a, b in ((pile[0], pile[1]), (pile[6], pile[7]), (pile[7], pile[11])):
        w.add_joint(PinJoint(a, b))
    w.add_joint(PinJoint(hook, pile[-1]))
    for _ in range(30):
        w.step()
    a = w.arrays()
    ctx = a.context[0]
    s = int(ctx["contact_set"])
    return a.buffers.sets[s][: int(ctx["contact_count"][s])].copy(), a.bodies.copy(), a.joints


CASES = {
    "pyramid of base 20, boxes (two-point manifolds, block solver)": lambda: settled(
        scenes.pyramid(20), 60
    ),
    "rain of 300 discs (one-point manifolds, their own lanes)": lambda: settled(
        scenes.rain(300), 150
    ),
    "a plank under 80 boxes (contacts no colour takes)": lambda: fan(80),
    "a plank under 40 boxes and 40 discs": lambda: fan(80, disc_every=2),
    "a pile of boxes and discs, some tied by pins (joints between the colours)": tied_pile,
}


@pytest.mark.parametrize("case", CASES)
def test_coloured_sweeps_equal_the_one_by_one_visits_bit_for_bit(case):
    contacts, bodies, *joints = CASES[case]()
    joints = joints[0] if joints else NO_JOINTS
    assert len(contacts) > 20
    wide_c, wide_b = contacts.copy(), bodies.copy()
    coloured_sweeps(wide_c, len(wide_c), joints.copy(), wide_b, 10)
    one_by_one(contacts, bodies, 10, joints.copy())
    for field in ("vel", "omega"):
        assert np.array_equal(wide_b[field], bodies[field]), field
    for field in ("normal_impulse", "tangent_impulse", "max_normal_impulse"):
        for j in range(2):
            used = contacts["count"] > j
            got = wide_c["points"][:, j][field][used]
            assert np.array_equal(got, contacts["points"][:, j][field][used]), field
    assert np.abs(bodies["vel"]).max() > 0.0  # the sweeps did something


@pytest.mark.parametrize("single", [False, True])
def test_no_colour_has_two_contacts_on_one_moving_body(single):
    # single: the one-point contacts get colours too (the velocity sweeps); else only the
    # two-point ones (the position passes)
    for case in CASES:
        contacts, bodies, *_ = CASES[case]()
        colours = np.empty(len(contacts), dtype=np.int64)
        count = colour(contacts, len(contacts), bodies, colours, False, single)
        wanted = contacts["count"] >= (1 if single else 2)
        assert np.all((colours < COLOURS) <= wanted), case
        on_plank = (contacts["a"] == 1) | (contacts["b"] == 1)  # body 1: the plank, if any
        if "plank" not in case or (wanted & on_plank).sum() <= COLOURS:
            assert np.all(colours[wanted] < COLOURS), case  # only a plank runs out of colours
        assert count <= COLOURS
        for c in range(count):
            moving = []
            for i in np.flatnonzero(colours == c):
                for side in ("a", "b"):
                    if contacts[f"inv_mass_{side}"][i] or contacts[f"inv_moment_{side}"][i]:
                        moving.append(contacts[side][i])
            assert len(moving) == len(set(moving))


def test_a_body_with_more_contacts_than_colours_has_the_rest_visited_alone():
    contacts, bodies = fan(80)
    colours = np.empty(len(contacts), dtype=np.int64)
    colour(contacts, len(contacts), bodies, colours)
    plank = 1  # the ground is body 0
    on_plank = (contacts["a"] == plank) | (contacts["b"] == plank)
    assert on_plank.sum() == 81  # the ground and 80 boxes
    assert (colours[on_plank] < COLOURS).sum() == COLOURS
    assert (colours == COLOURS).sum() == 81 - COLOURS


def test_empty_and_tiny_contact_lists():
    bodies = np.zeros(2, dtype=World().state.dtype)
    for k in (0, 1):
        contacts = np.zeros(k, dtype=CONTACT)
        if k:
            contacts["a"], contacts["b"], contacts["count"] = 0, 1, 1
        coloured_sweeps(contacts, k, np.zeros(0, dtype=JOINT), bodies, 3)
    assert not np.any(bodies["vel"])


def instructions(kernel, args, ops: str = "mul", **options) -> tuple[int, int]:
    """(packed, single): how many packed (``v<op>pd``) and single (``v<op>sd``) instructions of
    the ``ops`` (a regex alternative, as "mul|div") a fresh compile of ``kernel`` for ``args``
    holds (fresh, not from the cache, so that its assembly is kept). Skips the test where
    that says nothing: not x86, compiling off, or bounds checks on (they keep every loop one
    lane at a time)."""
    numba = pytest.importorskip("numba")
    if platform.machine() not in ("x86_64", "AMD64"):
        pytest.skip("x86 instructions")
    if not hasattr(kernel, "py_func"):
        pytest.skip("compiling is off (SANDBOX_JIT=0)")
    if numba.config.BOUNDSCHECK:
        pytest.skip("bounds checks keep the loop one lane at a time")
    fresh = numba.njit(**options)(kernel.py_func)
    fresh(*args)
    assembly = fresh.inspect_asm(fresh.signatures[-1])
    packed = len(re.findall(rf"\bv?({ops})pd\b", assembly))
    return packed, len(re.findall(rf"\bv?({ops})sd\b", assembly))


@pytest.mark.parametrize("kind", ["block solver", "point by point", "one point"])
def test_the_lane_loop_compiles_to_vector_instructions(kind):
    # what the wide sweeps are for: numba (LLVM) turns the loop over a block's eight lanes into
    # packed instructions (mulpd: several doubles at once), as long as the loop indexes the
    # lanes with unsigned numbers and hands the array to no other function; the two-point
    # lanes' function is compiled once with the block solver and once without
    from sandbox.solvers import wide, wide_single

    module = wide_single if kind == "one point" else wide
    extra = () if kind == "one point" else (kind == "block solver",)
    packed, single = instructions(
        module.visit_blocks, (np.zeros(module.BLOCK), np.uint64(0), 1, *extra)
    )
    assert packed > 10 and single < packed, (packed, single)


def test_each_lane_takes_its_bodies_velocities_from_the_lane_that_last_held_them():
    # two groups of one block of one-point lanes: body 1 in the first lane of both, body 0 in
    # the first group only, body 2 in the second only; every other lane empty (row 3)
    from sandbox.solvers import handoff, wide_single

    lanes = np.zeros((3, 2 * LANES), dtype=np.int64)
    lanes[1:] = 3
    lanes[:, 0], lanes[:, LANES] = (0, 0, 1), (1, 1, 2)
    none = np.zeros((3, 0), dtype=np.int64)
    size, at = wide_single.BLOCK, wide_single.VAX
    layouts = ((0, 0, at, 0), (0, size, at, 0))
    order = handoff.sweep_order(np.zeros(5, dtype=np.int64), np.array([0, 1, 2]), 2)
    sources, firsts, lasts = handoff.plan(order, (none, lanes), layouts, 4)
    other = handoff.OTHER
    first_b, second_a = int(at) + other, size + int(at)  # body 1 in each group
    now, later = sources[0], sources[1]
    assert now[1, 0] == first_b  # its first lane of a sweep: primed, itself
    assert now[0, LANES] == first_b  # the second group takes it from the first
    assert later[1, 0] == second_a  # a later sweep: from its last lane of the sweep before
    assert later[0, LANES] == first_b
    assert now[1, LANES] == later[1, LANES] == second_a + other  # body 2: one group, itself
    assert sorted(map(tuple, firsts)) == sorted(
        [(int(at), 0), (first_b, 1), (second_a + other, 2)]
        + [(int(at) + lane + side * other, 3) for lane in range(1, LANES) for side in (0, 1)]
    )
    assert dict(map(tuple, lasts)) == {
        0: int(at),
        1: second_a,
        2: second_a + other,
        3: size + int(at) + LANES - 1 + other,  # the empty lanes: the last of them
    }
