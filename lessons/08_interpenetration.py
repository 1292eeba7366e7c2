# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: percent
# ---

# %% [markdown]
# # 08 Solving interpenetration
#
# Slide "Solving Interpenetration". Collisions are found after the bodies have moved, so they
# already overlap by a depth $p$ along the normal $\hat{\mathbf{n}}$ (from body 1 to body 2).
# The impulse fixes the velocities; the positions still need pushing apart. Three options
# (`settings.penetration`):
#
# 1. **simple** (`half`): each body moves away by half the penetration,
#    $\mathbf{p}'_1 = \mathbf{p}_1 - \frac{p}{2}\hat{\mathbf{n}}$,
#    $\mathbf{p}'_2 = \mathbf{p}_2 + \frac{p}{2}\hat{\mathbf{n}}$
# 2. **better** (`mass_weighted`): the lighter body moves more,
#    $\mathbf{p}'_1 = \mathbf{p}_1 - \frac{m_2}{m_1 + m_2} p\,\hat{\mathbf{n}}$,
#    $\mathbf{p}'_2 = \mathbf{p}_2 + \frac{m_1}{m_1 + m_2} p\,\hat{\mathbf{n}}$
#    (the centre of mass of the pair stays where it was)
# 3. **even better** (`impulse`): the collision equation applied to positions. For each contact
#    point a pseudo-impulse $\lambda = -C / k$ with the collision equation's denominator
#    $k = \frac{1}{m_1} + \frac{1}{m_2} + \frac{(\mathbf{r}_1\times\hat{\mathbf{n}})^2}{I_1}
#    + \frac{(\mathbf{r}_2\times\hat{\mathbf{n}})^2}{I_2}$ and $C = \beta\,(\text{separation}
#    + \text{slop})$ moves *and turns* both bodies:
#    $\mathbf{p}_1 \mathrel{-}= \lambda\hat{\mathbf{n}} / m_1$,
#    $\theta_1 \mathrel{-}= (\mathbf{r}_1\times\lambda\hat{\mathbf{n}}) / I_1$, the opposite for
#    body 2. It removes a fraction $\beta$ (`settings.baumgarte`) per pass, a few passes per step.
#    One point's push is `push_point` in `sandbox/solvers/impulses.py`. Like the velocity
#    sweeps (lesson 09), a pass visits the contacts colour by colour, eight at a time with the
#    processor's vector instructions (`sandbox/solvers/wide_positions.py`): any fixed order is
#    a valid pass, and this one gives the same numbers as one contact at a time in that order.
#
# All three leave `settings.slop` (5 mm) of overlap so that resting contacts stay in touch.
# A static body has infinite mass: options 1 and 2 then both move the other body by all of $p$,
# so they only differ between two moving bodies.
#
# The first sections run these passes as the slide has them (`robust_positions: false`, and
# every pass of a step: `position_tolerance: 0`, `position_stall: 0`). The engine's default
# adds three things to them. Two are shown in the section on the default: the passes go from
# the ground up, and an overlap a body *started* the step with comes out at a bounded speed.
# The third, Box2D's, in the last section: a step's passes stop once no point overlaps more
# than `position_tolerance` (15 mm, three slops), so a resting pile, whose overlaps are a few
# millimetres, takes one pass a step instead of three; or once a pass stalls.

# %%
import math

import matplotlib.pyplot as plt
import numpy as np

from sandbox.body import Body
from sandbox.lessonkit import output_dir, print_table, save_figure, show_gif
from sandbox.recording import OutlineArrays, place, record
from sandbox.render import render_gif
from sandbox.shapes import Box, Circle
from sandbox.world import World

# knobs
OPTIONS = ("half", "mass_weighted", "impulse")
LABELS = {"half": "1: half", "mass_weighted": "2: mass weighted", "impulse": "3: impulse"}
COLORS = {"half": "C3", "mass_weighted": "C0", "impulse": "C2"}
HEAVY_DENSITY = 3.0  # kg/m^2 of the 2 x 1 m box (6 kg); the 1 x 1 m box has density 1 (1 kg)
OVERLAP = 0.25  # m, how deep the light box's corner starts inside the heavy one
LIGHT_TILT = 30.0  # degrees
PAIR_STEPS = 30
TILT = 30.0  # degrees, box dropped corner-first into the ground
DIVE = 0.3  # m, how deep its corner starts below the ground surface
DURATION = 1.5  # s
G = 9.81  # m/s^2
DT = 1.0 / 60.0
GIF_EVERY = 2
# the passes as the slide has them: the classic order, and every pass of a step
SLIDE_PASSES = {"robust_positions": False, "position_tolerance": 0.0, "position_stall": 0.0}

OUT = output_dir("08_interpenetration")


def max_depth(world: World) -> float:
    """Deepest overlap of any contact at the current state (m, 0 when apart)."""
    return max([c.depth for c in world.find_contacts()] + [0.0])


# %% [markdown]
# ## Two overlapping boxes of unequal mass
#
# No gravity and no velocities, so nothing but the penetration fix moves the boxes: a light
# 1 kg box, tilted 30 degrees and centred 0.5 m right of a heavy 6 kg box, has its lowest
# corner 0.25 m deep in the heavy box. Expected (with $p$ = 0.25 m - slop):
#
# - option 1: both boxes move $p/2$ = 0.1225 m; the pair's centre of mass moves
# - option 2: the heavy box moves $\frac{1}{7}p$ = 0.035 m, the light one $\frac{6}{7}p$ = 0.21 m;
#   the centre of mass stays
# - option 3: the corner is pushed out partly by *turning* the light box about its centre of mass,
#   which the lever arm $\mathbf{r}\times\hat{\mathbf{n}}$ makes cheap; the centre of mass stays


# %%
def pair_world(option: str) -> tuple[World, Body, Body]:
    world = World(gravity=(0.0, 0.0), dt=DT, penetration=option, **SLIDE_PASSES)
    heavy = world.add_body(Body(name="heavy"))
    heavy.add_shape(Box(2.0, 1.0, density=HEAVY_DENSITY))
    tilt = math.radians(LIGHT_TILT)
    reach = 0.5 * (math.cos(tilt) + math.sin(tilt))  # centre to lowest corner of a tilted box
    light = world.add_body(Body(name="light", position=(0.5, 0.5 + reach - OVERLAP), angle=tilt))
    light.add_shape(Box(1.0, 1.0, density=1.0))
    return world, heavy, light


def pair_com(heavy: Body, light: Body) -> np.ndarray:
    m = heavy.mass + light.mass
    return (
        heavy.mass * np.array(heavy.center_of_mass) + light.mass * np.array(light.center_of_mass)
    ) / m


pair, rows, pair_runs = {}, [], []
for option in OPTIONS:
    world, heavy, light = pair_world(option)
    start = (
        np.array(heavy.position),
        np.array(light.position),
        light.angle,
        pair_com(heavy, light),
    )
    depth, angle = [max_depth(world)], [math.degrees(light.angle)]
    rec = record(world, 0)
    for _ in range(PAIR_STEPS):
        world.step()
        depth.append(max_depth(world))
        angle.append(math.degrees(light.angle))
        rec.capture(world)
    pair_runs.append(rec)
    depth = np.array(depth)
    pair[option] = {"depth": depth, "angle": np.array(angle)}
    settled = int(np.argmax(depth <= 1.01 * world.settings.slop))
    rows.append((
        LABELS[option], settled, depth[-1],
        float(np.linalg.norm(np.array(heavy.position) - start[0])),
        float(np.linalg.norm(np.array(light.position) - start[1])),
        math.degrees(light.angle - start[2]), heavy.angle,
        float(np.linalg.norm(pair_com(heavy, light) - start[3])),
        float(np.abs(world.vel).max()),
    ))  # fmt: skip
print_table(
    ["option", "steps to slop", "depth left (m)", "heavy moved (m)", "light moved (m)",
     "light turned (deg)", "heavy angle (rad)", "pair COM moved (m)", "max |v| (m/s)"],
    rows,
)  # fmt: skip
p_fix = OVERLAP - 0.005
print(f"slides: option 1 moves each by {p_fix / 2:.4f} m; option 2 moves heavy by "
      f"{p_fix / 7:.4f} m and light by {6 * p_fix / 7:.4f} m (p = {OVERLAP} m - slop)")  # fmt: skip


# %%
def draw(ax, rec, frame: int, color) -> None:
    """The outlines of every body of a recording at one frame."""
    shapes = OutlineArrays.of(rec)
    polys = place(shapes.local, shapes.body, rec.frames[frame])
    for poly in polys:
        ax.fill(poly[:, 0], poly[:, 1], facecolor=color, alpha=0.25, edgecolor=color, lw=1.5)


fig, axes = plt.subplots(1, 4, figsize=(14, 4.0), sharey=True)
draw(axes[0], pair_runs[0], 0, "0.4")
axes[0].set_title("start: corner 0.25 m deep")
for ax, option, rec in zip(axes[1:], OPTIONS, pair_runs, strict=True):
    draw(ax, pair_runs[0], 0, "0.85")
    draw(ax, rec, -1, COLORS[option])
    ax.set_title(f"option {LABELS[option]} (grey: start)")
for ax in axes:
    ax.set(aspect="equal", xlim=(-1.2, 1.4), ylim=(-0.7, 1.9), xlabel="x (m)")
    ax.grid(alpha=0.3)
axes[0].set_ylabel("y (m)")
fig.tight_layout()
save_figure(fig, OUT / "overlapping_boxes.png", dpi=100)

# %% [markdown]
# ## A box pushed corner-first into the ground
#
# Gravity on, a 1 m box tilted 30 degrees, starting with its corner 0.3 m below the ground's
# surface (as if a large step had carried it there). The ground is static, so options 1 and 2
# give the same result: they lift the box straight up by almost the whole 0.3 m in the first
# step. That lift is potential energy from nowhere ($m g \Delta y$), and with its corner now
# resting on the ground the box topples over fast. Option 3 pushes at the corner: a push there
# both lifts the box and turns it towards lying flat, removing the overlap over a few steps
# with less lifting.


# %%
def corner_world(option: str) -> tuple[World, Body]:
    world = World(gravity=(0.0, -G), dt=DT, penetration=option, **SLIDE_PASSES)
    ground = world.add_body(Body(name="ground", type="static"))
    ground.add_shape(Box(8.0, 0.5, offset=(0.0, -0.25)))
    tilt = math.radians(TILT)
    reach = 0.5 * (math.cos(tilt) + math.sin(tilt))
    box = world.add_body(Body(name="box", position=(0.0, reach - DIVE), angle=tilt))
    box.add_shape(Box(1.0, 1.0))
    return world, box


corner, rows = {}, []
steps = int(round(DURATION / DT))
for option in OPTIONS:
    world, box = corner_world(option)
    e0 = world.energy()
    series = {k: [v] for k, v in (("t", 0.0), ("depth", max_depth(world)), ("y", box.center_of_mass[1]),
                                  ("angle", math.degrees(box.angle)), ("E", 0.0))}  # fmt: skip
    w_max = 0.0
    for _ in range(steps):
        world.step()
        series["t"].append(world.time)
        series["depth"].append(max_depth(world))
        series["y"].append(box.center_of_mass[1])
        series["angle"].append(math.degrees(box.angle))
        series["E"].append(world.energy() - e0)
        w_max = max(w_max, abs(box.angular_velocity))
    s = {k: np.array(v) for k, v in series.items()}
    corner[option] = s
    rows.append((LABELS[option], s["depth"][1], int(np.argmax(s["depth"] <= 0.01)),
                 s["y"][1] - s["y"][0], float(s["E"].max()), w_max, box.position[0],
                 box.position[1], math.degrees(box.angle)))  # fmt: skip
print_table(
    ["option", "depth after 1 step", "steps to < 1 cm", "COM lift in step 1", "max energy added (J)",
     "max |omega| (rad/s)", "final x", "final y", "final angle (deg)"],
    rows,
)  # fmt: skip
y_rest = 0.5  # m, centre of mass of the box lying flat on the ground
lift = y_rest - corner["half"]["y"][0]
print(
    f"box mass {box.mass:.2f} kg: lifting it {DIVE} m costs m g h = {box.mass * G * DIVE:.3f} J; "
    f"lying flat at the end needs m g ({y_rest} - y0) = {box.mass * G * lift:.3f} J whatever the "
    "option: the rest of what a fix adds turns into toppling speed"
)

# %%
fig, axes = plt.subplots(2, 2, figsize=(12, 7))
k = np.arange(PAIR_STEPS + 1)
for option in OPTIONS:
    c = COLORS[option]
    ls = "--" if option == "mass_weighted" else "-"  # drawn dashed where options 1 and 2 coincide
    axes[0, 0].plot(k, pair[option]["depth"], color=c, ls=ls, marker=".", label=LABELS[option])
    axes[0, 1].plot(k, pair[option]["angle"], color=c, ls=ls, marker=".", label=LABELS[option])
    s = corner[option]
    axes[1, 0].plot(s["t"], s["depth"], color=c, ls=ls, label=LABELS[option])
    axes[1, 1].plot(s["t"], s["angle"], color=c, ls=ls, label=LABELS[option])
axes[0, 0].set(xlabel="step (count)", ylabel="deepest overlap (m)",
               title="two boxes: penetration depth")  # fmt: skip
axes[0, 1].set(
    xlabel="step (count)", ylabel="light box angle (deg)", title="two boxes: only option 3 turns"
)
axes[1, 0].set(xlabel="t (s)", ylabel="deepest overlap (m)", title="box into the ground: depth",
               xlim=(0.0, 0.4))  # fmt: skip
axes[1, 1].set(xlabel="t (s)", ylabel="box angle (deg)", title="box into the ground: angle")
for ax in axes.flat:
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
fig.tight_layout()
save_figure(fig, OUT / "penetration.png", dpi=100)

# %%
runs = []
for option in OPTIONS:
    world, _ = corner_world(option)
    runs.append(record(world, steps, every=GIF_EVERY, draw="contacts,normals", energy=True))
gif = render_gif(
    runs, OUT / "corner_drop.gif", fps=15, size_px=360, labels=[LABELS[o] for o in OPTIONS],
    colors=[COLORS[o] for o in OPTIONS], panel="energy-bars", view=(-1.2, 2.2, -0.6, 1.6),
    draw="contacts,normals",
)  # fmt: skip
show_gif(gif)
print(f"wrote {len(runs[0])} frames to {gif.name}")

# %% [markdown]
# The animation draws the contact points and normals of each run and, beside it, its energy
# bars: the total energy of options 1 and 2 *rises* in the first step (the lift, energy from
# nowhere), and the "lost" bar goes negative by as much; option 3 adds less.
#
# **Which handles rotation?** Only option 3. Options 1 and 2 translate along the normal: a
# corner stuck in a surface is pushed out by moving the whole body, as if it could not turn, so
# the fix lifts the centre of mass further than needed and adds potential energy (in the
# animation options 1 and 2 coincide: their red and blue boxes overlap). Option 2 at
# least respects the masses (and keeps the pair's centre of mass where it was, like a real
# internal push would); option 1 moves a 6 kg box as far as a 1 kg one. Option 3 weighs each
# way of moving (linear or angular, either body) by its inverse mass or inverse moment, exactly
# as the collision equation does for velocities, so the push goes where it is cheapest. The
# price: it works on a linearised contact and removes only a fraction $\beta$ per pass, so a
# deep overlap takes a few steps.

# %% [markdown]
# ## The default: from the ground up, at a bounded speed
#
# The slide's passes fix each contact on its own, so two cases go badly wrong:
#
# - **100 boxes spawned in one spot** (1 mm apart, on the ground). Every pair overlaps by
#   almost a whole box. Each contact pushes its pair apart by all of it, and a box at the
#   bottom of the pile is pushed *down*, through the ground, faster than the ground's contact
#   can push it back.
# - **a 1 kg box under a 1000 kg box.** Option 3 moves the light box 1000 times as far as the
#   heavy one, so the overlap the heavy box makes each step is fixed by squeezing the light
#   box out sideways.
#
# `robust_positions` (on by default) changes two things.
# The contacts are visited in layers from the ground up (`shock.contact_layers`: the bodies
# touching the ground are layer 1, those on them layer 2, ...), and in a contact between two
# layers where the upper body is more than twice as heavy (or the lower one is the ground) only
# the upper body moves, so nothing heavy pushes a light box out or down. And an overlap present
# when the
# step began comes out by at most `max_push_speed` x dt per step (3 m/s, as Box2D), while what
# the step's own motion pushed in is still removed at once. A step with no deep overlap and
# no body on a much lighter one runs the classic pass, so a stack the velocity solver holds
# is not changed at all.

# %%
PILE, PILE_STEPS = 100, 120


def spawn_pile(robust: bool, solver: str = "iterative") -> dict[str, np.ndarray]:
    """PILE unit boxes 1 mm apart on the ground: lowest centre (m) and fastest speed (m/s)."""
    world = World(gravity=(0.0, -G), dt=DT, robust_positions=robust, solver=solver)
    ground = world.add_body(Body(name="ground", type="static", position=(0.0, -0.5)))
    ground.add_shape(Box(40.0, 1.0))
    boxes = [world.add_body(Body(name=f"b{i}", position=(0.001 * i, 0.5))) for i in range(PILE)]
    for b in boxes:
        b.add_shape(Box(1.0, 1.0))
    out = {"t": [], "lowest": [], "fastest": []}
    for _ in range(PILE_STEPS):
        world.step()
        out["t"].append(world.time)
        out["lowest"].append(min(b.position[1] for b in boxes))
        out["fastest"].append(max(math.hypot(*b.velocity) for b in boxes))
    return {k: np.array(v) for k, v in out.items()}


def heavy_on_light(robust: bool, seconds: float = 10.0) -> dict[str, np.ndarray]:
    """1 kg box (0.5 m) under a 1000 kg box (1 m): the light box's sideways offset (m)."""
    world = World(gravity=(0.0, -G), dt=DT, robust_positions=robust)
    ground = world.add_body(Body(name="ground", type="static", position=(0.0, -0.5)))
    ground.add_shape(Box(40.0, 1.0))
    light = world.add_body(Body(name="light", position=(0.0, 0.25)))
    light.add_shape(Box(0.5, 0.5, mass=1.0))
    heavy = world.add_body(Body(name="heavy", position=(0.0, 1.0)))
    heavy.add_shape(Box(1.0, 1.0, mass=1000.0))
    out = {"t": [], "offset": [], "heavy_y": []}
    for _ in range(int(round(seconds / DT))):
        world.step()
        out["t"].append(world.time)
        out["offset"].append(abs(light.position[0] - heavy.position[0]))
        out["heavy_y"].append(heavy.position[1])
    return {k: np.array(v) for k, v in out.items()}


PASSES = {False: ("classic pass", "C3"), True: ("default (robust_positions)", "C2")}
piles = {r: spawn_pile(r) for r in PASSES}
loads = {r: heavy_on_light(r) for r in PASSES}
soft_piles = {r: spawn_pile(r, "soft") for r in PASSES}  # lesson 16's solver, the same pile
print_table(
    ["pass", "pile: lowest centre (m)", "pile: fastest (m/s)", "heavy on light: max offset (m)",
     "heavy box lowest y (m)", "soft step pile: lowest (m)", "soft step pile: fastest (m/s)"],
    [(PASSES[r][0], piles[r]["lowest"].min(), piles[r]["fastest"].max(), loads[r]["offset"].max(),
      loads[r]["heavy_y"].min(), soft_piles[r]["lowest"].min(), soft_piles[r]["fastest"].max())
     for r in PASSES],
)  # fmt: skip

# %%
fig, axes = plt.subplots(1, 3, figsize=(14, 4.0))
for r, (label, color) in PASSES.items():
    axes[0].plot(piles[r]["t"], piles[r]["lowest"], color=color, label=label)
    axes[1].plot(piles[r]["t"], piles[r]["fastest"], color=color, label=label)
    axes[1].plot(soft_piles[r]["t"], soft_piles[r]["fastest"], color=color, ls="--",
                 label=f"{label}, soft step")  # fmt: skip
    axes[2].plot(loads[r]["t"], loads[r]["offset"], color=color, label=label)
axes[0].axhline(0.5, color="0.5", ls=":", label="resting on the ground (0.5 m)")
axes[0].set(
    xlabel="t (s)", ylabel="lowest box centre (m)", title=f"{PILE} boxes spawned in one spot"
)
axes[1].axhline(3.0, color="0.5", ls=":", label="max_push_speed (3 m/s)")
axes[1].set(
    xlabel="t (s)",
    ylabel="fastest box speed (m/s)",
    yscale="log",
    ylim=(1e-3, 1e5),  # room above the data for the legend
    title=f"{PILE} boxes: the fastest one",
)
axes[2].set(xlabel="t (s)", ylabel="light box offset sideways (m)", title="1 kg under 1000 kg",
            ylim=(0.0, 10.0))  # fmt: skip
axes[2].set_yscale("symlog", linthresh=0.01)  # linear below 1 cm: the default's offset is 0
for ax, where in zip(axes, ("best", "upper right", "best"), strict=True):
    ax.legend(fontsize=8, loc=where)
    ax.grid(alpha=0.3)
fig.tight_layout()
save_figure(fig, OUT / "robust_positions.png", dpi=100)

# %% [markdown]
# The classic pass fires one box of the pile metres below the ground within the first steps,
# and squeezes the light box out from under the heavy one. Under the soft step (lesson 16,
# dashed) each overlapping pair is pushed apart at up to 3 m/s by its soft bias, and a pile of
# 100 adds those pushes up; by default a point that began the step that deep gets no push from
# the bias and is left to these passes. The default keeps every box of the
# pile above the ground, no faster than `max_push_speed`, and the light box where it was.

# %% [markdown]
# ## When the passes stop
#
# `position_iterations` (3) is how many passes a step may take. Box2D stops them early: once a
# pass finds no point overlapping more than three slops (`position_tolerance`, 15 mm), the
# overlap left is the velocity solver's to hold, and another pass would only trim
# millimetres. A pile at rest overlaps by a few millimetres, so it takes one pass a step. The
# passes as the slide has them (`position_tolerance: 0`, `position_stall: 0`) go on while
# anything overlaps beyond the slop. `world.stats["position_passes"]` counts them; here for a
# pile of 144 discs dropped on the ground.
#
# (The slide's run also turns off the engine's other stop, the stall of the next section: at
# rest it would stop a pass now and then. It never stops the default's passes in this pile:
# its run comes out the same with `position_stall: 0`.)


# %%
def disc_pile(tolerance: float, seconds: float = 4.0) -> dict[str, np.ndarray]:
    """12 x 12 discs (r = 0.2 m) dropped in a staggered grid: each step's passes and deepest
    overlap (m)."""
    stall = {"position_stall": 0.0} if tolerance == 0.0 else {}  # the slide's: every pass
    world = World(gravity=(0.0, -G), dt=DT, position_tolerance=tolerance, **stall)
    ground = world.add_body(Body(name="ground", type="static", position=(0.0, -0.5)))
    ground.add_shape(Box(40.0, 1.0))
    for row in range(12):
        for i in range(12):
            x, y = 0.4 * i - 2.2 + 0.2 * (row % 2), 0.25 + 0.4 * row
            world.add_body(Body(name=f"disc {row} {i}", position=(x, y))).add_shape(Circle(0.2))
    world.step()  # the first step sets the world up (and compiles, once)
    out = {"passes": [], "deepest": []}
    for _ in range(round(seconds / DT)):
        world.step()
        out["passes"].append(world.stats["position_passes"])
        out["deepest"].append(max_depth(world))
    return {key: np.array(value) for key, value in out.items()}


TOLERANCES = {0.0: ("every pass (position_tolerance 0)", "C3"), 0.015: ("default (15 mm)", "C2")}
piles = {tolerance: disc_pile(tolerance) for tolerance in TOLERANCES}
last = slice(-round(1.0 / DT), None)  # the last second, at rest
print_table(["passes", "passes a step, last second",
             "deepest overlap, last second: median step (mm)", "worst step (mm)"],
            [(TOLERANCES[t][0], r["passes"][last].mean(), 1000 * np.median(r["deepest"][last]),
              1000 * r["deepest"][last].max()) for t, r in piles.items()], 2)  # fmt: skip

# %%
fig, (ax, bx) = plt.subplots(1, 2, figsize=(12, 4.2))
for tolerance, (label, color) in TOLERANCES.items():
    r = piles[tolerance]
    t = DT * np.arange(1, len(r["passes"]) + 1)
    ax.plot(t, r["passes"], color=color, label=label, drawstyle="steps-post")
    bx.plot(t, 1000 * r["deepest"], color=color, label=label)
ax.set(xlabel="t (s)", ylabel="position passes in the step (count)", ylim=(0, 3.5),
       title="144 discs dropped: passes per step")  # fmt: skip
bx.axhline(15.0, color="0.5", linestyle=":", label="position_tolerance (15 mm)")
bx.set(xlabel="t (s)", ylabel="deepest overlap (mm)", title="... and the deepest overlap")
for axis in (ax, bx):
    axis.grid(alpha=0.3)
    axis.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=3)
fig.tight_layout()
save_figure(fig, OUT / "passes_stop.png", dpi=100)

# %% [markdown]
# While the discs land, overlaps deeper than 15 mm make both runs take all three passes. Once
# the pile rests, the default takes one pass a step, and the slide's passes three, or one in a
# step whose first pass finds every point within the slop and moves nothing. What the
# default gives up is little: in a typical step the deepest overlap left is the slop, 5 mm, in
# both (the table's median step), since the velocity solver holds the pile and the passes only
# trim what sinks beyond the slop each step. Now and then a step leaves one contact deeper
# (the worst step; for the default, at the start of the last second, the spike on the right),
# and the passes of the next few steps take it out. What it saves is two passes over every
# contact, every step: in the engine's
# benchmarks (`benchmarks/ab.py`, which alternates runs to see through the machine's noise;
# a single run like this one cannot) a step of 100 discs at rest took about a tenth less time.

# %% [markdown]
# ## Passes that stall
#
# A pile of a thousand discs poured into a box is pressed together by its own load more than
# ten velocity sweeps can hold: its overlaps stay deeper than 15 mm, so Box2D's stop never
# comes. Each position pass then pushes every pair apart, and the pairs around them push them
# back. `world.stats["position_progress"]` says how much of the overlap the pass before the
# last took out: 1 - (the overlap the last pass met) / (the overlap the pass before met), the
# overlap being each point's depth beyond what it may keep, summed. The engine stops the
# passes once a pass stalls: it took out less than `position_stall` (0.005, half a percent).


# %%
def poured_pile(settings: dict, n: int = 1000, seconds: float = 4.0) -> dict[str, np.ndarray]:
    """``n`` discs (r = 0.2 m, 0.1 m apart in a staggered grid) falling into an open box:
    each step's passes and progress, then the mean and deepest overlap at the end (m)."""
    world = World(gravity=(0.0, -G), dt=DT, **settings)
    cols = round(math.sqrt(n))
    inner = (cols + 0.5) * 0.5 + 0.1
    height = 2.0 + math.ceil(n / cols) * 0.5
    for name, x, y, width, tall in (("floor", 0.0, -0.25, inner + 1.0, 0.5),
                                    ("left", -0.5 * inner - 0.25, 0.5 * height, 0.5, height),
                                    ("right", 0.5 * inner + 0.25, 0.5 * height, 0.5, height)):  # fmt: skip
        world.add_body(Body(name=name, type="static", position=(x, y))).add_shape(Box(width, tall))
    for i in range(n):
        row, col = divmod(i, cols)
        x = -0.5 * inner + 0.25 + (col + 0.5 * (row % 2)) * 0.5 + 0.02 * math.sin(12.9898 * i)
        disc = world.add_body(Body(name=f"disc {i}", position=(x, 1.2 + 0.5 * row)))
        disc.add_shape(Circle(0.2, friction=0.5))
    out = {"passes": [], "progress": []}
    for _ in range(round(seconds / DT)):
        world.step()
        out["passes"].append(world.stats["position_passes"])
        progress = world.stats["position_progress"]  # None: one pass, nothing to compare
        out["progress"].append(np.nan if progress is None else progress)
    depths = np.array([c.depth for c in world.find_contacts()])
    overlaps = depths[depths > 0.0]
    return {**{key: np.array(value) for key, value in out.items()},
            "mean": overlaps.mean(), "deepest": overlaps.max()}  # fmt: skip


def median_percent(progress: np.ndarray) -> float | str:
    """The median of the steps' progress in %, "-" when no step took two passes."""
    known = progress[np.isfinite(progress)]
    return 100 * float(np.median(known)) if len(known) else "-"


# label, colour and line width (every pass drawn wide underneath: where both take three
# passes, both lines show); the last run is in the table only
STALLS = {"position_stall 0: every pass": ({"position_stall": 0.0}, "C3", 3.5),
          "default (0.005)": ({}, "C2", 1.5),
          "position_iterations 1": ({"position_iterations": 1}, None, 0)}  # fmt: skip
poured = {label: poured_pile(settings) for label, (settings, _, _) in STALLS.items()}
settled = slice(-round(2.0 / DT), None)  # the last 2 s, once the pile has settled
# the last 2 s: passes a step and the median progress; at the end: the overlap left
print_table(["run", "passes a step", "progress (%)", "mean overlap (mm)", "deepest (mm)"],
            [(label, r["passes"][settled].mean(), median_percent(r["progress"][settled]),
              1000 * r["mean"], 1000 * r["deepest"]) for label, r in poured.items()], 2)  # fmt: skip

# %%
fig, (ax, bx) = plt.subplots(1, 2, figsize=(12, 4.2))
for label, (_, color, width) in list(STALLS.items())[:2]:
    r = poured[label]
    t = DT * np.arange(1, len(r["passes"]) + 1)
    ax.plot(t, r["passes"], color=color, label=label, drawstyle="steps-post", linewidth=width)
    bx.plot(t, 100 * r["progress"], color=color, label=label)
ax.set(xlabel="t (s)", ylabel="position passes in the step (count)", ylim=(0, 3.5),
       title="1,000 discs poured into a box: passes per step")  # fmt: skip
bx.axhline(0.5, color="0.5", linestyle=":", label="position_stall (0.5 %)")
bx.set(xlabel="t (s)", ylabel="overlap the pass before the last took out (%)", yscale="log",
       title="... and what the passes achieve")  # fmt: skip
for axis in (ax, bx):
    axis.grid(alpha=0.3)
    axis.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=3)
fig.tight_layout()
save_figure(fig, OUT / "passes_stall.png", dpi=100)

# %% [markdown]
# While the discs pour in, a pass takes out up to a fifth of the overlap, and every step takes
# all three passes. Once the pile lies in the box a pass takes out less than a tenth of a
# percent (the table's median over the last 2 s): what one pass pushes out, the load and the
# next pairs push back in. The default then stops after two passes, which show the stall, and
# skips the third;
# the pile is left about as deep as with every pass (the table's mean and deepest overlap,
# within a millimetre or two). In the engine's benchmark of 5,000 discs poured the same way,
# that takes about 8 % off a step (`benchmarks/ab.py rain_5000`). The passes cannot stop at
# one, though: with a single pass a step (`position_iterations: 1`, the table's last row) the
# pile sinks into itself, its deepest overlap four times as deep. Small as the second pass's
# share of the whole overlap is, it is what takes out the worst of it.

# %% [markdown]
# ## Exercises
#
# Predict first, then run the cell under the question, then open the answer.
#
# **1.** Give the big box the density 0.5 (so both boxes weigh 1 kg). How far does each box move
# under option 2 now?


# %%
def equal_pair(option: str, heavy_density: float = 0.5) -> tuple[float, float]:
    """pair_world with the big box at ``heavy_density`` (0.5: 1 kg); distances each box moved."""
    world = World(gravity=(0.0, 0.0), dt=DT, penetration=option, **SLIDE_PASSES)
    heavy = world.add_body(Body(name="heavy"))
    heavy.add_shape(Box(2.0, 1.0, density=heavy_density))
    _, _, template = pair_world(option)
    light = world.add_body(Body(name="light", position=template.position, angle=template.angle))
    light.add_shape(Box(1.0, 1.0, density=1.0))
    h0, l0 = np.array(heavy.position), np.array(light.position)
    for _ in range(PAIR_STEPS):
        world.step()
    return (float(np.linalg.norm(np.array(heavy.position) - h0)),
            float(np.linalg.norm(np.array(light.position) - l0)))  # fmt: skip


print("option 2, 1 kg + 1 kg: heavy moved {:.4f} m, light moved {:.4f} m".format(
    *equal_pair("mass_weighted")))  # fmt: skip

# %% [markdown]
# <details><summary>Answer</summary>
#
# With $m_1 = m_2$ the weights $m_2/(m_1 + m_2)$ and $m_1/(m_1 + m_2)$ are both $\frac{1}{2}$:
# option 2 becomes option 1, each box moves $p/2 = (0.25 - 0.005)/2 = 0.1225$ m. The run prints
# 0.1225 m for both.
#
# </details>
#
# **2.** Start the box of the second experiment only 0.15 m deep (`DIVE`). How much potential
# energy does option 1 add in its first step?


# %%
def first_step_energy(option: str, dive: float) -> tuple[float, float]:
    world, box = corner_world(option)
    box.position = (box.position[0], box.position[1] + DIVE - dive)
    y0, u0 = box.center_of_mass[1], world.potential_energy()
    world.step()
    return box.center_of_mass[1] - y0, world.potential_energy() - u0


lift_e2, du_e2 = first_step_energy("half", 0.15)
print(f"DIVE = 0.15 m: lifted {lift_e2:.4f} m, potential energy +{du_e2:.3f} J")

# %% [markdown]
# <details><summary>Answer</summary>
#
# Option 1 against a static ground moves the box by the whole depth less the slop,
# $0.15 - 0.005 = 0.145$ m, straight up: $\Delta U = m g \Delta y = 1 \times 9.81 \times 0.145
# = 1.42$ J from nowhere. The run lifts it 0.1448 m (this step's gravity takes off another
# 0.16 mm) and prints +1.421 J; half the 2.89 J of the 0.3 m dive.
#
# </details>
#
# **3.** Option 3 removes a fraction $\beta$ = `baumgarte` (0.2) of the remaining overlap in each
# of its 3 position passes per step: 13 steps for the two boxes. How many with $\beta = 0.4$?

# %%
world_e3, _, _ = pair_world("impulse")
world_e3.settings.baumgarte = 0.4
depths_e3 = [max_depth(world_e3)]
for _ in range(PAIR_STEPS):
    world_e3.step()
    depths_e3.append(max_depth(world_e3))
steps_e3 = int(np.argmax(np.array(depths_e3) <= 1.01 * world_e3.settings.slop))
print(f"beta = 0.4: {steps_e3} steps to the slop; depths {np.round(depths_e3[:4], 4)} m")

# %% [markdown]
# <details><summary>Answer</summary>
#
# Each step leaves $(1 - \beta)^3$ of the overlap above the slop: $0.512$ for $\beta = 0.2$,
# $0.216$ for $\beta = 0.4$. "At the slop" here means within 1% of it, an excess of $5 \times
# 10^{-5}$ m out of $0.245$: $n \ge \ln(2.04 \times 10^{-4}) / \ln 0.216 = 5.6$, so 6 steps
# (against $\ln(2.04 \times 10^{-4}) / \ln 0.512 = 12.7$, 13 steps, for 0.2). The run takes 6;
# after one step the depth is $0.005 + 0.245 \times 0.216 = 0.058$ m (printed 0.0568: the
# linearised push is not exactly $\beta$ of the true depth once the box turns).
#
# </details>
