"""The records every stage of the step shares: bodies, shapes, contacts, joints, forces, settings.

Each is a numpy structured dtype (a C struct with named fields), so the compiled code reads
``contact["points"][j]["normal_impulse"]`` instead of a column number, and one array of records
is one argument of a compiled call. Box2D keeps the same kinds of structs (``b2BodySim``,
``b2ContactConstraint`` holding ``b2ContactConstraintPoint``, ``b2JointSim``, ``b2StepContext``);
the fields here are named after the slides' symbols where the slides have one.

Conventions: SI units, y up, radians counter-clockwise. Body state is about the centre of mass;
a body-frame point ``q`` of body ``i`` is at ``com + R(angle) q`` in the world, with
``R = [[c, -s], [s, c]]`` and ``(c, s) = cs``. A contact's normal points from body ``a`` to body
``b``. Records are created zeroed (``np.zeros(n, BODY)``); fields say below what zero means.
"""

from __future__ import annotations

import numpy as np

# body kinds (``BODY["kind"]``); a SLEEPING body is a dynamic one put to sleep (sandbox.sleep):
# the step treats it as immovable until something wakes it
DYNAMIC, STATIC, KINEMATIC, SLEEPING = 0, 1, 2, 3
# shape kinds (``SHAPE["kind"]``)
CIRCLE, POLYGON = 0, 1
# joint kinds (``JOINT["kind"]``)
PIN, PIVOT, SPRING = 0, 1, 2
# force generator kinds (``GENERATOR["kind"]``)
DRAG, BUOYANCY, CONSTANT = 0, 1, 2

F8, I8 = np.float64, np.int64
V2 = (np.float64, 2)  # a 2D vector field

BODY = np.dtype(
    [
        ("kind", I8),  # DYNAMIC, STATIC, KINEMATIC or SLEEPING
        ("com", V2),  # centre of mass in the world (m)
        ("vel", V2),  # velocity of the centre of mass (m/s)
        ("omega", F8),  # angular velocity (rad/s)
        ("angle", F8),  # orientation (rad), continuous: turns accumulate
        ("cs", V2),  # (cos, sin) of the angle, from the stored orientation (what collision reads)
        ("local_com", V2),  # centre of mass in the body frame, about the origin (m)
        ("mass", F8),  # kg (inf for static and kinematic bodies)
        ("inv_mass", F8),  # 1/kg (0 for static and kinematic bodies)
        ("moment", F8),  # kg m^2 about the centre of mass
        ("inv_moment", F8),
        ("force", V2),  # accumulated for this step (N), cleared after it
        ("torque", F8),  # N m, likewise
        ("const_force", V2),  # applied every step (N)
        ("const_torque", F8),  # N m
        ("applied_force", V2),  # last step's forces besides gravity, generators, contacts (N)
        ("applied_torque", F8),  # N m, likewise
        ("generators", np.uint64),  # bit g set: force generator g acts on this body
        ("ccd", np.bool_),  # continuous collision (time of impact) for this body
        ("free_move", V2),  # the integrator's move of the centre of mass in free motion (m)
        ("free_turn", F8),  # and its turn (rad)
        ("free_vel", V2),  # the velocity free motion ends with, before impulses (m/s)
        ("free_omega", F8),  # rad/s
        ("motion", V2),  # this step's move: free_move + (vel - free_vel) dt (m)
        ("motion_turn", F8),  # and turn (rad); continuous collision may shorten both
        ("turn", F8),  # scratch: how far the position passes turned the body (rad)
        ("delta_position", V2),  # soft step: how far the centre of mass moved this step (m)
        ("sleep_time", F8),  # how long the body has been slower than the sleep tolerances (s)
        ("island", I8),  # sleep: the smallest body index of its island of contacts and joints
        ("sleep_inv_mass", F8),  # a sleeping body's inverse mass and moment, put aside
        ("sleep_inv_moment", F8),
    ],
    align=True,
)

SHAPE = np.dtype(
    [
        ("body", I8),  # owning body
        ("kind", I8),  # CIRCLE or POLYGON
        ("radius", F8),  # circle radius (m); 0 for polygons
        ("center", V2),  # circle centre, or polygon centroid, about the body's centre of mass (m)
        ("first_vertex", I8),  # polygons: VERTEX rows first_vertex ... + vertex_count
        ("vertex_count", I8),
        ("friction", F8),  # Coulomb coefficient (a contact uses the product of its shapes')
        ("restitution", F8),  # coefficient of restitution e (likewise)
        ("bound", F8),  # radius about the centre of mass that encloses the shape (m)
    ],
    align=True,
)

VERTEX = np.dtype(
    [
        ("point", V2),  # polygon vertex about the body's centre of mass, body frame, CCW (m)
        ("normal", V2),  # outward unit normal of the edge from this vertex to the next
    ],
    align=True,
)

CONTACT_POINT = np.dtype(
    [
        # what the solver's sweeps read and write, together (a cache line and a bit)
        ("rn_a", F8),  # r_a x n (m), r_a from a's centre of mass to the point (world frame),
        # worked out once a step: (w x r) . n = w (r x n)
        ("rn_b", F8),  # r_b x n
        ("rt_a", F8),  # r_a x t, t = (n_y, -n_x)
        ("rt_b", F8),  # r_b x t
        ("normal_mass", F8),  # 1 / k_n, k_n = 1/m_a + 1/m_b + (r_a x n)^2/I_a + (r_b x n)^2/I_b
        ("tangent_mass", F8),  # 1 / k_t, the same along the tangent t = (n_y, -n_x)
        ("bias", F8),  # the normal speed v_r . n the solver aims at (m/s)
        ("normal_impulse", F8),  # accumulated this step (N s), warm-started from the last
        ("tangent_impulse", F8),  # friction impulse along t (N s)
        ("max_normal_impulse", F8),  # the largest normal impulse of the step (N s)
        # what the narrowphase found, and what the passes before and after the sweeps use
        ("point", V2),  # world point midway between the surfaces, at detection (m)
        ("depth", F8),  # penetration at detection (m): > 0 overlapping, < 0 a gap
        ("feature", I8),  # which features touch; stays the same while they do (warm starting)
        ("local_a", V2),  # the point a's separation follows, a's body frame about its centre
        # of mass (m): the contact point, or a circle's centre (a circle turns under its contact)
        ("local_b", V2),  # likewise in b's
        ("anchor_depth", F8),  # the depth measured between those two (m): depth, plus how far
        # the point lies out from each circle's centre along the normal
        ("approach_speed", F8),  # v_r . n when the step began, before gravity (m/s)
        ("base_separation", F8),  # soft step: -anchor_depth - (r_b - r_a) . n, r the point's
        # arms at detection: what the bodies' moves are added to for the separation now
        ("separation", F8),  # soft step: the separation at the bodies' latest poses (m)
        ("held_sag", F8),  # soft step: how far below s = 0 the contact's springs rest (m), the
        # sag its load presses in, taken back over steps (sandbox.solvers.soft.hold_sag; the
        # same at a contact's points); carried from step to step with the impulses
        ("bounce_impulse", F8),  # what the passes after the sweeps added (N s), not warm-started
        ("bounce_tangent", F8),  # and their friction (N s, the shock pass's), not warm-started
    ],
    align=True,
)

STORE = 2  # the contact sets: 0 and 1 take turns (the last step's, this step's), 2 keeps the
# contacts of sleeping islands for when they wake (sandbox.sleeping_contacts)

CONTACT = np.dtype(
    [
        ("a", I8),  # body a (the normal points from a to b)
        ("b", I8),
        ("count", I8),  # points used: 1 or 2
        ("normal", V2),  # unit normal from a to b
        ("friction", F8),  # mu: the product of the two shapes' values
        ("inv_mass_a", F8),  # copied in the prepare stage (a frozen body in shock propagation)
        ("inv_moment_a", F8),
        ("inv_mass_b", F8),
        ("inv_moment_b", F8),
        ("use_block", np.bool_),  # two points solved together (block solver)
        ("block_k", F8, 3),  # the 2x2 effective mass matrix K as the block solver reads it:
        # (1 / normal_mass of point 0, k12, 1 / normal_mass of point 1)
        ("block_mass", F8, 3),  # K^-1 as (m11, m12, m22)
        ("points", CONTACT_POINT, 2),
        ("shape_a", I8),
        ("shape_b", I8),
        ("restitution", F8),  # e: the product of the two shapes' values
        ("rebound", F8),  # how much closer a bounce before touching leaves the pair (m)
        ("soft_bias_rate", F8),  # soft step: the spring's bias rate (1/s)
        ("soft_mass_scale", F8),  # soft step: scales the effective mass
        ("soft_impulse_scale", F8),  # soft step: keeps part of the accumulated impulse
    ],
    align=True,
)

JOINT = np.dtype(
    [
        ("kind", I8),  # PIN, PIVOT or SPRING
        ("a", I8),
        ("b", I8),
        ("pair_key", I8),  # min(a, b) * n + max(a, b): bodies sharing a joint do not collide
        ("sorted_key", I8),  # row i holds the i-th smallest pair_key (a sorted list, one per row)
        ("local_a", V2),  # anchor on a, body frame, about a's centre of mass (m)
        ("local_b", V2),
        ("length", F8),  # pin: the rod's length; spring: the rest length (m)
        ("stiffness", F8),  # spring k (N/m)
        ("damping", F8),  # spring c (N s/m)
        ("has_limits", np.bool_),
        ("lower", F8),  # pivot limits on angle_b - angle_a (rad)
        ("upper", F8),
        ("has_motor", np.bool_),
        ("motor_rate", F8),  # rad/s
        ("max_torque", F8),  # N m
        ("angle", F8),  # pivot: angle_b - angle_a (rad), continuous
        ("anchor_a", V2),  # this step's arms r_a, r_b from each centre of mass (m)
        ("anchor_b", V2),
        ("axis", V2),  # pin: unit vector from anchor a to anchor b
        ("axial_mass", F8),  # pin: 1 / K along the axis; pivot: 1 / (1/I_a + 1/I_b)
        ("k", F8, 3),  # pivot: the point constraint's 2x2 K as (k11, k12, k22)
        ("target", V2),  # velocity the rows aim at (arc correction) (m/s)
        ("impulse", V2),  # pin: (along the axis, 0); pivot: the point impulse (N s)
        ("motor_impulse", F8),  # N m s
        ("lower_impulse", F8),  # N m s, >= 0
        ("upper_impulse", F8),
        ("dt", F8),  # the step the impulses were applied over (s), for reaction forces
        ("delta_center", V2),  # soft step: (c_b - c_a) at the start of the step (m)
    ],
    align=True,
)

# one scalar row of a joint, as the soft step's direct joint solve (sandbox.joints.direct)
# gathers them each pass: a pivot has two (x, y), a pin one (along the rod)
JOINT_ROW = np.dtype(
    [
        ("joint", I8),  # which joint
        ("a", I8),  # its bodies
        ("b", I8),
        ("d", V2),  # the row's direction: Cdot = d . (v_b + w_b x r_b - v_a - w_a x r_a)
        ("arm_a", F8),  # r_a x d (m)
        ("arm_b", F8),  # r_b x d (m)
        ("inverse", F8, 4),  # (1/m_a, 1/I_a, 1/m_b, 1/I_b)
        ("error", F8),  # Cdot + bias at the pass start (m/s)
        ("impulse", F8),  # accumulated impulse at the pass start (N s)
        ("own", F8),  # pin: 1 / its prepared effective mass (the block a sweep divides by)
    ],
    align=True,
)

GENERATOR = np.dtype(
    [
        ("kind", I8),  # DRAG, BUOYANCY or CONSTANT
        ("linear", F8),  # drag: N s/m
        ("quadratic", F8),  # drag: N s^2/m^2
        ("angular", F8),  # drag: N m s
        ("surface_y", F8),  # buoyancy: water below this height (m)
        ("fluid_density", F8),  # buoyancy: kg/m^2
        ("linear_drag", F8),  # buoyancy: per unit submerged area
        ("angular_drag", F8),
        ("force", V2),  # constant: N, world frame
        ("torque", F8),  # constant: N m
        ("point", V2),  # constant: where it acts, in the body's origin frame (m)
        ("at_point", np.bool_),  # constant: acts at ``point`` (else at the centre of mass)
    ],
    align=True,
)

# a state the integrators evaluate forces at (and, with the same fields, its time derivative
# (v, a, w, alpha)): Verlet and RK4 look at states between the start and the end of the step
MOTION = np.dtype(
    [
        ("p", V2),  # centre of mass (m)
        ("v", V2),  # velocity (m/s)
        ("phi", F8),  # angle (rad)
        ("w", F8),  # angular velocity (rad/s)
    ],
    align=True,
)

# the broadphase's scratch, kept from step to step: row k describes shape k (the first three
# fields) and place k of the sweep-and-prune order (the others)
PROXY = np.dtype(
    [
        ("aabb", F8, 4),  # shape k's box [xmin, ymin, xmax, ymax], grown by the margin (m)
        ("body", I8),  # shape k's body
        ("fixed", I8),  # bit flags, pairs sharing a bit are left out (step.place_proxies)
        ("lo", F8),  # the lower end of shape k's box along the sweep direction (m)
        ("order", I8),  # the shape at place k of the sorted sweep (always a permutation)
    ],
    align=True,
)

# one box in one band of sort and sweep (sap.gather), the bands one after the other, each in
# sweep order: what the sweep reads of a box, in one record
SWEEP_ENTRY = np.dtype(
    [
        ("lo", F8),  # the box's interval along the sweep direction (m)
        ("hi", F8),
        ("lo_across", F8),  # along the axis across the sweep (y for x and the slanted ones) (m)
        ("hi_across", F8),
        ("x0", F8),  # and along x, which a slanted sweep tests too (m)
        ("x1", F8),
        ("shape", I8),
        ("body", I8),
        ("fixed", I8),  # its broadphase flags (PROXY["fixed"])
        ("first", I8),  # the first band the box crosses
    ],
    align=True,
)

# everything a compiled stage reads about the step, and what it reports back
CONTEXT = np.dtype(
    [
        ("dt", F8),
        ("inv_dt", F8),
        ("gravity", V2),
        ("orientation", I8),  # sandbox.orientation.ANGLE, MATRIX or COMPLEX
        ("integrator", I8),  # index into sandbox.settings.INTEGRATORS
        ("renormalise", np.bool_),
        ("iterations", I8),
        ("position_iterations", I8),
        ("substeps", I8),
        ("warm_start", np.bool_),  # warm starting on (needs accumulated impulses and a solver
        # that keeps impulses from step to step)
        ("accumulate", np.bool_),
        ("position_correction", np.bool_),
        ("penetration", I8),  # index into sandbox.settings.PENETRATIONS
        ("robust_positions", np.bool_),  # position passes from the ground up (shock order)
        ("hold_heavier", np.bool_),  # ... also in layers when a body rests on a much lighter one
        ("block_solver", np.bool_),  # the prepare stage readies the block solver's matrices
        # and warm starts the contacts (the rigid solvers; the soft step has no block solver
        # and warm starts in each substep)
        ("deep_overlap", F8),  # m: overlap at a step's start beyond which the push is bounded
        ("slop", F8),
        ("position_tolerance", F8),  # m: the position passes stop once no overlap is deeper
        ("position_stall", F8),  # ... or once a pass takes out less than this fraction of it
        ("baumgarte", F8),
        ("restitution_threshold", F8),
        ("contact_margin", F8),  # the setting, or |g| dt^2 when larger (m)
        ("touch_margin", F8),  # the setting: closer than this counts as touching (m)
        ("look_ahead", F8),  # s: speculative contacts reach as far as bodies move in this (dt,
        # with settings.speculative; 0: contact_margin alone; sandbox.speculative)
        ("box_prediction", F8),  # steps of travel the swept boxes are stretched by (sap)
        ("contact_hertz", F8),
        ("contact_damping_ratio", F8),
        ("joint_hertz", F8),
        ("joint_damping_ratio", F8),
        ("joint_solver", I8),  # soft step: index into sandbox.settings.JOINT_SOLVERS
        ("max_push_speed", F8),
        ("sag_recovery_time", F8),  # soft step (s), 0: the contacts' sag stays
        ("hold_ratio", F8),  # soft step: hold a lower body under one this many times heavier
        ("sleep", np.bool_),  # sleeping islands on
        # reported by the stages
        ("pair_tests", I8),
        ("pairs", I8),
        ("contacts", I8),
        ("contact_points", I8),
        ("warm_started_points", I8),
        ("shock_layers", I8),
        ("position_passes", I8),  # position passes in the last step (sandbox.penetration)
        ("position_progress", F8),  # the fraction of the overlap the pass before the last took
        # out: 1 - (overlap the last pass met) / (overlap the pass before met); NaN: one pass
        ("joints_together", np.bool_),  # the position stage solves the joints together (the
        # soft step's plan, set each step; the rigid steps sweep them)
        ("sweeps", I8),  # iterative solver: velocity sweeps in the last step (more at a large dt)
        ("sweep_direction", I8),  # sweep and prune: the direction PROXY["order"] is sorted
        # along (sandbox.broadphase.sap.DIRECTIONS), -1: none yet
        ("sweep_recount", I8),  # steps left before the directions are compared again
        ("pairs_kept", np.bool_),  # sweep and prune: pairs[1] holds the pairs of the boxes in
        # PROXY["aabb"], found with FAT_MARGIN to spare (sandbox.step.find_pairs)
        ("contact_set", I8),  # which of the two contact sets holds the last step's contacts
        ("contact_count", I8, 3),  # how many contacts each set holds (the third: STORE)
        ("need", I8),  # > 0: the pair buffer needs this many rows (nothing was changed)
        ("diverged", I8),  # the first body whose state stopped being finite, else -1
        ("energy_limit", F8),  # J: a closed system's KE + PE_gravity above this diverged
        ("energy", F8),  # J: KE + PE_gravity when that check last ran
        ("awake", I8),  # sleep: bodies awake after the last step (dynamic, not sleeping)
        ("fell_asleep", I8),  # sleep: bodies that fell asleep in the last step
    ],
    align=True,
)


def zeros(dtype: np.dtype, n: int) -> np.ndarray:
    """``n`` zeroed records of ``dtype`` (a C-contiguous array)."""
    return np.zeros(n, dtype=dtype)
