"""Rendering speed: frames per second of GIF output for many bodies (no physics).

A Recording is built by hand: ``n_bodies`` circles and boxes on known paths (each on its own
circle, turning at its own rate) above a static ground, then written as a GIF with
:func:`sandbox.render.render_gif`. The goal (``DESIGN.md``, Performance) is that rendering is never
the slow part of a lesson: at least 50 frames per second for 500 bodies at 480 px.

``--draw`` adds debug-drawing layers (the recording then holds made-up contacts, one under each
body, velocities and forces for them) and ``--panel energy-bars`` the energy panel, to see what
they cost; without them the recording holds no layer data.

    python benchmarks/bench_render.py [--bodies 500] [--frames 120] [--size 480]
                                      [--draw contacts,normals,impulses,velocities,...]
                                      [--panel energy-bars]
"""

from __future__ import annotations

import argparse
import math
import tempfile
import time
from pathlib import Path

import numpy as np

from sandbox.energy import ENERGY_SERIES
from sandbox.geometry import box_vertices
from sandbox.overlays import Overlays, parse_layers
from sandbox.recording import CircleOutline, Recording
from sandbox.render import FrameRenderer, render_gif

DT = 1.0 / 60.0


def orbit_recording(n_bodies: int = 500, frames: int = 120, draw: str = "") -> Recording:
    """``n_bodies`` bodies (even: circles, odd: boxes) on circular paths, plus a static ground.

    Body i sits on a grid, circles its grid point with radius 0.4 m at 1 + i % 5 rad/s and
    turns at (i % 7 - 3) rad/s: every pose is a closed form, nothing is simulated. With layers
    ``draw``, each frame also holds the velocities (closed form), a force and torque on each
    body, and a contact point under each body with impulses; and the energy series.
    """
    side = math.ceil(math.sqrt(n_bodies))
    names, types, outlines = ["ground"], ["static"], [[box_vertices(side * 1.5 + 2, 1.0)]]
    for i in range(n_bodies):
        names.append(f"b{i}")
        types.append("dynamic")
        shape = CircleOutline(np.zeros(2), 0.3) if i % 2 == 0 else box_vertices(0.6, 0.4)
        outlines.append([shape])
    rec = Recording(names, types, outlines, overlays=Overlays(layers=parse_layers(draw)))
    i = np.arange(n_bodies)
    home = 1.5 * np.stack([i % side - 0.5 * (side - 1), i // side + 1.0], axis=1)
    rate, spin = 1.0 + i % 5, (i % 7 - 3).astype(float)
    for k in range(frames):
        t = k * DT
        poses = np.zeros((n_bodies + 1, 3))
        poses[0] = (0.0, 0.0, 0.0)
        poses[1:, 0] = home[:, 0] + 0.4 * np.cos(rate * t + i)
        poses[1:, 1] = home[:, 1] + 0.4 * np.sin(rate * t + i)
        poses[1:, 2] = spin * t
        velocities = np.zeros((n_bodies + 1, 2))
        velocities[1:, 0] = -0.4 * rate * np.sin(rate * t + i)
        velocities[1:, 1] = 0.4 * rate * np.cos(rate * t + i)
        forces = np.zeros((n_bodies + 1, 3))
        forces[1:, :2] = 5.0 * velocities[1:]
        forces[1:, 2] = spin
        contacts = np.zeros((n_bodies, 7))
        contacts[:, 0:2] = poses[1:, :2] - (0.0, 0.3)
        contacts[:, 3] = 1.0  # normal (0, 1)
        contacts[:, 4] = 0.1 + 0.05 * np.sin(rate * t)  # N s
        contacts[:, 5] = 0.02 * np.cos(rate * t)
        overlay = {"contacts": contacts, "velocities": velocities, "forces": forces}
        ke = 0.5 * float(np.sum(velocities**2))
        energy = {name: 0.0 for name in ENERGY_SERIES}
        energy.update({"energy.kinetic_linear": ke, "energy.potential_gravity": 9.81 * k})
        rec.add_frame(poses, t, overlay=overlay, height=float(poses[1:, 1].mean()), **energy)
    return rec


def _gif_seconds(rec: Recording, size_px: int, **options) -> tuple[float, float]:
    """(wall, CPU) seconds of one whole GIF render into a temporary folder."""
    with tempfile.TemporaryDirectory() as folder:
        wall, cpu = time.perf_counter(), time.process_time()
        render_gif(rec, Path(folder) / "bench.gif", size_px=size_px, **options)
        return time.perf_counter() - wall, time.process_time() - cpu


def _draw_seconds(rec: Recording, size_px: int, **options) -> tuple[float, float]:
    """(wall, CPU) seconds of drawing every frame (pixels out of matplotlib, no encoding)."""
    with FrameRenderer(rec, size_px=size_px, **options) as renderer:
        wall, cpu = time.perf_counter(), time.process_time()
        for k in range(len(rec)):
            renderer.frame(k)
        return time.perf_counter() - wall, time.process_time() - cpu


def bench_render(n_bodies: int = 500, frames: int = 120, size_px: int = 480) -> float:
    """Frames per second (wall clock) of a whole GIF render: set-up, drawing, palette, encoding."""
    return frames / _gif_seconds(orbit_recording(n_bodies, frames), size_px)[0]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--bodies", type=int, default=500)
    parser.add_argument("--frames", type=int, default=120)
    parser.add_argument("--size", type=int, default=480)
    parser.add_argument("--repeat", type=int, default=3, help="best of this many runs")
    parser.add_argument("--draw", default="", help="debug layers, e.g. contacts,velocities")
    parser.add_argument("--panel", default=None, help="energy-bars")
    args = parser.parse_args()
    rec = orbit_recording(args.bodies, args.frames, args.draw)
    options = {"draw": args.draw or None, "panel": args.panel}
    extra = f", draw {args.draw}" if args.draw else ""
    extra += f", panel {args.panel}" if args.panel else ""
    print(
        f"render: {args.bodies} bodies, {args.frames} frames, {args.size} px{extra} "
        f"(best of {args.repeat})"
    )
    print("                 wall clock      CPU time   (frames/s; CPU time ~ an idle machine)")
    for label, timer in (("GIF output", _gif_seconds), ("drawing only", _draw_seconds)):
        runs = [timer(rec, args.size, **options) for _ in range(args.repeat)]
        wall, cpu = min(r[0] for r in runs), min(r[1] for r in runs)
        print(f"  {label:12s}  {args.frames / wall:9.1f}  {args.frames / cpu:12.1f}")
    print("  goal: GIF output >= 50 frames/s")


if __name__ == "__main__":
    main()
