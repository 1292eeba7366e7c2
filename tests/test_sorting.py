"""The kernels' one sort (``sandbox.sorting``) orders as ``np.argsort(kind="stable")`` does:
ties kept in order, NaN after every number, for float and integer keys, views included."""

from __future__ import annotations

import numpy as np
import pytest

from sandbox.sorting import argsort, sort_in_place


@pytest.mark.parametrize("n", [0, 1, 2, 15, 16, 17, 33, 100, 1000, 4097])
@pytest.mark.parametrize("kind", ["floats", "ties", "nan", "ints", "sorted", "reversed"])
def test_argsort_is_numpys_stable_argsort(n, kind):
    rng = np.random.default_rng(n)
    keys = {
        "floats": rng.normal(size=n),
        "ties": rng.integers(0, 5, n).astype(float),  # many equal keys: the order must hold
        "nan": np.where(rng.random(n) < 0.2, np.nan, rng.integers(0, 9, n) - 4.0),
        "ints": rng.integers(-50, 50, n),
        "sorted": np.arange(n, dtype=float),
        "reversed": np.arange(n, 0, -1).astype(np.int64),
    }[kind]
    order = argsort(keys)
    assert order.dtype == np.int64
    assert np.array_equal(order, np.argsort(keys, kind="stable"))


def test_negative_zero_ties_with_zero():
    keys = np.array([0.0, -0.0, 0.0, -1.0, -0.0])
    assert np.array_equal(argsort(keys), np.argsort(keys, kind="stable"))


@pytest.mark.parametrize("dtype", [np.float64, np.int64])
def test_sort_in_place_sorts_a_view_where_it_lies(dtype):
    rng = np.random.default_rng(3)
    table = rng.integers(0, 100, (50, 2)).astype(dtype)
    expected = table.copy()
    expected[10:40, 1] = np.sort(table[10:40, 1])
    sort_in_place(table[10:40, 1])  # a strided view: one column of some rows
    assert np.array_equal(table, expected)  # the rest untouched
    values = rng.normal(size=300).astype(dtype)
    expected = np.sort(values)
    sort_in_place(values)
    assert np.array_equal(values, expected)
