"""Every lesson runs as a notebook, the way `sandbox lessons` runs it (jupytext -> ipynb, a fresh
kernel forked from one that imported the course's libraries, the HTML page), once for the
whole module, two at a time, the longest first (its own schedule). Then: each writes figures,
shows every figure and animation inline in the cell that made it, shows each table once (and
saves it to tables.md), its explorer cell executes, and the course book's links all resolve.

The kernels run with SANDBOX_CHECK_FIGURES set, so every figure a lesson saves through
``sandbox.lessonkit.save_figure`` is checked against the figure standard
(``sandbox.figure_standard``: title, labelled axes with units, legends, no legend over data)
and a figure that breaks it fails its lesson here, with the list of problems."""

import base64
import os
import re
import subprocess
import sys
import tempfile
from concurrent.futures import wait
from pathlib import Path

import nbformat
import pytest

from sandbox import compile_cache, figure_standard
from sandbox.cli.lessons import Schedule
from sandbox.course.book import write_book
from sandbox.course.catalogue import find_lessons
from sandbox.course.links import book_problems
from sandbox.course.runner import kernels, run_notebook
from sandbox.explorer import CONTROLS_KEY
from sandbox.notebook import FILE_KEY

ROOT = Path(__file__).resolve().parent.parent
LESSONS = find_lessons(ROOT / "lessons")
IDS = [lesson.stem for lesson in LESSONS]
EXPLORERS = ("01_projectile", "07_collision_response", "09_stacking", "10_friction")
SEPARATOR = re.compile(r"^-+(  -+)*$", re.M)  # the dashed line under a printed table's header
IMAGES = ("image/png", "image/gif")


WARM_BEFORE = {}  # whether `sandbox warmup` had compiled every kernel before the lessons ran


@pytest.fixture(scope="module")
def course(tmp_path_factory):
    outputs = tmp_path_factory.mktemp("outputs")
    WARM_BEFORE["cache"] = compile_cache.is_warm()
    os.environ[figure_standard.ENV] = "1"  # save_figure raises on a figure that breaks it
    try:
        engine = WARM_BEFORE["cache"]  # as `sandbox lessons`: the steps loaded once, if compiled
        with tempfile.TemporaryDirectory() as tmp, kernels(Path(tmp), outputs, engine) as specs:
            logs = Path(tmp) / "compiles"  # as `sandbox lessons`: compiles counted, not shown
            logs.mkdir()
            run = lambda lesson: run_notebook(lesson, outputs, specs, logs)  # noqa: E731
            schedule = Schedule(LESSONS, run, 2)  # longest first, as `sandbox lessons`
            schedule.open(early=True, late=True)
            futures = [schedule.results[lesson.stem] for lesson in LESSONS]
            wait(futures)  # every lesson done before the kernels stop, even if one raised
            outcomes = [future.result() for future in futures]
    finally:
        os.environ.pop(figure_standard.ENV, None)
    write_book(LESSONS, outputs)
    return outputs, {o.lesson.stem: o for o in outcomes}


def notebook(outputs: Path, stem: str):
    return nbformat.read(outputs / stem / f"{stem}.ipynb", as_version=4)


def code_outputs(nb):
    for cell in nb.cells:
        if cell.cell_type == "code":
            for output in cell.outputs:
                yield cell, output


def test_there_are_lessons():
    assert len(LESSONS) >= 3
    assert len({lesson.number for lesson in LESSONS}) == len(LESSONS)


@pytest.mark.parametrize("stem", IDS)
def test_lesson_runs_as_a_notebook_and_writes_figures(course, stem):
    outputs, outcomes = course
    assert outcomes[stem].ok, outcomes[stem].error
    folder = outputs / stem
    figures = [p for p in folder.rglob("*") if p.suffix in (".png", ".gif")]
    assert figures, f"{stem} wrote no figure into {folder}"
    assert all(p.stat().st_size > 1000 for p in figures)
    assert (folder / f"{stem}.ipynb").exists() and (folder / f"{stem}.html").exists()


@pytest.mark.parametrize("stem", IDS)
def test_after_the_warmup_no_lesson_compiles(course, stem):
    # `sandbox warmup` compiles every kernel lessons call, also those they call on their own
    # (a kernel called from a lesson with other argument types is compiled again: lesson 09's
    # colouring was, before the warmup took it); counted in the lesson's compile log
    outputs, outcomes = course
    if not WARM_BEFORE["cache"]:
        pytest.skip("the compile cache was not warm when the lessons ran (no `sandbox warmup`)")
    assert outcomes[stem].compiled == 0, f"{stem} compiled {outcomes[stem].compiled} kernels"


@pytest.mark.parametrize("stem", IDS)
def test_no_page_shows_the_compile_notice(course, stem):
    # compiled or not, the notice goes to the compile log, and the page shows the lesson only
    outputs, _ = course
    for cell, output in code_outputs(notebook(outputs, stem)):
        text = output.get("text", "") if output.output_type == "stream" else ""
        assert "compiling the engine" not in text, f"{stem}: notice in\n{cell.source[:300]}"


@pytest.mark.parametrize("stem", ["01_projectile", "07_collision_response", "16_soft_step"])
def test_page_is_nbconverts_page(course, stem, monkeypatch):
    # the page's exporter leaves out nbconvert's sanitizing of highlighted code and its reparse
    # of the page (sandbox.course.exporter): the same page once both are read as HTML, the
    # focusable areas included (formulas left as placeholders, which the reparse would rewrite)
    from bs4 import BeautifulSoup
    from nbconvert import HTMLExporter

    from sandbox.course import exporter, page

    outputs, _ = course
    nb, folder = notebook(outputs, stem), outputs / stem
    monkeypatch.setattr(page, "restore_math", lambda body, fragments: body)
    ours = page.render_page(nb, folder, stem)
    monkeypatch.setattr(exporter, "LessonPageExporter", HTMLExporter)
    theirs = page.render_page(nb, folder, stem)
    assert 'tabindex="0"' in theirs
    assert str(BeautifulSoup(ours, "html.parser")) == theirs


@pytest.mark.parametrize("stem", IDS)
def test_every_figure_and_animation_is_shown_inline(course, stem):
    outputs, _ = course
    folder = outputs / stem
    shown = {}
    for _, output in code_outputs(notebook(outputs, stem)):
        for mime in IMAGES:
            if mime in output.get("data", {}):
                name = output.metadata[FILE_KEY]
                shown[name] = base64.b64decode(output.data[mime])
    assert shown, f"{stem}: no inline image"
    made = {
        p.relative_to(folder).as_posix() for p in folder.rglob("*") if p.suffix in (".png", ".gif")
    }
    assert made == set(shown), f"{stem}: files not shown inline: {sorted(made - set(shown))}"
    for name, data in shown.items():  # inline is the very file, and a GIF stays a GIF
        assert data == (folder / name).read_bytes(), name


@pytest.mark.parametrize("stem", IDS)
def test_each_table_is_shown_once_and_saved(course, stem):
    outputs, _ = course
    printed = 0
    for cell, output in code_outputs(notebook(outputs, stem)):
        if output.output_type == "stream":
            printed += len(SEPARATOR.findall(output.text))
        else:  # a table echoed as the cell's value, or displayed again
            text = output.get("data", {}).get("text/plain", "")
            assert not SEPARATOR.search(text), f"{stem}: a table shown twice in\n{cell.source}"
    tables = outputs / stem / "tables.md"
    saved = tables.read_text().count("\nTable ") if tables.exists() else 0
    assert printed == saved, f"{stem}: {printed} tables printed, {saved} in tables.md"


@pytest.mark.parametrize("stem", EXPLORERS)
def test_explorer_cell_executes_with_its_defaults(course, stem):
    outputs, _ = course
    cells = [c for c in notebook(outputs, stem).cells if "explore(" in c.get("source", "")]
    assert cells, f"{stem} has no explorer cell"
    (output,) = [o for o in cells[-1].outputs if "image/png" in o.get("data", {})]
    name = output.metadata[FILE_KEY]
    assert name.startswith("explore_") and (outputs / stem / name).exists()
    pytest.importorskip("ipywidgets")
    # the live controls were built (the saved notebook keeps the figure: the widget needs a kernel)
    assert len(output.metadata[CONTROLS_KEY]) >= 2


def test_a_lesson_run_uncompiled_writes_what_it_writes_compiled(course, tmp_path):
    # on a new machine the lessons that take seconds uncompiled run so (sandbox.cli.lessons.
    # plain_first): the files they write must be those they write compiled, to the byte. Lesson
    # 13 steps contacts, joints and force fields (the kernels only such lessons need); its
    # tables print 4 decimals, its figures and animation draw the bodies where they are
    outputs, _ = course
    stem = "13_user_and_agent_input"
    env = {**os.environ, "SANDBOX_JIT": "0"}
    cmd = [sys.executable, "-m", "sandbox", "lessons", "13", "--scripts", "--out", str(tmp_path)]
    done = subprocess.run(cmd, env=env, capture_output=True, text=True)
    assert done.returncode == 0, done.stdout + done.stderr
    plain = {p.name: p.read_bytes() for p in (tmp_path / stem).iterdir()}
    compiled = {name: (outputs / stem / name).read_bytes() for name in plain}
    assert "tables.md" in plain and any(name.endswith(".gif") for name in plain)
    assert plain == compiled


def test_course_book_links_and_images_resolve_offline(course):
    outputs, _ = course
    index = outputs / "index.html"
    text = index.read_text()
    assert book_problems(index) == []
    for stem in IDS:
        for link in (f"{stem}/{stem}.html", f"{stem}/{stem}.ipynb", f"{stem}/tables.md"):
            if (outputs / link).exists():
                assert f'href="{link}"' in text, link
        assert f'<img src="{stem}/' in text, f"{stem}: no thumbnail"
