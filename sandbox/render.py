"""Headless rendering of recordings to PNG and GIF files.

Frames are drawn by :class:`sandbox.frames.FrameRenderer` (matplotlib's Agg canvas, one collection
per run updated per frame); this module writes them: a PNG of one frame, or a looping GIF whose
frames all share one palette built once (Pillow, no dithering). Files are written whole or not
at all.
"""

from __future__ import annotations

import sys
from collections.abc import Iterator, Sequence
from pathlib import Path
from typing import Any

import numpy as np
from PIL import Image
from tqdm import tqdm

from sandbox.atomic import atomic_write
from sandbox.frames import (
    DEFAULT_COLORS,
    FILL_ALPHA,
    PROGRESS_FRAMES,
    STATIC_FACE,
    FrameRenderer,
    as_runs,
)
from sandbox.overlays import LAYERS, Layers
from sandbox.recording import (
    CircleOutline,
    Recording,
    record,
)

__all__ = [
    "DEFAULT_COLORS",
    "FILL_ALPHA",
    "STATIC_FACE",
    "CircleOutline",
    "FrameRenderer",
    "LAYERS",
    "Layers",
    "Recording",
    "record",
    "render_frames",
    "render_gif",
    "render_png",
]


def render_frames(
    runs: Recording | Sequence[Recording],
    frames: Sequence[int] | None = None,
    progress: bool = False,
    **options: Any,
) -> Iterator[np.ndarray]:
    """RGB frames ``(height, width, 3)`` uint8 of ``runs`` (options as :class:`FrameRenderer`).

    ``frames``: the frame indices to draw (default all). The figure is built once and reused.
    """
    with FrameRenderer(runs, **options) as renderer:
        ks = range(renderer.n_frames) if frames is None else list(frames)
        show = progress and len(ks) > PROGRESS_FRAMES and sys.stderr.isatty()
        for k in tqdm(ks, unit="frame", leave=False, disable=not show):
            yield renderer.frame(k)


def _source_runs(source: Any, draw: Any = None) -> Recording | list[Recording]:
    """A Recording, a list of them, or a world (its current state as a one-frame Recording,
    with the data of the layers ``draw``)."""
    if isinstance(source, Recording):
        return source
    if isinstance(source, (list, tuple)):
        return as_runs(source)
    if hasattr(source, "bodies"):
        rec = Recording.from_world(source, Layers.of(draw).names)
        rec.capture(source)
        return rec
    raise TypeError(f"cannot render a {type(source).__name__}")


def render_png(
    source: Any,
    path: str | Path,
    frame: int = -1,
    size_px: int = 480,
    draw: str | Sequence[str] | Layers | None = None,
    **options: Any,
) -> Path:
    """Write frame ``frame`` of ``source`` (Recording(s) or a world's current state) as a PNG.

    ``draw``: debug-drawing layers over the bodies (``"contacts,normals,impulses"``; the
    recording must hold their data: ``record(..., draw=...)``). Options as
    :class:`FrameRenderer` (labels, colors, panel, trail, view, axes, ...). The file is
    written whole or not at all. Returns the path.
    """
    runs = _source_runs(source, draw)
    with FrameRenderer(runs, size_px=size_px, draw=draw, **options) as renderer:
        rgb = renderer.frame(frame)
    path = Path(path)
    with atomic_write(path, "wb") as f:
        Image.fromarray(rgb).save(f, format="PNG")
    return path


def render_gif(
    runs: Recording | Sequence[Recording],
    path: str | Path,
    fps: float = 30,
    size_px: int = 480,
    labels: Sequence[str] | None = None,
    colors: Sequence[Any] | None = None,
    panel: str | Sequence[str] | None = None,
    trail: bool | int = False,
    stride: int = 1,
    draw: str | Sequence[str] | Layers | None = None,
    **options: Any,
) -> Path:
    """Write ``runs`` (a Recording or a list, overlaid one colour per run) as a looping GIF.

    Every ``stride``-th frame is drawn and shown for ``1/fps`` s. ``labels`` name the runs in a
    legend; ``panel`` plots series beside the scene (``"energy-bars"``: the energy bars, from
    ``record(..., energy=True)``); ``draw`` names debug-drawing layers (``"contacts,impulses"``,
    recorded with ``record(..., draw=...)``) drawn over the bodies with a key below; more
    options as :class:`FrameRenderer`.
    All frames share one palette (built from the first frame and the run colours, no
    dithering); a frame identical to the one before is merged into it (longer duration). The
    file is written whole or not at all. Returns the path.
    """
    if fps <= 0 or stride < 1:
        raise ValueError(f"need fps > 0 and stride >= 1, got fps={fps}, stride={stride}")
    path = Path(path)
    renderer = FrameRenderer(
        runs,
        size_px=size_px,
        labels=labels,
        colors=colors,
        panel=panel,
        trail=trail,
        draw=draw,
        **options,
    )
    with renderer:
        ks = range(0, renderer.n_frames, stride)
        show = len(ks) > PROGRESS_FRAMES and sys.stderr.isatty()
        bar = tqdm(total=len(ks), desc=path.name, unit="frame", leave=False, disable=not show)
        first = renderer.frame(0)
        # the palette is built from the scene and panel, not the key: a frame that draws
        # nothing more than a plain one gets the same pixels
        scene = first[: first.shape[0] - renderer.key_px]
        palette = _palette(scene, renderer.palette_colors())

        def quantized(indices: Sequence[int]) -> Iterator[Image.Image]:
            for k in indices:
                yield renderer.image(k).quantize(palette=palette, dither=Image.Dither.NONE)
                bar.update()

        head = Image.fromarray(first).quantize(palette=palette, dither=Image.Dither.NONE)
        bar.update()
        try:
            with atomic_write(path, "wb") as f:
                head.save(
                    f,
                    format="GIF",
                    save_all=True,
                    append_images=quantized(ks[1:]),
                    duration=max(1, int(round(1000.0 / fps))),
                    loop=0,
                    optimize=False,
                )
        finally:
            bar.close()
    return path


def _palette(first: np.ndarray, colors: np.ndarray) -> Image.Image:
    """A 256-colour palette: the renderer's own colours exactly, the rest from the first frame.

    Pillow maps pixels to a palette through a coarse colour cache, so frame colours within a
    few levels of an exact colour are left out: white must stay white, not become 254.
    """
    colors = np.unique(colors, axis=0)[:128].astype(np.int16)
    rest = Image.fromarray(first).quantize(
        colors=256 - len(colors), method=Image.Quantize.FASTOCTREE
    )
    entries = np.asarray(rest.getpalette(), dtype=np.int16).reshape(-1, 3)[: 256 - len(colors)]
    near = np.abs(entries[:, None, :] - colors[None, :, :]).max(axis=2).min(axis=1) < 8
    table = np.concatenate([colors, entries[~near]]).astype(np.uint8).ravel()
    palette = Image.new("P", (1, 1))
    palette.putpalette(np.concatenate([table, np.zeros(768 - len(table), np.uint8)]).tolist())
    return palette
