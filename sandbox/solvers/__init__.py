"""Contact and joint solvers, one module per strategy (slides, "Simultaneous Collision
Resolution"), all over the same CONTACT and JOINT records (:mod:`sandbox.records`):

- ``pairwise``: each contact once, in turn (the slides' collision algorithm);
- ``shock``: sequential impulses, then shock propagation layer by layer;
- ``iterative``: sequential impulses, accumulated and warm-started (box2d-lite);
- ``soft``: the soft step, substeps with soft constraints and a relax pass (Box2D v3), whose
  stages differ enough to be a sequence of their own (:mod:`sandbox.solvers.soft`,
  ``sandbox.step.soft_step``).

Each module but ``soft`` offers ``solve(contacts, k, joints, bodies, context)``, the step's
``solve`` stage (:mod:`sandbox.step`); what they share is in :mod:`sandbox.solvers.common`.
"""

from __future__ import annotations

from sandbox.solvers import iterative, pairwise, shock

SOLVERS = {"pairwise": pairwise, "shock": shock, "iterative": iterative}
NAMES = tuple(SOLVERS)
# solvers whose impulses carry over from step to step (and so are warm-started)
KEEPS_IMPULSES = ("shock", "iterative", "soft")
