# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: percent
# ---

# %% [markdown]
# # 09 Stacking
#
# Slides "Collision Algorithm", "The Stacking Problem" and "Simultaneous Collision Resolution".
#
# The slides' collision algorithm handles one collision at a time: for each collision
# (1) compute the impulse $j = -(1+e)\,\mathbf{v}_r\cdot\hat{\mathbf{n}} / k$, (2)-(3) update
# the linear and angular velocities, (4) solve the interpenetration. Its problems, as the slide
# says: *solving one interpenetration may cause another*, and it *cannot handle stacks*. In a
# stack every box carries the weight of all the boxes above it, but a contact handled once per
# step only stops its own two boxes from approaching; the box above then pushes down again and
# nothing is left to stop it.
#
# The slides' answer is to consider all collisions simultaneously. The engine has three solvers
# (`settings.solver`):
#
# - `pairwise`: the slides' collision algorithm, each contact once, in turn
# - `shock`: shock propagation (Guendelman, Bridson and Fedkiw 2003): relax all contacts a few
#   times, then sweep the contact graph from the ground up, treating the lower body of every
#   contact as immovable, so errors cannot travel back down the stack
# - `iterative`: sequential impulses (box2d-lite, Box2D): sweep over all contacts
#   `iterations` times; each visit fixes one contact given the others, and the sweeps converge
#   towards impulses that satisfy every contact at once. Three switches from box2d-lite show what
#   makes it work: `accumulate_impulses` (clamp each contact's *total* impulse to be >= 0, not each
#   increment, so later sweeps may take back part of an earlier push), `warm_start` (start from
#   last step's impulses, which in a resting stack are nearly the answer) and
#   `position_correction` (the penetration fix of lesson 08).
#
# Two scenes from `scenes/`: a vertical stack of ten 1 m boxes and a pyramid with ten boxes at
# the base (55 boxes), both starting exactly in touch and at rest. A perfect solver leaves them
# exactly where they are.

# %%
import json
import math

import matplotlib.pyplot as plt
import numpy as np

import sandbox
from sandbox.lessonkit import output_dir, print_table, save_figure, scene_path, show_gif
from sandbox.recording import Recording
from sandbox.render import render_gif

# knobs
DURATION = 5.0  # s simulated per run
SOLVERS = ("pairwise", "shock", "iterative")
COLORS = {"pairwise": "C3", "shock": "C0", "iterative": "C2"}
ITERATIONS = (1, 2, 4, 8, 16, 32)  # iterative solver, the stability study
STANDS = 0.05  # m: a scene "stands" when its top box dropped less than this
GIF_EVERY = 4  # steps per animation frame
SCENES = ("stack", "pyramid")

OUT = output_dir("09_stacking")


def load(scene: str, **settings) -> sandbox.World:
    """A scene file with some settings changed."""
    spec = json.loads(scene_path(scene).read_text())
    world = sandbox.load_scene(spec)
    for key, value in settings.items():
        setattr(world.settings, key, value)
    return world


def run(scene: str, frames: bool = False, **settings) -> dict:
    """Simulate DURATION s; per step: top box height error, deepest overlap, largest tilt."""
    world = load(scene, **settings)
    dyn = [b for b in world.bodies if b.type == "dynamic"]
    top = max(dyn, key=lambda b: b.position[1])
    y0 = top.position[1]
    rec = Recording.from_world(world) if frames else None
    if rec is not None:
        rec.capture(world)
    t, err, pen, tilt = [0.0], [0.0], [0.0], [0.0]
    for k in range(1, int(round(DURATION / world.dt)) + 1):
        world.step()
        m = world.manifolds  # contacts found at the start of this step: the previous step's result
        t.append(world.time)
        err.append(top.position[1] - y0)
        pen.append(max(float(m.depth.max()), 0.0) if m is not None and len(m) else 0.0)
        tilt.append(float(np.abs(world.angles()[world.kind == 0]).max()))
        if rec is not None and k % GIF_EVERY == 0:
            rec.capture(world)
    t, err, pen, tilt = map(np.array, (t, err, pen, tilt))
    return {"t": t, "err": err, "pen": pen, "tilt": tilt, "rec": rec, "drop": -err[-1],
            "max_pen": pen.max(), "max_tilt": math.degrees(tilt.max())}  # fmt: skip


# %% [markdown]
# ## Three solvers, two scenes
#
# Each scene under each solver (10 iterations where a solver iterates, the default settings
# otherwise). Measured: how far the top box has dropped after 5 s, the deepest overlap of any
# contact, and the largest tilt of any box.

# %%
results = {(scene, solver): run(scene, frames=True, solver=solver)
           for scene in SCENES for solver in SOLVERS}  # fmt: skip
rows = []
for (scene, solver), r in results.items():
    verdict = "stands" if r["drop"] < STANDS and r["max_tilt"] < 5.0 else "FAILS"
    rows.append((scene, solver, r["drop"], r["max_pen"], r["max_tilt"], verdict))
print_table(["scene", "solver", "top drop after 5 s (m)", "max penetration (m)",
             "max tilt (deg)", "verdict"], rows)  # fmt: skip

# %%
fig, axes = plt.subplots(2, 2, figsize=(12, 7))
for col, scene in enumerate(SCENES):
    for solver in SOLVERS:
        r = results[(scene, solver)]
        axes[0, col].plot(r["t"], r["err"], color=COLORS[solver], label=solver)
        axes[1, col].plot(r["t"], r["pen"], color=COLORS[solver], label=solver)
    axes[0, col].set(xlabel="t (s)", ylabel="top box height error (m)", yscale="symlog",
                     title=f"{scene}: top box y(t) - y(0)")  # fmt: skip
    axes[0, col].set_yscale("symlog", linthresh=1e-3)
    axes[1, col].set(xlabel="t (s)", ylabel="deepest overlap (m)", yscale="log", ylim=(1e-5, 2),
                     title=f"{scene}: max penetration")  # fmt: skip
for ax in axes.flat:
    ax.grid(alpha=0.3)
handles, names = axes[0, 0].get_legend_handles_labels()
fig.legend(handles, names, loc="lower center", ncol=3, fontsize=9)
fig.tight_layout(rect=(0, 0.05, 1, 1))
save_figure(fig, OUT / "solvers.png", dpi=100)

LANE_ORDER = ("shock", "iterative", "pairwise")  # side by side, left to right
for scene in SCENES:
    # each solver's run in its own lane: shifted right past the previous lane's widest extent
    lanes, left, top = [], 0.0, 0.0
    for solver in LANE_ORDER:
        rec = results[(scene, solver)]["rec"]
        poses = rec.poses()
        moving = [i for i, t in enumerate(rec.types) if t == "dynamic"]
        x_min, x_max = poses[:, moving, 0].min() - 0.8, poses[:, moving, 0].max() + 0.8
        top = max(top, poses[:, moving, 1].max() + 0.8)  # 0.8 m > half a box's diagonal
        shift = left - x_min
        lane = Recording(names=rec.names, types=rec.types, outlines=rec.outlines)
        for pose, t in zip(rec.frames, rec.times, strict=True):
            lane.add_frame(pose + (shift, 0.0, 0.0), t)
        lanes.append(lane)
        print(f"{scene}, {solver}: boxes between x = {x_min + 0.8:+.1f} and {x_max - 0.8:+.1f} m")
        left += x_max - x_min + 0.5
    gif = render_gif(
        lanes, OUT / f"{scene}.gif", fps=15, size_px=400, labels=list(LANE_ORDER),
        colors=[COLORS[s] for s in LANE_ORDER], view=(-0.5, left, -0.6, top + 0.5),
    )  # fmt: skip
    show_gif(gif)
    print(f"wrote {len(lanes[0])} frames to {gif.name}")

# %% [markdown]
# (In the animations each solver's run has its own lane, shifted sideways so that none hides
# another: shock and iterative stand identically, the pairwise boxes spread over metres.)
#
# The pairwise solver fails on both scenes: within the first second the stack sinks into itself
# (the overlap grows to tens of centimetres, far beyond what the one-pass penetration fix
# removes), boxes are squeezed out sideways and the stack falls over. Shock propagation and the
# iterative solver hold both scenes: the top box drops about 1 cm with 10 iterations, under a
# millimetre with shock propagation.
#
# Why the pairwise solver sinks: at rest, gravity gives every box a downward velocity $g\Delta t$
# each step. Box 1 on the ground gets an impulse that stops it; then the contact between box 1
# and box 2 stops box 2 by pushing box 1 *down* again, and the ground contact is not looked at
# again in this step. Every contact passes the weight one box down and no further, so each step
# leaves each box sinking, and the error grows with the height of the stack.
#
# ## Iterations against stability
#
# The iterative solver converges with the number of sweeps: each sweep carries the weight
# information one contact further. With warm starting, the impulses of the last step are a
# head start, so even one sweep per step holds both scenes up to a few centimetres; every doubling
# of the sweeps roughly halves the sag. (The dotted lines: shock propagation with 10 iterations;
# a drop below 1e-5 m is drawn at 1e-5.)

# %%
sweep = {(scene, it): run(scene, solver="iterative", iterations=it)
         for scene in SCENES for it in ITERATIONS}  # fmt: skip
print_table(
    ["iterations", *(f"{s}: top drop (m)" for s in SCENES), *(f"{s}: max pen (m)" for s in SCENES)],
    [(it, *(sweep[(s, it)]["drop"] for s in SCENES), *(sweep[(s, it)]["max_pen"] for s in SCENES))
     for it in ITERATIONS],
)  # fmt: skip

# %% [markdown]
# ## What the box2d-lite switches buy
#
# The same two scenes under the iterative solver (10 iterations) with one switch at a time off.

# %%
VARIANTS = [
    ("default (all on)", {}),
    ("warm_start off", {"warm_start": False}),
    ("warm_start off, 32 iterations", {"warm_start": False, "iterations": 32}),
    ("accumulate_impulses off", {"accumulate_impulses": False}),
    ("position_correction off", {"position_correction": False}),
]
SHORT = [
    "all on",
    "warm start\noff",
    "warm start off\n32 iterations",
    "accumulate\noff",
    "position\ncorrection off",
]
switches, rows = {}, []
for name, settings in VARIANTS:
    for scene in SCENES:
        r = run(scene, solver="iterative", **settings)
        switches[(name, scene)] = r
        rows.append((name, scene, r["drop"], r["max_pen"], r["max_tilt"],
                     "stands" if r["drop"] < STANDS and r["max_tilt"] < 5.0 else "FAILS"))  # fmt: skip
print_table(["iterative solver", "scene", "top drop (m)", "max pen (m)", "max tilt (deg)",
             "verdict"], rows)  # fmt: skip

# %%
fig, (ax, bx) = plt.subplots(1, 2, figsize=(12, 5.2))
for k, scene in enumerate(SCENES):
    ax.plot(ITERATIONS, [sweep[(scene, it)]["drop"] for it in ITERATIONS], marker="o",
            color=f"C{k}", label=f"{scene}: iterative")  # fmt: skip
    shock = results[(scene, "shock")]["drop"]
    ax.axhline(max(shock, 1e-5), color=f"C{k}", ls=":",
               label=f"{scene}: shock, 10 iterations ({shock:.1e} m"
               + (", drawn at 1e-5)" if shock < 1e-5 else ")"))  # fmt: skip
ax.set(xscale="log", yscale="log", xlabel="iterations per step (count)",
       ylabel="top drop after 5 s (m)", title="iterative solver: more sweeps, stiffer stack")  # fmt: skip
ax.set_xticks(ITERATIONS, [str(i) for i in ITERATIONS])
ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=2)
ax.grid(alpha=0.3)
names = [name for name, _ in VARIANTS]
x = np.arange(len(names))
for k, scene in enumerate(SCENES):
    bx.bar(x + (k - 0.5) * 0.38, [switches[(n, scene)]["drop"] for n in names], 0.38,
           color=f"C{k}", label=scene)  # fmt: skip
bx.axhline(STANDS, color="k", ls="--", lw=1, label=f"{STANDS} m")
bx.set_yscale("log")
bx.set_xticks(x, SHORT, fontsize=8)
bx.set(ylabel="top drop after 5 s (m)", title="box2d-lite switches (iterative, 10 iterations)")
bx.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.2), ncol=3)
fig.tight_layout()
save_figure(fig, OUT / "iterations_and_switches.png", dpi=100)

# %% [markdown]
# - **warm starting** matters most for a tall stack: without it each step starts from zero
#   impulses and 10 sweeps cannot carry nine boxes' weight down to the ground, so the stack
#   sags and leans; even 32 cold sweeps do worse than 10 warm ones.
# - **accumulated impulses**: clamping each increment to be >= 0 means a sweep can never take
#   back an earlier push, so the impulses overshoot and boxes bounce apart and sink in turns;
#   the stack topples. (Warm starting needs accumulated impulses, so it is off as well.)
# - **position correction** hardly matters here: the iterative solver keeps the overlaps below
#   the 5 mm slop, where the penetration fix does nothing. It matters when something pushes
#   bodies deep into each other (lesson 08).

# %% [markdown]
# ## A large dt: sweeping until the stack holds
#
# At dt = 1/60 s the 10 warm-started sweeps hold the stack. At a large dt they would not: a box
# falls |g| dt^2 in one step (2.45 m at dt = 0.5 s), so whatever the sweeps leave unsolved moves
# the boxes deep into one another before the next step can correct it, and the first step starts
# cold. So when |g| dt^2 is larger than the contact margin and the slop, the iterative solver
# keeps sweeping after its `iterations` until every normal constraint holds to a thousandth of
# the slop per dt (at most 20 times `iterations`); `world.stats["sweeps"]` says how many it took.

# %%
LARGE_DT = (1 / 60, 0.1, 0.25, 0.5)  # s
LARGE_DT_DURATION = 10.0  # s


def large_dt_run(dt: float) -> tuple:
    """The stack for LARGE_DT_DURATION s at ``dt``: steps, sweeps of the first step, most sweeps
    of a later step, mean sweeps per step, top box drop at the end (mm)."""
    spec = json.loads(scene_path("stack").read_text())
    spec["dt"] = dt
    world = sandbox.load_scene(spec)
    top = max((b for b in world.bodies if b.type == "dynamic"), key=lambda b: b.position[1])
    y0 = top.position[1]
    sweeps = []
    for _ in range(int(round(LARGE_DT_DURATION / dt))):
        world.step()
        sweeps.append(world.stats["sweeps"])
    drop = 1000 * (y0 - top.position[1])
    return dt, len(sweeps), sweeps[0], max(sweeps[1:]), float(np.mean(sweeps)), drop


print_table(["dt (s)", "steps", "sweeps, first step", "most sweeps, later steps",
             "mean sweeps per step", f"top box drop after {LARGE_DT_DURATION:g} s (mm)"],
            [large_dt_run(dt) for dt in LARGE_DT], digits=3)  # fmt: skip

# %% [markdown]
# At 60 Hz nothing changes: 10 sweeps a step, exactly what `iterations` asks. From dt = 0.1 s
# the cold first step needs the whole 200, and a step costs more sweeps the larger the dt
# (about 15, 26 and 49 on average here); in exchange the stack stands even at dt = 0.5 s, only
# 2 cm lower after 10 s, with 20 steps in all.

# %% [markdown]
# ## How a sweep runs: eight contacts at a time
#
# A sweep visits the contacts one after another, each given what the ones before it did, and
# any fixed order is a valid sweep (Gauss-Seidel). The engine picks an order its processor can
# run fast, as Box2D v3 does: it *colours* the contacts so that no two of one colour share a
# body that moves (the ground only pushes, so any number of one colour may touch it). Within a
# colour no visit changes what another reads, so visiting them one by one or all at once gives
# the very same numbers, and the processor visits eight at once with its vector instructions
# (`sandbox/solvers/wide.py`; the arithmetic of a visit is `sandbox/solvers/impulses.py`, the
# same for both). A sweep is one colour after another. Contacts with one point (a disc on
# anything) have lanes of their own (`sandbox/solvers/wide_single.py`): in a lane made for two
# points their second point and the block solver would be wasted work. So within each colour
# the contacts with two points come first, then those with one; only a body touching more than
# 63 others leaves contacts without a colour, visited one by one at the end.
#
# Below: the pyramid's contacts after 1 s, coloured as the step colours them, then the same
# ten sweeps on copies of them three ways: one contact at a time colour by colour, one at a
# time in the order the contacts are listed, and eight at a time colour by colour.

# %%
import time

from sandbox.records import JOINT
from sandbox.solvers.iterative import coloured_sweeps, visit_contact
from sandbox.solvers.iterative import sweep as sweep_as_listed
from sandbox.solvers.wide import COLOURS, LANES, colour

world_c = load("pyramid")
for _ in range(60):
    world_c.step()
contacts_c, bodies_c = world_c.manifolds.records.copy(), world_c.state.copy()
colours_c = np.empty(len(contacts_c), dtype=np.int64)
count_c = colour(contacts_c, len(contacts_c), bodies_c, colours_c, False, True)
sizes_c = np.bincount(colours_c[colours_c < COLOURS], minlength=count_c)
print_table(["colour", "contacts", f"blocks of {LANES}"],
            [*((c, int(n), -(-int(n) // LANES)) for c, n in enumerate(sizes_c)),
             ("one by one", int(np.sum(colours_c == COLOURS)), "-")])  # fmt: skip


def one_at_a_time(contacts, bodies, sweeps: int) -> None:
    """``sweeps`` sweeps, one contact at a time, colour by colour (two points, then one)."""
    points = contacts["count"]
    order = [
        i
        for c in range(count_c)
        for n in (2, 1)
        for i in np.flatnonzero((colours_c == c) & (points == n))
    ]
    for _ in range(sweeps):
        for i in order:
            visit_contact(contacts[i], bodies, True)


def timed(sweeps_of, repeats: int = 20) -> tuple[float, np.ndarray]:
    """The median time of ten sweeps on fresh copies (ms), and the velocities they leave."""
    times = []
    for _ in range(repeats):
        contacts, bodies = contacts_c.copy(), bodies_c.copy()
        start = time.perf_counter()
        sweeps_of(contacts, bodies)
        times.append(1000 * (time.perf_counter() - start))
    return float(np.median(times)), np.column_stack([bodies["vel"], bodies["omega"]])


def listed(contacts, bodies) -> None:
    """Ten sweeps one contact at a time in the order they are listed (compiled)."""
    for _ in range(10):
        sweep_as_listed(contacts, len(contacts), bodies, True)


no_joints = np.zeros(0, dtype=JOINT)
one_ms, one_v = timed(lambda c, b: one_at_a_time(c, b, 10))
list_ms, list_v = timed(listed)
wide_ms, wide_v = timed(lambda c, b: coloured_sweeps(c, len(c), no_joints, b, 10))
print_table(["10 sweeps", "ms", "largest velocity difference from the first (m/s)"],
            [("one at a time, colour by colour (a Python loop)", one_ms, "0"),
             ("one at a time, as listed (compiled)", list_ms, f"{np.abs(list_v - one_v).max():.1e}"),
             ("eight at a time, colour by colour (the engine)", wide_ms,
              f"{np.abs(wide_v - one_v).max():.1e}")], digits=4)  # fmt: skip


# %%
def ends(contact) -> np.ndarray:
    """The contact as an edge of the contact graph: from body a's centre to body b's, or from
    the middle of its points when a body does not move (the ground)."""
    middle = contact["points"][: contact["count"]]["point"].mean(axis=0)
    moves = [bodies_c["inv_mass"][contact[side]] > 0.0 for side in ("a", "b")]
    return np.array([bodies_c["com"][contact[side]] if moving else middle
                     for side, moving in zip(("a", "b"), moves, strict=True)])  # fmt: skip


fig, ax = plt.subplots(figsize=(8.0, 5.0))
square = ((-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5), (-0.5, -0.5))
for n, body in enumerate(b for b in world_c.bodies if b.type == "dynamic"):
    corners = np.array([body.world_point(p) for p in square])
    ax.plot(corners[:, 0], corners[:, 1], color="0.8", lw=0.8, label="boxes" if n == 0 else None)
alone_c = int(np.sum(colours_c == COLOURS))
for c in [*range(count_c), COLOURS]:
    chosen = np.flatnonzero(colours_c == c)
    for n, i in enumerate(chosen):
        edge = ends(contacts_c[i])
        style = {"color": "0.4", "ls": ":"} if c == COLOURS else {"color": f"C{c}"}
        label = f"colour {c}: {len(chosen)} contacts" if c < COLOURS else f"one by one: {alone_c}"
        ax.plot(edge[:, 0], edge[:, 1], lw=2, label=label if n == 0 else None, **style)
ax.set(aspect="equal", xlabel="x (m)", ylabel="y (m)",
       title=f"the pyramid's contact graph: {len(contacts_c)} contacts, {count_c} colours")  # fmt: skip
ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.02, 1.0))
fig.tight_layout()
save_figure(fig, OUT / "contact_colours.png", dpi=100)

# %% [markdown]
# No colour has two contacts on one box, so there are about as many colours as a box has
# contacts (its two neighbours, the one or two below and the one or two above). Colour by
# colour, one at a time or eight at a time give the very same velocities (difference 0: the
# same arithmetic in the same order); the order in which the contacts are listed gives
# slightly different ones, another valid sweep. On 145 contacts the sweeps take microseconds
# and the call costs as much; on the pyramid of base 40 (2,400 contacts in 6 colours) eight
# visits at a time took a fifth of the time of one at a time, and a whole sweep, with the
# velocities copied into the lanes and back, less than half (`benchmarks/profile_step.py`).
# The order does change the result a little against the
# engine's earlier one-by-one order, which sweeps the contacts as they are listed: the ten-box
# stack rests 0.8 mm lower (12.1 against 11.3 mm after 5 s), within the slop either way.

# %% [markdown]
# ## Explore: solver, iterations and warm starting
#
# Run a scene again with other settings: the picture shows it after 5 s, the plots how far the
# top box sank and how deep the worst overlap got. In JupyterLab the controls rerun and redraw;
# a script draws the defaults once.

# %%
from sandbox.explorer import Choice, Slider, Toggle, explore
from sandbox.frames import FrameRenderer


def stacking(scene: str = "stack", solver: str = "iterative", iterations: int = 10,
             warm_start: bool = True):  # fmt: skip
    """One run of DURATION s; the last frame beside the top drop and the deepest overlap."""
    r = run(scene, frames=True, solver=solver, iterations=iterations, warm_start=warm_start)
    with FrameRenderer(r["rec"], size_px=360, axes=True) as frames:
        picture = frames.frame(len(r["rec"]) - 1)
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 4.2), gridspec_kw={"width_ratios": [1, 1.4]})
    ax.imshow(picture)
    ax.set_axis_off()
    ax.set_title(f"{scene} after {DURATION:g} s: {solver}, {iterations} iterations, "
                 f"warm start {'on' if warm_start else 'off'}", fontsize=9)  # fmt: skip
    bx.plot(r["t"], np.maximum(-r["err"], 1e-6), color="C0", label="top box drop (m)")
    bx.plot(r["t"], np.maximum(r["pen"], 1e-6), color="C3", label="deepest overlap (m)")
    bx.axhline(STANDS, color="k", ls="--", lw=1, label=f"stands: drop < {STANDS} m")
    bx.set(yscale="log", ylim=(1e-6, 20), xlabel="t (s)", ylabel="length (m), 1e-6 at least",
           title=f"top drop after {DURATION:g} s: {r['drop']:.2e} m")  # fmt: skip
    bx.legend(fontsize=8, loc="lower right")
    bx.grid(alpha=0.3)
    fig.tight_layout()
    return fig


explore(stacking, OUT / "explore_stacking.png",
        scene=Choice(SCENES, "scene"), solver=Choice(SOLVERS, "solver"),
        iterations=Slider(1, 32, 1, "iterations"), warm_start=Toggle("warm start"))  # fmt: skip

# %% [markdown]
# ## Exercises
#
# Predict first, then run the cell under the question, then open the answer.
#
# **1.** The iterative solver with 4 sweeps per step lets the stack's top box sag by about 3 cm
# in 5 s. What do you expect with 8 sweeps, and with 32?

# %%
for it in (4, 8, 32):
    print(f"{it:2d} iterations: stack top drop {100 * sweep[('stack', it)]['drop']:.2f} cm")

# %% [markdown]
# <details><summary>Answer</summary>
#
# Each sweep carries the weight one contact further and warm starting keeps last step's
# progress, so the error left shrinks roughly in proportion to the number of sweeps: about half
# with twice as many. The table gives 3.24 cm, 1.55 cm (x 0.48) and 0.28 cm at 32 (x 0.09 for 8
# times the sweeps).
#
# </details>
#
# **2.** The pairwise solver lost the ten-box stack. Does it hold a stack of just *two* boxes?

# %%
spec_e2 = json.loads(scene_path("stack").read_text())
spec_e2["bodies"] = spec_e2["bodies"][:3]  # the ground and the first two boxes
world_e2 = sandbox.load_scene(spec_e2)
world_e2.settings.solver = "pairwise"
top_e2 = world_e2.bodies[-1]
y0_e2 = top_e2.position[1]
for _ in range(int(round(DURATION / world_e2.dt))):
    world_e2.step()
print(f"two boxes, pairwise: the top box dropped {y0_e2 - top_e2.position[1]:.3f} m, "
      f"turned {math.degrees(top_e2.angle):.1f} deg, ended at x = {top_e2.position[0]:.2f} m")  # fmt: skip

# %% [markdown]
# <details><summary>Answer</summary>
#
# No. Even with one box on another, the contact between the two boxes pushes the lower box back
# into the ground after the ground contact was handled, every step; the penetration fix pushes
# the pair out again, slightly unevenly at the two corners, and the error builds up until the top
# box slides off: after 5 s it has dropped 1.008 m (a box height: it is on the ground) and lies
# turned by 90 degrees. Handling contacts one at a time cannot hold even the smallest stack.
#
# </details>
#
# **3.** Turning `position_correction` off barely changed the iterative solver's result: the top
# box dropped just as far. Predict why from the deepest overlap it reached.

# %%
for name in ("default (all on)", "position_correction off"):
    r_e3 = switches[(name, "stack")]
    print(f"{name}: max penetration {1000 * r_e3['max_pen']:.2f} mm, top drop "
          f"{1000 * r_e3['drop']:.2f} mm (slop {1000 * load('stack').settings.slop:.0f} mm)")  # fmt: skip

# %% [markdown]
# <details><summary>Answer</summary>
#
# The position pass only pushes apart overlaps deeper than the slop, 5 mm. The iterative solver
# keeps the stack's deepest overlap near it: 5.47 mm without the pass, so the pass has a
# fraction of a millimetre to do, and with it the deepest overlap is 5.36 mm. The top box drops
# 12.12 mm either way. (Before the sweeps visited the contacts colour by colour, in another
# order, the deepest overlap stayed at 3.81 mm and the pass never acted at all: the order of
# the visits changes where within the slop a stack comes to rest, not whether it stands.)
#
# </details>
