"""Contact robustness at the defaults (``settings.robust_positions``: the position passes from
the ground up, a lower body held under a much heavier one, overlap present at the start of a step pushed
out at most at ``max_push_speed``): bodies spawned inside one another separate slowly instead
of being fired through the ground, and a light box under a heavy one stays under it.

Measured with the classic pass (``robust_positions: false``, the slides' pass): of 100 boxes
spawned in one spot, one ends 19.9 m below the ground and the fastest moves at 19 m/s; the 1 kg
box under 1000 kg is squeezed 1.6 m out sideways. The soft step separates the spawned pile the
same way (its bias leaves overlap that began deeper than the slop plus one step's bounded push
to the position stage), but its position passes hold no lighter body: its contacts carry their
own sag, and it holds a light body in its velocity passes instead (``settings.hold_ratio``,
``tests/test_soft_mass_ratio.py``)."""

from __future__ import annotations

import math

import pytest

from sandbox import Body, Box, World

G = 9.81
RIGID = ("iterative", "shock")  # the solvers that hold these; pairwise does not (one pass)


def ground_world(**settings) -> World:
    w = World(gravity=(0, -G), **settings)
    w.add_body(Body("ground", type="static", position=(0, -0.5))).add_shape(Box(40, 1))
    return w


def spawn_pile(**settings) -> tuple[float, float, float]:
    """100 unit boxes within 0.1 m of each other on the ground, 2 s: (lowest centre (m),
    fastest speed (m/s), max_push_speed (m/s))."""
    w = ground_world(**settings)
    boxes = []
    for i in range(100):
        boxes.append(w.add_body(Body(f"b{i}", position=(0.001 * i, 0.5))))
        boxes[-1].add_shape(Box(1, 1))
    lowest, fastest = math.inf, 0.0
    for _ in range(120):
        w.step()
        lowest = min(lowest, min(b.position[1] for b in boxes))
        fastest = max(fastest, max(math.hypot(*b.velocity) for b in boxes))
    return lowest, fastest, w.settings.max_push_speed


@pytest.mark.parametrize("solver", [*RIGID, "soft"])
def test_bodies_spawned_inside_one_another_separate_at_a_bounded_speed(solver):
    # no centre ever below 0.5 m - 1 cm (none pushed into the ground) and none faster than
    # max_push_speed (3 m/s); measured 0.495 m and 0.53 m/s (soft: 0.497 m, 0.90 m/s; with the
    # soft bias pushing every overlapping pair apart at 3 m/s, 57 m/s)
    lowest, fastest, push = spawn_pile(solver=solver)
    assert lowest > 0.49
    assert fastest < push


@pytest.mark.parametrize("solver", ["iterative", "soft"])
def test_the_classic_pass_fires_the_same_pile_through_the_ground(solver):
    # what the default replaced (the finding): one box ends metres below the ground
    lowest, fastest, push = spawn_pile(solver=solver, robust_positions=False)
    assert lowest < -1.0
    assert fastest > 3 * push


def test_a_light_box_under_a_heavy_one_stays_under_it():
    # 1 kg (0.5 m) under 1000 kg (1 m) on the ground, 10 s: neither sinks more than 2 cm below
    # where it rests (light centre 0.25 m, heavy 1.0 m), the light box stays centred (1 cm).
    # (The shock solver holds it too, with either pass, but lets it drift 1.4 cm.)
    w = ground_world()
    light = w.add_body(Body("light", position=(0, 0.25)))
    light.add_shape(Box(0.5, 0.5, mass=1.0))
    heavy = w.add_body(Body("heavy", position=(0, 1.0)))
    heavy.add_shape(Box(1.0, 1.0, mass=1000.0))
    for _ in range(600):
        w.step()
        assert light.position[1] > 0.25 - 0.02
        assert heavy.position[1] > 1.0 - 0.02
        assert abs(light.position[0] - heavy.position[0]) < 0.01


def ten_stack(**settings) -> float:
    """The top of a 10-box stack released at rest: how far it drops in 10 s (m)."""
    w = ground_world(**settings)
    stack = [w.add_body(Body(f"s{i}", position=(0, 0.5 + i))) for i in range(10)]
    for b in stack:
        b.add_shape(Box(1, 1))
    for _ in range(600):
        w.step()
    return 9.5 - stack[-1].position[1]


def test_the_switch_keeps_a_warm_started_stack_as_the_classic_pass_leaves_it():
    # warm started, the velocity solver holds the stack and no step needs layers: the top
    # ends exactly where the classic pass leaves it (11.3 mm down)
    robust, classic = ten_stack(), ten_stack(robust_positions=False)
    assert robust == classic
    assert robust < 0.02


def pyramid_drop(base: int = 20, **settings) -> float:
    """A pyramid of ``base`` boxes released at rest: how far its top box drops in 10 s (m)."""
    w = ground_world(**settings)
    top = None
    for row in range(base):
        for i in range(base - row):
            top = w.add_body(Body(f"r{row}b{i}", position=(i - 0.5 * (base - row - 1), 0.5 + row)))
            top.add_shape(Box(1, 1))
    y0 = top.position[1]
    for _ in range(600):
        w.step()
    return y0 - top.position[1]


def test_the_switch_keeps_a_pyramid_as_the_classic_pass_leaves_it():
    # boxes of one mass, no deep overlap: no step needs layers (position_layers.needs_layers), and
    # the pyramid of 20 rests exactly where the classic pass leaves it (28.38 mm down)
    assert pyramid_drop() == pyramid_drop(robust_positions=False)


def test_the_passes_visit_order_is_a_stable_sort_of_the_layer_keys():
    # the counting sort the layered passes order their contacts with gives numpy's stable
    # argsort exactly, ties in contact order
    import numpy as np

    from sandbox.position_layers import counting_order

    rng = np.random.default_rng(3)
    for size, top in ((0, 2), (1, 2), (50, 3), (1000, 41)):
        key = rng.integers(0, top, size)
        np.testing.assert_array_equal(counting_order(key, top), np.argsort(key, kind="stable"))
