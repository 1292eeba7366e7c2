"""The soft step (``solver: soft``, sandbox.solvers.soft) against closed forms and the bounds of
its design: a tall pyramid that does not sag, a long chain that does not stretch, bounces,
momentum, joints with limits and a motor, and the one-call path against the staged one."""

import math
import sys
from pathlib import Path

import numpy as np
import pytest
from step_paths import fast_and_staged, same_state

from sandbox import Body, Box, Circle, World, load_scene
from sandbox.build import build_world
from sandbox.bundled import scenes_folder
from sandbox.joints import PivotJoint
from sandbox.scene import validate_scene
from sandbox.solvers.soft import (
    MAX_CONTACT_HERTZ_PER_RATE,
    STATIC_STIFFNESS,
    load_sag,
    softness,
)

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
import scenes  # noqa: E402  (benchmarks/scenes.py: the benchmark scenes as scene dicts)


def test_softness_is_the_implicit_mass_spring_damper():
    # omega = 2 pi f; a1 = 2 zeta + h omega; bias_rate = omega / a1, mass_scale = a2 / (1 + a2),
    # impulse_scale = 1 / (1 + a2) with a2 = h omega a1 (hand computed, 1e-12); 0 Hz is rigid
    f, zeta, h = 30.0, 10.0, 1.0 / 240.0
    omega = 2 * math.pi * f
    a1 = 2 * zeta + h * omega
    a2 = h * omega * a1
    assert softness(f, zeta, h) == pytest.approx((omega / a1, a2 / (1 + a2), 1 / (1 + a2)), 1e-12)
    assert softness(0.0, zeta, h) == (0.0, 1.0, 0.0)


def pyramid_run(seconds: float = 10.0, **settings) -> dict:
    """The pyramid of base 40 (820 boxes) under the soft step: the top box's drop at every
    step (m), how far it moved sideways (m) and the largest turn of any box (deg)."""
    spec = validate_scene(scenes.pyramid(40))
    spec["settings"].update(solver="soft", **settings)
    world = build_world(spec)
    top = max(world.bodies, key=lambda b: b.position[1])
    (x0, y0), drops = top.position, []
    for _ in range(round(seconds / spec["dt"])):
        world.step()
        drops.append(y0 - top.position[1])
    turned = max(abs(b.angle) for b in world.bodies if b.type == "dynamic")
    sideways = top.position[0] - x0
    return {"drop": np.array(drops), "sideways": sideways, "turned": math.degrees(turned)}


def resting_points(**settings) -> np.ndarray:
    """The contact points of a 1 m box of 1 kg resting on the ground for 3 s under the soft
    step: (separation, held sag, the sag its load explains: load_sag) of each (m)."""
    w = World(gravity=(0, -9.81), solver="soft", **settings)
    w.add_body(Body("ground", type="static")).add_shape(Box(10.0, 1.0))
    w.add_body(Body("box", position=(0.3, 1.0))).add_shape(Box(1.0, 1.0, mass=1.0))
    for _ in range(180):
        w.step()
    a = w.arrays()
    ctx = a.context[0]
    c = a.buffers.sets[ctx["contact_set"]][0]
    return np.array(
        [(p["separation"], p["held_sag"], load_sag(c, p)) for p in c["points"][: c["count"]]]
    )


def test_sag_recovery_takes_back_the_static_error():
    # without it the spring rests where it carries the load, the static error
    # s = -lambda / (m_eff h omega^2) (load_sag): by hand, each of the two corners carries
    # m g / 2 on m_p = (1/m + (r x n)^2 / I)^-1 = (1 + 0.25 * 6)^-1 = 0.4 kg, against the static
    # ground at twice the capped 30 Hz, C = (g / 2) / (m_p (2 pi 60)^2) = 86.3 um; with it the
    # point holds that sag and its overlap decays as e^(-t / T), T = 1 s: after 3 s, e^-3 of it
    # (measured 0.89 of that: the box lands a few steps in), and what the overlap lost the held
    # sag gained
    hertz = STATIC_STIFFNESS * MAX_CONTACT_HERTZ_PER_RATE * 4 * 60  # the cap at 4 substeps
    by_hand = (9.81 / 2) / (0.4 * (2 * math.pi * hertz) ** 2)
    off = resting_points(sag_recovery_time=0.0)
    assert np.all(off[:, 1] == 0.0)
    assert np.allclose(off[:, 0], -off[:, 2], rtol=0.01)
    assert np.allclose(off[:, 2], by_hand, rtol=0.01)
    sag = off[:, 2]
    assert np.all(sag > 5e-5)
    on = resting_points()
    assert np.all(on[:, 0] < 0.0)
    assert np.all(-on[:, 0] < 1.2 * math.exp(-3.0) * sag)
    assert np.all(-on[:, 0] > 0.5 * math.exp(-3.0) * sag)
    assert np.allclose(on[:, 1] - on[:, 0], on[:, 2], rtol=0.01)  # held - s = the sag


def test_pyramid_of_base_40_holds_at_the_defaults():
    # the issue's bounds, at every step of the last 5 s (not only the last one): the contacts'
    # sag recovery (sag_recovery_time 1 s) takes back the 122 mm the 40 rows' static errors add
    # up to (measured 8.85 mm at worst, 6.65 mm at 10 s); the pile stays where it stood
    # (measured 0.8 mm sideways, 0.07 degrees)
    run = pyramid_run()
    assert np.abs(run["drop"][300:]).max() < 0.01
    assert run["turned"] < 1.0
    assert abs(run["sideways"]) < 0.01


def test_a_column_of_ten_boxes_rests_with_its_sag_taken_back():
    # the bundled stack (ten 1 m boxes on the ground) under the soft step at the defaults, 30 s:
    # the held sag is one number per contact, so it does not answer a tilt; held point by point
    # the column rocked further at every swing (its top box 0.5 m to either side within 25 s).
    # Over the last 20 s the top box stays within 1 mm of where it started, sideways and down
    # (measured 0.015 mm), and at 30 s nothing moves faster than 1 mm/s (measured 7e-8 m/s)
    world = load_scene(str(scenes_folder() / "stack.json"))
    world.settings.solver = "soft"
    top = world.bodies[-1]
    (x0, y0), worst = top.position, 0.0
    for step in range(1800):
        world.step()
        if step >= 600:
            worst = max(worst, abs(top.position[0] - x0), abs(top.position[1] - y0))
    assert worst < 1e-3
    assert max(np.hypot(*b.velocity) for b in world.bodies) < 1e-3


def test_pyramid_of_base_40_holds_when_every_load_is_held():
    # hold_ratio 0.5: every box holds still the boxes it rests on (shock propagation), each
    # contact carries one box on one box's effective mass, and the rows do not add up their
    # sags: the bounds, at every step of the last 5 s (measured 1.04 mm, 0.00 degrees)
    run = pyramid_run(hold_ratio=0.5)
    assert np.abs(run["drop"][300:]).max() < 0.01
    assert run["turned"] < 1.0


def test_pyramid_of_base_40_rests_without_sag_recovery():
    # Box2D's soft step (sag_recovery_time 0): with contacts capped at an eighth of the
    # substep rate (30 Hz at 4 substeps) the pyramid rests, its sag the static errors of 40
    # rows added up: over the last 5 s the top box stays within 1 mm of where it is, 13 cm
    # down at most (measured 122 mm; iterative 178 mm, Box2D v3.1 116 mm), within 6 cm of
    # where it started sideways (measured 43 mm; Box2D 1 mm), and no box turns 1 degree. With
    # the cap at a quarter (60 Hz) it rang forever: -15..69 mm, 1.3 m sideways
    run = pyramid_run(sag_recovery_time=0.0)
    late = run["drop"][300:]
    assert late.max() - late.min() < 0.001
    assert 0.09 < late.max() < 0.13  # the sag g / omega^2 per load explains (the lesson)
    assert abs(run["sideways"]) < 0.06
    assert run["turned"] < 1.0


def test_pyramid_of_base_40_rests_with_8_substeps():
    # without sag recovery, 8 substeps let contacts reach 60 Hz (an eighth of 480 Hz): the
    # pyramid is at rest within a second. Over the last 5 s the top box stays within 1 mm of
    # where it is, 35 mm down at most (measured 30 mm: the static errors of 40 rows of soft
    # contacts added up, a quarter of 4 substeps'; iterative 130 mm, pymunk 189 mm), within
    # 5 cm of where it started sideways, and no box turns 1 degree
    run = pyramid_run(substeps=8, sag_recovery_time=0.0)
    late = run["drop"][300:]
    assert late.max() - late.min() < 0.001
    assert late.max() < 0.035
    assert abs(run["sideways"]) < 0.05
    assert run["turned"] < 1.0


def chain(links: int = 20, ball: float = 0.0, **settings) -> World:
    """Boxes 0.5 m x 0.1 m of 1 kg hinged end to end from a static hook, horizontal at rest;
    ``ball`` > 0 hangs a disc of that many link masses at the free end."""
    w = World(gravity=(0, -9.81), solver="soft", **settings)
    prev = w.add_body(Body("hook", type="static", position=(0, 10)))
    for i in range(links):
        link = w.add_body(Body(f"link{i}", position=((i + 0.5) * 0.5, 10)))
        link.add_shape(Box(0.5, 0.1, density=20.0))
        w.add_joint(PivotJoint(prev, link, (0, 0) if i == 0 else (0.25, 0), (-0.25, 0)))
        prev = link
    if ball:
        disc = w.add_body(Body("ball", position=((links + 0.5) * 0.5, 10)))
        disc.add_shape(Circle(0.25, mass=ball * prev.mass))
        w.add_joint(PivotJoint(prev, disc, (0.25, 0), (-0.25, 0)))
    return w


def worst_stretch(world: World, steps: int = 600) -> float:
    worst = 0.0
    for _ in range(steps):
        world.step()
        worst = max(worst, max(j.anchor_error() for j in world.joints))
    return worst


def test_long_chain_does_not_stretch():
    # 20 links released horizontally, 10 s: every hinge within 5 mm (the bound) at the
    # defaults (4 substeps, joints at 120 Hz, damping ratio 5, solved together in the passes
    # and the position stage; measured 0.04 mm), at Box2D's 60 Hz (0.04 mm) and with 8
    # substeps and damping ratio 2. Swept one at a time instead, the same joints hold 3.9 mm at
    # 120 Hz but 10.3 mm at 60 Hz: why the default stiffness is not Box2D's
    assert worst_stretch(chain()) < 0.005
    assert worst_stretch(chain(joint_hertz=60.0)) < 0.005
    assert worst_stretch(chain(substeps=8, joint_hertz=120.0, joint_damping_ratio=2.0)) < 0.005
    assert worst_stretch(chain(joint_solver="sweeps")) < 0.005
    assert worst_stretch(chain(joint_solver="sweeps", joint_hertz=60.0)) > 0.008


def test_heavy_ball_on_a_chain_stays_on():
    # a ball of 100 link masses on 10 links: the iterative solver lets the chain come apart
    # (tens of metres); the soft step keeps every hinge within 2 mm from 50 to 200 link masses
    # (the issue asks for 1 cm at 100; measured at most 0.4 mm). Its joints are solved
    # together in the velocity passes and in the position stage
    # (sandbox.joints.positions_together), where the bodies move rather
    # than turn. With the position passes swept one joint at a time the worst stretch came when
    # the chain snapped taut behind the swinging ball, chaotic in the ball's mass (7.8 mm at
    # 100, 12.2 and 14.9 mm at 101 and 102); solved together with turning weighed as the
    # moments of inertia say, 5.6 and 10.2 mm at 90 and 95. Swept in the velocity passes too,
    # the light links pass the ball's pull on so slowly that the chain stretches 17.5 mm
    # (47 mm at 60 Hz)
    for ball in (50.0, 90.0, 95.0, 100.0, 103.0, 200.0):
        assert worst_stretch(chain(10, ball=ball)) < 0.002, ball
    assert worst_stretch(chain(10, ball=100.0, joint_solver="sweeps")) > 0.015
    assert worst_stretch(chain(10, ball=100.0, joint_solver="sweeps", joint_hertz=60.0)) > 0.035


def test_bounce_apex_is_e_squared_h():
    # a ball (e = 0.5) dropped from 2 m above the ground bounces to e^2 h = 0.5 m, within 3%
    w = World(gravity=(0, -9.81), solver="soft")
    w.add_body(Body("ground", type="static", position=(0, -0.5))).add_shape(
        Box(20, 1, restitution=1)
    )
    ball = w.add_body(Body("ball", position=(0, 2.5)))
    ball.add_shape(Circle(0.5, restitution=0.5))
    heights, bounced = [], False
    for _ in range(150):
        vy = ball.velocity[1]
        w.step()
        bounced = bounced or (vy < 0 <= ball.velocity[1])
        if bounced:
            heights.append(ball.position[1] - 0.5)
    assert max(heights) == pytest.approx(0.25 * 2.0, rel=0.03)


def test_box2d_hello_world_rests_at_one():
    # Box2D's HelloWorld: a 2 m box from y = 4 onto the ground (top at y = 0), gravity 10:
    # after 90 steps it rests at y = 1 +- 0.01, level
    w = World(gravity=(0, -10), solver="soft")
    w.add_body(Body("ground", type="static", position=(0, -10))).add_shape(Box(100, 20))
    box = w.add_body(Body("box", position=(0, 4)))
    box.add_shape(Box(2, 2, friction=0.6))
    for _ in range(90):
        w.step()
    assert box.position[1] == pytest.approx(1.0, abs=0.01)
    assert abs(box.angle) < 1e-3


def test_momentum_is_conserved_in_a_free_collision():
    # two discs meet head on, no gravity: total momentum unchanged to 1e-12 relative
    w = World(gravity=(0, 0), solver="soft")
    a = w.add_body(Body("a", position=(-1, 0), velocity=(3, 0.2)))
    a.add_shape(Circle(0.5, restitution=0.7))
    b = w.add_body(Body("b", position=(1, 0.3), velocity=(-2, 0)))
    b.add_shape(Circle(0.4, density=2.5, restitution=0.7))
    p0 = w.momentum()
    touched = 0
    for _ in range(60):
        w.step()
        touched += w.stats["contacts"]
    assert touched > 0
    assert np.allclose(w.momentum(), p0, rtol=0, atol=1e-12 * np.abs(p0).max())


def test_motor_and_limits_under_the_soft_step():
    # a motor drives a free wheel to its rate (2 rad/s within 1e-6 after 1 s of small torque
    # limit 50 N m); a hinged rod hanging against its limits stays within half a degree
    w = World(gravity=(0, -9.81), solver="soft")
    axle = w.add_body(Body("axle", type="static", position=(0, 5)))
    wheel = w.add_body(Body("wheel", position=(0, 5)))
    wheel.add_shape(Circle(0.5))
    w.add_joint(PivotJoint(axle, wheel, motor={"rate": 2.0, "max_torque": 50.0}))
    frame = w.add_body(Body("frame", type="static", position=(3, 5)))
    rod = w.add_body(Body("rod", position=(4, 5)))
    rod.add_shape(Box(2, 0.1))
    hinge = w.add_joint(PivotJoint(frame, rod, (0, 0), (-1, 0), limits=(-0.5, 0.5)))
    lowest = 0.0
    for _ in range(60):
        w.step()
        lowest = min(lowest, hinge.relative_angle())
    assert wheel.angular_velocity == pytest.approx(2.0, abs=1e-6)
    assert lowest > -0.5 - math.radians(0.5)


def test_one_call_soft_step_equals_the_staged_one():
    # the same stage functions either way: bit-identical after 120 steps of a falling pile
    def pile():
        w = World(gravity=(0, -9.81), solver="soft")
        w.add_body(Body("floor", type="static", position=(0, -0.5))).add_shape(Box(12, 1))
        for i in range(12):
            b = w.add_body(Body(f"b{i}", position=(-2 + 0.45 * i, 0.6 + 0.7 * (i % 3))))
            b.add_shape(Box(0.5, 0.4) if i % 2 else Circle(0.25))
        return w

    fast, staged = fast_and_staged(pile, 120)
    assert fast._fast and staged.timer.steps == 120
    assert same_state(fast, staged)


def test_each_pass_visits_every_contact_once_moving_pairs_first():
    # soft_order: a permutation of the step's contacts, those between moving bodies before
    # those with a body that cannot move (the ground has the last word in each pass)
    from sandbox.solvers.soft import soft_order

    world = build_world(validate_scene(scenes.pyramid(10)))
    world.settings.solver = "soft"
    for _ in range(30):
        world.step()
    arrays = world.arrays()
    ctx = arrays.context[0]
    contacts, k = arrays.buffers.sets[ctx["contact_set"]], ctx["contacts"]
    order = soft_order(contacts, k)
    assert sorted(order) == list(range(k))
    fixed = [contacts[i]["inv_mass_a"] == 0.0 or contacts[i]["inv_mass_b"] == 0.0 for i in order]
    assert 0 < sum(fixed) < k and fixed == sorted(fixed)  # all the moving pairs, then the rest
    assert list(order[: k - sum(fixed)]) != sorted(order[: k - sum(fixed)])  # interleaved
