"""Deep copies of a world's Python parts (``copy.deepcopy(world)``), faster.

A world holds a :class:`~sandbox.body.Body` per body and a :class:`~sandbox.shapes.Shape` per
shape, each a handful of numbers, names and arrays. ``copy.deepcopy`` visits every one of those
fields through its general machinery, a few microseconds each, though a number or a string
never needs copying: a world of 820 boxes took about 30 ms to copy. :func:`copy_fields` shares
what cannot change and deep-copies the rest with the same ``memo``, so the copy is the same
graph (a copied body's ``world`` is the copied world, its shapes point back to it).
"""

from __future__ import annotations

import copy
from typing import Any

IMMUTABLE = frozenset({type(None), bool, int, float, str})  # shared, never copied


def copy_fields(obj: Any, memo: dict) -> Any:
    """A deep copy of ``obj`` (an object with a ``__dict__``) for ``copy.deepcopy``: its
    immutable fields shared, the others deep-copied with ``memo``."""
    new = object.__new__(type(obj))
    memo[id(obj)] = new
    new.__dict__.update(
        (name, value if type(value) in IMMUTABLE else copy.deepcopy(value, memo))
        for name, value in obj.__dict__.items()
    )
    return new
