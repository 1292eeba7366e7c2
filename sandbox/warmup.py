"""Compile every kernel ahead of time (``sandbox warmup``): small worlds of every kind, stepped a
few times each, so that a class's first runs load machine code instead of compiling it.

Each world below exercises one family of stages: every solver through both the one-call step
and the staged step, every broadphase, every integrator with every kind of force, continuous
collision, every joint; then the functions lessons call directly (pair finding with a trace of
the tests, manifolds, distance and time of impact, the sweep's intervals, the rotation kernels,
the soft step's joint passes on copies of a world's records). When all of them ran, the cache
is marked warm (:func:`sandbox.compile_cache.mark_warm`), which the command line reads.

On a machine with two cores the families are shared out between two processes (:func:`part`),
each compiling its share into the same cache; then this process steps every family once more,
which loads what the other compiled and compiles whatever it missed. numba compiles one
function at a time per process, and every world steps through the same stages, so a process
loads from the cache what the other has already written there, and compiles again what the
other is still compiling. The two shares are therefore planned (:data:`FIRST_SHARE`), not dealt
round-robin:

- the first steps the iterative solver's one-call step, compiling its stages from the first
  (the longest family, 44 s on its own), its staged path, continuous collision (which steps
  staged, and whose time-of-impact code only it compiles), then the soft step, which reuses
  them, its staged path and the soft step with forces, and last the soft step's joint passes
  and the colouring on a world's records (:func:`record_kernels`);
- the second meanwhile compiles the same step's stages from the last, back to restitution
  (:func:`late_stages`: the position stage alone is a third of the step's compiling), so that
  the two meet in the middle and the first loads them; then the kernels lessons call on their
  own, which no step uses (:func:`lesson_kernels`), the integrators with forces, the other
  rigid solvers and the broadphases.

Measured on the project's 2-core machine from an empty cache (`sandbox warmup`, alternating the
codes): dealt round-robin, both shares began with the iterative solver and compiled the same
stages side by side for 40 s: 101 to 105 s and 182 to 190 CPU-s. Planned with both shares
starting at the first stage (the iterative step in one, the soft step in the other, which
compiled the shared stages beside it): 63.5 to 70.3 s and 112 to 123 CPU-s. With the second
share compiling from the last stage: 61.8 to 61.9 s and 116 to 117 CPU-s, no kernel compiled
twice but where the shares meet. In one process: about 103 s.
"""

from __future__ import annotations

import os
import subprocess
import sys
import threading
import time

import numpy as np

from sandbox.body import Body
from sandbox.compile_cache import CACHE_FOLDER, mark_warm
from sandbox.forces import Buoyancy, ConstantForce, Drag
from sandbox.joints import PinJoint, PivotJoint, SpringJoint
from sandbox.shapes import Box, Circle, Polygon
from sandbox.staged_step import StageTimer
from sandbox.world import World


def sample_world(**settings) -> World:
    """A floor, a box, a disc, a triangle, a pendulum on a pin, a hinged rod with limits and a
    motor, a spring: every kind of shape pair and joint."""
    w = World(gravity=(0.0, -9.81), **settings)
    floor = w.add_body(Body("floor", type="static", position=(0.0, -0.5)))
    floor.add_shape(Box(20.0, 1.0))
    w.add_body(Body("box", position=(0.0, 0.5))).add_shape(Box(1.0, 1.0))
    w.add_body(Body("disc", position=(0.3, 1.6))).add_shape(Circle(0.4, restitution=0.5))
    w.add_body(Body("tri", position=(-1.5, 0.6))).add_shape(
        Polygon([(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)])
    )
    hook = w.add_body(Body("hook", type="static", position=(4.0, 3.0)))
    bob = w.add_body(Body("bob", position=(5.0, 3.0)))
    bob.add_shape(Circle(0.2))
    w.add_joint(PinJoint(hook, bob))
    rod = w.add_body(Body("rod", position=(7.0, 3.0)))
    rod.add_shape(Box(2.0, 0.1))
    w.add_joint(PivotJoint(hook, rod, (2.0, 0.0), (-1.0, 0.0), limits=(-0.5, 0.5)))
    wheel = w.add_body(Body("wheel", position=(-5.0, 3.0)))
    wheel.add_shape(Circle(0.5))
    w.add_joint(PivotJoint(floor, wheel, (-5.0, 3.5), (0.0, 0.0), motor={"rate": 1.0}))
    return w


def with_forces(w: World) -> World:
    """Every force generator and a spring."""
    w.add_force(Drag(linear=0.1, quadratic=0.01, angular=0.01))
    w.add_force(Buoyancy(surface_y=0.5, fluid_density=2.0, linear_drag=0.5))
    w.add_force(ConstantForce(force=(1.0, 0.0), point=(0.1, 0.0), bodies=["box"]))
    w.add_joint(SpringJoint(w.body("box"), w.body("disc"), stiffness=20.0, damping=0.5))
    return w


def with_bullet(w: World) -> World:
    """A 5 cm ball at 400 m/s with continuous collision (``ccd``)."""
    w.add_body(Body("bullet", position=(-8.0, 2.0), velocity=(400.0, 0.0), ccd=True))
    w.body("bullet").add_shape(Circle(0.05))
    return w


def step(w: World, steps: int = 4, staged: bool = False) -> None:
    if staged:
        w.timer = StageTimer()
    for _ in range(steps):
        w.step()


# the families the bundled lessons step: every lesson ran from a cache with only these (and the
# helpers) compiled, and compiled nothing itself; the others (the broadphases' own steps, verlet
# and rk4 with forces, the soft step with forces, a lone verlet body with drag) took a two-core
# warmup from 53.5 s to 62 s
LESSON_FAMILIES = (
    "iterative solver",
    "iterative solver, staged",
    "soft solver",
    "soft solver, staged",
    "shock solver, staged",
    "pairwise solver, staged",
    "continuous collision",
    "explicit_euler and forces",
    "one body, semi_implicit_euler",
)


# the lessons' families the first share compiles last (the soft step's, then record_kernels): a
# first `sandbox lessons` starts the lessons that need none of them as soon as every other family
# is ready (on the core the second share has finished with), told by the file named in
# EARLY_READY, which the warmup creates then (sandbox.cli.lessons)
LATE_FAMILIES = ("soft solver", "soft solver, staged")
EARLY_READY = "SANDBOX_WARMUP_EARLY_READY"


def worlds(lessons: bool = False):
    """(label, world, staged) of every family the step compiles; ``lessons``: only those of
    :data:`LESSON_FAMILIES`."""
    for family in every_world():
        if not lessons or family[0] in LESSON_FAMILIES:
            yield family


def every_world():
    """(label, world, staged) of every family the step compiles."""
    for solver in ("iterative", "soft", "pairwise", "shock"):
        yield f"{solver} solver", sample_world(solver=solver), False
        yield f"{solver} solver, staged", sample_world(solver=solver), True
    for broadphase in ("brute", "grid", "quadtree", "kdtree"):
        yield f"{broadphase} broadphase", sample_world(broadphase=broadphase), False
    for integrator in ("explicit_euler", "verlet", "rk4"):
        yield f"{integrator} and forces", with_forces(sample_world(integrator=integrator)), False
    yield "rk4 and forces, staged", with_forces(sample_world(integrator="rk4")), True
    yield "soft step with forces", with_forces(sample_world(solver="soft")), False
    fast = with_bullet(sample_world())
    fast.body("disc").velocity = (0.0, -300.0)
    yield "continuous collision", fast, False
    yield "soft solver and continuous collision", with_bullet(sample_world(solver="soft")), False
    lone = World(integrator="semi_implicit_euler")
    lone.add_body(Body("ball")).add_shape(Circle(0.5))
    yield "one body, semi_implicit_euler", lone, False
    lone = World(integrator="verlet")  # a force field: the one-body step with work arrays
    lone.add_body(Body("ball")).add_shape(Circle(0.5))
    lone.add_force(Drag(linear=0.1))
    yield "one body, verlet and drag", lone, False


def late_stages() -> None:
    """The one-call steps' last stages, compiled first, on small worlds prepared but never
    stepped (no contacts): the iterative step's (:func:`sandbox.step.fast_step`) from the last,
    back to restitution (its position stage is a third of its compiling). The other share
    meanwhile compiles the step from its first stage, stepping its world, and loads from the
    cache what this share has finished, so the two meet in the middle instead of compiling
    the same stages side by side."""
    from sandbox.integrators import move_bodies, plan_motion
    from sandbox.penetration import fix_positions
    from sandbox.solvers.common import restitution
    from sandbox.step import finish_step

    a = prepared(box_on_floor())
    ctx = a.context[0]
    contacts, k = a.buffers.sets[1 - ctx["contact_set"]], 0
    finish_step(contacts, k, a.joints, a.bodies, a.context)
    fix_positions(contacts, k, a.joints, a.bodies, a.rot, a.context)
    move_bodies(a.bodies, a.rot, a.context)
    plan_motion(a.bodies, ctx["dt"])
    restitution(contacts, k, a.bodies, ctx["restitution_threshold"])


def box_on_floor(**settings) -> World:
    """A box on a static floor: no joints, nothing to divide by zero when a stage runs alone."""
    w = World(gravity=(0.0, -9.81), **settings)
    w.add_body(Body("floor", type="static", position=(0.0, -0.5))).add_shape(Box(20.0, 1.0))
    w.add_body(Body("box", position=(0.0, 0.5))).add_shape(Box(1.0, 1.0))
    return w


def prepared(w: World):
    """``w``'s records, prepared for a step on the staged path (which compiles nothing ahead,
    unlike the one-call step's)."""
    w.timer = StageTimer()
    w._prepare(w.dt)
    return w.arrays()


def helpers() -> None:
    """The compiled functions lessons and tests call on their own."""
    lesson_kernels()
    record_kernels()


def lesson_kernels() -> None:
    """The kernels lessons call on their own that no world's step uses: every broadphase with a
    trace of its tests, shape boxes, submerged areas, distance and time of impact, the sweep's
    intervals, the rotation kernels."""
    from sandbox import orientation
    from sandbox.broadphase import STRATEGIES, find_pairs_traced, sap, shape_aabbs
    from sandbox.buoyancy import circle_submerged, polygon_submerged
    from sandbox.toi import distance, time_of_impact

    boxes = np.array([[0.0, 0.0, 1.0, 1.0], [0.5, 0.5, 1.5, 1.5], [3.0, 3.0, 4.0, 4.0]])
    for name in STRATEGIES:
        find_pairs_traced(name, boxes, record=True)
    shape_aabbs(
        np.array([0]),
        np.array([0]),
        np.array([0.5]),
        np.zeros((1, 2)),
        np.array([0]),
        np.array([0]),
        np.zeros((0, 2)),
        np.zeros((1, 2)),
        np.array([[1.0, 0.0]]),
    )
    polygon_submerged(np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]]), 0.5)
    circle_submerged(0.0, 0.0, 1.0, 0.5)
    disc = (0, 0.5, np.zeros(2), np.zeros((0, 2)))
    square = (1, 0.0, np.zeros(2), np.array([[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]]))
    distance(disc, (np.zeros(2), 0.0), square, (np.array([2.0, 0.0]), 0.0))
    time_of_impact(  # with its limits, as the tunnelling lesson and the step call it
        disc,
        (np.zeros(2), 0.0, np.array([3.0, 0.0]), 0.0),
        square,
        (np.array([2.0, 0.0]), 0.0, np.array([2.0, 0.0]), 0.0),
        0.005,
        0.00125,
    )
    sap.describe(boxes)  # the sweep's intervals, as the broadphase lesson draws them
    rot, cs = np.zeros((2, 4)), np.zeros((2, 2))  # the rotation lesson's kernels
    kind = orientation.COMPLEX  # one compiled version serves every representation (an int)
    orientation.set_angles(kind, rot, np.zeros(2))
    orientation.integrate_rotations(kind, rot, np.zeros(2), True)
    orientation.cos_sin(kind, rot, cs)


def record_kernels() -> None:
    """The kernels lessons call from Python on copies of a stepped world's records: the soft
    step's joint passes, as the soft step lesson compares them (solved together, or swept),
    and the colouring of the contacts into independent groups, as the stacking lesson counts
    them."""
    from sandbox.joints.direct import solve_joints_direct
    from sandbox.joints.solve import solve_joints_soft
    from sandbox.solvers.soft import softness
    from sandbox.solvers.wide import colour

    world = sample_world(solver="soft")
    step(world)  # the joints' records prepared, as in a running world
    arrays = world.arrays()
    h = world.dt / world.settings.substeps
    soft = softness(world.settings.joint_hertz, world.settings.joint_damping_ratio, h)
    for solve in (solve_joints_direct, solve_joints_soft):
        solve(arrays.joints.copy(), arrays.bodies.copy(), soft, True, 1.0 / h)
    contacts = world.manifolds.records.copy()
    colours = np.empty(len(contacts), dtype=np.int64)
    colour(contacts, len(contacts), world.state.copy(), colours, False, True)


# two shares: the first's families, in this order; the second takes the others, the families of
# SECOND_SHARE_FIRST first (the integrators with forces and the other rigid solvers, which reuse
# the stages both shares compiled). Continuous collision moved to the first share when the soft
# step stopped compiling its time-of-impact code: left in the second, the lessons' warmup ended
# 10 s after the first share (62.8 s, against 51.9 s as here, the same hour)
FIRST_SHARE = (
    "iterative solver",
    "iterative solver, staged",
    "continuous collision",
    "soft solver",
    "soft solver, staged",
    "soft step with forces",
)
SECOND_SHARE_FIRST = (
    "explicit_euler and forces",
    "verlet and forces",
    "rk4 and forces",
    "rk4 and forces, staged",
    "shock solver",
    "shock solver, staged",
    "pairwise solver",
    "pairwise solver, staged",
)


def part(index: int, parts: int, lessons: bool = False) -> list:
    """Share ``index`` of ``parts`` of :func:`worlds` (``lessons``: of the lessons' families):
    (label, world, staged) of its families. Two shares are planned (:data:`FIRST_SHARE`, see
    the module); more are dealt round-robin, every family whose place in the list is ``index``
    modulo ``parts``."""
    families = list(worlds(lessons))
    if parts != 2:
        return [family for q, family in enumerate(families) if q % parts == index]
    by_label = {family[0]: family for family in families}
    if index == 0:
        return [by_label[label] for label in FIRST_SHARE if label in by_label]
    rest = [label for label in by_label if label not in FIRST_SHARE + SECOND_SHARE_FIRST]
    second = SECOND_SHARE_FIRST + tuple(rest)
    return [by_label[label] for label in second if label in by_label]


def warm_families(families, report=print) -> None:
    """Step each (label, world, staged) of ``families`` (compiling or loading its kernels) and
    report it ready."""
    for label, world, staged in families:
        step(world, staged=staged)
        world.find_contacts()
        report(f"  {label}: ready")


def warm_part(index: int, parts: int, report=print, lessons: bool = False) -> set[str]:
    """Compile (or load) share ``index`` of ``parts`` of the families (``lessons``: of the
    lessons' families), and the functions lessons call on their own (:func:`helpers`): with two
    shares the second begins with :func:`late_stages` and :func:`lesson_kernels` and the first
    ends with :func:`record_kernels` (see the module), otherwise the first share ends with all
    of them. Returns the labels of the families it stepped."""
    share = part(index, parts, lessons)
    planned = parts == 2
    if planned and index == 1:
        late_stages()  # while the first share compiles the steps from their first stage
        lesson_kernels()
    warm_families(share, report)
    if planned and index == 0:
        record_kernels()  # after the soft step, whose kernels they share
    elif index == 0:
        helpers()
    return {label for label, _, _ in share}


def warm_up(report=print, jobs: int | None = None, lessons: bool = False) -> float:
    """Compile (or load) every kernel; mark the cache warm. Returns the seconds it took.
    ``jobs``: processes to share the work between (default: 2 on a machine with two cores or
    more, else 1; always 1 without a cache to share, see the module). ``lessons``: only what
    the bundled lessons need (:data:`LESSON_FAMILIES` and the helpers), and the cache is not
    marked warm.

    ``report`` gets the line ``"  <family>: ready"`` once per family, as soon as the process
    whose share it is has stepped it: the other processes print theirs, and a thread here
    passes them on (:func:`relay`), so a progress bar moves with both shares."""
    start = time.perf_counter()
    jobs = jobs or min(2, os.cpu_count() or 1)
    if CACHE_FOLDER is None:  # nothing to share: each process would compile it all
        jobs = 1
    signal = os.environ.get(EARLY_READY) if lessons else None
    early = {f"  {label}: ready" for label in LESSON_FAMILIES if label not in LATE_FAMILIES}
    once = Once(report, early, signal)
    others = [
        subprocess.Popen(
            [sys.executable, "-m", "sandbox", "warmup", "--part", f"{i}/{jobs}"]
            + (["--lessons"] if lessons else []),
            stdin=subprocess.DEVNULL,
            stdout=subprocess.PIPE,  # its families' "ready" lines, passed on by relay()
            stderr=subprocess.DEVNULL,  # no compile notice nor bar of its own
            text=True,
        )
        for i in range(1, jobs)
    ]
    relays = [threading.Thread(target=relay, args=(p.stdout, once), daemon=True) for p in others]
    for thread in relays:
        thread.start()
    try:
        done = warm_part(0, jobs, once, lessons)  # with the helpers lessons call on their own
        for process, thread in zip(others, relays, strict=True):
            process.wait()
            thread.join()
    except BaseException:  # stopped (a signal to this process alone, Ctrl-C) or failed: the
        for process in others:  # other shares stop too, not compile on for a minute unowned
            process.kill()  # at once: a signal it could handle waits for LLVM's call to return
        release_lock(os.getpid())
        raise
    if jobs > 1:  # the others' shares: loaded from the cache, or compiled here if one missed them
        warm_families([family for family in worlds(lessons) if family[0] not in done], once)
    if not lessons:
        mark_warm()
    release_lock()
    return time.perf_counter() - start


def release_lock(pid: int | None = None) -> None:
    """Remove a background warmup's lock (:mod:`sandbox.cli.first_run`), when ``pid`` is given
    only if it names that process (a warmup that stops early leaves no lock behind it, which
    would keep the next run from starting one for ten minutes)."""
    if CACHE_FOLDER is None:
        return
    lock = CACHE_FOLDER / "warming"
    try:
        if pid is None or lock.read_text().strip() == str(pid):
            lock.unlink(missing_ok=True)
    except OSError:
        pass


class Once:
    """``report`` for each line the first time it comes (a family the other process compiled
    is stepped again here at the end, to load it: it is not ready twice), from any thread; and
    once every line of ``early`` has come, the file ``signal`` created (when not None)."""

    def __init__(self, report, early: set[str] | None = None, signal: str | None = None) -> None:
        self.report, self.seen, self.lock = report, set(), threading.Lock()
        self.early, self.signal = early or set(), signal

    def __call__(self, line: str) -> None:
        with self.lock:
            if line in self.seen:
                return
            self.seen.add(line)
            self.report(line)
            if self.signal is not None and self.early <= self.seen:
                with open(self.signal, "w"):  # the lessons that need only these can start
                    pass
                self.signal = None


def relay(stream, report) -> None:
    """Pass each line another warmup process prints (its families' "ready" lines) to
    ``report``, until that process ends."""
    for line in stream:
        if line.strip():
            report(line.rstrip("\n"))


def where() -> str:
    """Where the compiled kernels are kept."""
    return str(CACHE_FOLDER) if CACHE_FOLDER is not None else "nowhere (no writable folder)"
