"""The pymunk bridge against closed forms: free flight, bounce, pendulum, spring, mass, buoyancy."""

import math

import numpy as np
import pytest

from sandbox.buoyancy import polygon_area_centroid
from sandbox.pymunk_bridge import (
    BridgeError,
    PymunkScene,
    circle_submerged,
    polygon_submerged,
    run_pymunk,
    wrap_angle,
)

DT = 1.0 / 60.0
G = 9.81


def ball(name="ball", position=(0.0, 0.0), radius=0.25, **extra):
    shape = {"type": "circle", "radius": radius}
    shape.update(extra.pop("shape", {}))
    return {"name": name, "type": "dynamic", "position": list(position), "shapes": [shape], **extra}


def anchor(name="anchor", position=(0.0, 0.0)):
    return {
        "name": name,
        "type": "static",
        "position": list(position),
        "shapes": [{"type": "circle", "radius": 0.01}],
    }


def zero_crossing_period(ts, xs):
    """Mean period from the upward zero crossings of xs (linear interpolation)."""
    ups = [
        ts[i] - xs[i] * (ts[i + 1] - ts[i]) / (xs[i + 1] - xs[i])
        for i in range(len(xs) - 1)
        if xs[i] < 0.0 <= xs[i + 1]
    ]
    return (ups[-1] - ups[0]) / (len(ups) - 1)


def test_free_flight_matches_pymunk_step_closed_form():
    # pymunk moves positions with the previous velocity, then updates velocities:
    # p_n = s + u n dt + a dt^2 n (n - 1) / 2, v_n = u + a n dt, theta_n = theta_0 + w n dt
    s, u, a, w = (1.0, 2.0), (3.0, 4.0), (0.5, -G), 0.7
    spec = {
        "gravity": [0.5, -G],
        "bodies": [ball(position=s, velocity=list(u), angle=0.2, angular_velocity=w)],
    }
    rows = run_pymunk(spec, 120)
    for step, t, name, x, y, angle, vx, vy, omega in rows:
        n = step
        assert name == "ball"
        assert t == pytest.approx(n * DT, abs=1e-12)
        for k, p in ((0, x), (1, y)):
            closed = s[k] + u[k] * n * DT + a[k] * DT**2 * n * (n - 1) / 2
            assert p == pytest.approx(closed, abs=1e-9)  # tolerance 1e-9 m
        assert vx == pytest.approx(u[0] + a[0] * n * DT, abs=1e-9)
        assert vy == pytest.approx(u[1] + a[1] * n * DT, abs=1e-9)
        assert angle == pytest.approx(wrap_angle(0.2 + w * n * DT), abs=1e-9)
        assert omega == pytest.approx(w, abs=1e-12)


def test_trace_rows_cover_every_body_and_step():
    spec = {"bodies": [anchor(), ball(position=(0, 5))]}
    rows = run_pymunk(spec, 10)
    assert len(rows) == 11 * 2  # (steps + 1) x bodies
    assert [r[2] for r in rows[:2]] == ["anchor", "ball"]
    assert rows[1] == (0, 0.0, "ball", 0.0, 5.0, 0.0, 0.0, 0.0, 0.0)  # step 0: initial state
    assert rows[-1][0] == 10


@pytest.mark.parametrize("e", [0.5, 0.8])
def test_bounce_reaches_e_squared_height(e):
    h, r = 2.0, 0.25
    spec = {
        "bodies": [
            {
                "name": "ground",
                "type": "static",
                "shapes": [
                    {"type": "box", "width": 20, "height": 1, "offset": [0, -0.5], "restitution": 1}
                ],
            },
            ball(position=(0, h + r), radius=r, shape={"restitution": e}),
        ]
    }
    scene = PymunkScene.from_scene(spec)
    b = scene.body("ball")
    bounced, apex = False, -math.inf
    for _ in range(180):
        scene.step()
        bounced = bounced or b.velocity.y > 0.0
        if bounced:
            apex = max(apex, b.position.y - r)
            if b.velocity.y < 0.0:
                break
    # restitution is the product of the shapes' values (e * 1); the ball overlaps the ground by up
    # to v dt before the contact is seen, so allow 5 %
    assert apex == pytest.approx(e * e * h, rel=0.05)


def pendulum_spec(length, theta0):
    bob = ball("bob", (length * math.sin(theta0), -length * math.cos(theta0)), radius=0.05)
    return {
        "bodies": [anchor(), bob],
        "joints": [
            {"type": "pin", "a": "anchor", "b": "bob", "anchor_a": [0, 0], "anchor_b": [0, 0]}
        ],
    }


def test_pendulum_keeps_length_and_period():
    length, theta0 = 1.0, 0.05
    scene = PymunkScene.from_scene(pendulum_spec(length, theta0))
    bob = scene.body("bob")
    ts, xs, worst = [], [], 0.0
    for _ in range(300):
        scene.step()
        ts.append(scene.time)
        xs.append(bob.position.x)
        worst = max(worst, abs(bob.position.length - length))
    assert worst < 0.01 * length  # pin joint keeps the length within 1 %
    # the pin joint leaves the bob free to spin, so it swings as a point mass: T = 2 pi sqrt(L/g)
    assert zero_crossing_period(ts, xs) == pytest.approx(
        2 * math.pi * math.sqrt(length / G), rel=0.02
    )


def test_spring_period():
    m, k = 2.0, 50.0
    spec = {
        "gravity": [0, 0],
        "bodies": [anchor(), ball("mass", (1.1, 0), mass=m)],
        "joints": [
            {
                "type": "spring",
                "a": "anchor",
                "b": "mass",
                "anchor_a": [0, 0],
                "anchor_b": [0, 0],
                "rest_length": 1.0,
                "stiffness": k,
                "damping": 0.0,
            }
        ],
    }
    scene = PymunkScene.from_scene(spec)
    assert scene.body("mass").mass == pytest.approx(m, rel=1e-12)
    ts, xs = [], []
    for _ in range(240):
        scene.step()
        ts.append(scene.time)
        xs.append(scene.body("mass").position.x - 1.0)
    assert zero_crossing_period(ts, xs) == pytest.approx(2 * math.pi * math.sqrt(m / k), rel=0.02)


def test_spring_rest_length_defaults_to_initial_distance():
    spec = {
        "gravity": [0, 0],
        "bodies": [anchor(), ball("mass", (1.5, 0))],
        "joints": [{"type": "spring", "a": "anchor", "b": "mass", "stiffness": 10.0}],
    }
    scene = PymunkScene.from_scene(spec)
    assert list(scene.space.constraints)[0].rest_length == pytest.approx(1.5, abs=1e-12)
    for _ in range(30):
        scene.step()
    assert scene.body("mass").position.x == pytest.approx(1.5, abs=1e-12)  # no stretch, no force


def test_mass_and_moment_of_circle_and_box():
    rho, r, w, h = 2.5, 0.4, 1.2, 0.5
    spec = {
        "bodies": [
            ball("c", radius=r, shape={"density": rho}),
            {
                "name": "b",
                "shapes": [
                    {
                        "type": "box",
                        "width": w,
                        "height": h,
                        "offset": [0.3, -0.2],
                        "angle": 0.6,
                        "density": rho,
                    }
                ],
            },
        ]
    }
    scene = PymunkScene.from_scene(spec)
    c, b = scene.body("c"), scene.body("b")
    mc, mb = math.pi * r * r * rho, w * h * rho
    assert c.mass == pytest.approx(mc, rel=1e-12)  # m = pi r^2 rho
    assert c.moment == pytest.approx(mc * r * r / 2, rel=1e-12)  # I = m r^2 / 2
    assert b.mass == pytest.approx(mb, rel=1e-12)  # m = w h rho
    assert b.moment == pytest.approx(mb * (w * w + h * h) / 12, rel=1e-12)  # about its centre
    assert tuple(b.center_of_gravity) == pytest.approx((0.3, -0.2), abs=1e-12)


def test_body_mass_override_scales_moment_and_moment_override_replaces_it():
    r = 0.5
    spec = {"bodies": [ball("a", radius=r, mass=3.0), ball("b", radius=r, mass=3.0, moment=7.0)]}
    scene = PymunkScene.from_scene(spec)
    assert scene.body("a").mass == 3.0
    assert scene.body("a").moment == pytest.approx(3.0 * r * r / 2, rel=1e-12)  # same distribution
    assert scene.body("b").moment == 7.0


def test_offset_shape_state_reports_origin_not_centre_of_mass():
    spec = {
        "gravity": [0, 0],
        "bodies": [
            ball(position=(2.0, 3.0), angle=0.5, angular_velocity=1.5, shape={"offset": [1.0, 0.0]})
        ],
    }
    scene = PymunkScene.from_scene(spec)
    b = scene.body("ball")
    com = b.local_to_world(b.center_of_gravity)
    assert com.x == pytest.approx(2.0 + math.cos(0.5), abs=1e-12)  # com = origin + R(angle) offset
    assert scene.state()[0][1:3] == pytest.approx((2.0, 3.0), abs=1e-12)
    for _ in range(40):
        scene.step()
    # the centre of mass stays put while the body spins; the origin circles round it
    name, x, y, angle, vx, vy, omega = scene.state()[0]
    com = b.local_to_world(b.center_of_gravity)
    assert (com.x, com.y) == pytest.approx((2.0 + math.cos(0.5), 3.0 + math.sin(0.5)), abs=1e-9)
    assert (x, y) == pytest.approx((com.x - math.cos(angle), com.y - math.sin(angle)), abs=1e-9)
    assert (vx, vy, omega) == pytest.approx((0.0, 0.0, 1.5), abs=1e-12)


def test_angle_wrapping():
    assert wrap_angle(1.5 * math.pi) == pytest.approx(-0.5 * math.pi, abs=1e-15)
    assert wrap_angle(-2.5 * math.pi) == pytest.approx(-0.5 * math.pi, abs=1e-15)
    assert wrap_angle(0.25) == 0.25
    spec = {"gravity": [0, 0], "bodies": [ball(angular_velocity=10.0)]}
    rows = run_pymunk(spec, 60)
    assert all(-math.pi <= r[5] <= math.pi for r in rows)
    assert rows[-1][5] == pytest.approx(wrap_angle(10.0), abs=1e-9)  # 1 s at 10 rad/s


def test_motor_rate_is_angular_velocity_of_b_relative_to_a():
    spec = {
        "gravity": [0, 0],
        "bodies": [anchor(), ball("wheel", radius=1.0)],
        "joints": [
            {
                "type": "pivot",
                "a": "anchor",
                "b": "wheel",
                "anchor_a": [0, 0],
                "anchor_b": [0, 0],
                "motor": {"rate": 2.0, "max_torque": 1e6},
            }
        ],
    }
    scene = PymunkScene.from_scene(spec)
    for _ in range(10):
        scene.step()
    assert scene.body("wheel").angular_velocity == pytest.approx(2.0, abs=1e-6)  # CCW positive


def test_linear_and_quadratic_drag_follow_the_step_recursion():
    # v_{n+1} = v_n + (g - (c + k |v_n|) v_n / m) dt  (force from the state before the step)
    c, k, r = 0.3, 0.2, 0.5
    spec = {
        "bodies": [ball(radius=r, shape={"density": 1.0})],
        "forces": [{"type": "drag", "linear": c, "quadratic": k, "angular": 0.0, "bodies": None}],
    }
    m = math.pi * r * r
    v = 0.0
    for row in run_pymunk(spec, 100):
        vy = row[7]
        assert vy == pytest.approx(v, abs=1e-9)  # hand recursion, 1e-9 m/s
        v += (-G - (c + k * abs(v)) * v / m) * DT


def test_constant_body_force_and_torque():
    spec = {"gravity": [0, 0], "bodies": [ball(mass=2.0, moment=0.5, force=[4.0, 0.0], torque=1.0)]}
    rows = run_pymunk(spec, 30)
    assert rows[-1][6] == pytest.approx(2.0 * 30 * DT, abs=1e-12)  # v = F/m t
    assert rows[-1][8] == pytest.approx(2.0 * 30 * DT, abs=1e-12)  # omega = tau/I t


def test_submerged_geometry():
    r = 2.0
    area, x, y = circle_submerged(1.0, 0.0, r, 0.0)  # half a circle below its centre
    assert area == pytest.approx(math.pi * r * r / 2, rel=1e-12)
    assert (x, y) == pytest.approx((1.0, -4 * r / (3 * math.pi)), abs=1e-12)
    assert circle_submerged(0.0, 0.0, r, 3.0)[0] == pytest.approx(math.pi * r * r, rel=1e-12)
    assert circle_submerged(0.0, 0.0, r, -3.0)[0] == 0.0
    square = [(0, 0), (2, 0), (2, 2), (0, 2)]
    area, x, y = polygon_submerged(np.array(square, dtype=float), 0.5)
    assert (area, x, y) == pytest.approx((1.0, 1.0, 0.25), abs=1e-12)
    flipped = np.array(square[::-1], dtype=float)
    assert polygon_area_centroid(flipped, 4) == pytest.approx((4.0, 1.0, 1.0), abs=1e-12)


def test_buoyancy_floats_at_density_ratio():
    # Archimedes: a box of density rho in water of density 1 floats with fraction rho submerged
    rho, h = 0.5, 0.5
    spec = {
        "bodies": [
            {
                "name": "box",
                "position": [0, 0.5],
                "shapes": [{"type": "box", "width": 1.0, "height": h, "density": rho}],
            },
            ball("ball", (3, 0.5), radius=0.5, shape={"density": rho}),
        ],
        "forces": [
            {
                "type": "buoyancy",
                "surface_y": 0.0,
                "fluid_density": 1.0,
                "linear_drag": 2.0,
                "angular_drag": 1.0,
            }
        ],
    }
    scene = PymunkScene.from_scene(spec)
    for _ in range(600):
        scene.step()
    depth = h / 2 - scene.body("box").position.y
    assert depth / h == pytest.approx(rho, rel=0.02)  # 2 % after 10 s of damped bobbing
    assert scene.body("ball").position.y == pytest.approx(0.0, abs=0.01)  # half-submerged circle


def test_raw_and_normalised_scenes_agree():
    raw = {"bodies": [ball(position=(0, 3), velocity=[1, 0])]}
    normalised = {
        "version": 1,
        "name": "n",
        "gravity": [0.0, -9.81],
        "dt": DT,
        "settings": {
            "orientation": "complex",
            "integrator": "semi_implicit_euler",
            "broadphase": "sap",
            "solver": "iterative",
            "iterations": 10,
            "penetration": "impulse",
        },
        "bodies": [
            {
                "name": "ball",
                "type": "dynamic",
                "position": [0.0, 3.0],
                "angle": 0.0,
                "velocity": [1.0, 0.0],
                "angular_velocity": 0.0,
                "ccd": True,
                "mass": None,
                "moment": None,
                "force": [0.0, 0.0],
                "torque": 0.0,
                "shapes": [
                    {
                        "type": "circle",
                        "radius": 0.25,
                        "offset": [0.0, 0.0],
                        "density": 1.0,
                        "mass": None,
                        "restitution": 0.0,
                        "friction": 0.5,
                    }
                ],
            }
        ],
        "joints": [],
        "forces": [],
    }
    assert run_pymunk(raw, 20) == run_pymunk(normalised, 20)  # bit-identical
    notes = PymunkScene.from_scene(normalised).notes
    assert any("ccd" in n for n in notes)
    assert any("collision_slop" in n for n in notes)


@pytest.mark.parametrize(
    ("spec", "path"),
    [
        ({"bodies": [ball()], "forces": [{"type": "wind"}]}, "forces[0].type"),
        ({"bodies": [ball(), ball("b", shape={"type": "capsule"})]}, "bodies[1].shapes[0].type"),
        (
            {"bodies": [ball()], "joints": [{"type": "pin", "a": "ball", "b": "ghost"}]},
            "joints[0].b",
        ),
        (
            {"bodies": [ball()], "joints": [{"type": "weld", "a": "ball", "b": "ball"}]},
            "joints[0].type",
        ),
        ({"bodies": [ball(shape={"density": 0.0})]}, "bodies[0].mass"),
        ({"bodies": [ball(), ball()]}, "bodies[1].name"),
        (
            {
                "bodies": [
                    {"name": "p", "shapes": [{"type": "polygon", "vertices": [[0, 0], [1, 1]]}]}
                ]
            },
            "bodies[0].shapes[0].vertices",
        ),
    ],
)
def test_unsupported_or_bad_input_raises_bridge_error_with_path(spec, path):
    with pytest.raises(BridgeError) as err:
        PymunkScene.from_scene(spec)
    assert err.value.path == path
    assert isinstance(err.value, ValueError)
