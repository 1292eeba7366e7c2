"""Every compiled call of a step finds its machine code at once.

numba calls a compiled function from Python through its dispatcher: the argument types are
matched against the compiled signatures in C, in about a microsecond. A call that matches none
of them goes through ``_compile_for_args`` in Python, which types each record array afresh
(about 0.3 ms apiece). The position stage of the staged step left out the last argument of
``fix_positions`` (a default, since moved into the step's context); that call never matched
the machine code compiled for it and took the slow path every step: every staged step
(pairwise and shock solvers, the other broadphases, continuous collision, a stage timer) cost
1.4 ms more, ten times a whole step of 100 circles. Passing every argument matches at once.

The test counts the slow dispatches of later steps of every family the warm-up compiles, on
both paths (one call, stages one by one), and of a world that sleeps: there must be none. It
does not time anything."""

from __future__ import annotations

import pytest

from sandbox import jit, warmup
from sandbox.staged_step import StageTimer

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
    # the measure itself, on a call that takes the slow path: a compiled function with its
    # last arguments (defaults) left out, every time (the position stage's call did this,
    # before its flag moved into the step's context: sandbox.staged_step.position_stage)
    import numpy as np

    from sandbox.toi import time_of_impact

    disc = (0, 0.5, np.zeros(2), np.zeros((0, 2)))
    still, moving = (np.zeros(2), 0.0, np.zeros(2), 0.0), (np.zeros(2), 0.0, np.ones(2), 0.0)
    args = (disc, moving, disc, still)
    time_of_impact(*args, 0.0, 1e-4)
    time_of_impact(*args)
    slow_dispatches.clear()
    time_of_impact(*args, 0.0, 1e-4)
    assert slow_dispatches == []
    time_of_impact(*args)
    time_of_impact(*args)
    assert slow_dispatches == ["time_of_impact"] * 2


# In a fresh process: a compiled function of this script's, called first with a bool default
# left out, then every family's staged steps, counting their slow dispatches.
OMITTED_FIRST = """
import sys
from numba import njit
from numba.core.dispatcher import Dispatcher
from sandbox import warmup
from sandbox.staged_step import StageTimer

@njit
def flag(value={value}):
    return value

flag()
calls = []
original = Dispatcher._compile_for_args
def counted(self, *args, **kwargs):
    calls.append(self.py_func.__qualname__)
    return original(self, *args, **kwargs)
Dispatcher._compile_for_args = counted
slow = set()
for label, world, staged in warmup.worlds():
    world.timer = StageTimer()
    for _ in range(3):
        world.step()
    calls.clear()
    for _ in range(3):
        world.step()
    slow.update(f"{{label}}: {{name}}" for name in calls)
print(sorted(slow))
"""


@pytest.mark.parametrize("value", [False, True])
def test_a_default_left_out_elsewhere_does_not_slow_the_steps(value):
    # numba types an argument left out by a fingerprint of its default's type, not its value:
    # the first bool default a process leaves out fixes what every later one is taken for. A
    # step's call from Python that left out ``block=True`` (the prepare stage's, before the flag
    # moved into the context) then missed its machine code on every step once any other
    # call had left out a False, as a test of the wide position passes did (``colour``)
    import subprocess
    import sys

    script = OMITTED_FIRST.format(value=value)
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip().splitlines()[-1] == "[]"


def test_the_warmup_compiles_what_lessons_call_from_python(slow_dispatches):
    """Lessons call some kernels from Python with their own argument types (the soft step
    lesson's joint passes on copies of a chain's records, the rotation lesson's kernels, the
    broadphase lesson's sweep intervals): after the warm-up's helpers those calls find their
    machine code at once, so ``sandbox warmup`` leaves nothing for a lesson to compile."""
    import numpy as np

    from sandbox import orientation
    from sandbox.broadphase import sap
    from sandbox.joints.direct import solve_joints_direct
    from sandbox.joints.solve import solve_joints_soft
    from sandbox.scene import load_scene
    from sandbox.solvers.soft import softness

    warmup.helpers()
    slow_dispatches.clear()
    link = {"type": "box", "width": 0.5, "height": 0.1, "density": 20.0}
    bodies = [{"name": "hook", "type": "static", "position": [0.0, 10.0], "shapes": []}]
    joints = []
    for i in range(3):
        bodies.append({"name": f"link{i}", "position": [(i + 0.5) * 0.5, 10.0], "shapes": [link]})
        joints.append(
            {"type": "pivot", "a": "hook" if i == 0 else f"link{i - 1}", "b": f"link{i}",
             "anchor_a": [0.0, 0.0] if i == 0 else [0.25, 0.0], "anchor_b": [-0.25, 0.0]}
        )  # fmt: skip
    chain = load_scene({"version": 1, "name": "chain", "gravity": [0.0, -9.81], "dt": 1 / 60,
                        "settings": {"solver": "soft"}, "bodies": bodies, "joints": joints})  # fmt: skip
    chain.step()
    arrays = chain.arrays()
    h = chain.dt / chain.settings.substeps
    soft = softness(chain.settings.joint_hertz, chain.settings.joint_damping_ratio, h)
    for solve in (solve_joints_direct, solve_joints_soft):
        solve(arrays.joints.copy(), arrays.bodies.copy(), soft, True, 1.0 / h)
    rng = np.random.default_rng(0)
    for kind in orientation.NAMES.values():
        rot, cs = np.zeros((5, 4)), np.zeros((5, 2))
        orientation.set_angles(kind, rot, rng.uniform(-3.0, 3.0, 5))
        orientation.integrate_rotations(kind, rot, rng.uniform(-0.1, 0.1, 5), False)
        orientation.cos_sin(kind, rot, cs)
    sap.describe(rng.uniform(0.0, 1.0, (6, 4)) + np.array([0.0, 0.0, 1.0, 1.0]))
    assert slow_dispatches == []
