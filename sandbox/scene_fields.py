"""Checking one field of a scene file: numbers, vectors, names, choices, objects.

Every checker takes the value and its field path (e.g. ``bodies[1].shapes[0].radius``) and either
returns the value in normalized form or raises :class:`SceneError` naming that path.
"""

from __future__ import annotations

import difflib
import math
import numbers
from typing import Any

IGNORED_KEYS = ("description", "comment")  # and every key starting with "_"


class _Required:
    def __repr__(self) -> str:
        return "REQUIRED"


_REQUIRED: Any = _Required()  # the default of a field that must be given


class SceneError(ValueError):
    """A scene that breaks the contract. ``path`` names the field (``""``: the whole document,
    ``"file"``: the file itself); ``message`` says what was expected and what was found."""

    def __init__(self, path: str, message: str):
        super().__init__(f"{path}: {message}")
        self.path = path
        self.message = message

    def __str__(self) -> str:
        return f"{self.path}: {self.message}"

    def __reduce__(self):
        return (type(self), (self.path, self.message))


# --- checking one value --------------------------------------------------------------------------
def _key(path: str, key: object) -> str:
    return f"{path}.{key}" if path else str(key)


def _show(value: Any) -> str:
    """A short, one-line description of a found value."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if value is None:
        return "null"
    if isinstance(value, str):
        text = value if len(value) <= 40 else value[:37] + "..."
        return repr(text)
    if isinstance(value, float):
        if math.isnan(value):
            return "NaN"
        if math.isinf(value):
            return "Infinity" if value > 0 else "-Infinity"
        return repr(value)
    if isinstance(value, int):
        if value.bit_length() > 64:  # str() of a 5000-digit integer raises ValueError
            return "an integer too large"
        return str(value)
    if isinstance(value, list | tuple):
        return f"a list of {len(value)} item{'s' if len(value) != 1 else ''}" if value else "[]"
    if isinstance(value, dict):
        return "an object"
    return f"a {type(value).__name__}"


def _is_number(value: Any) -> bool:
    kind = type(value)
    if kind is float or kind is int:  # the usual case, without the slower check against the ABC
        return True
    return isinstance(value, numbers.Real) and not isinstance(value, bool)


def _bound(x: float) -> str:
    """A bound as people write it: ``1``, ``0.005``, ``1e+09``, ``1e-06``."""
    x = float(x)
    if x.is_integer() and abs(x) < 1e5:
        return str(int(x))
    if x != 0.0 and (abs(x) >= 1e5 or abs(x) < 1e-3):
        return f"{x:g}"
    return repr(x)


def _number(
    value: Any,
    path: str,
    *,
    gt: float | None = None,
    ge: float | None = None,
    le: float | None = None,
    lo: float | None = None,
    hi: float | None = None,
    unit: str = "",
) -> float:
    """A finite int or float (never a bool) within the given bounds, as a float.

    ``gt`` / ``ge`` / ``le`` are the sign rule (a length is > 0); ``[lo, hi]`` (in ``unit``) the
    physical range, checked after it with its own message.
    """
    if not _is_number(value):
        raise SceneError(path, f"expected {_expected(gt, ge, le)}, got {_show(value)}")
    try:
        x = float(value)
    except OverflowError:
        raise SceneError(path, f"expected a finite number, got {_show(value)}") from None
    if not math.isfinite(x):
        raise SceneError(path, f"expected a finite number, got {_show(value)}")
    if (
        (gt is not None and not x > gt)
        or (ge is not None and not x >= ge)
        or (le is not None and not x <= le)
    ):
        raise SceneError(path, f"expected {_expected(gt, ge, le)}, got {_show(value)}")
    if (lo is not None and x < lo) or (hi is not None and x > hi):
        where = f"[{_bound(lo)}, {_bound(hi)}]" if lo is not None and hi is not None else ""
        if not where:
            where = f">= {_bound(lo)}" if lo is not None else f"<= {_bound(hi)}"
        shown = f" {unit}" if unit else ""
        raise SceneError(path, f"expected a number in {where}{shown}, got {_show(value)}")
    return x


def _expected(gt: float | None, ge: float | None, le: float | None) -> str:
    """What :func:`_number` expected, for its message (made only when a value is wrong)."""
    if gt is not None:
        return f"a number > {_bound(gt)}"
    if ge is not None and le is not None:
        return f"a number in [{_bound(ge)}, {_bound(le)}]"
    if ge is not None:
        return f"a number >= {_bound(ge)}"
    return "a number"


def _integer(value: Any, path: str, lo: int, hi: int) -> int:
    if not (isinstance(value, numbers.Integral) and _is_number(value)) or not lo <= value <= hi:
        raise SceneError(path, f"expected an integer in [{lo}, {hi}], got {_show(value)}")
    return int(value)


def _vector(value: Any, path: str, **bounds) -> list[float]:
    """``[x, y]``: a list of exactly two finite numbers (``bounds`` as for :func:`_number`)."""
    if getattr(value, "ndim", None) == 1:  # a numpy array from the Python API
        value = value.tolist()
    if not isinstance(value, list | tuple) or len(value) != 2:
        raise SceneError(path, f"expected [x, y] (a list of 2 numbers), got {_show(value)}")
    return [_number(value[0], f"{path}[0]", **bounds), _number(value[1], f"{path}[1]", **bounds)]


def _boolean(value: Any, path: str) -> bool:
    if not isinstance(value, bool):
        raise SceneError(path, f"expected true or false, got {_show(value)}")
    return value


def _name(value: Any, path: str) -> str:
    if not isinstance(value, str) or not value.strip():
        raise SceneError(path, f"expected a non-empty string, got {_show(value)}")
    if not value.isascii():
        try:
            value.encode("utf-8")  # a lone surrogate ("\ud800" in JSON) cannot be written out
        except UnicodeEncodeError as e:
            raise SceneError(path, f"not valid Unicode text (character {e.start})") from None
    return value


def _choice(value: Any, path: str, options: tuple[str, ...]) -> str:
    if not isinstance(value, str) or value not in options:
        hint = ""
        if isinstance(value, str):
            close = difflib.get_close_matches(value, options, n=1)
            hint = f" (did you mean {close[0]!r}?)" if close else ""
        raise SceneError(path, f"expected one of {', '.join(options)}, got {_show(value)}{hint}")
    return value


def _object(value: Any, path: str, what: str, keys: tuple[str, ...]) -> dict:
    """A JSON object whose keys are all known (or ignored: ``_...``, description, comment)."""
    if not isinstance(value, dict):
        raise SceneError(path, f"expected {what} (a JSON object), got {_show(value)}")
    for key in value:
        if isinstance(key, str) and (key.startswith("_") or key in IGNORED_KEYS):
            continue
        if key not in keys:
            close = difflib.get_close_matches(str(key), keys, n=1)
            hint = f" (did you mean {close[0]!r}?)" if close else ""
            shown = key if isinstance(key, str) and key.isprintable() else repr(key)
            raise SceneError(_key(path, shown), f"unknown field{hint}")
    return value


def _list(value: Any, path: str, what: str) -> list:
    if not isinstance(value, list | tuple):
        raise SceneError(path, f"expected a list of {what}, got {_show(value)}")
    return list(value)


def _get(obj: dict, path: str, key: str, check, default: Any = _REQUIRED, *, nullable=False, **kw):
    """Check ``obj[key]`` with ``check``; a missing key takes ``default`` (or is an error)."""
    where = _key(path, key)
    if key not in obj:
        if default is _REQUIRED:
            raise SceneError(where, "required field is missing")
        return list(default) if isinstance(default, tuple) else default
    value = obj[key]
    if value is None and nullable:
        return None
    return check(value, where, **kw)


def _kind(obj: dict, path: str, options: tuple[str, ...]) -> str:
    return _get(obj, path, "type", _choice, options=options)
