"""Shock propagation (slides, "Simultaneous Collision Resolution"; Guendelman, Bridson and
Fedkiw 2003, "Nonconvex rigid bodies with stacking").

The contact graph is sorted into layers from the ground up: static and kinematic bodies are
layer 0, bodies touching them layer 1, bodies touching those layer 2, and so on (breadth-first
search over the contacts). Then:

1. relaxation: ``settings.iterations`` sweeps of sequential impulses over all contacts and
   joints, as the iterative solver does (accumulated, warm started, with its switches);
2. the shock pass: layer by layer from the bottom, each layer's contacts are resolved with the
   bodies of the layer below treated as immovable (infinite mass). Whatever the relaxation left
   of a box sinking into the one below is removed from the upper box alone, so the error cannot
   travel back down: the stack's weight no longer has to be carried by converged impulses.

Within the shock pass each increment only pushes (>= 0, friction within mu times it). Its
normal pushes and their friction are reported with the contact (``bounce_impulse`` and
``bounce_tangent``, which hold what the passes after the relaxation added) but not
warm-started: one-sided pushes would not balance in the next step. Bodies not connected to
the ground (a separate layer "infinity") are resolved with their normal masses.
"""

from __future__ import annotations

import numpy as np

from sandbox.jit import JIT_ENABLED, njit
from sandbox.math2d import effective_mass, set_velocity, velocity_of
from sandbox.prefetch import AHEAD, prefetch_record, span, where
from sandbox.records import CONTACT, CONTACT_POINT, DYNAMIC
from sandbox.solvers.common import (
    apply_normal,
    apply_tangent,
    masses,
    normal_speed,
    tangent_speed,
)
from sandbox.solvers.iterative import solve as relax
from sandbox.sorting import argsort

UNREACHED = 1 << 40  # layer of bodies with no path of contacts to a fixed body
LAYER_SWEEPS = 3  # sweeps over each layer's contacts in the shock pass


@njit
def touching(c, gap: float) -> bool:
    """Whether a contact's points came closer than ``gap`` (m) at detection."""
    deepest = c["points"][0]["depth"]
    if c["count"] == 2:
        deepest = max(deepest, c["points"][1]["depth"])
    return deepest >= -gap


# what the layering reads of a contact: its bodies and count, and point 0's depth (point 1's
# is on the line after it, read only for two points); asked for ahead, as its passes read two
# of the record's ten lines (sandbox.prefetch)
LAYER_READ = span(CONTACT, "a", "count")
DEPTH_READ = tuple(CONTACT.fields["points"][1] + at for at in span(CONTACT_POINT, "depth", "depth"))


@njit(inline="always")
def fetch_layer_fields(contacts_at, i: int, k: int) -> None:
    """Prefetch what :func:`contact_layers` reads of contact ``i + 2 AHEAD``."""
    if JIT_ENABLED and i + 2 * AHEAD < k:
        prefetch_record(contacts_at, i + 2 * AHEAD, LAYER_READ)
        prefetch_record(contacts_at, i + 2 * AHEAD, DEPTH_READ)


@njit
def contact_layers(contacts, k: int, bodies, gap: float = np.inf):
    """Breadth-first depth of every body from the fixed ones over the contact graph (over the
    contacts whose shapes came closer than ``gap`` (m): a speculative contact across a wide
    gap does not hold anything up)."""
    n = bodies.shape[0]
    contacts_at = where(contacts) if JIT_ENABLED else (0, 0)
    # the touching contacts' two bodies, read from the records once: a second pass over the
    # records (two of their ten lines each) took 70 of 300 us on the rain of 5,000
    ends = np.empty((k, 2), dtype=np.int64)
    m = 0
    degree = np.zeros(n + 1, dtype=np.int64)
    for i in range(k):
        fetch_layer_fields(contacts_at, i, k)
        if touching(contacts[i], gap):
            a, b = contacts[i]["a"], contacts[i]["b"]
            ends[m, 0], ends[m, 1] = a, b
            m += 1
            degree[a + 1] += 1
            degree[b + 1] += 1
    start = degree  # summed in place (np.cumsum compiled 0.3 s more from an empty cache):
    for u in range(n):  # the neighbours of body u are neighbour[start[u]:start[u + 1]]
        start[u + 1] += start[u]
    fill = start[:-1].copy()
    neighbour = np.empty(start[n], dtype=np.int64)
    for i in range(m):
        a, b = ends[i, 0], ends[i, 1]
        neighbour[fill[a]] = b
        fill[a] += 1
        neighbour[fill[b]] = a
        fill[b] += 1
    layer = np.full(n, UNREACHED, dtype=np.int64)
    queue = np.empty(n, dtype=np.int64)
    head = tail = 0
    for u in range(n):
        if bodies[u]["kind"] != DYNAMIC:
            layer[u] = 0
            queue[tail] = u
            tail += 1
    while head < tail:
        u = queue[head]
        head += 1
        for q in range(start[u], start[u + 1]):
            w = neighbour[q]
            if layer[w] == UNREACHED:
                layer[w] = layer[u] + 1
                queue[tail] = w
                tail += 1
    return layer


@njit
def hold_lower(mass, layer_a: int, layer_b: int) -> tuple[float, float, float, float]:
    """``mass`` = (1/m_a, 1/I_a, 1/m_b, 1/I_b) with the lower body of two layers frozen
    (1/m = 1/I = 0): immovable for this contact. Bodies of one layer keep their masses."""
    im_a, ii_a, im_b, ii_b = mass
    if layer_a < layer_b:
        im_a = ii_a = 0.0  # body a is below
    elif layer_b < layer_a:
        im_b = ii_b = 0.0
    return im_a, ii_a, im_b, ii_b


@njit
def push_layer(c, layer, bodies) -> None:
    """One contact of the shock pass: the lower body frozen (:func:`hold_lower`), pushes only."""
    a, b = c["a"], c["b"]
    nx, ny = c["normal"][0], c["normal"][1]
    mass = hold_lower(masses(c), layer[a], layer[b])
    im_a, ii_a, im_b, ii_b = mass
    va, vb = velocity_of(bodies, a), velocity_of(bodies, b)
    for j in range(c["count"]):
        p = c["points"][j]
        kn = effective_mass(im_a, ii_a, im_b, ii_b, p["rn_a"], p["rn_b"])
        if kn <= 0.0:
            continue
        dp = max((p["bias"] - normal_speed(va, vb, p, nx, ny)) / kn, 0.0)
        if dp == 0.0:
            continue
        p["bounce_impulse"] += dp
        va, vb = apply_normal(va, vb, mass, p, nx, ny, dp)
        # friction against the same frozen body, at most mu dp
        kt = effective_mass(im_a, ii_a, im_b, ii_b, p["rt_a"], p["rt_b"])
        limit = c["friction"] * dp
        dt = min(max(-tangent_speed(va, vb, p, nx, ny) / kt, -limit), limit)
        p["bounce_tangent"] += dt  # not warm-started either (a light body took it once as
        # the next step's warm start: 20 N s on 0.09 kg, and the pile's energy grew 45,000 times)
        va, vb = apply_tangent(va, vb, mass, p, nx, ny, dt)
    set_velocity(bodies, a, va)
    set_velocity(bodies, b, vb)


@njit
def shock_pass(contacts, k: int, bodies, gap: float = np.inf) -> int:
    """Resolve the contacts layer by layer from the ground up (:func:`push_layer`,
    ``LAYER_SWEEPS`` sweeps per layer). Layers are made over the contacts closer than ``gap``
    (m): at a large dt the contact margin (|g| dt^2) reaches past the next box, and counting
    those speculative contacts would put a whole stack in layer 1, next to the ground, where
    the pass holds nothing up. Returns the number of layers reached."""
    layer = contact_layers(contacts, k, bodies, gap)
    level = np.empty(k, dtype=np.int64)
    for i in range(k):
        level[i] = max(layer[contacts[i]["a"]], layer[contacts[i]["b"]])
    order = argsort(level)  # stable: contacts of a layer in pair order
    s = 0
    while s < k:
        e = s
        while e < k and level[order[e]] == level[order[s]]:
            e += 1
        for _ in range(LAYER_SWEEPS):
            for q in range(s, e):
                push_layer(contacts[order[q]], layer, bodies)
        s = e
    top = 0
    for i in range(k):
        if level[i] < UNREACHED:
            top = max(top, level[i])
    return top


@njit
def solve(contacts, k: int, joints, bodies, context) -> None:
    """Relaxation sweeps (contacts and joints), then the shock pass."""
    ctx = context[0]
    relax(contacts, k, joints, bodies, context)
    if k > 0:
        ctx["shock_layers"] = shock_pass(contacts, k, bodies, ctx["touch_margin"])
