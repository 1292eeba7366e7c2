"""The contacts of sleeping islands, kept for when they wake (as Box2D keeps them).

A sleeping island's pairs are left out of the broadphase, so the step after it wakes would find
its contacts anew, with no impulses to warm start from: a woken pile would begin from zero,
sag and slide for a few steps. So when islands fall asleep their contacts go to the *store*,
the third contact set (``sets[STORE]``, kept in shape-pair order like the others:
:func:`keep_sleeping_contacts`), and the first step after one wakes takes its impulses from
there (:func:`wake_contacts`), as from the last step's set.
"""

from __future__ import annotations

import numpy as np

from sandbox.jit import njit
from sandbox.records import CONTACT, DYNAMIC, SLEEPING
from sandbox.solvers.common import before, first_at_or_after, match_previous


@njit
def sleeping_pair(c, bodies) -> bool:
    """Whether contact ``c`` belongs to a sleeping island: neither body awake and one asleep
    (the other may be static)."""
    ka, kb = bodies[c["a"]]["kind"], bodies[c["b"]]["kind"]
    return ka != DYNAMIC and kb != DYNAMIC and (ka == SLEEPING or kb == SLEEPING)


@njit
def keep_sleeping_contacts(contacts, k: int, bodies, store, kept: int) -> int:
    """After islands fell asleep at the end of a step: the first ``kept`` records of ``store``
    that still belong to sleeping islands, merged in shape-pair order with this step's
    contacts of the islands that just fell asleep (the only ones of this step that can belong
    to a sleeping island). Returns how many records the store now holds (at most its length:
    the rest would only lose their warm start). Nothing is copied when no island fell asleep."""
    fresh = 0
    for i in range(k):
        fresh += sleeping_pair(contacts[i], bodies)
    if fresh == 0:
        return kept
    merged = np.empty(min(fresh + kept, store.shape[0]), dtype=CONTACT)
    n, i, q = 0, 0, 0
    while n < merged.shape[0] and (i < k or q < kept):
        if i < k and not sleeping_pair(contacts[i], bodies):
            i += 1
            continue
        if q < kept and not sleeping_pair(store[q], bodies):
            q += 1
            continue
        take_old = i == k or (
            q < kept
            and before(
                store[q]["shape_a"],
                store[q]["shape_b"],
                contacts[i]["shape_a"],
                contacts[i]["shape_b"],
            )
        )
        if take_old:
            merged[n] = store[q]
            q += 1
        else:
            merged[n] = contacts[i]
            i += 1
        n += 1
    store[:n] = merged[:n]
    return n


@njit
def wake_contacts(contacts, k: int, bodies, store, kept: int, last) -> tuple[int, int]:
    """Before the warm start of a step: if a body of the store's first ``kept`` records is
    awake again, give this step's contacts the impulses the store kept for them (the woken
    islands' contacts, as :func:`sandbox.solvers.common.match_previous` does from the last
    step's) and drop the records of woken islands. ``last`` = (the last step's contacts, how
    many): a record whose shape pair is there too is left to that set (a world that skipped
    its steps while everything slept still holds the contacts its islands fell asleep with),
    so no point is warm started twice. Returns (points matched, records the store keeps)."""
    woke = False
    for q in range(kept):
        if not sleeping_pair(store[q], bodies):
            woke = True
            break
    if not woke:
        return 0, kept
    previous, k_old = last
    woken = np.empty(kept, dtype=CONTACT)
    n = 0
    for q in range(kept):
        c = store[q]
        if sleeping_pair(c, bodies):
            continue
        sa, sb = c["shape_a"], c["shape_b"]
        at = first_at_or_after(previous, k_old, sa, sb)
        if at < k_old and previous[at]["shape_a"] == sa and previous[at]["shape_b"] == sb:
            continue
        woken[n] = c
        n += 1
    found = match_previous(contacts, k, woken, n)
    n = 0
    for q in range(kept):
        if sleeping_pair(store[q], bodies):
            if n < q:
                store[n] = store[q]
            n += 1
    return found, n
