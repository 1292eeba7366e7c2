"""The benchmarks' Box2D 2.3 builder (benchmarks/box2d_scene.py) builds the same bodies as this
engine from one scene dict: positions, velocities, masses, centres of mass, moments, shapes, and
contacts that combine friction and restitution as the scene contract says (the product).

Box2D computes in single precision, so values are compared to a relative 1e-6 (float32 keeps about
7 digits; the moments go through one more subtraction, 1e-5)."""

import math
import sys
from pathlib import Path

import pytest

pytest.importorskip("Box2D", reason="box2d (pybox2d) is not installed: pip install -e '.[bench]'")

from sandbox.build import build_world  # noqa: E402
from sandbox.scene import validate_scene  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
from box2d_scene import Box2DSceneError, box2d_scene  # noqa: E402

F32 = 1e-6  # relative: float32


def tiny_scene() -> dict:
    """A ground, a disc with an offset, a turned box with an offset beside a triangle on one body,
    a body whose shape gives a mass instead of a density, and a body with mass overrides."""
    return {
        "gravity": [0.0, -9.81],
        "dt": 1.0 / 60.0,
        "settings": {"iterations": 10},
        "bodies": [
            {
                "name": "ground",
                "type": "static",
                "position": [0.0, -0.5],
                "shapes": [{"type": "box", "width": 20.0, "height": 1.0, "friction": 0.6}],
            },
            {
                "name": "disc",
                "position": [-3.0, 2.0],
                "angle": 0.4,
                "velocity": [1.0, -2.0],
                "angular_velocity": 0.5,
                "shapes": [{"type": "circle", "radius": 0.3, "offset": [0.1, 0.2], "density": 2.0}],
            },
            {
                "name": "compound",
                "position": [0.0, 3.0],
                "angle": -0.3,
                "shapes": [
                    {
                        "type": "box",
                        "width": 1.0,
                        "height": 0.5,
                        "offset": [0.5, 0.0],
                        "angle": 0.2,
                    },
                    {"type": "polygon", "vertices": [[-1, 0], [0, 0], [-0.5, 1]], "density": 3.0},
                ],
            },
            {
                "name": "by_mass",
                "position": [3.0, 1.0],
                "shapes": [{"type": "box", "width": 0.4, "height": 0.8, "mass": 5.0}],
            },
            {
                "name": "override",
                "position": [5.0, 1.0],
                "mass": 7.0,
                "shapes": [{"type": "circle", "radius": 0.5, "offset": [0.2, 0.0]}],
            },
        ],
    }


def test_bodies_match_this_engine():
    spec = validate_scene(tiny_scene())
    world = build_world(spec)
    scene = box2d_scene(spec)
    assert len(scene.bodies) == len(world.bodies) == 5
    assert scene.dt == spec["dt"] and scene.velocity_iterations == 10
    assert scene.position_iterations == 3
    for mine, theirs in zip(world.bodies, scene.bodies, strict=True):
        assert tuple(theirs.position) == pytest.approx(tuple(mine.position), rel=F32, abs=F32)
        assert theirs.angle == pytest.approx(mine.angle, rel=F32, abs=F32)
        assert tuple(theirs.linearVelocity) == pytest.approx(tuple(mine.velocity), rel=F32)
        assert theirs.angularVelocity == pytest.approx(mine.angular_velocity, rel=F32)
        if mine.type != "dynamic":
            assert theirs.mass == 0.0
            continue
        assert theirs.mass == pytest.approx(mine.mass, rel=F32)
        assert tuple(theirs.worldCenter) == pytest.approx(tuple(mine.center_of_mass), rel=F32)
        cx, cy = theirs.localCenter
        moment = theirs.inertia - theirs.mass * (cx * cx + cy * cy)  # Box2D's is about the origin
        assert moment == pytest.approx(mine.moment, rel=1e-5)


def test_shapes_match_this_engine():
    spec = validate_scene(tiny_scene())
    world = build_world(spec)
    scene = box2d_scene(spec)
    for mine, theirs in zip(world.bodies, scene.bodies, strict=True):
        fixtures = list(theirs.fixtures)  # in the order they were made
        assert len(fixtures) == len(mine.shapes)
        for shape, fixture in zip(mine.shapes, fixtures, strict=True):
            if shape.kind == "circle":
                assert fixture.shape.radius == pytest.approx(shape.radius, rel=F32)
                assert tuple(fixture.shape.pos) == pytest.approx(tuple(shape.offset), abs=F32)
            else:  # the same corners, whichever one each engine lists first
                theirs_v = sorted(tuple(round(c, 5) for c in v) for v in fixture.shape.vertices)
                mine_v = sorted(tuple(round(float(c), 5) for c in v) for v in shape.vertices)
                assert theirs_v == mine_v
            # Box2D mixes friction as sqrt(f_a f_b): the fixture holds f^2
            assert fixture.friction == pytest.approx(shape.friction**2, rel=F32)


def contact_of(scene, a: int, b: int):
    a, b = scene.bodies[a], scene.bodies[b]  # Box2D's wrappers compare equal, are not the same
    for contact in scene.world.contacts:
        one, two = contact.fixtureA.body, contact.fixtureB.body
        if contact.touching and ((one == a and two == b) or (one == b and two == a)):
            return contact
    return None


def drop_on_ground(restitution_ball: float, restitution_ground: float) -> tuple:
    spec = {
        "bodies": [
            {
                "name": "ground",
                "type": "static",
                "shapes": [
                    {
                        "type": "box",
                        "width": 10.0,
                        "height": 1.0,
                        "offset": [0.0, -0.5],
                        "friction": 0.6,
                        "restitution": restitution_ground,
                    }
                ],
            },
            {
                "name": "ball",
                "position": [0.0, 0.49],
                "velocity": [0.0, -3.0],
                "shapes": [
                    {
                        "type": "circle",
                        "radius": 0.5,
                        "friction": 0.5,
                        "restitution": restitution_ball,
                    }
                ],
            },
        ]
    }
    scene = box2d_scene(spec)
    scene.step()
    return scene, contact_of(scene, 0, 1)


def test_contacts_use_the_product_of_friction_and_restitution():
    # the scene contract (and pymunk): friction 0.6 x 0.5 = 0.3, restitution 0.5 x 0.8 = 0.4;
    # Box2D's own mixing would give sqrt(0.3) = 0.548 and max = 0.8
    scene, contact = drop_on_ground(0.5, 0.8)
    assert contact is not None
    assert contact.friction == pytest.approx(0.3, rel=F32)
    assert contact.restitution == pytest.approx(0.4, rel=F32)
    assert scene.listener is not None
    # and it bounces with the product: v after = -e v before, where v before is 3 m/s plus the
    # step's gravity (Box2D adds it before solving): 0.4 x (3 + 9.81/60) (float32)
    assert scene.bodies[1].linearVelocity.y == pytest.approx(0.4 * (3.0 + 9.81 / 60), rel=F32)


def test_no_listener_without_restitution():
    scene, contact = drop_on_ground(0.0, 0.0)
    assert scene.listener is None
    assert contact.restitution == 0.0
    assert not scene.world.allowSleeping and not scene.world.continuousPhysics


def test_what_it_cannot_build_is_named():
    spec = tiny_scene()
    spec["joints"] = [{"type": "pin", "a": "disc", "b": "compound"}]
    with pytest.raises(Box2DSceneError, match="^joints:"):
        box2d_scene(spec)
    spec = tiny_scene()
    spec["bodies"][1]["force"] = [0.0, 5.0]
    with pytest.raises(Box2DSceneError, match=r"^bodies\[1\]\.force:"):
        box2d_scene(spec)


def test_ballistic_matches_until_box2d_caps_the_speed():
    # free flight: semi-implicit Euler in both, identical to float32 until the body would move more
    # than b2_maxTranslation = 2 m per step (120 m/s); 60 steps stay far below that
    spec = validate_scene(
        {
            "bodies": [
                {"name": "b", "velocity": [3, 20], "shapes": [{"type": "circle", "radius": 1}]}
            ]
        }
    )
    world = build_world(spec)
    scene = box2d_scene(spec)
    for _ in range(60):
        world.step()
        scene.step()
    assert scene.bodies[0].position.y == pytest.approx(world.bodies[0].position[1], rel=1e-5)
    assert scene.bodies[0].position.x == pytest.approx(world.bodies[0].position[0], rel=1e-5)
    assert not math.isclose(world.bodies[0].position[1], 0.0)
