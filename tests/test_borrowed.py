"""``sandbox.borrowed.borrowed``: the same memory, shape and strides as the array, for a loop
that hands it to an inlined function at every turn without numba counting references."""

import numpy as np

from sandbox.borrowed import borrowed
from sandbox.jit import njit


@njit
def write_through(array, value: float) -> tuple:
    """Write ``value`` into the last element of a borrowed view, read it back from the array."""
    view = borrowed(array)
    rows, columns = view.shape
    view[rows - 1, columns - 1] = value
    return array[rows - 1, columns - 1], view.shape[0], view.shape[1], view.strides[0]


def test_a_borrowed_view_is_the_array_itself():
    array = np.zeros((5, 4))
    got, rows, columns, stride = write_through(array, 2.5)
    assert (got, rows, columns, stride) == (2.5, 5, 4, 32)
    assert array[4, 3] == 2.5 and np.count_nonzero(array) == 1


def test_a_borrowed_view_of_a_column_keeps_its_strides():
    array = np.arange(12.0).reshape(4, 3)
    column = array[:, 1:2]  # not contiguous: the strides come from the array, not the shape
    got, rows, columns, stride = write_through(column, -1.0)
    assert (got, rows, columns, stride) == (-1.0, 4, 1, 24)
    assert array[3, 1] == -1.0 and array[3, 2] == 11.0
