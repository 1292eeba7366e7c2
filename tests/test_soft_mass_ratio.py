"""Heavy on light under the soft step (``settings.hold_ratio``, sandbox.solvers.soft
.hold_under_heavy_loads): a body resting on one more than ``hold_ratio`` times lighter treats it
as immovable, so a light box stays under a heavy one; nothing changes where no such body rests
on another (bodies of like mass, a light body on a heavy one, a heavy body striking from the
side)."""

import math

import numpy as np
import pytest

from sandbox import Body, Box, Circle, World
from sandbox.solvers.soft import MAX_CONTACT_HERTZ_PER_RATE, STATIC_STIFFNESS

G = 9.81


def heavy_on_light(heavy: float = 400.0, light_size: float = 0.5, **settings) -> World:
    """A box of ``light_size`` (m) and 1 kg on the ground, a 1 m box of ``heavy`` kg resting on
    it, both released at rest, under the soft step."""
    w = World(gravity=(0, -G), solver="soft", **settings)
    w.add_body(Body("ground", type="static", position=(0, -0.5))).add_shape(
        Box(40, 1, friction=0.6)
    )
    light = w.add_body(Body("light", position=(0, light_size / 2)))
    light.add_shape(Box(light_size, light_size, friction=0.6, mass=1.0))
    top = w.add_body(Body("heavy", position=(0, light_size + 0.5)))
    top.add_shape(Box(1, 1, friction=0.6, mass=heavy))
    return w


def watch(w: World, steps: int = 600) -> tuple[float, float, float]:
    """(worst sink of the light box into the ground, worst sink of the heavy box into the light
    one, worst sideways offset between them) over ``steps`` steps (m)."""
    ground, light, heavy = w.bodies
    size = light.shapes[0].height
    sink_light = sink_heavy = offset = 0.0
    for _ in range(steps):
        w.step()
        bottom = light.position[1] - size / 2
        sink_light = max(sink_light, -bottom)
        sink_heavy = max(sink_heavy, light.position[1] + size / 2 - (heavy.position[1] - 0.5))
        offset = max(offset, abs(light.position[0] - heavy.position[0]))
    return sink_light, sink_heavy, offset


def same_as_without_the_hold(make, steps: int) -> World:
    """Step ``make()`` and ``make(hold_ratio=0.0)`` side by side; they must stay bit for bit
    alike (nothing held). Returns the first."""
    a, b = make(), make(hold_ratio=0.0)
    for _ in range(steps):
        a.step()
        b.step()
    assert np.array_equal(a.com, b.com)
    assert np.array_equal(a.angles(), b.angles())
    return a


@pytest.mark.parametrize("light_size", [0.5, 1.0])
@pytest.mark.parametrize("substeps", [4, 8])
def test_a_light_box_stays_under_a_400_kg_box(light_size, substeps):
    # the bound: 1 kg under 400 kg, 10 s, neither sinks more than 2 cm and the light
    # box stays under (here: within 1 cm of centred); measured under 0.1 mm each. Held, the
    # light box is the heavy one's ground: the heavy box rests at the static error of a contact
    # with a body that cannot move, C = M g / (2 m_p omega^2), two points of effective mass
    # m_p = (1/M + r^2 / I)^-1 (r: half the light box, I = M / 6), omega = 2 pi (2 f), f the
    # contact hertz capped at an eighth of the substep rate (the soft step lesson, section 2):
    # 0.047 mm to 0.086 mm here, within 1e-6 relative (measured 2e-9), with the sag kept
    # (sag_recovery_time 0); at the defaults the contact takes that sag back as e^(-t / 1 s):
    # after 10 s under a thousandth of it is left (measured 2e-5 to 4e-5)
    def rest(w: World) -> float:
        light, heavy = w.bodies[1], w.bodies[2]
        return light.position[1] + light_size / 2 - (heavy.position[1] - 0.5)

    kept = heavy_on_light(light_size=light_size, substeps=substeps, sag_recovery_time=0.0)
    w = heavy_on_light(light_size=light_size, substeps=substeps)
    for world in (kept, w):
        sink_light, sink_heavy, offset = watch(world)
        assert sink_light < 0.02
        assert sink_heavy < 0.02
        assert offset < 0.01
    big, r = 400.0, light_size / 2
    m_p = 1 / (1 / big + r * r / (big / 6))
    hertz = STATIC_STIFFNESS * min(
        w.settings.contact_hertz, MAX_CONTACT_HERTZ_PER_RATE * substeps / w.dt
    )
    sag = big * G / (2 * m_p * (2 * math.pi * hertz) ** 2)
    assert rest(kept) == pytest.approx(sag, rel=1e-6)
    assert abs(rest(w)) < 1e-3 * sag


def test_without_the_hold_the_light_box_is_squeezed_out():
    # hold_ratio 0 is the soft step without it: the heavy box sinks 10 cm and more into the
    # light one (its static error on the light box's effective mass) and the light box is
    # worked out from under it (more than half a box) within 10 s
    sink_light, sink_heavy, offset = watch(heavy_on_light(hold_ratio=0.0))
    assert sink_heavy > 0.05
    assert offset > 0.25


@pytest.mark.parametrize("heavy", [2.0, 9.0])
def test_below_the_ratio_nothing_is_held(heavy):
    # 9 kg on 1 kg with hold_ratio 10: the same steps, bit for bit, as with the hold off
    same_as_without_the_hold(lambda **settings: heavy_on_light(heavy, **settings), 120)


def test_a_light_body_on_a_heavy_one_is_not_held():
    # 1 kg on 400 kg: the upper body is the light one, and it sits on the heavy box's soft
    # contact as on the ground; the same steps as with the hold off
    def world(**settings):
        w = World(gravity=(0, -G), solver="soft", **settings)
        w.add_body(Body("ground", type="static", position=(0, -0.5))).add_shape(Box(40, 1))
        w.add_body(Body("heavy", position=(0, 0.5))).add_shape(Box(1, 1, mass=400.0))
        w.add_body(Body("light", position=(0, 1.25))).add_shape(Box(0.5, 0.5, mass=1.0))
        return w

    same_as_without_the_hold(world, 120)


def test_a_heavy_ball_striking_from_the_side_still_pushes():
    # a 100 kg ball flying level at 4 m/s into the side of a 1 kg box on the ground: the ball
    # touches nothing else, so it is a layer above the box, but the normal between them is
    # level, not a load resting on the box, so nothing is held: the same steps as with the hold
    # off (held, the box would have stopped the ball as a wall does). An elastic impact
    # (e = 1, no friction) of M on m at rest: the ball goes on at v (M - m) / (M + m) = 3.921
    # m/s (measured 3.923, within 0.1%), the box leaves at 2 M v / (M + m) = 7.921 m/s (measured
    # 7.693: soft bounces fall short, within 5%), and the level momentum M v is kept (1e-9)
    def world(**settings):
        w = World(gravity=(0, -G), solver="soft", **settings)
        w.add_body(Body("ground", type="static", position=(0, -0.5))).add_shape(
            Box(40, 1, friction=0.0)
        )
        w.add_body(Body("ball", position=(-0.6, 0.3), velocity=(4, 0))).add_shape(
            Circle(0.2, mass=100.0, friction=0.0, restitution=1.0)
        )
        w.add_body(Body("box", position=(0, 0.25))).add_shape(
            Box(0.5, 0.5, mass=1.0, friction=0.0, restitution=1.0)
        )
        return w

    a = same_as_without_the_hold(world, 4)  # the impact comes in the third step
    ball, box = a.bodies[1], a.bodies[2]
    assert ball.position[1] - 0.2 > 0.0  # still in the air: not on the ground's layer
    big, small, v = 100.0, 1.0, 4.0
    assert ball.velocity[0] == pytest.approx(v * (big - small) / (big + small), rel=1e-3)
    assert box.velocity[0] == pytest.approx(2 * big * v / (big + small), rel=0.05)
    assert big * ball.velocity[0] + small * box.velocity[0] == pytest.approx(big * v, rel=1e-9)


def test_a_heavy_box_dropped_on_a_light_one_lands_and_rests():
    # 400 kg dropped from 1 m onto the 1 kg box: the landing is taken by the heavy box alone (the
    # light one is held), and both rest within 2 cm, the light box under the heavy one
    w = heavy_on_light()
    w.bodies[2].position = (0.0, 2.0)
    sink_light, sink_heavy, offset = watch(w)
    assert sink_light < 0.02
    assert sink_heavy < 0.02
    assert offset < 0.01
    assert abs(w.bodies[2].velocity[1]) < 1e-3


def test_a_light_box_striking_a_heavy_one_from_below_is_not_held():
    # the 1 kg box under 30 kg leaves the ground at 30 m/s: it strikes the heavy box, it does
    # not carry it. Held (immovable, keeping its 30 m/s), it would launch the heavy box at
    # 30 m/s; not held, momentum is shared: 30 N s over 31 kg, 0.97 m/s at most for the heavy
    # box, and the step is bit for bit the one without the hold
    def make(**settings) -> World:
        w = heavy_on_light(heavy=30.0, **settings)
        w.body("light").velocity = (0.0, 30.0)
        return w

    w = same_as_without_the_hold(make, steps=1)
    assert 0.0 < w.body("heavy").velocity[1] <= 30.0 / 31.0
