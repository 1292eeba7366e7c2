# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: percent
# ---

# %% [markdown]
# # 02 Three ways to store a 2D rotation
#
# Slides "Angular Motion", "2D Angular Motion" (options 1-3) and "Comparison of 2D Rotation
# Structures". The angular equations mirror the linear ones,
#
# $$\varphi(t + \Delta t) \approx \varphi(t) + \omega(t)\Delta t, \qquad
#   \omega(t + \Delta t) \approx \omega(t) + \alpha(t)\Delta t ,$$
#
# and only the orientation $\varphi$ has a choice of representation ($\omega$ and $\alpha$ stay
# scalars in 2D):
#
# | option | stored | update | floats |
# | --- | --- | --- | --- |
# | 1 scalar angle | $\varphi$, reduced to $[-\pi, \pi]$ | $\varphi \leftarrow \varphi + \omega\Delta t$ (then $\pm 2\pi$) | 1 |
# | 2 rotation matrix | $\Phi = \begin{bmatrix}\cos\varphi & -\sin\varphi \\ \sin\varphi & \cos\varphi\end{bmatrix}$ | $\Phi \leftarrow \Phi\,R(\omega\Delta t)$ | 4 |
# | 3 unit complex number | $z = \cos\varphi + i\sin\varphi = e^{i\varphi}$ | $z \leftarrow z\,e^{i\omega\Delta t}$ | 2 |
#
# The three live in `sandbox/orientation.py` (plain-Python classes, and compiled kernels over the
# world's `(n, 4)` orientation array). This lesson spins one body for many steps in all three,
# measures drift, agreement and cost, and checks the slides' comparison table against the numbers.

# %%
import math
import timeit
from decimal import Decimal
from fractions import Fraction
from itertools import accumulate

import matplotlib.pyplot as plt
import numpy as np

from sandbox import orientation
from sandbox.body import Body
from sandbox.lessonkit import output_dir, print_table, save_figure
from sandbox.recording import record
from sandbox.render import render_gif
from sandbox.shapes import Box
from sandbox.world import World

# knobs
PHI0 = 0.2  # rad, initial orientation
OMEGA0 = 1.3  # rad/s, spin during the first SWITCH steps
ALPHA = 0.01  # rad/s^2, constant angular acceleration after SWITCH steps
DT = 1.0 / 60.0  # s
SWITCH = 3_000  # steps at constant omega before the angular acceleration starts
STEPS = 100_000  # steps of the long (drift) run: about 28 minutes of simulated time
AGREE_STEPS = 10_000  # steps after which the three must agree to 1e-9 rad
WORLD_STEPS = 6_000  # steps of the world-level check
SAMPLE = 500  # steps between drift samples
N_BODIES = 10_000  # bodies in the compiled-kernel timing
TOLERANCE = 1e-9  # rad

OUT = output_dir("02_rotation_2d")
NAMES = ("angle", "matrix", "complex")
COLOR = {"angle": "C0", "matrix": "C3", "complex": "C2"}

# %% [markdown]
# ## A slip on the complex-number slide
#
# Option 3 writes the orientation as
# $\boldsymbol{\varphi} = e^{i\varphi\Delta t} = \cos\varphi\Delta t + i\sin\varphi\Delta t$.
# That mixes two things: $\varphi\Delta t$ has units of rad s and is not an angle. The
# **orientation** is $z = e^{i\varphi} = \cos\varphi + i\sin\varphi$; the **update** multiplies
# by the rotation of one step, $e^{i\omega\Delta t}$, and because multiplying unit complex
# numbers adds their angles,
#
# $$z(t + \Delta t) = e^{i\varphi}\,e^{i\omega\Delta t} = e^{i(\varphi + \omega\Delta t)} ,$$
#
# which is option 1's update in disguise. (The slide's next line,
# $\boldsymbol{\varphi}(t + \Delta t) \approx \boldsymbol{\varphi}(t)\,e^{i\omega(t)\Delta t}$,
# is right.)

# %%
z_slide = complex(math.cos(PHI0 * DT), math.sin(PHI0 * DT))  # the slide's e^{i phi dt}
z = complex(math.cos(PHI0), math.sin(PHI0))  # the orientation e^{i phi}
z_next = z * complex(math.cos(OMEGA0 * DT), math.sin(OMEGA0 * DT))  # one update
print(f"phi = {PHI0} rad, omega = {OMEGA0} rad/s, dt = {DT:.6f} s")
print(f"slide's e^(i phi dt) encodes the angle {math.atan2(z_slide.imag, z_slide.real):.6f} rad")
print(f"e^(i phi) encodes {math.atan2(z.imag, z.real):.6f} rad (the orientation)")
print(
    f"e^(i phi) e^(i omega dt) encodes {math.atan2(z_next.imag, z_next.real):.6f} rad "
    f"= phi + omega dt = {PHI0 + OMEGA0 * DT:.6f}"
)

# %% [markdown]
# ## Spinning one body for 100,000 steps
#
# The body turns at $\omega_0$ = `OMEGA0` for `SWITCH` steps, then speeds up at $\alpha$ =
# `ALPHA` (explicit Euler: $\omega_{k+1} = \omega_k + \alpha\Delta t$). Every representation is
# given the same increments $\omega_k\Delta t$. The **exact** orientation after $n$ steps is
# their sum, $\varphi_0 + \sum_k \omega_k\Delta t$, computed without rounding (each float
# increment is a whole number of units of $2^{-80}$ rad, so Python integers add them exactly;
# $2\pi$ is taken to 40 digits for the reduction to $[-\pi, \pi]$).
#
# **Drift** measures how far a stored orientation has strayed from being a rotation at all:
# $\big||z| - 1\big|$ for complex numbers, $\|\Phi^T\Phi - I\|_F$ for matrices (a scalar angle
# is always a rotation: its drift is 0). Each multiplication rounds, so both slowly stop being
# unit length / orthogonal; renormalising every step, $z' = z / |z|$ (slides) or Gram-Schmidt on
# $\Phi$'s first column, pulls them back.

# %%
omegas = np.empty(STEPS)
w = OMEGA0
for k in range(STEPS):
    omegas[k] = w
    if k >= SWITCH:
        w += ALPHA * DT  # omega(t + dt) = omega(t) + alpha dt
increments = omegas * DT  # the exact float increments every representation adds

UNIT = 2.0**80  # exact reference in integer units of 2^-80 rad
TWO_PI = int(Decimal("6.283185307179586476925286766559005768394") * int(UNIT))
scaled = [PHI0 * UNIT, *(increments * UNIT)]
assert all(x.is_integer() for x in scaled)  # every float increment is a whole number of units
exact_units = list(accumulate(int(x) for x in scaled))[1:]  # phi_0 + sum, after each step


def exact_angle(k: int) -> float:
    """The exact orientation after step k (0-based), reduced to [-pi, pi] (rad)."""
    r = exact_units[k] % TWO_PI
    if 2 * r > TWO_PI:
        r -= TWO_PI
    return float(Fraction(r, int(UNIT)))


samples = np.arange(SAMPLE - 1, STEPS, SAMPLE)  # 0-based step indices that are sampled


def angle_error(angle: float, k: int) -> float:
    return abs(orientation.wrap_angle(angle - exact_angle(k)))


def spin_float64(name: str, renormalise: bool) -> dict:
    """The library's plain-Python class for ``name``; samples of drift, angle error; angles."""
    rep = orientation.make_orientation(name, PHI0)
    drift, error, first = [], [], np.empty(AGREE_STEPS)
    for k in range(STEPS):
        rep.integrate(omegas[k], DT)  # slides, options 1-3
        if renormalise:
            rep.renormalise()
        if k < AGREE_STEPS:
            first[k] = rep.angle()
        if k % SAMPLE == SAMPLE - 1:
            drift.append(rep.drift())
            error.append(angle_error(rep.angle(), k))
    return {"drift": np.array(drift), "error": np.array(error), "angles": first}


runs = {}
for name in NAMES:
    for renormalise in (False, True) if name != "angle" else (False,):
        runs[name, "float64", renormalise] = spin_float64(name, renormalise)

# %% [markdown]
# In exact arithmetic every update is a rotation, so all of the drift comes from rounding. In
# double precision it stays tiny (a few $10^{-13}$ after 100,000 steps, harmless for drawing),
# and the plot shows how it accumulates. While $\omega$ is constant the *same* rounded
# $e^{i\omega\Delta t}$ is applied every step, and the rounded cosine and sine do not have length
# exactly 1 (the excess, computed exactly with fractions, is printed below), so the error adds up
# linearly, step after step: $|z_n| \approx 1 + n\varepsilon$, and for a matrix scaled by
# $1 + n\varepsilon$, $\|\Phi^T\Phi - I\|_F \approx 2\sqrt{2}\,n\varepsilon$. Once
# $\omega$ changes every step the roundings have varying signs and the drift only wanders. To
# see drift that matters, two experiments:
#
# 1. **single precision** (`float32`, as GPUs and many game engines store transforms): every
#    rounding is $2^{29} \approx 5\times10^{8}$ times larger;
# 2. **a cheap, inexact update**: replacing $e^{i\omega\Delta t}$ by its small-angle
#    approximation $1 + i\omega\Delta t$ (no trigonometry). Its length is
#    $\sqrt{1 + \omega^2\Delta t^2} > 1$, so $|z|$ grows by that factor *every step*,
#    exponentially. Renormalising then fixes the length, but not the angle: each step turns by
#    $\arctan\omega\Delta t$ instead of $\omega\Delta t$, an error of about $(\omega\Delta t)^3 / 3$
#    per step that no renormalisation can see.

# %%
f32 = np.float32
PI32, TWO_PI32 = f32(math.pi), f32(2.0 * math.pi)


def spin_float32(name: str, renormalise: bool) -> dict:
    """The same updates with every stored number in single precision (float32)."""
    c0, s0 = f32(math.cos(PHI0)), f32(math.sin(PHI0))
    phi = f32(PHI0)
    zr, zi = c0, s0
    m00, m01, m10, m11 = c0, -s0, s0, c0
    one = f32(1.0)
    drift, error = [], []
    for k in range(STEPS):
        d = f32(increments[k])
        if name == "angle":
            phi = phi + d  # option 1, then reduce by 2 pi
            if phi > PI32:
                phi = phi - TWO_PI32
            elif phi < -PI32:
                phi = phi + TWO_PI32
        else:
            c, s = f32(math.cos(d)), f32(math.sin(d))
            if name == "complex":  # option 3: z e^{i d}
                zr, zi = zr * c - zi * s, zr * s + zi * c
                if renormalise:
                    inv = one / np.sqrt(zr * zr + zi * zi)
                    zr, zi = zr * inv, zi * inv
            else:  # option 2: Phi R(d)
                m00, m01 = m00 * c + m01 * s, m01 * c - m00 * s
                m10, m11 = m10 * c + m11 * s, m11 * c - m10 * s
                if renormalise:  # Gram-Schmidt on the first column
                    inv = one / np.sqrt(m00 * m00 + m10 * m10)
                    m00, m10 = m00 * inv, m10 * inv
                    m01, m11 = -m10, m00
        if k % SAMPLE == SAMPLE - 1:
            if name == "angle":
                dr, ang = 0.0, float(phi)
            elif name == "complex":
                dr, ang = abs(math.hypot(zr, zi) - 1.0), math.atan2(zi, zr)
            else:
                m = np.array([[m00, m01], [m10, m11]], dtype=float)
                dr, ang = float(np.linalg.norm(m.T @ m - np.eye(2))), math.atan2(m10, m00)
            drift.append(dr)
            error.append(angle_error(ang, k))
    return {"drift": np.array(drift), "error": np.array(error)}


def spin_small_angle(renormalise: bool) -> dict:
    """Complex numbers updated by 1 + i omega dt (the small-angle shortcut), in double precision.

    Without renormalisation |z| soon exceeds the largest float (about 1.8e308): the run stops
    there (``overflow`` is that step) and the remaining samples are NaN.
    """
    z = complex(math.cos(PHI0), math.sin(PHI0))
    drift, error, overflow = [], [], None
    for k in range(STEPS):
        z = z * complex(1.0, increments[k])  # e^{i d} ~ 1 + i d: cheap, but |1 + i d| > 1
        if renormalise:
            z = z / abs(z)
        if max(abs(z.real), abs(z.imag)) > 1e300:  # |z| is about to overflow
            overflow = k
            break
        if k % SAMPLE == SAMPLE - 1:
            drift.append(abs(abs(z) - 1.0))
            error.append(angle_error(math.atan2(z.imag, z.real), k))
    missing = len(samples) - len(drift)
    drift, error = drift + [math.nan] * missing, error + [math.nan] * missing
    return {"drift": np.array(drift), "error": np.array(error), "overflow": overflow}


for name in NAMES:
    for renormalise in (False, True) if name != "angle" else (False,):
        runs[name, "float32", renormalise] = spin_float32(name, renormalise)
for renormalise in (False, True):
    runs["complex", "1 + i w dt", renormalise] = spin_small_angle(renormalise)

c0, s0 = math.cos(OMEGA0 * DT), math.sin(OMEGA0 * DT)  # the rounded e^{i omega0 dt}
excess = float(Fraction(c0) ** 2 + Fraction(s0) ** 2 - 1) / 2  # |e^{i omega0 dt}| - 1, exactly
k_sw = int(np.searchsorted(samples, SWITCH - 1))  # the sample at (or just after) SWITCH steps
n_sw = int(samples[k_sw]) + 1
drift_c = runs["complex", "float64", False]["drift"][k_sw]
drift_m = runs["matrix", "float64", False]["drift"][k_sw]
print(
    f"rounded e^(i omega0 dt) has length 1 + {excess:.3e}; x {n_sw:,} steps = {n_sw * excess:.3e}"
)
print(
    f"measured drift after {n_sw:,} steps: complex {drift_c:.3e}, "
    f"matrix {drift_m:.3e} (= 2 sqrt 2 x {drift_m / (2 * math.sqrt(2)):.3e})"
)


def fmt(x: float) -> str:
    return "overflow" if not math.isfinite(x) else f"{x:.2e}"


rows = []
for (name, precision, renormalise), r in runs.items():
    rows.append(
        (name, precision, "yes" if renormalise else "no", fmt(r["drift"][-1]),
         fmt(r["drift"].max()), fmt(r["error"][-1]), fmt(r["error"].max()))
    )  # fmt: skip
print(f"after {STEPS:,} steps (omega from {OMEGA0} to {omegas[-1]:.2f} rad/s):")
print_table(
    ["stored as", "arithmetic", "renormalised", "drift at end", "max drift",
     "angle error at end (rad)", "max angle error (rad)"],
    rows,
)  # fmt: skip
k_over = runs["complex", "1 + i w dt", False]["overflow"]
lag = float(np.sum(increments - np.arctan(increments)))  # sum of (omega dt - arctan omega dt)
print(
    f"1 + i w dt without renormalisation: |z| passes 1e300 (about to overflow) at step {k_over:,} "
    f"(t = {(k_over + 1) * DT:.0f} s); with renormalisation the body has turned "
    f"{lag:.1f} rad ({lag / (2 * math.pi):.1f} turns) too little after {STEPS:,} steps"
)

# %%
t_samples = (samples + 1) * DT
fig, axes = plt.subplots(1, 3, figsize=(16, 7.0))


def positive(t: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The samples a log axis can show: an exact 0 (or an overflow) is left out, not faked."""
    ok = np.isfinite(y) & (y > 0) & (y < 1e6)
    return t[ok], y[ok]


ax = axes[0]
for name in ("matrix", "complex"):
    for renormalise, style in ((False, "-"), (True, ".")):
        d = runs[name, "float64", renormalise]["drift"]
        zeros = int(np.sum(d == 0))
        tag = f"renormalised ({zeros} of {len(d)} samples exactly 0)" if renormalise else "raw"
        ax.semilogy(*positive(t_samples, d), style, color=COLOR[name], ms=3,
                    label=f"{name}, {tag}")  # fmt: skip
ax.plot([], [], color=COLOR["angle"], label="angle: drift always exactly 0 (no log point)")
ax.set(xlabel="t (s)", ylabel="drift (1)", title=f"double precision, {STEPS:,} steps")
ax.set_ylim(1e-18, 1e-8)
ax = axes[1]
for (name, precision, renormalise), r in runs.items():
    if precision == "float64" or name == "angle":
        continue
    color = COLOR[name] if precision == "float32" else "C4"
    tag = f"{name} {precision}, {'renormalised' if renormalise else 'raw'}"
    if precision == "1 + i w dt" and renormalise:
        tag += f" ({int(np.sum(r['drift'] == 0))} samples exactly 0)"
    ax.semilogy(*positive(t_samples, r["drift"]), ":" if renormalise else "-", color=color,
                label=tag)  # fmt: skip
ax.set(xlabel="t (s)", ylabel="drift (1)", title="single precision, and the 1 + i w dt shortcut")
ax.set_ylim(1e-17, 1e4)
ax.annotate(
    f"1 + i w dt, raw: |z| grows every step,\npasses 1e300 at t = {(k_over + 1) * DT:.0f} s",
    (t_samples[np.argmax(runs["complex", "1 + i w dt", False]["drift"] > 1e3)], 1e3),
    xytext=(0.25, 0.93), textcoords="axes fraction", fontsize=7, va="top", color="C4",
    arrowprops={"arrowstyle": "->", "color": "C4"},
)  # fmt: skip
ax = axes[2]
for (name, precision, renormalise), r in runs.items():
    if not renormalise and name != "angle":
        continue  # angle error of the renormalised runs (raw ones look the same, see the table)
    color = COLOR[name] if precision != "1 + i w dt" else "C4"
    ls = {"float64": "-", "float32": "--", "1 + i w dt": "-."}[precision]
    wide = name == "matrix"  # the matrix drawn wide and pale under the complex: they coincide
    ax.semilogy(*positive(t_samples, r["error"]), ls, color=color, lw=3.5 if wide else 1.2,
                alpha=0.45 if wide else 1.0, label=f"{name} {precision}")  # fmt: skip
ax.set(xlabel="t (s)", ylabel="|angle - exact| (rad)", title="angle error (renormalised runs)")
for ax in axes:
    ax.axvline(SWITCH * DT, color="0.6", lw=0.8)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.12))
fig.tight_layout()
save_figure(fig, OUT / "drift.png", dpi=100)

# %% [markdown]
# ### The other side of $1 + i\omega\Delta t$
#
# The shortcut looks hopeless above because this run spins fast: by the end
# $\omega\Delta t = 0.29$ rad per step. Yet Box2D v3 turns every body exactly this way
# (`b2IntegrateRotation`: $z \leftarrow (z + i\,\omega\Delta t\,z) / |z + i\,\omega\Delta t\,z|$,
# no cosine, no sine), and it is a sound choice there. Once renormalised, a step turns by
# $\arctan\omega\Delta t$ instead of $\omega\Delta t$, short by
# $\omega\Delta t - \arctan\omega\Delta t = (\omega\Delta t)^3/3 - (\omega\Delta t)^5/5 + \dots$:
# the spin comes out slow by a *fraction* $(\omega\Delta t)^2/3$. Box2D takes small steps (4
# substeps per 60 Hz frame, $\Delta t = 1/240$ s) and caps a substep's turn at $\pi/4$ rad, so
# for everyday spins the error is far below what anyone sees; a fast wheel is where it shows.

# %%
CASES_1IW = [  # (what, omega rad/s, dt s)
    ("this lesson at the start", OMEGA0, DT),
    ("this lesson at the end", omegas[-1], DT),
    ("a box tumbling, 60 Hz", 10.0, 1 / 60),
    ("a box tumbling, Box2D substep", 10.0, 1 / 240),
    ("a wheel at 10 turns/s, Box2D substep", 20 * math.pi, 1 / 240),
]
rows = []
for what, w_case, dt_case in CASES_1IW:
    x_step = w_case * dt_case
    lag = x_step - math.atan(x_step)  # rad lost per step, exactly
    seconds_to_degree = math.radians(1.0) / (lag / dt_case)
    rows.append((what, f"{x_step:.4f}", f"{lag:.2e}", f"{x_step**3 / 3:.2e}",
                 f"{lag / x_step:.2e}", f"{seconds_to_degree:.3g}"))  # fmt: skip
print_table(["case", "omega dt (rad)", "lag per step (rad)", "(omega dt)^3 / 3",
             "spin rate error (1)", "s to lag 1 degree"], rows)  # fmt: skip

fig, ax = plt.subplots(figsize=(8, 4.2))
xs = np.geomspace(1e-3, 1.0, 200)
ax.loglog(xs, xs - np.arctan(xs), color="0.5", lw=3, alpha=0.6,
          label=r"lag per step, $\omega\Delta t - \arctan\omega\Delta t$")  # fmt: skip
ax.loglog(xs, xs**3 / 3, "k:", label=r"$(\omega\Delta t)^3 / 3$")
for k, (what, w_case, dt_case) in enumerate(CASES_1IW):
    x_step = w_case * dt_case
    ax.loglog([x_step], [x_step - math.atan(x_step)], "o", color=f"C{k}", label=what)
ax.set(xlabel=r"$\omega\Delta t$ per step (rad)", ylabel="angle lost per step (rad)",
       title="renormalised 1 + i w dt: the turn it misses each step")  # fmt: skip
ax.grid(alpha=0.3, which="both")
ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.0, 1.0))
fig.tight_layout()
save_figure(fig, OUT / "small_angle_update.png", dpi=100)

# %% [markdown]
# ## Do the three agree?
#
# With renormalisation, over the first `AGREE_STEPS` steps, the largest difference between any
# two representations' angles (and against the exact sum):

# %%
a = {name: runs[name, "float64", name != "angle"]["angles"] for name in NAMES}
exact_first = np.array([exact_angle(k) for k in range(AGREE_STEPS)])


def gap(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    return np.abs(np.angle(np.exp(1j * (x - y))))  # difference of angles, wrapped


pairs = [("angle", "matrix"), ("angle", "complex"), ("matrix", "complex")]
rows = [
    (f"{p} vs {q}", f"{gap(a[p], a[q]).max():.2e}", f"{gap(a[p], a[q])[-1]:.2e}") for p, q in pairs
]
rows += [(f"{p} vs exact", f"{gap(a[p], exact_first).max():.2e}",
          f"{gap(a[p], exact_first)[-1]:.2e}") for p in NAMES]  # fmt: skip
print_table([f"{AGREE_STEPS:,} steps", "max |difference| (rad)", "at the last step (rad)"], rows)
worst = max(gap(a[p], a[q]).max() for p, q in pairs)
assert worst < TOLERANCE, worst
print(f"largest difference between representations: {worst:.2e} rad (< {TOLERANCE:g})")

# %% [markdown]
# ### The same body in the world
#
# `World(orientation=...)` stores every body's orientation in one of the three layouts and turns
# them with the compiled kernel `integrate_rotations`. A box spun by the world's explicit Euler
# integrator (a constant torque $\tau = I\alpha$ switched on after `SWITCH` steps) must end at the
# same angle whichever layout it uses.


# %%
def spinning_box(kind: str, x: float = 0.0, omega: float = OMEGA0) -> tuple[World, Body]:
    world = World(gravity=(0.0, 0.0), dt=DT, integrator="explicit_euler", orientation=kind)
    box = world.add_body(Body(name=kind, position=(x, 0.0), angle=PHI0, angular_velocity=omega))
    box.add_shape(Box(1.6, 0.8))
    return world, box


finals = {}
for kind in NAMES:
    world, box = spinning_box(kind)
    for k in range(WORLD_STEPS):
        if k == SWITCH:
            box.constant_torque = box.moment * ALPHA  # tau = I alpha from now on
        world.step()
    finals[kind] = (box.angle, box.angular_velocity, float(world.orientation_drift()[0]))
ref = exact_angle(WORLD_STEPS - 1)
print_table(
    ["world orientation", "angle (rad)", "omega (rad/s)", "drift", "vs exact sum (rad)"],
    [(k, f"{v[0]:.15f}", f"{v[1]:.12f}", f"{v[2]:.1e}",
      f"{abs(orientation.wrap_angle(v[0] - ref)):.1e}")
     for k, v in finals.items()],
)  # fmt: skip
world_gap = max(abs(orientation.wrap_angle(finals[p][0] - finals[q][0])) for p, q in pairs)
assert world_gap < TOLERANCE, world_gap
print(f"after {WORLD_STEPS:,} world steps the three layouts differ by at most {world_gap:.1e} rad")

# %% [markdown]
# ## What each one costs
#
# Two kinds of measurement (best of several `timeit` repeats on this machine):
#
# - the **plain-Python classes**, one body: microseconds per call. Here every call pays the
#   interpreter's overhead and, for anything that returns a matrix, the cost of building a numpy
#   array, which dwarfs the arithmetic.
# - the world's **compiled kernels** over `N_BODIES` bodies: nanoseconds per body. This is where
#   the arithmetic the slides talk about shows: an addition (angle), or a cosine and a sine plus
#   4 multiplications (complex) or 8 (matrix).
#
# "Conversion to a matrix" is what drawing needs: for the classes `matrix()`, for the kernels
# `cos_sin` (the $(\cos\varphi, \sin\varphi)$ pair that *is* the rotation matrix, which collision
# code and the renderer read).


# %%
def best_times(fns: dict, number: int, repeat: int = 15) -> dict:
    """Seconds per call of each fn() (best of ``repeat``; the candidates take turns, so that a
    busy moment of the machine does not favour one of them)."""
    best = dict.fromkeys(fns, math.inf)
    for _ in range(repeat):
        for key, fn in fns.items():
            best[key] = min(best[key], timeit.timeit(fn, number=number) / number)
    return best


x = OMEGA0 * DT  # the per-step rotation, converted to each representation's own form
reps = {name: orientation.make_orientation(name, PHI0) for name in NAMES}
calls = {}
for name, rep in reps.items():
    calls[name, "integrate"] = lambda rep=rep: rep.integrate(OMEGA0, DT)
    calls[name, "renormalise"] = rep.renormalise
    calls[name, "to matrix"] = rep.matrix
calls["angle", "omega conversion"] = lambda: OMEGA0 * DT
calls["matrix", "omega conversion"] = lambda: np.array(
    [[math.cos(x), -math.sin(x)], [math.sin(x), math.cos(x)]]
)
calls["complex", "omega conversion"] = lambda: complex(math.cos(x), math.sin(x))
py = {key: 1e6 * t for key, t in best_times(calls, number=2_000).items()}  # us per call

rng = np.random.default_rng(0)
start = rng.uniform(-math.pi, math.pi, N_BODIES)  # orientations all round the circle
dphi = rng.uniform(-10.0, 10.0, N_BODIES) * DT  # omega dt for |omega| < 10 rad/s
cs = np.zeros((N_BODIES, 2))
kernels = {}
for name in NAMES:
    kind = orientation.NAMES[name]
    rot = np.zeros((N_BODIES, 4))
    orientation.set_angles(kind, rot, start)
    orientation.integrate_rotations(kind, rot, dphi, True)  # compiled (or loaded) before timing
    orientation.cos_sin(kind, rot, cs)
    for renormalise in (False, True):
        kernels[name, renormalise] = lambda k=kind, r=rot, n=renormalise: (
            orientation.integrate_rotations(k, r, dphi, n)
        )
    kernels[name, "to matrix"] = lambda k=kind, r=rot: orientation.cos_sin(k, r, cs)
compiled = {key: 1e9 * t / N_BODIES for key, t in best_times(kernels, number=20).items()}
for name in NAMES:  # ns per body
    compiled[name, "renormalise"] = max(0.0, compiled[name, True] - compiled[name, False])

FLOPS = {  # per integrate step, counted in sandbox/orientation.py
    "angle": "1 add + range check",
    "matrix": "cos, sin, 8 mul, 4 add",
    "complex": "cos, sin, 4 mul, 2 add",
}
PY_COLUMNS = ("integrate", "renormalise", "to matrix", "omega conversion")
print("plain-Python classes, one body (us per call):")
print_table(
    ["representation", "floats", "bytes", "integrate", "renormalise", "to matrix",
     "omega conversion"],
    [(name, orientation.FLOATS_STORED[name], 8 * orientation.FLOATS_STORED[name],
      *(f"{py[name, k]:.3f}" for k in PY_COLUMNS))
     for name in NAMES],
)  # fmt: skip
print(f"\ncompiled kernels over {N_BODIES:,} bodies (ns per body):")
print_table(
    ["representation", "integrate_rotations", "+ renormalise", "cos_sin (to matrix)",
     "arithmetic per step"],
    [(name, f"{compiled[name, False]:.2f}", f"{compiled[name, 'renormalise']:.2f}",
      f"{compiled[name, 'to matrix']:.2f}", FLOPS[name]) for name in NAMES],
)  # fmt: skip

# %%
fig, axes = plt.subplots(1, 2, figsize=(12, 4.8))
bar_w = 0.25
for ax, data, unit, keys in (
    (axes[0], py, "us per call (plain-Python classes)",
     ("integrate", "renormalise", "to matrix", "omega conversion")),
    (axes[1], compiled, f"ns per body (compiled kernels, {N_BODIES:,} bodies)",
     (False, "renormalise", "to matrix")),
):  # fmt: skip
    xs = np.arange(len(keys))
    for j, name in enumerate(NAMES):
        ax.bar(xs + (j - 1) * bar_w, [data[name, k] for k in keys], bar_w, color=COLOR[name],
               label=f"{name} ({orientation.FLOATS_STORED[name]} float"
                     + ("s)" if orientation.FLOATS_STORED[name] > 1 else ")"))  # fmt: skip
    ax.set_xticks(xs, ["integrate" if k is False else k for k in keys])
    ax.set(ylabel=unit, yscale="log")
    ax.grid(alpha=0.3, axis="y")
    ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.12), ncol=3)
axes[0].set_title("Python: interpreter and numpy overhead dominate")
axes[1].set_title("compiled: the arithmetic (cos + sin dominate)")
fig.tight_layout()
save_figure(fig, OUT / "cost.png", dpi=100)

# %% [markdown]
# ## The slides' comparison table, with numbers
#
# Each claim of the slide next to the figure measured above that supports or contradicts it.
# "Supports"/"contradicts" are decided from the numbers at run time (timings vary a little from
# machine to machine).

# %%
ck, pk = compiled, py


def verdict(ok: bool) -> str:
    return "supports" if ok else "contradicts"


def ratio(x: float, y: float) -> str:
    return f"{x / y:.1f}x" if y > 0 else "-"


wraps = int(np.sum(np.abs(np.diff(a["angle"])) > math.pi))  # jumps between -pi and pi
claims = [
    ("angle", "+ very compact (1 scalar element)", "1 float (8 bytes)", "supports"),
    ("angle", "+ very cheap computation",
     f"{ck['angle', False]:.1f} ns/body vs {ck['complex', False]:.1f} (complex), "
     f"{ck['matrix', False]:.1f} (matrix)",
     verdict(ck["angle", False] < 0.5 * min(ck["matrix", False], ck["complex", False]))),
    ("angle", "- must handle angle discontinuity",
     f"{wraps} jumps of 2 pi in {AGREE_STEPS:,} steps (the wrap is in the ns above)", "supports"),
    ("angle", "- very costly conversion to matrix",
     f"cos + sin: {ck['angle', 'to matrix']:.1f} ns/body vs {ck['complex', 'to matrix']:.2f} "
     f"(complex), {ratio(ck['angle', 'to matrix'], ck['complex', 'to matrix'])}",
     verdict(ck["angle", "to matrix"] > 5 * ck["complex", "to matrix"])),
    ("matrix", "+ solves angle discontinuity", "atan2(m10, m00) is always in [-pi, pi]",
     "supports"),
    ("matrix", "+ can reuse for visualisation",
     f"to matrix: {ck['matrix', 'to matrix']:.2f} ns/body (a copy)", "supports"),
    ("matrix", "- wastes storage (4 scalar elements)", "4 floats (32 bytes) vs 2 for complex",
     "supports"),
    ("matrix", "- expensive computations",
     f"compiled {ck['matrix', False]:.1f} vs {ck['complex', False]:.1f} ns/body (complex); "
     f"Python {pk['matrix', 'integrate']:.2f} vs {pk['complex', 'integrate']:.2f} us",
     f"{verdict(ck['matrix', False] > 1.5 * ck['complex', False])} (compiled), "
     f"{verdict(pk['matrix', 'integrate'] > 1.5 * pk['complex', 'integrate'])} (Python)"),
    ("matrix", "- costly omega conversion",
     f"the same cos + sin as complex; Python {pk['matrix', 'omega conversion']:.2f} vs "
     f"{pk['complex', 'omega conversion']:.2f} us (a numpy array vs a complex)",
     "contradicts (arithmetic), supports (Python)"),
    ("matrix", "- costly renormalisation",
     f"compiled +{ck['matrix', 'renormalise']:.1f} vs +{ck['complex', 'renormalise']:.1f} "
     f"ns/body (complex); Python {pk['matrix', 'renormalise']:.2f} vs "
     f"{pk['complex', 'renormalise']:.2f} us",
     f"{verdict(ck['matrix', 'renormalise'] > 2 * ck['complex', 'renormalise'] + 0.5)} "
     f"(compiled), {verdict(pk['matrix', 'renormalise'] > 2 * pk['complex', 'renormalise'])} "
     "(Python)"),
    ("complex", "+ solves angle discontinuity", "atan2(Im z, Re z) is always in [-pi, pi]",
     "supports"),
    ("complex", "+ compact (2 scalar elements)", "2 floats (16 bytes)", "supports"),
    ("complex", "+ cheap omega conversion",
     f"cos + sin, like the matrix; Python {pk['complex', 'omega conversion']:.2f} us",
     "partly: no cheaper than the matrix's arithmetic"),
    ("complex", "+ cheap conversion to matrix",
     f"{ck['complex', 'to matrix']:.2f} ns/body (a copy, no trigonometry)", "supports"),
    ("complex", "+ cheap renormalisation", f"+{ck['complex', 'renormalise']:.1f} ns/body",
     "supports"),
    ("complex", "- less compact than scalar angles", "2 floats vs 1", "supports"),
    ("complex", "- visualisation matrix computed, but cheap",
     f"compiled {ck['complex', 'to matrix']:.2f} ns/body; Python "
     f"{pk['complex', 'to matrix']:.2f} us (building the numpy array)",
     "supports (compiled)"),
]  # fmt: skip
print_table(["", "slide's claim", "measured", "verdict"], claims)

# %% [markdown]
# Reading the tables:
#
# - **Trigonometry is the real cost.** In compiled code the scalar angle is by far the cheapest
#   to step (one addition and a range check) and the only one that needs a cosine and a sine to
#   be drawn; matrix and complex pay a cosine and a sine *every step* instead, for
#   $\omega\Delta t$. A body that is drawn or collided every step pays that trigonometry either
#   way, so in an engine the totals are closer than the slide suggests.
# - **Matrix vs complex.** "Expensive computations" is 8 multiplications against 4, small next to
#   the cosine and sine both need: the compiled kernels cost about the same. Renormalisation
#   likewise: a 2D rotation matrix is fixed by its first column, so Gram-Schmidt is one
#   2-vector normalisation plus two copies, the same work as $z / |z|$. The matrix's "costly"
#   labels hold in plain Python, where every $2\times2$ product builds numpy arrays.
# - **Storage**: 1, 4 and 2 floats, as the slide says. The world keeps one `(n, 4)` array
#   whatever the representation, so that it can switch between them; the saving would only be
#   real with a layout per representation.
# - **Drift** is real but slow in double precision (around $10^{-13}$ after 100,000 steps,
#   invisible); in single precision it is about $10^{8}$ times larger, enough to make drawn shapes
#   grow or shear over a long run, and renormalising every step keeps it at rounding level for
#   about a nanosecond per body.
# - **Accuracy of the angle itself** (third drift panel): the scalar angle is the *least*
#   accurate of the three, in both precisions. Adding a small $\omega\Delta t$ to a number of size
#   up to $\pi$ rounds away the low bits of the increment every step, while a product of unit
#   complex numbers (or matrices) keeps its relative precision. In `float32` that is the
#   difference between $10^{-4}$ and $10^{-5}$ rad after 100,000 steps.
# - An update that is not a rotation (the $1 + i\omega\Delta t$ shortcut) is a different matter:
#   renormalisation hides the growth of $|z|$ but cannot repair the angle. How much that costs
#   depends on $\omega\Delta t$ (the section on Box2D's use of it above): hopeless at 0.29 rad per
#   step, invisible at a few hundredths.

# %% [markdown]
# ## Animation: the three side by side
#
# Three boxes in three worlds, one per representation, spun by the same schedule (faster here so
# that the animation shows a few turns: $\omega_0 = 2$ rad/s, then $\alpha = 3$ rad/s$^2$). The
# boxes turn identically (the angles agree to $10^{-9}$ rad, above), so the panels show what
# *differs*, the numbers each world stores:
#
# - top: the scalar angle's stored $\varphi$, reduced to $[-\pi, \pi]$: it jumps by $2\pi$ at
#   every half turn (the discontinuity the slide warns about). Matrix and complex store no angle
#   (no curve).
# - bottom: the drift of the stored orientation with renormalisation switched off
#   (`renormalise=False`), in units of $10^{-15}$: $\big||z| - 1\big|$ for the complex number,
#   $\|\Phi^T\Phi - I\|_F$ for the matrix (about $2\sqrt{2}$ times larger, as found above) and
#   exactly 0 for the angle.

# %%
ANIM_STEPS, ANIM_EVERY, ANIM_SWITCH, ANIM_ALPHA = 180, 2, 90, 3.0
STORED, DRIFT = "stored angle (rad)", "drift (1e-15)"


def stored_angle(w: World) -> float:
    """The number a scalar-angle world stores (NaN for the others: they store no angle)."""
    return float(w.rot[0, 0]) if w.settings.orientation == "angle" else math.nan


recs = []
for j, kind in enumerate(NAMES):
    world, box = spinning_box(kind, x=2.2 * (j - 1), omega=2.0)
    world.settings.renormalise = False

    def controller(body, w, anim_alpha=ANIM_ALPHA):
        if w.steps == ANIM_SWITCH:
            body.constant_torque = body.moment * anim_alpha  # tau = I alpha

    box.controller = controller
    series = {STORED: stored_angle, DRIFT: lambda w: 1e15 * float(w.orientation_drift()[0])}
    recs.append(record(world, ANIM_STEPS, every=ANIM_EVERY, series=series))
end_angles = [r.frames[-1][0, 2] for r in recs]
print(
    "final angles in the animation:",
    ", ".join(f"{k} {v:.12f}" for k, v in zip(NAMES, end_angles, strict=True)),
)
wraps_anim = int(np.sum(np.abs(np.diff(recs[0].series[STORED])) > math.pi))
print(f"stored angle jumps by 2 pi {wraps_anim} times in {ANIM_STEPS} steps")
print_table(
    ["world", "drift after 180 steps, no renormalisation"],
    [(k, f"{r.series[DRIFT][-1] * 1e-15:.2e}") for k, r in zip(NAMES, recs, strict=True)],
)
gif = render_gif(
    recs,
    OUT / "three_representations.gif",
    fps=20,
    size_px=360,
    labels=list(NAMES),
    colors=[COLOR[n] for n in NAMES],
    panel=[STORED, DRIFT],
)
print(f"wrote {len(recs[0])} frames to {gif.name}")

# %% [markdown]
# ## Exercises
#
# Predict first, then run the cell under the question, then open the answer.
#
# **1.** A box spins at a steady $\omega = 2$ rad/s for one minute at $\Delta t = 1/60$ s, its
# orientation stored as a scalar angle (starting at `PHI0` = 0.2 rad). How many times does the
# stored angle jump by $2\pi$?

# %%
world, box = spinning_box("angle", omega=2.0)
stored = []
for _ in range(3600):
    world.step()
    stored.append(float(world.rot[0, 0]))
print(f"turned {2.0 * world.time:.4f} rad; stored angle jumped "
      f"{int(np.sum(np.abs(np.diff(stored)) > math.pi))} times")  # fmt: skip

# %% [markdown]
# <details><summary>Answer</summary>
#
# The box turns $2 \times 60 = 120$ rad, from 0.2 to 120.2 rad. The stored angle jumps from $\pi$
# to $-\pi$ each time the true angle passes $\pi + 2\pi k$: $\pi, 3\pi, \dots, 37\pi = 116.2$ rad,
# 19 values ($39\pi = 122.5$ is past the end). The run counts 19. Matrix and complex would store
# no jump at all: reading the angle back with `atan2` is where the wrap happens for them.
#
# </details>
#
# **2.** Box2D's update, $z \leftarrow (z + i\,\omega\Delta t\,z)/|\cdot|$, for a box spinning
# at 5 rad/s: after how many seconds has it fallen 1 degree behind the true angle at 60 Hz? And
# with Box2D's 4 substeps per frame ($\Delta t = 1/240$ s)?


# %%
def seconds_to_lag(omega: float, dt: float, degrees: float = 1.0) -> float:
    """Step z <- (z + i omega dt z) / |.| until it is ``degrees`` behind omega t."""
    z, t, turned = complex(1.0, 0.0), 0.0, 0.0
    while omega * t - turned < math.radians(degrees):
        z_new = z * complex(1.0, omega * dt)  # z + i omega dt z
        z_new /= abs(z_new)
        turned += math.atan2((z_new / z).imag, (z_new / z).real)  # this step's turn
        z, t = z_new, t + dt
    return t


for dt_e in (1 / 60, 1 / 240):
    print(f"dt = 1/{round(1 / dt_e)} s: 1 degree behind after {seconds_to_lag(5.0, dt_e):.2f} s")

# %% [markdown]
# <details><summary>Answer</summary>
#
# Each step loses $(\omega\Delta t)^3/3$ rad, so per second $(\omega\Delta t)^3/(3\Delta t) =
# \omega^3\Delta t^2/3$. At 60 Hz: $125 / (3 \times 3600) = 0.0116$ rad/s, and 1 degree
# (0.01745 rad) takes $1.51$ s. Four times smaller steps lose 16 times less per second:
# $7.2 \times 10^{-4}$ rad/s, 1 degree after $24.1$ s. The run prints 1.52 s and 24.14 s
# (the first step past 1 degree). Put differently, the spin rate comes out
# $(\omega\Delta t)^2/3 = 0.23\%$ low at 60 Hz and $0.014\%$ low with the substeps.
#
# </details>
#
# **3.** Without renormalisation, in double precision, the complex number drifted by about
# $n\varepsilon$ after $n$ steps at constant $\omega$ (printed near the top). Predict the matrix's
# drift after the same 2,999 steps from the complex number's, then check it in `runs`.

# %%
print(f"complex {runs['complex', 'float64', False]['drift'][k_sw]:.3e}, matrix "
      f"{runs['matrix', 'float64', False]['drift'][k_sw]:.3e}, ratio "
      f"{runs['matrix', 'float64', False]['drift'][k_sw] / runs['complex', 'float64', False]['drift'][k_sw]:.3f}")  # fmt: skip

# %% [markdown]
# <details><summary>Answer</summary>
#
# A matrix scaled by $1 + n\varepsilon$ has $\Phi^T\Phi - I = ((1 + n\varepsilon)^2 - 1)I
# \approx 2n\varepsilon I$, whose Frobenius norm is $2\sqrt{2}\,n\varepsilon$: $2.83$ times the
# complex number's $n\varepsilon$. The run gives 2.77, within 2% of $2\sqrt{2}$ (the matrix
# products round as well).
#
# </details>
