"""Joints against theory and pymunk: pendulum period, chain drift, motor rate, angle limits,
scene loading, and which body pairs must not collide."""

import math

import numpy as np
import pytest

from sandbox import Body, Box, Circle, World
from sandbox.build import build_world
from sandbox.joints import (
    PinJoint,
    PivotJoint,
    SpringJoint,
    joined_pairs,
    joint_from_dict,
)
from sandbox.narrowphase import joined
from sandbox.pymunk_bridge import run_pymunk
from sandbox.scene import validate_scene

G = 9.81


def elliptic_k(k: float) -> float:
    """Complete elliptic integral of the first kind K(k) by the arithmetic-geometric mean."""
    a, b = 1.0, math.sqrt(1.0 - k * k)
    while abs(a - b) > 1e-15:
        a, b = 0.5 * (a + b), math.sqrt(a * b)
    return math.pi / (2.0 * a)


def exact_period(length: float, amplitude: float) -> float:
    """T = 4 sqrt(L/g) K(sin(theta0 / 2)): the pendulum at any amplitude."""
    return 4.0 * math.sqrt(length / G) * elliptic_k(math.sin(0.5 * amplitude))


def mean_period(t, x) -> float:
    """Mean time between upward zero crossings of x(t), linearly interpolated."""
    t, x = np.asarray(t), np.asarray(x)
    k = np.flatnonzero((x[:-1] < 0.0) & (x[1:] >= 0.0))
    crossings = t[k] - x[k] * (t[k + 1] - t[k]) / (x[k + 1] - x[k])
    assert len(crossings) >= 3
    return float(np.mean(np.diff(crossings)))


def pendulum_scene(length: float = 2.0, degrees: float = 5.0) -> dict:
    th = math.radians(degrees)
    return {
        "name": "pendulum",
        "bodies": [
            {"name": "anchor", "type": "static", "position": [0.0, 5.0],
             "shapes": [{"type": "circle", "radius": 0.05}]},
            {"name": "bob", "position": [length * math.sin(th), 5.0 - length * math.cos(th)],
             "shapes": [{"type": "circle", "radius": 0.2}]},
        ],
        "joints": [{"type": "pin", "a": "anchor", "b": "bob"}],
    }  # fmt: skip


def run(world: World, seconds: float, probe):
    t, values = [], []
    for _ in range(int(round(seconds / world.dt))):
        world.step()
        t.append(world.time)
        values.append(probe(world))
    return np.array(t), np.array(values)


# --- pendulum ------------------------------------------------------------------------------------
def test_pendulum_period_matches_theory_at_small_amplitude():
    world = build_world(validate_scene(pendulum_scene(2.0, 5.0)))
    t, x = run(world, 12.0, lambda w: w.body("bob").position[0])
    period = mean_period(t, x)
    # 1%: the small-angle 2 pi sqrt(L/g) (5 degrees is 0.05% above it) and the exact form
    assert period == pytest.approx(2 * math.pi * math.sqrt(2.0 / G), rel=0.01)
    assert period == pytest.approx(exact_period(2.0, math.radians(5.0)), rel=0.01)
    assert world.joints[0].anchor_error() < 1e-6  # a lone pin holds to the micrometre


def test_large_amplitude_pendulum_is_slower_as_the_elliptic_integral_says():
    world = build_world(validate_scene(pendulum_scene(2.0, 60.0)))
    t, x = run(world, 12.0, lambda w: w.body("bob").position[0])
    # 1%: at 60 degrees the exact period is 7.3% longer than 2 pi sqrt(L/g)
    assert mean_period(t, x) == pytest.approx(exact_period(2.0, math.radians(60.0)), rel=0.01)


def test_pendulum_period_agrees_with_pymunk():
    spec = validate_scene(pendulum_scene(2.0, 30.0))
    world = build_world(spec)
    t, x = run(world, 12.0, lambda w: w.body("bob").position[0])
    rows = [r for r in run_pymunk(spec, len(t)) if r[2] == "bob" and r[0] > 0]
    t_pm = [r[1] for r in rows]
    x_pm = [r[3] for r in rows]
    assert mean_period(t, x) == pytest.approx(mean_period(t_pm, x_pm), rel=0.01)  # 1%


# --- chain ---------------------------------------------------------------------------------------
def chain_world(links: int = 20, length: float = 0.5, angle: float = -math.pi / 4) -> World:
    """Boxes 0.4 x 0.1 m hinged end to end every ``length`` m, hanging from a static anchor,
    released straight at ``angle`` (rad from the horizontal)."""
    world = World()
    anchor = world.add_body(Body("anchor", type="static", position=(0.0, 10.0)))
    prev, c, s = anchor, math.cos(angle), math.sin(angle)
    for i in range(links):
        r = (i + 0.5) * length
        link = world.add_body(Body(f"link{i}", position=(r * c, 10.0 + r * s), angle=angle))
        link.add_shape(Box(0.8 * length, 0.1))
        joint_a = (0.0, 0.0) if i == 0 else (0.5 * length, 0.0)
        world.add_joint(PivotJoint(prev, link, joint_a, (-0.5 * length, 0.0)))
        prev = link
    return world


def test_chain_of_twenty_links_drifts_less_than_a_centimetre_in_ten_seconds():
    world = chain_world()
    worst = 0.0
    for _ in range(600):
        world.step()
        worst = max(worst, max(j.anchor_error() for j in world.joints))
    assert worst < 0.01  # m, anchor separation, any joint, any step
    assert world.body("link19").position[1] < 10.0  # and it did swing down


# --- motor and limits ----------------------------------------------------------------------------
def wheel_world(rate: float = 2.0, max_torque: float = 10.0):
    world = World()
    axle = world.add_body(Body("axle", type="static", position=(0.0, 2.0)))
    wheel = world.add_body(Body("wheel", position=(0.0, 2.0)))
    wheel.add_shape(Circle(1.0))
    joint = world.add_joint(PivotJoint(axle, wheel, motor={"rate": rate, "max_torque": max_torque}))
    return world, wheel, joint


def test_motor_spins_up_at_its_torque_bound_then_holds_its_rate():
    world, wheel, joint = wheel_world(2.0, 10.0)
    world.step()
    alpha = 10.0 / wheel.moment  # tau = I alpha, with tau at its bound
    assert wheel.angular_velocity == pytest.approx(alpha * world.dt, rel=1e-9)
    assert joint.motor_torque == pytest.approx(10.0, rel=1e-9)
    for _ in range(179):
        world.step()
    assert wheel.angular_velocity == pytest.approx(2.0, rel=0.01)  # 1%
    assert joint.anchor_error() < 1e-9
    # turned alpha t1^2 / 2 + rate (T - t1), t1 = rate / alpha: past pi, without wrapping
    t1 = 2.0 / alpha
    assert joint.relative_angle() == pytest.approx(alpha * t1**2 / 2 + 2.0 * (3.0 - t1), abs=0.05)


def test_motor_against_a_heavy_load_stalls_at_its_bound():
    world = World(gravity=(0.0, -9.81))
    axle = world.add_body(Body("axle", type="static", position=(0.0, 0.0)))
    arm = world.add_body(Body("arm", position=(1.0, 0.0)))
    arm.add_shape(Box(2.0, 0.1, density=10.0))  # weight 19.62 N at 1 m: 19.6 N m
    world.add_joint(PivotJoint(axle, arm, (0, 0), (-1.0, 0.0), motor={"rate": 1, "max_torque": 5}))
    for _ in range(30):
        world.step()
    assert arm.angular_velocity < 0.0  # 5 N m cannot lift 19.6 N m: it falls, slowed


def limited_rod(limits):
    world = World()
    frame = world.add_body(Body("frame", type="static", position=(0.0, 0.0)))
    rod = world.add_body(Body("rod", position=(1.0, 0.0)))
    rod.add_shape(Box(2.0, 0.1))
    joint = world.add_joint(PivotJoint(frame, rod, (0.0, 0.0), (-1.0, 0.0), limits=limits))
    return world, rod, joint


def test_angle_limits_hold_against_gravity():
    world, rod, joint = limited_rod((-0.5, 0.3))
    theta = []
    for _ in range(180):
        world.step()
        theta.append(joint.relative_angle())
    assert min(theta) > -0.5 - 0.02  # rad
    assert theta[-1] == pytest.approx(-0.5, abs=0.02)  # resting on the lower stop
    assert joint.anchor_error() < 0.005


def test_angle_limits_hold_a_fast_swing_at_both_stops():
    world, rod, joint = limited_rod((-0.4, 0.4))
    world.gravity[:] = 0.0
    rod.angular_velocity = 6.0  # rad/s at the stops
    theta = []
    for _ in range(120):
        world.step()
        theta.append(joint.relative_angle())
        if abs(rod.angular_velocity) < 0.5:  # a perfectly inelastic stop: kick it back
            rod.angular_velocity = -6.0 if theta[-1] > 0 else 6.0
    assert max(theta) < 0.4 + 0.02 and min(theta) > -0.4 - 0.02  # rad
    assert max(theta) > 0.38 and min(theta) < -0.38  # it reached both


def test_limit_and_motor_relative_angle_is_angle_b_minus_angle_a():
    world = World(gravity=(0.0, 0.0))
    a = world.add_body(Body("a", position=(0, 0), angle=0.3))
    a.add_shape(Box(1, 1))
    b = world.add_body(Body("b", position=(0, 0), angle=1.0))
    b.add_shape(Box(1, 1))
    joint = world.add_joint(PivotJoint(a, b, limits=(0.0, 0.5)))
    assert joint.relative_angle() == pytest.approx(0.7, abs=1e-12)
    for _ in range(30):
        world.step()
    assert b.angle - a.angle == pytest.approx(0.5, abs=0.02)  # pushed back inside, like pymunk


# --- building and loading ------------------------------------------------------------------------
SCENE = {
    "bodies": [
        {"name": "ground", "type": "static", "shapes": [{"type": "box", "width": 1, "height": 1}]},
        {"name": "p", "position": [2, 0], "shapes": [{"type": "circle", "radius": 0.2}]},
        {"name": "q", "position": [4, 0], "shapes": [{"type": "circle", "radius": 0.2}]},
        {"name": "r", "position": [6, 0], "shapes": [{"type": "circle", "radius": 0.2}]},
    ],
    "joints": [
        {"type": "pin", "a": "ground", "b": "p", "anchor_a": [0.5, 0]},
        {"type": "pivot", "a": "p", "b": "q", "anchor_a": [1, 0], "anchor_b": [-1, 0],
         "limits": [-0.5, 0.5], "motor": {"rate": 1.0, "max_torque": 3.0}},
        {"type": "spring", "a": "q", "b": "r", "stiffness": 10.0, "damping": 0.5},
    ],
}  # fmt: skip


def test_every_joint_loads_from_a_scene_and_writes_back_the_same():
    spec = validate_scene(SCENE)
    world = build_world(spec)
    pin, pivot, spring = world.joints
    assert isinstance(pin, PinJoint) and pin.distance == pytest.approx(1.5)
    assert isinstance(pivot, PivotJoint) and pivot.limits == (-0.5, 0.5)
    assert pivot.motor == {"rate": 1.0, "max_torque": 3.0}
    assert isinstance(spring, SpringJoint) and spring.rest_length == pytest.approx(2.0)
    written = [j.to_dict() for j in world.joints]
    expected = [dict(j) for j in spec["joints"]]
    expected[2]["rest_length"] = 2.0  # null in the file: the initial distance, now explicit
    assert written == expected
    assert validate_scene(world.to_scene())["joints"] == expected
    for _ in range(10):
        world.step()  # and it runs


def test_joints_built_in_python_match_the_scene_ones():
    world = build_world(validate_scene(SCENE))
    p, q = world.body("p"), world.body("q")
    joint = joint_from_dict(SCENE["joints"][1], world)
    same = PivotJoint(
        p, q, (1, 0), (-1, 0), limits=(-0.5, 0.5), motor={"rate": 1.0, "max_torque": 3.0}
    )
    assert joint.to_dict() == same.to_dict()


def test_bad_joints_are_refused():
    world = World()
    s = world.add_body(Body("s", type="static"))
    t = world.add_body(Body("t", type="static", position=(1, 0)))
    d = world.add_body(Body("d"))
    d.add_shape(Circle(1))
    with pytest.raises(ValueError, match="two different bodies"):
        PinJoint(d, d)
    with pytest.raises(ValueError, match="at least one dynamic"):
        world.add_joint(PinJoint(s, t))
    with pytest.raises(ValueError, match="lo <= hi"):
        PivotJoint(s, d, limits=(1.0, -1.0))
    other = World().add_body(Body("o"))
    with pytest.raises(ValueError, match="not in this world"):
        world.add_joint(PivotJoint(s, other))


def test_joined_pairs_name_the_bodies_that_must_not_collide():
    world = build_world(validate_scene(SCENE))
    assert joined_pairs(world) == {(0, 1), (1, 2), (2, 3)}
    world.find_contacts()  # brings the joint records up to date (their pair keys)
    pairs = np.array([[0, 1], [0, 2], [1, 2], [1, 3], [2, 3]])
    kept = [[a, b] for a, b in pairs if not joined(world.joint_table, 4, a, b)]
    assert kept == [[0, 2], [1, 3]]


def test_motor_and_limits_agree_with_pymunk():
    spec = validate_scene(
        {
            "gravity": [0.0, -9.81],
            "bodies": [
                {"name": "axle", "type": "static", "position": [0, 2]},
                {"name": "wheel", "position": [0, 2], "shapes": [{"type": "circle", "radius": 1}]},
                {"name": "frame", "type": "static", "position": [5, 0]},
                {"name": "rod", "position": [6, 0],
                 "shapes": [{"type": "box", "width": 2, "height": 0.1}]},
            ],
            "joints": [
                {"type": "pivot", "a": "axle", "b": "wheel",
                 "motor": {"rate": 2.0, "max_torque": 10.0}},
                {"type": "pivot", "a": "frame", "b": "rod", "anchor_b": [-1, 0],
                 "limits": [-0.5, 0.3]},
            ],
        }
    )  # fmt: skip
    world = build_world(spec)
    for _ in range(90):
        world.step()
    rows = {r[2]: r for r in run_pymunk(spec, 90) if r[0] == 90}
    assert world.body("wheel").angular_velocity == pytest.approx(rows["wheel"][8], rel=0.01)
    assert world.body("rod").angle == pytest.approx(rows["rod"][5], abs=0.02)  # rad, at the stop
