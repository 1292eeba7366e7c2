"""Contact robustness with ``settings.robust_positions`` (the position passes from the ground
up, the lower body held, overlap present at the start of a step pushed out at most at
``max_push_speed``): bodies spawned inside one another separate slowly instead of being fired
through the ground, and a light box under a heavy one stays under it.

Measured with the classic pass (the default, which the lessons show): of 100 boxes spawned
in one spot, one ends 19.9 m below the ground and the fastest moves at 19 m/s; the 1 kg box
under 1000 kg is squeezed 1.6 m out sideways."""

from __future__ import annotations

import math

from sandbox import Body, Box, World

G = 9.81


def ground_world(**settings) -> World:
    w = World(gravity=(0, -G), **settings)
    w.add_body(Body("ground", type="static", position=(0, -0.5))).add_shape(Box(40, 1))
    return w


def test_bodies_spawned_inside_one_another_separate_at_a_bounded_speed():
    # 100 unit boxes within 0.1 m of each other on the ground, 2 s: no centre ever below
    # 0.5 m - 1 cm (none pushed into the ground) and none faster than max_push_speed (3 m/s)
    w = ground_world(robust_positions=True)
    boxes = []
    for i in range(100):
        boxes.append(w.add_body(Body(f"b{i}", position=(0.001 * i, 0.5))))
        boxes[-1].add_shape(Box(1, 1))
    lowest, fastest = math.inf, 0.0
    for _ in range(120):
        w.step()
        lowest = min(lowest, min(b.position[1] for b in boxes))
        fastest = max(fastest, max(math.hypot(*b.velocity) for b in boxes))
    assert lowest > 0.49
    assert fastest < w.settings.max_push_speed


def test_a_light_box_under_a_heavy_one_stays_under_it():
    # 1 kg (0.5 m) under 1000 kg (1 m) on the ground, 10 s: neither sinks more than 2 cm below
    # where it rests (light centre 0.25 m, heavy 1.0 m), the light box stays centred (1 cm)
    w = ground_world(robust_positions=True)
    light = w.add_body(Body("light", position=(0, 0.25)))
    light.add_shape(Box(0.5, 0.5, mass=1.0))
    heavy = w.add_body(Body("heavy", position=(0, 1.0)))
    heavy.add_shape(Box(1.0, 1.0, mass=1000.0))
    for _ in range(600):
        w.step()
        assert light.position[1] > 0.25 - 0.02
        assert heavy.position[1] > 1.0 - 0.02
        assert abs(light.position[0] - heavy.position[0]) < 0.01


def test_the_switch_keeps_a_resting_stack_as_the_classic_pass_leaves_it():
    # a 5-box stack at rest, 2 s, both passes: the same heights to 1 mm (the switch changes
    # what happens to deep overlap, not to a stack the velocity solver already holds)
    tops = []
    for robust in (False, True):
        w = ground_world(robust_positions=robust)
        stack = [w.add_body(Body(f"s{i}", position=(0, 0.5 + i))) for i in range(5)]
        for b in stack:
            b.add_shape(Box(1, 1))
        for _ in range(120):
            w.step()
        tops.append(stack[-1].position[1])
    assert abs(tops[0] - tops[1]) < 1e-3
    assert tops[1] > 4.5 - 0.03
