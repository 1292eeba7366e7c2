"""Contact and joint solvers, one module per strategy (slides, "Simultaneous Collision
Resolution"): ``pairwise`` (each contact once, in turn), ``shock`` (shock propagation) and
``iterative`` (sequential impulses).

Every solver module offers the same two functions, called by the world each step:

- ``solve_velocities(world, manifolds, dt, start=None)``: impulses on ``world.vel`` /
  ``world.omega`` for the contacts (``manifolds``, may be empty) and ``world.joints``; records the
  impulses it applied in ``manifolds.normal_impulse`` / ``manifolds.tangent_impulse``. ``start``
  = (vel, omega) at the start of the step, before this step's gravity and forces were added
  (default: the current velocities): restitution reflects the approach velocity measured there.
- ``solve_positions(world, manifolds, dt)``: after the positions moved, removes remaining overlap
  the way ``world.settings.penetration`` names (``half``, ``mass_weighted``, ``impulse``).
"""

from __future__ import annotations

from importlib import import_module
from types import ModuleType

NAMES = ("pairwise", "shock", "iterative")


def get(name: str) -> ModuleType:
    """The solver module called ``name``."""
    if name not in NAMES:
        raise ValueError(f"settings.solver: expected one of {', '.join(NAMES)}, got {name!r}")
    return import_module(f"sandbox.solvers.{name}")
