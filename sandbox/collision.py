"""Collision within the step: detection (broadphase + narrowphase), response (the solver's
impulses), continuous collision and the penetration fix. The world calls these four functions.

Slides, "Retroactive Collision Detection": update motion, then for each overlapping pair fix
penetration and handle the collision. Here the overlaps found at the start of a step are
resolved on velocities before the positions move (as box2d-lite does), which keeps resting
contacts quiet.
"""

from __future__ import annotations

import numpy as np

from sandbox.body import DYNAMIC


def detect(world, margin: float = 0.0):
    """Contact manifolds at the current state (``sandbox.contact.Manifolds``)."""
    from sandbox import narrowphase
    from sandbox.broadphase import find_pairs
    from sandbox.broadphase.aabb import shape_aabbs
    from sandbox.contact import Manifolds

    g = world.geometry()
    if len(g) < 2:
        world.stats.update(pair_tests=0, pairs=0, contacts=0, contact_points=0)
        return Manifolds.empty()
    aabb = shape_aabbs(
        g.shape_body,
        g.shape_kind,
        g.shape_radius,
        g.shape_center,
        g.shape_vstart,
        g.shape_vcount,
        g.verts,
        world.com,
        world.cs,
        margin,
    )
    # bodies that cannot be pushed (static and kinematic) never collide with each other
    fixed = world.kind[g.shape_body] != DYNAMIC
    pairs, tests = find_pairs(world.settings.broadphase, aabb, fixed, g.shape_body)
    if world.joints:  # bodies sharing a joint do not collide (as in pymunk's bridge)
        from sandbox.joints import drop_joined

        pairs = drop_joined(world, pairs, g.shape_body)
    manifolds = narrowphase.collide(
        pairs,
        g.shape_body,
        g.shape_kind,
        g.shape_radius,
        g.shape_center,
        g.shape_vstart,
        g.shape_vcount,
        g.verts,
        g.normals,
        g.shape_friction,
        g.shape_restitution,
        world.com,
        world.cs,
        margin,
    )
    world.stats.update(
        pair_tests=int(tests),
        pairs=int(len(pairs)),
        contacts=int(len(manifolds)),
        contact_points=int(np.sum(manifolds.count)) if len(manifolds) else 0,
    )
    return manifolds


def solve_velocities(world, dt: float):
    """Find contacts and let the world's solver change velocities; returns the manifolds."""
    has_shapes = len(world.geometry()) >= 2
    manifolds = detect(world, world.settings.contact_margin) if has_shapes else None
    if (manifolds is None or len(manifolds) == 0) and not world.joints:
        world.stats.setdefault("contacts", 0)
        return manifolds
    from sandbox import solvers

    solvers.get(world.settings.solver).solve_velocities(world, manifolds, dt)
    return manifolds


def solve_positions(world, manifolds, dt: float) -> None:
    """Remove what is left of the overlap after the positions moved (settings.penetration)."""
    if (manifolds is None or len(manifolds) == 0) and not world.joints:
        return
    from sandbox import solvers

    solvers.get(world.settings.solver).solve_positions(world, manifolds, dt)


def limit_ccd_motion(world, dp: np.ndarray, dphi: np.ndarray) -> None:
    """Conservative advancement: a ``ccd`` body moves only up to its time of impact (in place)."""
    from sandbox.toi import limit_motion

    limit_motion(world, dp, dphi)
