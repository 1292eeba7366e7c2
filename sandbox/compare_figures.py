"""The figures of :func:`sandbox.compare.compare`: the deviation from pymunk, the energy of
every run, and every run overlaid in one GIF."""

from __future__ import annotations

import math
import os
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from sandbox.atomic import atomic_write

if TYPE_CHECKING:
    from sandbox.compare import ComparisonResult

GIF_MAX_FRAMES = 150  # longer runs skip steps between frames
RUN_COLORS = ("C0", "C1", "C2", "C3", "C4", "C5", "C6", "C8", "C9")

ROUNDING = 1e-9  # m or rad: deviations below this are rounding, drawn on a linear scale
PER_BODY = 12  # a deviation figure draws one curve per body up to this many, else the largest


def save_figure(fig, path: Path) -> None:
    from sandbox.figure_standard import enforce

    enforce(fig, path.name)  # the lessons' figure standard, when SANDBOX_CHECK_FIGURES is set
    with atomic_write(path, "wb") as f:
        fig.savefig(f, format="png", dpi=100)


def deviation_figure(result: ComparisonResult, path: Path) -> None:
    """Deviation from pymunk against time: one curve per moving body when there are at most
    ``PER_BODY`` curves, else the largest over the bodies (one curve per run)."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(9, 6))
    axes = fig.subplots(2, 1, sharex=True)
    styles = ("-", "--", ":", "-.")
    labels = [r.label for r in result.runs if r.label != "pymunk"]
    per_body = 0 < len(result.moving) * len(labels) <= PER_BODY
    t = result.runs[0].times
    for ax, data, what in (
        (axes[0], result.position_deviation, "|p - p_pymunk| (m)"),
        (axes[1], result.angle_deviation, "|angle - angle_pymunk| (rad)"),
    ):
        peak = max((float(data[lab].max()) for lab in labels if data[lab].size), default=0.0)
        for k, lab in enumerate(labels):
            if not per_body:
                worst = data[lab].max(axis=1) if data[lab].size else np.zeros(len(t))
                name = f"largest of {len(result.moving)} bodies" + (f" ({lab})" if k else "")
                ax.plot(t, worst, styles[k % 4], color=f"C{k}", linewidth=1.0, label=name)
                continue
            for j, i in enumerate(result.moving):
                name = result.names[i] if len(labels) == 1 else f"{result.names[i]} ({lab})"
                ax.plot(
                    t, data[lab][:, j], styles[k % 4], color=f"C{j % 10}", linewidth=1.0, label=name
                )
        # log scale above ROUNDING, linear below: rounding differences (1e-14) show as 0, not as
        # data on a log axis reaching down to 1e-23
        ax.set_yscale("symlog", linthresh=ROUNDING)
        ax.set_ylim(0.0, max(2.0 * peak, 10.0 * ROUNDING))
        ax.set_ylabel(what)
        ax.grid(alpha=0.3)
        if ax.get_lines():
            for text in ax.legend(
                fontsize=7, loc="upper left", bbox_to_anchor=(1.0, 1.0)
            ).get_texts():
                text.set_parse_math(False)  # body names as typed, "$" and all
    axes[1].set_xlabel("t (s)")
    axes[0].set_title(
        f"{result.scene}: position deviation from pymunk (linear below {ROUNDING:g}: rounding)",
        parse_math=False,
    )
    axes[1].set_title("angle deviation from pymunk")
    fig.tight_layout()
    save_figure(fig, path)


def energy_figure(result: ComparisonResult, path: Path) -> None:
    from matplotlib.figure import Figure

    fig = Figure(figsize=(8, 4))
    ax = fig.subplots()
    for k, run in enumerate(result.runs):
        ax.plot(run.times, run.energy, color=RUN_COLORS[k % len(RUN_COLORS)], label=run.label)
    ax.set_xlabel("t (s)")
    ax.set_ylabel("kinetic + potential energy (J)")
    ax.set_title(f"{result.scene}: energy", parse_math=False)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    save_figure(fig, path)


def write_overlay_gif(
    result: ComparisonResult,
    spec: dict,
    path: str | os.PathLike,
    fps: float = 30.0,
    size_px: int = 480,
    max_frames: int = GIF_MAX_FRAMES,
    panel: bool = False,
    view: Sequence[float] | None = None,
) -> Path:
    """Every run of ``result`` overlaid in one GIF, one colour per run, with a legend.

    One frame per ``1 / fps`` s of simulated time (fewer when that would exceed ``max_frames``);
    ``panel`` adds the energy against time beside the scene; ``view`` ``(xmin, xmax, ymin, ymax)``
    in metres (default: everything in every frame).
    """
    from sandbox.build import build_world
    from sandbox.recording import Recording
    from sandbox.render import render_gif

    steps = len(result.runs[0].times) - 1
    every = max(1, round(1.0 / (result.dt * fps)), math.ceil((steps + 1) / max_frames))
    world = build_world(spec)
    recordings = []
    for run in result.runs:
        rec = Recording.from_world(world)
        for k in range(0, steps + 1, every):
            rec.add_frame(run.poses[k], run.times[k], energy=run.energy[k])
        recordings.append(rec)
    gif_fps = min(50.0, max(1.0, 1.0 / (every * result.dt)))
    return render_gif(
        recordings,
        path,
        fps=gif_fps,
        size_px=size_px,
        labels=[r.label for r in result.runs],
        colors=RUN_COLORS[: len(result.runs)],
        panel="energy" if panel else None,
        trail=len(result.moving) <= 12,  # each moving body's path so far
        title=result.scene,
        **({"view": tuple(view)} if view is not None else {}),
    )
