"""``sandbox.bits.lowest_bit``: the index of an integer's lowest set bit, compiled (one
instruction) and uncompiled (``SANDBOX_JIT=0``) alike, as the colouring uses it."""

import numpy as np
import pytest

from sandbox.bits import lowest_bit
from sandbox.jit import njit

CASES = [(1, 0), (2, 1), (12, 2), (1 << 40, 40), (1 << 62, 62), ((1 << 62) | 1, 0), (96, 5)]


@njit
def lowest_of(values, out) -> None:
    for i in range(values.shape[0]):
        out[i] = lowest_bit(values[i])


@njit
def lowest_of_one(value) -> int:
    return lowest_bit(value)


@pytest.mark.parametrize(("value", "index"), CASES)
def test_lowest_set_bit(value, index):
    assert lowest_of_one(np.int64(value)) == index
    assert lowest_of_one(value) == index  # a Python int, as numba types it


def test_lowest_set_bit_in_a_compiled_loop():
    values = np.array([v for v, _ in CASES], dtype=np.int64)
    out = np.empty(len(CASES), dtype=np.int64)
    lowest_of(values, out)
    assert out.tolist() == [i for _, i in CASES]


def test_the_colouring_gives_each_contact_the_lowest_colour_free_at_both_bodies():
    from sandbox.records import BODY, CONTACT
    from sandbox.solvers.wide import colour

    bodies = np.zeros(4, dtype=BODY)
    contacts = np.zeros(5, dtype=CONTACT)
    # a chain 0-1-2-3 and a contact 0-2: colours 0, 1, 0, then 2 (0 and 1 are taken at 0 or 2)
    for i, (a, b) in enumerate([(0, 1), (1, 2), (2, 3), (0, 2), (1, 3)]):
        c = contacts[i]
        c["a"], c["b"], c["count"] = a, b, 2
        c["inv_mass_a"] = c["inv_mass_b"] = 1.0
    colours = np.empty(5, dtype=np.int64)
    count = colour(contacts, 5, bodies, colours)
    assert colours.tolist() == [0, 1, 0, 2, 2]
    assert count == 3
