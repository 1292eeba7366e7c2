"""Arrow geometry for the debug-drawing layers, in whole arrays (no per-arrow Python loop).

An arrow is a shaft (a segment from its tail to its tip) and a head (a triangle at the tip).
Lengths are in metres of the scene; head sizes are given in metres too (the caller converts
from pixels), so an arrow looks the same at any zoom. An arrow longer than ``max_length`` is
cut to it and gets a second head behind the first: "longer than shown".

Scales map a quantity to metres of arrow (m per N, m per N s, m per m/s). :func:`auto_scale`
picks one from the values a recording holds, :func:`nice_value` a round reference value for
the key.
"""

from __future__ import annotations

import math

import numpy as np


class ArrowGeometry:
    """Shafts ``(A, 2, 2)`` and heads ``(H, 3, 2)`` of a set of arrows (metres)."""

    __slots__ = ("shafts", "heads")

    def __init__(self, shafts: np.ndarray, heads: np.ndarray) -> None:
        self.shafts, self.heads = shafts, heads


def arrows(
    tails: np.ndarray,
    vectors: np.ndarray,
    head_length: float,
    head_width: float,
    max_length: float = math.inf,
    min_length: float = 0.0,
) -> ArrowGeometry:
    """Arrows from ``tails`` (A, 2) along ``vectors`` (A, 2), both in metres.

    Arrows shorter than ``min_length`` (and zero vectors) are left out; longer than
    ``max_length`` are cut to it and get a second head. A head is ``head_length`` long and
    ``head_width`` wide, shrunk to the arrow for short arrows (the tip stays where it belongs).
    """
    tails = np.asarray(tails, dtype=float).reshape(-1, 2)
    vectors = np.asarray(vectors, dtype=float).reshape(-1, 2)
    length = np.hypot(vectors[:, 0], vectors[:, 1])
    keep = np.isfinite(length) & (length > max(min_length, 1e-300))
    tails, vectors, length = tails[keep], vectors[keep], length[keep]
    unit = vectors / length[:, None]
    clipped = length > max_length
    shown = np.minimum(length, max_length)
    tips = tails + unit * shown[:, None]
    hl = np.minimum(head_length, shown)  # a short arrow is all head
    hw = head_width * hl / head_length if head_length > 0 else np.zeros_like(hl)
    heads = _heads(tips, unit, hl, hw)
    if clipped.any():  # the second head, one head length behind the first
        back = tips[clipped] - unit[clipped] * hl[clipped, None]
        heads = np.concatenate([heads, _heads(back, unit[clipped], hl[clipped], hw[clipped])])
    shafts = np.stack([tails, tips - unit * (0.6 * hl)[:, None]], axis=1)  # under the head
    return ArrowGeometry(shafts, heads)


def _heads(tips: np.ndarray, unit: np.ndarray, length: np.ndarray, width: np.ndarray):
    """Triangles ``(A, 3, 2)``: the tip and two corners ``length`` back, ``width`` apart."""
    normal = np.stack([-unit[:, 1], unit[:, 0]], axis=1)
    base = tips - unit * length[:, None]
    side = normal * (0.5 * width)[:, None]
    return np.stack([tips, base + side, base - side], axis=1)


def arcs(
    centers: np.ndarray,
    sweeps: np.ndarray,
    radius: float,
    head_length: float,
    head_width: float,
    start: float = 0.5 * math.pi,
    points: int = 24,
) -> ArrowGeometry:
    """Curved arrows round ``centers`` (A, 2) of ``radius`` (m), turning ``sweeps`` (A,) rad
    (counter-clockwise positive) from the direction at angle ``start`` (default straight up),
    with a head at the end."""
    centers = np.asarray(centers, dtype=float).reshape(-1, 2)
    sweeps = np.asarray(sweeps, dtype=float).reshape(-1)
    keep = np.isfinite(sweeps) & (sweeps != 0.0)
    centers, sweeps = centers[keep], sweeps[keep]
    t = np.linspace(0.0, 1.0, points)
    angle = start + t[None, :] * sweeps[:, None]
    path = centers[:, None, :] + radius * np.stack([np.cos(angle), np.sin(angle)], axis=2)
    end = angle[:, -1]
    sign = np.sign(sweeps)
    unit = np.stack([-np.sin(end) * sign, np.cos(end) * sign], axis=1)  # tangent, turning way
    hl = np.minimum(head_length, np.abs(sweeps) * radius)
    hw = head_width * hl / head_length if head_length > 0 else np.zeros_like(hl)
    return ArrowGeometry(path, _heads(path[:, -1], unit, hl, hw))


def boxes(lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """Closed rectangles ``(B, 5, 2)`` from corners ``lo`` and ``hi`` (B, 2)."""
    return np.stack(
        [lo, np.stack([hi[:, 0], lo[:, 1]], 1), hi, np.stack([lo[:, 0], hi[:, 1]], 1), lo], axis=1
    )


def nice_value(x: float) -> float:
    """The largest of 1, 2, 5 times a power of ten that is <= ``x`` (x > 0)."""
    if not (math.isfinite(x) and x > 0):
        return 1.0
    power = 10.0 ** math.floor(math.log10(x))
    for step in (5.0, 2.0, 1.0):
        if step * power <= x * (1 + 1e-12):
            return step * power
    return power


def auto_scale(
    magnitudes: np.ndarray, target: float, quantile: float = 0.9, floor: float = 0.0
) -> float:
    """A scale (metres per unit) drawing the ``quantile`` of the nonzero ``magnitudes`` (or
    ``floor``, if larger) as an arrow ``target`` metres long; ``target`` per unit when there is
    nothing to draw."""
    m = np.abs(np.asarray(magnitudes, dtype=float).ravel())
    m = m[np.isfinite(m) & (m > 0)]
    reference = max(float(np.quantile(m, quantile)) if len(m) else 0.0, floor)
    return float(target / reference) if reference > 0 else float(target)


def format_value(value: float, unit: str) -> str:
    """``5 N s``, ``0.2 m/s``, ``2e+03 N``: a reference value and its unit."""
    text = f"{value:.0f}" if value >= 1 else f"{value:.3g}"
    if value >= 1e5 or value < 1e-3:
        text = f"{value:.0e}"
    return f"{text} {unit}"
