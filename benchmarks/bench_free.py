"""Free bodies, no collisions: the per-step cost of the world itself (integration and bookkeeping).

    python benchmarks/bench_free.py

Prints steps per second for a single ballistic body and for 1,000 free bodies (no shapes
touching: they are spread far apart and fall under gravity), for each integrator.
"""

from __future__ import annotations

import time

import sandbox


def free_world(n: int, integrator: str = "semi_implicit_euler") -> sandbox.World:
    """``n`` discs on a wide grid, far apart, thrown upwards; no two ever touch."""
    world = sandbox.World(gravity=(0.0, -9.81), dt=1.0 / 60.0, integrator=integrator)
    side = max(1, int(n**0.5))
    for i in range(n):
        body = world.add_body(
            sandbox.Body(
                f"b{i}",
                position=(10.0 * (i % side), 10.0 * (i // side)),
                velocity=(1.0, 5.0),
                angular_velocity=1.0,
            )
        )
        body.add_shape(sandbox.Circle(0.2))
    return world


def steps_per_second(world: sandbox.World, seconds: float = 1.0) -> float:
    """Step ``world`` for about ``seconds`` (after a warm-up) and return steps per second."""
    for _ in range(10):
        world.step()
    count, start = 0, time.perf_counter()
    while time.perf_counter() - start < seconds:
        for _ in range(20):
            world.step()
        count += 20
    return count / (time.perf_counter() - start)


def main() -> None:
    print(f"{'integrator':>20}  {'1 body (steps/s)':>17}  {'1000 bodies (steps/s)':>22}")
    for integrator in ("explicit_euler", "semi_implicit_euler", "verlet", "rk4"):
        one = steps_per_second(free_world(1, integrator))
        many = steps_per_second(free_world(1000, integrator))
        print(f"{integrator:>20}  {one:17.0f}  {many:22.0f}")


if __name__ == "__main__":
    main()
