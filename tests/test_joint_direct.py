"""The soft step's joints solved together (``joint_solver: "direct"``, sandbox.joints.direct):
one pass equals sweeps run until nothing changes, whatever order the joints are listed in; a
closed loop (a redundant row) stays solvable; and what it buys on the issue's chains."""

import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from sandbox import Body, Box, Circle, PinJoint, PivotJoint, World
from sandbox.joints.base import MAX_LINEAR_CORRECTION
from sandbox.joints.direct import solve_joints_direct
from sandbox.joints.positions_together import MAX_TURN, solve_joint_positions_together
from sandbox.joints.solve import solve_joint_positions, solve_joints_soft
from sandbox.solvers.soft import softness


def mixed_chain(order=None, **settings) -> World:
    """A hook, 6 light links and a ball of 50 link masses, released horizontally: pivots,
    except a 0.2 m rod (pin) between the 3rd and the 4th link; ``order`` lists the joints in
    another order."""
    w = World(gravity=(0, -9.81), solver="soft", **settings)
    prev = w.add_body(Body("hook", type="static", position=(0, 10)))
    joints, x = [], 0.0
    for i in range(6):
        gap = 0.2 if i == 3 else 0.0
        link = w.add_body(Body(f"link{i}", position=(x + gap + 0.25, 10)))
        link.add_shape(Box(0.5, 0.1, density=20.0))
        kind = PinJoint if gap else PivotJoint
        joints.append(kind(prev, link, (0, 0) if i == 0 else (0.25, 0), (-0.25, 0)))
        prev, x = link, x + gap + 0.5
    ball = w.add_body(Body("ball", position=(x + 0.25, 10)))
    ball.add_shape(Circle(0.25, mass=50.0))
    joints.append(PivotJoint(prev, ball, (0.25, 0), (-0.25, 0)))
    for i in order or range(len(joints)):
        w.add_joint(joints[i])
    return w


def passes(world: World, direct: bool, use_bias: bool, count: int):
    """A copy of the world's bodies and joints after ``count`` direct passes or sweeps."""
    arrays = world.arrays()
    bodies, joints = arrays.bodies.copy(), arrays.joints.copy()
    s = world.settings
    h = world.dt / s.substeps
    soft = softness(s.joint_hertz, s.joint_damping_ratio, h)
    for _ in range(count):
        if direct:
            solve_joints_direct(joints, bodies, soft, use_bias, 1.0 / h)
        else:
            solve_joints_soft(joints, bodies, soft, use_bias, 1.0 / h)
    return bodies, joints


@pytest.mark.parametrize("use_bias", [True, False])
def test_direct_passes_converge_to_where_sweeps_do(use_bias):
    # mid-swing (0.6 s), with stretched joints and warm impulses: the velocities and impulses
    # that 20,000 sweeps of the same soft joints converge to (soft solve, or rigid relax).
    # One direct pass lands within 2e-3 m/s of them (each row's arc correction reads the
    # angular velocities at the pass start; a sweep reads them as they change), where 10 sweeps
    # are still 5 to 10 times further off; four passes agree to 1e-7 of their size
    w = mixed_chain()
    for _ in range(36):
        w.step()
    swept, swept_joints = passes(w, False, use_bias, 20_000)
    scale = np.abs(swept["vel"]).max()
    one, _ = passes(w, True, use_bias, 1)
    ten, _ = passes(w, False, use_bias, 10)
    assert np.abs(one["vel"] - swept["vel"]).max() < 2e-3
    assert np.abs(ten["vel"] - swept["vel"]).max() > 5 * np.abs(one["vel"] - swept["vel"]).max()
    bodies, joints = passes(w, True, use_bias, 4)
    assert np.allclose(bodies["vel"], swept["vel"], rtol=0, atol=1e-7 * scale)
    assert np.allclose(bodies["omega"], swept["omega"], rtol=0, atol=1e-7 * scale)
    lam = np.abs(swept_joints["impulse"]).max()
    assert np.allclose(joints["impulse"], swept_joints["impulse"], rtol=0, atol=1e-7 * lam)


def ball_after(order, joint_solver: str) -> np.ndarray:
    """Where the ball is after 2 s, the position stage off (its passes are sweeps)."""
    w = mixed_chain(order, joint_solver=joint_solver, position_correction=False)
    for _ in range(120):
        w.step()
    return np.array(w.body("ball").position, dtype=float)


def test_the_order_of_the_joints_does_not_matter():
    # listed backwards or shuffled, the chain's joints move the ball the same to 1e-9 m over
    # 2 s (one solve: only rounding differs); swept, the order shapes the result (by 0.02 mm)
    orders = (None, [6, 5, 4, 3, 2, 1, 0], [3, 0, 6, 1, 5, 2, 4])
    direct = [ball_after(order, "direct") for order in orders]
    swept = [ball_after(order, "sweeps") for order in orders]
    for other in direct[1:]:
        assert np.abs(other - direct[0]).max() < 1e-9
    assert max(np.abs(other - swept[0]).max() for other in swept[1:]) > 1e-6


def test_closed_loops_stay_solvable():
    # a four-bar linkage (ground, crank, coupler, rocker: a loop of four pivots, one degree of
    # freedom left) swinging under gravity for 3 s, beside a bar hinged to the ground at both
    # ends (two pivots: four rows on three degrees of freedom, one row redundant, dropped in
    # the rigid relax pass): every velocity stays finite, every hinge holds within 2 mm and the
    # doubly hinged bar does not move (1 mm)
    w = World(gravity=(0, -9.81), solver="soft")
    ground = w.add_body(Body("ground", type="static"))
    crank = w.add_body(Body("crank", position=(0, 0.5)))
    crank.add_shape(Box(0.1, 1.0))
    coupler = w.add_body(Body("coupler", position=(1, 1)))
    coupler.add_shape(Box(2.0, 0.1))
    rocker = w.add_body(Body("rocker", position=(2, 0.5)))
    rocker.add_shape(Box(0.1, 1.0))
    w.add_joint(PivotJoint(ground, crank, (0, 0), (0, -0.5)))
    w.add_joint(PivotJoint(crank, coupler, (0, 0.5), (-1, 0)))
    w.add_joint(PivotJoint(coupler, rocker, (1, 0), (0, 0.5)))
    w.add_joint(PivotJoint(ground, rocker, (2, 0), (0, -0.5)))
    crank.angular_velocity = 1.0
    bar = w.add_body(Body("bar", position=(6, 1)))
    bar.add_shape(Box(2.0, 0.1))
    w.add_joint(PivotJoint(ground, bar, (5, 1), (-1, 0)))
    w.add_joint(PivotJoint(ground, bar, (7, 1), (1, 0)))
    worst = 0.0
    for _ in range(180):
        w.step()
        worst = max(worst, max(j.anchor_error() for j in w.joints))
        assert all(math.isfinite(b.angular_velocity) for b in w.bodies)
    assert worst < 0.002
    assert abs(bar.position[0] - 6) < 1e-3 and abs(bar.position[1] - 1) < 1e-3
    assert abs(crank.angle) > 0.1  # the linkage did move


def perturbed_chain(seed: int, spread: float):
    """The mixed chain after 30 steps, its moving bodies' centres shifted at random by about
    ``spread`` (m): (bodies, joints) copies."""
    w = mixed_chain()
    for _ in range(30):
        w.step()
    arrays = w.arrays()
    bodies, joints = arrays.bodies.copy(), arrays.joints.copy()
    bodies["com"][1:] += np.random.default_rng(seed).normal(0.0, spread, (len(bodies) - 1, 2))
    return bodies, joints


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_position_passes_together_close_the_joints_at_once(seed):
    # every hinge and the rod about 3 mm off: a pass solved together leaves only what the
    # linearisation misses (measured 0.04 to 0.07 % of the error, then 2e-11 m: its bodies
    # move rather than turn, and moving is linear), where a swept pass leaves most of it (41 %:
    # the ball is 50 link masses, each joint undoes the last)
    bodies, joints = perturbed_chain(seed, 0.003)
    swept_bodies = bodies.copy()
    errors = [solve_joint_positions_together(joints, bodies) for _ in range(3)]
    assert errors[0] > 0.002
    assert errors[1] < 1e-3 * errors[0]
    assert errors[2] < 1e-9
    solve_joint_positions(joints, swept_bodies)
    assert solve_joint_positions(joints, swept_bodies) > 0.1 * errors[0]


def test_position_passes_together_take_bounded_steps():
    # 20 cm off: the linear solve would turn light links by radians and move them decimetres;
    # the pass is scaled so that no body turns more than MAX_TURN or moves more than
    # MAX_LINEAR_CORRECTION (a joint far from closed is not closed in one jump through whatever
    # lies between), and the error still comes down pass by pass
    bodies, joints = perturbed_chain(4, 0.2)
    errors = []
    for _ in range(40):
        turned, placed = bodies["turn"].copy(), bodies["com"].copy()
        errors.append(solve_joint_positions_together(joints, bodies))
        assert np.abs(bodies["turn"] - turned).max() <= MAX_TURN * (1 + 1e-12)
        moved = np.hypot(*(bodies["com"] - placed).T).max()
        assert moved <= MAX_LINEAR_CORRECTION * (1 + 1e-12)
    assert errors[-1] < 1e-3 * errors[0]


def test_hanging_discs_hold_the_static_error_of_each_joint():
    # 400 kg under 1 kg under a hook, position correction off: each joint's spring settles at
    # F / (m_eff omega^2) as when swept (the fixed point sweeps converge to), within 1%
    w = World(gravity=(0, -9.81), solver="soft", position_correction=False)
    hook = w.add_body(Body("hook", type="static", position=(0, 10)))
    light = w.add_body(Body("light", position=(0, 9)))
    light.add_shape(Circle(0.2, mass=1.0))
    heavy = w.add_body(Body("heavy", position=(0, 8)))
    heavy.add_shape(Circle(0.3, mass=400.0))
    w.add_joint(PivotJoint(hook, light, (0, -1), (0, 0)))
    w.add_joint(PivotJoint(light, heavy, (0, -1), (0, 0)))
    for _ in range(600):
        w.step()
    k = (2 * math.pi * w.settings.joint_hertz) ** 2
    expected = (401 * 9.81 / (1.0 * k), 400 * 9.81 * (1 / 1.0 + 1 / 400) / k)
    measured = [j.anchor_error() for j in w.joints]
    assert measured == pytest.approx(expected, rel=0.01)


def test_plain_python_solves_the_joints_as_the_compiled_code_does(tmp_path):
    # the same functions uncompiled (SANDBOX_JIT=0): the chain's bodies after 30 steps agree
    # with the compiled run to 1e-12 m (measured: bit for bit)
    script = (
        "import sys, json; sys.path.insert(0, 'tests')\n"
        "from test_joint_direct import mixed_chain\n"
        "w = mixed_chain()\n"
        "for _ in range(30): w.step()\n"
        "print(json.dumps([list(b.position) for b in w.bodies]))\n"
    )
    root = Path(__file__).resolve().parent.parent
    env = {**os.environ, "SANDBOX_JIT": "0"}
    done = subprocess.run(
        [sys.executable, "-c", script], cwd=root, env=env, capture_output=True, text=True
    )
    assert done.returncode == 0, done.stderr
    w = mixed_chain()
    for _ in range(30):
        w.step()
    plain = np.array(json.loads(done.stdout))
    assert np.abs(plain - np.array([list(b.position) for b in w.bodies])).max() < 1e-12


def hinge_net(n: int, **settings) -> World:
    """An n x n net of 1.6 kg squares 0.5 m apart, each hinged to its right and lower
    neighbours, hung by its top corners from a static hook: loops everywhere, many rows more
    than the bodies have degrees of freedom."""
    w = World(gravity=(0, -9.81), solver="soft", **settings)
    hook = w.add_body(Body("hook", type="static", position=(0, 10)))
    grid = {}
    for i in range(n):
        for j in range(n):
            grid[i, j] = w.add_body(Body(f"b{i}_{j}", position=(i * 0.5, 10 - j * 0.5)))
            grid[i, j].add_shape(Box(0.2, 0.2, density=40.0))
    for i in range(n):
        for j in range(n):
            if i + 1 < n:
                w.add_joint(PivotJoint(grid[i, j], grid[i + 1, j], (0.25, 0), (-0.25, 0)))
            if j + 1 < n:
                w.add_joint(PivotJoint(grid[i, j], grid[i, j + 1], (0, -0.25), (0, 0.25)))
    w.add_joint(PivotJoint(hook, grid[0, 0]))
    w.add_joint(PivotJoint(hook, grid[n - 1, 0], ((n - 1) * 0.5, 0), (0, 0)))
    return w


def test_a_net_of_hinges_holds_solved_together_and_auto_sweeps_it():
    # a 10 x 10 net (180 pivots) falling into its hook for 2 s: solved together it holds every
    # hinge within 1 cm (measured 6.6 mm; swept 7.2 mm), its relax pass swept because the
    # hinges close loops (solved together there, it blew up within 6 steps); auto finds the
    # net too wide to factorise cheaply and sweeps it: the very same motion as sweeps
    worst = {}
    for how in ("direct", "sweeps", "auto"):
        w = hinge_net(10, joint_solver=how)
        worst[how] = 0.0
        for _ in range(120):
            w.step()
            worst[how] = max(worst[how], max(j.anchor_error() for j in w.joints))
        worst[how, "ball"] = np.array(w.body("b9_9").position, dtype=float)
    assert worst["direct"] < 0.01
    assert worst["auto"] == worst["sweeps"]
    assert np.array_equal(worst["auto", "ball"], worst["sweeps", "ball"])


def test_auto_solves_a_chain_together():
    # the heavy chain of the issue under auto (the default) and under direct: the same motion
    w_auto, w_direct = mixed_chain(), mixed_chain(joint_solver="direct")
    assert w_auto.settings.joint_solver == "auto"
    for _ in range(60):
        w_auto.step()
        w_direct.step()
    assert np.array_equal(
        np.array([list(b.position) for b in w_auto.bodies]),
        np.array([list(b.position) for b in w_direct.bodies]),
    )
