"""The engines ``run.py`` times, each built from the same scene dict: this engine under each solver
(one column each), pymunk, and Box2D 2.3 when the ``box2d`` package is installed.

An engine is built into a :class:`Stepper`: ``run(n)`` takes n steps of the scene's dt in a tight
loop (only the engine's own step call inside it, so the loop costs every engine alike), and
``mean_y(ids)`` is the mean height (m) of the body origins with those scene indices.
"""

from __future__ import annotations

import copy
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import pymunk

from sandbox.build import build_world
from sandbox.pymunk_bridge import PymunkScene

try:  # the bench extra: pip install -e '.[bench]'
    import Box2D
    from box2d_scene import box2d_scene  # benchmarks/box2d_scene.py, beside this file

    BOX2D_VERSION = Box2D.__version__
    BOX2D_MISSING = ""
except ImportError as err:  # run.py prints one line and goes on without the Box2D column
    BOX2D_VERSION = ""
    BOX2D_MISSING = f"{err}"


@dataclass
class Stepper:
    """A built engine: ``run(n)`` steps it n times, ``mean_y(ids)`` is a check of its state."""

    run: Callable[[int], None]
    mean_y: Callable[[Sequence[int]], float]


@dataclass
class Engine:
    """One column of the step table.

    ``name`` is the column's title and the CSV prefix; ``build`` makes a :class:`Stepper` from a
    validated scene dict; ``contacts_only`` engines are left out of scenes without contacts;
    ``peer`` engines are the ones this engine's variants are compared with (ratio columns).
    """

    name: str
    build: Callable[[dict], Stepper]
    contacts_only: bool = False
    peer: bool = False


def _mean(values: Sequence[float]) -> float:
    return sum(values) / max(1, len(values))


def sandbox_engine(name: str, settings: dict, contacts_only: bool = False) -> Engine:
    """This engine with ``settings`` laid over the scene's own (e.g. ``{"solver": "soft"}``)."""

    def build(spec: dict) -> Stepper:
        spec = copy.deepcopy(spec)
        spec["settings"].update(settings)
        world = build_world(spec)

        def run(n: int) -> None:
            step = world.step
            for _ in range(n):
                step()

        def mean_y(ids: Sequence[int]) -> float:
            return _mean([world.bodies[i].position[1] for i in ids])

        return Stepper(run, mean_y)

    return Engine(name, build, contacts_only)


def build_pymunk(spec: dict) -> Stepper:
    """pymunk through ``sandbox.pymunk_bridge``; only ``Space.step`` runs in the loop (the
    benchmark scenes have no forces for the bridge to add)."""
    bridge = PymunkScene.from_scene(spec)
    space: pymunk.Space = bridge.space
    dt = spec["dt"]

    def run(n: int) -> None:
        step = space.step
        for _ in range(n):
            step(dt)

    def mean_y(ids: Sequence[int]) -> float:
        return _mean([bridge.bodies[i].position.y for i in ids])

    return Stepper(run, mean_y)


def build_box2d(spec: dict) -> Stepper:
    """Box2D 2.3 through ``box2d_scene``: ``b2World.Step(dt, velocity its, position its)``."""
    scene = box2d_scene(spec)
    step, dt = scene.world.Step, scene.dt
    velocity_iterations, position_iterations = scene.velocity_iterations, scene.position_iterations

    def run(n: int) -> None:
        for _ in range(n):
            step(dt, velocity_iterations, position_iterations)

    def mean_y(ids: Sequence[int]) -> float:
        return _mean([scene.bodies[i].position.y for i in ids])

    return Stepper(run, mean_y)


SOFT_SUBSTEPS = 4

# This engine's columns, in table order. Sleeping islands would get their column here, one
# line: sandbox_engine("sleep", {"sleep": True}, contacts_only=True) (bench_sleep.py measures them).
SANDBOX_ENGINES = [
    sandbox_engine("iterative", {"solver": "iterative"}),
    sandbox_engine("soft", {"solver": "soft", "substeps": SOFT_SUBSTEPS}, contacts_only=True),
]
PEER_ENGINES = [Engine("pymunk", build_pymunk, peer=True)]
if not BOX2D_MISSING:
    PEER_ENGINES.append(Engine("Box2D", build_box2d, peer=True))
ENGINES = SANDBOX_ENGINES + PEER_ENGINES
ALL_NAMES = [e.name for e in SANDBOX_ENGINES] + ["pymunk", "Box2D"]  # CSV columns, always
