# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: percent
# ---

# %% [markdown]
# # 19 Soft bodies: masses and springs
#
# Slide "Physics Theory" lists soft body dynamics beside rigid bodies. The simplest soft body is
# a **mass-spring system**: the body is a set of particles (point masses) joined by damped
# springs, each pulling its two particles along the line between them,
#
# $$\mathbf{f} = -\big(k\,(|\mathbf{d}| - L) + c\,\Delta\mathbf{v}\cdot\hat{\mathbf{d}}\big)\,
#   \hat{\mathbf{d}},$$
#
# (lesson 12's spring) and the particles move under these forces and gravity like any body. A
# grid of particles needs **structural** springs (along the rows and columns: resist stretching)
# and **shear** springs (across the diagonals: without them a square folds into a rhombus at no
# cost). In the sandbox the particles are small discs and the springs `SpringJoint`s, so the
# soft body also collides with the rest of the world.
#
# Two things decide whether it works: the springs must be stiff enough to hold the shape, and
# the time step small enough for the stiffest spring. The lesson measures both.

# %%
import math

import matplotlib.pyplot as plt
import numpy as np

from sandbox import Body, Box, Circle, SimulationError, World
from sandbox.joints import SpringJoint
from sandbox.lessonkit import output_dir, print_table, save_figure, show_gif
from sandbox.recording import record
from sandbox.render import render_gif

# knobs
DT = 1.0 / 60.0  # s
PARTICLE = 0.04  # kg per particle
RADIUS = 0.05  # m, the particles' discs
GRID, SPACING = 5, 0.25  # particles per side, m between neighbours
STIFFNESS = 40.0  # N/m per spring of the soft box
DAMPING = 0.3  # N s/m per spring
CHAIN = 8  # particles in the hanging chain
DROP = 0.3  # m, the soft box's lowest corner falls from this height
TILT = 0.35  # rad, the soft box lands on a corner

OUT = output_dir("19_soft_bodies")
G = 9.81

# %% [markdown]
# ## One spring, two particles: the period, and the largest stable stiffness
#
# Two particles of mass $m$ on a spring oscillate about their centre with the reduced mass
# $\mu = m/2$: $\omega = \sqrt{k/\mu} = \sqrt{2k/m}$, period $T = 2\pi/\omega$.
#
# Semi-implicit Euler, the default integrator, is stable for an oscillator only while
# $\omega\Delta t \le 2$ (the step's update matrix has eigenvalues on the unit circle up to
# there, and one beyond $-1$ after). For the pair that is
#
# $$k \le k_{max} = \frac{2m}{\Delta t^2} = 2 \times 0.04 \times 60^2 = 288\ \text{N/m}.$$
#
# A stiffer spring does not just oscillate wrongly: its energy grows by a factor every step
# and the body explodes, unless something stops it. The engine does: a closed system (no
# motor, thruster or outside force) whose energy passes a million times the energies it started
# with has diverged, and the run stops with `sandbox.SimulationError`, naming the body and a
# likely cause, while its numbers are still finite. Runs of 60 steps at 95% and 105% of
# $k_{max}$:


# %%
def pair(k: float, stretch: float = 0.02) -> World:
    world = World(gravity=(0.0, 0.0), dt=DT)
    a = world.add_body(Body("a", position=(0.0, 0.0)))
    a.add_shape(Circle(RADIUS, mass=PARTICLE))
    b = world.add_body(Body("b", position=(SPACING + stretch, 0.0)))
    b.add_shape(Circle(RADIUS, mass=PARTICLE))
    world.add_joint(SpringJoint(a, b, rest_length=SPACING, stiffness=k))
    return world


def pair_run(k: float, steps: int) -> tuple[np.ndarray, np.ndarray]:
    """(length - L) of the pair and its energy relative to the start, step by step, up to
    ``steps`` or the step at which the engine stopped a diverging run (``stopped[k]``)."""
    world = pair(k)
    e0, x, e = world.energy(), [], []
    for _ in range(steps):
        try:
            world.step()
        except SimulationError as error:
            stopped[k] = error
            break
        pa, pb = np.array(world.bodies[0].position), np.array(world.bodies[1].position)
        x.append(np.linalg.norm(pb - pa) - SPACING)
        e.append(world.energy() / e0)
    return np.array(x), np.array(e)


stopped: dict[float, SimulationError] = {}


K_MAX = 2 * PARTICLE / DT**2
k_period = 20.0  # N/m: omega dt = 0.53, well inside the limit
x_p, _ = pair_run(k_period, 240)
t_p = DT * np.arange(1, 241)
peaks = np.flatnonzero((x_p[1:-1] > x_p[:-2]) & (x_p[1:-1] >= x_p[2:])) + 1
period = float(np.mean(np.diff(t_p[peaks])))
w_dt = math.sqrt(2 * k_period / PARTICLE) * DT
stable = {}
for frac in (0.95, 1.05):
    _, stable[frac] = pair_run(frac * K_MAX, 60)
print_table(
    ["", "value"],
    [("k (N/m) for the period", k_period),
     ("period 2 pi sqrt(m / 2k) (s)", 2 * math.pi * math.sqrt(PARTICLE / (2 * k_period))),
     ("measured (peaks, whole steps) (s)", period),
     ("semi-implicit Euler's own period 2 pi dt / arccos(1 - (w dt)^2 / 2) (s)",
      2 * math.pi * DT / math.acos(1 - w_dt**2 / 2)),
     ("k_max = 2 m / dt^2 (N/m)", K_MAX),
     ("energy after 1 s at 0.95 k_max (x start)", f"{stable[0.95][-1]:.3f}"),
     ("largest energy at 1.05 k_max (x start)", f"{stable[1.05].max():.3e}"),
     ("steps before the engine stopped the 1.05 k_max run", len(stable[1.05]))],
)  # fmt: skip
print(f"SimulationError: {stopped[1.05 * K_MAX]}")

# %% [markdown]
# Below the limit the energy stays bounded: it swings, up to $1/(1 - \omega\Delta t/2) = 40$
# times its start at 95% of $k_{max}$ (lesson 01's shadow energy), but no further; at 5% above
# the limit it grows every step, about 2.4 times, until the engine stops the run (the table,
# and the error it printed). In a soft body every particle has several springs, so the stiffest *mode*
# of the whole mesh is faster than one spring's and the safe stiffness is lower still; stiff
# soft bodies are why engines take substeps (Box2D v3's soft step, lesson 16) or integrate
# springs implicitly.
#
# ## A hanging chain: stretch under its own weight
#
# `CHAIN` particles hang in a line from a fixed point, each spring of rest length `SPACING`. The
# spring at the top carries all $N$ particles, the next $N - 1$, ..., the last one: spring $j$
# (from the top) stretches by $(N - j + 1)\,m g/k$, and the chain by
#
# $$\Delta L = \frac{m g}{k}\,\frac{N(N + 1)}{2}.$$
#
# Damping lets it settle.

# %%
k_chain = 60.0
world = World(dt=DT)
top = world.add_body(Body("hook", type="static", position=(0.0, 0.0)))
prev = top
for i in range(CHAIN):
    p = world.add_body(Body(f"p{i}", position=(0.0, -(i + 1) * SPACING)))
    p.add_shape(Circle(RADIUS, mass=PARTICLE))
    world.add_joint(SpringJoint(prev, p, rest_length=SPACING, stiffness=k_chain, damping=0.7))
    prev = p
for _ in range(1200):  # 20 s: the slowest swing of the chain is lightly damped
    world.step()
ys = np.array([0.0] + [b.position[1] for b in world.bodies[1:]])
stretch = -np.diff(ys) - SPACING  # per spring, from the top
expected = (CHAIN - np.arange(CHAIN)) * PARTICLE * G / k_chain
print(f"total stretch {stretch.sum():.6f} m; m g N (N + 1) / (2 k) = "
      f"{PARTICLE * G * CHAIN * (CHAIN + 1) / (2 * k_chain):.6f} m; largest error per spring "
      f"{np.abs(stretch - expected).max():.1e} m")  # fmt: skip

# %% [markdown]
# ## A soft box
#
# A `GRID` x `GRID` grid of particles, 1 m wide, with structural and shear springs
# (`STIFFNESS`, `DAMPING`), tilted by `TILT` and dropped onto a corner from `DROP` m. Its shape
# is measured by the area inside its outer particles (1 m$^2$ at rest).
#
# **How stiff may it be?** Linearised about its rest shape, the mesh moves as
# $m\ddot{\mathbf{x}} = -k\,L\,\mathbf{x} - c\,L\,\dot{\mathbf{x}}$, with $L$ the sum over the
# springs of their $\hat{\mathbf{u}}\hat{\mathbf{u}}^T$ blocks (a 50 x 50 matrix here). Its
# fastest mode has $\omega^2 = k\lambda_{max}/m$ and the damping rate $\gamma =
# c\lambda_{max}/m$, and semi-implicit Euler keeps such a mode bounded only while
# $\omega^2\Delta t^2 \le 4 - 2\gamma\Delta t$:
#
# $$k \le k_{max} = \frac{(4 - 2\,c\,\lambda_{max}\Delta t/m)\,m}{\lambda_{max}\,\Delta t^2}.$$
#
# (For the pair above, $\lambda_{max} = 2$ and $c = 0$: $2m/\Delta t^2$.) Damping lowers it.


# %%
def spring_pairs(shear: bool) -> list[tuple[int, int]]:
    """Particle index pairs (row-major) of the structural and, if ``shear``, diagonal springs."""
    pairs = []
    for i in range(GRID):
        for j in range(GRID):
            here = i * GRID + j
            pairs += [(here, here + 1)] if j + 1 < GRID else []
            pairs += [(here, here + GRID)] if i + 1 < GRID else []
            if shear and i + 1 < GRID and j + 1 < GRID:
                pairs += [(here, here + GRID + 1), (here + 1, here + GRID)]
    return pairs


def soft_box(shear: bool = True, k: float = STIFFNESS, x0: float = 0.0) -> World:
    """The particle grid tilted by TILT about its centre, its lowest corner DROP m up."""
    world = World(dt=DT)
    ground = world.add_body(Body("ground", type="static"))
    ground.add_shape(Box(9.0, 0.5, offset=(2.4, -0.25)))
    half = 0.5 * (GRID - 1) * SPACING
    c, s_ = math.cos(TILT), math.sin(TILT)
    lift = DROP + RADIUS + half * (c + s_)  # the centre's height: the lowest corner at DROP
    particles = []
    for i in range(GRID):
        for j in range(GRID):
            u, v = j * SPACING - half, i * SPACING - half
            p = world.add_body(
                Body(f"p{i}{j}", position=(x0 + c * u - s_ * v, lift + s_ * u + c * v))
            )
            p.add_shape(Circle(RADIUS, mass=PARTICLE, friction=0.8))
            particles.append(p)
    for a, b in spring_pairs(shear):  # rest length: as placed
        world.add_joint(SpringJoint(particles[a], particles[b], stiffness=k, damping=DAMPING))
    return world


RING = ([(0, j) for j in range(GRID)] + [(i, GRID - 1) for i in range(1, GRID)]
        + [(GRID - 1, j) for j in range(GRID - 2, -1, -1)] + [(i, 0) for i in range(GRID - 2, 0, -1)])  # fmt: skip


def area(world: World) -> float:
    """Area (m^2) inside the box's outer particles (shoelace formula); 1 m^2 at rest."""
    xy = np.array([world.bodies[1 + i * GRID + j].position for i, j in RING])
    x, y = xy[:, 0], xy[:, 1]
    return float(0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1))))


def mesh_lambda_max(shear: bool = True) -> float:
    """Largest eigenvalue of L, the sum of the springs' u u^T blocks at the rest shape (1)."""
    rest_xy = np.array([(j * SPACING, i * SPACING) for i in range(GRID) for j in range(GRID)])
    lap = np.zeros((2 * GRID * GRID, 2 * GRID * GRID))
    for a, b in spring_pairs(shear):
        u = rest_xy[b] - rest_xy[a]
        block = np.outer(u, u) / (u @ u)
        for p, q, sign in ((a, a, 1), (b, b, 1), (a, b, -1), (b, a, -1)):
            lap[2 * p : 2 * p + 2, 2 * q : 2 * q + 2] += sign * block
    return float(np.linalg.eigvalsh(lap).max())


AREA, ENERGY = "box area (m^2)", "energy K + U (J)"
lam_max = mesh_lambda_max()
k_grid_undamped = 4 * PARTICLE / (lam_max * DT**2)
k_grid = (4 - 2 * DAMPING * lam_max * DT / PARTICLE) * PARTICLE / (lam_max * DT**2)
runs, rows, curves = [], [], {}
for name, shear, k in (("with shear springs", True, STIFFNESS),
                       ("without shear springs", False, STIFFNESS),
                       ("with shear, k = 30 N/m", True, 30.0)):  # fmt: skip
    world = soft_box(shear=shear, k=k, x0=2.4 * len(runs))
    rec = record(world, 150, every=2, series={AREA: area, ENERGY: lambda w: w.energy()})
    runs.append(rec)
    a_s, e_s = np.array(rec.series[AREA]), np.array(rec.series[ENERGY])
    curves[name] = (np.array(rec.times), a_s)
    rows.append((name, len(world.joints), a_s.min(), a_s[-1], e_s[0] - e_s[-1]))
print(
    f"lambda_max = {lam_max:.4f}: k_max = {k_grid_undamped:.1f} N/m without damping, "
    f"{k_grid:.1f} N/m with c = {DAMPING} N s/m (the box uses {STIFFNESS:g} N/m)"
)
print_table(["soft box", "springs", "least area (m^2)", "area after 2.5 s (m^2)",
             "energy lost (J)"], rows, 4)  # fmt: skip
for frac in (0.95, 1.05):
    world = soft_box(k=frac * k_grid)
    peak = 0.0  # m/s: the fastest any particle went (the speed at one moment rises and falls)
    for _ in range(120):
        world.step()
        peak = max(peak, max(math.hypot(*b.velocity) for b in world.bodies[1:]))
    print(f"k = {frac} k_max = {frac * k_grid:.1f} N/m: fastest particle within 2 s {peak:.3g} m/s")

# %% [markdown]
# With the shear springs the box squashes on impact and springs back to within a few per cent
# of its area; without them it folds flat (nothing resists a square becoming a rhombus). Softer
# springs (30 N/m) let the impact turn cells inside out: the diagonal springs are then at their
# rest length again in the mirrored cell, nothing pushes back, and the box stays crumpled: a
# known failure of mass-spring meshes (stiffer springs, more particles, or an area-preserving
# force fix it). Above $k_{max}$ the mesh does not crumple, it explodes.

# %%
fig, axes = plt.subplots(1, 3, figsize=(16, 4.6))
ax = axes[0]
for frac, color in ((0.95, "C0"), (1.05, "C3")):
    ax.semilogy(DT * np.arange(1, len(stable[frac]) + 1), stable[frac], color=color,
                label=f"k = {frac} k_max" + (" (stopped: diverged)" if frac * K_MAX in stopped
                                               else ""))  # fmt: skip
ax.set(xlabel="t (s)", ylabel="energy / energy at the start (1)",
       title=f"two particles: k_max = 2 m / dt^2 = {K_MAX:.0f} N/m")  # fmt: skip
ax = axes[1]
ax.plot(np.arange(1, CHAIN + 1), 1000 * stretch, "o", color="C2", label="engine")
ax.plot(np.arange(1, CHAIN + 1), 1000 * expected, color="k", lw=1, label="(N - j + 1) m g / k")
ax.set(xlabel="spring j, from the top (count)", ylabel="stretch (mm)",
       title=f"hanging chain of {CHAIN}, k = {k_chain:g} N/m")  # fmt: skip
ax = axes[2]
for (name, (t_s, a_s)), color in zip(curves.items(), ("C0", "C1", "C4"), strict=True):
    ax.plot(t_s, a_s, color=color, label=name)
ax.axhline(1.0, color="k", ls=":", lw=1, label="rest area")
ax.set(xlabel="t (s)", ylabel=AREA, title="soft box dropped on a corner")
for a in axes:
    a.grid(alpha=0.3)
    a.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.16))
fig.tight_layout()
save_figure(fig, OUT / "soft_bodies.png", dpi=100)

gif = render_gif(runs, OUT / "soft_box.gif", fps=30, size_px=360, labels=list(curves),
                 panel=AREA, view=(-1.2, 6.6, -0.6, 2.6))  # fmt: skip
show_gif(gif)
print(f"wrote {len(runs[0])} frames to {gif.name}")

# %% [markdown]
# ## Exercises
#
# Predict first, then run the cell under the question, then open the answer.
#
# **1.** Make the two particles four times heavier (0.16 kg). What is the largest stable stiffness
# of the pair now?

# %%
for frac in (0.95, 1.05):
    heavy = World(gravity=(0.0, 0.0), dt=DT)
    a_e1 = heavy.add_body(Body("a"))
    a_e1.add_shape(Circle(RADIUS, mass=0.16))
    b_e1 = heavy.add_body(Body("b", position=(SPACING + 0.02, 0.0)))
    b_e1.add_shape(Circle(RADIUS, mass=0.16))
    heavy.add_joint(SpringJoint(a_e1, b_e1, rest_length=SPACING, stiffness=frac * 2 * 0.16 / DT**2))
    e0_e1 = heavy.energy()
    try:
        for _ in range(60):
            heavy.step()
        print(f"k = {frac} x {2 * 0.16 / DT**2:.0f} N/m: energy after 1 s "
              f"x {heavy.energy() / e0_e1:.3g}")  # fmt: skip
    except SimulationError:
        print(f"k = {frac} x {2 * 0.16 / DT**2:.0f} N/m: stopped as diverged at step {heavy.steps}")

# %% [markdown]
# <details><summary>Answer</summary>
#
# $k_{max} = 2m/\Delta t^2$ grows with the mass: $2 \times 0.16 \times 3600 = 1152$ N/m, four
# times 288. The run behaves exactly as with the light pair at 95% and 105% of its own limit
# (the same $\omega\Delta t$): bounded, then exploding, stopped at the same step. Heavier
# particles tolerate stiffer
# springs; halving $\Delta t$ would raise the limit four times.
#
# </details>
#
# **2.** Hang the chain with 16 particles instead of 8 (same $k$). How much longer does it get?

# %%
print(f"N = 16: m g N (N + 1) / (2 k) = {PARTICLE * G * 16 * 17 / (2 * k_chain):.4f} m, "
      f"N = 8: {PARTICLE * G * 8 * 9 / (2 * k_chain):.4f} m")  # fmt: skip

# %% [markdown]
# <details><summary>Answer</summary>
#
# The stretch grows as $N(N + 1)/2$: 136 against 36 spring-loads, 3.8 times: 0.8894 m instead of
# 0.2354 m. Each added particle loads every spring above it.
#
# </details>
