"""What a lesson shows when it runs in a notebook kernel: its figures and animations, inline.

A lesson run as a script writes files and prints; the same lesson in a Jupyter kernel also shows
each figure (PNG) and animation (GIF, which plays) in the cell that made it. Nothing here imports
IPython unless a kernel is already running, so scripts never pay for it.

Each inline image carries the metadata ``{"sandbox_file": "<path relative to the lesson's output
folder>"}``, so that an HTML page written beside the files can link them instead of embedding.
"""

from __future__ import annotations

import base64
import os
import sys
from pathlib import Path

MIME = {".png": "image/png", ".gif": "image/gif"}
FILE_KEY = "sandbox_file"  # output metadata: the shown file, relative to the lesson folder


def in_kernel() -> bool:
    """True inside a running Jupyter kernel (not a plain script, not terminal IPython)."""
    ipython = sys.modules.get("IPython")
    if ipython is None:
        return False
    shell = ipython.get_ipython()
    return shell is not None and getattr(shell, "kernel", None) is not None


def image_bundle(data: bytes, suffix: str, label: str) -> dict:
    """A display bundle for an image: the image (base64) and a plain-text stand-in."""
    mime = MIME[suffix.lower()]
    return {mime: base64.b64encode(data).decode("ascii"), "text/plain": f"<{label}>"}


def show_file(path: str | os.PathLike, folder: Path | None = None) -> bool:
    """Show a PNG or GIF file inline when running in a kernel; returns whether it was shown.

    ``folder`` is the lesson's output folder: the metadata names the file relative to it.
    """
    path = Path(path)
    if not in_kernel() or path.suffix.lower() not in MIME:
        return False
    from IPython.display import display

    name = path.name
    if folder is not None:
        try:
            name = path.resolve().relative_to(folder.resolve()).as_posix()
        except ValueError:
            pass
    bundle = image_bundle(path.read_bytes(), path.suffix, name)
    display(bundle, raw=True, metadata={FILE_KEY: name})
    return True
