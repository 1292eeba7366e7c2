"""Sort and sweep in bands across the sweep (``sandbox.broadphase.sap``): the same pairs as one
band, each pair tested once, far fewer tests in a tall pile, and no index past an array's end
for outliers and boxes that are not finite (also run with numba's bounds checks, ``Makefile``
``test-bounds``)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from sandbox import Body, Circle, World
from sandbox.broadphase import describe, find_pairs, find_pairs_traced
from sandbox.broadphase.sap import BAND_SPAN, MIN_BANDED
from sandbox.shapes import Box


def pile(rows: int, cols: int, radius: float = 0.2, gap: float = 0.01) -> np.ndarray:
    """Boxes of discs packed in staggered rows, each resting on the two below (a settled pile)."""
    pitch = 2.0 * radius + gap
    centres = np.array(
        [
            [pitch * (c + 0.5 * (r % 2)), pitch * math.sqrt(3.0) / 2.0 * r]
            for r in range(rows)
            for c in range(cols)
        ]
    )
    return np.concatenate([centres - radius, centres + radius], axis=1)


def reference(aabb: np.ndarray) -> np.ndarray:
    a = np.where(np.isfinite(aabb), aabb, np.nan)
    with np.errstate(invalid="ignore"):
        hit = (
            (a[:, None, 0] <= a[None, :, 2])
            & (a[None, :, 0] <= a[:, None, 2])
            & (a[:, None, 1] <= a[None, :, 3])
            & (a[None, :, 1] <= a[:, None, 3])
        )
    i, j = np.nonzero(np.triu(hit, k=1))
    return np.stack([i, j], axis=1).astype(np.int64)


def test_bands_cut_the_tests_of_a_tall_pile():
    # 50 rows of 60 discs: along x one band tests each disc against its whole column (about 50
    # rows); bands twice a disc tall leave a few rows each
    aabb = pile(50, 60)
    one, tests_one = find_pairs("sap", aabb, axis=0, bands=False)
    banded, tests = find_pairs("sap", aabb, axis=0)
    assert np.array_equal(banded, one) and np.array_equal(banded, reference(aabb))
    assert len(one) > 5700  # each disc's box overlaps the two below it (1 cm apart in a row)
    assert tests_one > 100_000
    assert len(one) <= tests < 0.1 * tests_one


@pytest.mark.parametrize("axis", [0, 1])
def test_each_pair_is_tested_in_one_band(axis):
    aabb = pile(20, 20)
    pairs, tests, tested = find_pairs_traced("sap", aabb, record=True, axis=axis)
    sweep = describe("sap", aabb, axis=axis)
    assert sweep["across"] == 1 - axis and len(sweep["edges"]) > 3  # cut into bands
    assert len(tested) == tests
    keys = tested[:, 0] * len(aabb) + tested[:, 1]
    assert len(np.unique(keys)) == tests  # no pair twice, though many boxes cross two bands
    assert np.any(sweep["band"][:, 1] > sweep["band"][:, 0])
    assert np.all(np.isin(pairs[:, 0] * len(aabb) + pairs[:, 1], keys))


def test_every_box_lies_in_its_bands():
    aabb = pile(12, 30)
    sweep = describe("sap", aabb, axis=0)
    edges, band, o = sweep["edges"], sweep["band"], sweep["across"]
    inner = edges[1:-1]  # the outer edges stand for the world's ends
    # equal bands from the lowest box to the highest, each at most BAND_SPAN mean boxes tall
    tallest = BAND_SPAN * np.mean(aabb[:, o + 2] - aabb[:, o])
    assert np.allclose(np.diff(edges), edges[1] - edges[0])
    assert edges[0] == aabb[:, o].min() and edges[-1] == pytest.approx(aabb[:, o + 2].max())
    n = len(edges) - 1
    assert tallest * n / (n + 1) < edges[1] - edges[0] <= tallest
    lo, hi = aabb[:, o], aabb[:, o + 2]
    first, last = band[:, 0], band[:, 1]
    assert np.all((first == 0) | (lo >= inner[np.maximum(first - 1, 0)]))
    assert np.all((last == len(inner)) | (hi < inner[np.minimum(last, len(inner) - 1)]))


def test_small_and_slanted_sweeps_keep_one_band():
    aabb = pile(4, MIN_BANDED // 4 - 1)  # fewer boxes than MIN_BANDED
    assert describe("sap", aabb, axis=0)["across"] == -1
    aabb = pile(20, 20)
    assert describe("sap", aabb, axis=2)["across"] == -1
    pairs, tests, tested = find_pairs_traced("sap", aabb, record=True, axis=2)
    assert len(tested) == tests and np.array_equal(pairs, reference(aabb))
    one_band, one_band_tests = find_pairs("sap", aabb, axis=2, bands=False)
    assert np.array_equal(pairs, one_band) and tests == one_band_tests


def test_outliers_and_boxes_that_are_not_finite():
    # a box far away stretches the bands (at most MAX_BANDS of them); boxes with a NaN or an
    # infinite end fall in the outer bands; nothing is read past an array's end and the
    # finite boxes' pairs are all found
    aabb = pile(20, 20)
    far = np.array([[1e12, 1e12, 1e12 + 1.0, 1e12 + 1.0]])
    odd = np.array([[np.nan, 0.0, 1.0, 1.0], [0.0, np.nan, 1.0, 1.0], [0.0, -np.inf, 1.0, np.inf]])
    for extra in (far, odd, np.concatenate([far, odd])):
        world = np.concatenate([aabb, extra])
        for axis in (0, 1, None):
            pairs, _ = find_pairs("sap", world, axis=axis)
            found = {tuple(p) for p in pairs.tolist()}
            assert {tuple(p) for p in reference(aabb).tolist()} <= found
    # a box infinite across the sweep: the span is not finite, so one band, and the box
    # meets every box whose x interval overlaps its own
    world = np.concatenate([aabb, [[0.0, -np.inf, 1.0, np.inf]]])
    assert describe("sap", world, axis=0)["across"] == -1
    pairs, _ = find_pairs("sap", world, axis=0)
    tall = len(aabb)
    crossing = np.flatnonzero((aabb[:, 0] <= 1.0) & (aabb[:, 2] >= 0.0))
    assert pairs[pairs[:, 1] == tall, 0].tolist() == crossing.tolist()


def test_the_step_sweeps_in_bands():
    # a world's first step sweeps its boxes as find_pairs("sap") does: the same pairs and the
    # same test count, well under the count of one band
    w = World(gravity=(0.0, -9.81))
    w.add_body(Body("floor", type="static", position=(0.0, -0.5))).add_shape(Box(20.0, 1.0))
    for k, (x0, y0, x1, y1) in enumerate(pile(30, 20)):
        w.add_body(Body(f"d{k}", position=(0.5 * (x0 + x1), 0.5 * (y0 + y1) + 0.3)))
        w.bodies[-1].add_shape(Circle(0.2))
    w.step()
    proxies = w.arrays().buffers.proxies
    args = (proxies["aabb"].copy(), proxies["fixed"].copy(), proxies["body"].copy())
    pairs, tests = find_pairs("sap", *args)
    assert w.stats["pair_tests"] == tests and w.stats["pairs"] == len(pairs)
    assert tests < 0.3 * find_pairs("sap", *args, bands=False)[1]
