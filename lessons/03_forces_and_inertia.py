# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: percent
# ---

# %% [markdown]
# # 03 Forces and inertia
#
# Slides "Force", "Effects of Force", "Torque", "Effects of Torque", "Centre of Mass",
# "Moment of Inertia" and their worked examples.
#
# - a force accelerates the centre of mass: $\mathbf{f} = m\mathbf{a}$, i.e.
#   $\mathbf{a} = \mathbf{f} / m$, with forces summed as vectors, $\mathbf{f}_{total} = \sum_i \mathbf{f}_i$
# - a force acting off-centre also turns the body: $\tau = \mathbf{r} \times \mathbf{f}
#   = (r \sin\theta) f$, and $\tau = I\alpha$, i.e. $\alpha = \tau / I$
# - the centre of mass of point masses is $\mathbf{c} = \sum_i m_i \mathbf{r}_i / \sum_i m_i$
# - the moment of inertia about an axis is $I = \sum_i m_i r_i^2$, with $r_i$ the perpendicular
#   distance of mass $i$ to that axis; in a simulation the axis goes through the centre of mass
#
# The formulas live in `sandbox/mass.py`. This lesson checks the slides' two worked examples
# (one of them has an error), measures the moments of the standard 2D shapes against their
# closed forms, and then pushes a plate off-centre in the world to see $a = F/m$ and
# $\alpha = \tau / I$ come out of the simulation.

# %%
import math

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.patches import Polygon as PolygonPatch

from sandbox.body import Body
from sandbox.geometry import box_vertices
from sandbox.lessonkit import output_dir, print_table, save_figure
from sandbox.mass import (
    box_mass_properties,
    center_of_mass,
    circle_mass_properties,
    combine,
    moment_of_inertia,
    parallel_axis,
    polygon_mass_properties,
)
from sandbox.recording import Recording
from sandbox.render import render_gif
from sandbox.shapes import Box
from sandbox.world import World

# knobs
MASSES = (1.0, 2.0)  # kg, the slides' example
POSITIONS = (0.0, 0.6)  # m, along a line
PLATE = (2.0, 1.0)  # width, height of the pushed plate (m)
DENSITY = 1.0  # kg/m^2
FORCE = (0.0, 2.0)  # N, constant, world frame
LEVER = (0.8, 0.0)  # m, where the force acts, measured from the centre of mass
DURATION = 1.5  # s simulated
DT = 1.0 / 60.0  # s
GIF_EVERY = 1  # steps per animation frame (90 frames for 1.5 s at 60 Hz)

OUT = output_dir("03_forces_and_inertia")

# %% [markdown]
# ## The slides' worked examples
#
# **Centre of mass.** $m_1 = 1$ kg at $0$, $m_2 = 2$ kg at $0.6$ m:
# $c = (1 \times 0 + 2 \times 0.6) / (1 + 2) = 1.2 / 3 = 0.4$ m. The slide is right.
#
# **Moment of inertia.** The slide writes
# $\mathbf{c} = m_1 r_1^2 + m_2 r_2^2 = 1 \times 0.2^2 + 2 \times 0.4^2 = 0.36$ kg m$^2$.
# Two things are off. The result is a moment of inertia, so it should be labelled $I$, not
# $\mathbf{c}$. And the distances are swapped: about the centre of mass at $0.4$ m, mass $m_1$
# is $0.4$ m away and $m_2$ is $0.2$ m away, so
#
# $$I = 1 \times 0.4^2 + 2 \times 0.2^2 = 0.16 + 0.08 = 0.24 \text{ kg m}^2 .$$
#
# Which axis does give $0.36$? About an axis at $a$ the moment is
# $I(a) = 1\,a^2 + 2\,(0.6 - a)^2 = 3a^2 - 2.4a + 0.72$, and $I(a) = 0.36$ has two roots,
# $a = 0.2$ m and $a = 0.6$ m (through $m_2$ itself): both are $0.2$ m from the centre of mass,
# and indeed the parallel axis theorem gives $0.24 + 3 \times 0.2^2 = 0.36$. The centre of
# mass is where $I(a)$ is smallest, which is why the simulation spins bodies about it.

# %%
c = center_of_mass(MASSES, POSITIONS)
M = sum(MASSES)
rows = []
for a, note in [
    (c, "centre of mass (correct)"),
    (0.2, "gives the slide's 0.36"),
    (0.6, "gives the slide's 0.36 (through m2)"),
    (0.0, "through m1"),
]:
    r1, r2 = abs(POSITIONS[0] - a), abs(POSITIONS[1] - a)
    rows.append((a, r1, r2, moment_of_inertia(MASSES, POSITIONS, axis=a), note))
print(f"centre of mass c = (1 x 0 + 2 x 0.6) / (1 + 2) = {c:.4f} m   (slide: 0.4 m, correct)")
print_table(["axis x (m)", "r1 (m)", "r2 (m)", "I = m1 r1^2 + m2 r2^2 (kg m^2)", "axis"], rows)
i_cm = moment_of_inertia(MASSES, POSITIONS, axis=c)
print(f"slide: 1 x 0.2^2 + 2 x 0.4^2 = {1 * 0.2**2 + 2 * 0.4**2:.4f} kg m^2 (distances swapped)")
print(f"correct about c: 1 x 0.4^2 + 2 x 0.2^2 = {i_cm:.4f} kg m^2")
print(
    f"parallel axis check: I_c + M d^2 = {i_cm:.2f} + {M:.0f} x 0.2^2 = {parallel_axis(i_cm, M, 0.2):.4f}"
)

# %%
fig, (ax, bx) = plt.subplots(1, 2, figsize=(10, 4.4))
ax.plot(POSITIONS, [0, 0], color="0.5", lw=2, zorder=1)
for m, x, name in zip(MASSES, POSITIONS, ("m1 = 1 kg", "m2 = 2 kg"), strict=True):
    ax.scatter([x], [0], s=400 * m, color="tab:blue", zorder=3)
    ax.annotate(name, (x, 0), xytext=(0, 22), textcoords="offset points", ha="center")
ax.scatter([c], [0], marker="x", s=120, color="k", zorder=4)
ax.annotate("c = 0.4 m", (c, 0), xytext=(0, -26), textcoords="offset points", ha="center")
ax.axvline(c, color="tab:green", lw=2, label="axis through c: I = 0.24 kg m$^2$")
for a in (0.2, 0.6):
    ax.axvline(a, color="tab:red", ls="--", lw=1.5)
ax.plot([], [], color="tab:red", ls="--", label="axes at 0.2, 0.6 m: I = 0.36 kg m$^2$")
ax.set(xlim=(-0.2, 0.8), ylim=(-0.6, 0.6), xlabel="x (m)", yticks=[])
ax.set_title("slides' example: which axis?")
ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.16), fontsize=8, ncol=2)

a_grid = np.linspace(-0.1, 0.9, 201)
bx.plot(a_grid, [moment_of_inertia(MASSES, POSITIONS, axis=a) for a in a_grid], color="k",
        label="I(a) about an axis at a")  # fmt: skip
bx.scatter([c], [i_cm], color="tab:green", zorder=3, label="about c: 0.24 (correct)")
bx.scatter([0.2, 0.6], [0.36, 0.36], color="tab:red", zorder=3, label="0.36 (the slide's figure)")
bx.axhline(0.36, color="tab:red", ls=":", lw=1)
bx.set(xlabel="axis position a (m)", ylabel="I(a) (kg m$^2$)", title="I(a) = 3a$^2$ - 2.4a + 0.72")
bx.legend(fontsize=8)
fig.tight_layout()
save_figure(fig, OUT / "worked_examples.png", dpi=100)

# %% [markdown]
# ## Moments of the standard 2D shapes
#
# For a solid body the sum becomes an integral, $I = \int \rho\, r^2\, dA$. Evaluated for the
# usual shapes (about the centroid; all given a mass of 1 kg so that only the *distribution*
# differs):
#
# | shape | closed form |
# | --- | --- |
# | disc, radius $r$ | $I = m r^2 / 2$ |
# | box $w \times h$ | $I = m (w^2 + h^2) / 12$ |
# | right triangle, legs $a, b$ | centroid at $(a/3, b/3)$, $I = m (a^2 + b^2) / 18$ |
# | regular $n$-gon, circumradius $R$ | $I = m R^2 (1 + 2\cos^2(\pi/n)) / 6$ |
# | L-shape from two boxes | parallel axis theorem: $I = \sum_k (I_k + m_k d_k^2)$ |
#
# `polygon_mass_properties` knows none of these: it cuts any polygon into triangles and adds
# them up. The table compares the two.

# %%
R = 0.5  # m, the size of the shapes


def ngon(n: int, radius: float) -> np.ndarray:
    k = np.arange(n)
    return radius * np.stack([np.cos(2 * np.pi * k / n), np.sin(2 * np.pi * k / n)], axis=1)


L_VERTS = np.array([(0, 0), (0.9, 0), (0.9, 0.3), (0.3, 0.3), (0.3, 0.9), (0, 0.9)])
L_DENSITY = 1.0 / (0.9 * 0.3 + 0.3 * 0.6)  # kg/m^2 that makes the L weigh 1 kg
l_two = combine(  # the L as a 0.9 x 0.3 foot plus a 0.3 x 0.6 upright
    [
        box_mass_properties(0.9, 0.3, L_DENSITY, offset=(0.45, 0.15)),
        box_mass_properties(0.3, 0.6, L_DENSITY, offset=(0.15, 0.6)),
    ]
)

shapes = [  # name, outline, computed by triangles, closed form (all 1 kg)
    ("disc r=0.5", ngon(64, R), circle_mass_properties(R, mass=1.0).moment, R**2 / 2),
    ("box 1 x 0.5", box_vertices(1.0, 0.5), None, (1.0 + 0.25) / 12),
    ("triangle 1, 0.5", np.array([(0, 0), (1.0, 0), (0, 0.5)]), None, (1.0 + 0.25) / 18),
    *[
        (f"{n}-gon R=0.5", ngon(n, R), None, R**2 * (1 + 2 * math.cos(math.pi / n) ** 2) / 6)
        for n in (3, 5, 8)
    ],
    ("L (two boxes)", L_VERTS, l_two.moment, None),
]
rows, names, computed, formula = [], [], [], []
for name, verts, given, closed in shapes:
    by_triangles = polygon_mass_properties(verts, mass=1.0).moment
    if given is None:  # polygons: triangles vs the closed form
        i_num, i_ref, how = by_triangles, closed, "triangles vs formula"
    elif closed is None:  # the L: one polygon vs the parallel axis sum of two boxes
        i_num, i_ref, how = by_triangles, given, "polygon vs two boxes"
    else:  # the disc: its own formula; the 64-gon beside it is only drawn
        i_num, i_ref, how = given, closed, "circle_mass_properties vs formula"
    names.append(name)
    computed.append(i_num)
    formula.append(i_ref)
    rows.append((name, i_num, i_ref, f"{abs(i_num - i_ref) / i_ref:.1e}", how))
print_table(["shape (1 kg)", "I computed (kg m^2)", "I formula", "rel. diff", "compared"], rows, 6)
centroid_tri = polygon_mass_properties(shapes[2][1], mass=1.0).centroid
print(f"right triangle centroid = ({centroid_tri[0]:.6f}, {centroid_tri[1]:.6f}) m = (1/3, 0.5/3)")
print(f"L-shape: m = 1 kg, centroid = ({l_two.centroid[0]:.4f}, {l_two.centroid[1]:.4f}) m")

# %%
fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 4), gridspec_kw={"width_ratios": [1.2, 1]})
for k, (name, verts, _, _) in enumerate(shapes):
    shift = np.array([1.3 * (k % 4), -1.3 * (k // 4)])
    props = polygon_mass_properties(verts, mass=1.0)
    ax.add_patch(PolygonPatch(verts - props.centroid + shift, alpha=0.5, color=f"C{k}"))
    ax.plot(*shift, "k+")
    ax.annotate(name, shift + (0, -0.62), ha="center", fontsize=8)
ax.set(xlim=(-0.8, 4.6), ylim=(-2.1, 0.7), aspect="equal", title="centroid (+) of each shape")
ax.axis("off")
x = np.arange(len(names))
bx.bar(x - 0.2, computed, 0.4, label="computed (sandbox.mass)")
bx.bar(x + 0.2, formula, 0.4, label="closed form / two boxes", hatch="//", alpha=0.6)
bx.set_xticks(x, names, rotation=35, ha="right", fontsize=8)
bx.set(ylabel="I about the centroid, m = 1 kg (kg m$^2$)", title="same mass, different spread")
bx.legend(fontsize=8)
fig.tight_layout()
save_figure(fig, OUT / "shape_moments.png", dpi=100)

# %% [markdown]
# ## f = m a and tau = r x f in the world
#
# A plate (the knobs `PLATE`, `DENSITY`) floats without gravity. Every step a constant force
# $\mathbf{f}$ = `FORCE` pushes it at a point off the centre of mass. The world sums the forces
# on each body and their torques about its centre of mass, then integrates
#
# $$\mathbf{a} = \mathbf{f} / m, \qquad \alpha = \tau / I, \qquad
# \tau = \mathbf{r} \times \mathbf{f} = r_x f_y - r_y f_x .$$
#
# Two runs with the same force:
#
# 1. **lever fixed in the world**: the force acts at $\mathbf{c} + \mathbf{r}$ with
#    $\mathbf{r}$ = `LEVER` held fixed in the world (a pusher that follows the plate). Then $\tau$
#    is constant, so $\omega(t)$ is a straight line of slope $\tau / I$.
# 2. **lever fixed in the body**: the force acts at the material point that started at
#    $\mathbf{c} + \mathbf{r}$, which turns with the plate. Now $\tau = (r \sin\theta) f$ changes
#    with the angle $\theta$ between $\mathbf{r}$ and $\mathbf{f}$: it falls to zero when the lever
#    lines up with the force (plate turned by $\pi/2$), and beyond that it brakes the plate.
#
# In both runs the net force is the same, so the centre of mass accelerates identically:
# $v(t)$ is a straight line of slope $F / m$ wherever the force acts.
#
# In 2D the torque and the angular acceleration both point along $z$, so the slide's "angular
# acceleration parallel to torque" always holds here. In 3D it holds only for a torque along a
# principal axis of the body, symmetric or not (lesson 15 measures the angle between them).

# %%
F = np.asarray(FORCE, dtype=float)
r_lever = np.asarray(LEVER, dtype=float)
steps = int(round(DURATION / DT))
OMEGA = "omega (rad/s)"  # the series drawn beside the animation


def make_world(x0: float = 0.0) -> tuple[World, Body]:
    world = World(gravity=(0.0, 0.0), dt=DT)
    plate = world.add_body(Body(name="plate", type="dynamic", position=(x0, 0.0), angle=0.0))
    plate.add_shape(Box(width=PLATE[0], height=PLATE[1], density=DENSITY))
    return world, plate


def run(lever_in_body: bool) -> tuple[Recording, dict]:
    """Push the plate for DURATION s; returns the recording and per-step series. The body-lever
    plate starts 3 m to the right, so that the animation shows the two side by side."""
    world, plate = make_world(3.0 if lever_in_body else 0.0)
    anchor = plate.local_point(np.asarray(plate.center_of_mass) + r_lever)  # body frame
    rec = Recording.from_world(world, draw="forces")  # keep the applied force for drawing
    rec.capture(world, **{OMEGA: 0.0})
    out = {k: [] for k in ("t", "omega", "vy", "tau", "angle")}
    for _ in range(steps):
        c = np.asarray(plate.center_of_mass)
        point = plate.world_point(anchor) if lever_in_body else c + r_lever
        r = point - c
        out["tau"].append(r[0] * F[1] - r[1] * F[0])  # slides, "Torque": tau = r x f
        plate.apply_force(F, point=point)  # cleared again after the step
        world.step()
        out["t"].append(world.time)
        out["omega"].append(plate.angular_velocity)
        out["vy"].append(plate.velocity[1])
        out["angle"].append(plate.angle)
        rec.capture(world, **{OMEGA: plate.angular_velocity})
    return rec, {k: np.asarray(v) for k, v in out.items()}


world_rec, fixed = run(lever_in_body=False)
body_rec, turning = run(lever_in_body=True)

_, plate = make_world()
theory = box_mass_properties(PLATE[0], PLATE[1], DENSITY)
tau = r_lever[0] * F[1] - r_lever[1] * F[0]  # slides, "Torque": tau = r x f
alpha_theory = tau / theory.moment  # slides, "Effects of Torque": alpha = tau / I
a_theory = F[1] / theory.mass  # slides, "Effects of Force": a = f / m
alpha_fit = np.polyfit(fixed["t"], fixed["omega"], 1)[0]
a_fit = np.polyfit(fixed["t"], fixed["vy"], 1)[0]
a_fit_body = np.polyfit(turning["t"], turning["vy"], 1)[0]
# lever in the body: each step's change of omega against that step's tau(t) / I
alpha_steps = np.diff(np.concatenate([[0.0], turning["omega"]])) / DT
worst = float(np.max(np.abs(alpha_steps - turning["tau"] / theory.moment)))


def rel(x: float, ref: float) -> str:
    return f"{abs(x - ref) / abs(ref):.1e}"


print_table(
    ["quantity", "theory", "world", "rel. diff"],
    [
        ("m = rho w h (kg)", theory.mass, plate.mass, rel(plate.mass, theory.mass)),
        ("I = m (w^2 + h^2) / 12 (kg m^2)", theory.moment, plate.moment,
         rel(plate.moment, theory.moment)),
        ("tau = r x f vs I alpha measured (N m)", tau, plate.moment * alpha_fit,
         rel(plate.moment * alpha_fit, tau)),
        ("a = F / m, lever in world (m/s^2)", a_theory, a_fit, rel(a_fit, a_theory)),
        ("a = F / m, lever in body (m/s^2)", a_theory, a_fit_body, rel(a_fit_body, a_theory)),
        ("alpha = tau / I, lever in world (rad/s^2)", alpha_theory, alpha_fit,
         rel(alpha_fit, alpha_theory)),
    ],
    6,
)  # fmt: skip
print(f"lever in body: max |d omega / dt - tau(t) / I| over {steps} steps = {worst:.1e} rad/s^2")
k_peak = int(np.argmax(turning["omega"]))
print(
    f"lever in body: omega peaks at t = {turning['t'][k_peak]:.3f} s, angle = "
    f"{turning['angle'][k_peak]:.3f} rad (pi/2 = {math.pi / 2:.3f}: r along f, tau = 0)"
)

# %%
fig, axes = plt.subplots(1, 3, figsize=(13, 3.8))
t_line = np.concatenate([[0.0], fixed["t"]])
ax = axes[0]
ax.plot(
    t_line, alpha_theory * t_line, "k--", lw=1, zorder=3, label=r"theory $\omega = (\tau / I)\, t$"
)
ax.plot(fixed["t"], fixed["omega"], color="C0", label="lever fixed in world")
ax.plot(turning["t"], turning["omega"], color="C1", label="lever fixed in body")
ax.set(xlabel="t (s)", ylabel=r"$\omega$ (rad/s)", title=f"slope tau / I = {alpha_theory:.3f}")
ax.legend(fontsize=8)
ax = axes[1]
ax.plot(t_line, a_theory * t_line, "k--", lw=1, zorder=3, label=r"theory $v = (F / m)\, t$")
ax.plot(fixed["t"], fixed["vy"], color="C0", label="lever fixed in world")
ax.plot(turning["t"], turning["vy"], color="C1", ls=":", lw=2, label="lever fixed in body")
ax.set(xlabel="t (s)", ylabel="$v_y$ (m/s)", title=f"slope F / m = {a_theory:.3f}")
ax.legend(fontsize=8)
ax = axes[2]
ax.plot(fixed["t"] - DT, fixed["tau"], color="C0", label=r"$\tau = r \times f$ (world lever)")
ax.plot(
    turning["t"] - DT, turning["tau"], color="C1", label=r"$\tau = (r \sin\theta) f$ (body lever)"
)
ax.set(xlabel="t (s)", ylabel=r"$\tau$ (N m)", title="torque about the centre of mass")
ax.legend(fontsize=8)
fig.tight_layout()
save_figure(fig, OUT / "force_and_torque.png", dpi=100)

# %% [markdown]
# The animation shows both runs side by side, with $\omega(t)$ beside them: the two plates rise
# together (same $\mathbf{f}$, same $m$) but only the one pushed on a world-fixed lever keeps
# spinning up. The force is drawn as the engine applies it to the body (the `forces` debug
# layer): the straight arrow is $\mathbf{f}$ moved to the centre of mass, the curved one the
# torque $\tau = \mathbf{r}\times\mathbf{f}$ that moving it there leaves (the same push, as
# far as the motion is concerned). The curved arrow of the body-fixed lever shrinks to nothing
# as its lever turns into line with the force.

# %%
gif = render_gif(
    [world_rec, body_rec],
    OUT / "off_centre_push.gif",
    fps=30,
    size_px=360,
    labels=["lever fixed in world", "lever fixed in body"],
    panel=OMEGA,
    trail=True,
    stride=GIF_EVERY,
    draw="forces",
)
print(f"wrote {len(world_rec)} frames to {gif.name}")
