# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: percent
# ---

# %% [markdown]
# # 10 Friction
#
# Slide "Further Topics on Physics Animation": simulating friction, e.g. a box on an inclined
# plane.
#
# On a slope at angle $\theta$ a box of mass $m$ feels gravity $m g$, split into
# $m g \sin\theta$ down the slope and $m g \cos\theta$ into it; the slope pushes back with the
# normal force $N = m g\cos\theta$. Coulomb friction acts along the surface with
# $|f| \le \mu N$:
#
# - the box **stays** while the force needed to hold it is within the limit,
#   $m g\sin\theta \le \mu\, m g\cos\theta$, i.e. $\tan\theta \le \mu$: the critical angle is
#   $\theta_c = \arctan\mu$, whatever the mass
# - once it **slides**, friction is $\mu N$ against the motion and
#   $a = g(\sin\theta - \mu\cos\theta)$ down the slope
# - on flat ground a box pushed off at $v_0$ decelerates at $\mu g$ and stops after
#   $d = v_0^2 / (2\mu g)$, in $t = v_0 / (\mu g)$
#
# The engine applies friction as an impulse along the tangent at every contact point, clamped to
# $|j_t| \le \mu\, j_n$ (one $\mu$ for sticking and sliding). A contact's $\mu$ is the
# **product** of its two shapes' friction values, as in pymunk; so the ramp and the floor get
# friction 1.0 and the box carries the $\mu$ under test.

# %%
import json
import math

import matplotlib.pyplot as plt
import numpy as np

import sandbox
from sandbox.body import Body
from sandbox.lessonkit import output_dir, print_table, save_figure, scene_path
from sandbox.overlays import Layers
from sandbox.recording import record
from sandbox.render import render_gif
from sandbox.shapes import Box
from sandbox.world import World

# knobs
G = 9.81  # m/s^2
DT = 1.0 / 60.0  # s
ANGLES = (10, 20, 30, 40, 50)  # degrees, the acceleration table
MUS = (0.0, 0.2, 0.4, 0.6)  # friction of the box (the ramp has 1.0)
SLIDE_TIME = 1.2  # s per incline run
CRITICAL_MUS = (0.3, 0.5, 0.8)  # the critical angle sweep
SWEEP_HALF_WIDTH = 8  # degrees either side of arctan(mu), in 1 degree steps
MOVED = 1e-3  # m: a box that moved more than this in 1 s "slides"
V0S = (1.0, 2.0, 4.0, 6.0)  # m/s, pushed along the floor
FLOOR_MUS = (0.2, 0.5)
GIF_ANGLE = 30  # degrees
GIF_EVERY = 2

OUT = output_dir("10_friction")
RAMP_LENGTH, RAMP_THICK, START = 14.0, 0.4, 5.5  # m; the box starts START m up the ramp's middle


def incline_world(angle_deg: float, mu: float) -> tuple[World, Body, np.ndarray, np.ndarray]:
    """A static ramp (friction 1.0) at angle_deg and a 1 m box (friction mu) resting on it."""
    th = math.radians(angle_deg)
    along = np.array([math.cos(th), math.sin(th)])  # up the slope
    normal = np.array([-math.sin(th), math.cos(th)])
    world = World(gravity=(0.0, -G), dt=DT)
    ramp = world.add_body(Body(name="ramp", type="static", angle=th))
    ramp.add_shape(Box(RAMP_LENGTH, RAMP_THICK, friction=1.0))
    start = START * along + (0.5 * RAMP_THICK + 0.5) * normal
    box = world.add_body(Body(name="box", position=start, angle=th))
    box.add_shape(Box(1.0, 1.0, friction=mu))
    return world, box, start, along


def slide(angle_deg: float, mu: float, duration: float = SLIDE_TIME) -> dict:
    """Distance and velocity down the slope over time; acceleration from a straight-line fit."""
    world, box, start, along = incline_world(angle_deg, mu)
    t, s, v = [0.0], [0.0], [0.0]
    tip = 0.0
    for _ in range(int(round(duration / DT))):
        world.step()
        t.append(world.time)
        s.append(-(np.array(box.position) - start) @ along)  # down the slope positive
        v.append(-np.array(box.velocity) @ along)
        tip = max(tip, abs(box.angle - math.radians(angle_deg)))
    t, s, v = np.array(t), np.array(s), np.array(v)
    accel = float(np.polyfit(t[1:], v[1:], 1)[0])
    return {"t": t, "s": s, "v": v, "a": accel, "tip": tip}


def theory_accel(angle_deg: float, mu: float) -> float:
    th = math.radians(angle_deg)
    return max(G * (math.sin(th) - mu * math.cos(th)), 0.0)  # slides only when tan(th) > mu


# %% [markdown]
# ## Acceleration down the slope
#
# Each box starts at rest on the ramp. The acceleration is the slope of a straight line fitted
# to its velocity along the ramp.

# %%
rows, accel, worst_tip = [], {}, 0.0
for mu in MUS:
    for ang in ANGLES:
        r = slide(ang, mu)
        accel[(ang, mu)] = r["a"]
        worst_tip = max(worst_tip, r["tip"])
        th = theory_accel(ang, mu)
        err = f"{100 * (r['a'] - th) / th:+.4f}" if th > 0 else "-"
        rows.append((mu, ang, math.degrees(math.atan(mu)), r["a"], th, err,
                     "slides" if th > 0 else "stays"))  # fmt: skip
print_table(["mu", "angle (deg)", "arctan mu (deg)", "a measured (m/s^2)",
             "g(sin - mu cos)", "error %", "theory"], rows)  # fmt: skip
print(f"largest change of the box's angle while sliding: {worst_tip:.1e} rad (it does not tip)")

# %% [markdown]
# The product rule in action: `scenes/incline.json` puts a box with friction 0.5 on a 20 degree
# ramp with friction 0.5. The contact's $\mu$ is $0.5 \times 0.5 = 0.25 < \tan 20° = 0.364$,
# so the box slides, although $\mu = 0.5$ on both shapes would hold it.

# %%
world = sandbox.load_scene(json.loads(scene_path("incline").read_text()))
box = world.body("box")
th = world.body("ramp").angle
down = -np.array([math.cos(th), math.sin(th)])
t_s, v_s = [], []
for _ in range(int(round(0.8 / world.dt))):
    world.step()
    t_s.append(world.time)
    v_s.append(np.array(box.velocity) @ down)
a_scene = float(np.polyfit(t_s, v_s, 1)[0])
print_table(
    ["scenes/incline.json", "a (m/s^2)"],
    [("measured", a_scene),
     ("theory with mu = 0.5 x 0.5 = 0.25", G * (math.sin(th) - 0.25 * math.cos(th))),
     ("theory with mu = 0.5 (would stay)", theory_accel(math.degrees(th), 0.5))],
)  # fmt: skip

# %% [markdown]
# ## The critical angle: $\tan\theta_c = \mu$
#
# For each $\mu$ a sweep of slope angles around $\arctan\mu$, 1 degree apart: does the box move
# more than 1 mm in 1 s?

# %%
crit, rows = {}, []
for mu in CRITICAL_MUS:
    centre = round(math.degrees(math.atan(mu)))
    angles = np.arange(centre - SWEEP_HALF_WIDTH, centre + SWEEP_HALF_WIDTH + 1)
    moved = np.array([slide(a, mu, duration=1.0)["s"][-1] for a in angles])
    crit[mu] = (angles, moved)
    slides = angles[moved > MOVED]
    stays = angles[moved <= MOVED]
    rows.append((mu, math.degrees(math.atan(mu)), int(stays.max()), int(slides.min()),
                 "yes" if stays.max() < math.degrees(math.atan(mu)) < slides.min() else "no"))  # fmt: skip
print_table(["mu", "arctan mu (deg)", "steepest that stays", "shallowest that slides",
             "theta_c in between"], rows)  # fmt: skip

# %%
fig, (ax, bx) = plt.subplots(1, 2, figsize=(12, 4.2))
fine = np.linspace(0, 60, 241)
for k, mu in enumerate(MUS):
    ax.plot(fine, [theory_accel(a, mu) for a in fine], color=f"C{k}", lw=1)
    ax.scatter(ANGLES, [accel[(a, mu)] for a in ANGLES], color=f"C{k}", zorder=3,
               label=f"mu = {mu}")  # fmt: skip
ax.set(xlabel="slope angle (deg)", ylabel="acceleration down the slope (m/s$^2$)",
       title="dots: engine; lines: g(sin - mu cos), 0 below arctan mu")  # fmt: skip
ax.legend(fontsize=8)
ax.grid(alpha=0.3)
for k, mu in enumerate(CRITICAL_MUS):
    angles, moved = crit[mu]
    bx.plot(angles, moved, marker="o", color=f"C{k + 4}", label=f"mu = {mu}")
    bx.axvline(math.degrees(math.atan(mu)), color=f"C{k + 4}", ls=":")
bx.axhline(MOVED, color="k", lw=0.8, ls="--", label=f"{MOVED * 1000:g} mm")
bx.set_yscale("symlog", linthresh=1e-4)
bx.set_ylim(0.0, 2.0)
bx.set(xlabel="slope angle (deg)", ylabel="distance slid in 1 s (m)",
       title="critical angle (dotted: arctan mu)")  # fmt: skip
bx.legend(fontsize=8)
bx.grid(alpha=0.3)
fig.tight_layout()
save_figure(fig, OUT / "incline.png", dpi=100)

# %% [markdown]
# The animation draws each box's contact points with their normal impulses (magenta) and
# friction impulses (teal, along the slope) of the last step: on the stuck box ($\mu = 0.6$)
# friction holds exactly the pull down the slope, on the sliding ones it is capped at $\mu$
# times the normal impulse; the lower corner of each box carries more of the normal impulse.

# %%
runs = []
for mu in MUS:
    world, box, _, along = incline_world(GIF_ANGLE, mu)
    speed = {"v down the slope (m/s)": lambda w, i=box.index, u=along: -float(w.vel[i] @ u)}
    runs.append(record(world, int(round(1.5 / DT)), every=GIF_EVERY, series=speed,
                       draw="contacts,impulses"))  # fmt: skip
layers = Layers("contacts,impulses", impulse=15.0)  # m of arrow per N s: each corner of a box
# carries about 0.07 N s per step, drawn about 1 m long
gif = render_gif(runs, OUT / "incline.gif", fps=20, size_px=360, draw=layers,
                 labels=[f"mu = {mu}" for mu in MUS], panel="v down the slope (m/s)")  # fmt: skip
print(f"wrote {len(runs[0])} frames to {gif.name}")

# %% [markdown]
# ## Pushed along the floor: stopping distance $v_0^2 / (2\mu g)$
#
# A box on a flat floor starts at $v_0$. Friction takes $\mu g\Delta t$ off its speed every step,
# exactly the deceleration $\mu g$. The distance comes out a little short of
# $v_0^2/(2\mu g)$ for a reason that is the integrator's, not friction's: semi-implicit Euler
# moves each step with the velocity at its *end*, $x_n = \sum_{k=1}^{n} v_k\Delta t$ with
# $v_k = v_0 - k\mu g\Delta t$, which sums to $v_0^2/(2\mu g) - v_0\Delta t/2$ when the box stops
# (lesson 01 has the same first-order lag for the projectile).


# %%
def push(v0: float, mu: float, duration: float) -> dict:
    world = World(gravity=(0.0, -G), dt=DT)
    floor = world.add_body(Body(name="floor", type="static"))
    floor.add_shape(Box(30.0, 0.5, offset=(13.0, -0.25), friction=1.0))
    box = world.add_body(Body(name="box", position=(0.0, 0.5), velocity=(v0, 0.0)))
    box.add_shape(Box(1.0, 1.0, friction=mu))
    t, x, v = [0.0], [0.0], [v0]
    stop = None
    for _ in range(int(round(duration / DT))):
        world.step()
        t.append(world.time)
        x.append(box.position[0])
        v.append(box.velocity[0])
        if stop is None and abs(v[-1]) < 1e-3:
            stop = world.time
    return {"t": np.array(t), "x": np.array(x), "v": np.array(v), "stop": stop, "angle": box.angle}


rows, pushes = [], {}
for mu in FLOOR_MUS:
    for v0 in V0S:
        r = push(v0, mu, duration=v0 / (mu * G) + 0.4)
        pushes[(mu, v0)] = r
        d, d_th = r["x"][-1], v0 * v0 / (2 * mu * G)
        d_euler = d_th - v0 * DT / 2
        rows.append((mu, v0, d, d_th, f"{100 * (d - d_th) / d_th:+.2f}", d_euler,
                     f"{100 * (d - d_euler) / d_euler:+.2f}", r["stop"], v0 / (mu * G)))  # fmt: skip
print_table(["mu", "v0 (m/s)", "d measured (m)", "v0^2/(2 mu g)", "error %",
             "minus v0 dt/2", "error %", "stopped at (s)", "v0/(mu g)"], rows)  # fmt: skip

# %%
fig, (ax, bx) = plt.subplots(1, 2, figsize=(12, 4))
v_line = np.linspace(0, max(V0S), 50)
for k, mu in enumerate(FLOOR_MUS):
    ax.plot(
        v_line, v_line**2 / (2 * mu * G), color=f"C{k}", lw=1, label=f"v0^2/(2 mu g), mu = {mu}"
    )
    ax.scatter(V0S, [pushes[(mu, v0)]["x"][-1] for v0 in V0S], color=f"C{k}", zorder=3,
               label=f"engine, mu = {mu}")  # fmt: skip
    for v0 in V0S:
        r = pushes[(mu, v0)]
        bx.plot(r["t"], r["v"], color=f"C{k}", lw=1)
    bx.plot([], [], color=f"C{k}", label=f"mu = {mu}: slope -mu g = {-mu * G:.2f} m/s$^2$")
ax.set(xlabel="v0 (m/s)", ylabel="stopping distance (m)", title="box pushed along the floor")
ax.legend(fontsize=8)
ax.grid(alpha=0.3)
bx.set(xlabel="t (s)", ylabel="v (m/s)", title="velocity: a straight line down to rest")
bx.legend(fontsize=8)
bx.grid(alpha=0.3)
fig.tight_layout()
save_figure(fig, OUT / "stopping.png", dpi=100)

# %% [markdown]
# ## Static against kinetic friction
#
# Real surfaces hold a little harder than they drag: a box at rest stays put until the push
# passes the **static** limit $\mu_s N$, and once it slides the friction drops to the **kinetic**
# $\mu_k N$ ($\mu_k < \mu_s$). The two-coefficient Coulomb model is a small state machine:
#
# - **stuck**: friction balances the push exactly, $f = -P$, as long as $|P| \le \mu_s N$;
# - **sliding**: $f = -\mu_k N\,\mathrm{sign}(v)$, so $m\,a = P - \mu_k N$; it sticks again only
#   when it stops with $|P| \le \mu_s N$.
#
# At break-away the friction drops by $(\mu_s - \mu_k) N$ and the box jumps from $a = 0$ to
# $a = (\mu_s - \mu_k) g$ at once: the "stick-slip" that makes chalk squeak.
#
# **What this engine does**: one $\mu$ per contact, used for both (as pymunk and Box2D do): the
# solver clamps the friction impulse to $|j_t| \le \mu\,j_n$ whether the contact is at rest or
# sliding, so the box breaks loose at $\mu N$ and slides with the same $\mu N$. Below, a 1 kg box
# on the floor is pushed with a force growing at `RAMP` N/s: in the engine ($\mu$ = 0.5) and in
# the two-coefficient model ($\mu_s$ = `MU_S`, $\mu_k$ = `MU_K`, integrated with the same
# semi-implicit Euler step). The engine's friction force is read from the contact's tangent
# impulses, $f = \sum j_t / \Delta t$.

# %%
RAMP, MU_ENGINE, MU_S, MU_K, PUSH_TIME = 2.5, 0.5, 0.6, 0.4, 3.0  # N/s, 1, 1, 1, s
SLIDING = 1e-4  # m/s: faster than this the box slides (the solver lets a stuck box creep ~1e-6)


def ramp_push_engine(mu: float = MU_ENGINE) -> dict:
    """A 1 kg box on the floor pushed with P = RAMP t: push, friction force, velocity per step."""
    world = World(gravity=(0.0, -G), dt=DT)
    floor = world.add_body(Body(name="floor", type="static"))
    floor.add_shape(Box(30.0, 0.5, offset=(13.0, -0.25), friction=1.0))
    box = world.add_body(Body(name="box", position=(0.0, 0.5)))
    box.add_shape(Box(1.0, 1.0, friction=mu))
    out = {k: [] for k in ("t", "P", "f", "v")}
    for _ in range(int(round(PUSH_TIME / DT))):
        push = RAMP * (world.time + DT)  # the force over this step
        box.apply_force((push, 0.0))
        world.step()
        m = world.manifolds
        f = float(m.tangent_impulse.sum()) / DT if m is not None and len(m) else 0.0
        out["t"].append(world.time)
        out["P"].append(push)
        out["f"].append(abs(f))
        out["v"].append(box.velocity[0])
    return {k: np.array(v) for k, v in out.items()} | {"m": box.mass}


def ramp_push_model(m: float, mu_s: float = MU_S, mu_k: float = MU_K) -> dict:
    """The two-coefficient Coulomb model, the same push and step (v first, then x)."""
    n, v, stuck = m * G, 0.0, True
    out = {k: [] for k in ("t", "P", "f", "v")}
    for k in range(int(round(PUSH_TIME / DT))):
        push = RAMP * (k + 1) * DT
        if stuck and abs(push) > mu_s * n:
            stuck = False  # break-away
        f = -push if stuck else -mu_k * n * np.sign(v if v != 0.0 else push)
        v += (push + f) / m * DT
        if not stuck and v <= 0.0 and abs(push) <= mu_s * n:
            v, stuck = 0.0, True
        out["t"].append((k + 1) * DT)
        out["P"].append(push)
        out["f"].append(abs(f))
        out["v"].append(v)
    return {k: np.array(v) for k, v in out.items()}


engine_run = ramp_push_engine()
model_run = ramp_push_model(engine_run["m"])
n_force = engine_run["m"] * G
rows = []
for name, r, mu_break, mu_slide in (("engine, one mu", engine_run, MU_ENGINE, MU_ENGINE),
                                    ("model, mu_s / mu_k", model_run, MU_S, MU_K)):  # fmt: skip
    k = int(np.argmax(r["v"] > SLIDING))  # the first step that slides
    late = r["t"] > r["t"][k] + 0.2  # well into sliding
    rows.append((name, mu_break * n_force, r["P"][k - 1], r["P"][k], r["f"][k - 1],
                 float(np.median(r["f"][late])), mu_slide * n_force,
                 f"{np.abs(r['v'][:k]).max():.1e}"))  # fmt: skip
print(f"m = {engine_run['m']:.3f} kg, N = m g = {n_force:.3f} N, push grows {RAMP} N/s")
print_table(["run", "mu_s N (N)", "last push stuck (N)", "first push sliding (N)",
             "friction just before (N)", "friction sliding (N)", "mu_k N (N)",
             "creep while stuck (m/s)"], rows, 3)  # fmt: skip
jump = (MU_S - MU_K) * G
k_m = int(np.argmax(model_run["v"] > 0))
a_after = (model_run["v"][k_m + 1] - model_run["v"][k_m]) / DT
print(
    f"model: acceleration right after break-away {a_after:.3f} m/s^2 "
    f"(P/m - mu_k g = {RAMP * model_run['t'][k_m + 1] / engine_run['m'] - MU_K * G:.3f}; "
    f"jump (mu_s - mu_k) g = {jump:.3f})"
)

# %%
fig, (ax, bx) = plt.subplots(1, 2, figsize=(13, 4.6))
for name, r, color in (("engine (mu = 0.5)", engine_run, "C0"),
                       (f"model (mu_s = {MU_S}, mu_k = {MU_K})", model_run, "C3")):  # fmt: skip
    wide = color == "C0"  # the engine drawn wide under the model: both follow f = P while stuck
    ax.plot(r["P"], r["f"], color=color, lw=3.5 if wide else 1.3, alpha=0.6 if wide else 1.0,
            label=name)  # fmt: skip
    bx.plot(r["t"], r["v"], color=color, label=name)
for mu, ls in ((MU_ENGINE, ":"), (MU_S, "--"), (MU_K, "-.")):
    ax.axhline(mu * n_force, color="0.4", ls=ls, lw=1, label=f"{mu} x N = {mu * n_force:.2f} N")
ax.plot([0, RAMP * PUSH_TIME], [0, RAMP * PUSH_TIME], color="0.7", lw=4, alpha=0.5, zorder=0,
        label="f = P (stuck)")  # fmt: skip
ax.set(xlabel="push P (N)", ylabel="friction force |f| (N)", ylim=(0, 7.5),
       title="friction against the push")  # fmt: skip
bx.set(xlabel="t (s)", ylabel="box velocity (m/s)", title="stuck, then sliding")
ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.0, 1.0))
bx.legend(fontsize=8, loc="upper left")
for a in (ax, bx):
    a.grid(alpha=0.3)
fig.tight_layout()
save_figure(fig, OUT / "static_kinetic.png", dpi=100)

# %% [markdown]
# The engine's box holds exactly until the push passes $\mu N = 4.905$ N (the last step it
# stays put is at $P$ just below, the first that moves just above; while stuck the iterative
# solver lets it creep at a few micrometres per second) and then feels the same $\mu N$ while
# sliding. The model holds until $\mu_s N = 5.886$ N, then the friction drops to
# $\mu_k N = 3.924$ N and the box takes off with $a = P/m - \mu_k g$, about
# $(\mu_s - \mu_k) g = 1.96$ m/s$^2$ right after break-away: the drop of the red curve on the
# left. An engine could offer it per contact (the friction clamp $\mu_s$ while a contact point's
# tangential speed is below a small threshold, $\mu_k$ above); the one-coefficient solvers keep
# one clamp so that resting and sliding contacts are solved alike and a stack does not creep.

# %% [markdown]
# ## Exercises
#
# Predict first, then run the cell under the question, then open the answer.
#
# **1.** A box with $\mu = 0.3$ on a 20 degree ramp: does it slide, and at what acceleration?

# %%
print(f"mu = 0.3, 20 deg: a = {slide(20, 0.3)['a']:.4f} m/s^2 "
      f"(tan 20 deg = {math.tan(math.radians(20)):.3f})")  # fmt: skip

# %% [markdown]
# <details><summary>Answer</summary>
#
# $\tan 20° = 0.364 > 0.3$: it slides, with $a = g(\sin 20° - 0.3\cos 20°) =
# 9.81 \times (0.3420 - 0.2819) = 0.589$ m/s$^2$. The engine prints 0.589.
#
# </details>
#
# **2.** Push a box along the floor at $v_0 = 3$ m/s with $\mu = 0.25$. Where does it stop?

# %%
r_e2 = push(3.0, 0.25, duration=3.0 / (0.25 * G) + 0.4)
print(f"stops after {r_e2['x'][-1]:.4f} m, at t = {r_e2['stop']:.3f} s")

# %% [markdown]
# <details><summary>Answer</summary>
#
# $v_0^2/(2\mu g) = 9 / 4.905 = 1.835$ m, less the integrator's $v_0\Delta t/2 = 0.025$ m:
# 1.810 m, after $v_0/(\mu g) = 1.22$ s. The engine prints 1.8099 m and stops within a step of
# 1.22 s.
#
# </details>
#
# **3.** In the two-coefficient model ($\mu_s = 0.6$, $\mu_k = 0.4$), a steady push of 5 N on
# the 1 kg box. Does the box move if it starts at rest? And if it is already sliding at 1 m/s?


# %%
def steady_push(v0: float, push: float = 5.0, seconds: float = 1.0) -> float:
    """The two-coefficient model under a constant push; the velocity after ``seconds``."""
    n, v, stuck = G, v0, v0 == 0.0
    for _ in range(int(round(seconds / DT))):
        if stuck and push > MU_S * n:
            stuck = False
        f = -push if stuck else -MU_K * n * np.sign(v if v != 0.0 else push)
        v += (push + f) * DT
    return v


print(f"from rest: v(1 s) = {steady_push(0.0):.4f} m/s; "
      f"from 1 m/s: v(1 s) = {steady_push(1.0):.4f} m/s")  # fmt: skip

# %% [markdown]
# <details><summary>Answer</summary>
#
# From rest, 5 N is below $\mu_s N = 5.886$ N: it stays stuck, $v = 0$. Already sliding, the
# friction is only $\mu_k N = 3.924$ N, so the 5 N push wins and the box *speeds up* at
# $5 - 3.924 = 1.076$ m/s$^2$: $v(1\,\mathrm{s}) = 2.076$ m/s. The same push, two outcomes,
# depending on the history: that hysteresis is what the engine's single $\mu$ cannot show.
#
# </details>
