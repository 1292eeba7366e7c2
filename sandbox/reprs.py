"""``repr`` for force generators, built from their scene-file form.

:mod:`sandbox.forces` defines no ``__repr__``; this module gives :class:`ForceGenerator` one
without touching that file: ``Drag(linear=0.1, quadratic=0, angular=0, bodies=None)``. (Shapes
have their own in :mod:`sandbox.shapes`; joints in :mod:`sandbox.joints.base`.)
"""

from __future__ import annotations

from sandbox.forces import ForceGenerator

__all__ = ["force_repr"]


def _show(value) -> str:
    if isinstance(value, float):
        return f"{value:g}"
    if isinstance(value, list | tuple):
        return "[" + ", ".join(_show(v) for v in value) + "]"
    return repr(value)


def force_repr(force: ForceGenerator) -> str:
    """``Type(field=value, ...)`` from ``force.to_dict()`` (class name if it has none)."""
    to_dict = getattr(force, "to_dict", None)
    if to_dict is None:
        return f"{type(force).__name__}()"
    fields = {k: v for k, v in to_dict().items() if k != "type"}
    return f"{type(force).__name__}({', '.join(f'{k}={_show(v)}' for k, v in fields.items())})"


if "__repr__" not in vars(ForceGenerator):  # forces.py may define its own one day
    ForceGenerator.__repr__ = force_repr  # type: ignore[method-assign]
