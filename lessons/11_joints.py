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
from sandbox.lessonkit import output_dir, print_table, save_figure
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
ax.set(xlabel=r"amplitude $\theta_0$ (deg)", ylabel="T / T0 (1)", title="pendulum period")
ax.legend(fontsize=8)
fig.tight_layout()
save_figure(fig, OUT / "pendulum_period.png", dpi=100)

# %% [markdown]
# The measured periods sit on the exact curve. The true period exceeds the small-angle $T_0$ by
# the amounts printed below: 0.05% at 5 degrees, 18% at 90 degrees and 37% at 120. The amplitude
# barely changes over the swings: the pin's velocity rule aims at where the bob will be at the
# *end* of the step (it adds the inward $v^2\Delta t / 2L$ that a straight step along the
# tangent misses), so the position pass has almost nothing to pull back and the pendulum keeps
# its energy.

# %%
print_table(
    ["amplitude (deg)", "T exact / T0", "T exact / T0 - 1", "T measured / T0"],
    [(deg, exact_period(math.radians(deg)) / T0,
      f"{exact_period(math.radians(deg)) / T0 - 1:.2%}", t_m / T0)
     for deg, t_m in zip(AMPLITUDES, measured, strict=True) if deg in (5, 60, 90, 120)],
)  # fmt: skip

# %% [markdown]
# ## The pin's Jacobian and effective mass
#
# How does the solver turn "keep the distance" into an impulse? Write the velocities of both
# bodies as one vector $V = (\mathbf{v}_a, \omega_a, \mathbf{v}_b, \omega_b)$ (6 numbers) and
# let $\mathbf{r}_a, \mathbf{r}_b$ run from each centre of mass to its anchor,
# $\mathbf{d} = \mathbf{p}_b - \mathbf{p}_a$ between the anchors, $\hat{\mathbf{u}} =
# \mathbf{d}/|\mathbf{d}|$.
#
# 1. **Position constraint**: $C = |\mathbf{d}| - L = 0$.
# 2. **Velocity constraint**: differentiate. $\dot C = \hat{\mathbf{u}}\cdot\dot{\mathbf{d}}$,
#    and each anchor moves with its body, $\dot{\mathbf{p}} = \mathbf{v} + \omega\times
#    \mathbf{r}$, so with $\hat{\mathbf{u}}\cdot(\omega\times\mathbf{r}) =
#    \omega\,(\mathbf{r}\times\hat{\mathbf{u}})$:
#    $$\dot C = -\hat{\mathbf{u}}\cdot\mathbf{v}_a - (\mathbf{r}_a\times\hat{\mathbf{u}})\,\omega_a
#    + \hat{\mathbf{u}}\cdot\mathbf{v}_b + (\mathbf{r}_b\times\hat{\mathbf{u}})\,\omega_b = J\,V,$$
#    $$J = \big[-\hat{\mathbf{u}}^T,\ -(\mathbf{r}_a\times\hat{\mathbf{u}}),\
#    \hat{\mathbf{u}}^T,\ (\mathbf{r}_b\times\hat{\mathbf{u}})\big]$$
#    the **Jacobian**: one row, how fast each velocity component changes $C$.
# 3. **The impulse acts along $J$**: a rod can only push or pull along itself, so the impulse on
#    the bodies is $\Delta(MV) = J^T\lambda$ ($\lambda\hat{\mathbf{u}}$ on b at its anchor,
#    $-\lambda\hat{\mathbf{u}}$ on a), with $M = \mathrm{diag}(m_a, m_a, I_a, m_b, m_b, I_b)$:
#    $\Delta V = M^{-1}J^T\lambda$. Such an impulse does no work on the constrained motion.
# 4. **Solve for $\lambda$**: after the impulse $J(V + M^{-1}J^T\lambda) = 0$, so
#    $$\lambda = -\frac{J V}{J M^{-1} J^T}, \qquad J M^{-1} J^T = \frac{1}{m_a} + \frac{1}{m_b}
#    + \frac{(\mathbf{r}_a\times\hat{\mathbf{u}})^2}{I_a} + \frac{(\mathbf{r}_b\times
#    \hat{\mathbf{u}})^2}{I_b} = K.$$
#    $1/K$ is the **effective mass** of the pin: the same expression as a contact's (lesson 07),
#    with the rod's direction in place of the contact normal. A static body has $1/m = 1/I = 0$.
#
# Below, two free boxes pinned corner to corner are pulled apart along the rod at $\dot C = 2$
# m/s, without turning. One engine step must apply exactly this $\lambda$ (the engine's arc
# correction, a small inward target for $\dot C$, is zero when nothing turns or slides
# sideways) and leave $J V' = 0$.

# %%
world = World(gravity=(0.0, 0.0), dt=DT)
box_a = world.add_body(Body("a", position=(0.0, 0.0), velocity=(-1.0, 0.3)))
box_a.add_shape(Box(1.0, 0.4))
box_b = world.add_body(Body("b", position=(1.8, 0.5), velocity=(1.0, 0.3)))
box_b.add_shape(Box(0.6, 0.6))
pin = world.add_joint(PinJoint(box_a, box_b, (0.5, 0.2), (-0.3, -0.3)))  # corner to corner
r_a = np.array(box_a.world_point((0.5, 0.2))) - np.array(box_a.center_of_mass)
r_b = np.array(box_b.world_point((-0.3, -0.3))) - np.array(box_b.center_of_mass)
d = np.array(box_b.world_point((-0.3, -0.3))) - np.array(box_a.world_point((0.5, 0.2)))
u = d / np.linalg.norm(d)


def cross2(p, q) -> float:
    return float(p[0] * q[1] - p[1] * q[0])


J = np.array([-u[0], -u[1], -cross2(r_a, u), u[0], u[1], cross2(r_b, u)])
M_inv = np.diag([1 / box_a.mass, 1 / box_a.mass, 1 / box_a.moment,
                 1 / box_b.mass, 1 / box_b.mass, 1 / box_b.moment])  # fmt: skip


def state() -> np.ndarray:
    return np.array([*box_a.velocity, box_a.angular_velocity, *box_b.velocity,
                     box_b.angular_velocity])  # fmt: skip


V = state()
K = float(J @ M_inv @ J)
lam = -float(J @ V) / K
V_hand = V + M_inv @ J * lam
world.step()
print(
    f"u = ({u[0]:.3f}, {u[1]:.3f}), r_a x u = {cross2(r_a, u):+.3f} m, r_b x u = {cross2(r_b, u):+.3f} m"
)
print("J = [" + ", ".join(f"{x:+.3f}" for x in J) + "]")
print(f"J M^-1 J^T = {K:.5f} = 1/ma + 1/mb + (ra x u)^2/Ia + (rb x u)^2/Ib = "
      + " + ".join(f"{x:.5f}" for x in (1 / box_a.mass, 1 / box_b.mass,
                                        cross2(r_a, u) ** 2 / box_a.moment,
                                        cross2(r_b, u) ** 2 / box_b.moment))
      + f"; effective mass 1/K = {1 / K:.5f} kg")  # fmt: skip
print_table(
    ["", "by hand", "engine", "difference"],
    [("impulse lambda (N s)", lam, pin.impulse, abs(lam - pin.impulse)),
     ("J V before (m/s)", float(J @ V), "", ""),
     ("J V after (m/s)", float(J @ V_hand), float(J @ state()), abs(float(J @ state()))),
     *((f"V'[{k}] ({name})", V_hand[k], state()[k], abs(V_hand[k] - state()[k]))
       for k, name in enumerate(("m/s", "m/s", "rad/s", "m/s", "m/s", "rad/s")))],
    6,
)  # fmt: skip

# %% [markdown]
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

fig, (ax, bx) = plt.subplots(1, 2, figsize=(12, 4.2))
ax.plot(t, theta, label=r"$\theta_b - \theta_a$")
for lim in LIMITS:
    ax.axhline(lim, color="k", ls=":", lw=1)
ax.plot([], [], color="k", ls=":", lw=1, label="limits")
ax.set(xlabel="t (s)", ylabel="relative angle (rad)", title=f"hinge with limits {LIMITS} rad")
ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=2)
bx.plot(t, omega, color="C0", label=r"$\omega$ wheel")
bx.plot(t, np.minimum(alpha * np.array(t), MOTOR["rate"]), "k--", lw=1, label=r"$\alpha t$, capped")
bx.set(xlabel="t (s)", ylabel=r"wheel $\omega$ (rad/s)", ylim=(0, 2.6),
       title="motor: rate 2 rad/s, at most 10 N m")  # fmt: skip
tx = bx.twinx()  # the torque is a different quantity: its own axis, on the right
tx.plot(t, torque, color="C1", label=r"motor torque $\tau$")
tx.set(ylabel="motor torque (N m)", ylim=(0, 13))
lines = bx.get_lines() + tx.get_lines()
bx.legend(lines, [ln.get_label() for ln in lines], fontsize=8, loc="upper center",
          bbox_to_anchor=(0.5, -0.16), ncol=3)  # fmt: skip
fig.tight_layout()
save_figure(fig, OUT / "hinge_and_motor.png", dpi=100)

# %% [markdown]
# ## All four together
#
# A pendulum at 60 degrees, the chain, the limited hinge and the motor wheel in one world
# (far enough apart not to touch), with the joint anchors and lever arms drawn (the `joints`
# layer) and the world's energy bars beside them (gravity measured from y = 0, where the wheel
# and the hinge sit): gravity's energy turns into motion, the motor does work (the "work by
# forces W" bar, which ends as the wheel's rotational energy), and the rod hitting its stop loses
# some. The work counts each step's torque with the spin at the end of the step (semi-implicit
# Euler), so it exceeds the wheel's $\frac{1}{2}I\omega^2$ by $\tau_{max}\,\Delta\omega\,\Delta t/2 =
# 10 \times 2/120 = 0.17$ J (printed).

# %%
world = World(dt=DT)
anchor = world.add_body(Body("anchor", type="static", position=(-6.0, 5.0)))
anchor.add_shape(Circle(0.08))  # drawn as a disc; the rod is drawn as a line
bob = world.add_body(Body("bob", position=(-6.0 + LENGTH * math.sin(1.047), 5.0 - LENGTH * 0.5)))
bob.add_shape(Circle(0.15))
world.add_joint(PinJoint(anchor, bob))
prev = world.add_body(Body("chain anchor", type="static", position=(-1.0, 5.0)))
for i in range(6):
    link = world.add_body(Body(f"link{i}", position=(-1.0 + (i + 0.5) * LINK, 5.0)))
    link.add_shape(Box(0.8 * LINK, 0.1))
    world.add_joint(PivotJoint(prev, link, (0, 0) if i == 0 else (0.5 * LINK, 0), (-0.5 * LINK, 0)))
    prev = link
frame = world.add_body(Body("frame", type="static", position=(-6.0, 0.0)))
rod = world.add_body(Body("rod", position=(-5.0, 0.0)))
rod.add_shape(Box(2.0, 0.15))
world.add_joint(PivotJoint(frame, rod, (0.0, 0.0), (-1.0, 0.0), limits=LIMITS))
axle = world.add_body(Body("axle", type="static", position=(0.5, 0.0)))
wheel = world.add_body(Body("wheel", position=(0.5, 0.0)))
wheel.add_shape(Circle(1.0))
for x in (-0.6, 0.6):
    wheel.add_shape(Box(0.3, 0.3, offset=(x, 0.0)))
world.add_joint(PivotJoint(axle, wheel, motor=MOTOR))
rec = record(world, 180, every=2, draw="joints", energy=True)
work = rec.series["energy.work"]
print(
    f"motor work over {rec.times[-1]:.1f} s: {work[-1]:.3f} J; wheel's kinetic energy "
    f"I w^2 / 2 = {0.5 * wheel.moment * wheel.angular_velocity**2:.3f} J; difference "
    f"{work[-1] - 0.5 * wheel.moment * wheel.angular_velocity**2:.3f} J"
)
gif = render_gif(rec, OUT / "joints.gif", fps=30, size_px=360, panel="energy-bars", trail=40,
                 draw="joints")  # fmt: skip
print(f"wrote {len(rec)} frames to {gif.name}")

# %% [markdown]
# ## Exercises
#
# Predict first, then run the cell under the question, then open the answer.
#
# **1.** Shorten the pendulum to $L = 0.5$ m and release it at 5 degrees. What period?


# %%
def short_pendulum_period(length: float = 0.5, degrees: float = 5.0) -> float:
    world_e1 = World(dt=DT)
    pivot = world_e1.add_body(Body("pivot", type="static"))
    th = math.radians(degrees)
    bob_e1 = world_e1.add_body(
        Body("bob", position=(length * math.sin(th), -length * math.cos(th)))
    )
    bob_e1.add_shape(Circle(0.05))
    world_e1.add_joint(PinJoint(pivot, bob_e1))
    t_e1, x_e1 = [], []
    for _ in range(300):
        world_e1.step()
        t_e1.append(world_e1.time)
        x_e1.append(bob_e1.position[0])
    t_e1, x_e1 = np.array(t_e1), np.array(x_e1)
    k = np.flatnonzero(np.sign(x_e1[:-1]) != np.sign(x_e1[1:]))
    zeros = t_e1[k] - x_e1[k] * (t_e1[k + 1] - t_e1[k]) / (x_e1[k + 1] - x_e1[k])
    return 2.0 * float(np.mean(np.diff(zeros)))


print(f"L = 0.5 m, 5 deg: T = {short_pendulum_period():.4f} s")

# %% [markdown]
# <details><summary>Answer</summary>
#
# $T_0 = 2\pi\sqrt{0.5/9.81} = 1.4185$ s (half the length, $1/\sqrt{2}$ of the period), and at 5
# degrees the exact period is 0.05% longer: 1.4192 s. The engine measures 1.4189 s, 0.02%
# short, although one period is only 85 steps of $\Delta t = 1/60$ s.
#
# </details>
#
# **2.** Halve the motor's torque limit to 5 N m. How long does the wheel take to reach 2 rad/s?

# %%
world_e2 = World(dt=DT)
axle_e2 = world_e2.add_body(Body("axle", type="static"))
wheel_e2 = world_e2.add_body(Body("wheel"))
wheel_e2.add_shape(Circle(1.0))
for x in (-0.6, 0.6):
    wheel_e2.add_shape(Box(0.3, 0.3, offset=(x, 0.0)))
world_e2.add_joint(PivotJoint(axle_e2, wheel_e2, motor={"rate": 2.0, "max_torque": 5.0}))
while wheel_e2.angular_velocity < 2.0 - 1e-9:
    world_e2.step()
print(f"I = {wheel_e2.moment:.4f} kg m^2; 2 rad/s reached at t = {world_e2.time:.4f} s")

# %% [markdown]
# <details><summary>Answer</summary>
#
# The wheel's moment is $I = 10 / 6.1039 = 1.6383$ kg m$^2$ (the spin-up above), so 5 N m gives
# $\alpha = 3.052$ rad/s$^2$ and 2 rad/s takes $2 / 3.052 = 0.655$ s: 39.3 steps, so the rate
# is reached in the 40th step, $t = 0.667$ s, which the run prints.
#
# </details>
#
# **3.** In the Jacobian example, anchor the pin at the boxes' centres instead of their corners
# (`anchor_a = anchor_b = (0, 0)`, same positions and velocities). Predict $K$ and $\lambda$.

# %%
world_e3 = World(gravity=(0.0, 0.0), dt=DT)
a_e3 = world_e3.add_body(Body("a", position=(0.0, 0.0), velocity=(-1.0, 0.3)))
a_e3.add_shape(Box(1.0, 0.4))
b_e3 = world_e3.add_body(Body("b", position=(1.8, 0.5), velocity=(1.0, 0.3)))
b_e3.add_shape(Box(0.6, 0.6))
pin_e3 = world_e3.add_joint(PinJoint(a_e3, b_e3))
u_e3 = np.array(b_e3.position) - np.array(a_e3.position)
u_e3 /= np.linalg.norm(u_e3)
k_e3 = 1 / a_e3.mass + 1 / b_e3.mass
world_e3.step()
print(
    f"u = ({u_e3[0]:.4f}, {u_e3[1]:.4f}); K = {k_e3:.5f}; engine impulse {pin_e3.impulse:.6f} N s"
)

# %% [markdown]
# <details><summary>Answer</summary>
#
# With the anchors at the centres of mass $\mathbf{r}_a = \mathbf{r}_b = 0$: no angular terms,
# $K = 1/0.4 + 1/0.36 = 5.27778$, the bodies cannot turn from the rod's pull. The rod now points
# from $(0, 0)$ to $(1.8, 0.5)$, $\hat{\mathbf{u}} = (0.9635, 0.2676)$, and the anchors separate at
# $\hat{\mathbf{u}}\cdot(2, 0) = 1.9271$ m/s, so $\lambda = -1.9271 / 5.27778 = -0.36513$ N s,
# nearly twice the corner pin's: with the corners, turning soaked up part of the pull. The
# engine applies $-0.36537$ N s. The difference is its arc correction: here the anchors also
# slide sideways, at $\hat{\mathbf{u}}_\perp\cdot(2, 0) = 0.535$ m/s, and a straight step of
# $D = 0.535/60$ m sideways would lengthen the rod by $D^2/2L$; the engine asks for that much
# inward speed, $\dot C = -D^2/(2L\Delta t) = -0.00128$ m/s, so
# $\lambda = -(1.92706 + 0.00128)/5.27778 = -0.36537$ N s.
#
# </details>
