"""The step context: what every compiled stage reads about the step (dt, gravity, the settings
as numbers), one CONTEXT record per world (:data:`sandbox.records.CONTEXT`), filled again
whenever a setting, gravity or dt changes. The stages also report their counters into it."""

from __future__ import annotations

import numpy as np

from sandbox.integrators import CODES as INTEGRATORS
from sandbox.orientation import NAMES as ORIENTATIONS
from sandbox.penetration import METHODS as PENETRATIONS
from sandbox.settings import JOINT_SOLVERS
from sandbox.solvers import KEEPS_IMPULSES

# soft-step settings and their defaults, for a Settings that does not know them yet
SOFT_DEFAULTS = (
    ("substeps", 4),
    ("contact_hertz", 60.0),
    ("contact_damping_ratio", 10.0),
    ("joint_hertz", 120.0),
    ("joint_damping_ratio", 5.0),
    ("max_push_speed", 3.0),
    ("hold_ratio", 10.0),
    ("sag_recovery_time", 1.0),
    ("sleep", False),
)


def fill_context(ctx, settings, gravity: np.ndarray, dt: float) -> None:
    """Write ``settings``, ``gravity`` (m/s^2) and ``dt`` (s) into the CONTEXT record ``ctx``
    (kept as they are: the broadphase's sort axis and the contact sets' bookkeeping)."""
    s = settings
    ctx["dt"], ctx["inv_dt"] = dt, 1.0 / dt
    ctx["pairs_kept"] = False  # a new margin or flags: sweep the boxes again
    ctx["gravity"] = gravity
    ctx["orientation"] = ORIENTATIONS[s.orientation]
    ctx["integrator"] = INTEGRATORS[s.integrator]
    ctx["renormalise"] = s.renormalise
    ctx["iterations"] = s.iterations
    ctx["position_iterations"] = s.position_iterations
    ctx["accumulate"] = s.accumulate_impulses
    # warm starting needs accumulated impulses and a solver that keeps them between steps
    ctx["warm_start"] = s.warm_start and s.accumulate_impulses and s.solver in KEEPS_IMPULSES
    ctx["position_correction"] = s.position_correction
    ctx["penetration"] = PENETRATIONS.index(s.penetration)
    ctx["robust_positions"] = s.robust_positions
    # the soft step's contacts carry their own sag under a heavy load (g / omega^2 per load):
    # holding the light body would fight it, so only overlap makes its passes go in layers
    ctx["hold_heavier"] = s.robust_positions and s.solver != "soft"
    # the prepare stage's block matrices and warm start: none in soft (it warm starts per substep)
    ctx["block_solver"] = s.solver != "soft"
    # overlap beyond the slop plus one step's bounded push (m) is pushed out at max_push_speed
    # by the position passes (sandbox.solvers.wide_positions.allowed_separation); infinite: never
    deep = s.slop + s.max_push_speed * dt
    ctx["deep_overlap"] = deep if s.robust_positions and s.position_correction else np.inf
    ctx["slop"], ctx["baumgarte"] = s.slop, s.baumgarte
    ctx["position_tolerance"] = s.position_tolerance
    ctx["position_stall"] = s.position_stall
    ctx["restitution_threshold"] = s.restitution_threshold
    # at least as far as gravity moves a body from rest in one step (|g| dt^2), so a resting
    # stack keeps its contacts even at a large dt
    ctx["contact_margin"] = max(s.contact_margin, float(np.hypot(*gravity)) * dt * dt)
    ctx["touch_margin"] = s.contact_margin
    ctx["look_ahead"] = dt if getattr(s, "speculative", False) else 0.0
    ctx["box_prediction"] = s.box_prediction  # sap: steps of travel a swept box reaches ahead
    for key, default in SOFT_DEFAULTS:
        ctx[key] = getattr(s, key, default)
    ctx["joint_solver"] = JOINT_SOLVERS.index(getattr(s, "joint_solver", "auto"))
    ctx["diverged"] = -1
    ctx["energy_limit"] = np.inf  # set by the world for a closed system (sandbox.energy_growth)
    ctx["awake"] = -1  # sleep: not known until a step has run
