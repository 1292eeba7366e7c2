"""The two-thread narrowphase measured in ``benchmarks/bench_threads.py`` gives bit-identical
results to the engine's one-thread narrowphase: every manifold is computed by the same code from
the same inputs and the list is put together in pair order on one thread. Exact comparisons
(``==``), no tolerance. (It is not in the engine: on this kind of machine it did not pay.)"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest

from sandbox.narrowphase import collide_into
from sandbox.records import CONTACT

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
import bench_threads  # noqa: E402

STATE = ("com", "vel", "omega", "angle")
WRITTEN = ("a", "b", "shape_a", "shape_b", "count", "normal", "friction", "restitution")


def ground(width: float) -> dict:
    return {
        "name": "ground",
        "type": "static",
        "position": [0.0, -0.5],
        "shapes": [{"type": "box", "width": width, "height": 1.0, "friction": 0.6}],
    }


def pyramid(base: int) -> dict:
    """``base * (base + 1) / 2`` unit boxes resting on the ground in a pyramid."""
    bodies = [ground(2.0 * base)]
    for row in range(base):
        for k in range(base - row):
            x = k - 0.5 * (base - row - 1)
            box = {"type": "box", "width": 1.0, "height": 1.0, "friction": 0.6}
            bodies.append({"name": f"r{row}b{k}", "position": [x, row + 0.5], "shapes": [box]})
    return {"version": 1, "gravity": [0.0, -9.81], "dt": 1 / 60, "bodies": bodies}


def heap(n: int) -> dict:
    """``n`` circles, boxes and triangles in a tight, slightly overlapping grid falling onto
    the ground, every tenth one pinned to its neighbour (joined bodies do not collide)."""
    cols = int(math.sqrt(n))
    bodies, joints = [ground(cols + 4.0)], []
    for i in range(n):
        row, col = divmod(i, cols)
        x = col * 0.38 - 0.19 * cols + 0.02 * math.sin(12.9898 * i)
        if i % 3 == 0:
            shape = {"type": "circle", "radius": 0.2, "restitution": 0.3}
        elif i % 3 == 1:
            shape = {"type": "box", "width": 0.4, "height": 0.35, "friction": 0.8}
        else:
            shape = {"type": "polygon", "vertices": [[-0.2, -0.15], [0.2, -0.15], [0.0, 0.2]]}
        bodies.append({"name": f"b{i}", "position": [x, 0.3 + 0.36 * row], "shapes": [shape]})
        if i % 10 == 1:
            joints.append({"type": "pin", "a": f"b{i - 1}", "b": f"b{i}"})
    return {"version": 1, "gravity": [0.0, -9.81], "dt": 1 / 60, "bodies": bodies, "joints": joints}


def run(spec: dict, threads: int, steps: int):
    """A world stepped ``steps`` times with the ``threads``-thread narrowphase."""
    world = bench_threads.build(spec)
    bench_threads.step(world, threads, steps)
    return world


@pytest.mark.parametrize(("spec", "steps"), [(pyramid(25), 30), (heap(600), 60)])
def test_two_threads_step_bit_identical_to_one(spec, steps, monkeypatch):
    calls = []

    def counted(*args):
        calls.append(args[1])
        return bench_threads.collide_two_threads(*args)

    monkeypatch.setitem(bench_threads.NARROWPHASES, 2, counted)
    one = run(spec, 1, steps)
    two = run(spec, 2, steps)
    assert len(calls) == steps and min(calls) > 100  # the two-thread kernel did the work
    x, y = one.arrays().bodies, two.arrays().bodies
    for field in STATE:
        assert np.array_equal(x[field], y[field]), field
    m1, m2 = one.manifolds.records, two.manifolds.records
    assert len(m1) == len(m2) > 0
    for field in WRITTEN:
        assert np.array_equal(m1[field], m2[field]), field
    assert np.array_equal(m1["points"], m2["points"])


def test_threaded_kernel_writes_the_same_manifolds_in_pair_order():
    """Every pair of a settled heap (brute force, so most are far apart and skipped)."""
    world = run(heap(300), 1, 60)
    a = world.arrays()
    m = a.shapes.shape[0]
    i, j = np.triu_indices(m, 1)
    pairs = np.ascontiguousarray(np.stack([i, j], axis=1), dtype=np.int64)
    geometry = (a.shapes, a.vertices, a.bodies, a.joints)
    margin = float(a.context[0]["contact_margin"])
    one, two = np.zeros(len(pairs), CONTACT), np.zeros(len(pairs), CONTACT)
    k1 = collide_into(pairs, len(pairs), *geometry, (margin, 0.0), one)
    k2 = bench_threads.collide_two_threads(pairs, len(pairs), *geometry, (margin, 0.0), two)
    assert k1 == k2 > 100
    for field in WRITTEN:
        assert np.array_equal(one[field][:k1], two[field][:k2]), field
    for field in ("point", "depth", "feature"):
        assert np.array_equal(one["points"][field][:k1], two["points"][field][:k2]), field
