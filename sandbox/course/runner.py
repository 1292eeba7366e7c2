"""Running one lesson into ``<outputs>/<lesson>/``: as an executed notebook (jupytext converts,
nbclient executes in a fresh kernel, nbconvert renders the page) when the notebook tools are
installed, else as a plain script. Either way its figures, animations and ``tables.md`` land in
the lesson's folder.
"""

from __future__ import annotations

import importlib.util
import os
import subprocess
import sys
import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path

from sandbox.compile_cache import COMPILE_LOG
from sandbox.course.catalogue import Lesson
from sandbox.course.page import WIDGET_VIEW

NOTEBOOK_TOOLS = ("jupytext", "nbformat", "nbclient", "ipykernel", "nbconvert")
INSTALL_HINT = "pip install 'physics-sandbox[notebook]'"
MADE = (".png", ".gif", ".md", ".ipynb", ".html", ".txt", ".csv", ".json")  # what lessons write
CELL_TIMEOUT = 600  # s, one cell of one lesson
_stopping: list[threading.Thread] = []  # kernels being stopped (joined when kernels() ends)


@dataclass
class Outcome:
    """What running one lesson gave: ``error`` is one line, or "" when it ran through."""

    lesson: Lesson
    seconds: float
    error: str = ""
    written: list[Path] = field(default_factory=list)  # the notebook and its page, if made
    compiled: int = 0  # kernels the lesson compiled (counted when run with a compile log)

    @property
    def ok(self) -> bool:
        return not self.error


def missing_notebook_tools() -> list[str]:
    """The notebook tools that are not installed (executing and rendering need all of them)."""
    return [name for name in NOTEBOOK_TOOLS if importlib.util.find_spec(name) is None]


def lesson_env(outputs: Path, log: Path | None = None) -> dict[str, str]:
    """Environment of a lesson's process: where to write, Agg, no stray warnings; with ``log``,
    each kernel the lesson compiles is a line in that file rather than a notice in its output
    (:data:`sandbox.compile_cache.COMPILE_LOG`; :func:`compiled_in` counts them)."""
    env = {**os.environ, "SANDBOX_OUTPUTS": str(outputs), "MPLBACKEND": "Agg"}
    env["PYDEVD_DISABLE_FILE_VALIDATION"] = "1"  # the kernel's debugger warns on stderr otherwise
    env["JUPYTER_PLATFORM_DIRS"] = "1"
    env.pop(COMPILE_LOG, None)
    if log is not None:
        env[COMPILE_LOG] = str(log)
    return env


def compile_log(logs: Path | None, lesson: Lesson) -> Path | None:
    """The file in the folder ``logs`` where the lesson's compiles are written (emptied), or
    None without a folder."""
    if logs is None:
        return None
    log = logs / f"{lesson.stem}.compiles"
    log.unlink(missing_ok=True)
    return log


def compiled_in(log: Path | None) -> int:
    """How many kernels were compiled into ``log`` (0 without one)."""
    if log is None or not log.exists():
        return 0
    return len(log.read_text(encoding="utf-8").splitlines())


def clear_folder(folder: Path) -> None:
    """Remove what an earlier run of the lesson wrote there (its kinds of file only)."""
    if not folder.is_dir():
        return
    for path in sorted(folder.rglob("*"), reverse=True):
        if path.is_file() and path.suffix.lower() in MADE:
            path.unlink()
        elif path.is_dir() and not any(path.iterdir()):
            path.rmdir()


def run_script(lesson: Lesson, outputs: Path, logs: Path | None = None) -> Outcome:
    """Run the lesson as ``python NN_name.py``; its printed output is kept from the console
    (the tables are in ``tables.md``) and shown only when it fails. With ``logs`` (a folder),
    the kernels it compiles are counted there (:func:`compile_log`), not announced."""
    folder = outputs / lesson.stem
    clear_folder(folder)
    folder.mkdir(parents=True, exist_ok=True)
    log = compile_log(logs, lesson)
    start = time.perf_counter()
    result = subprocess.run(
        [sys.executable, str(lesson.path)],
        cwd=folder,
        env=lesson_env(outputs, log),
        capture_output=True,
        text=True,
    )
    error = ""
    if result.returncode:
        tail = (result.stderr or result.stdout).strip().splitlines()
        error = f"exit status {result.returncode}: {tail[-1] if tail else 'no output'}"
    return Outcome(lesson, time.perf_counter() - start, error, compiled=compiled_in(log))


def kernel_specs(folder: Path) -> Path:
    """A kernel spec ``python3`` for this very interpreter, written under ``folder``.

    Using it (rather than whatever ``python3`` kernel Jupyter finds first on the machine) makes
    every lesson run with the same ``sandbox`` as the command that runs it.
    """
    from ipykernel.kernelspec import write_kernel_spec

    specs = folder / "kernels"
    if not (specs / "python3" / "kernel.json").exists():
        write_kernel_spec(str(specs / "python3"))
    return specs


@contextmanager
def kernels(folder: Path, outputs: Path, engine: bool = False) -> Iterator[Path]:
    """Kernel specs under ``folder`` for executing lessons that write into ``outputs``, while
    the ``with`` block lasts: kernels forked from one process that has imported the course's
    libraries (:mod:`sandbox.course.prefork`) on Linux, else ordinary kernels
    (:func:`kernel_specs`); ``engine``: the engine's compiled steps are in the cache, and the
    forked kernels start with them loaded (:func:`sandbox.course.prefork.load_engine`). Start
    it after setting anything in the environment the lessons should see: the forking process
    takes the environment it starts with."""
    from sandbox.course import prefork

    try:
        if not prefork.available():
            yield kernel_specs(folder)
            return
        address = server_address(folder)
        with prefork.Server(address, lesson_env(outputs), engine):
            yield prefork.write_spec(folder / "kernels", address)
    finally:
        while _stopping:  # every kernel the lessons ran in has exited
            _stopping.pop().join()


def server_address(folder: Path) -> Path:
    """Where the forking server of :func:`kernels` started in ``folder`` listens (its kernel
    specs are in ``folder / "kernels"``)."""
    return folder / "prefork"


def load_engine(specs: Path, early: bool = False) -> None:
    """Have the kernels of :func:`kernels` (``specs``, started with ``engine`` False) start with
    the compiled engine from now on, once what the lessons need is in the cache (``early``:
    all but the soft step's kernels; :func:`sandbox.course.prefork.request_engine`; nothing
    where kernels are not forked)."""
    from sandbox.course import prefork

    address = server_address(specs.parent)
    if prefork.available() and address.exists():
        prefork.request_engine(address, early=early)


def run_notebook(lesson: Lesson, outputs: Path, specs: Path, logs: Path | None = None) -> Outcome:
    """Execute the lesson as a notebook and write ``NN_name.ipynb`` and ``NN_name.html``.

    ``specs`` is the folder of :func:`kernels` (or :func:`kernel_specs`). A failing cell stops
    the run; the notebook and page are still written, showing the error where it happened.
    With ``logs`` (a folder), the kernels it compiles are counted there (:func:`compile_log`),
    and no compile notice lands in the notebook.
    """
    import jupytext
    import nbclient
    import nbformat
    from jupyter_client.kernelspec import KernelSpecManager
    from jupyter_client.manager import KernelManager

    from sandbox.atomic import atomic_write_text
    from sandbox.course.page import render_page

    folder = outputs / lesson.stem
    clear_folder(folder)
    folder.mkdir(parents=True, exist_ok=True)
    log = compile_log(logs, lesson)
    start = time.perf_counter()
    nb = jupytext.read(lesson.path)
    nb.metadata.pop("jupytext", None)
    for i, cell in enumerate(nb.cells):  # the same notebook on every run (jupytext draws ids)
        cell.id = f"cell-{i}"
    nb.metadata["kernelspec"] = {
        "name": "python3",
        "display_name": "Python 3",
        "language": "python",
    }
    manager = KernelManager(
        kernel_name="python3",
        kernel_spec_manager=KernelSpecManager(kernel_dirs=[str(specs)], ensure_native_kernel=False),
        client_class="sandbox.course.kernel_client.ReadyClient",  # ready sooner
    )
    if os.name == "posix":  # local sockets in the private folder rather than TCP ports
        manager.transport, manager.ip = "ipc", str(specs.parent / lesson.stem)
    client = nbclient.NotebookClient(
        nb,
        km=manager,
        timeout=CELL_TIMEOUT,
        record_timing=False,  # the same notebook on every run
        store_widget_state=False,  # an explorer's saved state would only repeat its figure
        resources={"metadata": {"path": str(folder)}},
    )
    error = ""
    try:
        client.execute(env=lesson_env(outputs, log))
    except nbclient.exceptions.CellExecutionError as err:
        error = _cell_error(err)
    except Exception as err:  # a kernel that died or timed out
        error = f"{type(err).__name__}: {' '.join(str(err).split())[:300]}"
    finally:
        if manager.has_kernel:  # stopped beside the next lesson (it waits 0.1 s for the exit)
            stopping = threading.Thread(target=manager.shutdown_kernel, kwargs={"now": True})
            stopping.start()
            _stopping.append(stopping)
    settle(nb)
    notebook = folder / f"{lesson.stem}.ipynb"
    atomic_write_text(notebook, nbformat.writes(nb) + "\n")
    written = [notebook]
    page = folder / f"{lesson.stem}.html"
    nav = {"course book": "../index.html", "notebook": notebook.name}
    if (folder / "tables.md").exists():
        nav["tables"] = "tables.md"
    try:
        atomic_write_text(page, render_page(nb, folder, lesson.title, nav))
        written.append(page)
    except Exception as err:  # the notebook is written; say why its page is not
        error = error or f"HTML page: {type(err).__name__}: {' '.join(str(err).split())[:300]}"
    return Outcome(lesson, time.perf_counter() - start, error, written, compiled_in(log))


def settle(nb) -> None:
    """Make an executed notebook the same on every run: a cell's printed output as one stream
    (the kernel splits it where its messages happened to be cut), and an explorer shown by its
    figure (its live widget cannot be shown once the kernel is gone; a rerun brings it back)."""
    for cell in nb.cells:
        merged: list = []
        for output in cell.get("outputs", []):
            last = merged[-1] if merged else None
            same = last is not None and last.output_type == "stream"
            if same and output.output_type == "stream" and last.name == output.name:
                last.text += output.text
                continue
            if output.get("data"):
                output.data.pop(WIDGET_VIEW, None)
            merged.append(output)
        if "outputs" in cell:
            cell.outputs = merged


def _cell_error(err: Exception) -> str:
    """One line for a failing cell: the exception's name and message."""
    name = getattr(err, "ename", "") or type(err).__name__
    value = getattr(err, "evalue", "") or str(err).strip().splitlines()[-1]
    return f"{name}: {' '.join(str(value).split())[:300]}"
