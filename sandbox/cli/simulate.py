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
import sys

from sandbox import replay
from sandbox.cli.common import (
    DT,
    FPS,
    STEPS,
    CliError,
    add_settings_options,
    cache_note,
    check_output,
    field_type,
    input_phase,
    load_spec,
    shown,
)
from sandbox.cli.first_run import choose_engine_speed
from sandbox.settings import CHOICES, Settings

EXAMPLES = """examples:
  sandbox simulate scenes/drop.json --steps 240 --trace out.csv --gif out.gif
  sandbox simulate scenes/stack.json --set warm_start=false --set iterations=4 --png stack.png
  sandbox simulate scenes/pyramid.json --engine pymunk --trace pymunk.csv
  sandbox simulate scenes/incline.json --gif incline.gif --draw contacts,impulses --panel energy-bars
"""

PANELS = ("energy-bars",)


def add_parser(sub) -> None:
    """The ``simulate`` command and its options."""
    sim = sub.add_parser(
        "simulate",
        help="run a scene file",
        description="Run a scene file for a number of steps; write a trace, a GIF, a PNG.",
        epilog=EXAMPLES,
    )
    sim.add_argument("scene", metavar="SCENE.json", help="the scene file")
    sim.add_argument(
        "--steps",
        type=field_type(STEPS, "--steps"),
        default=STEPS.default,
        help=f"number of steps, {STEPS.range_text()}",
    )
    sim.add_argument(
        "--dt",
        type=field_type(DT, "--dt"),
        default=None,
        help=f"time step, {DT.range_text()} (default: the scene's dt)",
    )
    sim.add_argument(
        "--engine",
        choices=("sandbox", "pymunk"),
        default="sandbox",
        help="which engine runs the scene",
    )
    sim.add_argument(
        "--trace", metavar="OUT.csv", help="write step,t,body,x,y,angle,vx,vy,omega rows (CSV)"
    )
    sim.add_argument("--gif", metavar="OUT.gif", help="write an animation")
    sim.add_argument("--png", metavar="OUT.png", help="write the last frame")
    sim.add_argument(
        "--fps",
        type=field_type(FPS, "--fps"),
        default=FPS.default,
        help=f"GIF frames per simulated second, {FPS.range_text()}",
    )
    sim.add_argument(
        "--draw",
        metavar="LAYER,...",
        help="debug layers on the GIF/PNG: contacts, normals, impulses, forces, gravity, "
        "velocities, aabbs, com, joints, sleep (or all)",
    )
    sim.add_argument("--panel", metavar="PANEL", help="a panel beside the GIF/PNG: energy-bars")
    for key, choices in CHOICES.items():
        sim.add_argument(f"--{key}", choices=choices, help=f"override settings.{key}")
    iterations = Settings.spec("iterations")
    sim.add_argument(
        "--iterations",
        type=field_type(iterations, "--iterations"),
        default=None,
        help=f"override settings.iterations, {iterations.range_text()}",
    )
    add_settings_options(sim)
    sim.set_defaults(func=run)


def check_drawing(args: argparse.Namespace) -> tuple[tuple[str, ...], str | None]:
    """The ``--draw`` layers and the ``--panel``, checked before anything runs."""
    from sandbox.overlays import FROM_TRACE, LayerError, parse_layers

    layers: tuple[str, ...] = ()
    for option, value in (("--draw", args.draw), ("--panel", args.panel)):
        if value is not None and not (args.gif or args.png):
            raise CliError(option, "draws on an image: give --gif or --png as well")
    if args.draw is not None:
        try:
            layers = parse_layers(args.draw)
        except LayerError as err:
            raise CliError("--draw", err.message) from None
        refused = [name for name in layers if name not in FROM_TRACE]
        if args.engine == "pymunk" and refused:
            raise CliError(
                "--draw",
                f"layer {refused[0]!r} is not available with --engine pymunk: its trace holds "
                f"poses and velocities only (it draws {', '.join(FROM_TRACE)})",
            )
        if not layers:
            raise CliError("--draw", "expected a comma-separated list of layers, got nothing")
    if args.panel is not None and args.panel not in PANELS:
        raise CliError("--panel", f"unknown panel {args.panel!r} (known: {', '.join(PANELS)})")
    return layers, args.panel


def pymunk_note(spec: dict) -> str | None:
    """A one-line note naming each setting of ``spec`` pymunk cannot honour, or None."""
    from sandbox.settings import pymunk_ignores

    ignored = pymunk_ignores(spec["settings"])
    if not ignored:
        return None
    return (
        f"note: pymunk cannot honour {', '.join(ignored)} "
        "(the bridge uses only iterations, dt and gravity); they apply to --engine sandbox"
    )


def steps_per_frame(dt: float, fps: float, steps: int) -> int:
    """Steps of ``dt`` (s) between GIF frames shown ``1/fps`` s each (real time), in 1..steps+1."""
    per = 1.0 / (dt * fps) if dt * fps > 0 else math.inf
    if not per < steps + 1:
        return steps + 1
    return max(1, round(per))


def _world_steps(world, steps: int, recorders: list):
    """(step, t, rows) of this engine, step 0 (initial state) to ``steps``; ``recorders`` (each
    a :class:`~sandbox.recording.Recorder`) see every step as it is made."""
    from sandbox.trace import world_rows

    yield 0, float(world.time), world_rows(world, 0)
    for k in range(1, steps + 1):
        world.step()
        for recorder in recorders:
            recorder.step_done()
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

    for option, path, suffix in (
        ("--trace", args.trace, ".csv"),
        ("--gif", args.gif, ".gif"),
        ("--png", args.png, ".png"),
    ):
        check_output(option, path, suffix)
    layers, panel = check_drawing(args)
    with input_phase():
        spec = load_spec(args.scene, args)
        if args.engine == "sandbox":
            choose_engine_speed(spec, args.steps)
        from sandbox.build import build_world

        world = build_world(spec)
        scene = None
        if args.engine == "pymunk":
            from sandbox.pymunk_bridge import PymunkScene

            scene = PymunkScene.from_scene(spec)
    if scene is None:
        cache_note()
    dt, energy = spec["dt"], panel == "energy-bars"
    natural = steps_per_frame(dt, args.fps, args.steps)
    limit = replay.MAX_FRAMES  # frames kept, however long the run
    gif_every = replay.frame_stride(args.steps, natural, limit)
    png_every = replay.frame_stride(args.steps, 1, limit)  # the view fits the whole run
    frames = {}  # "gif"/"png": a Recorder (this engine) or a RowSampler (pymunk's rows)
    for kind, every in (("gif", gif_every), ("png", png_every)):
        if getattr(args, kind):
            frames[kind] = _frames(world, scene, every, kind == "png", layers, energy)
    if scene is None:
        steps = _world_steps(world, args.steps, list(frames.values()))
    else:
        steps = _pymunk_steps(scene, args.steps, dt)
    written = []
    with output_set():
        last, rows_written = _run(
            steps, args.steps, args.trace, list(frames.values()), scene is not None
        )
        if args.trace:
            written.append((args.trace, _trace_note(rows_written, args.steps, len(world.bodies))))
        if frames:
            from sandbox.render import render_gif, render_png

            recordings = {kind: _finish(frames[kind], args.steps, kind == "png") for kind in frames}
            if args.gif:
                rec = recordings["gif"]
                label = f"{args.engine}: {spec['name']}"
                render_gif(rec, args.gif, fps=args.fps, labels=[label], draw=layers, panel=panel)
                written.append((args.gif, _gif_note(len(rec), gif_every, natural, dt, args)))
            if args.png:
                render_png(recordings["png"], args.png, draw=layers, panel=panel)
                written.append((args.png, f"the state after step {args.steps}"))
    if scene is not None:
        note = pymunk_note(spec)  # after the run: a scene pymunk cannot express is one error line
        if note:
            print(note, file=sys.stderr)
    print(f"{shown(spec['name'])}: {args.steps} steps of {dt:.6g} s with {args.engine}")
    for row in last:
        print(f"  {shown(row[2])}: x={row[3]:.6g} y={row[4]:.6g} angle={row[5]:.6g}")
    for path, what in written:
        print(f"wrote {path} ({what})")
    return 0


def _frames(world, scene, every: int, keep_last: bool, layers, energy: bool):
    """What keeps the frames of one image: this engine's world is recorded as it runs (its
    contacts and forces too); pymunk's trace rows are sampled."""
    if scene is None:
        from sandbox.recording import Recorder

        return Recorder(world, every, draw=layers, energy=energy)
    return replay.RowSampler(world, every, keep_last=keep_last, draw=layers, energy=energy)


def _finish(frames, steps: int, keep_last: bool):
    """The recording; a picture of the end (``keep_last``) gets the final step even off the
    stride."""
    if isinstance(frames, replay.RowSampler):
        return frames.finish()
    if keep_last and steps % frames.every:
        frames.capture()
    return frames.recording


def _run(steps, total: int, trace_path, samplers: list, rows_sampled: bool) -> tuple[list, int]:
    """Step through ``steps`` (``total`` of them), streaming rows to the trace, with a bar of the
    steps on a terminal when the run takes more than a couple of seconds
    (:class:`~sandbox.step_bar.StepBar`); the last rows and the rows written."""
    from sandbox.step_bar import StepBar
    from sandbox.trace import TraceWriter, check_finite

    last: list = []
    with contextlib.ExitStack() as stack:
        trace = stack.enter_context(TraceWriter(trace_path)) if trace_path else None
        bar = stack.enter_context(StepBar(total))
        for step, t, rows in steps:
            if step > 0:  # step 0: the initial state
                bar.step()
            if trace is not None:
                trace.write(rows)  # refuses rows that are not finite
            else:
                check_finite(rows)  # a diverged run is reported, never drawn
            if rows_sampled:
                for sampler in samplers:
                    sampler.add(step, t, rows)
            last = rows
    return last, trace.rows if trace is not None else 0


def _trace_note(rows: int, steps: int, bodies: int) -> str:
    return f"{rows:,} rows: steps 0-{steps} of {bodies} bod{'y' if bodies == 1 else 'ies'}"


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
