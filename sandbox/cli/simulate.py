"""``sandbox simulate SCENE.json``: run a scene, write a trace, a GIF, a PNG."""

from __future__ import annotations

import argparse
import sys

from sandbox.cli.common import (
    DT,
    FPS,
    STEPS,
    CliError,
    add_settings_options,
    check_output,
    field_type,
    load_spec,
)
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


def run(args: argparse.Namespace) -> int:
    """Run the scene and write what was asked for."""
    from sandbox.build import build_world
    from sandbox.trace import write_trace

    for option, path, suffix in (
        ("--trace", args.trace, ".csv"),
        ("--gif", args.gif, ".gif"),
        ("--png", args.png, ".png"),
    ):
        check_output(option, path, suffix)
    layers, panel = check_drawing(args)
    spec = load_spec(args.scene, args)
    world = build_world(spec)
    want_frames = bool(args.gif or args.png)
    energy = panel == "energy-bars"
    # the GIF shows every `stride`-th step; a PNG shows the last step, so all are kept for it
    stride = max(1, round(1.0 / (spec["dt"] * args.fps)))
    every = 1 if args.png else stride
    if args.engine == "pymunk":
        from sandbox.pymunk_bridge import run_pymunk
        from sandbox.replay import recording_from_rows

        rows = run_pymunk(spec, args.steps, spec["dt"])
        note = pymunk_note(spec)  # after the run: a scene pymunk cannot express is one error line
        if note:
            print(note, file=sys.stderr)
        if want_frames:
            rec = recording_from_rows(build_world(spec), rows, every, layers, energy)
    else:
        from sandbox.recording import Recorder
        from sandbox.trace import run_world

        on_step = None
        if want_frames:  # recorded while it runs: contacts, forces and energies of each step
            recorder = Recorder(world, every, draw=layers, energy=energy)
            on_step = recorder.step_done
            rec = recorder.recording
        rows = list(run_world(world, args.steps, on_step=on_step))
    if want_frames:
        from sandbox.render import render_gif, render_png

        label = f"{args.engine}: {spec['name']}"
        if args.gif:
            options = {"draw": layers, "panel": panel, "stride": stride // every}
            render_gif(rec, args.gif, fps=args.fps, labels=[label], **options)
        if args.png:
            render_png(rec, args.png, draw=layers, panel=panel)
    if args.trace:
        write_trace(rows, args.trace)
    last = rows[-len(world.bodies) :] if world.bodies else []
    print(f"{spec['name']}: {args.steps} steps of {spec['dt']:.6g} s with {args.engine}")
    for row in last:
        print(f"  {row[2]}: x={row[3]:.6g} y={row[4]:.6g} angle={row[5]:.6g}")
    return 0
