# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: percent
# ---

# %% [markdown]
# # 06 Tunnelling and conservative advancement
#
# Slides "Collision Detection", "Conservative Advancement" and "Retroactive Collision
# Detection".
#
# The slides give two ways to deal with collisions in a time step $\Delta t$:
#
# - **Retroactive detection**: update the motion of all bodies by $\Delta t$; then, for each
#   overlapping pair, fix the penetration and handle the collision (change the velocities).
#   Its problems: it must deal with interpenetration, the **tunnelling problem** (small
#   bodies, high velocities, large $\Delta t$) and stacking.
# - **Conservative advancement**: for all possible collisions, estimate the time of impact
#   $\Delta t_{impact} < \Delta t$; if there is one, update the motion by $\Delta t_{impact}$
#   only, handle the collision, then resume. Its problems: the time of impact is harder to
#   estimate than an overlap, the simulation comes to a virtual stop when many bodies touch,
#   and a constant animation rate is harder to keep.
#
# The sandbox steps with retroactive detection (contacts are found at the positions of the
# step, `sandbox/collision.py`). A body created with `Body(ccd=True)` (or `"ccd": true` in a
# scene) also gets conservative advancement (`sandbox/toi.py`): its move in a step is cut at
# its time of impact, and the next step's retroactive detection finds the contact.
#
# The test case is `scenes/bullet.json`: a bullet of radius $r = 0.05$ m at $200$ m/s
# towards a wall $h = 0.1$ m thick, at $\Delta t = 1/60$ s. In one step the bullet moves
# $v\,\Delta t = 3.33$ m, more than thirty times the wall's thickness.

# %%
import json
import math

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.patches import Circle as CirclePatch
from matplotlib.patches import Rectangle

import sandbox
from sandbox import Body, Box, Circle, World
from sandbox.geometry import box_vertices
from sandbox.lessonkit import output_dir, print_table, save_figure, scene_path, show_gif
from sandbox.recording import Recording
from sandbox.render import record, render_gif
from sandbox.toi import distance, time_of_impact

# knobs
STEPS = 30  # steps of the bullet runs (0.5 s at the scene's dt)
BOUNCE = 0.5  # restitution e of the extra "ccd, bouncing" run
SWEEP_DTS = (1 / 30, 1 / 60, 1 / 120, 1 / 240)  # s, time steps of the tunnelling sweep
SWEEP_STEP = 0.01  # m, grid step of the sweep in v dt (so the speed step is SWEEP_STEP / dt)
SWEEP_RANGE = (5, 35)  # the sweep's v dt runs over (k + 1/2) SWEEP_STEP for k in this range
PHASES = 32  # start positions per speed, spread over one step's travel
GIF_FPS = 5  # frames per second of the animation: one step per frame, slowed down

OUT = output_dir("06_tunnelling")
SCENE = json.loads(scene_path("bullet").read_text())


def bullet_world(ccd: bool, restitution: float = 0.0) -> World:
    """The bullet scene with ccd on or off and a contact restitution e = ``restitution`` (a
    contact uses the product of its shapes' values: the wall's 1 times the bullet's e)."""
    scene = json.loads(json.dumps(SCENE))  # a copy
    scene["bodies"][0]["shapes"][0]["restitution"] = 1.0
    scene["bodies"][1]["shapes"][0]["restitution"] = restitution
    scene["bodies"][1]["ccd"] = ccd
    return sandbox.load_scene(scene)


world = bullet_world(ccd=False)
wall, bullet = world.body("wall"), world.body("bullet")
H = wall.shapes[0].width  # wall thickness (m)
WALL_X = wall.position[0]  # wall centre line (m)
WALL_HEIGHT = wall.shapes[0].height
R = bullet.shapes[0].radius  # bullet radius (m)
SPEED = bullet.velocity[0]  # m/s
DT = world.dt
MARGIN = world.settings.contact_margin  # m, speculative contact distance
FACE = WALL_X - H / 2  # the wall's front face
print(
    f"wall h = {H} m at x = {WALL_X} m, bullet r = {R} m, v = {SPEED} m/s, dt = {DT:.5f} s: "
    f"v dt = {SPEED * DT:.3f} m per step, h + 2r = {H + 2 * R:.3f} m"
)

# %% [markdown]
# ## The bullet with and without ccd
#
# Both runs start at $x = 0$. Without ccd the bullet is sampled at $x = 0, 3.33, 6.67, \dots$:
# no sample overlaps the wall ($4.95 \le x + r$ and $x - r \le 5.05$ never hold), so
# retroactive detection never sees a collision and the bullet is on the other side.
# With ccd the step from $3.33$ m is cut where the bullet comes within a small target
# distance ($0.005$ m, a quarter of the contact margin) of the wall; the next step finds the
# contact and the solver stops the bullet (restitution $0$, as in the scene). A third run has
# a restitution $e$ = `BOUNCE`, so the contact sends the bullet back at $e\,v$.

# %%
runs = {
    "no ccd": bullet_world(ccd=False),
    "ccd": bullet_world(ccd=True),
    f"ccd, e = {BOUNCE}": bullet_world(ccd=True, restitution=BOUNCE),
}
recordings = {name: record(w, STEPS) for name, w in runs.items()}
times = np.array(recordings["no ccd"].times)
xs = {name: rec.poses()[:, 1, 0] for name, rec in recordings.items()}  # body 1 is the bullet
print_table(
    ["step", "t (s)", *(f"x {name} (m)" for name in runs)],
    [(k, times[k], *(xs[name][k] for name in runs)) for k in range(8)],
)
crossed = {name: bool(np.any(x > WALL_X)) for name, x in xs.items()}
print("behind the wall at some step:", crossed)

# %%
fig, ax = plt.subplots(figsize=(8, 4.5))
ax.axhspan(FACE, WALL_X + H / 2, color="0.4", label=f"wall ({H} m)")
ax.axhspan(FACE - R, WALL_X + H / 2 + R, color="0.8", zorder=0, label="overlap band (+- r)")
styles = {"no ccd": ("C0", "o"), "ccd": ("C1", "s")}
for name, x in xs.items():
    colour, marker = styles.get(name, ("C2", "^"))
    ax.plot(times, x, marker=marker, ms=4, color=colour, label=name)
ax.set(
    xlabel="t (s)",
    ylabel="bullet x (m)",
    ylim=(-0.5, 12.0),
    title=f"bullet at {SPEED:.0f} m/s, dt = 1/{round(1 / DT)} s: {SPEED * DT:.2f} m per step",
)
ax.annotate(
    "no sample lands in the wall:\nthe overlap is never seen",
    (times[2], xs["no ccd"][2]),
    xytext=(0.12, 9.5),
    arrowprops={"arrowstyle": "->"},
    fontsize=9,
)
ax.legend(loc="lower right", fontsize=8)
fig.tight_layout()
save_figure(fig, OUT / "bullet_x.png", dpi=100)

# %% [markdown]
# ## Conservative advancement, one iteration at a time
#
# How does the ccd step find its time of impact? Over the step the bullet moves from
# $\mathbf{p}_0$ to $\mathbf{p}_1$, at $\mathbf{p}(t) = \mathbf{p}_0 + t(\mathbf{p}_1 - \mathbf{p}_0)$
# for $t \in [0, 1]$. At the current $t$ the bullet and the wall are $d$ apart along the unit
# direction $\hat{\mathbf{n}}$ (`sandbox.toi.distance`). Along $\hat{\mathbf{n}}$ the gap
# closes at most at the rate $|\Delta\mathbf{p} \cdot \hat{\mathbf{n}}|$ per unit $t$ (plus
# $|\Delta\varphi| R$ for a turning body of radius $R$), so the bodies cannot touch before
#
# $$t \leftarrow t + \frac{d - d_{target}}{|\Delta\mathbf{p}\cdot\hat{\mathbf{n}}|} .$$
#
# Repeat until $d < d_{target}$ + a tolerance (impact at $t$) or $t \ge 1$ (no impact this
# step). Every move is safe: it never steps past the first contact, which is why the method is
# called conservative. Head on, the first estimate is exact. Towards the wall's corner the
# direction $\hat{\mathbf{n}}$ turns as the bullet approaches and it takes a few iterations.

# %%
TARGET, TOL = 0.25 * MARGIN, 0.25 * 0.25 * MARGIN  # what the world's ccd uses
no_verts = np.zeros((0, 2))
wall_verts = box_vertices(H, WALL_HEIGHT)  # relative to the wall's centre of mass
# shapes as sandbox.toi takes them: (kind 0 circle / 1 polygon, radius, centre, vertices)
BULLET = (0, R, np.zeros(2), no_verts)
WALL = (1, 0.0, np.zeros(2), wall_verts)


def advance(p0, p1) -> tuple[list, float]:
    """Conservative advancement of the bullet from p0 to p1 against the wall, by hand."""
    p0, p1 = np.asarray(p0, dtype=float), np.asarray(p1, dtype=float)
    t, rows = 0.0, []
    for it in range(20):
        p = p0 + t * (p1 - p0)
        d, nx, ny = distance(BULLET, (p, 0.0), WALL, (np.array([WALL_X, 0.0]), 0.0))
        # d is measured from the bullet (a) towards the wall (b); n points the same way
        closing = abs((p1 - p0) @ np.array([nx, ny]))
        rows.append((it, t, p[0], p[1], d, f"({nx:+.3f}, {ny:+.3f})", closing))
        if d < TARGET + TOL:
            return rows, t
        t += (d - TARGET) / closing  # slides, "Conservative Advancement"
        if t >= 1.0:
            return rows, 1.0
    return rows, t


def engine_toi(p0, p1) -> float:
    wall_at = np.array([WALL_X, 0.0])
    bullet_motion = (np.asarray(p0, float), 0.0, np.asarray(p1, float), 0.0)
    return time_of_impact(BULLET, bullet_motion, WALL, (wall_at, 0.0, wall_at, 0.0), TARGET, TOL)


head_on = ((xs["no ccd"][1], 0.0), (xs["no ccd"][2], 0.0))  # the step that tunnels
corner = ((4.35, 2.45), (5.45, 1.55))  # past the wall's top corner at (4.95, 2.0)
headers = ["iteration", "t", "x (m)", "y (m)", "d (m)", "n (bullet -> wall)", "|dp . n| (m)"]
results = {}
for name, (p0, p1) in (("head on", head_on), ("towards the corner", corner)):
    rows, t_hand = advance(p0, p1)
    results[name] = (p0, p1, rows, t_hand)
    print(f"{name}: from {np.round(p0, 3)} to {np.round(p1, 3)}")
    print_table(headers, rows)
    print(f"  t by hand = {t_hand:.6f}, sandbox.toi.time_of_impact = {engine_toi(p0, p1):.6f}")
x_cut = head_on[0][0] + results["head on"][3] * (head_on[1][0] - head_on[0][0])
print(f"head on: the ccd run stops its step at x = {xs['ccd'][2]:.4f} m (by hand {x_cut:.4f} m)")

# %% [markdown]
# ### Stop at the impact, or resume?
#
# The slides' conservative advancement advances to the impact, handles the collision, then
# *resumes*: the rest of the step, $(1 - t)\,\Delta t$, is still simulated. This engine stops
# the ccd body at the impact and drops the rest of its step; the next step's ordinary contact
# solver then handles the collision, with the other contacts, friction and restitution. Box2D v3
# does the same. Resuming would need a collision solve inside the step for this one pair and a
# second integration of the remaining time, while every other body has already finished its
# step: in a pile of touching bodies that is the slides' "virtual stop". The price of stopping is
# that the ccd body loses up to one step of motion at each impact. For the bullet that bounces
# ($e$ = `BOUNCE`), the loss shows as a lag: it should have touched the wall at
# $t_{hit} = (x_{face} - r - x_0)/v$ and left at $e\,v$ right away.

# %%
t_hit = (FACE - R - xs["no ccd"][0]) / SPEED  # s, when the bullet's surface reaches the wall
lost = (1.0 - results["head on"][3]) * DT  # s of the cut step that are dropped
x_ideal = FACE - R - BOUNCE * SPEED * (times - t_hit)  # had it bounced at t_hit
bounce = xs[f"ccd, e = {BOUNCE}"]
lag = float(bounce[5] - x_ideal[5])
print_table(
    ["quantity", "value"],
    [
        ("time of impact in the step (fraction)", f"{results['head on'][3]:.4f}"),
        ("step time dropped, (1 - t) dt (ms)", f"{1000 * lost:.3f}"),
        ("bouncing bullet at step 5, engine (m)", f"{bounce[5]:.4f}"),
        ("bouncing bullet at step 5, bounce at t_hit (m)", f"{x_ideal[5]:.4f}"),
        ("lag (m)", f"{lag:.4f}"),
        ("lag / (e v) (ms)", f"{1000 * lag / (BOUNCE * SPEED):.3f}"),
    ],
)

# %%
fig, axes = plt.subplots(1, 2, figsize=(11, 5.4))
for ax, (name, (p0, p1, rows, t_hand)) in zip(axes, results.items(), strict=True):
    ax.add_patch(Rectangle((FACE, -WALL_HEIGHT / 2), H, WALL_HEIGHT, color="0.5", label="wall"))
    ax.plot([p0[0], p1[0]], [p0[1], p1[1]], "k--", lw=1, label="planned move (one step)")
    lines = []
    for it, t, x, y, d, _, _ in rows:
        colour = f"C{it % 10}"
        ax.add_patch(CirclePatch((x, y), R, color=colour, alpha=0.8))
        # nothing of the wall is within d of the bullet's surface: a safe disc of radius r + d
        ax.add_patch(CirclePatch((x, y), R + d, fill=False, ls=":", color=colour))
        ax.annotate(str(it), (x, y), xytext=(-14, 6 + 10 * it), textcoords="offset points",
                    fontsize=9, color=colour, weight="bold")  # fmt: skip
        lines.append(f"{it}: t = {t:.4f}, d = {d:.4f} m")
    ax.text(0.98, 0.98, "\n".join(lines), transform=ax.transAxes, ha="right", va="top",
            fontsize=8, bbox={"fc": "w", "ec": "0.7"})  # fmt: skip
    ax.plot(*p1, "x", color="k")
    ax.set_aspect("equal")
    if name == "head on":
        ax.set(xlim=(p0[0] - 0.3, p1[0] + 0.3), ylim=(-1.2, 1.2))
    else:
        ax.set(xlim=(4.2, 5.6), ylim=(1.3, 2.7))
    ax.set(xlabel="x (m)", ylabel="y (m)")
    ax.set_title(f"{name}: {len(rows)} iterations, impact at t = {t_hand:.3f}", fontsize=10)
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.14), fontsize=8, ncol=2)
fig.suptitle("conservative advancement: each dotted circle is a region the wall is not in")
fig.tight_layout()
save_figure(fig, OUT / "conservative_advancement.png", dpi=100)

# %% [markdown]
# ## When does a bullet tunnel?
#
# Without ccd, the bullet is only looked at every $v\,\Delta t$ metres. Its centre overlaps
# the wall (touching counts) on a band of width $h + 2r$ around the wall; a collision is
# detected only if one of the samples $x_0 + k\,v\,\Delta t$ falls in that band. So
#
# $$v\,\Delta t \le h + 2r \quad\Rightarrow\quad \text{always detected}, \qquad
#   v\,\Delta t > h + 2r \quad\Rightarrow\quad \text{missed for some start positions},$$
#
# and for a start position spread evenly over one step a fraction
# $1 - (h + 2r)/(v\,\Delta t)$ of the bullets is never seen. This is the slides' "small
# bodies, high velocities, large $\Delta t$": at $\Delta t = 1/60$ s a $0.1$ m wall and a
# $0.05$ m bullet are safe only up to $(h + 2r)/\Delta t = 12$ m/s.
#
# Being *seen* is not the same as being *stopped*, though. A sample in the back half of the
# wall is closer to the far face; the narrowphase then reports the far face's normal and the
# penetration fix pushes the bullet out on the far side. The sandbox also makes contacts
# `contact_margin` $= 0.02$ m before touching (speculative contacts, which stop the bullet
# before it overlaps). So the bullet ends up behind the wall when no sample falls in the band
# from `contact_margin` in front of the wall to the wall's middle:
#
# $$v\,\Delta t > \frac{h}{2} + r + m \quad (m = \text{contact margin}) .$$
#
# The sweep measures both boundaries. For each $\Delta t$ and each speed it shoots `PHASES`
# bullets whose start positions are spread over one step's travel (one of them just short of
# touching the wall), and records
#
# - **missed**: the wall never appears in the step's contacts, with `contact_margin = 0` (pure
#   retroactive detection, as in the slides);
# - **behind the wall**: the bullet ends on the far side, with the default settings;
# - **ccd**: the same as "behind the wall", with `ccd=True`.
#
# Every bullet is its own experiment: all of them fly in one world, in rows $0.15$ m apart
# (more than $2r$ + the margin, so they never touch each other), against one tall wall.

# %%
ROW = 0.15  # m between the bullets' paths


def sweep(vdts: np.ndarray, dt: float, margin: float | None = None, ccd: bool = False, ahead=False):
    """Shoot PHASES bullets per v dt in ``vdts``; returns (seen, behind) arrays (len, PHASES)
    of booleans: the wall was in some step's contacts / the bullet ended behind the wall.
    ``ahead``: speculative contacts that reach as far as the step (``settings.speculative``)."""
    options = {} if margin is None else {"contact_margin": margin}
    w = World(gravity=(0.0, 0.0), dt=dt, speculative=ahead, **options)
    n = len(vdts) * PHASES
    height = ROW * (n + 2)
    target = w.add_body(Body("wall", type="static", position=(WALL_X, 0.0)))
    target.add_shape(Box(H, height))
    touching = FACE - R  # bullet centre x at which it touches the wall
    shots = []
    for vdt in vdts:
        for j in range(PHASES):
            # the first sample lands j / PHASES of a step (plus 1 micrometre) short of touching
            x0 = touching - 1e-6 - (1 + j / PHASES) * vdt
            y = -height / 2 + ROW * (len(shots) + 1.5)
            b = w.add_body(
                Body(f"b{len(shots)}", position=(x0, y), velocity=(vdt / dt, 0.0), ccd=ccd)
            )
            b.add_shape(Circle(R))
            shots.append(b.index)
    shots = np.array(shots)
    seen = np.zeros(len(w.bodies), dtype=bool)
    steps = math.ceil((H + 2 * R + 2 * MARGIN) / min(vdts)) + 3  # the slowest is past the wall
    for _ in range(steps):
        w.step()
        m = w.manifolds
        if m is not None and len(m):
            hit = (m.a == target.index) | (m.b == target.index)
            seen[m.a[hit]] = seen[m.b[hit]] = True
    behind = w.com[shots, 0] > WALL_X
    return seen[shots].reshape(-1, PHASES), behind.reshape(-1, PHASES)


def first(flags: np.ndarray, values: np.ndarray) -> float:
    """The first value whose row has any flag set (nan if none)."""
    rows = flags.any(axis=1)
    return float(values[np.argmax(rows)]) if rows.any() else math.nan


VDT = (np.arange(*SWEEP_RANGE) + 0.5) * SWEEP_STEP  # m travelled per step
L_SEEN = H + 2 * R  # band in which an overlap is seen
L_STOP = H / 2 + R + MARGIN  # band in which the bullet is stopped (default settings)
table, boundary, fractions = [], {}, {}
for dt in SWEEP_DTS:
    seen0, _ = sweep(VDT, dt, margin=0.0)
    _, behind = sweep(VDT, dt)
    _, behind_ccd = sweep(VDT, dt, ccd=True)
    _, behind_ahead = sweep(VDT, dt, ahead=True)
    v_missed, v_behind = first(~seen0, VDT) / dt, first(behind, VDT) / dt
    boundary[dt] = (v_missed, v_behind)
    fractions[dt] = ((~seen0).mean(axis=1), behind.mean(axis=1))
    table.append(
        (
            f"1/{round(1 / dt)}",
            SWEEP_STEP / dt,
            L_SEEN / dt,
            v_missed,
            L_STOP / dt,
            v_behind,
            f"{int(behind_ccd.sum())} of {behind_ccd.size}",
            f"{int(behind_ahead.sum())} of {behind_ahead.size}",
        )
    )
print_table(
    [
        "dt (s)",
        "speed step",
        "(h+2r)/dt",
        "first missed",
        "(h/2+r+m)/dt",
        "first behind",
        "ccd: behind the wall",
        "speculative: behind the wall",
    ],
    table,
    2,
)
print("speeds in m/s; 'first ...' = the lowest swept speed at which some start position fails")

# %%
fig, (ax, bx) = plt.subplots(1, 2, figsize=(14, 4.8))
dt = 1 / 60
v = VDT / dt
missed, behind = fractions[dt]
ax.plot(v, missed, "o", color="C0", ms=4, label="missed (contact_margin = 0)")
ax.plot(v, np.clip(1 - L_SEEN / VDT, 0, None), "-", color="C0", lw=1,
        label="1 - (h + 2r) / (v dt)")  # fmt: skip
ax.plot(v, behind, "s", color="C3", ms=4, label="behind the wall (default settings)")
ax.plot(v, np.clip(1 - L_STOP / VDT, 0, None), "-", color="C3", lw=1,
        label="1 - (h/2 + r + m) / (v dt)")  # fmt: skip
ax.set(xlabel="bullet speed v (m/s)", ylabel=f"fraction of the {PHASES} start positions (1)",
       title="dt = 1/60 s: how many bullets tunnel")  # fmt: skip
ax.legend(fontsize=8, loc="upper left")

v_line = np.geomspace(2, 400, 100)
bx.loglog(v_line, L_SEEN / v_line, color="C0", lw=1, label="v dt = h + 2r (slides)")
bx.loglog(v_line, L_STOP / v_line, color="C3", lw=1, label="v dt = h/2 + r + m")
dts = np.array(SWEEP_DTS)
bx.loglog([b[0] for b in boundary.values()], dts, "o", color="C0", label="measured: first missed")
bx.loglog([b[1] for b in boundary.values()], dts, "s", color="C3", label="measured: first behind")
bx.loglog([SPEED], [DT], "*", color="k", ms=12, label="scenes/bullet.json")
bx.fill_between(v_line, L_SEEN / v_line, 1, color="C0", alpha=0.12)
bx.fill_between(v_line, L_STOP / v_line, L_SEEN / v_line, color="C3", alpha=0.12)
bx.text(60, 0.04, "missed\n(for some starts)", fontsize=9, ha="center")
bx.text(2.3, 0.0022, "always stopped", fontsize=9)
bx.set(xlabel="bullet speed v (m/s)", ylabel="time step dt (s)", xlim=(2, 400), ylim=(2e-3, 0.1),
       title="tunnelling boundary (no ccd)")  # fmt: skip
bx.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.0, 1.0))
fig.tight_layout()
# the middle band is narrow: its label runs along it, at the band's centre line
band = [(v, math.sqrt(L_STOP * L_SEEN) / v) for v in (6.0, 60.0)]
(x0, y0), (x1, y1) = bx.transData.transform(band)
bx.text(*band[0], "seen, but may be pushed through", fontsize=8, va="center", ha="left",
        rotation=math.degrees(math.atan2(y1 - y0, x1 - x0)), rotation_mode="anchor")  # fmt: skip
save_figure(fig, OUT / "tunnelling_boundary.png", dpi=100)

# %% [markdown]
# What the sweep shows:
#
# - the missed-detection boundary is $v\,\Delta t = h + 2r$, the same line for every
#   $\Delta t$, as the slides' "small bodies, high velocities, large $\Delta t$" says: halving
#   $\Delta t$ doubles the safe speed, a thicker wall or a bigger bullet raises it;
# - the bullet already ends up behind the wall at about $0.6\times$ that speed here, because
#   a bullet caught deeper than the middle of the wall is pushed out on the far side;
# - with ccd no bullet of the sweep gets through, at any speed or time step;
# - nor with **speculative contacts** that reach as far as the step (next section).
#
# The price of ccd is a time of impact per nearby pair of each ccd body and step, which is
# why it is a per-body switch for small fast bodies, not the default. And the slides'
# "virtual stop" problem is avoided by advancing only the ccd bodies and leaving pairs already
# in contact to the ordinary retroactive contacts.
#
# ## Speculative contacts that reach as far as the step, and their ghosts
#
# The 2 cm `contact_margin` already makes *speculative* contacts: a point with a gap $g > 0$
# asks the solver only that the pair close no more than $g$ in this step (its target speed is
# $g/\Delta t$), so a body arriving at a surface stops on it. That stops bodies up to
# $m/\Delta t$ = 1.2 m/s. With `settings.speculative` on, the margin of each pair grows to
# as far as the pair can close in the step (`sandbox/speculative.py`, as Box2D v3 and Bepu do;
# Erin Catto, "Continuous Collision", GDC 2013). No point of a shape moves faster than
# $|v| + |\omega|\,r$, with $r$ the radius about the centre of mass that holds the shape, so
#
# $$m_{pair} = m + \left(|v_b - v_a| + |\omega_a|\,r_a + |\omega_b|\,r_b\right)\Delta t ,$$
#
# and each shape's box in the broadphase grows by $(|v| + |\omega|\,r)\,\Delta t$ so that every
# such pair is found. Nothing changes in the solver: a point that would not close gets no
# impulse, one that would stops at the surface. The sweep above: not one bullet behind the wall,
# at any speed or time step, and no time of impact is computed.
#
# The price is the **ghost**. A speculative contact's normal is that of the closest features
# *now*, not along the path. A bullet that will fly past a corner is, a step before, closer to
# that corner than one step of its speed *along the line to the corner*; the solver then
# limits that component, and the bullet is knocked off a path that would have missed. Below,
# the scene's bullet at 200 m/s passes 10, 50 and 100 cm above the top corner of a block
# 0.1 m thick, with no contact on its path at all.

# %%
CLEARANCES = (0.1, 0.5, 1.0)  # m between the bullet's lowest point and the block's top corner


def past_the_corner(clearance: float, mode: str) -> np.ndarray:
    """Positions (m) at the end of each of 6 steps of the scene's bullet, flying at
    ``clearance`` above the top corner of a block (0.1 m x 1 m, top face at y = 0, front face
    at x = FACE), with ``mode``: "margin only", "ccd" or "speculative"."""
    w = World(gravity=(0.0, 0.0), dt=DT, speculative=mode == "speculative")
    block = w.add_body(Body("block", type="static", position=(WALL_X, -0.5)))
    block.add_shape(Box(H, 1.0))
    start = (0.0, clearance + R)
    b = w.add_body(Body("bullet", position=start, velocity=(SPEED, 0.0), ccd=mode == "ccd"))
    b.add_shape(Circle(R))
    path = [start]
    for _ in range(6):
        w.step()
        path.append(tuple(b.position))
    return np.array(path)


MODES = ("margin only", "ccd", "speculative")
paths = {(c, mode): past_the_corner(c, mode) for c in CLEARANCES for mode in MODES}
print_table(
    ["clearance (m)", "contacts", "speed after 6 steps (m/s)", "direction (deg)",
     "height after 6 steps (m)"],
    [(c, mode, float(np.hypot(*(p[-1] - p[-2]))) / DT,
      math.degrees(math.atan2(*(p[-1] - p[-2])[::-1])), p[-1, 1])
     for (c, mode), p in paths.items()],
    3,
)  # fmt: skip

# %%
fig, ax = plt.subplots(figsize=(10, 4.2))
ax.add_patch(Rectangle((FACE, -1.0), H, 1.0, color="0.6", label="block (static)"))
for n, c in enumerate(CLEARANCES):
    for mode, style in zip(MODES, ("o-", "s--", "^-"), strict=True):
        if mode == "ccd":
            continue  # the same path as "margin only": drawn once
        p = paths[(c, mode)]
        label = (f"{mode} ('ccd' the same)" if mode == "margin only" else mode) if n == 0 else None
        ax.plot(p[:, 0], p[:, 1], style, color="C0" if mode == "margin only" else "C3",
                ms=5, label=label)  # fmt: skip
ax.set(xlabel="x (m)", ylabel="y (m)", xlim=(-0.5, 21.0), ylim=(-1.2, 4.0),
       title="a bullet at 200 m/s passing 10, 50 and 100 cm above a corner: "
             "where each step ends")  # fmt: skip
ax.set_aspect("equal")
ax.legend(fontsize=8, loc="upper left")
fig.tight_layout()
save_figure(fig, OUT / "speculative_ghost.png", dpi=100)

# %% [markdown]
# Without speculative contacts (and with ccd, whose time of impact finds nothing on the path)
# the bullet flies on at 200 m/s. With them it is knocked 6 to 14 degrees upwards and slowed
# to 96 to 157 m/s (the table), even a metre above the corner: at 10 cm, one step before, the
# corner was 1.6 m away along a line 5 degrees off the path, and the bullet would have covered
# 3.3 m of that line in the step, so the solver held it to 1.6 m. That is
# why the setting is off by default, and why Box2D keeps its speculative distance small (4
# times its linear slop) and leaves fast bodies to continuous collision: the ghosts grow with
# $v\,\Delta t$. For bodies that move less than their own size in a step they are rare and
# small, and a ball landing at 6 m/s meets the ground in the step it gets there, where with
# the 2 cm margin alone it is found a step late, 13 to 19 mm deep (lesson 16, bounces). Its
# bounce, though, is still worked out from the speed it had at the start of the step (lesson
# 07), and met up to a step before it lands it misses what gravity adds until then, up to
# $g\,\Delta t$: dropped from 2 m with $e = 0.5$ it climbs to 0.45 m, not 0.50 m
# (`tests/test_speculative.py` measures both).

# %% [markdown]
# ## Animation
#
# The three runs of the scene overlaid (no ccd, ccd, ccd bouncing), zoomed on the wall, with
# `SUBFRAMES` frames per step from the first to the fourth step. Each frame shows every run at
# its latest step no later than the frame's time, so the engine's bullets *jump* once per step;
# the grey ghost is the straight flight they are sampled from ($x = v t$, no contacts at all).
# All bullets fly at $y = 0$; each run is drawn in its own lane, 0.6 m apart.
# Watch the blue bullet jump from 3.33 m to 6.67 m while the ghost passes through the wall, and
# the orange one stop at the wall; the green one bounces back at $e\,v$, a step late.

# %%
SUBFRAMES = 24  # frames per step of the animation
LANES = {"ghost": 0.9, "no ccd": 0.3, "ccd": -0.3, f"ccd, e = {BOUNCE}": -0.9}  # m, drawn apart
GHOST = Recording(names=recordings["ccd"].names, types=recordings["ccd"].types,
                  outlines=recordings["ccd"].outlines)  # fmt: skip
runs_anim = {name: Recording(names=GHOST.names, types=GHOST.types, outlines=GHOST.outlines)
             for name in recordings}  # fmt: skip
frame_times = DT * (1.0 + np.arange(3 * SUBFRAMES + 1) / SUBFRAMES)
for tf in frame_times:
    k = int(math.floor(tf / DT + 1e-9))  # the latest step at or before this frame
    for name, rec in recordings.items():
        poses = rec.frames[k].copy()
        poses[1, 1] += LANES[name]  # the bullets fly at y = 0; each run is drawn in its lane
        runs_anim[name].add_frame(poses, tf)
    ghost = rec.frames[0].copy()
    ghost[1] = (SPEED * tf, LANES["ghost"], 0.0)  # x = v t, straight through
    GHOST.add_frame(ghost, tf)
gif = render_gif(
    [GHOST, *runs_anim.values()],
    OUT / "bullet.gif",
    fps=16,
    size_px=480,
    labels=["straight flight (no contacts)", *runs_anim],
    colors=["0.6", "C0", "C1", "C2"],
    trail=True,
    view=(3.0, 7.8, -1.2, 1.2),
    axes=True,
)
show_gif(gif)
print(f"wrote {len(GHOST)} frames to {gif.name}: steps 1 to 4, {SUBFRAMES} frames per step")

# %% [markdown]
# ## Exercises
#
# Predict first, then run the cell under the question, then open the answer.
#
# **1.** Pure retroactive detection (no contact margin, no ccd) at $\Delta t = 1/240$ s: up to
# what speed is the bullet of `scenes/bullet.json` always seen by the wall?

# %%
seen_e1, _ = sweep(np.array([0.19, 0.22]), 1 / 240, margin=0.0)
for vdt, row in zip((0.19, 0.22), seen_e1, strict=True):
    print(f"v = {vdt * 240:.1f} m/s (v dt = {vdt} m): missed by {int((~row).sum())} of {PHASES}")

# %% [markdown]
# <details><summary>Answer</summary>
#
# Always seen while $v\,\Delta t \le h + 2r = 0.2$ m, i.e. up to $0.2 \times 240 = 48$ m/s,
# four times the 12 m/s of 60 Hz. Just below (45.6 m/s) no start position is missed; at
# 52.8 m/s a fraction $1 - 0.2/0.22 = 9\%$ of the starts should be, about 3 of 32: the run
# misses 3.
#
# </details>
#
# **2.** Start the bouncing ccd bullet ($e$ = `BOUNCE`) at $x = 1$ m instead of 0. How much of
# its impact step is dropped now, and how far behind the ideal bounce is it afterwards?

# %%
w2 = bullet_world(ccd=True, restitution=BOUNCE)
w2.body("bullet").position = (1.0, 0.0)
x2 = record(w2, 6).poses()[:, 1, 0]
ideal2 = FACE - R - BOUNCE * SPEED * (times[:7] - (FACE - R - 1.0) / SPEED)
print(f"x after 6 steps {x2[6]:.4f} m, bounce at t_hit {ideal2[6]:.4f} m, "
      f"lag {x2[6] - ideal2[6]:.4f} m = {1000 * (x2[6] - ideal2[6]) / (BOUNCE * SPEED):.2f} ms")  # fmt: skip

# %% [markdown]
# <details><summary>Answer</summary>
#
# The samples are now at 1, 4.333, 7.667 m: the second step starts 0.567 m from touching, so its
# time of impact is $t = (4.895 - 4.333)/3.333 = 0.169$ (the engine stops 5 mm short) and
# $(1 - 0.169)\,\Delta t = 13.9$ ms are dropped, against 8.9 ms from $x = 0$. After the bounce
# the bullet trails the ideal one by $e\,v \times 13.9$ ms $= 1.39$ m. The run prints a lag of
# 1.39 m, 13.9 ms.
#
# </details>
#
# **3.** Conservative advancement took 2 iterations head on and 3 towards the corner. How many
# for a bullet flying at 45 degrees into the middle of the wall's face, from $(3.4, -1.5)$ to
# $(5.4, 0.5)$?

# %%
rows3, t3 = advance((3.4, -1.5), (5.4, 0.5))
print(f"{len(rows3)} iterations, impact at t = {t3:.4f}, "
      f"engine {engine_toi((3.4, -1.5), (5.4, 0.5)):.4f}")  # fmt: skip

# %% [markdown]
# <details><summary>Answer</summary>
#
# The nearest feature is the face all the way, so $\hat{\mathbf{n}} = (1, 0)$ stays fixed and
# the gap closes at the constant rate $|\Delta\mathbf{p}\cdot\hat{\mathbf{n}}| = 2$ m per unit
# $t$: the first estimate is exact, as head on. 2 iterations (one move and the check),
# $t = (4.895 - 3.4)/2 = 0.7475$. The sideways part of the motion does not slow it down; only a
# nearest feature that changes (a corner) does.
#
# </details>
