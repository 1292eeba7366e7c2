# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: percent
# ---

# %% [markdown]
# # 07 Collision response
#
# Slides "Collision Response", "Coefficient of Restitution", "Collision Effects" and
# "Collision Equation".
#
# Rigid bodies do not squash and spring back: the engine replaces the short compression and
# expansion of a real collision by an **impulse**, an instant change of momentum along the
# contact normal $\hat{\mathbf{n}}$,
# $$\mathbf{J}_1 = m_1(\mathbf{v}'_{n1} - \mathbf{v}_{n1}) = -\mathbf{J}_2
#   = -m_2(\mathbf{v}'_{n2} - \mathbf{v}_{n2}),$$
# sized so that the normal relative velocity of the contact points changes by the
# **coefficient of restitution** $e = |\mathbf{v}'_n| / |\mathbf{v}_n|$ ($e = 1$ elastic,
# $e = 0$ sticky), while the tangential part is untouched (no friction in this lesson):
# $\mathbf{v}' = \mathbf{v} - (1 + e)(\mathbf{v}\cdot\hat{\mathbf{n}})\,\hat{\mathbf{n}}$.
#
# (The slide writes the last member as $= m_2(\mathbf{v}'_{n2} - \mathbf{v}_{n2})$, without the
# minus: one of three sign slips, section 5.)
#
# The lesson checks, against closed forms: a ball bouncing to $e^2 h$; two discs colliding
# head-on and off-centre; the collision equation derived step by step and worked by hand for one
# contact; the three sign slips in the slides; and a Newton's cradle.
#
# A contact's restitution is the **product** of the two shapes' values (as in pymunk), so the
# ground and the second disc get $e = 1$ and the moving body carries the $e$ we want.

# %%
import json
import math

import matplotlib.pyplot as plt
import numpy as np

import sandbox
from sandbox.body import Body
from sandbox.lessonkit import output_dir, print_table, save_figure, scene_path
from sandbox.recording import record
from sandbox.render import render_gif
from sandbox.shapes import Box, Circle
from sandbox.world import World

# knobs
G = 9.81  # m/s^2
DT = 1.0 / 60.0  # s
DROP_HEIGHT = 2.0  # m, gap under the ball at release
RESTITUTIONS = (0.0, 0.3, 0.6, 0.9, 1.0)
BALL_RADIUS = 0.25  # m
DROP_TIME = 2.6  # s simulated per drop
DT_STUDY = (1 / 60, 1 / 120, 1 / 240, 1 / 480)  # s, the bounce error against the step
V1, V2 = 3.0, -1.0  # m/s, head-on: disc 1 moves right, disc 2 left
IMPACT_PARAMETER = 0.5  # m, off-centre: sideways offset of the disc that is hit
CRADLE_TIME = 4.0  # s
GIF_EVERY = 3  # steps per animation frame

OUT = output_dir("07_collision_response")


def cross(a, b) -> float:
    """z-component of the 2D cross product a x b."""
    return float(a[0] * b[1] - a[1] * b[0])


def w_cross_r(w: float, r) -> np.ndarray:
    """omega x r for omega along z: (-w r_y, w r_x)."""
    return np.array([-w * r[1], w * r[0]])


# %% [markdown]
# ## 1. A bouncing ball: apex $e^2 h$
#
# Dropped from a height $h$ the ball arrives at $v = \sqrt{2 g h}$ and leaves at $e v$, so it
# climbs to $(e v)^2 / (2g) = e^2 h$. Five balls, $e = 0, 0.3, 0.6, 0.9, 1$, each in its own
# world on a ground with $e = 1$. The measured $e$ is the speed after the bounce step over the
# speed before it.


# %%
def drop_world(e: float, dt: float = DT, x: float = 0.0) -> tuple[World, Body]:
    world = World(gravity=(0.0, -G), dt=dt)
    ground = world.add_body(Body(name="ground", type="static"))
    ground.add_shape(Box(7.0, 0.5, offset=(1.6, -0.25), restitution=1.0))
    ball = world.add_body(Body(name="ball", position=(x, DROP_HEIGHT + BALL_RADIUS)))
    ball.add_shape(Circle(BALL_RADIUS, restitution=e))
    return world, ball


def drop(e: float, dt: float = DT) -> dict:
    """Drop one ball; first apex after the bounce, speeds just before and after it."""
    world, ball = drop_world(e, dt)
    t, y, v = [0.0], [DROP_HEIGHT], [0.0]
    for _ in range(int(round(DROP_TIME / dt))):
        world.step()
        t.append(world.time)
        y.append(ball.position[1] - BALL_RADIUS)
        v.append(ball.velocity[1])
    t, y, v = np.array(t), np.array(y), np.array(v)
    hit = int(np.argmax(np.diff(v) > 0)) + 1  # the step whose velocity jumped up: the bounce
    end = hit + int(np.argmax(v[hit:] <= 0.0)) if v[hit] > 0 else hit
    nxt = end + int(np.argmax(np.diff(v[end:]) > 0)) if v[hit] > 0 else len(v) - 1
    return {
        "t": t,
        "y": y,
        "apex": float(y[hit : end + 1].max()) if v[hit] > 0 else float(max(y[hit:].max(), 0.0)),
        "v_in": -v[hit - 1],
        "v_out": max(float(v[hit]), 0.0),
        "apex2": float(y[nxt : nxt + 200].max()) if v[hit] > 0 else 0.0,
    }


drops = {e: drop(e) for e in RESTITUTIONS}
rows = []
for e, d in drops.items():
    theory = e * e * DROP_HEIGHT
    err = f"{100 * (d['apex'] - theory) / theory:+.1f}" if theory > 0 else "-"
    rows.append((e, d["apex"], theory, err, d["v_in"], d["v_out"], d["v_out"] / d["v_in"]))
print_table(
    ["e", "apex (m)", "e^2 h (m)", "error %", "v in (m/s)", "v out (m/s)", "measured e"], rows
)
d1 = drops[1.0]
print(
    f"e = 1: second apex {d1['apex2']:.3f} m (h = {DROP_HEIGHT} m): the elastic ball "
    f"{'keeps its height' if abs(d1['apex2'] - d1['apex']) < 0.01 * DROP_HEIGHT else 'changes height'}"
)

# %%
fig, (ax, bx) = plt.subplots(1, 2, figsize=(12, 4), gridspec_kw={"width_ratios": [1.6, 1]})
for k, (e, d) in enumerate(drops.items()):
    ax.plot(d["t"], d["y"], color=f"C{k}", label=f"e = {e}")
    ax.axhline(e * e * DROP_HEIGHT, color=f"C{k}", ls=":", lw=1)
ax.set(xlabel="t (s)", ylabel="height of the ball's bottom (m)")
ax.set_title("y(t); dotted: e$^2$ h")
ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.0, 1.0))
e_line = np.linspace(0, 1, 50)
bx.plot(e_line, e_line**2 * DROP_HEIGHT, "k--", label="theory e$^2$ h")
bx.scatter(RESTITUTIONS, [d["apex"] for d in drops.values()], color="C3", zorder=3,
           label="measured first apex")  # fmt: skip
bx.set(xlabel="restitution e (1)", ylabel="apex (m)",
       title=f"h = {DROP_HEIGHT} m, dt = 1/{round(1 / DT)} s")  # fmt: skip
bx.legend(fontsize=8)
fig.tight_layout()
save_figure(fig, OUT / "bounce_heights.png", dpi=100)

# %% [markdown]
# **Where the remaining error comes from.** The measured $e$ equals the set one exactly: the
# engine reflects the approach speed the ball had at the *start* of the step, before this
# step's gravity was added (as Box2D does). Measuring it after adding gravity would reflect
# $e\,(v + g\Delta t)$ instead of $e\,v$ and make every bounce about
# $2 g\Delta t / v$ = 5 % too high at this $\Delta t$, so an elastic ball would climb higher at
# every bounce. What is left is where the impact falls inside a step: the contact is found up
# to a margin before touching and the ball is moved as if it had bounced at the moment of
# contact, which costs up to $(1 + e)$ times the remaining gap. For the small bounce of
# $e = 0.3$ (0.18 m, under two steps of travel at impact) that is a few per cent; impacts
# slower than 1 m/s do not bounce at all. The table below shows the error against $\Delta t$:
# it stays within a couple of per cent and does not shrink monotonically, because where the
# impact falls inside a step changes with $\Delta t$.

# %%
study = []
for dt in DT_STUDY:
    a9, a10 = drop(0.9, dt), drop(1.0, dt)
    study.append(
        (f"1/{round(1 / dt)}", a9["apex"], 100 * (a9["apex"] / (0.81 * DROP_HEIGHT) - 1),
         a10["apex"], 100 * (a10["apex"] / DROP_HEIGHT - 1), a10["v_out"] / a10["v_in"])
    )  # fmt: skip
print_table(["dt (s)", "apex e=0.9", "error %", "apex e=1", "error %", "measured e (e=1)"], study)

# %%
runs, labels = [], []
for k, e in enumerate(RESTITUTIONS):
    world, _ = drop_world(e, DT, x=0.8 * k)
    runs.append(record(world, int(round(DROP_TIME / DT)), every=GIF_EVERY))
    labels.append(f"e = {e}")
gif = render_gif(runs, OUT / "bounce.gif", fps=20, size_px=420, labels=labels,
                 view=(-0.6, 5.4, -0.4, DROP_HEIGHT + 0.6))  # room for the legend, right  # fmt: skip
print(f"wrote {len(runs[0])} frames to {gif.name}")

# %% [markdown]
# The energy of one bounce, as bars (PhET-style): the ball with $e = 0.6$ trades potential energy
# for kinetic energy on the way down, and each impact takes $1 - e^2 = 64\%$ of the kinetic
# energy it arrives with (the "lost" bar grows in steps); the contact points and impulses are
# drawn at the impacts.

# %%
world_bars, _ = drop_world(0.6)
bars = record(world_bars, int(round(DROP_TIME / DT)), every=GIF_EVERY,
              draw="contacts,impulses", energy=True)  # fmt: skip
e_start = sum(bars.series[k][0] for k in ("energy.kinetic_linear", "energy.potential_gravity"))
e_end = sum(bars.series[k][-1] for k in ("energy.kinetic_linear", "energy.kinetic_rotational",
                                          "energy.potential_gravity"))  # fmt: skip
m_ball = world_bars.body("ball").mass
print(
    f"energy lost in the first bounce, theory m g h (1 - e^2) = "
    f"{m_ball * G * DROP_HEIGHT * (1 - 0.36):.3f} J; after {DROP_TIME} s the ball has lost "
    f"{e_start - e_end:.3f} J in total"
)
gif = render_gif(bars, OUT / "bounce_energy.gif", fps=20, size_px=360, panel="energy-bars",
                 draw="contacts,impulses", view=(-0.6, 1.0, -0.4, DROP_HEIGHT + 0.6))  # fmt: skip
print(f"wrote {len(bars)} frames to {gif.name}")

# %% [markdown]
# ## 2. Two discs head-on
#
# Along the line of centres, momentum conservation $m_1 v_1 + m_2 v_2 = m_1 v'_1 + m_2 v'_2$
# and the restitution law $v'_2 - v'_1 = -e\,(v_2 - v_1)$ give
#
# $$v'_1 = \frac{(m_1 - e m_2) v_1 + (1 + e) m_2 v_2}{m_1 + m_2}, \qquad
#   v'_2 = \frac{(m_2 - e m_1) v_2 + (1 + e) m_1 v_1}{m_1 + m_2},$$
#
# and the kinetic energy lost is $\Delta K = \frac{1}{2}\frac{m_1 m_2}{m_1 + m_2}
# (1 - e^2)(v_1 - v_2)^2$ (none for $e = 1$). No gravity, frictionless discs of radius 0.5 m.


# %%
def discs(m1, m2, e, v1=(V1, 0.0), v2=(V2, 0.0), offset=0.0, dt=DT, steps=90):
    """Two discs (radius 0.5) with no gravity; returns per-step series and the collision normal."""
    world = World(gravity=(0.0, 0.0), dt=dt)
    a = world.add_body(Body(name="d1", position=(-2.0, 0.0), velocity=v1))
    a.add_shape(Circle(0.5, mass=m1, restitution=e, friction=0.0))
    b = world.add_body(Body(name="d2", position=(0.0, offset), velocity=v2))
    b.add_shape(Circle(0.5, mass=m2, restitution=1.0, friction=0.0))
    s = {k: [] for k in ("t", "v1", "v2", "px", "py", "K", "L", "x1", "x2")}
    normal = None

    def sample():
        s["t"].append(world.time)
        s["v1"].append(a.velocity)
        s["v2"].append(b.velocity)
        p = world.momentum()
        s["px"].append(p[0])
        s["py"].append(p[1])
        s["K"].append(world.kinetic_energy())
        s["L"].append(world.angular_momentum())
        s["x1"].append(a.position)
        s["x2"].append(b.position)

    sample()
    for _ in range(steps):
        world.step()
        m = world.manifolds
        if normal is None and m is not None and len(m) and m.normal_impulse.max() > 0:
            normal = m.normal[0].copy()
        sample()
    out = {k: np.array(v) for k, v in s.items()}
    out["normal"] = normal
    out["spin"] = (a.angular_velocity, b.angular_velocity)
    return out


def closed_form(m1, m2, e, u1, u2):
    w1 = ((m1 - e * m2) * u1 + (1 + e) * m2 * u2) / (m1 + m2)
    w2 = ((m2 - e * m1) * u2 + (1 + e) * m1 * u1) / (m1 + m2)
    return w1, w2


CASES = [(1.0, 1.0, 1.0), (1.0, 1.0, 0.0), (1.0, 3.0, 1.0), (1.0, 3.0, 0.0)]
head_on, rows = {}, []
for m1, m2, e in CASES:
    r = discs(m1, m2, e)
    head_on[(m1, m2, e)] = r
    t1, t2 = closed_form(m1, m2, e, V1, V2)
    loss = 0.5 * m1 * m2 / (m1 + m2) * (1 - e * e) * (V1 - V2) ** 2
    rows.append(
        (f"{m1:g}, {m2:g}", e, r["v1"][-1, 0], t1, r["v2"][-1, 0], t2,
         r["px"][-1] - r["px"][0], r["K"][0] - r["K"][-1], loss)
    )  # fmt: skip
print_table(
    ["m1, m2 (kg)", "e", "v1' engine", "v1' closed", "v2' engine", "v2' closed",
     "change of p", "K lost", "K lost theory"],
    rows,
)  # fmt: skip

# %%
fig, axes = plt.subplots(1, 4, figsize=(16, 4.4))
for k, ((m1, m2, e), r) in enumerate(head_on.items()):
    # coinciding curves are drawn as nested stripes: the first widest and palest
    style = {"color": f"C{k}", "lw": 7.0 - 1.8 * k, "alpha": 0.35 + 0.2 * k,
             "label": f"m = {m1:g}, {m2:g} kg; e = {e:g}"}  # fmt: skip
    axes[0].plot(r["t"], r["v1"][:, 0], **style)
    axes[1].plot(r["t"], r["v2"][:, 0], **style)
    axes[2].plot(r["t"], r["px"], **style)
    axes[3].plot(r["t"], r["K"], **style)
axes[0].set(xlabel="t (s)", ylabel="$v_1$ (m/s)", title="disc 1 velocity")
axes[1].set(xlabel="t (s)", ylabel="$v_2$ (m/s)", title="disc 2 velocity")
axes[2].set(xlabel="t (s)", ylabel="$p_x$ (kg m/s)", title="momentum: constant (2 and 0 kg m/s)")
axes[3].set(xlabel="t (s)", ylabel="K (J)", title="kinetic energy: kept for e = 1 only")
handles, names = axes[0].get_legend_handles_labels()
fig.legend(handles, names, loc="lower center", ncol=4, fontsize=8)
fig.tight_layout(rect=(0, 0.08, 1, 1))
save_figure(fig, OUT / "head_on.png", dpi=100)

# %% [markdown]
# ## 3. Off-centre
#
# Disc 1 moves along $x$ and hits disc 2 (at rest) off-centre, the centres $b$ = 0.5 m apart
# sideways. At the touch the normal is the line of centres,
# $\hat{\mathbf{n}} = (\cos\varphi, \sin\varphi)$ with $\sin\varphi = b / (r_1 + r_2)$
# ($\varphi = 30°$). Frictionless discs feel only the normal impulse: it passes through both
# centres, so neither starts to spin, and only the normal components change, by the head-on
# formula applied to $u_i = \mathbf{v}_i\cdot\hat{\mathbf{n}}$. For equal masses and $e = 1$
# the two discs leave at right angles.

# %%
phi = math.asin(IMPACT_PARAMETER / 1.0)
n_true = np.array([math.cos(phi), math.sin(phi)])


def oblique(m1, m2, e, n):
    u1, u2 = V1 * n[0], 0.0
    w1, w2 = closed_form(m1, m2, e, u1, u2)
    v1 = np.array([V1, 0.0]) + (w1 - u1) * n
    v2 = (w2 - u2) * n
    return v1, v2


rows, oblique_runs = [], {}
for m1, m2, e in [(1.0, 1.0, 1.0), (1.0, 3.0, 0.5)]:
    r = discs(m1, m2, e, v2=(0.0, 0.0), offset=IMPACT_PARAMETER)
    oblique_runs[(m1, m2, e)] = r
    for name, n in (("true normal", n_true), ("engine's normal", r["normal"])):
        v1, v2 = oblique(m1, m2, e, n)
        rows.append((f"{m1:g}, {m2:g}, {e:g}", name, math.degrees(math.atan2(n[1], n[0])),
                     f"({v1[0]:.4f}, {v1[1]:.4f})", f"({v2[0]:.4f}, {v2[1]:.4f})"))  # fmt: skip
    v1e, v2e = r["v1"][-1], r["v2"][-1]
    rows.append((f"{m1:g}, {m2:g}, {e:g}", "engine", "", f"({v1e[0]:.4f}, {v1e[1]:.4f})",
                 f"({v2e[0]:.4f}, {v2e[1]:.4f})"))  # fmt: skip
    print(f"m = {m1:g}, {m2:g}, e = {e:g}: spins after {r['spin'][0]:.1e}, {r['spin'][1]:.1e} "
          f"rad/s; p change {np.ptp(r['px']):.1e}, {np.ptp(r['py']):.1e}; "
          f"L change {np.ptp(r['L']):.1e}")  # fmt: skip
print_table(["m1, m2, e", "closed form with", "normal angle (deg)", "v1'", "v2'"], rows)
r = oblique_runs[(1.0, 1.0, 1.0)]
print(f"equal masses, e = 1: angle between v1' and v2' = "
      f"{math.degrees(math.acos(r['v1'][-1] @ r['v2'][-1] / np.linalg.norm(r['v1'][-1]) / np.linalg.norm(r['v2'][-1]))):.2f} deg")  # fmt: skip
for dt in (1 / 60, 1 / 240, 1 / 960):
    n = discs(1.0, 1.0, 1.0, v2=(0.0, 0.0), offset=IMPACT_PARAMETER, dt=dt, steps=int(1.5 / dt))
    print(f"dt = 1/{round(1 / dt)}: engine's normal at "
          f"{math.degrees(math.atan2(n['normal'][1], n['normal'][0])):.3f} deg (touching: 30)")  # fmt: skip

# %% [markdown]
# The engine matches the closed form to rounding **with the normal it used**. That normal is
# the line of centres at the start of the step in which the discs meet, when they are still a
# little apart (a speculative contact), so it is a fraction of a degree off the touching
# normal; the error shrinks with $\Delta t$.

# %%
fig, axes = plt.subplots(1, 3, figsize=(14, 3.8))
ax = axes[0]
for k, ((m1, m2, e), r) in enumerate(oblique_runs.items()):
    lab = f"m = {m1:g}, {m2:g}; e = {e:g}"
    ax.plot(r["x1"][:, 0], r["x1"][:, 1], color=f"C{k}", label=lab + " disc 1")
    ax.plot(r["x2"][:, 0], r["x2"][:, 1], color=f"C{k}", ls="--", label=lab + " disc 2")
    axes[1].plot(r["t"], r["px"], color=f"C{k}", label=f"$p_x$, {lab}")
    axes[1].plot(r["t"], r["py"], color=f"C{k}", ls=":", label=f"$p_y$, {lab}")
    axes[2].plot(r["t"], r["K"], color=f"C{k}", label=f"K, {lab}")
ax.add_patch(plt.Circle((0.0, IMPACT_PARAMETER), 0.5, fill=False, color="0.5"))
ax.set(xlabel="x (m)", ylabel="y (m)", aspect="equal", title="paths of the centres")
axes[1].set(xlabel="t (s)", ylabel="momentum (kg m/s)", title="momentum: constant")
axes[2].set(xlabel="t (s)", ylabel="K (J)", title="kinetic energy")
for ax in axes:
    ax.legend(fontsize=7)
fig.tight_layout()
save_figure(fig, OUT / "off_centre.png", dpi=100)

# %% [markdown]
# ## 4. The collision impulse, derived step by step
#
# The slides jump from "compute the contact point velocities" to the collision equation
# ("several substitutions later"). The substitutions, for one contact point, in 2D (a turn
# $\omega$ is a vector $\omega\hat{\mathbf{z}}$ and $\mathbf{a}\times\mathbf{b} = a_xb_y -
# a_yb_x$ is a number):
#
# 1. **What is unknown.** One number, the impulse magnitude $j$: the contact pushes body 2 with
#    $+j\hat{\mathbf{n}}$ and body 1 with $-j\hat{\mathbf{n}}$ (Newton's third law;
#    $\hat{\mathbf{n}}$ points from body 1 to body 2), along the normal only because there is no
#    friction.
# 2. **What an impulse does to a body.** An impulse $\mathbf{J}$ at $\mathbf{r}$ from the
#    centre of mass changes the momentum and the angular momentum:
#    $\Delta\mathbf{v} = \mathbf{J}/m$, $\Delta\omega = (\mathbf{r}\times\mathbf{J})/I$. So
#    $\mathbf{v}'_2 = \mathbf{v}_2 + j\hat{\mathbf{n}}/m_2$,
#    $\omega'_2 = \omega_2 + j\,(\mathbf{r}_2\times\hat{\mathbf{n}})/I_2$, and the same with
#    $-j$ for body 1.
# 3. **What that does to the contact point.** Its velocity is
#    $\mathbf{v}_{c} = \mathbf{v} + \omega\hat{\mathbf{z}}\times\mathbf{r}$, and along the normal
#    $(\omega\hat{\mathbf{z}}\times\mathbf{r})\cdot\hat{\mathbf{n}} =
#    \omega\,(\mathbf{r}\times\hat{\mathbf{n}})$ (a triple product). So the impulse changes
#    $\mathbf{v}_{c2}\cdot\hat{\mathbf{n}}$ by $j\,[1/m_2 + (\mathbf{r}_2\times
#    \hat{\mathbf{n}})^2/I_2]$ and $\mathbf{v}_{c1}\cdot\hat{\mathbf{n}}$ by
#    $-j\,[1/m_1 + (\mathbf{r}_1\times\hat{\mathbf{n}})^2/I_1]$.
# 4. **The relative normal velocity is linear in $j$.** With $v_n = (\mathbf{v}_{c2} -
#    \mathbf{v}_{c1})\cdot\hat{\mathbf{n}}$ (negative while approaching):
#    $$v'_n = v_n + j\,k, \qquad k = \frac{1}{m_1} + \frac{1}{m_2} +
#    \frac{(\mathbf{r}_1\times\hat{\mathbf{n}})^2}{I_1} +
#    \frac{(\mathbf{r}_2\times\hat{\mathbf{n}})^2}{I_2}.$$
#    $1/k$ is the **effective mass** of the contact: the mass a unit push along the normal "feels"
#    at that point. A push far off the centre ($\mathbf{r}\times\hat{\mathbf{n}}$ large) turns
#    the body more easily than it moves it, so the point gives way more: $k$ grows.
# 5. **Impose restitution.** $v'_n = -e\,v_n$ gives $j\,k = -(1 + e)\,v_n$, i.e.
#    $$j = \frac{-(1 + e)\,v_n}{k},$$
#    the slides' step 1. Their 3D denominator term
#    $(I^{-1}(\mathbf{r}\times\hat{\mathbf{n}})\times\mathbf{r})\cdot\hat{\mathbf{n}}$ is the same
#    thing: in 2D $((\mathbf{r}\times\hat{\mathbf{n}})\hat{\mathbf{z}}\times\mathbf{r})\cdot
#    \hat{\mathbf{n}}/I = (\mathbf{r}\times\hat{\mathbf{n}})^2/I$.
# 6. **Checks.** Momentum: $m_1\Delta\mathbf{v}_1 + m_2\Delta\mathbf{v}_2 = -j\hat{\mathbf{n}} +
#    j\hat{\mathbf{n}} = 0$. Energy: the impulse does work $j\,(v_n + v'_n)/2$ (force times the
#    mean speed of the point), so $\Delta K = -\frac{(1 - e^2)\,v_n^2}{2k}$: nothing lost for
#    $e = 1$, the most for $e = 0$. For two discs head on, $k = 1/m_1 + 1/m_2$ and this is the
#    $\frac{1}{2}\frac{m_1 m_2}{m_1 + m_2}(1 - e^2)(v_1 - v_2)^2$ of section 2.
#
# ### By hand, for one contact
#
# One contact between two dynamic bodies that turn: a tilted box (body 1, 1 x 0.5 m, $e = 0.5$)
# whose corner just touches the top of a slab (body 2, 2 x 0.5 m, $e = 1$, so $e = 0.5$ in the
# contact), no gravity, no friction. With $\mathbf{r}_i$ from each centre of mass to the contact
# point and $\hat{\mathbf{n}}$ from body 1 to body 2:
#
# - contact point velocities $\mathbf{v}_{ci} = \mathbf{v}_i + \boldsymbol{\omega}_i \times
#   \mathbf{r}_i$, relative velocity $\mathbf{v}_r = \mathbf{v}_{c2} - \mathbf{v}_{c1}$
# - step 1: $j = \dfrac{-(1+e)\,\mathbf{v}_r\cdot\hat{\mathbf{n}}}{\frac{1}{m_1} + \frac{1}{m_2}
#   + \left(I_1^{-1}(\mathbf{r}_1\times\hat{\mathbf{n}})\times\mathbf{r}_1
#   + I_2^{-1}(\mathbf{r}_2\times\hat{\mathbf{n}})\times\mathbf{r}_2\right)\cdot\hat{\mathbf{n}}}$,
#   where in 2D each bracket term is $(\mathbf{r}_i\times\hat{\mathbf{n}})^2 / I_i$
# - step 2: $\mathbf{j}_1 = -j\hat{\mathbf{n}}$, $\mathbf{j}_2 = +j\hat{\mathbf{n}}$
#   (see section 5 for the sign)
# - step 3: $\mathbf{v}'_i = \mathbf{v}_i + \mathbf{j}_i / m_i$,
#   $\omega'_i = \omega_i + I_i^{-1}(\mathbf{r}_i\times\mathbf{j}_i)$
#
# One `world.step()` of the engine applies exactly this (a non-penetration impulse, then the
# restitution pass, which together add up to the slide's $j$).


# %%
def equation_world() -> tuple[World, Body, Body]:
    world = World(gravity=(0.0, 0.0), dt=DT)
    b1 = world.add_body(Body(name="box", angle=0.4, velocity=(0.5, -2.0), angular_velocity=1.5))
    b1.add_shape(Box(1.0, 0.5, restitution=0.5, friction=0.0))
    low = min((b1.world_point(v) for v in b1.shapes[0].vertices), key=lambda p: p[1])
    slab_at = (low[0] + 0.6, low[1] - 0.25 + 0.001)  # 1 mm overlap, 0.6 m off the slab's centre
    b2 = world.add_body(Body(name="slab", position=slab_at, velocity=(0.0, 0.5)))
    b2.add_shape(Box(2.0, 0.5, restitution=1.0, friction=0.0))
    return world, b1, b2


world, b1, b2 = equation_world()
(contact,) = world.find_contacts()
assert contact.a is b1 and contact.b is b2
n, p, e = np.asarray(contact.normal), np.asarray(contact.points[0]), 0.5 * 1.0
m1, m2, i1, i2 = b1.mass, b2.mass, b1.moment, b2.moment
r1, r2 = p - np.asarray(b1.center_of_mass), p - np.asarray(b2.center_of_mass)
v1, v2 = np.asarray(b1.velocity), np.asarray(b2.velocity)
w1, w2 = b1.angular_velocity, b2.angular_velocity
vc1, vc2 = v1 + w_cross_r(w1, r1), v2 + w_cross_r(w2, r2)
vr = vc2 - vc1
terms = (1 / m1, 1 / m2, cross(r1, n) ** 2 / i1, cross(r2, n) ** 2 / i2)
j = -(1 + e) * (vr @ n) / sum(terms)  # step 1
j1, j2 = -j * n, j * n  # step 2 (body 1 is pushed away from body 2)
v1n, v2n = v1 + j1 / m1, v2 + j2 / m2  # step 3a
w1n, w2n = w1 + cross(r1, j1) / i1, w2 + cross(r2, j2) / i2  # step 3b
vr_after = (v2n + w_cross_r(w2n, r2)) - (v1n + w_cross_r(w1n, r1))


def fmt(v) -> str:
    return "(" + ", ".join(f"{float(c):+.5f}" for c in np.atleast_1d(v)) + ")"


print(f"m1 = {m1:.4f} kg, I1 = {i1:.5f} kg m^2; m2 = {m2:.4f} kg, I2 = {i2:.5f} kg m^2")
print(f"n = {fmt(n)}, contact point {fmt(p)}, r1 = {fmt(r1)}, r2 = {fmt(r2)}")
print(f"v_c1 = v1 + w1 x r1 = {fmt(vc1)}, v_c2 = {fmt(vc2)}, v_r = {fmt(vr)}, "
      f"v_r.n = {vr @ n:+.5f} m/s")  # fmt: skip
print("denominator 1/m1 + 1/m2 + (r1 x n)^2/I1 + (r2 x n)^2/I2 = "
      + " + ".join(f"{t:.5f}" for t in terms) + f" = {sum(terms):.5f}")  # fmt: skip
print(f"j = -(1 + {e}) ({vr @ n:+.5f}) / {sum(terms):.5f} = {j:.6f} N s")
world.step()
print_table(
    ["quantity", "by hand", "engine", "difference"],
    [
        ("v1' x (m/s)", v1n[0], b1.velocity[0], abs(v1n[0] - b1.velocity[0])),
        ("v1' y (m/s)", v1n[1], b1.velocity[1], abs(v1n[1] - b1.velocity[1])),
        ("omega1' (rad/s)", w1n, b1.angular_velocity, abs(w1n - b1.angular_velocity)),
        ("v2' x (m/s)", v2n[0], b2.velocity[0], abs(v2n[0] - b2.velocity[0])),
        ("v2' y (m/s)", v2n[1], b2.velocity[1], abs(v2n[1] - b2.velocity[1])),
        ("omega2' (rad/s)", w2n, b2.angular_velocity, abs(w2n - b2.angular_velocity)),
        ("impulse j (N s)", j, float(world.manifolds.normal_impulse[0, 0]),
         abs(j - float(world.manifolds.normal_impulse[0, 0]))),
    ],
    6,
)  # fmt: skip
print(f"check: v_r'.n = {vr_after @ n:+.5f} = -e v_r.n = {-e * (vr @ n):+.5f}")
k_before = 0.5 * (m1 * v1 @ v1 + i1 * w1**2 + m2 * v2 @ v2 + i2 * w2**2)
k_after = 0.5 * (m1 * np.dot(b1.velocity, b1.velocity) + i1 * b1.angular_velocity**2
                 + m2 * np.dot(b2.velocity, b2.velocity) + i2 * b2.angular_velocity**2)  # fmt: skip
print(
    f"check: K lost by the engine {k_after - k_before:+.5f} J, "
    f"-(1 - e^2) v_n^2 / (2 k) = {-(1 - e * e) * (vr @ n) ** 2 / (2 * sum(terms)):+.5f} J"
)

# %% [markdown]
# ## 5. Three sign slips in the slides
#
# **Newton's third law.** The slide "Collision Response" writes
# $\mathbf{J}_1 = m_1(\mathbf{v}'_{n1} - \mathbf{v}_{n1}) = -\mathbf{J}_2 =
# m_2(\mathbf{v}'_{n2} - \mathbf{v}_{n2})$. Body 2's impulse is $\mathbf{J}_2 =
# m_2(\mathbf{v}'_{n2} - \mathbf{v}_{n2})$, so the last member needs a minus,
# $-\mathbf{J}_2 = -m_2(\mathbf{v}'_{n2} - \mathbf{v}_{n2})$; as printed it says the two bodies
# change momentum by the *same* amount in the same direction, which would create momentum. (This
# lesson's introduction writes the corrected form.) The head-on run of section 2 with
# $m = 1, 3$ kg and $e = 1$ shows it below.
#
# **Contact point velocity.** The slide writes $\mathbf{v}_{contact} = \mathbf{v} +
# \mathbf{r}\times\boldsymbol{\omega}$. With $\boldsymbol{\omega} = \omega\hat{\mathbf{z}}$,
# $\boldsymbol{\omega}\times\mathbf{r} = \omega(-r_y, r_x)$ but
# $\mathbf{r}\times\boldsymbol{\omega} = \omega(r_y, -r_x)$: the same vector reversed. The
# right one is $\mathbf{v} + \boldsymbol{\omega}\times\mathbf{r}$; we check it against the
# actual motion of the box's corner, $(\mathbf{p}(t + h) - \mathbf{p}(t - h)) / 2h$ for the rigid
# motion $\mathbf{p}(t) = \mathbf{c} + \mathbf{v}t + R(\theta + \omega t)\,\mathbf{q}$.
#
# **Which body gets $+j\hat{\mathbf{n}}$.** With $\hat{\mathbf{n}}$ pointing from body 1 to body
# 2 and $j > 0$, $+j\hat{\mathbf{n}}$ pushes towards body 2. The slide's
# $\mathbf{j}_1 = j\hat{\mathbf{n}}$ drives body 1 *into* body 2. Below, every combination is
# applied to the same contact and judged by the true relative normal velocity afterwards
# (it should be $-e\,\mathbf{v}_r\cdot\hat{\mathbf{n}}$, separating) and the kinetic energy.

# %%
r13 = head_on[(1.0, 3.0, 1.0)]
j1_run = 1.0 * (r13["v1"][-1, 0] - r13["v1"][0, 0])  # m1 (v'1 - v1), N s along x
j2_run = 3.0 * (r13["v2"][-1, 0] - r13["v2"][0, 0])  # m2 (v'2 - v2)
print_table(
    ["head-on, m = 1, 3 kg, e = 1", "N s"],
    [("J1 = m1 (v'1 - v1)", j1_run), ("m2 (v'2 - v2) = J2", j2_run),
     ("slide: -J2 = m2 (v'2 - v2), i.e. J1 =", j2_run),
     ("corrected: -J2 = -m2 (v'2 - v2), i.e. J1 =", -j2_run)],
)  # fmt: skip

world, b1, b2 = equation_world()
theta, q = b1.angle, b1.local_point(p) + 0.0  # the corner in body 1's origin frame
h = 1e-6


def corner_at(t: float) -> np.ndarray:
    c0 = np.asarray(b1.position)
    a = theta + w1 * t
    rot = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
    return c0 + v1 * t + rot @ q


fd = (corner_at(h) - corner_at(-h)) / (2 * h)
print_table(
    ["contact point velocity of body 1", "x (m/s)", "y (m/s)"],
    [
        ("finite difference of the corner's motion", fd[0], fd[1]),
        ("v + omega x r (engine)", vc1[0], vc1[1]),
        ("v + r x omega (slide)", (v1 - w_cross_r(w1, r1))[0], (v1 - w_cross_r(w1, r1))[1]),
    ],
    5,
)
K0 = world.kinetic_energy()


def respond(slide_velocity: bool, slide_sign: bool):
    """Apply the collision equation with the slides' choices switched on or off."""
    sgn = -1.0 if slide_velocity else 1.0  # r x w = -(w x r)
    a1, a2 = v1 + sgn * w_cross_r(w1, r1), v2 + sgn * w_cross_r(w2, r2)
    jj = -(1 + e) * ((a2 - a1) @ n) / sum(terms)
    s1 = 1.0 if slide_sign else -1.0  # body 1 receives s1 j n, body 2 the opposite
    nv1, nv2 = v1 + s1 * jj * n / m1, v2 - s1 * jj * n / m2
    nw1 = w1 + cross(r1, s1 * jj * n) / i1
    nw2 = w2 + cross(r2, -s1 * jj * n) / i2
    after = (nv2 + w_cross_r(nw2, r2)) - (nv1 + w_cross_r(nw1, r1))  # true kinematics
    k = 0.5 * (m1 * nv1 @ nv1 + i1 * nw1**2 + m2 * nv2 @ nv2 + i2 * nw2**2)
    return jj, after @ n, k


rows = []
for sv, sj, name in [
    (False, False, "w x r, j1 = -j n (engine)"),
    (True, False, "r x w (slide), j1 = -j n"),
    (False, True, "w x r, j1 = +j n (slide)"),
    (True, True, "both as on the slide"),
]:
    jj, vn_after, k = respond(sv, sj)
    rows.append((name, jj, vn_after, -e * (vr @ n), k, 100 * (k - K0) / K0))
print_table(
    ["convention", "j (N s)", "v_r'.n after", "should be", "K after (J)", "K change %"], rows, 4
)
print(f"K before = {K0:.4f} J; an approaching contact has v_r.n = {vr @ n:+.4f} m/s < 0")
sign_rows = rows

# %%
fig, (ax, bx, cx) = plt.subplots(1, 3, figsize=(14, 5.2), gridspec_kw={"width_ratios": [1.2, 1, 1]})
for body, col in ((b1, "C0"), (b2, "0.5")):
    pts = np.array([body.world_point(v) for v in body.shapes[0].vertices])
    ax.fill(pts[:, 0], pts[:, 1], color=col, alpha=0.3)
c1 = np.asarray(b1.center_of_mass)
ax.plot(*c1, "k+")
ax.annotate("", p, c1, arrowprops={"arrowstyle": "->", "color": "k"})
ax.text(*(0.5 * (c1 + p) + (-0.12, 0.05)), "r1")
scale = 0.15
for vec_, col, lab in [
    (fd, "k", "corner's actual velocity"),
    (vc1, "C2", r"$v + \omega \times r$"),
    (v1 - w_cross_r(w1, r1), "C3", r"$v + r \times \omega$ (slide)"),
    (n * 0.4 / scale, "C1", "n (body 1 to body 2)"),
]:
    wide = 0.016 if col == "k" else 0.008  # the actual velocity drawn wider, under the others
    ax.quiver(*p, *(scale * vec_), angles="xy", scale_units="xy", scale=1, color=col, width=wide,
              label=lab)  # fmt: skip
ax.set(aspect="equal", xlim=(-1.0, 1.0), ylim=(-1.05, 0.5), title="contact point of the box",
       xlabel="x (m)", ylabel="y (m)")  # fmt: skip
ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=2)
labels = ["engine", "r x w", "j1 = +j n", "both slide"]
bx.bar(np.arange(4), [r[2] for r in sign_rows], 0.6, color=["C2", "C3", "C3", "C3"])
bx.axhline(-e * (vr @ n), color="C2", ls="--", label="target -e v_r.n (separating)")
bx.axhline(0, color="k", lw=0.8)
bx.set_xticks(np.arange(4), labels)
bx.set(ylabel="v_r'.n after (m/s)", title="normal velocity after the impulse")
bx.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.1))
cx.bar(np.arange(4), [r[5] for r in sign_rows], 0.6, color=["C2", "C3", "C3", "C3"])
cx.axhline(0, color="k", lw=0.8)
cx.set_xticks(np.arange(4), labels)
cx.set(ylabel="kinetic energy change (%)", title=f"K before = {K0:.3f} J, e = {e}")
fig.tight_layout()
save_figure(fig, OUT / "sign_slips.png", dpi=100)

# %% [markdown]
# With the slide's $\mathbf{r}\times\boldsymbol{\omega}$ the engine would misjudge how fast the
# corner approaches, so the impulse is wrong and the bodies do not leave at $-e$ times the
# approach speed. With the slide's $\mathbf{j}_1 = +j\hat{\mathbf{n}}$ the bodies are pushed
# into each other: they approach faster after the "collision" than before, and kinetic energy
# appears from nowhere.
#
# ## 6. Newton's cradle
#
# Five balls ($e = 1$) hang from pin joints (`scenes/newtons_cradle.json`); the first is pulled
# out 30 degrees. Theory for a chain of *separate* elastic collisions of equal masses: each
# collision swaps the two velocities, so the momentum runs down the chain and only the last ball
# swings out, with the whole energy. The balls here touch, so all four contacts are in the same
# step, and the solvers disagree:
#
# - `pairwise` resolves each contact once, in turn (the slides' collision algorithm). The
#   contacts come in the order ball0-ball1, ball1-ball2, ..., and each sees the velocities the
#   one before left: within one step the swap runs down the chain, the classic result.
# - `iterative` works in two passes per step (as Box2D does). First its sweeps make every
#   contact stop approaching, with no bounce: for touching balls of equal mass that is one
#   inelastic block, all five at $v_0/5$. Then a single **restitution pass** visits only the
#   contacts that approached faster than `restitution_threshold` (1 m/s) at the start of the
#   step, here ball0-ball1 alone, and pushes those two balls apart at $e v_0 = v_0$: ball0 gets
#   $v_0/5 - v_0/2 = -0.3\,v_0$ (it rebounds), ball1 $0.7\,v_0$. Next step ball1 approaches
#   ball2 at $0.5\,v_0 = 1.40$ m/s, above the threshold: balls 1-4 become a block at
#   $0.325\,v_0$ and the bounce of contact 1-2 leaves ball1 at $0.075\,v_0$, ball2 at
#   $0.575\,v_0$. Ball2 then approaches ball3 at only $0.25\,v_0 = 0.70$ m/s, below the
#   threshold: no bounce, balls 2-4 move on as one block at $0.408\,v_0$. The bounce dies in the
#   chain and much of the kinetic energy goes with it, although $e = 1$.
# - `shock` relaxes the contacts the same way, and its shock pass (which only removes what is
#   left of bodies sinking into the layer below) finds nothing to do in a row of balls that
#   already stopped approaching; the restitution pass comes after it. So here it gives the same
#   velocities as `iterative`.
#
# `chain_model` below replays exactly these rules for five equal balls (no gravity, no pins:
# the impulses only) and predicts the velocities; the engine's differ by what gravity and the
# pins do during the five steps.


# %%
def no_approach(v: np.ndarray) -> np.ndarray:
    """The sweeps' answer for touching equal balls: neighbours that approach merge into blocks
    moving at their mean velocity, until no ball moves faster than the one ahead of it."""
    blocks = []  # [sum of velocities, count]
    for x in v:
        blocks.append([x, 1])
        while len(blocks) > 1 and blocks[-2][0] / blocks[-2][1] > blocks[-1][0] / blocks[-1][1]:
            s_, c_ = blocks.pop()
            blocks[-1][0] += s_
            blocks[-1][1] += c_
    return np.concatenate([np.full(c_, s_ / c_) for s_, c_ in blocks])


def chain_model(v0: float, steps: int = 5, e: float = 1.0, threshold: float = 1.0):
    """Velocities of five equal touching balls after ``steps`` steps, ball0 arriving at v0:
    each step the sweeps (no approach), then one restitution pass."""
    v = np.array([v0, 0.0, 0.0, 0.0, 0.0])
    for _ in range(steps):
        approach = v[:-1] - v[1:]  # at the start of the step (> 0: closing)
        v = no_approach(v)  # the velocity sweeps
        for i in np.flatnonzero(approach > threshold):  # the restitution pass, once, in order
            push = max(0.0, (e * approach[i] - (v[i + 1] - v[i])) / 2)
            v[i] -= push
            v[i + 1] += push
    return v


# %%
def cradle(solver: str):
    scene = json.loads(scene_path("newtons_cradle").read_text())
    scene.setdefault("settings", {})["solver"] = solver
    world = sandbox.load_scene(scene)
    return world, [world.body(f"ball{i}") for i in range(5)]


rows = []
for solver in ("pairwise", "shock", "iterative"):
    world, balls = cradle(solver)
    hit = False
    while not hit:  # swing until the step in which ball0 first pushes ball1
        state = ([b.velocity[0] for b in balls], world.energy(), world.kinetic_energy())
        world.step()
        m = world.manifolds
        hit = m is not None and len(m) > 0 and float(m.normal_impulse.max()) > 0.0
    before, e_before, k_before = state
    for _ in range(4):  # four more steps: the velocities after the impact have settled
        world.step()
    after = [b.velocity[0] for b in balls]
    e_after = world.energy()
    rows.append((solver, " ".join(f"{v:+.2f}" for v in before),
                 " ".join(f"{v:+.2f}" for v in after), k_before, e_after - e_before,
                 100 * (e_after - e_before) / k_before))  # fmt: skip
    if solver != "pairwise":
        model = chain_model(before[0])
        rows.append((f"{solver}, chain_model", "", " ".join(f"{v:+.2f}" for v in model),
                     "", "", 100 * (float(model @ model) / before[0] ** 2 - 1)))  # fmt: skip
print_table(["solver", "vx before (5 balls)", "vx 5 steps later", "K before (J)",
             "E = K + U change (J)", "as % of K"], rows, 3)  # fmt: skip
print("theory for e = 1 and separate collisions: after = (0, 0, 0, 0, v0), K kept")

# %% [markdown]
# In the animation (both runs overlaid, blue pairwise, orange iterative) the debug layers draw
# each contact point and the normal impulse it applied in the last step, and the energy bars
# beside it (one bar per run) show where the energy goes: the pairwise cradle passes its kinetic
# energy on whole, the iterative one loses 40% of it in the first impacts (the "lost" bar).

# %%
runs = []
for solver in ("pairwise", "iterative"):
    world, _ = cradle(solver)
    for body in world.bodies:  # 2 m lower: the balls hang at y = 0, where gravity's energy is 0
        body.position = (body.position[0], body.position[1] - 2.0)
    steps = int(round(CRADLE_TIME / world.dt))
    runs.append(record(world, steps, every=GIF_EVERY, draw="contacts,impulses", energy=True))
gif = render_gif(runs, OUT / "newtons_cradle.gif", fps=20, size_px=360,
                 labels=["pairwise (in turn)", "iterative (together)"], panel="energy-bars",
                 draw="contacts,impulses")  # fmt: skip
print(f"wrote {len(runs[0])} frames to {gif.name}")

# %% [markdown]
# ## Exercises
#
# Predict first, then run the cell under the question, then open the answer.
#
# **1.** Drop the ball with $e = 0.5$. How high are its first and its second bounce?

# %%
d5 = drop(0.5)
print(f"e = 0.5: first apex {d5['apex']:.4f} m, second apex {d5['apex2']:.4f} m")

# %% [markdown]
# <details><summary>Answer</summary>
#
# Each bounce keeps $e^2$ of the height: $0.25 \times 2 = 0.5$ m, then $0.25 \times 0.5 =
# 0.125$ m. The run gives $0.4985$ m and $0.117$ m. The first is within 0.3%; the second,
# smaller bounce (3.1 m/s at impact, 5 cm per step) is 6% low: where the impact falls inside a
# step costs up to $(1 + e)$ times the gap left at the start of that step (section 1), a larger
# share of a smaller bounce.
#
# </details>
#
# **2.** Head on, $m_1 = 2$ kg at $3$ m/s against $m_2 = 1$ kg at $-1$ m/s, $e = 0.5$. Final
# velocities and the kinetic energy lost?

# %%
r2e = discs(2.0, 1.0, 0.5)
print(f"v1' = {r2e['v1'][-1, 0]:.4f} m/s, v2' = {r2e['v2'][-1, 0]:.4f} m/s, "
      f"K lost = {r2e['K'][0] - r2e['K'][-1]:.4f} J")  # fmt: skip

# %% [markdown]
# <details><summary>Answer</summary>
#
# $v'_1 = ((2 - 0.5)\,3 + 1.5 \times 1 \times (-1))/3 = 1$ m/s and
# $v'_2 = ((1 - 1)(-1) + 1.5 \times 2 \times 3)/3 = 3$ m/s: they separate at $2 = 0.5 \times 4$
# m/s. Lost: $\frac{1}{2}\,\frac{2}{3}\,(1 - 0.25)\,4^2 = 4$ J of the initial 10 J. The engine
# prints 1, 3 and 4.
#
# </details>
#
# **3.** Make the slab of section 4 static (it no longer moves, so its velocity is 0 and its
# mass infinite). Predict the impulse $j$ and the box's new $v_y$.

# %%
world_e3 = World(gravity=(0.0, 0.0), dt=DT)
box_e3 = world_e3.add_body(Body(name="box", angle=0.4, velocity=(0.5, -2.0), angular_velocity=1.5))
box_e3.add_shape(Box(1.0, 0.5, restitution=0.5, friction=0.0))
low_e3 = min((box_e3.world_point(v) for v in box_e3.shapes[0].vertices), key=lambda q: q[1])
slab_e3 = world_e3.add_body(
    Body(name="slab", type="static", position=(low_e3[0] + 0.6, low_e3[1] - 0.25 + 0.001))
)
slab_e3.add_shape(Box(2.0, 0.5, restitution=1.0, friction=0.0))
world_e3.step()
print(
    f"j = {world_e3.manifolds.normal_impulse[0, 0]:.6f} N s, box v_y = {box_e3.velocity[1]:.5f} m/s"
)

# %% [markdown]
# <details><summary>Answer</summary>
#
# A static body contributes nothing to $k$ ($1/m_2 = 1/I_2 = 0$): $k = 2 + 2.53242 = 4.53242$
# (the first and third terms printed in section 4). Its contact point does not move, so
# $v_n = -\mathbf{v}_{c1}\cdot\hat{\mathbf{n}} = -2.54476$ m/s and
# $j = 1.5 \times 2.54476 / 4.53242 = 0.84219$ N s. The box's $v_y$ becomes
# $-2 + 0.84219 / 0.5 = -0.31562$ m/s. The engine prints the same.
#
# </details>
