"""What ``world.find_contacts()`` costs per contact, and how much of it is building the Python
:class:`sandbox.contact.Contact` objects from the contact records.

    python benchmarks/bench_contacts.py [--base 20 40]

A pyramid (``scenes.pyramid``) settles for 0.5 s; then ``world.find_contacts()`` (broadphase,
narrowphase and the objects) and :func:`sandbox.contact.contacts_from_manifolds` on the step's
own manifolds alone are timed, the best of 15 calls each (thread time), in microseconds per
contact. Lesson 08 calls ``find_contacts`` after every step to plot the deepest overlap.
"""

from __future__ import annotations

import argparse
import time

from sandbox import load_scene
from sandbox.contact import contacts_from_manifolds
from scenes import pyramid


def best_us(call, runs: int = 15) -> float:
    """The shortest thread time of ``runs`` calls of ``call`` (us)."""
    best = float("inf")
    for _ in range(runs):
        start = time.thread_time()
        call()
        best = min(best, time.thread_time() - start)
    return best * 1e6


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--base", type=int, nargs="+", default=[20, 40], help="pyramid bases")
    args = parser.parse_args()
    print("| pyramid base | contacts | find_contacts (us/contact) | objects alone (us/contact) |")
    print("|---|---|---|---|")
    for base in args.base:
        world = load_scene(pyramid(base))
        for _ in range(30):
            world.step()
        manifolds, bodies = world.manifolds, world.bodies
        n = len(world.find_contacts())
        found = best_us(world.find_contacts) / n
        objects = best_us(lambda m=manifolds, b=bodies: contacts_from_manifolds(m, b)) / len(
            manifolds
        )
        print(f"| {base} | {n} | {found:.1f} | {objects:.1f} |")


if __name__ == "__main__":
    main()
