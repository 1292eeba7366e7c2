# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: percent
# ---

# %% [markdown]
# # 11 Joints
#
# Slides, "Further Topics on Physics Animation": joints (ball-and-socket, hinges, motors).
#
# A joint is a rule about two bodies' relative motion. The engine keeps it the way it keeps a
# contact (slides, "Simultaneous Collision Resolution", iterative solver): every step it looks
# at the joint's *velocity* rule and applies the impulse $\mathbf{j}$ that makes it hold,
# $\Delta\mathbf{v} = \mathbf{j}/m$, $\Delta\omega = (\mathbf{r}\times\mathbf{j})/I$, sweeping
# over all joints and contacts several times (`settings.iterations`); after the positions
# moved, a position pass removes what is left of the error.
#
# - **pin** (`PinJoint`): $C = |\mathbf{p}_b - \mathbf{p}_a| - L = 0$, a massless rod
# - **pivot** (`PivotJoint`): $\mathbf{p}_b - \mathbf{p}_a = \mathbf{0}$, a hinge, with optional
#   limits $lo \le \theta_b - \theta_a \le hi$ (one-sided: the stop only pushes) and a motor
#   driving $\omega_b - \omega_a$ to a rate with a bounded torque
#
# We check a pendulum against its closed-form period, swing a chain, stop a hinge at its
# limits and spin a wheel up with a motor.

# %%
import math

import matplotlib.pyplot as plt
import numpy as np

from sandbox import Body, Box, Circle, World
from sandbox.joints import PinJoint, PivotJoint
from sandbox.lessonkit import output_dir, print_table, save_figure, show_gif
from sandbox.recording import record
from sandbox.render import render_gif

# knobs
LENGTH = 2.0  # m, pendulum
AMPLITUDES = (5, 15, 30, 45, 60, 90, 120, 150)  # degrees
SWINGS = 3  # periods simulated per amplitude
LINKS = 10  # chain
LINK = 0.5  # m between a link's two hinges
ITERATIONS = (5, 10, 20)  # solver sweeps per step, for the chain
LIMITS = (-0.6, 0.4)  # rad, the hinge's stops
MOTOR = {"rate": 2.0, "max_torque": 10.0}  # rad/s, N m
DT = 1.0 / 60.0  # s
G = 9.81

OUT = output_dir("11_joints")

# %% [markdown]
# ## A pendulum: period against amplitude
#
# For small swings $\ddot\theta = -(g/L)\sin\theta \approx -(g/L)\theta$, so
# $T_0 = 2\pi\sqrt{L/g}$ whatever the amplitude. For a swing of amplitude $\theta_0$ the exact
# period is
#
# $$T = 4\sqrt{L/g}\,K\!\left(\sin\tfrac{\theta_0}{2}\right)
#     = T_0\left(1 + \tfrac{1}{16}\theta_0^2 + \tfrac{11}{3072}\theta_0^4 + \dots\right),$$
#
# with $K(k) = \int_0^{\pi/2} d\phi / \sqrt{1 - k^2\sin^2\phi}$, the complete elliptic integral
# of the first kind (computed below with the arithmetic-geometric mean:
# $K(k) = \pi / (2\,\mathrm{AGM}(1, \sqrt{1-k^2}))$). A bob on a pin joint, released at rest, is
# that pendulum.


# %%
def elliptic_k(k: float) -> float:
    a, b = 1.0, math.sqrt(1.0 - k * k)
    while abs(a - b) > 1e-15:
        a, b = 0.5 * (a + b), math.sqrt(a * b)
    return math.pi / (2.0 * a)


def exact_period(amplitude: float) -> float:
    return 4.0 * math.sqrt(LENGTH / G) * elliptic_k(math.sin(0.5 * amplitude))


def series_period(amplitude: float) -> float:
    return T0 * (1 + amplitude**2 / 16 + 11 * amplitude**4 / 3072)


def pendulum(degrees: float) -> tuple[World, Body]:
    world = World(dt=DT)
    anchor = world.add_body(Body("anchor", type="static", position=(0.0, 0.0)))
    th = math.radians(degrees)
    bob = world.add_body(Body("bob", position=(LENGTH * math.sin(th), -LENGTH * math.cos(th))))
    bob.add_shape(Circle(0.15))
    world.add_joint(PinJoint(anchor, bob))
    return world, bob


def measure(degrees: float) -> tuple[float, float, float]:
    """Period from the zero crossings of the swing angle, the amplitude left after SWINGS
    periods (degrees) and the worst pin error (m)."""
    world, bob = pendulum(degrees)
    steps = int(SWINGS * exact_period(math.radians(degrees)) / DT) + 2
    t, theta, error = [], [], 0.0
    for _ in range(steps):
        world.step()
        x, y = bob.position
        t.append(world.time)
        theta.append(math.atan2(x, -y))
        error = max(error, world.joints[0].anchor_error())
    t, theta = np.array(t), np.array(theta)
    k = np.flatnonzero(np.sign(theta[:-1]) != np.sign(theta[1:]))
    crossings = t[k] - theta[k] * (t[k + 1] - t[k]) / (theta[k + 1] - theta[k])
    period = 2.0 * float(np.mean(np.diff(crossings)))  # crossings are half a period apart
    last = np.degrees(np.max(np.abs(theta[-int(exact_period(1.0) / DT) :])))
    return period, last, error


T0 = 2 * math.pi * math.sqrt(LENGTH / G)
rows, measured = [], []
for deg in AMPLITUDES:
    th0 = math.radians(deg)
    period, last, error = measure(deg)
    measured.append(period)
    exact = exact_period(th0)
    rows.append(
        (deg, period, T0, series_period(th0), exact, f"{(period - exact) / exact:+.2%}", last,
         error * 1000)
    )  # fmt: skip
print(f"L = {LENGTH} m, g = {G} m/s^2, dt = {DT:.4f} s: T0 = 2 pi sqrt(L/g) = {T0:.4f} s")
print_table(
    ["amplitude (deg)", "T measured (s)", "T0", "T series", "T exact", "vs exact",
     f"amplitude after {SWINGS} T", "pin error (mm)"],
    rows,
)  # fmt: skip

# %%
grid = np.radians(np.linspace(0.5, 170, 300))
fig, ax = plt.subplots(figsize=(7, 4))
ax.plot(np.degrees(grid), [exact_period(a) / T0 for a in grid], "k", label="exact (elliptic K)")
ax.plot(np.degrees(grid), [series_period(a) / T0 for a in grid], "C1--", label="series, 2 terms")
ax.axhline(1.0, color="C2", ls=":", label=r"small angle $2\pi\sqrt{L/g}$")
ax.plot(AMPLITUDES, np.array(measured) / T0, "o", color="C0", label="pin joint, this engine")
ax.set(xlabel=r"amplitude $\theta_0$ (deg)", ylabel="T / T0", title="pendulum period")
ax.legend(fontsize=8)
fig.tight_layout()
save_figure(fig, OUT / "pendulum_period.png", dpi=100)

# %% [markdown]
# The measured periods sit on the exact curve; the small-angle formula is 0.05% off at
# 5 degrees and 18% at 120. The amplitude barely changes over the swings: the pin's velocity
# rule aims at where the bob will be at the *end* of the step (it adds the inward
# $v^2\Delta t / 2L$ that a straight step along the tangent misses), so the position pass has
# almost nothing to pull back and the pendulum keeps its energy.
#
# ## A chain
#
# Ten boxes hinged end to end, released horizontally. Each pivot is two rows of equations
# ($x$ and $y$) with the 2x2 effective mass
# $K = (1/m_a + 1/m_b)\,\mathbf{1} + \ldots$; the solver sweeps the chain `iterations` times per
# step, each hinge correcting its two links given what the others did. Fewer sweeps leave more
# stretch for the position pass to remove: we measure the worst anchor separation.


# %%
def chain(iterations: int = 10) -> World:
    world = World(dt=DT, iterations=iterations)
    anchor = world.add_body(Body("chain anchor", type="static", position=(0.0, 0.0)))
    prev = anchor
    for i in range(LINKS):
        link = world.add_body(Body(f"link{i}", position=((i + 0.5) * LINK, 0.0)))
        link.add_shape(Box(0.8 * LINK, 0.1))
        world.add_joint(
            PivotJoint(prev, link, (0.0, 0.0) if i == 0 else (0.5 * LINK, 0.0), (-0.5 * LINK, 0))
        )
        prev = link
    return world


drift_curves, rows = {}, []
for iterations in ITERATIONS:
    world = chain(iterations)
    e0, worst = world.energy(), []
    for _ in range(240):
        world.step()
        worst.append(max(j.anchor_error() for j in world.joints))
    drift_curves[iterations] = worst
    rows.append((iterations, 1000 * max(worst), 1000 * float(np.mean(worst)), world.energy() - e0))
print_table(["iterations", "worst anchor error (mm)", "mean (mm)", "energy change (J)"], rows, 3)

fig, ax = plt.subplots(figsize=(7, 3.5))
t = DT * np.arange(1, 241)
for iterations, worst in drift_curves.items():
    ax.plot(t, 1000 * np.array(worst), label=f"{iterations} iterations")
ax.set(xlabel="t (s)", ylabel="worst anchor separation (mm)", title=f"{LINKS}-link chain")
ax.legend(fontsize=8)
fig.tight_layout()
save_figure(fig, OUT / "chain_drift.png", dpi=100)

# %% [markdown]
# ## A hinge with limits, and a motor
#
# A 2 m rod hinged at one end falls from the horizontal onto its lower stop
# ($\theta_b - \theta_a = lo$, as pymunk's `RotaryLimitJoint`). The stop is an inequality: its
# impulse may only push ($\lambda \ge 0$, accumulated, like a contact's), so the rod rests on
# it and can leave it.
#
# A motor is a velocity rule $\omega_b - \omega_a = \text{rate}$ whose impulse is capped at
# $\tau_{max}\,\Delta t$: a wheel of moment $I$ spins up at $\alpha = \tau_{max} / I$
# (slides, "Effects of Torque") until it reaches the rate, then holds it.


# %%
def hinge_and_wheel() -> tuple[World, PivotJoint, PivotJoint]:
    world = World(dt=DT)
    frame = world.add_body(Body("frame", type="static", position=(-4.0, -5.0)))
    rod = world.add_body(Body("rod", position=(-3.0, -5.0)))
    rod.add_shape(Box(2.0, 0.15))
    hinge = world.add_joint(PivotJoint(frame, rod, (0.0, 0.0), (-1.0, 0.0), limits=LIMITS))
    axle = world.add_body(Body("axle", type="static", position=(2.5, -5.0)))
    wheel = world.add_body(Body("wheel", position=(2.5, -5.0)))
    wheel.add_shape(Circle(1.0))
    for x in (-0.6, 0.6):  # two marks to see it turn, balanced: the centre of mass stays put
        wheel.add_shape(Box(0.3, 0.3, offset=(x, 0.0)))
    motor = world.add_joint(PivotJoint(axle, wheel, motor=MOTOR))
    return world, hinge, motor


world, hinge, motor = hinge_and_wheel()
wheel = world.body("wheel")
t, theta, omega, torque = [], [], [], []
for _ in range(150):
    world.step()
    t.append(world.time)
    theta.append(hinge.relative_angle())
    omega.append(wheel.angular_velocity)
    torque.append(motor.motor_torque)
alpha = MOTOR["max_torque"] / wheel.moment
print_table(
    ["quantity", "theory", "measured"],
    [
        ("lowest hinge angle (rad)", LIMITS[0], min(theta)),
        ("hinge angle at rest (rad)", LIMITS[0], theta[-1]),
        ("wheel spin-up alpha = tau / I (rad/s^2)", alpha, (omega[4] - omega[0]) / (4 * DT)),
        ("wheel rate at the end (rad/s)", MOTOR["rate"], omega[-1]),
        ("motor torque at the end (N m)", 0.0, torque[-1]),
    ],
)

fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 3.5))
ax.plot(t, theta, label=r"$\theta_b - \theta_a$")
for lim in LIMITS:
    ax.axhline(lim, color="k", ls=":", lw=1)
ax.set(xlabel="t (s)", ylabel="rad", title=f"hinge with limits {LIMITS}")
ax.legend(fontsize=8)
bx.plot(t, omega, label=r"$\omega$ wheel")
bx.plot(t, np.minimum(alpha * np.array(t), MOTOR["rate"]), "k--", lw=1, label=r"$\alpha t$, capped")
bx.plot(t, np.array(torque) / MOTOR["max_torque"], color="C1", label=r"$\tau / \tau_{max}$")
bx.set(xlabel="t (s)", title="motor: rate 2 rad/s, at most 10 N m")
bx.legend(fontsize=8)
fig.tight_layout()
save_figure(fig, OUT / "hinge_and_motor.png", dpi=100)

# %% [markdown]
# ## All four together
#
# A pendulum at 60 degrees, the chain, the limited hinge and the motor wheel in one world
# (far enough apart not to touch), with the pendulum's angle beside them.

# %%
world = World(dt=DT)
anchor = world.add_body(Body("anchor", type="static", position=(-6.0, 0.0)))
anchor.add_shape(Circle(0.08))  # drawn as a disc; the rod is drawn as a line
bob = world.add_body(Body("bob", position=(-6.0 + LENGTH * math.sin(1.047), -LENGTH * 0.5)))
bob.add_shape(Circle(0.15))
world.add_joint(PinJoint(anchor, bob))
prev = world.add_body(Body("chain anchor", type="static", position=(-1.0, 0.0)))
for i in range(6):
    link = world.add_body(Body(f"link{i}", position=(-1.0 + (i + 0.5) * LINK, 0.0)))
    link.add_shape(Box(0.8 * LINK, 0.1))
    world.add_joint(PivotJoint(prev, link, (0, 0) if i == 0 else (0.5 * LINK, 0), (-0.5 * LINK, 0)))
    prev = link
frame = world.add_body(Body("frame", type="static", position=(-6.0, -5.0)))
rod = world.add_body(Body("rod", position=(-5.0, -5.0)))
rod.add_shape(Box(2.0, 0.15))
world.add_joint(PivotJoint(frame, rod, (0.0, 0.0), (-1.0, 0.0), limits=LIMITS))
axle = world.add_body(Body("axle", type="static", position=(0.5, -5.0)))
wheel = world.add_body(Body("wheel", position=(0.5, -5.0)))
wheel.add_shape(Circle(1.0))
for x in (-0.6, 0.6):
    wheel.add_shape(Box(0.3, 0.3, offset=(x, 0.0)))
world.add_joint(PivotJoint(axle, wheel, motor=MOTOR))
ANGLE = "pendulum angle (deg)"
rec = record(
    world,
    180,
    every=2,
    series={ANGLE: lambda w: math.degrees(math.atan2(bob.position[0] + 6, -bob.position[1]))},
)
gif = render_gif(rec, OUT / "joints.gif", fps=30, size_px=360, panel=ANGLE, trail=40)
show_gif(gif)
print(f"wrote {len(rec)} frames to {gif.name}")
