"""This engine and pymunk side by side on one scene: traces, an overlaid animation, deviations.

``compare(spec, steps, out_dir)`` runs a scene in this engine and in pymunk (same dt, gravity and
solver iterations, built from the same scene dict by :mod:`sandbox.pymunk_bridge`), plus one more
run of this engine per variant setting (``variants={"solver": ["pairwise"], "warm_start":
[False]}``: any world setting), and writes into
``out_dir``:

- ``trace_sandbox.csv``, ``trace_pymunk.csv``, ``trace_<key>_<value>.csv`` per variant
  (``step,t,body,x,y,angle,vx,vy,omega``, see :mod:`sandbox.trace`)
- ``overlay.gif``: every run overlaid, one colour per engine or variant, with a legend
- ``deviation.png``: |p_run - p_pymunk| (m, body origin) and |theta_run - theta_pymunk| (rad)
  against time, one line per moving body
- ``energy.png``: kinetic + potential energy (J) of every run against time
- ``summary.txt``: the table printed at the end of the run

Energy of a pymunk run is computed from its bodies the way :meth:`sandbox.world.World.energy`
does: sum over dynamic bodies of m |v|^2 / 2 + I omega^2 / 2 - m g . c (c the centre of mass),
plus k (d - L)^2 / 2 for every damped spring.

Everything is simulated before anything is written: a scene pymunk cannot express raises
:class:`~sandbox.pymunk_bridge.BridgeError` (a ValueError with ``.path``) and a bad variant raises
ValueError, leaving ``out_dir`` untouched. The files are written as one set: all of them, or (on
any failure) none and no new folder (:func:`sandbox.atomic.output_set`).
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from sandbox.atomic import atomic_write_text, make_folder, output_set
from sandbox.compare_figures import (
    GIF_MAX_FRAMES,
    deviation_figure,
    energy_figure,
    write_overlay_gif,
)
from sandbox.settings import Settings

__all__ = ["ComparisonResult", "Run", "compare", "pymunk_energy", "run_pymunk_scene", "run_sandbox"]

VARIANT_KEYS = Settings.names()  # any world setting may vary


@dataclass
class Run:
    """One simulated run of the scene.

    ``label`` names it ("sandbox", "pymunk", "sandbox solver=pairwise"); ``overrides`` the settings
    changed from the scene's; ``times`` (T,) in s; ``poses`` (T, n, 3) ``[x, y, angle]`` of every
    body's origin; ``velocities`` (T, n, 3) ``[vx, vy, omega]``; ``energy`` (T,) kinetic + potential
    in J; ``rows`` the trace rows; ``slug`` the file-name part (``trace_<slug>.csv``).
    """

    label: str
    slug: str
    overrides: dict
    times: np.ndarray
    poses: np.ndarray
    velocities: np.ndarray
    energy: np.ndarray
    rows: list = field(repr=False)

    def track(self, body: int) -> np.ndarray:
        """``(T, 3)`` poses ``[x, y, angle]`` of body index ``body`` over the run."""
        return self.poses[:, body, :]


@dataclass
class ComparisonResult:
    """What :func:`compare` computed and wrote.

    ``runs``: this engine first, pymunk second, then the variants. ``names``: every body, scene
    order; ``moving``: indices of the non-static bodies. ``position_deviation[label]`` (T, m) and
    ``angle_deviation[label]`` (T, m): |run - pymunk| for each moving body (m, rad).
    ``table``: the printed summary; ``files``: what was written; ``notes``: the bridge's notes.
    """

    scene: str
    steps: int
    dt: float
    names: list[str]
    moving: list[int]
    runs: list[Run]
    position_deviation: dict[str, np.ndarray]
    angle_deviation: dict[str, np.ndarray]
    table: str = ""
    files: dict[str, Path] = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)

    def run(self, label: str) -> Run:
        """The run called ``label`` (KeyError if none)."""
        for r in self.runs:
            if r.label == label:
                return r
        raise KeyError(f"no run labelled {label!r} (have {[r.label for r in self.runs]})")

    def body_index(self, name: str) -> int:
        """Index of the body called ``name`` in every run's arrays."""
        return self.names.index(name)

    def max_position_deviation(self, label: str = "sandbox") -> float:
        """Largest |p_run - p_pymunk| over all moving bodies and steps (m)."""
        dev = self.position_deviation[label]
        return float(dev.max()) if dev.size else 0.0


# ---------------------------------------------------------------- running the engines


def pymunk_energy(scene) -> float:
    """Kinetic + potential energy (J) of a :class:`~sandbox.pymunk_bridge.PymunkScene`.

    sum over dynamic bodies of m |v|^2 / 2 + I omega^2 / 2 - m g . c, plus k (d - L)^2 / 2 per
    damped spring: the same terms as :meth:`sandbox.world.World.energy`.
    """
    import pymunk

    gx, gy = scene.space.gravity
    energy = 0.0
    for body in scene.bodies:
        if body.body_type != pymunk.Body.DYNAMIC:
            continue
        m = body.mass
        vx, vy = body.velocity
        c = body.local_to_world(body.center_of_gravity)
        energy += 0.5 * m * (vx * vx + vy * vy) - m * (gx * c.x + gy * c.y)
        if math.isfinite(body.moment):
            energy += 0.5 * body.moment * body.angular_velocity**2
    for joint in scene.space.constraints:
        if isinstance(joint, pymunk.DampedSpring):
            pa = joint.a.local_to_world(joint.anchor_a)
            pb = joint.b.local_to_world(joint.anchor_b)
            stretch = (pb - pa).length - joint.rest_length
            energy += 0.5 * joint.stiffness * stretch * stretch
    return energy


def _arrays(rows: Sequence[tuple], n: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Trace rows -> times (T,), poses (T, n, 3), velocities (T, n, 3)."""
    if n == 0:
        steps = sorted({r[0] for r in rows})
        return np.array(steps, dtype=float), np.zeros((len(steps), 0, 3)), np.zeros((0, 0, 3))
    data = np.array([r[3:9] for r in rows], dtype=float).reshape(-1, n, 6)
    times = np.array([rows[k * n][1] for k in range(len(data))], dtype=float)
    return times, np.ascontiguousarray(data[..., :3]), np.ascontiguousarray(data[..., 3:])


def run_sandbox(
    spec: dict,
    steps: int,
    label: str = "sandbox",
    overrides=None,
    on_step: Callable[[], None] | None = None,
) -> Run:
    """Run a validated scene dict in this engine for ``steps`` steps (energy recorded each step);
    ``on_step()``, if given, is called after each step."""
    from sandbox.build import build_world
    from sandbox.trace import run_world

    world = build_world(spec)
    energy = [world.energy()]

    def stepped(w) -> None:
        energy.append(w.energy())
        if on_step is not None:
            on_step()

    rows = list(run_world(world, steps, on_step=stepped))
    times, poses, vels = _arrays(rows, len(world.bodies))
    slug = "_".join(f"{k}_{_shown(v)}" for k, v in (overrides or {}).items()) or "sandbox"
    return Run(label, slug, dict(overrides or {}), times, poses, vels, np.array(energy), rows)


def run_pymunk_scene(scene, steps: int, on_step: Callable[[], None] | None = None) -> Run:
    """Run a built :class:`~sandbox.pymunk_bridge.PymunkScene` for ``steps`` steps;
    ``on_step()``, if given, is called after each step."""
    rows: list[tuple] = []
    energy = []
    for n in range(int(steps) + 1):
        if n > 0:
            scene.step()
            if on_step is not None:
                on_step()
        rows.extend((n, scene.time, *row) for row in scene.state())
        energy.append(pymunk_energy(scene))
    times, poses, vels = _arrays(rows, len(scene.bodies))
    return Run("pymunk", "pymunk", {}, times, poses, vels, np.array(energy), rows)


def _variant_specs(spec: dict, variants: Mapping[str, Sequence] | None) -> list[tuple[dict, dict]]:
    """(overrides, scene dict) per requested variant; values equal to the scene's are skipped.

    Any world setting may vary (``{"warm_start": [False]}``); each value is checked as a scene
    file's ``settings`` would be (ValueError naming ``variants.<key>``).
    """
    from sandbox.fieldspec import check_value
    from sandbox.scene import validate_scene
    from sandbox.settings import FIELDS, unknown_setting

    out: list[tuple[dict, dict]] = []
    seen = set()
    for key, values in (variants or {}).items():
        if key not in FIELDS:
            raise unknown_setting(key, f"variants.{key}")
        for value in values or ():
            value = check_value(FIELDS[key], value, f"variants.{key}")
            if spec["settings"].get(key, FIELDS[key].default) == value or (key, value) in seen:
                continue
            seen.add((key, value))
            changed = {**spec, "settings": {**spec["settings"], key: value}}
            out.append(({key: value}, validate_scene(changed)))
    return out


def _shown(value) -> str:
    """A setting's value as a label or file name shows it (``false``, not ``False``)."""
    return str(value).lower() if isinstance(value, bool) else str(value)


# ---------------------------------------------------------------- deviations and the table


def _deviations(run: Run, ref: Run, moving: list[int]) -> tuple[np.ndarray, np.ndarray]:
    """|p_run - p_ref| (T, m) in m and |wrap(theta_run - theta_ref)| (T, m) in rad."""
    d = run.poses[:, moving, :] - ref.poses[:, moving, :]
    pos = np.hypot(d[..., 0], d[..., 1])
    ang = np.abs(np.remainder(d[..., 2] + math.pi, 2.0 * math.pi) - math.pi)
    return pos, ang


def _table(result: ComparisonResult, spec: dict) -> str:
    from sandbox.lessonkit import format_table

    g = spec["gravity"]
    head = (
        f"compare {result.scene!r}: {result.steps} steps of dt = {result.dt:.6g} s, "
        f"iterations {spec['settings']['iterations']}, gravity ({g[0]:g}, {g[1]:g})"
    )
    rows = []
    for run in result.runs:
        if run.label == "pymunk":
            continue
        pos, ang = result.position_deviation[run.label], result.angle_deviation[run.label]
        for j, i in enumerate(result.moving):
            rows.append(
                [
                    run.label,
                    result.names[i],
                    f"{pos[:, j].max():.3e}",
                    f"{pos[-1, j]:.3e}",
                    f"{ang[:, j].max():.3e}",
                    f"{ang[-1, j]:.3e}",
                ]
            )
    deviation = format_table(
        ["run", "body", "max |dp| m", "final |dp| m", "max |dangle| rad", "final |dangle| rad"],
        rows,
    )
    energy_rows = [
        [r.label, f"{r.energy[0]:.6g}", f"{r.energy[-1]:.6g}", f"{r.energy[-1] - r.energy[0]:+.4g}"]
        for r in result.runs
    ]
    energy = format_table(["run", "initial E (J)", "final E (J)", "change (J)"], energy_rows)
    return (
        f"{head}\n\ndeviation from pymunk (body origin and angle, moving bodies)\n{deviation}\n\n"
        f"kinetic + potential energy\n{energy}\n"
    )


# ---------------------------------------------------------------- the comparison


def compare(
    spec: dict,
    steps: int,
    out_dir: str | os.PathLike | None,
    variants: Mapping[str, Sequence] | None = None,
    gif: bool = True,
    *,
    fps: float = 30.0,
    size_px: int = 480,
    max_frames: int = GIF_MAX_FRAMES,
    panel: bool = False,
    view: Sequence[float] | None = None,
    quiet: bool = False,
) -> ComparisonResult:
    """Run ``spec`` in this engine, in pymunk and per variant; write the outputs into ``out_dir``.

    ``spec``: a scene dict (validated again here); ``steps``: number of steps of the scene's dt;
    ``variants``: settings to overlay, e.g. ``{"solver": ["pairwise"], "integrator": ["rk4"]}``;
    ``gif``: write ``overlay.gif`` (``fps`` frames per simulated second, at most ``max_frames``,
    ``size_px`` high, ``panel`` adds the energy plot, ``view`` (xmin, xmax, ymin, ymax) in m).
    ``out_dir=None`` computes without writing. The table is printed unless ``quiet``, and on a
    terminal a bar of the runs' steps is drawn while they take more than a couple of seconds
    (:class:`~sandbox.step_bar.StepBar`). Raises BridgeError (scene not expressible in pymunk)
    or ValueError (bad variant) before anything is written.
    """
    from sandbox.pymunk_bridge import PymunkScene
    from sandbox.scene import validate_scene
    from sandbox.step_bar import StepBar

    spec = validate_scene(spec)
    steps = int(steps)
    if steps < 0:
        raise ValueError(f"steps: must be >= 0, got {steps}")
    scene = PymunkScene.from_scene(spec)  # BridgeError here, before anything runs or is written
    extra = _variant_specs(spec, variants)

    # every run's steps in one bar on a terminal, for a comparison of more than a few seconds
    with StepBar(steps * (2 + len(extra)), quiet=quiet) as bar:
        runs = [
            run_sandbox(spec, steps, on_step=bar.step),
            run_pymunk_scene(scene, steps, bar.step),
        ]
        for overrides, variant in extra:
            label = "sandbox " + " ".join(f"{k}={_shown(v)}" for k, v in overrides.items())
            runs.append(run_sandbox(variant, steps, label, overrides, bar.step))

    names = [b["name"] for b in spec["bodies"]]
    moving = [i for i, b in enumerate(spec["bodies"]) if b["type"] != "static"]
    pymunk_run = runs[1]
    pos_dev, ang_dev = {}, {}
    for run in runs:
        if run is not pymunk_run:
            pos_dev[run.label], ang_dev[run.label] = _deviations(run, pymunk_run, moving)
    result = ComparisonResult(
        scene=spec["name"],
        steps=steps,
        dt=spec["dt"],
        names=names,
        moving=moving,
        runs=runs,
        position_deviation=pos_dev,
        angle_deviation=ang_dev,
        notes=list(scene.notes),
    )
    result.table = _table(result, spec)
    if not quiet:
        print(result.table, end="")
    if out_dir is None:
        return result

    from sandbox.trace import write_trace

    out = Path(out_dir)
    with output_set():  # every file, or none (a folder created for them is removed again)
        make_folder(out)
        for run in runs:
            path = out / f"trace_{run.slug}.csv"
            write_trace(run.rows, path)
            result.files[path.stem] = path
        if gif:
            result.files["overlay"] = write_overlay_gif(
                result,
                spec,
                out / "overlay.gif",
                fps=fps,
                size_px=size_px,
                max_frames=max_frames,
                panel=panel,
                view=view,
            )
        deviation_figure(result, out / "deviation.png")
        energy_figure(result, out / "energy.png")
        result.files["deviation"] = out / "deviation.png"
        result.files["energy"] = out / "energy.png"
        notes = "".join(f"- {note}\n" for note in result.notes)
        atomic_write_text(out / "summary.txt", f"{result.table}\npymunk bridge notes\n{notes}")
        result.files["summary"] = out / "summary.txt"
    if not quiet:
        print(f"wrote {len(result.files)} files to {out}")
    return result
