"""``sandbox simulate SCENE.json``: run a scene, write a trace, a GIF, a PNG."""

from __future__ import annotations

import argparse

from sandbox.cli.common import check_output, load_spec, positive_float, positive_int
from sandbox.settings import CHOICES


def add_parser(sub) -> None:
    """The ``simulate`` command and its options."""
    sim = sub.add_parser("simulate", help="run a scene file")
    sim.add_argument("scene", metavar="SCENE.json")
    sim.add_argument("--steps", type=positive_int, default=300)
    sim.add_argument("--dt", type=positive_float, default=None)
    sim.add_argument("--engine", choices=("sandbox", "pymunk"), default="sandbox")
    sim.add_argument("--trace", metavar="OUT.csv")
    sim.add_argument("--gif", metavar="OUT.gif")
    sim.add_argument("--png", metavar="OUT.png")
    sim.add_argument("--fps", type=positive_float, default=30.0, help="GIF frames per second")
    for key, choices in CHOICES.items():
        sim.add_argument(f"--{key}", choices=choices, help=f"override settings.{key}")
    sim.add_argument("--iterations", type=positive_int, default=None)
    sim.set_defaults(func=run)


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
    spec = load_spec(args.scene, args)
    world = build_world(spec)
    want_frames = args.gif or args.png
    if args.engine == "pymunk":
        from sandbox.pymunk_bridge import run_pymunk

        rows = run_pymunk(spec, args.steps, spec["dt"])
    else:
        from sandbox.trace import run_world

        rows = list(run_world(world, args.steps))
    if want_frames:
        from sandbox.render import render_gif, render_png
        from sandbox.replay import recording_from_rows

        label = f"{args.engine}: {spec['name']}"
        if args.gif:
            every = max(1, round(1.0 / (spec["dt"] * args.fps)))
            rec = recording_from_rows(build_world(spec), rows, every=every)
            render_gif(rec, args.gif, fps=args.fps, labels=[label])
        if args.png:
            render_png(recording_from_rows(build_world(spec), rows), args.png)
    if args.trace:
        write_trace(rows, args.trace)
    last = rows[-len(world.bodies) :] if world.bodies else []
    print(f"{spec['name']}: {args.steps} steps of {spec['dt']:.6g} s with {args.engine}")
    for row in last:
        print(f"  {row[2]}: x={row[3]:.6g} y={row[4]:.6g} angle={row[5]:.6g}")
    return 0
