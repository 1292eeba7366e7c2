"""Warm starting: last step's contact impulses, found again for this step's contacts.

A resting stack needs nearly the same impulses every step. Starting the iterations from last
step's answer instead of zero (box2d-lite's ``Arbiter::Update``) lets a few iterations reach
it. A point of this step matches a point of the last step when the shapes (a, b) and the
narrowphase's feature id are the same; unmatched points start from zero.

The cache lives in ``world._solver_cache["contacts"]`` and is dropped when the world's shapes
change (shape indices would mean something else).
"""

from __future__ import annotations

import numpy as np

from sandbox.jit import njit


def pair_keys(sa: np.ndarray, sb: np.ndarray, m: int) -> np.ndarray:
    """One int64 per shape pair: sa * m + sb (m shapes)."""
    return sa.astype(np.int64) * np.int64(max(m, 1)) + sb.astype(np.int64)


@njit
def copy_matched(match, count, feature, old_count, old_feature, old, new) -> int:
    """For manifold i matched to old manifold match[i] (-1: none), copy the per-point values
    ``old[:, q, jj]`` of the points with equal feature ids into ``new[:, i, j]`` (zero
    elsewhere). Returns the number of points matched."""
    found = 0
    for i in range(len(match)):
        for f in range(new.shape[0]):
            new[f, i, 0] = new[f, i, 1] = 0.0
        q = match[i]
        if q < 0:
            continue
        for j in range(count[i]):
            for jj in range(old_count[q]):
                if old_feature[q, jj] == feature[i, j]:
                    for f in range(new.shape[0]):
                        new[f, i, j] = old[f, q, jj]
                    found += 1
                    break
    return found


def load(world, manifolds) -> int:
    """Fill ``manifolds.normal_impulse`` / ``tangent_impulse`` with last step's impulses of the
    matching points (zero elsewhere). Returns the number of points matched."""
    m = manifolds
    out = np.zeros((2, len(m), 2))
    old = world._solver_cache.get("contacts")
    geometry = world.geometry()
    found = 0
    if old is not None and old["geometry"] is geometry and len(m) and len(old["keys"]):
        keys = pair_keys(m.sa, m.sb, len(geometry))
        order = old["order"]
        sorted_keys = old["keys"][order]
        pos = np.minimum(np.searchsorted(sorted_keys, keys), len(sorted_keys) - 1)
        match = np.where(sorted_keys[pos] == keys, order[pos], -1).astype(np.int64)
        found = copy_matched(
            match, m.count, m.feature, old["count"], old["feature"], old["values"], out
        )
    m.normal_impulse[:] = out[0]
    m.tangent_impulse[:] = out[1]
    return int(found)


def save(world, manifolds) -> None:
    """Remember this step's impulses for the next step's warm start."""
    if manifolds is None or len(manifolds) == 0:
        world._solver_cache.pop("contacts", None)
        return
    m = manifolds
    keys = pair_keys(m.sa, m.sb, len(world.geometry()))
    world._solver_cache["contacts"] = {
        "geometry": world.geometry(),
        "keys": keys,
        "order": np.argsort(keys, kind="stable"),
        "count": m.count.copy(),
        "feature": m.feature.copy(),
        "values": np.stack([m.normal_impulse, m.tangent_impulse]),
    }
