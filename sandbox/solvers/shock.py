"""Shock propagation (slides, "Simultaneous Collision Resolution"; Guendelman, Bridson and
Fedkiw 2003, "Nonconvex rigid bodies with stacking").

The contact graph is sorted into layers from the ground up: static and kinematic bodies are
layer 0, bodies touching them layer 1, bodies touching those layer 2, and so on (breadth-first
search over the contacts). Then:

1. relaxation: ``settings.iterations`` sweeps of sequential impulses over all contacts and
   joints, as the iterative solver does (accumulated, warm started, with its switches), and
   its restitution pass;
2. the shock pass: layer by layer from the bottom, each layer's contacts are resolved with the
   bodies of the layer below treated as immovable (infinite mass). Whatever the relaxation left
   of a box sinking into the one below is removed from the upper box alone, so the error cannot
   travel back down: the stack's weight no longer has to be carried by converged impulses.

Within the shock pass each increment only pushes (>= 0, friction within mu times it), so
bounces from the restitution pass survive. Bodies not connected to the ground (a separate
layer "infinity") are resolved with their normal masses.
"""

from __future__ import annotations

import numpy as np

from sandbox.jit import njit
from sandbox.solvers import impulse, iterative
from sandbox.solvers.impulse import along, apply, effective_mass, load, store

UNREACHED = 1 << 40  # layer of bodies with no path of contacts to a fixed body
LAYER_SWEEPS = 3  # sweeps over each layer's contacts in the shock pass


@njit
def contact_layers(a, b, fixed):
    """Breadth-first depth of every body from the fixed ones over the contact graph."""
    n, k = len(fixed), len(a)
    degree = np.zeros(n + 1, dtype=np.int64)
    for i in range(k):
        degree[a[i] + 1] += 1
        degree[b[i] + 1] += 1
    start = np.cumsum(degree)  # neighbours of body u: nbr[start[u]:start[u + 1]]
    fill = start[:-1].copy()
    nbr = np.empty(2 * k, dtype=np.int64)
    for i in range(k):
        nbr[fill[a[i]]] = b[i]
        fill[a[i]] += 1
        nbr[fill[b[i]]] = a[i]
        fill[b[i]] += 1
    layer = np.full(n, UNREACHED, dtype=np.int64)
    queue = np.empty(n, dtype=np.int64)
    head = tail = 0
    for u in range(n):
        if fixed[u]:
            layer[u] = 0
            queue[tail] = u
            tail += 1
    while head < tail:
        u = queue[head]
        head += 1
        for q in range(start[u], start[u + 1]):
            w = nbr[q]
            if layer[w] == UNREACHED:
                layer[w] = layer[u] + 1
                queue[tail] = w
                tail += 1
    return layer


@njit
def shock_pass(
    order, level, a, b, normal, count, friction, r1, r2, bias, pn, pt, layer,
    vel, omega, inv_mass, inv_moment, sweeps,
) -> None:  # fmt: skip
    """Resolve the manifolds layer by layer (``order`` sorted by ``level``), the lower body of
    a contact between two layers frozen (1/m = 1/I = 0)."""
    v = np.empty(6)
    s = 0
    while s < len(order):
        e = s
        while e < len(order) and level[order[e]] == level[order[s]]:
            e += 1
        for _ in range(sweeps):
            for q in range(s, e):
                i = order[q]
                ia, ib = a[i], b[i]
                nx, ny = normal[i, 0], normal[i, 1]
                im1, ii1, im2, ii2 = inv_mass[ia], inv_moment[ia], inv_mass[ib], inv_moment[ib]
                if layer[ia] < layer[ib]:
                    im1 = ii1 = 0.0  # body 1 is below: immovable for this contact
                elif layer[ib] < layer[ia]:
                    im2 = ii2 = 0.0
                mass = (im1, ii1, im2, ii2)
                load(v, vel, omega, ia, ib)
                for j in range(count[i]):
                    r1x, r1y, r2x, r2y = r1[i, j, 0], r1[i, j, 1], r2[i, j, 0], r2[i, j, 1]
                    k = effective_mass(im1, ii1, im2, ii2, r1x, r1y, r2x, r2y, nx, ny)
                    if k <= 0.0:
                        continue
                    dp = max((bias[i, j] - along(i, j, nx, ny, r1, r2, v)) / k, 0.0)
                    if dp == 0.0:
                        continue
                    pn[i, j] += dp
                    apply(i, j, dp * nx, dp * ny, r1, r2, mass, v)
                    # friction against the same frozen body, at most mu dp
                    k = effective_mass(im1, ii1, im2, ii2, r1x, r1y, r2x, r2y, ny, -nx)
                    limit = friction[i] * dp
                    dt = min(max(-along(i, j, ny, -nx, r1, r2, v) / k, -limit), limit)
                    pt[i, j] += dt
                    apply(i, j, dt * ny, -dt * nx, r1, r2, mass, v)
                store(v, vel, omega, ia, ib)
        s = e


def solve_velocities(world, manifolds, dt: float, start=None) -> None:
    """Relaxation sweeps (contacts and joints) and restitution, then the shock pass. ``start``:
    the velocities at the start of the step, for the bounces (see :func:`iterative.relax`)."""
    # the relaxation remembers its own impulses for warm starting: the shock pass's
    # one-sided pushes (still reported in the manifolds) would not balance in the next step
    m = iterative.relax(world, manifolds, dt, start)
    if len(m):
        # lever arms and velocity targets of the contacts (positions only: the same as the
        # relaxation's)
        cons = impulse.build(world, m, dt)
        layer = contact_layers(m.a, m.b, world.inv_mass == 0.0)
        level = np.maximum(layer[m.a], layer[m.b])
        order = np.argsort(level, kind="stable")
        world.stats["shock_layers"] = int(level[level < UNREACHED].max(initial=0))
        shock_pass(
            order, level, m.a, m.b, m.normal, m.count, m.friction, cons.r1, cons.r2, cons.bias,
            m.normal_impulse, m.tangent_impulse, layer, world.vel, world.omega, world.inv_mass,
            world.inv_moment, LAYER_SWEEPS,
        )  # fmt: skip


solve_positions = iterative.solve_positions
