"""The position passes stop once a pass stalls (``settings.position_stall``): it met more than
1 - position_stall of the overlap the pass before met (:func:`sandbox.penetration.fix_positions`).

A ball sunk in the ground is linear in its height: each pass leaves exactly 0.8 of the overlap
beyond the slop (1 - beta), so the second pass meets 0.8 of what the first met, a stall at
position_stall 0.25 and not at 0.15. A pile of discs its own load presses together is where the
rule acts at the default: each pass pushes every pair apart and the next pair pushes them
back."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

from sandbox import Body, Box, Circle, World
from sandbox.build import build_world
from sandbox.scene import validate_scene

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
import scenes  # noqa: E402  (benchmarks/scenes.py: the benchmark scenes as scene dicts)

DT = 1.0 / 60.0


@pytest.mark.parametrize("stall, passes", [(0.0, 3), (0.15, 3), (0.25, 2), (0.005, 3)])
def test_a_pass_that_takes_out_less_than_position_stall_is_the_last(stall, passes):
    w = World(gravity=(0.0, 0.0), dt=DT, robust_positions=False, position_tolerance=0.0)
    w.settings.position_stall = stall
    ground = w.add_body(Body(name="ground", type="static", position=(0.0, -0.5)))
    ground.add_shape(Box(10.0, 1.0))
    ball = w.add_body(Body(name="ball", position=(0.0, 0.4)))  # 0.1 m deep
    ball.add_shape(Circle(0.5))
    w.step()
    slop = w.settings.slop
    assert w.stats["position_passes"] == passes
    assert 0.5 - ball.position[1] - slop == pytest.approx((0.1 - slop) * 0.8**passes, rel=1e-9)


def mean_overlap(discs: list, r: float = 0.2) -> float:
    """The mean overlap of the discs that overlap (m)."""
    p = np.array([d.position for d in discs])
    gap = np.hypot(*(p[:, None, :] - p[None, :, :]).transpose(2, 0, 1)) - 2 * r
    over = -gap[np.triu_indices(len(p), 1)]
    return float(over[over > 0].mean())


def test_a_pile_its_load_presses_together_stops_after_two_passes():
    # 1,000 discs settle in about 100 steps; from then on every step of the default takes two
    # passes (the second one meets more than 99.5 % of what the first met) where
    # position_stall 0 takes all three, and the pile's mean overlap is within a tenth of it
    # (measured: 10.4 and 9.7 mm after 200 steps)
    runs = {}
    for stall in (0.005, 0.0):
        spec = scenes.rain(1000)
        spec["settings"]["position_stall"] = stall
        w = build_world(validate_scene(spec))
        discs = [b for b in w.bodies if b.type == "dynamic"]
        passes = []
        for _ in range(200):
            w.step()
            passes.append(w.stats["position_passes"])
        runs[stall] = (np.array(passes[150:]), mean_overlap(discs))
    assert np.all(runs[0.005][0] == 2), runs[0.005][0]
    assert np.all(runs[0.0][0] == 3), runs[0.0][0]
    assert runs[0.005][1] == pytest.approx(runs[0.0][1], rel=0.1)


def test_the_stats_give_what_the_pass_before_the_last_took_out():
    # the sunk ball: each pass takes out a fifth (beta) of the overlap beyond the slop; one
    # pass (within the tolerance) reports None
    w = World(gravity=(0.0, 0.0), dt=DT, robust_positions=False, position_tolerance=0.0)
    ground = w.add_body(Body(name="ground", type="static", position=(0.0, -0.5)))
    ground.add_shape(Box(10.0, 1.0))
    w.add_body(Body(name="ball", position=(0.0, 0.4))).add_shape(Circle(0.5))
    w.step()
    assert w.stats["position_passes"] == 3
    assert w.stats["position_progress"] == pytest.approx(0.2, abs=1e-4)  # whole micrometres
    w.settings.position_tolerance = 0.5
    w.step()
    assert w.stats["position_passes"] == 1
    assert w.stats["position_progress"] is None
