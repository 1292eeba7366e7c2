"""Force generators and controllers against closed forms and pymunk: springs (period, damped
envelope), drag (terminal velocity, spin-down), buoyancy (draft, sinking, same forces as the
pymunk bridge), constant forces, scene loading, the lander autopilot and scripted replay."""

import math

import numpy as np
import pymunk
import pytest

from sandbox import Body, Box, Circle, World
from sandbox.build import build_world
from sandbox.buoyancy import box_draft, circle_segment_area, disc_draft
from sandbox.controllers import LanderController, Scripted, lander_thrusters
from sandbox.forces import Buoyancy, ConstantForce, Drag, force_from_dict
from sandbox.joints import SpringJoint
from sandbox.pymunk_bridge import PymunkScene, buoyancy_force
from sandbox.scene import validate_scene

G = 9.81


def peaks(t, x):
    """Times and values of the local maxima of x(t) (parabola through each top sample)."""
    t, x = np.asarray(t), np.asarray(x)
    k = np.flatnonzero((x[1:-1] > x[:-2]) & (x[1:-1] >= x[2:])) + 1
    a, b, c = x[k - 1], x[k], x[k + 1]
    shift = 0.5 * (a - c) / (a - 2 * b + c)
    dt = t[1] - t[0]
    return t[k] + shift * dt, b - 0.25 * (a - c) * shift


# --- springs -------------------------------------------------------------------------------------
def spring_world(k=20.0, c=0.0, stretch=0.2, integrator="semi_implicit_euler"):
    """A 1 kg box on a spring of rest length 2 m from a static anchor, no gravity."""
    world = World(gravity=(0.0, 0.0), integrator=integrator)
    anchor = world.add_body(Body("anchor", type="static"))
    box = world.add_body(Body("box", position=(2.0 + stretch, 0.0)))
    box.add_shape(Box(1.0, 1.0))
    spring = world.add_joint(SpringJoint(anchor, box, rest_length=2.0, stiffness=k, damping=c))
    return world, box, spring


def run_x(world, body, seconds):
    t, x = [], []
    for _ in range(int(round(seconds / world.dt))):
        world.step()
        t.append(world.time)
        x.append(body.position[0] - 2.0)
    return np.array(t), np.array(x)


@pytest.mark.parametrize("integrator", ["semi_implicit_euler", "verlet", "rk4"])
def test_spring_period_is_two_pi_root_m_over_k(integrator):
    world, box, _ = spring_world(integrator=integrator)
    t, x = run_x(world, box, 8.0)
    tp, _ = peaks(t, x)
    period = float(np.mean(np.diff(tp)))
    assert period == pytest.approx(2 * math.pi * math.sqrt(1.0 / 20.0), rel=0.01)  # 1%


def test_undamped_spring_keeps_its_energy_under_rk4():
    world, box, spring = spring_world(integrator="rk4")
    e0 = world.energy()
    assert e0 == pytest.approx(0.5 * 20.0 * 0.2**2)  # all in the spring: k x^2 / 2
    run_x(world, box, 5.0)
    assert world.energy() == pytest.approx(e0, rel=1e-4)  # RK4 sees the spring at its stages


def test_damped_spring_decays_inside_the_envelope_exp_minus_c_t_over_2m():
    c, m = 0.5, 1.0
    world, box, _ = spring_world(c=c)
    t, x = run_x(world, box, 10.0)
    tp, xp = peaks(t, x)
    rate = -np.polyfit(tp, np.log(xp), 1)[0]  # the peaks lie on x0 e^{-rate t}
    assert rate == pytest.approx(c / (2 * m), rel=0.01)  # 1%
    omega_d = math.sqrt(20.0 / m - (c / (2 * m)) ** 2)
    assert float(np.mean(np.diff(tp))) == pytest.approx(2 * math.pi / omega_d, rel=0.01)  # 1%


def damped_oscillator(t, x0: float, k: float, m: float, c: float):
    """x(t) of m x'' + c x' + k x = 0 from rest at x0: under-, critically or over-damped."""
    w0, zeta = math.sqrt(k / m), c / (2 * math.sqrt(k * m))
    if zeta < 1:
        wd = w0 * math.sqrt(1 - zeta**2)
        return x0 * np.exp(-zeta * w0 * t) * (np.cos(wd * t) + zeta * w0 / wd * np.sin(wd * t))
    if zeta == 1:
        return x0 * (1 + w0 * t) * np.exp(-w0 * t)
    s = w0 * math.sqrt(zeta**2 - 1)
    r1, r2 = -zeta * w0 + s, -zeta * w0 - s
    return x0 * (r2 * np.exp(r1 * t) - r1 * np.exp(r2 * t)) / (r2 - r1)


@pytest.mark.parametrize("zeta", [0.1, 1.0, 3.0])
def test_damped_spring_follows_the_closed_form_under_rk4(zeta):
    k, m = 20.0, 1.0
    c = zeta * 2 * math.sqrt(k * m)
    world, box, _ = spring_world(k=k, c=c, integrator="rk4")
    t, x = run_x(world, box, 3.0)
    exact = damped_oscillator(t, 0.2, k, m, c)
    assert np.max(np.abs(x - exact)) < 1e-4 * 0.2  # 0.01% of the release stretch


def test_spring_torque_turns_a_body_hung_off_centre():
    world = World(gravity=(0.0, 0.0))
    anchor = world.add_body(Body("anchor", type="static", position=(0.0, 1.0)))
    bar = world.add_body(Body("bar"))
    bar.add_shape(Box(2.0, 0.2))
    world.add_joint(SpringJoint(anchor, bar, (0, 0), (1.0, 0.0), rest_length=0.5, stiffness=10))
    world.step()
    # F = k (|d| - L) towards the anchor at r = (1, 0): tau = r x F
    d = np.array([-1.0, 1.0])
    f = 10.0 * (math.sqrt(2) - 0.5) * d / np.linalg.norm(d)
    assert bar.angular_velocity == pytest.approx(1.0 * f[1] / bar.moment * world.dt, rel=1e-9)


# --- drag ----------------------------------------------------------------------------------------
def falling(drag: Drag, seconds: float):
    world = World()
    ball = world.add_body(Body("ball"))
    ball.add_shape(Circle(0.5, density=2.0))
    world.add_force(drag)
    for _ in range(int(round(seconds / world.dt))):
        world.step()
    return ball


def test_linear_drag_gives_terminal_velocity_m_g_over_c():
    ball = falling(Drag(linear=3.0), 10.0)
    assert -ball.velocity[1] == pytest.approx(ball.mass * G / 3.0, rel=0.01)  # 1%


def test_quadratic_drag_gives_terminal_velocity_root_m_g_over_k():
    ball = falling(Drag(quadratic=0.5), 10.0)
    assert -ball.velocity[1] == pytest.approx(math.sqrt(ball.mass * G / 0.5), rel=0.01)  # 1%


def test_angular_drag_spins_down_as_exp_minus_c_t_over_i():
    world = World(gravity=(0.0, 0.0))
    disc = world.add_body(Body("disc", angular_velocity=5.0))
    disc.add_shape(Circle(1.0))
    world.add_force(Drag(angular=0.3, bodies=["disc"]))
    for _ in range(120):
        world.step()
    expected = 5.0 * math.exp(-0.3 * 2.0 / disc.moment)
    assert disc.angular_velocity == pytest.approx(expected, rel=0.01)  # 1%


# --- buoyancy ------------------------------------------------------------------------------------
@pytest.mark.parametrize("density", [0.3, 0.5, 0.8])
def test_floating_draft_is_the_density_ratio(density):
    world = World()
    box = world.add_body(Body("box", position=(0.0, 1.0)))
    box.add_shape(Box(2.0, 0.5, density=density))  # wide: floats flat at any density
    disc = world.add_body(Body("disc", position=(3.0, 1.0)))
    disc.add_shape(Circle(0.5, density=density))
    world.add_force(Buoyancy(surface_y=0.0, fluid_density=1.0, linear_drag=2.0, angular_drag=0.5))
    for _ in range(480):
        world.step()
    box_depth = 0.25 - box.position[1]  # bottom face below the surface
    disc_depth = 0.5 - disc.position[1]
    assert box_depth == pytest.approx(box_draft(0.5, density), rel=0.02)  # 2%
    assert disc_depth == pytest.approx(disc_draft(0.5, density), rel=0.02)  # 2%
    assert abs(box.angle) < 1e-6


def test_disc_draft_closed_form_is_the_segment_area():
    for ratio in (0.1, 0.5, 0.9):
        d = disc_draft(0.5, ratio)
        assert circle_segment_area(0.5, d) == pytest.approx(ratio * math.pi * 0.25, rel=1e-12)
    assert disc_draft(0.5, 0.5) == pytest.approx(0.5, abs=1e-12)


def test_a_heavy_body_sinks_at_g_times_one_minus_the_density_ratio():
    world = World()
    stone = world.add_body(Body("stone", position=(0.0, -2.0)))
    stone.add_shape(Box(0.5, 0.5, density=2.5))
    world.add_force(Buoyancy(surface_y=0.0, fluid_density=1.0))
    world.step()
    a = -G * (1.0 - 1.0 / 2.5)  # weight minus the displaced fluid's weight, over m
    assert stone.velocity[1] == pytest.approx(a * world.dt, rel=1e-9)


def test_buoyancy_forces_are_the_pymunk_bridges():
    world = World(gravity=(0.0, -9.81))
    box = world.add_body(Body("box", position=(0.3, 0.1), angle=0.4, velocity=(1.0, -0.5)))
    box.add_shape(Box(1.0, 0.6, offset=(0.2, 0.0)))
    box.add_shape(Circle(0.3, offset=(-0.4, 0.1)))
    box.angular_velocity = 1.5
    spec = {"type": "buoyancy", "surface_y": 0.05, "fluid_density": 1.3,
            "linear_drag": 2.0, "angular_drag": 0.7}  # fmt: skip
    gen = world.add_force(force_from_dict({**spec, "bodies": None}, world))
    f, tau = np.zeros((1, 2)), np.zeros(1)
    gen.accumulate(world, world.com, world.vel, world.angles(), world.omega, f, tau)

    body = pymunk.Body()
    body.position, body.angle = box.position, box.angle
    shapes = [
        pymunk.Poly(body, [tuple(v) for v in box.shapes[0].vertices]),
        pymunk.Circle(body, 0.3, (-0.4, 0.1)),
    ]
    for s in shapes:
        s.density = 1.0
    space = pymunk.Space()
    space.add(body, *shapes)
    body.velocity, body.angular_velocity = box.velocity, box.angular_velocity
    fx, fy, torque = buoyancy_force(body, spec, (0.0, -9.81))
    np.testing.assert_allclose([*f[0], tau[0]], [fx, fy, torque], rtol=1e-9, atol=1e-12)


def test_floating_discs_agree_with_pymunk():
    spec = validate_scene(
        {
            "bodies": [
                {"name": f"disc{i}", "position": [2.0 * i, 1.0],
                 "shapes": [{"type": "circle", "radius": 0.5, "density": rho}]}
                for i, rho in enumerate((0.3, 0.6))
            ],
            "forces": [{"type": "buoyancy", "surface_y": 0, "fluid_density": 1,
                        "linear_drag": 2, "angular_drag": 0.5}],
        }
    )  # fmt: skip
    world = build_world(spec)
    other = PymunkScene.from_scene(spec)
    for _ in range(300):
        world.step()
        other.step()
    for body, (_, _, y, *_) in zip(world.bodies, other.state(), strict=True):
        assert body.position[1] == pytest.approx(y, abs=0.005)  # m


# --- constant forces and scenes ------------------------------------------------------------------
def test_constant_force_at_a_point_pushes_and_turns():
    world = World(gravity=(0.0, 0.0))
    plate = world.add_body(Body("plate"))
    plate.add_shape(Box(2.0, 1.0))
    world.add_force(ConstantForce(force=(0.0, 3.0), point=(1.0, 0.0), bodies=[plate]))
    world.step()
    # slides, "Force" and "Torque": a = F / m, alpha = (r x F) / I
    assert plate.velocity[1] == pytest.approx(3.0 / plate.mass * world.dt, rel=1e-12)
    assert plate.angular_velocity == pytest.approx(3.0 / plate.moment * world.dt, rel=1e-12)


def test_every_force_loads_from_a_scene_and_writes_back_the_same():
    spec = validate_scene(
        {
            "bodies": [
                {"name": "a", "shapes": [{"type": "circle", "radius": 0.5}]},
                {"name": "b", "position": [3, 0], "shapes": [{"type": "box", "width": 1, "height": 1}]},
            ],
            "forces": [
                {"type": "drag", "linear": 0.1, "quadratic": 0.2, "angular": 0.3, "bodies": ["b"]},
                {"type": "buoyancy", "surface_y": -1, "fluid_density": 1.2, "linear_drag": 1},
            ],
        }
    )  # fmt: skip
    world = build_world(spec)
    drag, water = world.forces
    assert isinstance(drag, Drag) and [b.name for b in drag.bodies] == ["b"]
    assert isinstance(water, Buoyancy) and water.bodies is None
    assert [f.to_dict() for f in world.forces] == spec["forces"]
    assert validate_scene(world.to_scene())["forces"] == spec["forces"]
    python = [Drag(0.1, 0.2, 0.3, bodies=["b"]), Buoyancy(-1, 1.2, 1.0)]
    for gen in python:
        gen.attach(world)
    assert [g.to_dict() for g in python] == spec["forces"]
    for _ in range(5):
        world.step()


def test_bad_forces_are_refused():
    with pytest.raises(ValueError, match="fluid_density"):
        Buoyancy(fluid_density=0.0)
    with pytest.raises(ValueError, match="linear"):
        Drag(linear=-1.0)
    world = World()
    with pytest.raises(KeyError, match="nobody"):
        world.add_force(Drag(1.0, bodies=["nobody"]))


# --- user and agent input ------------------------------------------------------------------------
def lander_world():
    world = World()
    lander = world.add_body(Body("lander"))
    lander.add_shape(Box(1.0, 0.5))
    return world, lander


def test_lander_autopilot_reaches_its_target_with_bounded_thrust():
    world, lander = lander_world()
    thrusters = lander_thrusters(1.0, 0.5, max_thrust=5.0)
    pilot = LanderController(target=(6.0, 4.0), thrusters=thrusters)
    lander.controller = pilot
    for _ in range(420):
        world.step()
    assert np.hypot(lander.position[0] - 6.0, lander.position[1] - 4.0) < 0.05  # m
    assert np.hypot(*lander.velocity) < 0.05  # m/s
    thrust = np.array([row[1:] for row in pilot.log])
    assert thrust.min() >= 0.0 and thrust.max() <= 5.0  # N, each thruster within its bound
    assert thrust.max() == 5.0  # and the bound was reached while climbing
    # hovering at the end: total thrust carries the weight
    assert thrust[-1].sum() == pytest.approx(lander.mass * G, rel=0.01)


def test_scripted_replay_of_the_autopilots_log_flies_the_same_path():
    world, lander = lander_world()
    pilot = LanderController(target=(-3.0, 2.0), thrusters=lander_thrusters(1.0, 0.5, 5.0))
    lander.controller = pilot
    for _ in range(240):
        world.step()
    replay_world, replayed = lander_world()
    replayed.controller = Scripted.from_log(pilot.log, lander_thrusters(1.0, 0.5, 5.0))
    for _ in range(240):
        replay_world.step()
    assert replayed.position == lander.position  # bit for bit: deterministic, open loop
    assert replayed.angle == lander.angle


def test_scripted_force_commands_hold_until_the_next_one():
    world = World(gravity=(0.0, 0.0))
    puck = world.add_body(Body("puck"))
    puck.add_shape(Circle(0.5))
    m = puck.mass
    puck.controller = Scripted([(0.5, {"force": (2.0, 0.0)}), (1.0, {"torque": 0.5})])
    for _ in range(90):
        world.step()
    # 2 N from t = 0.5 s to t = 1 s: impulse 1 N s; then 0.5 N m for 0.5 s
    assert puck.velocity[0] == pytest.approx(1.0 / m, rel=1e-9)
    assert puck.angular_velocity == pytest.approx(0.25 / puck.moment, rel=1e-9)


def test_constant_force_at_a_point_agrees_with_pymunk():
    # a 1 N sideways push at a rim point fixed on a resting disc: v = F t / m exactly; the point
    # turns with the disc, so only the first step's spin is closed form (omega = -r F dt / I);
    # after that both engines agree to O(dt): pymunk moves positions before velocities, so its
    # lever lags one step; at dt = 1/600 they agree within 1% after 1 s
    from sandbox.build import build_world
    from sandbox.pymunk_bridge import run_pymunk
    from sandbox.scene import validate_scene

    spec = validate_scene(
        {
            "gravity": [0, 0],
            "dt": 1.0 / 600.0,
            "bodies": [{"name": "disc", "shapes": [{"type": "circle", "radius": 0.5}]}],
            "forces": [{"type": "constant", "force": [1.0, 0.0], "point": [0.0, 0.5]}],
        }
    )
    world = build_world(spec)
    disc = world.body("disc")
    world.step()
    assert disc.angular_velocity == pytest.approx(-0.5 * world.dt / disc.moment, rel=1e-12)
    for _ in range(599):
        world.step()
    last = run_pymunk(spec, 600)[-1]
    assert disc.velocity[0] == pytest.approx(1.0 / disc.mass, rel=1e-9)
    assert last[6] == pytest.approx(disc.velocity[0], rel=1e-9)
    assert last[8] == pytest.approx(disc.angular_velocity, rel=1e-2)
