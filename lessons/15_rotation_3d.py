# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: percent
# ---

# %% [markdown]
# # 15 Rotation in 3D, and the inertia tensor
#
# Slides "3D Angular Motion" (options 1-3), "Quaternions", "Rotation Quaternions",
# "Quaternion-Based Orientation", "Comparison of 3D Rotation Structures", "General Torque
# Equations", "Moment of Inertia Tensor" and the sphere / cuboid / cylinder examples.
#
# The engine is 2D, so this lesson uses three small, separate modules:
#
# - `sandbox/rotation3d.py`: the three structures behind one interface (`integrate`,
#   `integrate_exact`, `rotate`, `matrix`, `renormalise`, `drift`), quaternion algebra and
#   conversions between all three;
# - `sandbox/inertia3d.py`: inertia tensors of the slides' solids and of point masses;
# - `sandbox/rigid3d.py`: a torque-free body with a full inertia tensor.
#
# Conventions: a quaternion is $[s\ \mathbf{v}] = [s\ x\ y\ z]$; an orientation takes body-frame
# vectors to the world frame; $\boldsymbol{\omega}$ is a world-frame scaled axis (rad/s).

# %%
import timeit

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.collections import PolyCollection
from PIL import Image

from sandbox import inertia3d as inr
from sandbox import rigid3d as rb
from sandbox import rotation3d as r3
from sandbox.lessonkit import output_dir, print_table, save_figure, show_gif

# knobs
CUBOID = (1.0, 0.3, 0.2, 0.1)  # mass (kg), w, h, d (m): three different moments
SPIN = np.array([0.05, 6.0, 0.05])  # rad/s, body frame: mostly about the intermediate axis y
DT = 2e-3  # s, rigid-body step
T_END = 8.0  # s, long enough for two flips
TABLE_OMEGA = np.array([1.0, 2.0, 3.0])  # rad/s, constant world angular velocity
TABLE_DT, TABLE_STEPS = 1e-3, 5000  # the drift runs (5 s, 18.7 rad about the axis)
BATCH = 4096  # orientations stepped together for the per-body cost
GIF_FRAMES, GIF_PIXELS = 80, 360

OUT = output_dir("15_rotation_3d")
rng = np.random.default_rng(15)

# %% [markdown]
# ## Quaternion algebra, and the slides' inverse
#
# $|\mathbf{q}| = \sqrt{s^2 + \mathbf{v}\cdot\mathbf{v}}$, $\mathbf{q}^* = [s\ -\mathbf{v}]$,
# $\mathbf{q}_1\mathbf{q}_2 = [s_1 s_2 - \mathbf{v}_1\cdot\mathbf{v}_2\ \ s_1\mathbf{v}_2 +
# s_2\mathbf{v}_1 + \mathbf{v}_1\times\mathbf{v}_2]$.
#
# The slides give $\mathbf{q}^{-1} = \mathbf{q}^*/|\mathbf{q}|$. That is wrong: the product rule
# gives $\mathbf{q}\mathbf{q}^* = [s^2 + \mathbf{v}\cdot\mathbf{v}\ \ \mathbf{0}] = [|\mathbf{q}|^2\
# \mathbf{0}]$, so dividing by $|\mathbf{q}|$ leaves $[|\mathbf{q}|\ \mathbf{0}]$, not $[1\
# \mathbf{0}]$. The right figure is
#
# $$\mathbf{q}^{-1} = \frac{\mathbf{q}^*}{|\mathbf{q}|^2}.$$
#
# For a unit quaternion both give $\mathbf{q}^*$, which is why the slip goes unnoticed with
# rotation quaternions; it bites as soon as a quaternion has drifted off unit length.

# %%
i, j, k = np.eye(4)[1:]
q = np.array([1.0, 2.0, 3.0, 4.0])
rows = [
    ["i j", r3.qmul(i, j)],
    ["j i", r3.qmul(j, i)],
    ["|q|, q = [1 2 3 4]", r3.qnorm(q)],
    ["q q*", r3.qmul(q, r3.qconj(q))],
    ["q (q*/|q|)   slides", r3.qmul(q, r3.qconj(q) / r3.qnorm(q))],
    ["q (q*/|q|^2) fixed", r3.qmul(q, r3.qinv(q))],
]
print_table(["expression", "value"], [[a, np.round(b, 4)] for a, b in rows])

# %% [markdown]
# ## One rotation, three structures
#
# The slides' example $\boldsymbol{\varphi} = [0\ 0\ \pi/2]$ turns x into y. As a matrix it is
# the slides' $\mathbf{R}_{\hat{\mathbf{n}},\varphi}$; as a quaternion $\hat{\mathbf{q}} =
# [\cos\frac{\varphi}{2}\ \ \hat{\mathbf{n}}\sin\frac{\varphi}{2}]$ and $\mathbf{v}' =
# \hat{\mathbf{q}}\mathbf{v}\hat{\mathbf{q}}^*$. Every structure converts to every other;
# random round trips check the conversions.

# %%
phi = np.array([0.0, 0.0, np.pi / 2])
reps = [cls.from_scaled_axis(phi) for cls in r3.REPRESENTATIONS]
print_table(
    ["structure", "stored", "x rotated"],
    [[o.name, np.round(o.data, 4).tolist(), np.round(o.rotate([1.0, 0, 0]), 12)] for o in reps],
)
many = rng.normal(size=(1000, 3))
many *= (rng.uniform(0, np.pi, 1000) / r3.norm(many))[:, None]
mats = r3.scaled_axis_to_matrix(many)
trips = {
    "phi -> q -> phi": r3.quat_to_scaled_axis(r3.scaled_axis_to_quat(many)) - many,
    "phi -> R -> phi": r3.matrix_to_scaled_axis(mats) - many,
    "R -> q -> R": r3.quat_to_matrix(r3.matrix_to_quat(mats)) - mats,
    "slides' R formula vs q v q*": r3.quat_to_matrix(r3.scaled_axis_to_quat(many)) - mats,
}
print_table(
    ["round trip (1000 rotations)", "max error"],
    [[a, f"{np.abs(b).max():.1e}"] for a, b in trips.items()],
)

# %% [markdown]
# ### $\mathbf{q}$ and $-\mathbf{q}$: two quaternions per rotation
#
# $\mathbf{v}' = \hat{\mathbf{q}}\mathbf{v}\hat{\mathbf{q}}^*$ has $\hat{\mathbf{q}}$ in it twice, so
# $-\hat{\mathbf{q}}$ gives the same $\mathbf{v}'$: every rotation has two unit quaternions (the
# "double cover"), $[\cos\frac{\theta}{2}\ \hat{\mathbf{n}}\sin\frac{\theta}{2}]$ and its
# negative, which is the rotation by $\theta - 2\pi$ about the same axis (the slide's "angle
# automatically within $[-\pi, \pi]$" holds only up to this sign). Code that compares or blends
# quaternions must allow for it: the angle between two orientations is
# $2\arccos|\mathbf{q}_a\cdot\mathbf{q}_b|$, with the absolute value, and interpolation first
# flips one of them when $\mathbf{q}_a\cdot\mathbf{q}_b < 0$.

# %%
q350 = r3.quat_from_axis_angle([0.0, 0.0, 1.0], np.radians(350.0))  # 350 deg about z
print_table(
    ["", "value"],
    [["q for 350 deg about z", np.round(q350, 4)],
     ["-q", np.round(-q350, 4)],
     ["max |R(q) - R(-q)|", f"{np.abs(r3.quat_to_matrix(q350) - r3.quat_to_matrix(-q350)).max():.1e}"],
     ["angle of -q (deg)", f"{np.degrees(2 * np.arctan2(r3.norm(-q350[1:]), -q350[0])):.1f}"],
     ["4D angle between q and -q (deg)", f"{np.degrees(np.arccos(np.clip(q350 @ -q350, -1, 1))):.1f}"],
     ["rotation between them, 2 arccos|q.q'| (deg)",
      f"{np.degrees(r3.angle_between(q350, -q350)):.1e}"]],
)  # fmt: skip

# %% [markdown]
# ## The slides' update rules, checked
#
# - Option 1, $\boldsymbol{\varphi} \leftarrow \boldsymbol{\varphi} + \boldsymbol{\omega}\Delta t$,
#   is only right while the axis is fixed. The true rate is
#   $\dot{\boldsymbol{\varphi}} = \boldsymbol{\omega} - \frac12\boldsymbol{\varphi}\times\boldsymbol{\omega}
#   + c\,\boldsymbol{\varphi}\times(\boldsymbol{\varphi}\times\boldsymbol{\omega})$,
#   $c = (1 - \frac{\theta}{2}\cot\frac{\theta}{2})/\theta^2$, $\theta = |\boldsymbol{\varphi}|$
#   (`scaled_axis_rate`); the extra terms vanish only when $\boldsymbol{\varphi} \parallel
#   \boldsymbol{\omega}$. Example: $90°$ about x, then a quarter turn about z.
# - Option 2 prints $\Phi(t+\Delta t) \approx \mathbf{R}_{\hat{\boldsymbol{\omega}},|\boldsymbol{\omega}|}\Phi(t)$:
#   the angle must be $|\boldsymbol{\omega}|\Delta t$. With it the update is an exact rotation
#   (for constant $\boldsymbol{\omega}$) and only rounding erodes orthogonality.
# - Option 3, $\boldsymbol{\varphi} + \frac{\Delta t}{2}[0\ \boldsymbol{\omega}]\boldsymbol{\varphi}$,
#   is right for a world-frame $\boldsymbol{\omega}$ (body frame: $\frac{\Delta t}{2}\boldsymbol{\varphi}
#   [0\ \boldsymbol{\omega}]$). $[0\ \boldsymbol{\omega}]\boldsymbol{\varphi}$ is orthogonal to
#   $\boldsymbol{\varphi}$ in 4D, so every step multiplies $|\boldsymbol{\varphi}|$ by exactly
#   $\sqrt{1 + (|\boldsymbol{\omega}|\Delta t/2)^2}$: renormalising is not optional.
# - "Angular velocity integration still computed as scalar": in 3D it is the vector update
#   $\boldsymbol{\omega} + \boldsymbol{\alpha}\Delta t$.
# - "State Update (Take 2)" swaps two headings: under "update position and orientation" it lists
#   the updates of $\mathbf{p}$ and $\mathbf{v}$, under "update linear and angular velocities"
#   those of $\boldsymbol{\varphi}$ and $\boldsymbol{\omega}$. Take 3 groups them right: the
#   table below applies each of the four lines to a state and prints what it changed.
# - Option 1 says to "reduce $|\boldsymbol{\varphi}|$ to $[0, \pi]$ by subtracting $2\pi$";
#   $\boldsymbol{\varphi}$ is a vector, and subtracting $2\pi$ from it (or from each component)
#   is a different rotation. The wrap keeps the axis and subtracts $2\pi$ from the *length*:
#   when $|\boldsymbol{\varphi}| > \pi$, $\boldsymbol{\varphi} \leftarrow \boldsymbol{\varphi}\,
#   (1 - 2\pi/|\boldsymbol{\varphi}|)$, a vector of length $2\pi - |\boldsymbol{\varphi}|$ pointing
#   the other way (a turn by $\theta$ one way is a turn by $2\pi - \theta$ the other way). Next
#   section.

# %%
start, w = np.array([np.pi / 2, 0.0, 0.0]), np.array([0.0, 0.0, 1.0])
exact = r3.qmul(r3.scaled_axis_to_quat(w * np.pi / 2), r3.scaled_axis_to_quat(start))
naive = r3.ScaledAxis(start).integrate(w, np.pi / 2)
rate = r3.scaled_axis_rate(start, w)
q1 = r3.Quaternion.identity().integrate(TABLE_OMEGA, TABLE_DT)
grow = np.sqrt(1 + (r3.norm(TABLE_OMEGA) * TABLE_DT / 2) ** 2)
print_table(
    ["check", "value"],
    [
        ["exact phi after the turn (rad)", np.round(r3.quat_to_scaled_axis(exact), 4)],
        ["slides' phi + w dt (rad)", np.round(naive.data, 4)],
        ["  angle between them (deg)", np.degrees(r3.angle_between(naive.quaternion(), exact))],
        ["true phi' at the start (rad/s)", np.round(rate, 4)],
        ["|q| after one quaternion step", f"{r3.qnorm(q1.data):.12f}"],
        ["sqrt(1 + (|w| dt / 2)^2)", f"{grow:.12f}"],
    ],
)
state = {"p": np.zeros(3), "v": np.array([1.0, 0, 0]), "phi": np.zeros(3),
         "omega": np.array([0, 0, 1.0])}  # fmt: skip
a_, alpha_ = np.array([0, -9.81, 0]), np.array([0.5, 0, 0])
take2 = [  # (the slide's heading, the line under it, what it updates)
    ("position and orientation", "p + v dt", "p", state["p"] + state["v"] * TABLE_DT),
    ("position and orientation", "v + a dt", "v", state["v"] + a_ * TABLE_DT),
    ("linear and angular velocities", "phi + dt/2 [0 w] phi", "phi",
     r3.quat_to_scaled_axis(r3.Quaternion.identity().integrate(state["omega"], TABLE_DT).data)),
    ("linear and angular velocities", "w + alpha dt", "omega",
     state["omega"] + alpha_ * TABLE_DT),
]  # fmt: skip
print_table(
    ["slide heading (Take 2)", "line", "changes", "which is a"],
    [(head, line, f"{key}: |change| = {np.linalg.norm(new - state[key]):.1e}",
      {"p": "position", "v": "linear velocity", "phi": "orientation",
       "omega": "angular velocity"}[key])
     for head, line, key, new in take2],
)  # fmt: skip

# %% [markdown]
# ### Wrapping the scaled axis
#
# A body turns at 2 rad/s about a fixed axis $\hat{\mathbf{n}}$ for 5 s (10 rad, more than
# one and a half turns). Stored as $\boldsymbol{\varphi} = \theta\hat{\mathbf{n}}$ without a
# wrap, $|\boldsymbol{\varphi}|$ grows for ever; with the wrap it stays in $[0, \pi]$ and the
# vector flips direction each time $|\boldsymbol{\varphi}|$ passes $\pi$. Both describe the same
# rotation at every instant; the slides' literal "subtract $2\pi$" does not.

# %%
n_hat = np.array([12.0, 15.0, 16.0]) / 25.0  # a unit axis
t_wrap = np.linspace(0.0, 5.0, 501)
raw = 2.0 * t_wrap[:, None] * n_hat  # phi = theta n, theta = 2 t
wrapped = raw.copy()
for k in range(len(wrapped)):  # the wrap, applied whenever |phi| > pi
    while r3.norm(wrapped[k]) > np.pi:
        wrapped[k] = wrapped[k] * (1.0 - 2.0 * np.pi / r3.norm(wrapped[k]))
literal = raw - 2.0 * np.pi * np.floor((r3.norm(raw) + np.pi) / (2 * np.pi))[:, None]  # slides
same = np.abs(r3.scaled_axis_to_matrix(wrapped) - r3.scaled_axis_to_matrix(raw)).max()
engine = np.abs(r3.wrap_scaled_axis(raw) - wrapped).max()
wrong = np.abs(r3.scaled_axis_to_matrix(literal) - r3.scaled_axis_to_matrix(raw)).max()
print_table(
    ["check over 5 s (501 samples)", "value"],
    [["max |R(phi wrapped) - R(phi)|", f"{same:.1e}"],
     ["max |phi wrapped - rotation3d.wrap_scaled_axis(phi)|", f"{engine:.1e}"],
     ["max |R(phi - 2 pi, per component) - R(phi)|", f"{wrong:.2f}"],
     ["largest |phi| wrapped (rad)", f"{r3.norm(wrapped).max():.4f} (pi = {np.pi:.4f})"]],
)  # fmt: skip
fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 3.8))
ax.plot(t_wrap, r3.norm(raw), color="0.5", label=r"$|\varphi|$, not wrapped")
ax.plot(t_wrap, r3.norm(wrapped), color="C0", label=r"$|\varphi|$, wrapped")
ax.axhline(np.pi, color="k", ls=":", lw=1, label=r"$\pi$")
ax.set(xlabel="t (s)", ylabel=r"$|\varphi|$ (rad)", title="the length of the scaled axis")
for c, name in enumerate("xyz"):
    bx.plot(t_wrap, wrapped[:, c], color=f"C{c + 1}", label=rf"$\varphi_{name}$ wrapped")
bx.set(xlabel="t (s)", ylabel=r"$\varphi$ component (rad)",
       title="wrapped: the axis flips at |phi| = pi")  # fmt: skip
for a in (ax, bx):
    a.grid(alpha=0.3)
    a.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.18), ncol=3)
fig.tight_layout()
save_figure(fig, OUT / "scaled_axis_wrap.png", dpi=100)

# %% [markdown]
# ## The comparison table, measured
#
# Each structure is stepped with its slides' rule for 5 s at a constant world
# $\boldsymbol{\omega} = [1\ 2\ 3]$ rad/s, from 64 orientations: one parallel to
# $\boldsymbol{\omega}$ (fixed axis) and 63 random ones (axis not fixed), never renormalised.
# The reference is the closed form $\mathbf{q}(t) = \mathbf{q}_{\boldsymbol{\omega}t}\mathbf{q}_0$.
# Costs are `timeit` averages: for one orientation (Python and numpy call overhead dominate) and
# per orientation when 4096 are stepped as one array (closer to the arithmetic): the fastest of
# 30 short runs, as a run that another program interrupted reads slower, and a run of a
# millisecond or so is seldom interrupted. Absolute times depend on the machine; the ratios are
# the point.

# %%
starts = np.vstack([0.3 * TABLE_OMEGA, rng.normal(size=(63, 3))])
ref = r3.qmul(
    r3.scaled_axis_to_quat(TABLE_OMEGA * TABLE_DT * TABLE_STEPS), r3.scaled_axis_to_quat(starts)
)
batch_w = np.broadcast_to(TABLE_OMEGA, (BATCH, 3))
batch_phi = rng.normal(size=(BATCH, 3))
v = np.array([0.3, -0.2, 0.9])


def cost_us(fn, number):
    """Microseconds a call of ``fn``: the fastest of 30 runs of ``number`` / 10 calls each,
    after one run not counted (the first calls of a function run slower)."""
    calls = max(1, number // 10)
    return min(timeit.repeat(fn, number=calls, repeat=31)[1:]) / calls * 1e6


table = []
for cls in r3.REPRESENTATIONS:
    o = cls.from_scaled_axis(starts)
    for _ in range(TABLE_STEPS):
        o.integrate(TABLE_OMEGA, TABLE_DT)
    err = r3.angle_between(o.quaternion(), ref)
    one, many_o = cls.from_scaled_axis(starts[1]), cls.from_scaled_axis(batch_phi)
    table.append(
        [
            cls.name,
            cls.storage,
            cost_us(lambda o=one: o.integrate(TABLE_OMEGA, TABLE_DT), 500),
            cost_us(lambda o=many_o: o.integrate(batch_w, TABLE_DT), 20) / BATCH * 1e3,
            cost_us(lambda o=one: o.matrix(), 500),
            cost_us(lambda o=one: o.rotate(v), 500),
            cost_us(lambda o=one: o.renormalise(), 500),
            f"{o.drift().max():.1e}",
            f"{err[0]:.1e}",
            f"{err[1:].max():.1e}",
        ]
    )
headers = ["structure", "floats", "us/step", "ns/step (x4096)", "us to matrix", "us rotate v"]
headers += ["us renormalise", "drift, 5000 steps", "err fixed axis (rad)", "err axis moving (rad)"]
comparison = print_table(headers, table, digits=2)
_ = (OUT / "comparison_table.txt").write_text(comparison + "\n")  # the count it returns: not shown

# %% [markdown]
# Reading the table against the slides: the scaled axis is the most compact (3 floats) and its
# step is one vector add, but it is exact only along a fixed axis (the last two columns) and
# it is the most expensive to turn into a matrix (a length, `cos`, `sin`, a normalised axis). The
# matrix leaves the rotations only by rounding (drift at the 1e-13 level) but costs 9 floats, a
# full matrix build per step and an SVD to renormalise. The quaternion stores 4 floats, steps
# with one quaternion product, converts to a matrix with a few multiplications and renormalises
# with one division; the slides' first-order step lets $|\mathbf{q}|$ creep up (the drift
# column) and turns each step by $2\arctan(|\boldsymbol{\omega}|\Delta t/2)$ instead of
# $|\boldsymbol{\omega}|\Delta t$ (the small error in both error columns).
#
# ## The inertia tensor
#
# $I_{xx} = \int\rho(r_y^2 + r_z^2)dV$, ..., $I_{xy} = -\int\rho\,r_x r_y dV$, ...: for point
# masses $\mathbf{I} = \sum_i m_i(|\mathbf{r}_i|^2\mathbf{E} - \mathbf{r}_i\mathbf{r}_i^T)$.
# Filling each solid with a 40 x 40 x 40 lattice of equal point masses must give the slides'
# closed forms (for the box, exactly the closed form times $1 - 1/n^2$).

# %%
m, w_, h_, d_ = CUBOID
ball = lambda p: np.sum(p * p, axis=1) <= 0.1**2  # noqa: E731
tube = lambda p: p[:, 0] ** 2 + p[:, 2] ** 2 <= 0.1**2  # noqa: E731
solids = [
    ("sphere m=1 r=0.1", inr.sphere(m, 0.1), (0.1, 0.1, 0.1), ball),
    ("cuboid 0.3x0.2x0.1", inr.cuboid(m, w_, h_, d_), (w_ / 2, h_ / 2, d_ / 2), None),
    ("cylinder r=0.1 h=0.3", inr.cylinder(m, 0.1, 0.3), (0.1, 0.15, 0.1), tube),
]
rows = []
for name, closed, half, inside in solids:
    summed = inr.point_masses(*inr.lattice_point_masses(m, half, 40, inside))
    rel = np.abs(np.diag(summed) / np.diag(closed) - 1).max()
    rows.append(
        [name, np.round(np.diag(closed) * 1e3, 4), np.round(np.diag(summed) * 1e3, 4), f"{rel:.1e}"]
    )
print_table(["solid", "closed form diag (g m^2)", "point-mass sum", "max rel diff"], rows)

# %% [markdown]
# ### A turned body: products of inertia and principal moments
#
# The slides' tensors are diagonal because each solid's axes are its symmetry axes. Turn the
# cuboid and express the tensor in the world axes, $\mathbf{I}' = \mathbf{R}\mathbf{I}\mathbf{R}^T$:
# off-diagonal **products of inertia** appear (with the slides' sign, $I_{xy} = -\int\rho\,r_x r_y
# \,dV$), and the diagonal entries change. So $I_{xx}, I_{yy}, I_{zz}$ are the moments about the x,
# y and z axes, but they are the **principal moments** only in the principal axes, the frame in
# which the products vanish. The eigenvalues of any $\mathbf{I}'$ give them back, its
# eigenvectors the body's axes. A turn about z by $\theta$ gives in closed form
# $I'_{xx} = I_x\cos^2\theta + I_y\sin^2\theta$, $I'_{yy} = I_x\sin^2\theta + I_y\cos^2\theta$,
# $I'_{xy} = (I_x - I_y)\sin\theta\cos\theta$. The point-mass lattice, turned point by point,
# checks it.

# %%
box_i = inr.cuboid(*CUBOID)
turn = r3.scaled_axis_to_matrix(np.array([0.0, 0.0, np.radians(30.0)])) @ r3.scaled_axis_to_matrix(
    np.array([np.radians(20.0), 0.0, 0.0])
)  # 20 deg about x, then 30 deg about z
turned = inr.rotate_tensor(box_i, turn)
lattice_m, lattice_p = inr.lattice_point_masses(m, (w_ / 2, h_ / 2, d_ / 2), 40, None)
turned_lattice = inr.point_masses(lattice_m, lattice_p @ turn.T)
moments_back, axes_back = inr.principal_axes(turned)
print("cuboid turned 20 deg about x then 30 deg about z, tensor in world axes (g m^2):")
print(np.round(1e3 * turned, 4))
print_table(
    ["check", "value"],
    [["diagonal of the turned tensor (g m^2)", np.round(1e3 * np.diag(turned), 4)],
     ["principal moments, eigenvalues (g m^2)", np.round(1e3 * moments_back, 4)],
     ["the slides' diagonal (g m^2)", np.round(1e3 * np.diag(box_i), 4)],
     ["max |eigenvector . body axis| - 1", f"{np.abs(np.abs(np.sum(axes_back * turn, axis=0)) - 1).max():.1e}"],
     ["turned lattice vs R I R^T, max rel diff", f"{np.abs(turned_lattice / turned - 1).max():.1e}"]],
)  # fmt: skip
thetas = np.radians(np.linspace(0.0, 180.0, 181))
rz = [r3.scaled_axis_to_matrix(np.array([0.0, 0.0, th])) for th in thetas]
entries = np.array([inr.rotate_tensor(box_i, r) for r in rz])
ix, iy = box_i[0, 0], box_i[1, 1]
fig, ax = plt.subplots(figsize=(8, 4))
for (i, j), name, closed, color in (
    ((0, 0), "$I_{xx}$", ix * np.cos(thetas) ** 2 + iy * np.sin(thetas) ** 2, "C0"),
    ((1, 1), "$I_{yy}$", ix * np.sin(thetas) ** 2 + iy * np.cos(thetas) ** 2, "C1"),
    ((0, 1), "$I_{xy}$", (ix - iy) * np.sin(thetas) * np.cos(thetas), "C2"),
):
    ax.plot(
        np.degrees(thetas), 1e3 * closed, color=color, lw=3, alpha=0.4, label=f"{name} closed form"
    )
    ax.plot(np.degrees(thetas[::10]), 1e3 * entries[::10, i, j], "o", color=color, ms=4,
            label=f"{name} of R I R^T")  # fmt: skip
ax.axhline(1e3 * ix, color="k", ls=":", lw=1, label="principal moments $I_x$, $I_y$")
ax.axhline(1e3 * iy, color="k", ls=":", lw=1)
ax.set(xlabel="turn about z (deg)", ylabel="tensor entry (g m$^2$)",
       title="the cuboid's tensor in turned axes")  # fmt: skip
ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.0, 1.0))
ax.grid(alpha=0.3)
fig.tight_layout()
save_figure(fig, OUT / "turned_tensor.png", dpi=100)

# %% [markdown]
# **"Angular acceleration parallel to torque (for symmetric bodies)"** holds for a symmetric
# body only when the torque lies along a principal axis: $\boldsymbol{\alpha} =
# \mathbf{I}^{-1}\boldsymbol{\tau}$ divides each principal component by a different moment. (A
# sphere, whose three moments are equal, is the exception: any axis is principal.) The cuboid is
# as symmetric as a box can be; the angle between $\boldsymbol{\alpha}$ and $\boldsymbol{\tau}$ for
# a body at rest:

# %%
rows = []
for name, tau_dir in (("x (principal)", [1.0, 0, 0]), ("y (principal)", [0, 1.0, 0]),
                      ("x + y", [1.0, 1.0, 0]), ("x + y + z", [1.0, 1.0, 1.0])):  # fmt: skip
    tau_v = np.asarray(tau_dir) / np.linalg.norm(tau_dir)
    row = [name]
    for tensor in (box_i, inr.sphere(m, 0.1)):
        alpha_v = np.linalg.solve(tensor, tau_v)
        cosine = alpha_v @ tau_v / np.linalg.norm(alpha_v)
        row.append(f"{np.degrees(np.arccos(np.clip(cosine, -1, 1))):.2f}")
    rows.append(row)
print_table(["torque along", "angle(alpha, tau), cuboid (deg)", "sphere (deg)"], rows)

# %% [markdown]
# ## Torque-free motion: Euler's equations and the tennis racket
#
# The slides' $\boldsymbol{\tau} = \mathbf{I}\boldsymbol{\alpha}$ is missing a term. Angular
# momentum is $\mathbf{L} = \mathbf{I}\boldsymbol{\omega}$, and $\boldsymbol{\tau} =
# \dot{\mathbf{L}}$; in the body frame, where $\mathbf{I}$ is constant,
#
# $$\boldsymbol{\tau} = \mathbf{I}\boldsymbol{\alpha} + \boldsymbol{\omega}\times(\mathbf{I}\boldsymbol{\omega}),$$
#
# (in the world frame $\mathbf{I} = \mathbf{R}\mathbf{I}_{body}\mathbf{R}^T$ changes with the
# orientation: the slides' "needs to be recalculated every time"). With $\boldsymbol{\tau} = 0$
# the slides' formula gives $\boldsymbol{\alpha} = 0$ and a constant spin; Euler's equations do
# not. A cuboid spun about its intermediate axis (y here: $I_x < I_y < I_z$) turns over every
# half period; spun about the smallest or largest axis it stays put. The flip interval has a
# closed form (Jacobi's elliptic functions, `rigid3d.omega_period`).

# %%
box = inr.cuboid(*CUBOID)
steps = round(T_END / DT)
t = np.arange(steps + 1) * DT
fig, axes = plt.subplots(3, 1, figsize=(8, 6.5), sharex=True)
rows = []
for ax, axis in zip(axes, range(3), strict=True):
    w0 = np.roll(SPIN, axis - 1)  # the big component on x, y, then z
    wb = rb.integrate_omega(box, w0, DT, steps)
    for c, name in enumerate("xyz"):
        ax.plot(t, wb[:, c], label=f"$\\omega_{name}$")
    ax.set_ylabel(r"$\omega$ (rad/s)")
    ax.set_title(f"spin about {'xyz'[axis]} (I = {box[axis, axis] * 1e3:.2f} g m$^2$)", fontsize=9)
    # the middle-axis component ~ sn(tau) changes sign every half period, flip or wobble
    gaps = np.diff(rb.sign_change_times(t, wb[:, 1]))
    flips = len(rb.sign_change_times(t, wb[:, axis]))
    half = rb.omega_period(np.diag(box), w0) / 2
    rows.append(["xyz"[axis], flips, gaps.mean(), half, f"{abs(gaps.mean() / half - 1):.1e}"])
handles, names = axes[0].get_legend_handles_labels()
fig.legend(handles, names, loc="center right", fontsize=8)
axes[-1].set_xlabel("t (s)")
fig.tight_layout(rect=(0, 0, 0.88, 1))
save_figure(fig, OUT / "tennis_racket_omega.png", dpi=110)
headers = ["spin axis", "spin reversals", "measured T/2 (s)", "closed form T/2 (s)", "rel diff"]
print_table(headers, rows, digits=4)

# %% [markdown]
# The same intermediate-axis run with an orientation (quaternion, RK4), drawn as the cuboid's
# orthographic projection on a fixed view plane. Faces are coloured by body axis (red x, green
# y, blue z); the dashed line is the fixed world angular momentum, the green one the body's y
# axis. Watch the green axis swap ends while $\mathbf{L}$ stays put.

# %%
racket = rb.simulate(box, SPIN, r3.Quaternion.identity(), DT, steps, "rk4")
half = rb.omega_period(np.diag(box), SPIN) / 2  # omega_y crosses 0 at T/4: frames 0 .. T/2
frames = np.linspace(0, min(half, T_END) / DT, GIF_FRAMES).round().astype(int)
corners = (
    np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)])
    * np.array([w_, h_, d_])
    / 2
)
faces = [
    (a, [c for c in range(8) if (c >> (2 - a)) & 1 == side]) for a in range(3) for side in (0, 1)
]
faces = [(a, [f[0], f[1], f[3], f[2]]) for a, f in faces]  # corner order around each face
view = r3.scaled_axis_to_matrix(np.array([0.35, -0.5, 0.0]))  # world -> a slightly tilted view
base = np.array([[0.85, 0.3, 0.3], [0.3, 0.75, 0.35], [0.35, 0.45, 0.9]])
fig, ax = plt.subplots(figsize=(GIF_PIXELS / 90, GIF_PIXELS / 90), dpi=90)
ax.set(xlim=(-0.22, 0.22), ylim=(-0.22, 0.22), aspect="equal", xticks=[], yticks=[])
polys = ax.add_collection(PolyCollection([], edgecolors="k", linewidths=0.6))
lhat = view @ racket.momentum[0] / np.linalg.norm(racket.momentum[0])
ax.plot([0, 0.2 * lhat[0]], [0, 0.2 * lhat[1]], "k--", lw=1.2)
(yline,) = ax.plot([], [], color="green", lw=2.5)
label = ax.text(0.03, 0.95, "", transform=ax.transAxes, fontsize=8, va="top")
fig.tight_layout()
images = []
for f in frames:
    rot = view @ racket.matrix[f]
    p = corners @ rot.T
    order = sorted(range(6), key=lambda n: p[faces[n][1], 2].mean())  # far faces first
    polys.set_verts([p[faces[n][1], :2] for n in order])
    shade = [0.55 + 0.45 * abs(rot[2, faces[n][0]]) for n in order]  # facing the viewer: bright
    polys.set_facecolor([base[faces[n][0]] * g for n, g in zip(order, shade, strict=True)])
    tip = rot[:, 1] * 0.14
    yline.set_data([0, tip[0]], [0, tip[1]])
    label.set_text(f"t = {racket.t[f]:.2f} s   $\\omega_y$ = {racket.omega_body[f, 1]:+.2f} rad/s")
    fig.canvas.draw()
    images.append(np.asarray(fig.canvas.buffer_rgba())[..., :3].copy())
plt.close(fig)
sample = Image.fromarray(np.vstack(images[:: max(1, len(images) // 8)]))
palette = sample.quantize(colors=96, method=Image.Quantize.FASTOCTREE)
gif = [Image.fromarray(a).quantize(palette=palette, dither=Image.Dither.NONE) for a in images]
gif[0].save(OUT / "tennis_racket.gif", save_all=True, append_images=gif[1:], duration=60, loop=0)
show_gif(OUT / "tennis_racket.gif")
print(f"GIF: {len(gif)} frames, {gif[0].size[0]} x {gif[0].size[1]} px")

# %% [markdown]
# ## A body under torque
#
# With a torque, $\boldsymbol{\tau} = \dot{\mathbf{L}}$ still holds in the world frame, so a
# constant world torque gives $\mathbf{L}(t) = \mathbf{L}_0 + \boldsymbol{\tau}t$ exactly. But the
# spin it produces is $\boldsymbol{\omega} = \mathbf{I}_{world}^{-1}\mathbf{L}$ with
# $\mathbf{I}_{world} = \mathbf{R}\mathbf{I}\mathbf{R}^T$, and $\mathbf{R}$ changes as the body
# turns: the slides' "moment of inertia needs to be recalculated every time". Below, the cuboid
# starts at rest and a constant world torque `TORQUE` (not along a principal axis) acts for
# `TORQUE_TIME`. The orientation is stepped with the exact rotation for the step's midpoint
# $\boldsymbol{\omega}$ (a quaternion). Against it, the slides' $\boldsymbol{\alpha} =
# \mathbf{I}^{-1}\boldsymbol{\tau}$ with the tensor of the start, $\boldsymbol{\omega} =
# \mathbf{I}^{-1}\boldsymbol{\tau}t$: right at first, wrong once the body has turned. The work
# done, $\int\boldsymbol{\tau}\cdot\boldsymbol{\omega}\,dt$, must equal the kinetic energy gained,
# $\frac{1}{2}\boldsymbol{\omega}\cdot\mathbf{L}$.

# %%
TORQUE, TORQUE_TIME, TORQUE_DT = np.array([0.002, 0.001, 0.0015]), 3.0, 2e-3  # N m, s, s
inv_box = np.linalg.inv(box)
q_t = r3.Quaternion.identity()
n_t = round(TORQUE_TIME / TORQUE_DT)
t_t = np.arange(n_t + 1) * TORQUE_DT


def spin(q: r3.Quaternion, t: float) -> np.ndarray:
    """World angular velocity w = R I^-1 R^T L with L = tau t (rad/s)."""
    rot = q.matrix()
    return rot @ inv_box @ rot.T @ (TORQUE * t)


omegas_t = [np.zeros(3)]
for k in range(n_t):
    half = r3.Quaternion(q_t.data.copy()).integrate_exact(spin(q_t, k * TORQUE_DT), TORQUE_DT / 2)
    q_t.integrate_exact(spin(half, (k + 0.5) * TORQUE_DT), TORQUE_DT)  # midpoint rule
    q_t.renormalise()
    omegas_t.append(spin(q_t, (k + 1) * TORQUE_DT))
omegas_t = np.array(omegas_t)
naive = t_t[:, None] * (inv_box @ TORQUE)  # the slides' alpha = I^-1 tau, I never updated
work = np.concatenate([[0.0], np.cumsum(0.5 * (omegas_t[1:] + omegas_t[:-1]) @ TORQUE * TORQUE_DT)])
kinetic = 0.5 * np.sum(omegas_t * (TORQUE * t_t[:, None]), axis=1)  # K = w . L / 2
cos_wt = omegas_t[1:] @ TORQUE / np.linalg.norm(omegas_t[1:], axis=1) / np.linalg.norm(TORQUE)
turned_by = np.degrees(r3.angle_between(q_t.quaternion(), r3.Quaternion.identity().data))
print_table(
    ["after the torque", "value"],
    [["body turned by (deg)", f"{turned_by:.1f}"],
     ["omega, tensor updated (rad/s)", np.round(omegas_t[-1], 4)],
     ["omega, the slides' I^-1 tau t (rad/s)", np.round(naive[-1], 4)],
     ["angle(omega, tau) at the start, at the end (deg)",
      f"{np.degrees(np.arccos(cos_wt[0])):.2f}, {np.degrees(np.arccos(cos_wt[-1])):.2f}"],
     ["kinetic energy w . L / 2 (mJ)", f"{1e3 * kinetic[-1]:.6f}"],
     ["work, integral of tau . w dt (mJ)", f"{1e3 * work[-1]:.6f}"],
     ["relative difference", f"{abs(kinetic[-1] / work[-1] - 1):.1e}"]],
)  # fmt: skip
fig, (ax, bx) = plt.subplots(1, 2, figsize=(12, 4))
for c, name in enumerate("xyz"):
    ax.plot(t_t, omegas_t[:, c], color=f"C{c}", label=rf"$\omega_{name}$, tensor updated")
    ax.plot(
        t_t,
        naive[:, c],
        color=f"C{c}",
        ls="--",
        lw=1,
        label=rf"$\omega_{name}$ = $(I^{{-1}}\tau)_{name}\,t$",
    )
ax.set(xlabel="t (s)", ylabel=r"world $\omega$ (rad/s)", title="constant world torque, from rest")
ax.legend(fontsize=7, loc="upper left", ncol=2)
bx.plot(t_t[1:], np.degrees(np.arccos(np.clip(cos_wt, -1, 1))), color="C3")
bx.set(xlabel="t (s)", ylabel=r"angle between $\omega$ and $\tau$ (deg)",
       title="omega is not along the torque")  # fmt: skip
for a in (ax, bx):
    a.grid(alpha=0.3)
fig.tight_layout()
save_figure(fig, OUT / "torque.png", dpi=100)

# %% [markdown]
# ## Energy and angular momentum, per structure and integrator
#
# Conserved: $E = \frac12\boldsymbol{\omega}\cdot\mathbf{I}\boldsymbol{\omega}$ and the world
# $\mathbf{L} = \mathbf{R}\mathbf{I}\boldsymbol{\omega}$. Integrators: the slides' explicit Euler
# (each structure's own update with $\boldsymbol{\omega}(t)$, then $\boldsymbol{\omega} +
# \boldsymbol{\alpha}\Delta t$), the same renormalised every step, and RK4 on
# $\boldsymbol{\omega}$ with the exact rotation for the step's mean $\boldsymbol{\omega}$.
# In the body frame $\boldsymbol{\omega}$ does not depend on the orientation, so the energy
# error is the same for every structure; $\mathbf{L}$ needs the orientation, and shows it.
# (These nine runs use a step of `CONS_DT` = 4 ms, twice the tennis racket's.)

# %%
CONS_DT = 4e-3  # s
cons_steps = round(T_END / CONS_DT)
t = np.arange(cons_steps + 1) * CONS_DT
fig, (ax_e, ax_l) = plt.subplots(2, 1, figsize=(9, 7), sharex=True)
colors = {"scaled axis": "tab:orange", "3x3 matrix": "tab:blue", "quaternion": "tab:green"}
widths = {"scaled axis": 3.5, "3x3 matrix": 2.2, "quaternion": 1.0}  # coinciding lines show
runs = {
    "euler": ("euler", 0, ":"),
    "euler + renormalise": ("euler", 1, "--"),
    "rk4": ("rk4", 0, "-"),
}
rows, energy = [], {}
for cls in r3.REPRESENTATIONS:
    for name, (method, every, ls) in runs.items():
        tr = rb.simulate(box, SPIN, cls.identity(), CONS_DT, cons_steps, method, every)
        e_err, l_err = tr.energy_error(), tr.momentum_error()
        energy.setdefault(method, []).append(e_err)
        lw = widths[cls.name]
        ax_l.semilogy(
            tr.t[1:], l_err[1:], color=colors[cls.name], ls=ls, lw=lw, label=f"{cls.name}, {name}"
        )
        rows.append(
            [cls.name, name, f"{e_err.max():.1e}", f"{l_err.max():.1e}", f"{tr.drift[-1]:.1e}"]
        )
for method, errs in energy.items():
    spread = np.max(np.abs(np.array(errs) - errs[0]))
    print(f"energy error, {method}: identical for all structures (largest difference {spread:.1e})")
    ax_e.semilogy(
        t[1:], errs[0][1:], color="k", ls=runs[method][2], label=f"{method}, every structure"
    )
ax_e.set(ylabel="|E - E0| / E0 (1)", title="energy error, torque-free cuboid")
ax_e.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.0, 1.0))
ax_l.set(ylabel="|L - L0| / |L0| (1)", xlabel="t (s)", title="world angular momentum error")
ax_l.legend(fontsize=6, loc="upper left", bbox_to_anchor=(1.0, 1.0))
fig.tight_layout()
save_figure(fig, OUT / "conservation.png", dpi=110)
print_table(["structure", "integrator", "max energy err", "max L err", "final drift"], rows)

# %% [markdown]
# What to take away:
#
# - the scaled axis with $\boldsymbol{\varphi} + \boldsymbol{\omega}\Delta t$ loses the angular
#   momentum completely once the body tumbles: the update itself is wrong, renormalising
#   (wrapping $|\boldsymbol{\varphi}|$ into $[0, \pi]$) cannot help;
# - the slides' quaternion step without renormalising inflates $\mathbf{L}$ through
#   $|\mathbf{q}|^2$; renormalised, it tracks the matrix to second order;
# - explicit Euler on Euler's equations gains energy at first order in $\Delta t$; RK4 holds it
#   below 1e-9 here (1.1e-10 at 4 ms), and with exact rotations all three structures then agree to rounding: the
#   choice between them is about storage and cost, the table above.

# %% [markdown]
# ## Exercises
#
# Predict first, then run the cell under the question, then open the answer.
#
# **1.** Turn the cuboid (`CUBOID`: $I_x, I_y, I_z$ = 4.17, 8.33, 10.83 g m$^2$) by 45 degrees
# about z. What are $I'_{xx}$, $I'_{yy}$ and $I'_{xy}$ in the world axes?

# %%
t45 = inr.rotate_tensor(box_i, r3.scaled_axis_to_matrix(np.array([0.0, 0.0, np.pi / 4])))
print(
    f"I'xx = {1e3 * t45[0, 0]:.4f}, I'yy = {1e3 * t45[1, 1]:.4f}, I'xy = {1e3 * t45[0, 1]:.4f} g m^2"
)

# %% [markdown]
# <details><summary>Answer</summary>
#
# With $\cos^2 45° = \sin^2 45° = \frac{1}{2}$: $I'_{xx} = I'_{yy} = (I_x + I_y)/2 = 6.25$ g m$^2$,
# and $I'_{xy} = (I_x - I_y)\sin 45°\cos 45° = (4.1667 - 8.3333)/2 = -2.0833$ g m$^2$, the
# largest product of inertia any turn about z gives. $I_{zz}$ stays 10.8333. The run prints the
# same.
#
# </details>
#
# **2.** A torque along $(1, 0, 1)$ on the cuboid at rest: what angle does $\boldsymbol{\alpha}$
# make with $\boldsymbol{\tau}$?

# %%
tau_e2 = np.array([1.0, 0.0, 1.0]) / np.sqrt(2.0)
alpha_e2 = np.linalg.solve(box_i, tau_e2)
print(f"alpha direction {np.round(alpha_e2 / np.linalg.norm(alpha_e2), 4)}, angle to tau "
      f"{np.degrees(np.arccos(alpha_e2 @ tau_e2 / np.linalg.norm(alpha_e2))):.2f} deg")  # fmt: skip

# %% [markdown]
# <details><summary>Answer</summary>
#
# $\boldsymbol{\alpha} = \mathbf{I}^{-1}\boldsymbol{\tau} \propto (1/I_x, 0, 1/I_z) = (0.240, 0,
# 0.0923)$ (per g m$^2$): the small $I_x$ makes $\boldsymbol{\alpha}$ lean towards x. The cosine
# of the angle is $(0.240 + 0.0923)/(0.2571\sqrt{2}) = 0.914$: 24.0 degrees. Printed: 23.96.
#
# </details>
#
# **3.** A body has turned 5 rad about z, $\boldsymbol{\varphi} = (0, 0, 5)$. Wrap it. What
# rotation does the slides' "subtract $2\pi$" from each component give instead?

# %%
phi_e3 = np.array([0.0, 0.0, 5.0])
wrapped_e3 = r3.wrap_scaled_axis(phi_e3)
per_component = phi_e3 - 2 * np.pi
print(f"wrapped: {np.round(wrapped_e3, 4)}, same rotation: "
      f"{np.allclose(r3.scaled_axis_to_matrix(wrapped_e3), r3.scaled_axis_to_matrix(phi_e3))}; "
      f"per component: {np.round(per_component, 4)}, same rotation: "
      f"{np.allclose(r3.scaled_axis_to_matrix(per_component), r3.scaled_axis_to_matrix(phi_e3))}")  # fmt: skip

# %% [markdown]
# <details><summary>Answer</summary>
#
# $\boldsymbol{\varphi}(1 - 2\pi/5) = (0, 0, 5 - 2\pi) = (0, 0, -1.2832)$: 1.28 rad clockwise is
# the same as 5 rad anticlockwise. Subtracting $2\pi$ from every component gives
# $(-6.2832, -6.2832, -1.2832)$, a turn by 9.0 rad about a tilted axis: a different rotation
# (the run prints False for it).
#
# </details>
