# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: percent
# ---

# %% [markdown]
# # 18 Fix your timestep: an accumulator, and interpolation for drawing
#
# The slides' numerical algorithm steps, draws, steps, draws: one update of $\Delta t$ per
# picture. A real program draws when the screen is ready (50, 60, 144 Hz, or whenever a slow
# frame finishes), and that raises two problems:
#
# - **step with the frame time** ($\Delta t$ = the time since the last frame) and the simulation
#   depends on the frame rate: a slow frame is a big step, big steps change the physics
#   (lesson 01: Euler's error grows with $\Delta t$; lesson 06: tunnelling), and no two runs are
#   the same;
# - **step with a fixed $\Delta t$** and the steps no longer line up with the frames.
#
# The usual answer (Glenn Fiedler's article "Fix your timestep!"; Unity's `FixedUpdate` with
# rigidbody interpolation works this way) keeps the physics on a fixed $\Delta t$ and lets the
# drawing adapt:
#
# ```
# accumulator += frame_time                  # real time that has passed
# while accumulator >= dt:                   # as many fixed steps as fit
#     previous = current; world.step(dt); current = state(world)
#     accumulator -= dt
# alpha = accumulator / dt                   # how far we are into the next step, 0 <= alpha < 1
# draw(lerp(previous, current, alpha))       # interpolate between the last two steps
# ```
#
# The drawn state is then always one step behind the newest one, but it moves smoothly. This
# lesson measures each part with the engine: steps per frame, judder with and without
# interpolation, and the frame-rate dependence of stepping with the frame time.

# %%
import matplotlib.pyplot as plt
import numpy as np

from sandbox import Body, Box, Circle, World
from sandbox.lessonkit import output_dir, print_table, save_figure
from sandbox.recording import Recording
from sandbox.render import render_gif

# knobs
PHYSICS_HZ = 60  # fixed steps per second
DISPLAY_HZ = 50  # frames per second of a steady display
SPEED = 3.0  # m/s, the moving ball
SECONDS = 2.0  # s of real time
JITTER = (1 / 90, 1 / 30)  # s, range of frame times of an uneven display
SEED = 18
MAX_FRAME = 0.25  # s: longer frames are clamped (no "spiral of death")

OUT = output_dir("18_fixed_timestep")
DT = 1.0 / PHYSICS_HZ


def moving_ball(y: float = 0.0) -> World:
    """A ball gliding at SPEED along x, no gravity (its exact position is SPEED t)."""
    world = World(gravity=(0.0, 0.0), dt=DT)
    ball = world.add_body(Body("ball", position=(0.0, y), velocity=(SPEED, 0.0)))
    ball.add_shape(Circle(0.25))
    return world


def pose(world: World) -> np.ndarray:
    return np.array([(*b.position, b.angle) for b in world.bodies])


def game_loop(world: World, frame_times, interpolate: bool) -> dict:
    """Run the fixed-step loop over ``frame_times`` (s): per frame the drawn poses, the number
    of steps taken, alpha and the real time."""
    accumulator, clock = 0.0, 0.0
    previous = current = pose(world)
    out = {"poses": [], "steps": [], "alpha": [], "t": []}
    for frame_time in frame_times:
        clock += frame_time
        accumulator += min(frame_time, MAX_FRAME)
        steps = 0
        while accumulator >= DT - 1e-12:  # a tolerance for the rounding of the sums
            previous = current
            world.step()
            current = pose(world)
            accumulator -= DT
            steps += 1
        alpha = max(accumulator, 0.0) / DT
        drawn = (1.0 - alpha) * previous + alpha * current if interpolate else current
        out["poses"].append(drawn)
        out["steps"].append(steps)
        out["alpha"].append(alpha)
        out["t"].append(clock)
    return {k: np.array(v) for k, v in out.items()}


# %% [markdown]
# ## A steady display that is not a multiple of the physics rate
#
# The display runs at `DISPLAY_HZ` = 50 Hz, the physics at `PHYSICS_HZ` = 60 Hz: 1.2 steps per
# frame. A frame takes the steps that fit: 1, 1, 1, 1, then 2 (every fifth frame a double step).
# Drawing the newest state makes the ball jump twice as far on those frames: judder, 10 times a
# second. Interpolating draws where the ball was $\alpha\,\Delta t$ into the step that is still
# to come, one step behind the newest state, and every frame moves the same distance.

# %%
steady = np.full(int(SECONDS * DISPLAY_HZ), 1.0 / DISPLAY_HZ)
newest = game_loop(moving_ball(), steady, interpolate=False)
smooth = game_loop(moving_ball(), steady, interpolate=True)
true_x = SPEED * newest["t"]
rows = []
for name, run in (("newest state", newest), ("interpolated", smooth)):
    x = run["poses"][:, 0, 0]
    moves = np.diff(x)  # from frame to frame (the first frame, starting up, left out)
    behind = (true_x - x)[1:]
    rows.append((name, f"{moves.min():.4f} .. {moves.max():.4f}", f"{moves.std():.2e}",
                 f"{behind.min():.4f} .. {behind.max():.4f}"))  # fmt: skip
print(
    f"steps per frame, first 10 frames: {newest['steps'][:10].tolist()}; "
    f"alpha: {np.round(newest['alpha'][:5], 3).tolist()}"
)
print_table(["drawn", "distance per frame (m)", "its spread (std, m)",
             "behind the true position (m)"], rows)  # fmt: skip
print(f"one step at {SPEED} m/s is {SPEED * DT:.3f} m; one frame {SPEED / DISPLAY_HZ:.3f} m")

# %% [markdown]
# The interpolated ball moves exactly $v/50 = 0.06$ m every frame and trails the true position
# by exactly one step, $v\,\Delta t = 0.05$ m: a constant delay of 1/60 s, which the eye does not
# see. The newest-state ball moves 0.05 m four times and 0.10 m once, and its distance behind
# the truth wobbles between 0 and 0.04 m: that unevenness is what the eye sees.
#
# ## An uneven display, and stepping with the frame time
#
# Now frames of random length between 11 and 33 ms (a busy machine). A ball bounces ($e = 0.8$)
# on the floor. Two ways to run it:
#
# - **frame time as the step**: `world.step(frame_time)`, one step per frame;
# - **fixed step with an accumulator**, as above.
#
# Each is run with the uneven frames and with steady 50 Hz frames. The physics of the fixed-step
# runs does not depend on the frames at all: after the same number of steps the two runs are
# identical to the last bit. The frame-time runs are two different simulations.

# %%
rng = np.random.default_rng(SEED)
uneven = rng.uniform(*JITTER, 200)
uneven = uneven[: int(np.searchsorted(np.cumsum(uneven), SECONDS)) + 1]


def bouncing_ball() -> World:
    world = World(gravity=(0.0, -9.81), dt=DT)
    floor = world.add_body(Body("floor", type="static"))
    floor.add_shape(Box(4.0, 0.5, offset=(0.0, -0.25), restitution=1.0))
    ball = world.add_body(Body("ball", position=(0.0, 2.25)))
    ball.add_shape(Circle(0.25, restitution=0.8))
    return world


def frame_time_steps(frame_times) -> tuple[np.ndarray, np.ndarray]:
    world = bouncing_ball()
    t, y = [0.0], [world.body("ball").position[1]]
    for frame_time in frame_times:
        world.step(frame_time)  # the step is whatever the frame took
        t.append(world.time)
        y.append(world.body("ball").position[1])
    return np.array(t), np.array(y)


variable = {name: frame_time_steps(ft) for name, ft in (("steady", steady), ("uneven", uneven))}
fixed = {}
for name, ft in (("steady", steady), ("uneven", uneven)):
    world = bouncing_ball()
    run = game_loop(world, ft, interpolate=True)
    fixed[name] = (world, run)
n_common = min(fixed[k][0].steps for k in fixed)  # compare after the same number of steps
replay = {}
for name in fixed:
    world = bouncing_ball()
    for _ in range(n_common):
        world.step()
    replay[name] = pose(world)[1]
y_var = {k: np.interp(1.9, *v) for k, v in variable.items()}
print_table(
    ["", "steady 50 Hz", "uneven frames", "difference"],
    [("frames", len(steady), len(uneven), ""),
     ("fixed steps taken", fixed["steady"][0].steps, fixed["uneven"][0].steps, ""),
     (f"fixed step: ball y after {n_common} steps (m)", f"{replay['steady'][1]:.15f}",
      f"{replay['uneven'][1]:.15f}", f"{abs(replay['steady'][1] - replay['uneven'][1]):.1e}"),
     ("frame-time steps: ball y at t = 1.9 s (m)", f"{y_var['steady']:.6f}",
      f"{y_var['uneven']:.6f}", f"{abs(y_var['steady'] - y_var['uneven']):.3f}")],
)  # fmt: skip
print(f"longest frame {1000 * uneven.max():.1f} ms = a step of {uneven.max() / DT:.2f} fixed steps")

# %%
fig, axes = plt.subplots(1, 3, figsize=(16, 4.4))
ax = axes[0]
ax.plot(newest["t"], true_x - newest["poses"][:, 0, 0], "o-", color="C3", ms=3,
        label="newest state")  # fmt: skip
ax.plot(smooth["t"], true_x - smooth["poses"][:, 0, 0], "s-", color="C0", ms=3,
        label="interpolated")  # fmt: skip
ax.set(xlabel="frame time t (s)", ylabel="true x - drawn x (m)", xlim=(0, 0.5),
       title="50 Hz frames, 60 Hz steps: how far behind")  # fmt: skip
ax = axes[1]
ax.step(np.arange(len(newest["steps"])), newest["steps"], where="mid", color="C2",
        label="steps in the frame")  # fmt: skip
ax.plot(newest["alpha"], ".", color="C4", label="alpha after the frame")
ax.set(xlabel="frame (count)", ylabel="steps (count), alpha (1)", xlim=(0, 25), ylim=(-0.1, 2.4),
       title="the accumulator, frame by frame")  # fmt: skip
ax = axes[2]
for (name, (t, y)), color in zip(variable.items(), ("C1", "C5"), strict=True):
    ax.plot(t, y, color=color, label=f"frame-time steps, {name} frames")
world_s, run_s = fixed["steady"]
ax.plot(run_s["t"] - DT, run_s["poses"][:, 1, 1], color="k", lw=2.5, alpha=0.35,
        label="fixed steps, either frames (drawn one step late)")  # fmt: skip
ax.set(xlabel="t (s)", ylabel="ball height y (m)", title="bouncing ball, e = 0.8")
for a in axes:
    a.grid(alpha=0.3)
    a.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.16))
fig.tight_layout()
save_figure(fig, OUT / "fixed_timestep.png", dpi=100)

# %% [markdown]
# **The spiral of death.** If one step costs more real time than it simulates, every frame owes
# more steps than the last and the program stalls. The loop clamps a frame's time to
# `MAX_FRAME` (0.25 s): after a long pause the simulation loses time (it runs slow for a moment)
# instead of trying to catch up (Unity's "maximum allowed timestep" is such a cap).
#
# ## Animation
#
# The two moving balls at the steady 50 Hz display, one frame of the GIF per display frame
# (the GIF plays at 50 frames per second): top, the newest state (watch it hitch every fifth
# frame); middle, interpolated; bottom, the exact position $x = vt$ at the frame's time, which
# the interpolated ball follows at a constant 5 cm.

# %%
lanes = []
for y, interpolate in ((0.8, False), (0.0, True)):
    world = moving_ball(y)
    run = game_loop(world, steady, interpolate)
    rec = Recording.from_world(world)
    for t, drawn in zip(run["t"], run["poses"], strict=True):
        rec.add_frame(drawn, t)
    lanes.append(rec)
truth = Recording.from_world(moving_ball(-0.8))
for t in run["t"]:
    truth.add_frame([[SPEED * t, -0.8, 0.0]], t)  # the exact position at the frame's time
lanes.append(truth)
gif = render_gif(lanes, OUT / "interpolation.gif", fps=DISPLAY_HZ, size_px=360,
                 labels=["newest state", "interpolated", "exact, x = v t"],
                 view=(-0.4, SPEED * SECONDS + 0.4, -1.6, 1.6), colors=["C3", "C0", "0.5"])  # fmt: skip
print(f"wrote {len(lanes[0])} frames to {gif.name}")

# %% [markdown]
# ## Exercises
#
# Predict first, then run the cell under the question, then open the answer.
#
# **1.** A 144 Hz display with the 60 Hz physics: how many steps does each frame take, and how far
# behind the true position is the interpolated ball?

# %%
fast = game_loop(moving_ball(), np.full(144, 1 / 144), interpolate=True)
print(f"steps per frame, first 12: {fast['steps'][:12].tolist()}; behind the true x: "
      f"{np.round((SPEED * fast['t'] - fast['poses'][:, 0, 0])[:3], 4).tolist()} m ...")  # fmt: skip

# %% [markdown]
# <details><summary>Answer</summary>
#
# $60/144 = 0.42$ steps per frame: most frames take no step at all (0, 0, 1, 0, 1, 0, 0, 1, ...),
# and without interpolation the ball would be drawn in the same place two or three frames in a
# row. Interpolated, it is drawn one step ($3 \times 1/60 = 0.05$ m) behind the truth in every
# frame once the first step has been taken (the first two frames, before it, trail by 0.021 and
# 0.042 m), moving $3/144 = 0.021$ m per frame.
#
# </details>
#
# **2.** The game freezes for half a second (one frame of 0.5 s) while the physics runs at 60 Hz.
# How many steps does the next frame take with `MAX_FRAME` = 0.25 s, and how much simulated time
# is lost?

# %%
pause = game_loop(moving_ball(), [1 / 50, 0.5, 1 / 50], interpolate=True)
print(f"steps per frame: {pause['steps'].tolist()}; simulated {sum(pause['steps']) * DT:.4f} s "
      f"of {pause['t'][-1]:.4f} s")  # fmt: skip

# %% [markdown]
# <details><summary>Answer</summary>
#
# The 0.5 s frame is clamped to 0.25 s: 15 steps ($0.25 \times 60$), not 30. The three frames
# last 0.54 s but only $1 + 15 + 1 = 17$ steps (0.283 s) are simulated: 0.25 s is dropped, and
# the program stays responsive instead of spending the next frame catching up.
#
# </details>
