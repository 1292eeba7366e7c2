# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: percent
# ---

# %% [markdown]
# # 12 Springs and buoyancy
#
# Slides, "Further Topics on Physics Animation": modelling forces (springs, buoyancy); "Force":
# forces add up as vectors, $\mathbf{f}_{total} = \sum_i \mathbf{f}_i$, and $\mathbf{a} =
# \mathbf{f}/m$; "Torque": a force acting off-centre turns the body, $\tau = \mathbf{r} \times
# \mathbf{f}$.
#
# Both are *force generators*: each step the integrator asks them for the force at a state
# $(\mathbf{p}, \mathbf{v}, \varphi, \omega)$ (several states per step for Verlet and RK4), so
# they are not constraints but ordinary terms of $\mathbf{f}_{total}$.
#
# - **damped spring** (`SpringJoint`), between two anchors $d$ apart, rest length $L$:
#   $\mathbf{f} = -k(|\mathbf{d}| - L)\,\hat{\mathbf{d}} - c\,(\Delta\mathbf{v}\cdot\hat{\mathbf{d}})
#   \,\hat{\mathbf{d}}$, potential energy $k x^2 / 2$
# - **buoyancy** (`Buoyancy`, Archimedes): the water pushes up with the weight of the water the
#   body displaces, $\mathbf{f} = -\rho_{fluid} A\,\mathbf{g}$, at the centroid of the submerged
#   area $A$ (the part of each shape below the surface, clipped), plus drag in the water

# %%
import math

import matplotlib.pyplot as plt
import numpy as np

from sandbox import Body, Box, Circle, World
from sandbox.buoyancy import box_draft, disc_draft
from sandbox.forces import Buoyancy
from sandbox.joints import SpringJoint
from sandbox.lessonkit import output_dir, print_table, save_figure
from sandbox.pymunk_bridge import PymunkScene
from sandbox.recording import record
from sandbox.render import render_gif

# knobs
MASS = 1.0  # kg (a 1 m x 1 m box of density 1)
STIFFNESS = 20.0  # N/m
STRETCH = 0.2  # m, released from rest this far from the rest length
ZETAS = (0.1, 1.0, 3.0)  # damping ratio c / (2 sqrt(k m)): under-, critically, over-damped
DENSITIES = (0.25, 0.5, 0.75)  # body / fluid
FLUID = 1.0  # kg/m^2
STONE = 2.0  # density of something that sinks
DT = 1.0 / 60.0  # s
G = 9.81

OUT = output_dir("12_springs_and_buoyancy")

# %% [markdown]
# ## A mass on a spring
#
# $m\ddot x + c\dot x + kx = 0$ with $\omega_0 = \sqrt{k/m}$ and $\zeta = c / (2\sqrt{km})$.
# Released from rest at $x_0$:
#
# - $\zeta < 1$: $x = x_0 e^{-\zeta\omega_0 t}(\cos\omega_d t + \frac{\zeta\omega_0}{\omega_d}
#   \sin\omega_d t)$, $\omega_d = \omega_0\sqrt{1-\zeta^2}$: it rings inside the envelope
#   $x_0 e^{-ct/2m}$, with period $2\pi/\omega_d \approx 2\pi\sqrt{m/k}$
# - $\zeta = 1$: $x = x_0(1 + \omega_0 t)e^{-\omega_0 t}$, the fastest return without overshoot
# - $\zeta > 1$: $x = x_0 (r_2 e^{r_1 t} - r_1 e^{r_2 t}) / (r_2 - r_1)$,
#   $r_{1,2} = -\zeta\omega_0 \pm \omega_0\sqrt{\zeta^2 - 1}$: a slow creep back


# %%
def oscillator(t, zeta: float):
    w0 = math.sqrt(STIFFNESS / MASS)
    if zeta < 1:
        wd = w0 * math.sqrt(1 - zeta**2)
        return STRETCH * np.exp(-zeta * w0 * t) * (np.cos(wd * t) + zeta * w0 / wd * np.sin(wd * t))
    if zeta == 1:
        return STRETCH * (1 + w0 * t) * np.exp(-w0 * t)
    s = w0 * math.sqrt(zeta**2 - 1)
    r1, r2 = -zeta * w0 + s, -zeta * w0 - s
    return STRETCH * (r2 * np.exp(r1 * t) - r1 * np.exp(r2 * t)) / (r2 - r1)


def spring_run(zeta: float, integrator: str, seconds: float = 5.0):
    world = World(gravity=(0.0, 0.0), dt=DT, integrator=integrator)
    anchor = world.add_body(Body("anchor", type="static"))
    box = world.add_body(Body("box", position=(2.0 + STRETCH, 0.0)))
    box.add_shape(Box(1.0, 1.0, density=MASS))
    c = zeta * 2 * math.sqrt(STIFFNESS * MASS)
    world.add_joint(SpringJoint(anchor, box, rest_length=2.0, stiffness=STIFFNESS, damping=c))
    t, x = [0.0], [STRETCH]
    for _ in range(int(seconds / DT)):
        world.step()
        t.append(world.time)
        x.append(box.position[0] - 2.0)
    return np.array(t), np.array(x)


rows, runs = [], {}
for zeta in ZETAS:
    for integrator in ("semi_implicit_euler", "rk4"):
        t, x = spring_run(zeta, integrator)
        runs[zeta, integrator] = (t, x)
        err = np.max(np.abs(x - oscillator(t, zeta)))
        rows.append((zeta, integrator, zeta * 2 * math.sqrt(STIFFNESS * MASS), 1000 * err))
print_table(["zeta", "integrator", "c (N s/m)", "max |x - closed form| (mm)"], rows, 4)

# the undamped period and the envelope of the light damping, from the peaks
t, x = spring_run(0.0, "semi_implicit_euler", 8.0)
top = np.flatnonzero((x[1:-1] > x[:-2]) & (x[1:-1] >= x[2:])) + 1
period = float(np.mean(np.diff(t[top])))
t, x = runs[0.1, "semi_implicit_euler"]
top = np.flatnonzero((x[1:-1] > x[:-2]) & (x[1:-1] >= x[2:])) + 1
rate = -np.polyfit(t[top], np.log(x[top]), 1)[0]
c = 0.1 * 2 * math.sqrt(STIFFNESS * MASS)
print_table(
    ["quantity", "theory", "measured", "error"],
    [
        ("period 2 pi sqrt(m/k) (s)", 2 * math.pi * math.sqrt(MASS / STIFFNESS), period,
         f"{period / (2 * math.pi * math.sqrt(MASS / STIFFNESS)) - 1:+.3%}"),
        ("envelope rate c / 2m (1/s)", c / (2 * MASS), rate, f"{rate / (c / (2 * MASS)) - 1:+.3%}"),
    ],
)  # fmt: skip

# %%
fig, ax = plt.subplots(figsize=(8, 4))
tt = np.linspace(0, 5, 600)
for k, zeta in enumerate(ZETAS):
    t, x = runs[zeta, "semi_implicit_euler"]
    ax.plot(tt, oscillator(tt, zeta), color=f"C{k}", lw=1.5, label=f"closed form, zeta = {zeta}")
    ax.plot(t[::6], x[::6], "o", color=f"C{k}", ms=3, label=f"engine, zeta = {zeta}")
env = STRETCH * np.exp(-0.1 * math.sqrt(STIFFNESS / MASS) * tt)
ax.plot(tt, env, "k:", lw=1, label=r"envelope $x_0 e^{-ct/2m}$")
ax.plot(tt, -env, "k:", lw=1)
ax.set(xlabel="t (s)", ylabel="x (m)", title="mass on a damped spring (semi-implicit Euler)")
ax.legend(fontsize=7, ncol=2)
fig.tight_layout()
save_figure(fig, OUT / "damped_spring.png", dpi=100)

# %% [markdown]
# RK4 follows the closed forms to a micrometre. The default semi-implicit Euler is a few
# millimetres off on a 200 mm swing: with light damping its small period error adds up over the
# swings, with strong damping the damper uses the velocity at the start of the step
# ($c\,\Delta t / m = 0.15$ at $\zeta = 1$). Period and envelope still come out within 1%.
# That is why the spring is a force
# generator and not a constraint: the integrator you choose sees it.
#
# The animation shows it with energy bars (as PhET's "Masses and Springs"): the same undamped
# box on the spring under explicit Euler (top) and semi-implicit Euler (bottom). Elastic and
# kinetic energy trade places every quarter period; under explicit Euler the total grows every
# step, by the factor $1 + (\omega\Delta t)^2$ of lesson 01, so the "lost" bar goes negative
# (energy from nowhere), while semi-implicit Euler's total only wobbles.

# %%
bar_runs = []
for integrator, y in (("explicit_euler", 0.0), ("semi_implicit_euler", -1.5)):
    world = World(gravity=(0.0, 0.0), dt=DT, integrator=integrator)
    anchor = world.add_body(Body("anchor", type="static", position=(0.0, y)))
    box = world.add_body(Body("box", position=(2.0 + STRETCH, y)))
    box.add_shape(Box(1.0, 1.0, density=MASS))
    world.add_joint(SpringJoint(anchor, box, rest_length=2.0, stiffness=STIFFNESS))
    bar_runs.append(record(world, 240, every=2, energy=True))
grown = [sum(r.series[k][-1] for k in ("energy.kinetic_linear", "energy.elastic"))
         / sum(r.series[k][0] for k in ("energy.kinetic_linear", "energy.elastic"))
         for r in bar_runs]  # fmt: skip
w_dt = math.sqrt(STIFFNESS / MASS) * DT
print(
    f"after 4 s: explicit Euler's energy x {grown[0]:.3f} ((1 + (w dt)^2)^240 = "
    f"{(1 + w_dt**2) ** 240:.3f}), semi-implicit Euler's x {grown[1]:.4f}"
)
gif = render_gif(bar_runs, OUT / "spring_energy_bars.gif", fps=30, size_px=360,
                 labels=["explicit Euler", "semi-implicit Euler"], panel="energy-bars")  # fmt: skip
print(f"wrote {len(bar_runs[0])} frames to {gif.name}")

# %% [markdown]
# ## Floating
#
# In 2D the fluid density is a mass per area. A body of density $\rho_b$ floats when the water
# it displaces weighs as much as it does: $\rho_{fluid} A_{sub} g = \rho_b A g$, so the
# submerged fraction is $A_{sub}/A = \rho_b / \rho_{fluid}$, whatever its shape or tilt.
# For a box floating flat the draft is $d = h\,\rho_b/\rho_{fluid}$; for a disc, the depth whose
# circular segment has area $\pi r^2 \rho_b/\rho_{fluid}$. The lift acts at the centroid of the
# submerged part, so when a tilted body's centroid moves off the vertical through its centre of
# mass the pair of forces turns it: a square of density 0.5 does not float flat.

# %%
world = World(dt=DT)
# the floor's top is at y = -4 m; it is 15 m thick so that drawn, it fills the view below the tank
world.add_body(Body("floor", type="static", position=(8.5, -11.5))).add_shape(Box(22.0, 15.0))
for x in (-2.0, 19.0):  # tank walls, their tops at the water line
    world.add_body(Body(f"wall{x:g}", type="static", position=(x, -2.0))).add_shape(Box(0.3, 4))
for k, rho in enumerate(DENSITIES):
    x = 5.5 * k
    world.add_body(Body(f"plank {rho}", position=(x, 0.55))).add_shape(Box(2.0, 0.5, density=rho))
    world.add_body(Body(f"square {rho}", position=(x + 2.4, 0.8), angle=0.1)).add_shape(
        Box(1.0, 1.0, density=rho)
    )
    world.add_body(Body(f"disc {rho}", position=(x + 4.0, 0.8))).add_shape(Circle(0.5, density=rho))
world.add_body(Body("stone", position=(17.0, 0.6))).add_shape(Box(0.6, 0.6, density=STONE))
water = world.add_force(Buoyancy(0.0, FLUID, linear_drag=2.0, angular_drag=0.5))
spec = world.to_scene()  # the same scene for pymunk, below

HEIGHT = "stone y (m)"
rec = record(world, 600, every=5, series={HEIGHT: lambda w: w.body("stone").position[1]})

area, _ = water.submerged(world)
rows = []
for body in world.bodies:
    if body.type != "dynamic" or body.name == "stone":
        continue
    rho = body.shapes[0].density
    total = sum(s.mass_properties().mass / s.density for s in body.shapes)
    kind, y = body.name.split()[0], body.position[1]
    if kind == "plank":
        depth, theory = 0.25 - y, box_draft(0.5, rho)
    elif kind == "disc":
        depth, theory = 0.5 - y, disc_draft(0.5, rho)
    else:
        depth, theory = math.nan, math.nan
    rows.append(
        (body.name, rho / FLUID, area[body.index] / total, depth, theory,
         (depth - theory) / theory if theory == theory else math.nan, math.degrees(body.angle))
    )  # fmt: skip
print_table(
    ["body", "rho_b / rho_f", "A_sub / A", "draft (m)", "theory (m)", "rel. error", "angle (deg)"],
    rows,
)
stone = world.body("stone")
print(
    f"stone (density {STONE}): y = {stone.position[1]:.3f} m, resting on the floor (its top at -4.0 m)"
)

# %% [markdown]
# The submerged fraction equals the density ratio for every body, and planks and discs sit at
# the closed-form draft.

# %% [markdown]
# The stone sinks: once under water it accelerates at $g(1 - \rho_{fluid}/\rho_b)$ less the
# water's drag, then rests on the floor. The same scene in pymunk (where the bridge applies the same buoyancy formulas each
# step) floats the planks and discs at the same heights:

# %%
pm = PymunkScene.from_scene(spec)
for _ in range(600):
    pm.step()
rows = []
for (name, _, y, *_), body in zip(pm.state(), world.bodies, strict=True):
    if name.startswith(("plank", "disc")):
        rows.append((name, body.position[1], y, 1000 * (body.position[1] - y)))
print_table(["body", "y this engine (m)", "y pymunk (m)", "difference (mm)"], rows)

# %%
t = np.array(rec.times)
fig, ax = plt.subplots(figsize=(7, 3.5))
ax.plot(t, rec.series[HEIGHT], label="stone")
ax.axhline(0.0, color="C0", ls=":", lw=1, label="water surface")
ax.axhline(-4.0 + 0.3, color="k", ls=":", lw=1, label="resting on the floor")
ax.set(xlabel="t (s)", ylabel="y (m)", title=f"a stone of density {STONE} sinks")
ax.legend(fontsize=8)
fig.tight_layout()
save_figure(fig, OUT / "sinking.png", dpi=100)

# the view is the tank, wall to wall: the water (drawn across the whole view) stays inside it
gif = render_gif(rec, OUT / "floating.gif", fps=30, size_px=360, panel=HEIGHT,
                 view=(-2.15, 19.15, -18.8, 2.5))  # fmt: skip
print(f"wrote {len(rec)} frames to {gif.name}")

# %% [markdown]
# ## How far does a floating square tip?
# A floating body settles where the energy
# $E = m g\,(y_G - y_B)$ is lowest, $y_G$ its centre of mass and $y_B$ the centroid of the water
# it displaces, with the waterline placed (for each tilt $\theta$) so that the displaced area
# stays $A\,\rho_b/\rho_{fluid}$: the lower the centre of mass sits below the centre of
# buoyancy, the better. For a unit square (clipped at the waterline, as the buoyancy force does) the minimum is *not* always on a corner: at density 0.5 it floats
# corner-down at 45 degrees, at 0.25 and 0.75 tilted by $\arctan\frac{1}{2} = 26.6$ degrees, and
# below 0.21 or above 0.79 flat. (By symmetry a tilt of $\theta$ and $90° - \theta$ are the same
# pose: the table folds the measured angles into $[0°, 45°]$.) After the animation's 10 s the
# squares still rock a little; 20 s later they have settled.


# %%
def clip_below(points: list, level: float) -> list:
    """The part of a convex polygon below y = ``level`` (one Sutherland-Hodgman pass)."""
    out = []
    for (x0, y0), (x1, y1) in zip(points, points[1:] + points[:1], strict=True):
        if y0 <= level:
            out.append((x0, y0))
        if (y0 < level) != (y1 < level):  # the edge crosses the waterline
            out.append((x0 + (level - y0) * (x1 - x0) / (y1 - y0), level))
    return out


def area_and_centroid_y(points: list) -> tuple[float, float]:
    """Area (m^2) and centroid height (m) of a polygon (shoelace formula)."""
    a = cy = 0.0
    for (x0, y0), (x1, y1) in zip(points, points[1:] + points[:1], strict=True):
        cross_ = x0 * y1 - x1 * y0
        a += cross_
        cy += (y0 + y1) * cross_
    return 0.5 * a, cy / (3.0 * a) if a else 0.0


def buoyancy_energy(theta: float, ratio: float) -> float:
    """(y_G - y_B) of a unit square tilted by theta with a fraction ``ratio`` under water (m)."""
    c, s_ = math.cos(theta), math.sin(theta)
    corners = [
        (c * x - s_ * y, s_ * x + c * y)
        for x, y in ((-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5))
    ]
    lo, hi = -0.75, 0.75  # the waterline, found by bisection on the submerged area
    for _ in range(50):
        mid = 0.5 * (lo + hi)
        lo, hi = (
            (mid, hi) if area_and_centroid_y(clip_below(corners, mid))[0] < ratio else (lo, mid)
        )
    return 0.0 - area_and_centroid_y(clip_below(corners, 0.5 * (lo + hi)))[1]


tilts = np.radians(np.linspace(0.0, 45.0, 451))
landscape = {rho: np.array([buoyancy_energy(t, rho) for t in tilts]) for rho in DENSITIES}


def tilt_of(body: Body) -> float:
    """The body's tilt folded into [0, 45] degrees (a square looks the same every 90)."""
    a = abs(math.degrees(body.angle)) % 90.0
    return min(a, 90.0 - a)


def refined_minimum(e: np.ndarray) -> float:
    """The tilt (deg) of the minimum of ``e`` on the grid ``tilts``, refined by a parabola."""
    k = int(np.clip(np.argmin(e), 1, len(e) - 2))
    y0, y1, y2 = e[k - 1 : k + 2]
    step = float(tilts[1] - tilts[0])
    shift = 0.5 * (y0 - y2) / (y0 - 2 * y1 + y2) if y0 - 2 * y1 + y2 > 0 else 0.0
    return math.degrees(tilts[k] + shift * step)


at_10_s = {rho: tilt_of(world.body(f"square {rho}")) for rho in DENSITIES}
for _ in range(1200):  # 20 s more: the squares rock slowly (the water's drag damps them)
    world.step()
rows = []
for rho in DENSITIES:
    theory_tilt, measured_tilt = (
        refined_minimum(landscape[rho]),
        tilt_of(world.body(f"square {rho}")),
    )
    rows.append((rho, theory_tilt, at_10_s[rho], measured_tilt, measured_tilt - theory_tilt))
print_table(["square, rho_b / rho_f", "theory tilt (deg)", "tilt at 10 s (deg)",
             "tilt at 30 s (deg)", "difference (deg)"], rows, 3)  # fmt: skip
print(f"arctan(1/2) = {math.degrees(math.atan(0.5)):.2f} deg")

fig, ax = plt.subplots(figsize=(7.5, 4))
for k, rho in enumerate(DENSITIES):
    e = landscape[rho]
    ax.plot(np.degrees(tilts), e - e.min(), color=f"C{k}", label=f"density ratio {rho}")
    tilt_m = rows[k][3]
    ax.plot([tilt_m], [buoyancy_energy(math.radians(tilt_m), rho) - e.min()], "o",
            color=f"C{k}", ms=7, mfc="none")  # fmt: skip
ax.plot([], [], "o", color="0.3", mfc="none", label="where the engine's square settled")
ax.set(xlabel="tilt of the square (deg)", ylabel="(y_G - y_B) - minimum (m)",
       title="floating square: energy against tilt")  # fmt: skip
ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.0, 1.0))
ax.grid(alpha=0.3)
fig.tight_layout()
save_figure(fig, OUT / "floating_square.png", dpi=100)

# %% [markdown]
# ## Exercises
#
# Predict first, then run the cell under the question, then open the answer.
#
# **1.** A 2 x 0.5 m plank of density 0.6 floats flat. How deep is it in the water? And a unit
# square of density 0.1, released tilted by 0.1 rad: at what tilt does it settle?

# %%
pond = World(dt=DT)
pond.add_body(Body("plank 0.6", position=(0.0, 0.3))).add_shape(Box(2.0, 0.5, density=0.6))
pond.add_body(Body("square 0.1", position=(4.0, 0.5), angle=0.1)).add_shape(
    Box(1.0, 1.0, density=0.1)
)
pond.add_force(Buoyancy(0.0, FLUID, linear_drag=2.0, angular_drag=0.5))
for _ in range(1200):
    pond.step()
print(f"plank draft {0.25 - pond.body('plank 0.6').position[1]:.4f} m; square tilt "
      f"{tilt_of(pond.body('square 0.1')):.3f} deg (theory "
      f"{refined_minimum(np.array([buoyancy_energy(t, 0.1) for t in tilts])):.1f} deg)")  # fmt: skip

# %% [markdown]
# <details><summary>Answer</summary>
#
# The plank displaces its own weight: draft $= h\,\rho_b/\rho_{fluid} = 0.5 \times 0.6 = 0.3$ m;
# the run prints 0.3000 m. The light square floats *flat*: at density 0.1 the energy
# $y_G - y_B$ is lowest at 0 degrees (a shallow, wide submerged strip keeps the centre of
# buoyancy high), and the tilted square rights itself to 0.000 degrees.
#
# </details>
#
# **2.** A 1 kg box on a spring of $k = 80$ N/m (four times stiffer), no damping. Its period?

# %%
stiff = World(gravity=(0.0, 0.0), dt=DT, integrator="rk4")
anchor_e2 = stiff.add_body(Body("anchor", type="static"))
box_e2 = stiff.add_body(Body("box", position=(2.0 + STRETCH, 0.0)))
box_e2.add_shape(Box(1.0, 1.0, density=MASS))
stiff.add_joint(SpringJoint(anchor_e2, box_e2, rest_length=2.0, stiffness=80.0, damping=0.0))
xs_e2 = []
for _ in range(300):
    stiff.step()
    xs_e2.append(box_e2.position[0] - 2.0)
xs_e2 = np.array(xs_e2)
peaks_e2 = np.flatnonzero((xs_e2[1:-1] > xs_e2[:-2]) & (xs_e2[1:-1] >= xs_e2[2:])) + 1
print(f"k = 80 N/m: period {DT * float(np.mean(np.diff(peaks_e2))):.4f} s "
      f"(peaks are whole steps apart)")  # fmt: skip

# %% [markdown]
# <details><summary>Answer</summary>
#
# $T = 2\pi\sqrt{m/k} = 2\pi\sqrt{1/80} = 0.7025$ s: four times the stiffness halves the period
# (1.405 s at 20 N/m). The run prints 0.7028 s: its peaks are found on whole steps of 1/60 s,
# so over the 6 periods counted the mean is known to about a step / 6 = 0.003 s.
#
# </details>
