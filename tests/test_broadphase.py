"""Broadphase: every strategy returns exactly the overlapping pairs brute force finds, with far
fewer tests on spread-out worlds; shape AABBs against hand-computed boxes."""

from __future__ import annotations

import math
import os
import subprocess
import sys

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from sandbox.broadphase import (
    STRATEGIES,
    describe,
    find_pairs,
    find_pairs_traced,
    shape_aabbs,
    swept_aabbs,
)


def reference_pairs(aabb: np.ndarray, static: np.ndarray, body: np.ndarray) -> np.ndarray:
    """Independent numpy check: all i < j with overlap on both axes (<=), filtered."""
    a = np.asarray(aabb)
    hit = (
        (a[:, None, 0] <= a[None, :, 2])
        & (a[None, :, 0] <= a[:, None, 2])
        & (a[:, None, 1] <= a[None, :, 3])
        & (a[None, :, 1] <= a[:, None, 3])
    )
    hit &= ~(static[:, None] & static[None, :])
    hit &= body[:, None] != body[None, :]
    i, j = np.nonzero(np.triu(hit, k=1))
    return np.stack([i, j], axis=1).astype(np.int64)


def random_world(m: int, seed: int, style: int):
    """Boxes of mixed size; style 0 floats, 1 integer lattice (many exact touches),
    2 a tight cluster, 3 some huge boxes and repeated identical boxes."""
    rng = np.random.default_rng(seed)
    side = math.sqrt(max(m, 1)) * 1.5
    if style == 1:
        lo = rng.integers(0, int(side) + 2, (m, 2)).astype(float)
        size = rng.integers(0, 3, (m, 2)).astype(float)
    else:
        lo = rng.uniform(-side, side, (m, 2)) * (0.05 if style == 2 else 1.0)
        size = rng.uniform(0.0, 2.0, (m, 2)) * rng.choice([0.2, 1.0, 3.0], (m, 1))
    if style == 3 and m:
        big = rng.random(m) < 0.05
        size[big] *= 30.0
        dup = rng.random(m) < 0.2
        src = rng.integers(0, m, m)
        lo[dup], size[dup] = lo[src[dup]], size[src[dup]]
    aabb = np.concatenate([lo, lo + size], axis=1)
    static = rng.random(m) < rng.choice([0.0, 0.3, 0.9])
    body = rng.integers(0, max(1, m // rng.choice([1, 2, 4])), m).astype(np.int64)
    return aabb, static, body


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    m=st.integers(0, 300),
    seed=st.integers(0, 2**32 - 1),
    style=st.integers(0, 3),
    capacity=st.integers(1, 12),
    cell=st.sampled_from([None, 0.3, 1.0, 4.0]),
)
def test_every_strategy_matches_brute_force(m, seed, style, capacity, cell):
    aabb, static, body = random_world(m, seed, style)
    expected = reference_pairs(aabb, static, body)
    options = {
        "brute": {},
        "grid": {"cell_size": cell},
        "sap": {},
        "quadtree": {"capacity": capacity},
        "kdtree": {"capacity": capacity},
    }
    for name in STRATEGIES:
        pairs, tests = find_pairs(name, aabb, static, body, **options[name])
        # exact equality of the int64 arrays: same pairs, same order, no duplicates
        assert pairs.dtype == np.int64 and pairs.shape == expected.shape, name
        assert np.array_equal(pairs, expected), name
        assert len(pairs) <= tests <= m * (m - 1) // 2, name


def test_5000_shapes_all_strategies_identical():
    aabb, static, body = random_world(5000, seed=2024, style=0)
    expected, brute_tests = find_pairs("brute", aabb, static, body)
    assert np.array_equal(expected, reference_pairs(aabb, static, body))
    assert len(expected) > 1000  # a busy world (about 1,900 overlapping pairs)
    for name in STRATEGIES[1:]:
        pairs, _ = find_pairs(name, aabb, static, body)
        assert np.array_equal(pairs, expected), name


def test_brute_counts_all_pairs_minus_filtered():
    aabb, static, body = random_world(200, seed=7, style=0)
    _, tests = find_pairs("brute", aabb, static, body)
    i, j = np.triu_indices(200, k=1)
    filtered = np.sum((static[i] & static[j]) | (body[i] == body[j]))
    assert tests == 200 * 199 // 2 - filtered  # exact count
    _, tests = find_pairs("brute", aabb)
    assert tests == 200 * 199 // 2


def test_static_static_and_same_body_pairs_excluded():
    box = [0.0, 0.0, 1.0, 1.0]
    aabb = np.array([box] * 5)  # five identical boxes: all 10 pairs overlap
    static = np.array([True, True, False, False, False])
    body = np.array([0, 1, 2, 3, 3])
    # left out: (0, 1) both static, (3, 4) one body
    expected = [[0, 2], [0, 3], [0, 4], [1, 2], [1, 3], [1, 4], [2, 3], [2, 4]]
    for name in STRATEGIES:
        pairs, _ = find_pairs(name, aabb, static, body)
        assert pairs.tolist() == expected, name


def test_touching_boxes_count_as_overlapping():
    aabb = np.array(
        [
            [0.0, 0.0, 1.0, 1.0],
            [1.0, 0.0, 2.0, 1.0],  # shares an edge with 0
            [2.0, 1.0, 3.0, 2.0],  # shares a corner with 1
            [3.0 + 1e-12, 0.0, 4.0, 1.0],  # a hair away from 2
            [0.5, 0.5, 0.5, 0.5],  # a point inside 0
        ]
    )
    for name in STRATEGIES:
        pairs, _ = find_pairs(name, aabb)
        assert pairs.tolist() == [[0, 1], [0, 4], [1, 2]], name


def test_empty_and_single_shape_worlds():
    for name in STRATEGIES:
        for m in (0, 1):
            pairs, tests = find_pairs(name, np.zeros((m, 4)), np.zeros(m, bool), np.arange(m))
            assert pairs.shape == (0, 2) and pairs.dtype == np.int64 and tests == 0


def test_unknown_strategy_is_an_error():
    with pytest.raises(ValueError, match="unknown broadphase"):
        find_pairs("octree", np.zeros((3, 4)))


def spread_world(m: int, seed: int = 5) -> np.ndarray:
    """Circles of radius 0.1-0.5 m scattered over a square sized for 30 % area coverage."""
    rng = np.random.default_rng(seed)
    r = rng.uniform(0.1, 0.5, m)
    side = math.sqrt(np.sum(math.pi * r * r) / 0.3)
    c = rng.uniform(0.0, side, (m, 2))
    return np.concatenate([c - r[:, None], c + r[:, None]], axis=1)


@pytest.mark.parametrize("name", ["grid", "sap", "quadtree", "kdtree"])
def test_far_fewer_tests_than_brute_force(name):
    m = 2000
    aabb = spread_world(m)
    pairs, tests = find_pairs(name, aabb)
    all_pairs = m * (m - 1) // 2
    # the spatial strategies should test well under 10 % of the 1,999,000 pairs
    # (about 0.1 % to 2 % in practice), and at least every reported pair
    assert len(pairs) <= tests < 0.10 * all_pairs


@pytest.mark.parametrize("name", STRATEGIES)
def test_recorded_tests_are_unique_and_cover_the_pairs(name):
    aabb = spread_world(400, seed=11)
    pairs, tests, tested = find_pairs_traced(name, aabb, record=True)
    assert len(tested) == tests
    assert np.all(tested[:, 0] < tested[:, 1])
    keys = tested[:, 0] * 400 + tested[:, 1]
    assert len(np.unique(keys)) == tests  # each pair tested once
    assert np.all(np.isin(pairs[:, 0] * 400 + pairs[:, 1], keys))


def test_slides_grid_example_tests_five_pairs():
    # slides, "Regular Grids": 9 bodies, 5 of the 36 pairs share a cell ((5) spans two cells)
    aabb = np.array(
        [
            [0.1, 0.1, 0.4, 0.4],  # 1 } cell (0, 0)
            [0.5, 0.5, 0.9, 0.9],  # 2 }
            [2.1, 0.1, 2.4, 0.4],  # 3 } cell (2, 0)
            [2.5, 0.2, 2.8, 0.5],  # 4 }
            [2.3, 0.6, 2.7, 1.4],  # 5 cells (2, 0) and (2, 1)
            [2.1, 1.5, 2.5, 1.9],  # 6 cell (2, 1)
            [0.2, 2.2, 0.8, 2.8],  # 7 alone
            [1.2, 1.2, 1.8, 1.8],  # 8 alone
            [3.2, 2.2, 3.8, 2.8],  # 9 alone
        ]
    )
    pairs, tests, tested = find_pairs_traced("grid", aabb, record=True, cell_size=1.0)
    assert tests == 5 and 9 * 8 // 2 == 36
    assert sorted(map(tuple, (tested + 1).tolist())) == [(1, 2), (3, 4), (3, 5), (4, 5), (5, 6)]
    assert pairs.tolist() == reference_pairs(aabb, np.zeros(9, bool), np.arange(9)).tolist()
    cells = describe("grid", aabb, cell_size=1.0)["cells"]
    assert len(cells) == 6  # (0,0) (2,0) (2,1) (0,2) (1,1) (3,2)


def test_structures_for_drawing():
    aabb = spread_world(300, seed=3)
    quad = describe("quadtree", aabb)
    leaves = quad["rects"][quad["leaf"]]
    root = quad["rects"][0]
    # the leaves tile the root square: their areas sum to its area (to rounding)
    area = np.prod(leaves[:, 2:] - leaves[:, :2], axis=1).sum()
    assert area == pytest.approx(np.prod(root[2:] - root[:2]), rel=1e-12)
    kd = describe("kdtree", aabb)
    assert kd["kept"].sum() == 300 and np.all(kd["node_of"] >= 0)
    inner = np.flatnonzero(kd["axis"] >= 0)
    ax = kd["axis"][inner]
    # every split line lies inside its node's region
    assert np.all(kd["region"][inner, ax] <= kd["split"][inner])
    assert np.all(kd["split"][inner] <= kd["region"][inner, ax + 2])
    sweep = describe("sap", aabb)
    assert np.all(np.diff(sweep["intervals"][sweep["order"], 0]) >= 0)


def test_aabb_of_rotated_box_and_offset_circle():
    angle = math.radians(30.0)
    c, s = math.cos(angle), math.sin(angle)
    com = np.array([[1.0, 2.0], [-3.0, 0.5]])
    cs = np.array([[c, s], [0.0, 1.0]])  # body 1 turned by 90 degrees
    hw, hh = 1.0, 0.5  # box 2 m x 1 m centred on body 0's centre of mass
    verts = np.array([[-hw, -hh], [hw, -hh], [hw, hh], [-hw, hh]])
    aabb = shape_aabbs(
        np.array([0, 1]),  # shape_body
        np.array([1, 0]),  # polygon, circle
        np.array([0.0, 0.25]),
        np.array([[0.0, 0.0], [1.0, 0.0]]),  # circle 1 m along the body's x axis
        np.array([0, 0]),
        np.array([4, 0]),
        verts,
        com,
        cs,
        0.1,
    )
    # box: half extents |c| hw + |s| hh = 1.1160 and |s| hw + |c| hh = 0.9330, plus margin
    ex = c * hw + s * hh + 0.1
    ey = s * hw + c * hh + 0.1
    assert aabb[0] == pytest.approx([1.0 - ex, 2.0 - ey, 1.0 + ex, 2.0 + ey], abs=1e-12)
    # circle: the offset (1, 0) turned by 90 degrees is (0, 1): centre (-3, 1.5), r + margin 0.35
    assert aabb[1] == pytest.approx([-3.35, 1.15, -2.65, 1.85], abs=1e-12)


def test_swept_aabbs_is_the_union():
    a0 = np.array([[0.0, 0.0, 1.0, 1.0]])
    a1 = np.array([[0.5, -2.0, 3.0, 0.5]])
    assert swept_aabbs(a0, a1).tolist() == [[0.0, -2.0, 3.0, 1.0]]


def test_plain_python_mode_gives_the_same_pairs_and_counts():
    code = (
        "import numpy as np\n"
        "from sandbox.broadphase import find_pairs, STRATEGIES\n"
        "rng = np.random.default_rng(9)\n"
        "lo = rng.uniform(0, 12, (150, 2)); a = np.concatenate([lo, lo + 1.0], 1)\n"
        "s = rng.random(150) < 0.3; b = rng.integers(0, 100, 150)\n"
        "for n in STRATEGIES:\n"
        "    p, t = find_pairs(n, a, s, b); print(n, t, p.tolist())\n"
    )
    env = dict(os.environ, SANDBOX_JIT="0")
    slow = subprocess.run(
        [sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True
    )
    fast = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert slow.stdout == fast.stdout and slow.stdout.count("\n") == len(STRATEGIES)


def lattice(n: int, spacing: float = 10.0, radius: float = 0.2) -> np.ndarray:
    """Boxes of ``n`` discs on a square grid ``spacing`` m apart (the free-body benchmark)."""
    side = int(math.sqrt(n))
    c = np.array([[spacing * (i % side), spacing * (i // side)] for i in range(n)], float)
    return np.concatenate([c - radius, c + radius], axis=1)


def test_sap_counts_the_candidates_of_every_direction():
    # the count that chooses the direction is the sweep's own test count: with no pair
    # filtered (each shape its own body, none fixed) the two must agree exactly in one band;
    # in bands the count is of the visits, and a pair that shares two bands is visited twice
    # and tested once
    from sandbox.broadphase.sap import DIRECTIONS, ONE_BAND, band_layout, candidates, proxies_of

    m = 500
    aabb = spread_world(m, seed=5)
    proxies = proxies_of(aabb, np.zeros(m, np.int64), np.arange(m))
    static, body = np.zeros(m, bool), np.arange(m)
    expected = reference_pairs(aabb, static, body).tolist()
    for d in range(len(DIRECTIONS)):
        pairs, tests = find_pairs("sap", aabb, axis=d, bands=False)
        assert tests == candidates(proxies, d, ONE_BAND)
        assert pairs.tolist() == expected  # the same pairs whatever the direction
        pairs, tests = find_pairs("sap", aabb, axis=d)
        visits = candidates(proxies, d, band_layout(proxies, d))
        if d < 2:  # cut into bands: a few pairs share two
            assert tests <= visits < 1.5 * tests
        else:  # a slanted sweep is not cut
            assert tests == visits
        assert pairs.tolist() == expected


def test_sap_sweeps_a_lattice_along_a_slanted_direction():
    # a row of a grid shares its lower end along y (and a column along x): swept along an
    # axis in one band, each disc is tested against its whole row; along the slanted
    # direction the rows fan out 10 sin(0.15) = 1.5 m apart, beyond a disc's 0.4 m
    aabb = lattice(1000)
    along_y = find_pairs("sap", aabb, axis=1, bands=False)[1]
    pairs, tests = find_pairs("sap", aabb, bands=False)
    assert describe("sap", aabb, bands=False)["axis"] in (2, 3)
    assert len(pairs) == 0 and along_y > 10_000
    assert tests < 0.1 * along_y
    # in bands each row is swept on its own, along x: not one test
    assert describe("sap", aabb)["axis"] in (0, 1)
    assert find_pairs("sap", aabb)[1] == 0


def test_sap_sweeps_a_wide_scatter_along_x():
    # a world ten times wider than high: in one band x is the direction with the fewest
    # candidates (the slanted ones lengthen every interval and mix in the height)
    rng = np.random.default_rng(2)
    c = rng.uniform((0.0, 0.0), (100.0, 10.0), (800, 2))
    aabb = np.concatenate([c - 0.2, c + 0.2], axis=1)
    assert describe("sap", aabb, bands=False)["axis"] == 0


def test_sap_keeps_a_pyramid_on_an_axis():
    # a pyramid of 20 1 m boxes at the base, grown by 2 cm: in one band the slanted y has 14%
    # fewer candidates than x (2,977 against 3,465), but a slanted test weighs a third more,
    # so x; in bands x and y take under half the tests of either
    boxes = []
    for row in range(20):
        for k in range(20 - row):
            x, y = k - 0.5 * (19 - row), row + 0.5
            boxes.append([x - 0.52, y - 0.52, x + 0.52, y + 0.52])
    aabb = np.array(boxes)
    tests = [find_pairs("sap", aabb, axis=d, bands=False)[1] for d in range(4)]
    assert tests[3] < tests[0] < tests[3] * 4 / 3  # the case the weight decides
    assert describe("sap", aabb, bands=False)["axis"] == 0
    banded = find_pairs("sap", aabb)[1]
    assert describe("sap", aabb)["axis"] in (0, 1) and banded < 0.5 * tests[3]
