"""Record arrays for the uncompiled engine (``SANDBOX_JIT=0``): the same records, read faster.

Compiled, ``contacts[i]["normal"]`` is a load from memory. In plain Python, numpy answers it
with a *void scalar*, and every field read or write on one builds a temporary array: about
0.8 us, where indexing an array of one field takes 0.06 us. The solvers read a record field
tens of times per contact and sweep, so an uncompiled step spends most of its time there.

:func:`fast_records` gives the same memory a view whose elements are :class:`Record`: ``r[name]``
indexes the container of that field, one per field, made once per array. A number reads as a
Python ``float`` (or ``int``, ``bool``) of exactly numpy's value, and Python's arithmetic on it
is the same IEEE double arithmetic as numpy's, so an uncompiled step gives bit for bit the same
numbers (``tests/test_plain_records.py``), only sooner; a vector field (a point, a velocity)
reads as a writable view of its numbers. Slices, field names and numpy functions work on the
array as on any other. Two things behave as in compiled code rather than as numpy's scalars
would: a division by zero raises ``ZeroDivisionError`` (numba's default), and a float written
to an integer field is refused (``TypeError``) instead of being cut to an integer.
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np


class Records(np.ndarray):
    """A structured array whose elements are :class:`Record` (see the module)."""

    def __getitem__(self, index):
        if index.__class__ is int or isinstance(index, np.integer):
            try:
                return self._items[index]
            except AttributeError:  # the first element read: make them all
                self._items = elements(self)
                return self._items[index]
        return super().__getitem__(index)


def elements(records: Records) -> list:
    """What ``records[i]`` gives for every i, made once: a :class:`Record` (one dimension) or a
    row of ``records`` (more: a contact's points, one of the contact sets)."""
    if records.ndim > 1:
        return [np.ndarray.__getitem__(records, i) for i in range(records.shape[0])]
    views = field_views(records)
    return [Record(views, i) for i in range(records.shape[0])]


def field_views(records: np.ndarray) -> dict:
    """Each field of ``records`` as a container of its own over the same memory, indexed as
    the records are: records as :class:`Records`, and records within each record (a contact's
    points) as a list of :class:`Record` per record, since a list is indexed sooner; numbers
    as a ``memoryview`` (it reads and writes Python numbers, several times faster than numpy's
    scalars, and with the same values); a vector per record (a point, a velocity) as a list of
    ``memoryview``, one per record."""
    views = {}
    for name in records.dtype.names:
        view = np.ndarray.__getitem__(records, name)
        if view.dtype.names and view.ndim == 2:  # records in each record (a contact's points)
            columns = [field_views(view[:, j]) for j in range(view.shape[1])]
            views[name] = [[Record(column, i) for column in columns] for i in range(len(view))]
        elif view.dtype.names:
            views[name] = view.view(Records)
        elif view.ndim == 1:
            views[name] = memoryview(view.view(np.ndarray))
        elif view.ndim == 2:
            views[name] = [memoryview(row) for row in view.view(np.ndarray)]
        else:
            views[name] = view.view(np.ndarray)
    return views


class Record:
    """One element of a :class:`Records` array: ``r[name]`` and ``r[name] = value`` go to the
    field's own array (see the module)."""

    __slots__ = ("_index", "_views")

    def __init__(self, views: dict, index) -> None:
        self._views, self._index = views, index

    def __getitem__(self, name: str):
        return self._views[name][self._index]

    def __setitem__(self, name: str, value) -> None:
        self._views[name][self._index] = value

    def __repr__(self) -> str:
        fields = ", ".join(f"{name}={shown(self[name])}" for name in self._views)
        return f"Record({fields})"


def shown(value) -> str:
    """A field's value as a debugger shows it: numbers and vectors as numbers, records by count."""
    if isinstance(value, memoryview):
        return repr(value.tolist())
    if isinstance(value, Records | list):
        return f"<{len(value)} records>"
    return repr(value)


def fast_records(value):
    """``value`` with every structured array in it (also inside tuples and lists) viewed as
    :class:`Records`; anything else as it is."""
    if isinstance(value, np.ndarray) and value.dtype.names and not isinstance(value, Records):
        return value.view(Records)
    if isinstance(value, tuple | list):
        return type(value)(fast_records(v) for v in value)
    return value


def staged_view(world, arrays):
    """The staged step's ``arrays`` (a ``WorldArrays``) with the record arrays in them, and in
    its contact buffers, viewed as :class:`Records`; made once and kept on ``world`` while the
    arrays stay the same objects (a world makes new ones when bodies, shapes or the buffers'
    size change)."""
    buffers = arrays.buffers
    originals = (*arrays[:6], arrays.context, arrays.work, buffers.sets, buffers.proxies)
    kept = getattr(world, "_staged_view", None)
    if kept is None or any(a is not b for a, b in zip(kept[0], originals, strict=True)):
        view = SimpleNamespace(
            sets=fast_records(buffers.sets), proxies=fast_records(buffers.proxies), pairs=None
        )
        fields = ("bodies", "rot", "shapes", "vertices", "joints", "generators", "context", "work")
        viewed = arrays._replace(**{f: fast_records(getattr(arrays, f)) for f in fields})
        kept = world._staged_view = (originals, viewed._replace(buffers=view))
    view = kept[1]
    view.buffers.pairs = buffers.pairs  # an int array: as it is (replaced when it grows)
    return view
