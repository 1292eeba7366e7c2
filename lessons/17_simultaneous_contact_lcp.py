# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: percent
# ---

# %% [markdown]
# # 17 Simultaneous contact as a linear complementarity problem
#
# Slide "Simultaneous Collision Resolution" lists three ways to handle all collisions at once:
# shock propagation, an iterative solver and a **linear complementarity problem (LCP)**
# formulation. Lesson 09 ran the first two; this lesson writes the third one down, solves it
# exactly for two contacts, and measures how the iterative solver approaches that answer.
#
# For each contact point $i$ the solver looks for a normal impulse $\lambda_i$ (N s). After the
# impulses, the point's normal velocity is $w_i$ (m/s, $> 0$ separating). Three rules, for every
# point at once:
#
# $$\lambda_i \ge 0 \ \text{(contacts push, never pull)}, \qquad
#   w_i \ge 0 \ \text{(no point approaches)}, \qquad
#   \lambda_i\,w_i = 0 \ \text{(a point pushes only while it stays in touch)}.$$
#
# The velocities are linear in the impulses: $\mathbf{w} = A\boldsymbol{\lambda} + \mathbf{b}$,
# with $\mathbf{b}$ the normal velocities without any impulse (after this step's gravity) and
# $A = J M^{-1} J^T$ (1/kg), the matrix that turns impulses into velocity changes. Its diagonal
# entries are the $k = 1/m_1 + 1/m_2 + (\mathbf{r}_1\times\hat{\mathbf{n}})^2/I_1 + \dots$ of the
# collision equation (lesson 07); its off-diagonal entries couple two points that share a
# body. Finding $\boldsymbol{\lambda}$ with $\boldsymbol{\lambda} \ge 0$, $\mathbf{w} \ge 0$,
# $\boldsymbol{\lambda}\cdot\mathbf{w} = 0$ is a linear complementarity problem.
#
# `sandbox/lcp.py` solves small ones exactly by trying every set of pushing points, and runs
# projected Gauss-Seidel, the iterative solver's sweep, on the same $A$ and $\mathbf{b}$.

# %%
import matplotlib.pyplot as plt
import numpy as np

from sandbox import Body, Box, Circle, World, lcp
from sandbox.lessonkit import output_dir, print_table, save_figure

# knobs
G, DT = 9.81, 1.0 / 60.0  # m/s^2, s
M_A, M_B = 1.0, 10.0  # kg: a light ball under a heavy one
DROP_SPEED = 2.0  # m/s, the upper ball arrives at this speed
SWEEPS = (1, 2, 5, 10, 20, 50, 100, 200)  # iterations per step of the iterative solver
RATIOS = (1.0, 10.0, 100.0)  # m_B / m_A, the convergence study

OUT = output_dir("17_simultaneous_contact_lcp")

# %% [markdown]
# ## Two balls, two contacts
#
# Ball A (radius 0.5 m, mass `M_A`) rests on the ground; ball B (mass `M_B`) lands on it at
# `DROP_SPEED`, no bounce ($e = 0$), no friction. Two contacts, both vertical: ground-A (normal
# up, it pushes A) and A-B (it pushes B up and A down). With $\hat{\mathbf{n}}$ up for both,
#
# $$A = \begin{bmatrix} 1/m_A & -1/m_A \\ -1/m_A & 1/m_A + 1/m_B \end{bmatrix}, \qquad
#   \mathbf{b} = \begin{bmatrix} -g\Delta t \\ -u \end{bmatrix}$$
#
# ($-1/m_A$: the A-B push moves A *down*, into the ground). Both points must push, and the exact
# answer is $A\boldsymbol{\lambda} = -\mathbf{b}$: $\lambda_1 = (m_A + m_B)g\Delta t + m_B u$,
# $\lambda_2 = m_B(u + g\Delta t)$: the ground stops both balls.
#
# The engine's iterative solver visits ground-A, then A-B, `iterations` times per step. Here
# with warm starting off (`warm_start=False`), so that one step shows the bare sweeps.


# %%
def stacked_balls(sweeps: int, m_b: float = M_B, speed: float = DROP_SPEED) -> World:
    """Ball A on the ground, ball B arriving on top of it; warm starting off."""
    world = World(gravity=(0.0, -G), dt=DT, iterations=sweeps)
    world.settings.warm_start = False
    ground = world.add_body(Body("ground", type="static"))
    ground.add_shape(Box(4.0, 1.0, offset=(0.0, -0.5), friction=0.0))
    a = world.add_body(Body("A", position=(0.0, 0.5)))
    a.add_shape(Circle(0.5, mass=M_A, friction=0.0))
    b = world.add_body(Body("B", position=(0.0, 1.5), velocity=(0.0, -speed)))
    b.add_shape(Circle(0.5, mass=m_b, friction=0.0))
    return world


def stack_lcp(m_b: float = M_B, speed: float = DROP_SPEED) -> tuple[np.ndarray, np.ndarray]:
    a = np.array([[1 / M_A, -1 / M_A], [-1 / M_A, 1 / M_A + 1 / m_b]])
    return a, np.array([-G * DT, -speed])


A, b = stack_lcp()
exact, active = lcp.solve_by_enumeration(A, b)
closed = np.array([(M_A + M_B) * G * DT + M_B * DROP_SPEED, M_B * (DROP_SPEED + G * DT)])
pgs = lcp.projected_gauss_seidel(A, b, max(SWEEPS))
rows, engine = [], {}
for n in SWEEPS:
    world = stacked_balls(n)
    world.step()
    engine[n] = world.manifolds.normal_impulse[:, 0].copy()  # ground-A, then A-B
    rows.append((n, *engine[n], *pgs[n], world.body("B").velocity[1],
                 float(np.abs(engine[n] - pgs[n]).max())))  # fmt: skip
print(f"A = {np.round(A, 4).tolist()} 1/kg, b = {np.round(b, 4).tolist()} m/s")
print(
    f"exact LCP: lambda = {np.round(exact, 6).tolist()} N s, pushing points {active}; "
    f"closed form {np.round(closed, 6).tolist()}"
)
print_table(["sweeps", "engine ground-A", "engine A-B", "PGS ground-A", "PGS A-B",
             "B's v_y after (m/s)", "|engine - PGS|"], rows, 6)  # fmt: skip

# %% [markdown]
# The engine's impulses are projected Gauss-Seidel's, sweep for sweep, and they creep towards
# the exact answer: after the default 10 sweeps they are only 58% and 61% of it, and B is still
# sinking at 0.83 m/s (the position pass and the next steps clean up). Why so slow? Solving
# ground-A pushes A up, then solving A-B pushes A back down into the ground, and so on: every
# sweep hands the heavy ball's weight one contact further and back. For a 2x2 problem each
# sweep multiplies the error by the Gauss-Seidel factor
#
# $$\rho = \frac{A_{12}A_{21}}{A_{11}A_{22}} = \frac{m_B}{m_A + m_B},$$
#
# 0.909 here: a heavy body on a light one is the worst case (the "mass ratio" problem of
# iterative solvers).

# %%
fig, (ax, bx) = plt.subplots(1, 2, figsize=(13, 5.4))
k_all = np.arange(len(pgs))
for i, (name, color) in enumerate((("ground-A", "C0"), ("A-B", "C1"))):
    ax.plot(k_all, pgs[:, i], color=color, lw=1.2, label=f"{name}: projected Gauss-Seidel")
    ax.plot(SWEEPS, [engine[n][i] for n in SWEEPS], "o", color=color, mfc="none", ms=8,
            label=f"{name}: engine, one step")  # fmt: skip
    ax.axhline(exact[i], color=color, ls=":", lw=1.5, label=f"{name}: exact LCP")
ax.set_xscale("symlog", linthresh=1.0)
ax.set(xlim=(0, 250), xlabel="sweeps per step (count)", ylabel="normal impulse (N s)",
       title=f"m_A = {M_A:g} kg under m_B = {M_B:g} kg")  # fmt: skip
ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=2)
rates = []
for j, ratio in enumerate(RATIOS):
    a_r, b_r = stack_lcp(m_b=ratio * M_A)
    exact_r, _ = lcp.solve_by_enumeration(a_r, b_r)
    err = np.abs(lcp.projected_gauss_seidel(a_r, b_r, 60) - exact_r).max(axis=1)
    rho = ratio / (1.0 + ratio)
    fit = float(np.exp(np.polyfit(np.arange(5, 25), np.log(err[5:25]), 1)[0]))
    rates.append((ratio, rho, fit))
    ok = err > 1e-14
    bx.semilogy(np.arange(61)[ok], err[ok] / exact_r.max(), color=f"C{j + 2}",
                label=f"m_B / m_A = {ratio:g}")  # fmt: skip
    bx.semilogy(np.arange(61), rho ** np.arange(61), color=f"C{j + 2}", ls=":", lw=1,
                label=f"rho^k, rho = {rho:.3f}")  # fmt: skip
bx.set(xlabel="sweeps (count)", ylabel="max |lambda - exact| / max lambda (1)", ylim=(1e-12, 2),
       title="convergence: the error shrinks by rho per sweep")  # fmt: skip
bx.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.0, 1.0))
for a_ in (ax, bx):
    a_.grid(alpha=0.3, which="both")
fig.tight_layout()
save_figure(fig, OUT / "lcp_vs_iterations.png", dpi=100)
print_table(["m_B / m_A", "rho = m_B / (m_A + m_B)", "measured factor per sweep"], rates, 4)

# %% [markdown]
# ## Two points of one contact: what the block solver does
#
# The two corners of a box on the ground are a 2x2 LCP too, with a strong coupling: both push
# the same body, and a push at one corner turns the box and moves the other. Which corners push
# is not known in advance. Here a 1 x 0.5 m box lands flat at 1 m/s while spinning
# anticlockwise at 3 rad/s: without impulses its left corner approaches at 2.66 m/s and its right
# corner *separates* at 0.34 m/s. The enumeration tries all four sets of pushing points:

# %%
world = World(gravity=(0.0, -G), dt=DT, iterations=1)
world.settings.warm_start = False
ground = world.add_body(Body("ground", type="static"))
ground.add_shape(Box(4.0, 1.0, offset=(0.0, -0.5), friction=0.0))
box = world.add_body(Body("box", position=(0.0, 0.25), velocity=(0.0, -1.0), angular_velocity=3.0))
box.add_shape(Box(1.0, 0.5, friction=0.0))
(contact,) = world.find_contacts()
n = np.asarray(contact.normal)
r = np.asarray(contact.points) - np.asarray(box.center_of_mass)  # arms of the two corners
rxn = r[:, 0] * n[1] - r[:, 1] * n[0]
A2 = 1.0 / box.mass + np.outer(rxn, rxn) / box.moment
v_free = np.asarray(box.velocity) + np.array([0.0, -G * DT])  # after this step's gravity
b2 = (v_free + box.angular_velocity * np.stack([-r[:, 1], r[:, 0]], axis=1)) @ n
rows = []
for active2 in ((), (0,), (1,), (0, 1)):
    lam2 = np.zeros(2)
    if active2:
        idx = list(active2)
        lam2[idx] = np.linalg.solve(A2[np.ix_(idx, idx)], -b2[idx])
    w2 = A2 @ lam2 + b2
    names = " and ".join("right" if i == 0 else "left" for i in active2) or "none"
    rows.append((names, *lam2, *w2, "yes" if lcp.is_solution(A2, b2, lam2) else "no"))
print(f"corners at x = {np.round(r[:, 0], 3).tolist()} m; b = {np.round(b2, 4).tolist()} m/s")
print_table(["pushing corners", "lambda right", "lambda left", "w right", "w left",
             "lambda >= 0, w >= 0, lambda w = 0"], rows, 5)  # fmt: skip
exact2, _ = lcp.solve_by_enumeration(A2, b2)
world.step()
print_table(
    ["impulses (N s)", "right corner", "left corner"],
    [("exact LCP", *exact2), ("engine, 1 iteration", *world.manifolds.normal_impulse[0]),
     ("projected Gauss-Seidel, 1 sweep", *lcp.projected_gauss_seidel(A2, b2, 1)[-1]),
     ("projected Gauss-Seidel, 3 sweeps", *lcp.projected_gauss_seidel(A2, b2, 3)[-1])],
    6,
)  # fmt: skip
pgs2 = lcp.projected_gauss_seidel(A2, b2, 8)
rho2 = A2[0, 1] * A2[1, 0] / (A2[0, 0] * A2[1, 1])
print(
    f"Gauss-Seidel, point by point: max error after 1..8 sweeps "
    f"{np.round(np.abs(pgs2[1:] - exact2).max(axis=1), 6).tolist()} N s (rho = {rho2:.3f})"
)

# %% [markdown]
# Only "both push" satisfies all three rules, although the right corner was separating: the
# push at the left corner turns the box clockwise and swings its right corner down into the
# ground. The engine gets it exactly in one iteration, because it solves the two points of a
# manifold together (Box2D's "block solver": exactly this enumeration for two points).
# Gauss-Seidel on the two points one at a time gets there too, the error shrinking by
# $\rho = A_{12}A_{21}/(A_{11}A_{22}) = 0.17$ per sweep, but after any finite number of sweeps
# the corner visited first has done more than its share: the asymmetry that makes pymunk's
# stack of lesson 14 lean. Between different contacts, as for the two balls, the engine sweeps,
# and warm starting carries each step's impulses into the next, so a resting stack converges
# over a few steps instead of within one:

# %%
world = stacked_balls(10, speed=0.0)  # B already resting on A: the impulses should hold both
world.settings.warm_start = True
a_rest, b_rest = stack_lcp(speed=0.0)
exact_rest, _ = lcp.solve_by_enumeration(a_rest, b_rest)
errors = []
for _ in range(40):
    world.step()
    errors.append(float(np.abs(world.manifolds.normal_impulse[:, 0] - exact_rest).max()))
errors = np.array(errors) / exact_rest.max()
print(f"resting stack, 10 sweeps per step, warm started: relative impulse error after step 1 "
      f"{errors[0]:.2e}, step 5 {errors[4]:.2e}, step 40 {errors[-1]:.2e}; within 1e-6 from step "
      f"{int(np.argmax(errors < 1e-6)) + 1}")  # fmt: skip

# %% [markdown]
# ## Exercises
#
# Predict first, then run the cell under the question, then open the answer.
#
# **1.** Make the two balls equally heavy ($m_B = m_A$). How many sweeps until the impulses are
# within 1% of the exact ones?

# %%
a_e1, b_e1 = stack_lcp(m_b=M_A)
exact_e1, _ = lcp.solve_by_enumeration(a_e1, b_e1)
err_e1 = np.abs(lcp.projected_gauss_seidel(a_e1, b_e1, 30) - exact_e1).max(axis=1) / exact_e1.max()
print(f"within 1% after {int(np.argmax(err_e1 < 0.01))} sweeps; errors {np.round(err_e1[:9], 4)}")

# %% [markdown]
# <details><summary>Answer</summary>
#
# $\rho = m_B/(m_A + m_B) = 0.5$: each sweep halves the error. The first sweep hardly counts
# (its ground-A visit only holds up A: the error is still 93%), then $0.93 \times 0.5^k < 0.01$
# needs $k = 7$ more: within 1% after 8 sweeps, as the run finds. With $m_B = 10\,m_A$
# ($\rho = 0.909$) it takes about 50.
#
# </details>
#
# **2.** Drop the box flat, without spin (`angular_velocity=0`). Which corners push, and how
# hard?

# %%
v_e2 = np.array([0.0, -1.0 - G * DT])
b_e2 = (v_e2 + 0.0 * r) @ n  # no spin: both corners approach at 1 + g dt
lam_e2, active_e2 = lcp.solve_by_enumeration(A2, b_e2)
print(f"pushing corners {active_e2}, impulses {np.round(lam_e2, 6).tolist()} N s, "
      f"m (1 + g dt) / 2 = {box.mass * (1.0 + G * DT) / 2:.6f}")  # fmt: skip

# %% [markdown]
# <details><summary>Answer</summary>
#
# By symmetry both corners push equally, and together they stop the box:
# $\lambda_1 = \lambda_2 = m(u + g\Delta t)/2 = 0.5 \times 1.1635/2 = 0.29088$ N s. No turn, so
# the $(\mathbf{r}\times\hat{\mathbf{n}})$ terms cancel.
#
# </details>
#
# **3.** In the two-ball stack, let B move *up* at 2 m/s (it is leaving). Which contacts push?

# %%
a_e3, b_e3 = stack_lcp(speed=-2.0)  # a negative arrival speed: B separates
lam_e3, active_e3 = lcp.solve_by_enumeration(a_e3, b_e3)
print(f"pushing contacts {active_e3}, impulses {np.round(lam_e3, 6).tolist()} N s")

# %% [markdown]
# <details><summary>Answer</summary>
#
# Only ground-A (contact 0): it holds up ball A alone, $\lambda_1 = m_A g\Delta t = 0.1635$ N s.
# A-B has $w_2 = 2$ m/s $> 0$ without any impulse, so complementarity forces $\lambda_2 = 0$:
# a separating contact does not pull.
#
# </details>
