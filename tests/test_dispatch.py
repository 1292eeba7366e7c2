"""Every compiled call of a step finds its machine code at once.

numba calls a compiled function from Python through its dispatcher: the argument types are
matched against the compiled signatures in C, in about a microsecond. A call that matches none
of them goes through ``_compile_for_args`` in Python, which types each record array afresh
(about 0.3 ms apiece). The position stage of the staged step left out the last argument of
``fix_positions`` (a default); that call never matched the machine code compiled for it and
took the slow path every step: every staged step (pairwise and shock solvers, the other
broadphases, continuous collision, a stage timer) cost 1.4 ms more, ten times a whole step
of 100 circles. Passing every argument matches at once.

The test counts the slow dispatches of later steps of every family the warm-up compiles, on
both paths (one call, stages one by one), and of a world that sleeps: there must be none. It
does not time anything."""

from __future__ import annotations

import pytest

from sandbox import jit, warmup
from sandbox.step import StageTimer

pytestmark = pytest.mark.skipif(not jit.JIT_ENABLED, reason="dispatch only exists compiled")


@pytest.fixture
def slow_dispatches(monkeypatch):
    """A list that grows by the function's name at every slow (Python) dispatch."""
    from numba.core.dispatcher import Dispatcher

    calls: list[str] = []
    original = Dispatcher._compile_for_args

    def counted(self, *args, **kwargs):
        calls.append(self.py_func.__qualname__)
        return original(self, *args, **kwargs)

    monkeypatch.setattr(Dispatcher, "_compile_for_args", counted)
    return calls


def worlds():
    """Every family the warm-up compiles, on its own path and with a stage timer (the stages
    one by one), and a sleeping world."""
    for label, world, staged in warmup.worlds():
        if staged:
            world.timer = StageTimer()
        yield label, world
    for label, world, staged in warmup.worlds():
        if not staged:
            world.timer = StageTimer()
            yield f"{label}, timed", world
    yield "sleep", warmup.sample_world(sleep=True)


@pytest.mark.parametrize("label", [label for label, _ in worlds()])
def test_later_steps_never_take_the_slow_dispatch(label, slow_dispatches):
    world = dict(worlds())[label]
    for _ in range(3):  # the first steps may compile (or load from the cache)
        world.step()
    slow_dispatches.clear()
    for _ in range(3):
        world.step()
    assert slow_dispatches == []


def test_the_counter_sees_the_slow_dispatch_this_test_was_written_for(slow_dispatches):
    # the measure itself, on the call that took the slow path: the position stage with its
    # last argument (a default) left out, every time
    from sandbox.penetration import fix_positions

    world = warmup.sample_world(solver="pairwise")
    world.step()
    a = world.arrays()
    stage = (a.buffers.sets[0], 0, a.joints, a.bodies, a.rot, a.context)
    fix_positions(*stage, False)
    fix_positions(*stage)
    slow_dispatches.clear()
    fix_positions(*stage, False)
    assert slow_dispatches == []
    fix_positions(*stage)
    fix_positions(*stage)
    assert slow_dispatches == ["fix_positions"] * 2
