"""Sleeping islands: what a settled pile costs per step, against an awake one, here and in pymunk.

    python benchmarks/bench_sleep.py [--base 20]

A pyramid (``scenes.pyramid``) with ``settings.sleep: true`` settles for 6 s. The table gives
the mean thread time of a step while it is awake (its first second) and once settled, in two
worlds: the pyramid alone (everything sleeps: the world skips the step) and the pyramid with a
kinematic box turning far away (the step runs, over no awake island). pymunk runs the same
scenes with its own sleeping (``space.sleep_time_threshold``).
"""

from __future__ import annotations

import argparse
import time

from sandbox import load_scene
from sandbox.pymunk_bridge import PymunkScene
from scenes import pyramid

SPINNER = {
    "name": "spinner",
    "type": "kinematic",
    "position": [-30.0, 3.0],
    "angular_velocity": 1.0,
    "shapes": [{"type": "box", "width": 1.0, "height": 1.0}],
}


def mean_step_ms(step, steps: int) -> float:
    """Mean thread time of ``steps`` calls of ``step`` (ms)."""
    start = time.thread_time()
    for _ in range(steps):
        step()
    return (time.thread_time() - start) / steps * 1e3


def measure(scene: dict, engine: str) -> tuple[float, float, int, int]:
    """(awake ms, settled ms, bodies asleep after 6 s, dynamic bodies) for one engine."""
    if engine == "sandbox":
        world = load_scene(scene)
        step = world.step
    else:
        world = PymunkScene.from_scene(scene)
        step = world.step
    step()
    awake = mean_step_ms(step, 60)
    for _ in range(round(6.0 / scene["dt"])):
        step()
    settled = mean_step_ms(step, 300)
    if engine == "sandbox":
        asleep = int(world.sleeping.sum())
    else:
        asleep = sum(b.is_sleeping for b in world.bodies if b.body_type == b.DYNAMIC)
    dynamic = sum(1 for b in scene["bodies"] if b.get("type", "dynamic") == "dynamic")
    return awake, settled, asleep, dynamic


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--base", type=int, default=20, help="boxes in the bottom row")
    args = parser.parse_args()
    alone = pyramid(args.base)
    alone.setdefault("settings", {})["sleep"] = True
    alone.setdefault("dt", 1.0 / 60.0)
    spinning = {**alone, "bodies": [*alone["bodies"], SPINNER]}
    print(f"pyramid of base {args.base}, sleep on, settled for 6 s (thread time per step)\n")
    print("| world | engine | awake step (ms) | settled step (ms) | settled / awake | asleep |")
    print("|---|---|---|---|---|---|")
    for label, scene in (("pyramid alone", alone), ("pyramid + turning kinematic box", spinning)):
        for engine in ("sandbox", "pymunk"):
            awake, settled, asleep, dynamic = measure(scene, engine)
            print(
                f"| {label} | {engine} | {awake:.3f} | {settled:.4f} | {settled / awake:.3f} "
                f"| {asleep} of {dynamic} |"
            )


if __name__ == "__main__":
    main()
