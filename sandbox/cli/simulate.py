"""``sandbox simulate SCENE.json``: run a scene, write a trace, a GIF, a PNG.

The run streams: each step's rows go to the trace's temporary file as they are made, and the
GIF and PNG keep a bounded number of frames (:data:`sandbox.replay.MAX_FRAMES`; a longer run is
drawn every few steps, and the line saying the GIF was written says so), so memory stays flat
however many steps. All outputs are renamed into place together at the end, or none is.
"""

from __future__ import annotations

import argparse
import contextlib
import math

from sandbox import replay
from sandbox.cli.common import (
    MAX_STEPS,
    cache_note,
    check_output,
    fps_value,
    input_phase,
    load_spec,
    positive_float,
    positive_int,
    shown,
    steps_count,
)
from sandbox.settings import CHOICES


def add_parser(sub) -> None:
    """The ``simulate`` command and its options."""
    sim = sub.add_parser("simulate", help="run a scene file")
    sim.add_argument("scene", metavar="SCENE.json")
    sim.add_argument(
        "--steps", type=steps_count(MAX_STEPS), default=300, help=f"0 to {MAX_STEPS:,}"
    )
    sim.add_argument("--dt", type=positive_float, default=None)
    sim.add_argument("--engine", choices=("sandbox", "pymunk"), default="sandbox")
    sim.add_argument("--trace", metavar="OUT.csv")
    sim.add_argument("--gif", metavar="OUT.gif")
    sim.add_argument("--png", metavar="OUT.png")
    sim.add_argument(
        "--fps", type=fps_value, default=30.0, help="GIF frames per second (0.1 to 50)"
    )
    for key, choices in CHOICES.items():
        sim.add_argument(f"--{key}", choices=choices, help=f"override settings.{key}")
    sim.add_argument("--iterations", type=positive_int, default=None)
    sim.set_defaults(func=run)


def steps_per_frame(dt: float, fps: float, steps: int) -> int:
    """Steps of ``dt`` (s) between GIF frames shown ``1/fps`` s each (real time), in 1..steps+1."""
    per = 1.0 / (dt * fps) if dt * fps > 0 else math.inf
    if not per < steps + 1:
        return steps + 1
    return max(1, round(per))


def _world_steps(world, steps: int):
    """(step, t, rows) of this engine, step 0 (initial state) to ``steps``."""
    from sandbox.trace import world_rows

    yield 0, float(world.time), world_rows(world, 0)
    for k in range(1, steps + 1):
        world.step()
        yield k, float(world.time), world_rows(world, k)


def _pymunk_steps(scene, steps: int, dt: float):
    """(step, t, rows) of a :class:`~sandbox.pymunk_bridge.PymunkScene`."""
    for n in range(steps + 1):
        if n > 0:
            scene.step(dt)
        yield n, float(scene.time), [(n, scene.time, *row) for row in scene.state()]


def run(args: argparse.Namespace) -> int:
    """Run the scene and write what was asked for, as one set of files."""
    from sandbox.atomic import output_set
    from sandbox.build import build_world
    from sandbox.trace import TraceWriter, check_finite

    for option, path, suffix in (
        ("--trace", args.trace, ".csv"),
        ("--gif", args.gif, ".gif"),
        ("--png", args.png, ".png"),
    ):
        check_output(option, path, suffix)
    with input_phase():
        spec = load_spec(args.scene, args)
        world = build_world(spec)
        if args.engine == "pymunk":
            from sandbox.pymunk_bridge import PymunkScene

            steps = _pymunk_steps(PymunkScene.from_scene(spec), args.steps, spec["dt"])
        else:
            steps = _world_steps(world, args.steps)
    if args.engine == "sandbox":
        cache_note()
    dt, n = spec["dt"], len(world.bodies)
    natural = steps_per_frame(dt, args.fps, args.steps)
    limit, gif, png = replay.MAX_FRAMES, None, None  # frames kept, however long the run
    if args.gif:
        gif = replay.RowSampler(world, replay.frame_stride(args.steps, natural, limit))
    if args.png:  # the view of the picture fits the whole run; it shows the last step
        png = replay.RowSampler(world, replay.frame_stride(args.steps, 1, limit), keep_last=True)
    samplers = [s for s in (gif, png) if s is not None]
    written = []
    last: list = []
    with output_set(), contextlib.ExitStack() as stack:
        trace = stack.enter_context(TraceWriter(args.trace)) if args.trace else None
        for step, t, rows in steps:
            if trace is not None:
                trace.write(rows)  # refuses rows that are not finite
            else:
                check_finite(rows)  # a diverged run is reported, never drawn
            for sampler in samplers:
                sampler.add(step, t, rows)
            last = rows
        stack.close()  # the trace is complete (renamed with the rest at the end)
        if trace is not None:
            bodies = f"{n} bodies" if n != 1 else "1 body"
            written.append((args.trace, f"{trace.rows:,} rows: steps 0-{args.steps} of {bodies}"))
        if gif is not None or png is not None:
            from sandbox.render import render_gif, render_png

            if gif is not None:
                rec = gif.finish()
                render_gif(rec, args.gif, fps=args.fps, labels=[f"{args.engine}: {spec['name']}"])
                written.append((args.gif, _gif_note(len(rec), gif.every, natural, dt, args)))
            if png is not None:
                render_png(png.finish(), args.png)
                written.append((args.png, f"the state after step {args.steps}"))
    print(f"{shown(spec['name'])}: {args.steps} steps of {dt:.6g} s with {args.engine}")
    for row in last:
        print(f"  {shown(row[2])}: x={row[3]:.6g} y={row[4]:.6g} angle={row[5]:.6g}")
    for path, what in written:
        print(f"wrote {path} ({what})")
    return 0


def _gif_note(frames: int, every: int, natural: int, dt: float, args) -> str:
    """What the GIF holds; says so when a long run was drawn every few steps."""
    text = f"{frames:,} frames at {args.fps:g} fps"
    if every > natural:  # more steps than MAX_FRAMES frames at the asked rate can show
        speed = every * dt * args.fps
        text += (
            f", one every {every:,} steps to keep at most {replay.MAX_FRAMES} frames: "
            f"plays {speed:.3g} times faster than real time"
        )
    return text
