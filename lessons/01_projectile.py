# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: percent
# ---

# %% [markdown]
# # 01 Analytic vs numeric projectile
#
# Slides "Analytical Model Example", "Numerical Integration", "Numerical Model Example" and
# "Analytic vs Numeric Results".
#
# - **analytic model**: the state is a function of time,
#   $\mathbf{p}(t) = \mathbf{s} + \mathbf{u}t + \frac{1}{2}\mathbf{a}t^2$,
#   $\mathbf{v}(t) = \mathbf{u} + \mathbf{a}t$: exact at any $t$, but only for problems someone
#   has solved in closed form
# - **numeric model**: the state is updated over small steps, the slides' first-order
#   approximation (explicit Euler)
#   $$\mathbf{p}(t + \Delta t) \approx \mathbf{p}(t) + \mathbf{v}(t)\Delta t, \qquad
#   \mathbf{v}(t + \Delta t) \approx \mathbf{v}(t) + \mathbf{a}(t)\Delta t$$
#   which works for anything we can compute an acceleration for, at the price of an error that
#   creeps in step after step
#
# The lesson rebuilds the slides' two tables with the engine (a ball in a `World` with the
# `analytic` and the `explicit_euler` integrators), explains in closed form why the numeric ball
# lands at $x = 27$ instead of $24$, measures how the error of each integrator shrinks with
# $\Delta t$, and animates the two balls side by side.

# %%
import math

import matplotlib.pyplot as plt
import numpy as np
import pymunk

from sandbox import integrators, projectile
from sandbox.body import Body
from sandbox.geometry import box_vertices
from sandbox.lessonkit import output_dir, print_table, save_figure
from sandbox.recording import CircleOutline, Recording
from sandbox.render import render_gif
from sandbox.shapes import Circle
from sandbox.world import World

# knobs (the slides' numerical example)
S = (0.0, 0.0)  # m, launch point
U = (3.0, 4.0)  # m/s, launch velocity u
A = (0.0, -1.0)  # m/s^2, acceleration a = [0 -g] with g = 1
DT = 1.0  # s, the slides' time step
RADIUS = 0.5  # m, ball radius (drawing only: nothing to collide with)
DRAG = 0.1  # 1/m, quadratic drag coefficient c in a = g - c |v| v (convergence study)
SPRING = 2.0  # rad/s, angular frequency of the harmonic oscillator x'' = -SPRING^2 x
DTS = (0.1, 0.05, 0.025, 0.0125, 0.00625)  # s, the step sizes of the convergence study
ANIM_DT = 0.1  # s between animation frames (the analytic ball can be drawn at any t)

OUT = output_dir("01_projectile")
METHODS = ("explicit_euler", "semi_implicit_euler", "verlet", "rk4")
LABEL = {
    "explicit_euler": "explicit Euler",
    "semi_implicit_euler": "semi-implicit Euler",
    "verlet": "velocity Verlet",
    "rk4": "RK4",
    "analytic": "analytic",
}
COLOR = {
    "analytic": "k",
    "explicit_euler": "C3",
    "semi_implicit_euler": "C2",
    "verlet": "C0",
    "rk4": "C1",
}


def vec(x) -> str:
    """A vector written like the slides: [3 4], [12.0 8.0] (no negative zero)."""
    return "[" + " ".join(f"{float(c) + 0.0:g}" for c in x) + "]"


def ball_world(integrator: str, dt: float = DT) -> tuple[World, Body]:
    """One ball launched from S at U under gravity A, no ground (free flight)."""
    world = World(gravity=A, dt=dt, integrator=integrator)
    ball = world.add_body(Body(name="ball", position=S, velocity=U))
    ball.add_shape(Circle(RADIUS))
    return world, ball


# %% [markdown]
# ## The analytic table
#
# With $\mathbf{u} = [3\ 4]$, $\mathbf{a} = [0\ {-1}]$ and $\Delta t = 1$ the component
# equations are $p_x(t) = u_x t = 3t$ and
# $p_y(t) = u_y t + \frac{1}{2}a_y t^2 = 4t - \frac{1}{2}t^2$.
# The world's `analytic` integrator evaluates exactly these closed forms at every step.

# %%
SLIDES_ANALYTIC = [  # slides, "Analytical Model Example": t, p_x, p_y
    (0, 0.0, 0.0), (1, 3.0, 3.5), (2, 6.0, 6.0), (3, 9.0, 7.5), (4, 12.0, 8.0),
    (5, 15.0, 7.5), (6, 18.0, 6.0), (7, 21.0, 3.5), (8, 24.0, 0.0),
]  # fmt: skip

world, ball = ball_world("analytic")
analytic_rows = []
for n in range(9):
    if n > 0:
        world.step()
    px, py = ball.position
    analytic_rows.append((n, px, py))
assert analytic_rows == SLIDES_ANALYTIC, analytic_rows
print_table(
    ["Time", "p_x = 3t", "p_y = 4t - t^2/2", "p(t) = [p_x p_y]"],
    [(n, px, py, f"[{px:.1f} {py:.1f}]") for n, px, py in analytic_rows],
    digits=1,
)
print("matches the slides' analytic table exactly:", analytic_rows == SLIDES_ANALYTIC)

# %% [markdown]
# ## The numeric (explicit Euler) table
#
# The slides' algorithm: let $\mathbf{p}' := \mathbf{p} + \mathbf{v}\Delta t$,
# $\mathbf{v}' := \mathbf{v} + \mathbf{a}\Delta t$, then $\mathbf{p} := \mathbf{p}'$,
# $\mathbf{v} := \mathbf{v}'$. Both updates use the *old* state. The world's `explicit_euler`
# integrator is that algorithm; each row below is read from the ball before and after one
# `world.step()`.

# %%
SLIDES_NUMERIC = [  # slides, "Numerical Model Example": t, p, v, a, p' = p + v, v' = v + a
    (0, "[0 0]", "[3 4]", "[0 -1]", "[3 4]", "[3 3]"),
    (1, "[3 4]", "[3 3]", "[0 -1]", "[6 7]", "[3 2]"),
    (2, "[6 7]", "[3 2]", "[0 -1]", "[9 9]", "[3 1]"),
    (3, "[9 9]", "[3 1]", "[0 -1]", "[12 10]", "[3 0]"),
    (4, "[12 10]", "[3 0]", "[0 -1]", "[15 10]", "[3 -1]"),
    (5, "[15 10]", "[3 -1]", "[0 -1]", "[18 9]", "[3 -2]"),
    (6, "[18 9]", "[3 -2]", "[0 -1]", "[21 7]", "[3 -3]"),
    (7, "[21 7]", "[3 -3]", "[0 -1]", "[24 4]", "[3 -4]"),
    (8, "[24 4]", "[3 -4]", "[0 -1]", "[27 0]", "[3 -5]"),
    (9, "[27 0]", "[3 -5]", "[0 -1]", "", ""),
]

world, ball = ball_world("explicit_euler")
numeric_rows, euler_path = [], [np.array(ball.position)]
for n in range(10):
    p, v = np.array(ball.position), np.array(ball.velocity)
    a = world.gravity  # the only force: a = [0 -g]
    if n < 9:
        world.step()
        p1, v1 = np.array(ball.position), np.array(ball.velocity)
        euler_path.append(p1)
        numeric_rows.append((n, vec(p), vec(v), vec(a), vec(p1), vec(v1)))
    else:
        numeric_rows.append((n, vec(p), vec(v), vec(a), "", ""))
euler_path = np.array(euler_path)
assert numeric_rows == SLIDES_NUMERIC, numeric_rows
print_table(["Time", "p", "v", "a", "p' = p + v dt", "v' = v + a dt"], numeric_rows)
print("matches the slides' numeric table exactly:", numeric_rows == SLIDES_NUMERIC)

# %% [markdown]
# ## Why the numeric ball lands one step late
#
# Unroll the Euler loop. The velocity is exact at every step, $\mathbf{v}_k = \mathbf{u} +
# \mathbf{a}\,k\Delta t$, but each position step uses the velocity from the *start* of the step:
#
# $$\mathbf{p}_n = \mathbf{s} + \sum_{k=0}^{n-1} \mathbf{v}_k \Delta t
#   = \mathbf{s} + \mathbf{u}\,n\Delta t + \mathbf{a}\,\Delta t^2\,\frac{n(n-1)}{2}$$
#
# (`sandbox.projectile.euler_position`). Against the analytic
# $\mathbf{p}(n\Delta t) = \mathbf{s} + \mathbf{u}\,n\Delta t
# + \mathbf{a}\,\Delta t^2\,\frac{n^2}{2}$
# the difference is
#
# $$\mathbf{p}_n - \mathbf{p}(t_n) = -\tfrac{1}{2}\mathbf{a}\,\Delta t^2\,n
#   = -\tfrac{1}{2}\mathbf{a}\,\Delta t\,t_n ,$$
#
# a lag that grows linearly with time and linearly with $\Delta t$ (first order). While the ball
# rises, the velocity used is too large, so it climbs too high (apex $10$ instead of $8$).
# Rewriting $\mathbf{p}_n = \mathbf{s} + (\mathbf{u} - \frac{1}{2}\mathbf{a}\Delta t)\,t_n +
# \frac{1}{2}\mathbf{a}t_n^2$ shows that the Euler points lie *exactly* on the parabola of a ball
# thrown at $\mathbf{u} - \frac{1}{2}\mathbf{a}\Delta t = [3\ 4.5]$. That ball stays up
# $2 \times 4.5 / 1 = 9$ s instead of $2 u_y / g = 8$ s, i.e. one step $\Delta t$ longer, in
# general $T + \Delta t$; at $u_x = 3$ m/s that is $x = 27$ instead of $24$.
#
# Semi-implicit Euler ($\mathbf{v}$ first, then $\mathbf{p}$ with the new $\mathbf{v}$) makes
# the mirror error, $\mathbf{p}_n = \mathbf{s} + \mathbf{u}\,n\Delta t +
# \mathbf{a}\,\Delta t^2\,n(n+1)/2$, and lands one step early ($x = 21$). Averaging the two
# velocities, $\mathbf{p}' = \mathbf{p} + \frac{1}{2}(\mathbf{v} + \mathbf{v}')\Delta t$, is
# exact for constant acceleration: that is what velocity Verlet does.

# %%
n = np.arange(10)
t = n * DT
closed = projectile.euler_position(S, U, A, DT, n)
exact = projectile.position(S, U, A, t)
lag_formula = -0.5 * np.asarray(A) * DT * t[:, None]
assert np.array_equal(closed, euler_path)  # the world's Euler = the closed form, bit for bit
print_table(
    ["n", "t", "p(t) analytic", "p_n world Euler", "p_n closed form", "p_n - p(t)", "-a dt t / 2"],
    [
        (k, t[k], vec(exact[k]), vec(euler_path[k]), vec(closed[k]), vec(euler_path[k] - exact[k]),
         vec(lag_formula[k]))
        for k in n
    ],
    digits=0,
)  # fmt: skip
g = -A[1]
t_flight = projectile.flight_time(U[1], g)
t_euler = 2.0 * (U[1] + 0.5 * g * DT) / g  # flight time of the parabola thrown at u - a dt / 2
t_semi = 2.0 * (U[1] - 0.5 * g * DT) / g
print(f"analytic lands at t = {t_flight:g} s, x = {U[0] * t_flight:g} m")
print(f"explicit Euler lands at t = T + dt = {t_euler:g} s, x = {U[0] * t_euler:g} m")
print(f"semi-implicit Euler lands at t = T - dt = {t_semi:g} s, x = {U[0] * t_semi:g} m")
print(f"apex: analytic {projectile.apex(U, g)[1]:g} m, explicit Euler {euler_path[:, 1].max():g} m")

# %%
tt = np.linspace(0.0, 9.0, 181)
fine = projectile.position(S, U, A, tt)
semi = projectile.semi_implicit_position(S, U, A, DT, np.arange(8))
fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 4), gridspec_kw={"width_ratios": [1.6, 1]})
ax.plot(fine[:, 0], fine[:, 1], color="k", lw=1, ls=":", label="analytic p(t)")
ax.plot(exact[:9, 0], exact[:9, 1], "o", color="k", ms=6, label="analytic table (t = 0..8)")
ax.plot(
    euler_path[:, 0], euler_path[:, 1], "s-", color=COLOR["explicit_euler"], ms=6,
    label="explicit Euler table (t = 0..9)",
)  # fmt: skip
ax.plot(
    semi[:, 0], semi[:, 1], "^--", color=COLOR["semi_implicit_euler"], ms=5, lw=1,
    label="semi-implicit Euler (t = 0..7)",
)  # fmt: skip
for x, text, color in ((24, "x = 24", "k"), (27, "x = 27", COLOR["explicit_euler"])):
    ax.annotate(text, (x, 0), xytext=(0, -22), textcoords="offset points", ha="center",
                color=color, arrowprops={"arrowstyle": "->", "color": color})  # fmt: skip
ax.axhline(0, color="0.6", lw=0.8)
ax.set(xlabel="x (m)", ylabel="y (m)", ylim=(-2.5, 14.5), aspect="equal")
ax.set_title(r"u = [3 4], a = [0 -1], $\Delta t$ = 1")
ax.legend(fontsize=8, loc="upper center", ncol=2)
bx.plot(t, (euler_path - exact)[:, 1], "s", color=COLOR["explicit_euler"], label="world Euler")
bx.plot(t, lag_formula[:, 1], color="k", lw=1, label=r"$-\frac{1}{2} a_y \Delta t\, t$")
bx.set(xlabel="t (s)", ylabel=r"$p_{y,n} - p_y(t_n)$ (m)", title="Euler's lag grows linearly")
bx.legend(fontsize=8)
bx.grid(alpha=0.3)
fig.tight_layout()
save_figure(fig, OUT / "analytic_vs_euler.png", dpi=100)

# %% [markdown]
# ## Error against the time step
#
# An integrator of order $k$ has a global error $\approx C\,\Delta t^k$: halving $\Delta t$ divides
# the error by $2^k$, a straight line of slope $k$ on a log-log plot. Four integrators (all in
# `sandbox/integrators.py`, the code the world runs):
#
# | integrator | one step | order |
# | --- | --- | --- |
# | explicit Euler | $\mathbf{p}' = \mathbf{p} + \mathbf{v}\Delta t$, $\mathbf{v}' = \mathbf{v} + \mathbf{a}\Delta t$ | 1 |
# | semi-implicit Euler | $\mathbf{v}' = \mathbf{v} + \mathbf{a}\Delta t$, $\mathbf{p}' = \mathbf{p} + \mathbf{v}'\Delta t$ | 1 |
# | velocity Verlet | $\mathbf{p}' = \mathbf{p} + \mathbf{v}\Delta t + \frac{1}{2}\mathbf{a}\Delta t^2$, $\mathbf{v}' = \mathbf{v} + \frac{1}{2}(\mathbf{a} + \mathbf{a}')\Delta t$ | 2 |
# | RK4 | four slopes per step, weighted $1, 2, 2, 1$ | 4 |
#
# Three problems, error $|\mathbf{p}_N - \mathbf{p}(T)|$ at a fixed end time $T$:
#
# 1. **gravity only** (the slides' ball, $T = 8$ s): the acceleration is constant, so Verlet and
#    RK4 are *exact* (their error is rounding, $\sim 10^{-15}$, and no order can be fitted), and
#    both Eulers have the error $\frac{1}{2}|\mathbf{a}|\,\Delta t\,T$ found above: order 1.
# 2. **quadratic drag**, $\mathbf{a} = \mathbf{g} - c\,|\mathbf{v}|\,\mathbf{v}$ (the same ball
#    through air, $T = 6$ s): no closed form; the reference is RK4 with $\Delta t = 10^{-3}$ s.
# 3. **a spring**, $x'' = -\omega^2 x$ ($x(0) = 1$, $v(0) = 0$, $T = 2$ s): closed form
#    $x(t) = \cos\omega t$.

# %%
G_VEC = np.array(A)


def drag_accel(p, v, phi, w):
    """a = g - c |v| v (quadratic drag); no angular part."""
    speed = np.sqrt(np.sum(v * v, axis=-1, keepdims=True))
    return G_VEC - DRAG * speed * v, np.zeros_like(w)


def spring_accel(p, v, phi, w):
    """a = -omega^2 p (a spring to the origin)."""
    return -(SPRING**2) * p, np.zeros_like(w)


def run(method: str, accel, s, u, dt: float, T: float) -> np.ndarray:
    """Position after T / dt steps of ``method`` (the same increments the world applies)."""
    steps = int(round(T / dt))
    p, _, _, _ = integrators.integrate(method, s, u, 0.0, 0.0, accel, dt, steps)
    return p


T_DRAG = 6.0
p_drag_ref = run("rk4", drag_accel, S, U, 1e-3, T_DRAG)
problems = {
    "gravity only": (integrators.constant_acceleration(G_VEC), S, U, 8.0,
                     projectile.position(S, U, A, 8.0)),
    "quadratic drag": (drag_accel, S, U, T_DRAG, p_drag_ref),
    "spring": (spring_accel, (1.0, 0.0), (0.0, 0.0), 2.0,
               np.array([math.cos(SPRING * 2.0), 0.0])),
}  # fmt: skip
dts = np.array(DTS)
errors: dict[tuple[str, str], np.ndarray] = {}
for prob, (accel, s, u, T, ref) in problems.items():
    for method in METHODS:
        errors[prob, method] = np.array(
            [np.linalg.norm(run(method, accel, s, u, dt, T) - ref) for dt in dts]
        )

EXACT = 1e-12  # m: an error this small is rounding, not truncation


def fitted_order(err: np.ndarray) -> float:
    """Slope of log(error) against log(dt); NaN when the method is exact."""
    if err.max() < EXACT:
        return math.nan
    return float(np.polyfit(np.log(dts), np.log(err), 1)[0])


for prob in problems:
    print(f"\n{prob}: error |p_N - p(T)| (m)")
    print_table(
        ["dt (s)", *(LABEL[m] for m in METHODS)],
        [(f"{dt:g}", *(f"{errors[prob, m][i]:.3e}" for m in METHODS)) for i, dt in enumerate(dts)],
    )
orders = {key: fitted_order(err) for key, err in errors.items()}
print("\nfitted order of convergence (slope of log error vs log dt)")
print_table(
    ["integrator", "expected", *problems],
    [
        (LABEL[m], integrators.ORDER[m],
         *("exact" if math.isnan(orders[p, m]) else f"{orders[p, m]:.2f}" for p in problems))
        for m in METHODS
    ],
)  # fmt: skip

# %%
fig, axes = plt.subplots(1, 4, figsize=(16, 5))
floor = 1e-16  # where "exact" results are drawn on the log axis
for ax, prob in zip(axes[:3], problems, strict=True):
    for m in METHODS:
        err = np.maximum(errors[prob, m], floor)
        o = orders[prob, m]
        tag = "exact (rounding)" if math.isnan(o) else f"order {o:.2f}"
        hollow = m in ("semi_implicit_euler", "rk4")  # drawn over an identical line in panel 1
        ax.loglog(
            dts, err, marker="o", ls="--" if hollow else "-", ms=7 if hollow else 4,
            mfc="none" if hollow else COLOR[m], color=COLOR[m], label=f"{LABEL[m]}: {tag}",
        )  # fmt: skip
    ax.set(xlabel=r"$\Delta t$ (s)", ylabel="error at T (m)", title=prob)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.18), ncol=2)
axes[0].set_ylim(1e-17, 10)
ax = axes[3]  # the drag paths at the coarsest step, against the reference
dt_show = DTS[0]
ref_path = [np.array(S)]
p_ref, v_ref = np.array(S), np.array(U)
for _ in range(int(round(T_DRAG / 1e-2))):
    p_ref, v_ref, _, _ = integrators.integrate("rk4", p_ref, v_ref, 0.0, 0.0, drag_accel, 1e-2)
    ref_path.append(p_ref)
ref_path = np.array(ref_path)
ax.plot(ref_path[:, 0], ref_path[:, 1], color="k", lw=3, alpha=0.3, label="reference")
for m in METHODS:
    p_m, v_m, path = np.array(S), np.array(U), [np.array(S)]
    for _ in range(int(round(T_DRAG / dt_show))):
        p_m, v_m, _, _ = integrators.integrate(m, p_m, v_m, 0.0, 0.0, drag_accel, dt_show)
        path.append(p_m)
    path = np.array(path)
    ax.plot(path[:, 0], path[:, 1], ".-", color=COLOR[m], ms=4, lw=1, label=LABEL[m])
ax.set(xlabel="x (m)", ylabel="y (m)", title=f"quadratic drag, c = {DRAG}, dt = {dt_show} s")
ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.18), ncol=2)
ax.grid(alpha=0.3)
fig.tight_layout()
save_figure(fig, OUT / "error_vs_dt.png", dpi=100)

# %%
for prob in ("quadratic drag", "spring"):
    ratio = errors[prob, "explicit_euler"] / errors[prob, "rk4"]
    print(
        f"{prob}: explicit Euler error / RK4 error = {ratio[0]:.1e} at dt = {dts[0]:g} s, "
        f"{ratio[-1]:.1e} at dt = {dts[-1]:g} s"
    )

# %% [markdown]
# What the numbers say:
#
# - **gravity only**: both Eulers have the same error, $4\,\Delta t$ m ($= \frac{1}{2}\cdot 1
#   \cdot \Delta t \cdot 8$), one too high and one too low; Verlet and RK4 hit the parabola to
#   rounding. A constant acceleration is the one case the simple second-order update gets right.
# - **quadratic drag** and **spring**: the acceleration changes within a step, and the fitted
#   slopes come out at the textbook orders 1, 1, 2, 4. Halving $\Delta t$ halves the Euler error
#   but divides RK4's by 16 (the ratios are printed above), for four acceleration evaluations
#   per step instead of one.
# - semi-implicit Euler is not more *accurate* than explicit Euler (on the drag problem it is
#   worse); its strength is stability: it keeps an oscillator's energy bounded where explicit
#   Euler's grows (next section), which is why Box2D uses it.
#
# ## A spring's energy under three integrators
#
# The spring $x'' = -\omega^2 x$ has the energy (per kg) $E = \frac{1}{2}v^2 +
# \frac{1}{2}\omega^2x^2$, constant in the exact motion. What one step does to it, with
# $h = \Delta t$:
#
# - **explicit Euler**, $x' = x + vh$, $v' = v - \omega^2 x h$: expanding,
#   $v'^2 + \omega^2x'^2 = (v^2 + \omega^2x^2)(1 + \omega^2h^2)$. Every step *multiplies* the
#   energy by $1 + (\omega h)^2$: it grows exponentially, whatever $h$.
# - **semi-implicit Euler**, $v' = v - \omega^2xh$ first, then $x' = x + v'h$: it keeps the
#   "shadow energy" $\tilde E = \frac{1}{2}v^2 + \frac{1}{2}\omega^2x^2 - \frac{1}{2}\omega^2h\,xv$
#   exactly, so $E$ only wobbles around it, by at most a fraction $\omega h / 2$: bounded for ever.
# - **RK4**: one step multiplies $(x, v/\omega)$ by $R(i\omega h)$, the Taylor polynomial of
#   $e^{i\omega h}$ to 4th order, so the energy is multiplied by $|R|^2 = 1 - (\omega h)^6/72 +
#   (\omega h)^8/576$: a loss so small that it takes thousands of periods to see.
#
# **pymunk** (Chipmunk) orders its step differently from both Eulers above: it first moves every
# body with its *old* velocity, $x' = x + vh$, then finds contacts and updates the velocities with
# the forces, $v' = v + a h$. Under a constant acceleration (gravity) that is exactly the slides'
# explicit Euler (lesson 14 shows pymunk's ball on the explicit Euler parabola). For a spring it
# depends on *where* the force is evaluated: Chipmunk's `DampedSpring` computes its force during
# the step, after the move, at the new position, $v' = v - \omega^2x'h$, which is the mirror image of
# semi-implicit Euler (it keeps $\frac{1}{2}v^2 + \frac{1}{2}\omega^2x^2 + \frac{1}{2}\omega^2h\,xv$)
# and bounded; a force a user computes *before* `space.step()` is the old position's, and that is
# explicit Euler again. Below, a pymunk body on a `DampedSpring` runs beside the three.

# %%
ENERGY_DT, ENERGY_T = 0.05, 20.0  # s: omega dt = 0.1, about 6 periods
n_energy = int(round(ENERGY_T / ENERGY_DT))
t_energy = ENERGY_DT * np.arange(n_energy + 1)


def spring_energy(p: np.ndarray, v: np.ndarray) -> float:
    """E = v^2 / 2 + omega^2 x^2 / 2 (J per kg)."""
    return 0.5 * float(v @ v) + 0.5 * SPRING**2 * float(p @ p)


energy_runs = {}
for m in ("explicit_euler", "semi_implicit_euler", "rk4"):
    p_m, v_m, e_m = np.array([1.0, 0.0]), np.array([0.0, 0.0]), []
    for _ in range(n_energy + 1):
        e_m.append(spring_energy(p_m, v_m))
        p_m, v_m, _, _ = integrators.integrate(m, p_m, v_m, 0.0, 0.0, spring_accel, ENERGY_DT)
    energy_runs[LABEL[m]] = np.array(e_m)

space = pymunk.Space()  # a 1 kg body on a spring to (-2, 0) of rest length 2: force -k x
anchor = pymunk.Body(body_type=pymunk.Body.STATIC)
anchor.position = (-2.0, 0.0)
bob = pymunk.Body(1.0, float("inf"))
bob.position = (1.0, 0.0)
space.add(bob, pymunk.DampedSpring(anchor, bob, (0, 0), (0, 0), 2.0, SPRING**2, 0.0))
e_pm = []
for _ in range(n_energy + 1):
    e_pm.append(spring_energy(np.array(bob.position), np.array(bob.velocity)))
    space.step(ENERGY_DT)
energy_runs["pymunk DampedSpring"] = np.array(e_pm)

wh = SPRING * ENERGY_DT
bounded = f"in [{1 / (1 + wh / 2):.4f}, {1 / (1 - wh / 2):.4f}]"  # E / shadow E, |xv| <= E / w
closed_energy = {
    "explicit Euler": (1 + wh**2) ** n_energy,
    "RK4": (1 - wh**6 / 72 + wh**8 / 576) ** n_energy,
}
print(
    f"omega dt = {wh:g}, {n_energy} steps ({ENERGY_T:g} s, {ENERGY_T * SPRING / (2 * math.pi):.1f} periods)"
)
print_table(
    ["integrator", "E(T) / E(0)", "max |E / E(0) - 1|", "closed form E(T) / E(0)"],
    [
        (name, f"{e[-1] / e[0]:.10f}", f"{np.max(np.abs(e / e[0] - 1)):.2e}",
         f"{closed_energy[name]:.10f}" if name in closed_energy else bounded)
        for name, e in energy_runs.items()
    ],
)  # fmt: skip

# %%
fig, (ax, bx) = plt.subplots(1, 2, figsize=(12, 4))
styles = {
    "explicit Euler": (COLOR["explicit_euler"], "-"),
    "semi-implicit Euler": (COLOR["semi_implicit_euler"], "-"),
    "RK4": (COLOR["rk4"], "-"),
    "pymunk DampedSpring": ("C4", "--"),
}
for name, e in energy_runs.items():
    color, ls = styles[name]
    ax.plot(t_energy, e / e[0], color=color, ls=ls, label=name)
    bx.semilogy(t_energy[1:], np.abs(e[1:] / e[0] - 1), color=color, ls=ls, label=name)
ax.plot(t_energy, (1 + wh**2) ** np.arange(n_energy + 1), "k:", lw=1,
        label=r"$(1 + \omega^2\Delta t^2)^n$")  # fmt: skip
ax.set(xlabel="t (s)", ylabel="E / E(0) (1)", ylim=(0.0, 2.5),
       title=f"spring energy, $\\omega\\Delta t$ = {wh:g}")  # fmt: skip
bx.set(xlabel="t (s)", ylabel="|E / E(0) - 1| (1)", title="the same, relative error (log)")
for a in (ax, bx):
    a.grid(alpha=0.3)
    a.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.0, 1.0))
fig.tight_layout()
save_figure(fig, OUT / "spring_energy.png", dpi=100)

# %% [markdown]
# ## Animation
#
# Three balls launched together: the analytic ball (drawn at any time: it is a function of $t$),
# the slides' explicit Euler ball with $\Delta t = 1$ s (it only moves when a step happens, so it
# jumps once per second), and explicit Euler with $\Delta t$ = `ANIM_DT`. Each frame at time
# $t_k$ shows every ball at its latest state *no later than* $t_k$: a run is never drawn ahead of
# the frame's time, so the $\Delta t = 1$ s ball sits at its start until $t = 1$ s, and comes back
# to $y = 0$ at $t = 9$ s, one second after the exact ball. Each stops where it first comes back
# to $y = 0$: $x = 24$, $x = 27$ and $x = 24 + u_x\,\Delta t = 24.3$.

# %%
frame_times = np.arange(0.0, 9.0 + 0.5 * ANIM_DT, ANIM_DT)
ground = box_vertices(30.0, 0.4, offset=(13.5, -RADIUS - 0.2))
runs, labels = [], []
for integrator, dt, label in (
    ("analytic", ANIM_DT, "analytic"),
    ("explicit_euler", DT, f"explicit Euler, dt = {DT:g} s"),
    ("explicit_euler", ANIM_DT, f"explicit Euler, dt = {ANIM_DT:g} s"),
):
    world, ball = ball_world(integrator, dt)
    rec = Recording(
        names=["ground", "ball"],
        types=["static", "dynamic"],
        outlines=[[ground], [CircleOutline(np.zeros(2), RADIUS)]],
    )
    landed, shown = None, []
    for tk in frame_times:
        # sample at the frame time, never ahead of it: step only while the next state is due
        while world.time + dt <= tk + 1e-9 and landed is None:
            world.step()
            if ball.position[1] <= 1e-9:  # back at launch height: stop here
                landed = (*ball.position, ball.angle, world.time)
        x, y, ang, t_state = landed or (*ball.position, ball.angle, world.time)
        shown.append((tk, t_state, y))
        rec.add_frame([[0.0, 0.0, 0.0], [x, y, ang]], tk, **{"y (m)": y})
    runs.append(rec)
    labels.append(label)
    shown = np.array(shown)
    first = int(np.argmax(shown[:, 1] == shown[-1, 1]))  # first frame showing the last state
    ahead = float(np.max(shown[:, 1] - shown[:, 0]))
    print(
        f"{label}: frame t = 0.1 s shows its t = {shown[1, 1]:.1f} s state; back at y = 0 at "
        f"t = {shown[-1, 1]:.1f} s (from frame t = {shown[first, 0]:.1f} s), "
        f"x = {runs[-1].frames[-1][1, 0]:.4f} m; latest state time - frame time = {ahead:+.1f} s"
    )

gif = render_gif(
    runs,
    OUT / "analytic_vs_numeric.gif",
    fps=15,
    size_px=360,
    labels=labels,
    colors=[COLOR["analytic"], COLOR["explicit_euler"], "C4"],
    panel="y (m)",
    trail=True,
)
print(f"wrote {len(frame_times)} frames to {gif.name}")

# %% [markdown]
# ## Exercises
#
# Predict first, then run the cell under the question, then open the answer.
#
# **1.** Halve the slides' step to $\Delta t = 0.5$ s (explicit Euler). When and where does the
# ball come back to $y = 0$, and how high is the highest point of its table?


# %%
def land(integrator: str, dt: float) -> tuple[float, float, float]:
    """Step a ball until it is back at y <= 0: (time, x, highest y of its steps)."""
    world, ball = ball_world(integrator, dt)
    top = 0.0
    while True:
        world.step()
        top = max(top, ball.position[1])
        if ball.position[1] <= 1e-9:
            return world.time, ball.position[0], top


t1, x1, top1 = land("explicit_euler", 0.5)
print(f"explicit Euler, dt = 0.5 s: back at y = 0 at t = {t1:g} s, x = {x1:g} m, top {top1:g} m")

# %% [markdown]
# <details><summary>Answer</summary>
#
# The Euler points lie on the parabola thrown at $\mathbf{u} - \frac{1}{2}\mathbf{a}\Delta t =
# [3\ 4.25]$: it stays up $2 \times 4.25 / 1 = 8.5$ s $= T + \Delta t$, so the ball lands at
# $x = 3 \times 8.5 = 25.5$ m, half as far past 24 m as with $\Delta t = 1$ s (first order).
# That parabola peaks at $4.25^2 / 2 = 9.03$ m at $t = 4.25$ s, between two steps; the steps at
# $t = 4$ and $4.5$ s both sit at $4.25 t - t^2/2 = 9.0$ m. The run prints exactly these.
#
# </details>
#
# **2.** Switch the slides' example ($\Delta t = 1$ s) to semi-implicit Euler. Where does it land
# now, and what is the top of its table?

# %%
t2, x2, top2 = land("semi_implicit_euler", 1.0)
print(f"semi-implicit Euler, dt = 1 s: back at y = 0 at t = {t2:g} s, x = {x2:g} m, top {top2:g} m")

# %% [markdown]
# <details><summary>Answer</summary>
#
# The mirror image: $\mathbf{p}_n = \mathbf{s} + \mathbf{u}\,n\Delta t + \mathbf{a}\,\Delta t^2
# n(n+1)/2$, the parabola thrown at $\mathbf{u} + \frac{1}{2}\mathbf{a}\Delta t = [3\ 3.5]$. It is
# up for $2 \times 3.5 = 7$ s $= T - \Delta t$: $x = 21$ m, one step *early*. Its apex,
# $3.5^2/2 = 6.125$ m at $t = 3.5$ s, falls between steps 3 and 4, both at $6$ m.
#
# </details>
#
# **3.** The spring again, with explicit Euler at twice the step ($\Delta t = 0.1$ s,
# $\omega\Delta t = 0.2$). By what factor has its energy grown after 20 s? And semi-implicit
# Euler's?

# %%
for m in ("explicit_euler", "semi_implicit_euler"):
    p3, v3 = np.array([1.0, 0.0]), np.array([0.0, 0.0])
    e3 = [spring_energy(p3, v3)]
    for _ in range(200):
        p3, v3, _, _ = integrators.integrate(m, p3, v3, 0.0, 0.0, spring_accel, 0.1)
        e3.append(spring_energy(p3, v3))
    e3 = np.array(e3) / e3[0]
    print(f"{LABEL[m]}: E(20 s) / E(0) = {e3[-1]:.1f}, range {e3.min():.3f} .. {e3.max():.3f}")

# %% [markdown]
# <details><summary>Answer</summary>
#
# Each explicit step multiplies the energy by $1 + (\omega\Delta t)^2 = 1.04$; 200 steps give
# $1.04^{200} = 2550.7$: doubling the step did not double the growth, it raised it from 53 to
# 2551 (the exponent doubled). Semi-implicit Euler keeps its shadow energy, so its energy stays
# within $[1/(1 + \omega\Delta t/2), 1/(1 - \omega\Delta t/2)] = [0.909, 1.111]$; the run
# reaches $0.909$ and $1.111$.
#
# </details>
