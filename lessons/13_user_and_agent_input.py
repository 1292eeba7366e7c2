# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: percent
# ---

# %% [markdown]
# # 13 User and agent input
#
# Slides, "User / Agent Input": human users and autonomous agents influence the simulation, for
# example a user or an AI controlling a simulated vehicle. Whatever they decide ends up as
# **applied forces**, and forces are the source of linear and angular acceleration:
# $\mathbf{a} = \mathbf{f}_{total}/m$, $\alpha = \tau_{total}/I$ with $\tau = \mathbf{r} \times
# \mathbf{f}$ for a force applied at $\mathbf{r}$ from the centre of mass (slides, "Force",
# "Torque").
#
# In the engine a controller is a function `controller(body, world)` called at the start of
# every step; it calls `body.apply_force(f, point)` and `body.apply_torque(t)`. Here the
# vehicle is a lander, a 1 m x 0.5 m box with two thrusters under its bottom corners, each
# pushing along the lander's "up" with 0 to 5 N. Firing both lifts it; firing one more than
# the other turns it (the thrust is off-centre, so it makes a torque); tilted, the thrust also
# pushes it sideways.
#
# - an **agent**: a PD autopilot flying to a target
#   (`sandbox.controllers.LanderController`)
# - a **user**: a time-stamped list of commands replayed step by step
#   (`sandbox.controllers.Scripted`), as a recorded player's key presses would be

# %%
import math

import matplotlib.pyplot as plt
import numpy as np

from sandbox import Body, Box, Circle, World
from sandbox.controllers import LanderController, Scripted, lander_thrusters
from sandbox.forces import ConstantForce
from sandbox.lessonkit import output_dir, print_table, save_figure
from sandbox.recording import record
from sandbox.render import render_gif

# knobs
TARGET = (6.0, 4.0)  # m, where the autopilot flies to
MAX_THRUST = 5.0  # N per thruster (the lander weighs 0.5 kg x 9.81 = 4.9 N)
WIND = (-0.15, 0.0)  # N, a steady side wind for the second act
SECONDS = 7.0
DT = 1.0 / 60.0
G = 9.81

OUT = output_dir("13_user_and_agent_input")
STEPS = int(round(SECONDS / DT))


def lander_world(wind=(0.0, 0.0)):
    world = World(dt=DT)
    beacon = world.add_body(Body("beacon", type="static", position=(TARGET[0], TARGET[1] + 0.8)))
    beacon.add_shape(Circle(0.1))  # marks the target, above the lander's hover point
    lander = world.add_body(Body("lander", position=(0.0, 0.0)))
    lander.add_shape(Box(1.0, 0.5))
    if any(wind):
        world.add_force(ConstantForce(force=wind, bodies=[lander]))
    return world, lander


# %% [markdown]
# ## The autopilot (an agent)
#
# Each step it turns "where I am" into forces, in three lines of physics:
#
# 1. the acceleration it wants: a spring-damper pull to the target plus hovering,
#    $\mathbf{a}^* = k_p(\mathbf{p}_{target} - \mathbf{p}) - k_d\mathbf{v} - \mathbf{g}$
# 2. the thrust must point along $\mathbf{a}^*$, so it wants the tilt
#    $\theta^* = \operatorname{atan2}(-a^*_x, a^*_y)$, and a torque to get there,
#    $\tau^* = I\,(k_\theta(\theta^* - \theta) - k_\omega\omega)$
# 3. total thrust $T = m\,\mathbf{a}^*\cdot\widehat{\text{up}}$, split so that
#    $T_L + T_R = T$ and $(T_R - T_L)\,\ell = \tau^*$ ($\ell$ = half the thrusters' spacing), each
#    clamped to $[0, T_{max}]$: the engines are bounded, so a far target is approached at the
#    speed the thrust allows, not the one the formula asks for.

# %%
world, lander = lander_world()
pilot = LanderController(TARGET, lander_thrusters(1.0, 0.5, MAX_THRUST))
lander.controller = pilot
DIST = "distance to target (m)"


def distance(w):
    x, y = w.body("lander").position
    return math.hypot(x - TARGET[0], y - TARGET[1])


calm = record(world, STEPS, every=3, series={DIST: distance})
log = np.array(pilot.log)  # t, left thrust, right thrust per step

settle = next(t for t, d in zip(calm.times[::-1], calm.series[DIST][::-1], strict=True) if d > 0.05)
rows = [
    ("final distance to target (m)", distance(world)),
    ("final speed (m/s)", math.hypot(*lander.velocity)),
    ("time to stay within 5 cm (s)", settle),
    ("largest left thrust (N)", float(log[:, 1].max())),
    ("largest right thrust (N)", float(log[:, 2].max())),
    ("steps with the left thruster at its bound", int(np.sum(log[:, 1] >= MAX_THRUST - 1e-9))),
    ("steps with the right thruster at its bound", int(np.sum(log[:, 2] >= MAX_THRUST - 1e-9))),
    ("final total thrust (N)", float(log[-1, 1:].sum())),
    ("weight m g (N)", lander.mass * G),
]
print_table(["autopilot, calm air", "value"], rows)

# %%
fig, (ax, bx) = plt.subplots(1, 2, figsize=(12, 4.6))
ax.plot(log[:, 0], log[:, 1], label="left thruster")
ax.plot(log[:, 0], log[:, 2], label="right thruster")
ax.axhline(MAX_THRUST, color="k", ls=":", lw=1, label="bound")
ax.axhline(lander.mass * G / 2, color="C2", ls="--", lw=1, label="half the weight")
ax.set(xlabel="t (s)", ylabel="thrust (N)", title="the autopilot's commands")
frames = np.array(calm.frames)[:, 1]  # lander poses
bx.plot(calm.times, frames[:, 0], label="x")
bx.plot(calm.times, frames[:, 1], label="y")
for v in TARGET:
    bx.axhline(v, color="k", ls=":", lw=1)
bx.plot([], [], color="k", ls=":", lw=1, label="target x, y")
bx.set(xlabel="t (s)", ylabel="position (m)", title="the lander's path")
tx = bx.twinx()  # the tilt is an angle: its own axis, on the right
tx.plot(calm.times, np.degrees(frames[:, 2]), color="C2", label="tilt")
tx.set_ylabel("tilt (deg)")
lines = bx.get_lines() + tx.get_lines()
bx.legend([ln for ln in lines if not ln.get_label().startswith("_")],
          [ln.get_label() for ln in lines if not ln.get_label().startswith("_")],
          fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=4)  # fmt: skip
ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=2)
fig.tight_layout()
save_figure(fig, OUT / "autopilot.png", dpi=100)

# %% [markdown]
# At first the formula asks for a steep climb *and* a turn to the right, towards the target:
# more thrust on the left. The left thruster sits at its 5 N bound for the first 8 steps
# (0.13 s) while the right one gives at most 4.41 N (the table above); then the difference
# between them tilts the lander towards the target and back, and at the end their sum carries
# the weight, $T_L + T_R = mg$.
#
# ## The same flight as a script (a user)
#
# A script is a list of time-stamped commands, each held until the next one (what a recorded
# player does with the keys). Replaying the autopilot's own log as a script gives the same
# flight to the last bit: the engine is deterministic. But a script does not look at the
# lander. Add a side wind: the autopilot notices the drift and leans into it, the script flies
# the calm-air commands and misses.
#
# The animation draws what the controllers do, with the `forces` debug layer: the thrust and
# the wind summed into one force arrow at each lander's centre of mass, and the torque of the
# uneven thrusters as a curved arrow.
#
# Note the autopilot's own miss in the wind: a PD controller balances a steady force $F$ with
# a steady offset, $m k_p \Delta x = F$, i.e. $\Delta x = F / (m k_p)$ (an integral term
# would remove it).

# %%
replay_world, replayed = lander_world()
replayed.controller = Scripted.from_log(pilot.log, lander_thrusters(1.0, 0.5, MAX_THRUST))
record(replay_world, STEPS, every=STEPS)
print(f"script replay in calm air: final position {replayed.position} vs {lander.position}")
print(f"identical: {replayed.position == lander.position and replayed.angle == lander.angle}")

windy_world, windy = lander_world(WIND)
windy_pilot = LanderController(TARGET, lander_thrusters(1.0, 0.5, MAX_THRUST))
windy.controller = windy_pilot
windy_rec = record(windy_world, STEPS, every=3, series={DIST: distance}, draw="forces")
script_world, scripted = lander_world(WIND)
scripted.controller = Scripted.from_log(pilot.log, lander_thrusters(1.0, 0.5, MAX_THRUST))
script_rec = record(script_world, STEPS, every=3, series={DIST: distance}, draw="forces")

# a hand-written script (a player's keys): climb, coast up, lean right, fly, level, lean back
# to brake, level, hover. Each lean is a push on one side then the other (start and stop the
# turn); the thrusts always add up to about the weight, 4.9 N.
HOVER = 0.5 * 0.5 * G
keys = Scripted(
    [(0.0, (5.0, 5.0)), (0.6, (0.0, 0.0)),
     (1.22, (2.65, 2.25)), (1.47, (2.25, 2.65)), (1.72, (2.53, 2.53)),
     (2.52, (2.25, 2.65)), (2.77, (2.65, 2.25)), (3.02, (HOVER, HOVER)),
     (3.3, (2.25, 2.65)), (3.55, (2.65, 2.25)), (3.8, (2.53, 2.53)),
     (4.6, (2.65, 2.25)), (4.85, (2.25, 2.65)), (5.1, (HOVER, HOVER))],
    lander_thrusters(1.0, 0.5, MAX_THRUST),
)  # fmt: skip
hand_world, hand = lander_world()
hand.controller = keys
hand_rec = record(hand_world, STEPS, every=3, series={DIST: distance})
print_table(
    ["run", "final x (m)", "final y (m)", "distance to target (m)"],
    [
        ("autopilot, calm", *lander.position, distance(world)),
        (f"autopilot, wind {WIND} N", *windy.position, distance(windy_world)),
        (f"script (calm-air log), wind {WIND} N", *scripted.position, distance(script_world)),
        ("hand-written script, calm", *hand.position, distance(hand_world)),
    ],
)
lean = np.degrees(windy.angle)
print(
    f"in the wind the autopilot holds a lean of {lean:.1f} deg: tan = {math.tan(-windy.angle):.3f}"
)
print(f"wind / weight = {abs(WIND[0]) / (windy.mass * G):.3f} (the lean that balances the wind)")
offset = abs(WIND[0]) / (windy.mass * pilot.kp)
print(f"PD offset F / (m kp) = {offset:.4f} m, measured {distance(windy_world):.4f} m")

# %%
fig, ax = plt.subplots(figsize=(7, 3.5))
for rec, label in (
    (calm, "autopilot, calm"),
    (windy_rec, "autopilot, wind"),
    (script_rec, "script, wind"),
    (hand_rec, "hand-written script"),
):
    ax.plot(rec.times, rec.series[DIST], label=label)
ax.set(xlabel="t (s)", ylabel="distance to target (m)", yscale="log", title="feedback vs script")
ax.legend(fontsize=8)
fig.tight_layout()
save_figure(fig, OUT / "feedback_vs_script.png", dpi=100)

gif = render_gif(
    [windy_rec, script_rec],
    OUT / "lander.gif",
    fps=30,
    size_px=360,
    labels=["autopilot (feedback)", "script (open loop)"],
    panel=DIST,
    trail=True,
    draw="forces",
)
print(f"wrote {len(windy_rec)} frames to {gif.name}")

# %% [markdown]
# ## Exercises
#
# Predict first, then run the cell under the question, then open the answer.
#
# **1.** Double the side wind to 0.3 N. How far from the target does the autopilot hold the
# lander now?

# %%
world_e1, lander_e1 = lander_world((-0.3, 0.0))
lander_e1.controller = LanderController(TARGET, lander_thrusters(1.0, 0.5, MAX_THRUST))
record(world_e1, STEPS, every=STEPS)
print(f"wind 0.3 N: {distance(world_e1):.4f} m from the target, "
      f"F / (m kp) = {0.3 / (lander_e1.mass * pilot.kp):.4f} m")  # fmt: skip

# %% [markdown]
# <details><summary>Answer</summary>
#
# A PD controller balances a steady force with a steady offset, $\Delta x = F/(m k_p) =
# 0.3 / (0.5 \times 3) = 0.2$ m: twice the 0.1 m of the 0.15 N wind. The run holds it 0.210 m
# away, about 5% beyond the formula, as at 0.15 N (0.110 m): the offset doubles with the wind.
# Only an integral term (or a model of the wind) removes it.
#
# </details>
#
# **2.** Give the lander weaker engines, 2.4 N per thruster. What happens?

# %%
world_e2, lander_e2 = lander_world()
lander_e2.controller = LanderController(TARGET, lander_thrusters(1.0, 0.5, 2.4))
record(world_e2, STEPS, every=STEPS)
print(f"2.4 N thrusters: after {SECONDS:g} s at {tuple(round(c, 3) for c in lander_e2.position)} m, "
      f"v_y = {lander_e2.velocity[1]:.3f} m/s, tilt {math.degrees(lander_e2.angle):.1f} deg")  # fmt: skip

# %% [markdown]
# <details><summary>Answer</summary>
#
# Both thrusters together give 4.8 N, less than the weight $0.5 \times 9.81 = 4.905$ N: the
# autopilot asks for full thrust on both sides, and with both clamped at their bound there is no
# difference left to turn with. The lander sinks straight down at $(4.8 - 4.905)/0.5 = -0.21$
# m/s$^2$: after 7 s $v_y = -1.47$ m/s and $y = -\frac{1}{2}\,0.21 \times 7^2 = -5.15$ m (the
# run: $-5.157$ m; semi-implicit Euler adds $\frac{1}{2} a\,\Delta t\,t$). Bounded actuators
# can make a goal unreachable, whatever the controller.
#
# </details>
