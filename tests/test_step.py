"""The step in one compiled call (``sandbox.step.fast_step``) against the same stages called one
by one from Python (``staged_step``), the contact buffers it reuses, and the manifolds it hands
out."""

import numpy as np
import pytest
from step_paths import fast_and_staged, same_state

from sandbox import Body, Box, Circle, World
from sandbox.step import STAGES


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


def test_compiled_step_equals_the_staged_step():
    # one compiled call and the stages called from Python run the same functions in the same
    # order: bit-identical bodies, impulses and statistics (exact equality)
    fast, staged = fast_and_staged(pile, 90)
    assert fast._fast and staged.timer.steps == 90
    assert same_state(fast, staged)
    assert np.array_equal(fast.manifolds.normal_impulse, staged.manifolds.normal_impulse)
    assert np.array_equal(fast.manifolds.point, staged.manifolds.point)
    assert fast.stats == staged.stats and fast.stats["contacts"] > 10
    assert fast.stats["warm_started_points"] > 0
    assert set(staged.timer.seconds) == set(STAGES) and sum(staged.timer.seconds.values()) > 0


@pytest.mark.parametrize("solver", ["iterative", "soft"])
def test_the_step_counts_the_points_it_handed_out(solver):
    # the prepare stage counts the contacts' points as it goes (no pass of its own at the end):
    # the count is the handed-out manifolds', on both paths, discs (one point) and boxes (two)
    fast, staged = fast_and_staged(lambda: pile(solver=solver), 60)
    for w in (fast, staged):
        m = w.manifolds
        counts = np.bincount(m.count, minlength=3)
        assert counts[1] > 0 and counts[2] > 0, counts
        assert w.stats["contact_points"] == int(np.sum(m.count)) > w.stats["contacts"]


def test_every_broadphase_gives_the_same_step():
    # the broadphases return the same sorted pair list, so the simulation is identical
    reference = run(pile("sap"), 40)
    for name in ("brute", "grid", "quadtree", "kdtree"):
        assert same_state(run(pile(name), 40), reference), name


def test_buffers_grow_without_changing_the_result():
    # room for 2 pairs at first: the step grows its buffers and runs again from where it
    # started, so the result is the same to the bit
    from sandbox.contact import ContactBuffers

    small, normal = pile(), pile()
    small.step()
    normal.step()
    small._buffers = ContactBuffers(len(small.geometry()), capacity=2)
    small._choose_path()  # the step's calls take the new buffers
    small.context[0]["contact_count"][:] = 0
    normal.context[0]["contact_count"][:] = 0
    normal.context[0]["sweep_direction"] = small.context[0]["sweep_direction"] = -1
    run(small), run(normal)
    assert small._buffers.capacity >= small.stats["pairs"] > 2
    assert same_state(small, normal)


def test_held_manifolds_keep_their_step():
    # the buffers are reused every other step; manifolds someone still holds are copied out
    # first, so they keep showing the step they came from (exactly)
    w = run(pile(), 60)
    held = w.manifolds
    copy = held.records.copy()
    for _ in range(3):
        w.step()
    assert len(held) == len(copy) > 0
    assert np.array_equal(held.records, copy)


@pytest.mark.parametrize("switches", [{"warm_start": False}, {"position_correction": False}])
def test_switches_take_the_compiled_step_too(switches):
    # the teaching switches are read from the step context: same result either way
    fast, staged = fast_and_staged(lambda: pile(**switches), 40)
    assert same_state(fast, staged)


def test_a_timer_set_after_the_first_step_times_the_next_ones():
    # the world takes the staged path as soon as a timer is set, prepared or not
    from sandbox import Body, Circle, World
    from sandbox.staged_step import StageTimer

    w = World()
    w.add_body(Body("b")).add_shape(Circle(0.5))
    w.step()
    w.timer = StageTimer()
    w.step()
    w.step()
    assert w.timer.steps == 2


def test_the_stage_timer_is_still_found_where_it_was():
    from sandbox import staged_step
    from sandbox.step import StageTimer
    from sandbox.step import staged_step as moved

    assert StageTimer is staged_step.StageTimer
    assert moved is staged_step.staged_step
    with pytest.raises(ImportError):
        from sandbox.step import no_such_stage  # noqa: F401
