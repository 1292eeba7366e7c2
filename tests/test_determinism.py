"""Deterministic: the same scene and settings give bit-identical results; every broadphase
gives the same simulation (they all return the same sorted pair list)."""

from pathlib import Path

import numpy as np
import pytest

import sandbox
from sandbox.scene import read_scene_file, validate_scene

SCENES = Path(__file__).resolve().parent.parent / "scenes"


def run(spec: dict, steps: int) -> np.ndarray:
    world = sandbox.load_scene(spec)
    for _ in range(steps):
        world.step()
    return np.concatenate([world.com.ravel(), world.vel.ravel(), world.omega, world.angles()])


@pytest.mark.parametrize("name", ["pyramid", "rain", "newtons_cradle"])
def test_same_scene_twice_is_bit_identical(name):
    spec = validate_scene(read_scene_file(SCENES / f"{name}.json"))
    a, b = run(spec, 90), run(spec, 90)
    assert np.array_equal(a, b)


def test_every_broadphase_gives_the_same_simulation():
    spec = validate_scene(read_scene_file(SCENES / "rain.json"))
    results = {}
    for name in ("brute", "grid", "sap", "quadtree", "kdtree"):
        spec["settings"]["broadphase"] = name
        results[name] = run(spec, 120)
    for name, state in results.items():
        assert np.array_equal(state, results["brute"]), name
