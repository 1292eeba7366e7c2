"""Every lesson runs as a notebook (jupytext -> ipynb, executed with a real kernel) and writes
its figures. Two lessons run at a time (one kernel each).

The kernels run with SANDBOX_CHECK_FIGURES set, so every figure a lesson saves through
``sandbox.lessonkit.save_figure`` is checked against the figure standard
(``sandbox.figure_standard``: title, labelled axes with units, legends, no legend over data)
and a figure that breaks it fails its lesson here, with the list of problems."""

import os
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import jupytext
import nbclient
import pytest

from sandbox import figure_standard

ROOT = Path(__file__).resolve().parent.parent
LESSONS = sorted((ROOT / "lessons").glob("[0-9][0-9]_*.py"))


def execute(lesson: Path, outputs: Path) -> str | None:
    """Run one lesson as a notebook; returns an error text or None."""
    nb = jupytext.read(lesson)
    nb.metadata["kernelspec"] = {
        "name": "python3",
        "display_name": "Python 3",
        "language": "python",
    }
    client = nbclient.NotebookClient(
        nb, timeout=600, kernel_name="python3", resources={"metadata": {"path": str(ROOT)}}
    )
    try:
        client.execute()
    except Exception as err:  # report the failing cell, not the thread's traceback
        return f"{lesson.name}: {type(err).__name__}: {str(err)[-2000:]}"
    return None


@pytest.fixture(scope="module")
def executed(tmp_path_factory):
    outputs = tmp_path_factory.mktemp("outputs")
    os.environ["SANDBOX_OUTPUTS"] = str(outputs)
    os.environ["MPLBACKEND"] = "Agg"
    os.environ[figure_standard.ENV] = "1"  # save_figure raises on a figure that breaks it
    try:
        with ThreadPoolExecutor(max_workers=2) as pool:
            errors = dict(
                zip(LESSONS, pool.map(lambda f: execute(f, outputs), LESSONS), strict=True)
            )
    finally:
        os.environ.pop("SANDBOX_OUTPUTS", None)
        os.environ.pop(figure_standard.ENV, None)
    return outputs, errors


def test_there_are_lessons():
    assert len(LESSONS) >= 3


@pytest.mark.parametrize("lesson", LESSONS, ids=[f.stem for f in LESSONS])
def test_lesson_runs_as_a_notebook_and_writes_figures(executed, lesson):
    outputs, errors = executed
    assert errors[lesson] is None, errors[lesson]
    folder = outputs / lesson.stem
    figures = [p for p in folder.glob("*") if p.suffix in (".png", ".gif")]
    assert figures, f"{lesson.stem} wrote no figure into {folder}"
    assert all(p.stat().st_size > 1000 for p in figures)
