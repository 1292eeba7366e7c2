"""The contacts of sleeping islands, kept for when they wake (as Box2D keeps them).

A sleeping island's pairs are left out of the broadphase, so the step after it wakes would find
its contacts anew, with no impulses to warm start from: a woken pile would begin from zero,
sag and slide for a few steps. So when islands fall asleep their contacts go to the *store*,
the third contact set (``sets[STORE]``, in shape-pair order like the others), and the first
step after one wakes takes its impulses from there (:func:`wake_contacts`), as from the last
step's set.

Filling the store is plain numpy, run by the world after a step in which bodies fell asleep
(:func:`keep_sleeping_contacts`): it happens once per island that falls asleep, and compiled,
its record copies made every step kernel a fifth longer to compile (the iterative step: 57 s
from an empty cache against 44 s). Waking is compiled, inside the step, because an island
woken by a body that touches it wakes in the step's own narrowphase, before its warm start.
"""

from __future__ import annotations

import numpy as np

from sandbox.jit import njit
from sandbox.records import DYNAMIC, SLEEPING, STORE
from sandbox.solvers.common import first_at_or_after, match_previous


@njit
def sleeping_pair(c, bodies) -> bool:
    """Whether contact ``c`` belongs to a sleeping island: neither body awake and one asleep
    (the other may be static)."""
    ka, kb = bodies[c["a"]]["kind"], bodies[c["b"]]["kind"]
    return ka != DYNAMIC and kb != DYNAMIC and (ka == SLEEPING or kb == SLEEPING)


@njit
def wake_contacts(contacts, k: int, bodies, store, context, last) -> int:
    """Before the warm start of a step: if a body of a record in the store is awake again,
    give this step's contacts the impulses the store kept for them (the woken islands'
    contacts: the store's sleeping ones cannot match, their pairs are not found while they
    sleep; :func:`sandbox.solvers.common.match_previous`), and empty the records of woken
    islands (``count`` 0; the store is emptied when none is left). ``last`` = (the last
    step's contacts, how many): a record whose shape pair is there too is left to that set (a
    world that skipped its steps while everything slept still holds the contacts its islands
    fell asleep with), so no point is warm started twice. Returns the points matched."""
    ctx = context[0]
    kept = ctx["contact_count"][STORE]
    woke = False
    for q in range(kept):
        if store[q]["count"] > 0 and not sleeping_pair(store[q], bodies):
            woke = True
            break
    if not woke:
        return 0
    previous, k_old = last
    for q in range(kept):
        c = store[q]
        if c["count"] == 0 or sleeping_pair(c, bodies):
            continue
        at = first_at_or_after(previous, k_old, c["shape_a"], c["shape_b"])
        if at < k_old and previous[at]["shape_a"] == c["shape_a"]:
            if previous[at]["shape_b"] == c["shape_b"]:
                c["count"] = 0  # the last step's set has it
    found = match_previous(contacts, k, store, kept)
    left = 0
    for q in range(kept):
        if sleeping_pair(store[q], bodies):
            left += store[q]["count"] > 0
        else:
            store[q]["count"] = 0  # awake: its contacts are this step's now
    if left == 0:
        ctx["contact_count"][STORE] = 0
    return found


def keep_sleeping_contacts(ctx, sets: np.ndarray, kind: np.ndarray) -> None:
    """After a step in which bodies fell asleep: the store keeps its records of islands still
    asleep and takes this step's contacts of the islands that fell asleep now (with ``kind``
    each body's kind after the step), in shape-pair order; at most as many as a set holds (the
    rest would only lose their warm start). ``ctx``: the world's step context."""
    cur, kept = int(ctx["contact_set"]), int(ctx["contact_count"][STORE])
    fresh = sets[cur][: int(ctx["contact_count"][cur])]
    old = sets[STORE][:kept]

    def asleep(c: np.ndarray) -> np.ndarray:
        ka, kb = kind[c["a"]], kind[c["b"]]
        return (ka != DYNAMIC) & (kb != DYNAMIC) & ((ka == SLEEPING) | (kb == SLEEPING))

    both = np.concatenate([old[asleep(old) & (old["count"] > 0)], fresh[asleep(fresh)]])
    both = both[np.lexsort((both["shape_b"], both["shape_a"]))][: sets.shape[1]]
    sets[STORE][: len(both)] = both
    ctx["contact_count"][STORE] = len(both)
