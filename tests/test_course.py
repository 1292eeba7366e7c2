"""The course around the engine: bundled scenes and lessons, picking lessons by name, tables
printed once and saved, the explorer's controls, formulas as MathML, the offline link check,
and `sandbox lessons` without the notebook tools."""

import json
from pathlib import Path

import matplotlib.pyplot as plt
import pytest

import sandbox
from sandbox import lessonkit
from sandbox.bundled import bundled_scene, lesson_files, scene_files
from sandbox.cli import main
from sandbox.course.catalogue import Lesson, find_lessons, pick, read_intro
from sandbox.course.links import book_problems, page_problems
from sandbox.course.markup import inline_html, protect_math, restore_math
from sandbox.explorer import Choice, Slider, Toggle, check_controls, figure_png

ROOT = Path(__file__).resolve().parent.parent


# --- bundled scenes ------------------------------------------------------------------------------
def test_bundled_folders_are_the_checkouts():
    # an editable install maps sandbox.scenes / sandbox.lessons onto the top-level folders
    assert [p.name for p in scene_files()] == sorted(
        p.name for p in (ROOT / "scenes").glob("*.json")
    )
    assert [p.name for p in lesson_files()] == sorted(
        p.name for p in (ROOT / "lessons").glob("[0-9][0-9]_*.py")
    )


def test_load_scene_and_simulate_take_a_bundled_name_from_an_empty_folder(
    tmp_path, monkeypatch, capsys
):
    monkeypatch.chdir(tmp_path)
    world = sandbox.load_scene("drop")
    ref = sandbox.load_scene(ROOT / "scenes" / "drop.json")
    assert [b.name for b in world.bodies] == [b.name for b in ref.bodies] == ["ground", "ball"]
    assert world.body("ball").position == ref.body("ball").position
    assert bundled_scene("drop.json") == bundled_scene("drop") and bundled_scene("../drop") is None
    assert main(["simulate", "drop", "--steps", "3", "--trace", "t.csv"]) == 0
    out = capsys.readouterr().out.splitlines()
    assert out[0] == "drop: no such file here; using the bundled example scene drop.json"
    assert (tmp_path / "t.csv").read_text().count("\n") == 1 + 4 * 2  # header, 4 states x 2 bodies


def test_a_file_in_the_working_folder_wins_over_the_bundled_scene(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    spec = json.loads((ROOT / "scenes" / "drop.json").read_text())
    spec["bodies"][1]["position"] = [0, 3]
    (tmp_path / "drop").write_text(json.dumps(spec))
    assert sandbox.load_scene("drop").body("ball").position == (0, 3)
    assert main(["simulate", "drop", "--steps", "1"]) == 0
    assert "bundled" not in capsys.readouterr().out


def test_a_mistyped_scene_name_points_to_the_bundled_scenes(tmp_path, monkeypatch, capsys):
    # one line, exit 2, nothing written: the closest bundled scene when one is close
    monkeypatch.chdir(tmp_path)
    for name, hint in (
        ("pyramd", "(did you mean the bundled scene pyramid? `sandbox scenes` lists"),
        ("pyramd.json", "(did you mean the bundled scene pyramid?"),
        ("nothing_like_it", "(`sandbox scenes` lists the bundled example scenes)"),
    ):
        assert main(["simulate", name, "--trace", "t.csv"]) == 2
        err = capsys.readouterr().err
        assert err.startswith(f"error: file: cannot read '{name}': no such file {hint}"), err
        assert err.count("\n") == 1 and not (tmp_path / "t.csv").exists()
    assert main(["simulate", "sub/pyramd.json"]) == 2  # a path: only that it is not there
    assert capsys.readouterr().err == "error: file: cannot read 'sub/pyramd.json': no such file\n"


def test_scenes_help_has_examples(capsys):
    assert main(["scenes", "--help"]) == 0
    assert "examples:\n  sandbox scenes" in capsys.readouterr().out


def test_scenes_lists_every_bundled_scene_with_one_line(capsys):
    assert main(["scenes"]) == 0
    lines = capsys.readouterr().out.splitlines()
    for path in scene_files():
        (line,) = [s for s in lines if s.split()[:1] == [path.stem]]
        assert len(line.split(None, 1)[1]) > 10, line  # a description, not just the name
    assert any("Ten 1 m boxes" in s for s in lines)  # the stack's own description


def test_scenes_copy_writes_every_scene_and_each_loads(tmp_path, capsys):
    d = tmp_path / "d"
    assert main(["scenes", "--copy", str(d)]) == 0
    assert sorted(p.name for p in d.iterdir()) == [p.name for p in scene_files()]
    for path in d.iterdir():
        assert path.read_bytes() == (ROOT / "scenes" / path.name).read_bytes()
        assert len(sandbox.load_scene(path).bodies) >= 1
    capsys.readouterr()
    # a second copy would overwrite edits: refused with one line, nothing changed
    (d / "drop.json").write_text("edited")
    assert main(["scenes", "--copy", str(d)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("error: --copy: ")
    assert (d / "drop.json").read_text() == "edited"


# --- lessons by name -----------------------------------------------------------------------------
def test_pick_by_number_stem_or_unique_part():
    lessons = find_lessons(ROOT / "lessons")
    assert [x.stem for x in pick(lessons, ["10"])] == ["10_friction"]
    assert [x.stem for x in pick(lessons, ["1", "10_friction", "friction"])] == [
        "01_projectile",
        "10_friction",
    ]
    assert [x.stem for x in pick(lessons, ["Stacking"])] == ["09_stacking"]
    assert pick(lessons, []) == lessons
    with pytest.raises(LookupError, match="02_rotation_2d, 15_rotation_3d"):
        pick(lessons, ["rotation"])  # ambiguous
    with pytest.raises(LookupError, match="01_projectile, 02_rotation_2d"):
        pick(lessons, ["nosuch"])


def test_lessons_nosuch_exits_2_with_one_line_listing_the_lessons(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    assert main(["lessons", "nosuch"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("error: NAME: no lesson matches 'nosuch'")
    assert all(p.stem in err for p in lesson_files())
    assert list(tmp_path.iterdir()) == []  # nothing written


def test_no_lesson_found_exits_2(tmp_path, monkeypatch, capsys):
    monkeypatch.setattr("sandbox.bundled.lessons_folder", lambda: tmp_path)
    assert main(["lessons", "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert err.startswith("error: lessons: no lesson found in ") and err.count("\n") == 1


def test_title_and_opening_paragraph():
    source = '# %%\nimport x\n\n# %% [markdown]\n# # 42 Springs\n#\n# Slides "A", "B" and\n# "C".\n#\n# More.\n'
    assert read_intro(source, "42_springs") == ("42 Springs", 'Slides "A", "B" and "C".')
    # a paragraph that runs on into a formula is cut after its last sentence
    assert read_intro("# %% [markdown]\n# # T\n#\n# One. Two,\n", "t") == ("T", "One.")
    lesson = Lesson(ROOT / "lessons" / "10_friction.py")
    assert lesson.title == "10 Friction" and lesson.number == 10
    assert lesson.opening.startswith('Slide "Further Topics on Physics Animation"')


# --- tables --------------------------------------------------------------------------------------
def test_print_table_prints_saves_and_is_not_echoed(tmp_path, monkeypatch, capsys):
    monkeypatch.setenv("SANDBOX_OUTPUTS", str(tmp_path))
    monkeypatch.setattr(lessonkit, "_current", None)  # restored after the test
    folder = lessonkit.output_dir("99_test")
    text = lessonkit.print_table(["a", "|x| (m)"], [(1, 0.5), (2, 0.25)], digits=2)
    lessonkit.print_table(["b"], [("y",)])
    assert capsys.readouterr().out == text + "\n" + "b\n-\ny\n"
    assert text == "a  |x| (m)\n-  -------\n1     0.50\n2     0.25"
    assert text._ipython_display_() is None  # a notebook shows nothing for the cell's value
    assert (folder / "tables.md").read_text() == (
        "# 99_test: printed tables\n\nTable 1\n\n| a | \\|x\\| (m) |\n|---:|---:|\n"
        "| 1 | 0.50 |\n| 2 | 0.25 |\n\nTable 2\n\n| b |\n|---:|\n| y |\n"
    )
    lessonkit.output_dir("99_test")  # a new run starts the file afresh
    lessonkit.print_table(["c"], [(3,)])
    assert (folder / "tables.md").read_text().count("Table ") == 1


def test_a_notebook_in_its_own_output_folder_writes_beside_itself(tmp_path, monkeypatch):
    monkeypatch.delenv("SANDBOX_OUTPUTS", raising=False)
    monkeypatch.setattr(lessonkit, "_current", None)
    (tmp_path / "10_friction").mkdir()
    monkeypatch.chdir(tmp_path / "10_friction")
    assert lessonkit.output_dir("10_friction") == tmp_path / "10_friction"
    monkeypatch.chdir(tmp_path)
    assert lessonkit.output_dir("10_friction") == tmp_path / "outputs" / "10_friction"
    assert (
        lessonkit.scene_path("incline").read_bytes() == (ROOT / "scenes/incline.json").read_bytes()
    )


# --- explorer ------------------------------------------------------------------------------------
def draw(a: float = 1.0, n: int = 3, on: bool = True, kind: str = "line"):
    fig, ax = plt.subplots(figsize=(3, 2))
    ax.plot([0, n], [0, a], "o-" if kind == "dots" else "-", lw=2 if on else 1)
    return fig


CONTROLS = {"a": Slider(0.0, 2.0, 0.1), "n": Slider(1, 10, 1), "on": Toggle("on"),
            "kind": Choice({"a line": "line", "dots": "dots"})}  # fmt: skip


def test_explorer_checks_its_controls_against_the_function():
    assert check_controls(draw, CONTROLS) == {"a": 1.0, "n": 3, "on": True, "kind": "line"}
    with pytest.raises(TypeError, match="'b'"):
        check_controls(draw, {"b": Toggle()})
    with pytest.raises(ValueError, match="a: default 1.0"):
        check_controls(draw, {"a": Slider(2.0, 3.0, 0.1)})
    with pytest.raises(ValueError, match="kind"):
        check_controls(draw, {"kind": Choice(("x", "y"))})


def test_explorer_widgets_rerun_and_redraw():
    pytest.importorskip("ipywidgets")
    from sandbox.explorer import build_view

    defaults = check_controls(draw, CONTROLS)
    png = figure_png(draw(**defaults))
    box, inputs, image = build_view(draw, CONTROLS, defaults, png)
    kinds = {k: type(w).__name__ for k, w in inputs.items()}
    assert kinds == {
        "a": "FloatSlider",
        "n": "IntSlider",
        "on": "Checkbox",
        "kind": "ToggleButtons",
    }
    assert image.value == png
    inputs["n"].value = 7
    assert image.value == figure_png(draw(a=1.0, n=7))  # redrawn with the new value
    assert box.children[1].value == "a = 1, n = 7, on = True, kind = line"
    box.children[0].children[-1].click()  # "defaults"
    assert image.value == png and inputs["n"].value == 3


def test_explore_in_a_script_saves_the_default_figure(tmp_path):
    from sandbox.explorer import explore

    path = explore(draw, tmp_path / "e.png", **CONTROLS)
    assert path.read_bytes() == figure_png(draw())


# --- pages ---------------------------------------------------------------------------------------
def test_formulas_become_mathml_outside_code():
    text, fragments = protect_math("a $\\theta_c$ and `$x$` then\n$$v^2\n/ 2$$ done")
    assert text == "a sbxmath0x and `$x$` then\nsbxmath1x done"
    assert fragments[0].startswith("<math") and 'display="block"' in fragments[1]
    # a token inside a tag (a heading's id) is dropped there, kept in the text
    assert restore_math('<h2 id="a-sbxmath0x">a sbxmath0x</h2>', ["<math/>"]) == (
        '<h2 id="a-">a <math/></h2>'
    )
    assert inline_html("**b** *i* `c<d` [l](x.html)") == (
        '<strong>b</strong> <em>i</em> <code>c&lt;d</code> <a href="x.html">l</a>'
    )


@pytest.mark.parametrize("fallback", [False, True], ids=["own", "nbconverts"])
def test_a_page_is_nbconverts_page_without_its_sanitizer_and_reparse(tmp_path, fallback):
    # sandbox.course.exporter: the page of a notebook with code, printed text, an error and a
    # figure is nbconvert's own once both are read as HTML, focusable areas included; with an
    # nbconvert whose pieces moved (fallback) it is nbconvert's export itself
    pytest.importorskip("nbconvert")
    import nbformat
    from bs4 import BeautifulSoup
    from nbconvert import HTMLExporter

    from sandbox.course import exporter

    nb = nbformat.v4.new_notebook()
    code = nbformat.v4.new_code_cell("for i in range(2):\n    print('<b>', i)  # a < b")
    code.outputs = [
        nbformat.v4.new_output("stream", name="stdout", text="<b> 0\n<b> 1\n"),
        nbformat.v4.new_output("display_data", data={"image/png": "iVBORw0KGgo="}),
        nbformat.v4.new_output("error", ename="ValueError", evalue="x < 0", traceback=["t"]),
    ]
    nb.cells = [nbformat.v4.new_markdown_cell("# Title\n\nSome *text* & a [link](a.html)."), code]
    with pytest.MonkeyPatch.context() as patch:
        if fallback:
            patch.setattr(exporter, "WidgetsDataTypeFilter", None)
        ours, _ = exporter.LessonPageExporter(template_name="lab").from_notebook_node(nb)
    theirs, _ = HTMLExporter(template_name="lab").from_notebook_node(nb)
    assert ours.count('tabindex="0"') == theirs.count('tabindex="0"') >= 3
    assert (ours if fallback else str(BeautifulSoup(ours, "html.parser"))) == theirs


def test_link_check_finds_missing_files_and_network_loads(tmp_path):
    (tmp_path / "ok.png").write_bytes(b"x")
    page = tmp_path / "p.html"
    page.write_text(
        '<link rel="stylesheet" href="https://cdn.example/a.css"><style>@font-face '
        '{src: url(https://fonts.example/f.woff)}</style><img src="ok.png"><img src="gone.png">'
        '<a href="https://example.org">web</a><a href="#top">top</a><script src="//x/y.js"></script>'
    )
    problems = page_problems(page)
    assert len(problems) == 4, problems
    assert any("gone.png" in p for p in problems) and any("f.woff" in p for p in problems)
    index = tmp_path / "index.html"
    index.write_text('<a href="p.html">p</a>')
    assert len(book_problems(index)) == 4


def test_link_check_still_sees_links_and_styles_inside_highlighted_code(tmp_path):
    # plain class-only spans (most of a page's tags: the highlighted code) are left out before
    # parsing; a span with a style, and a link or image among spans, are still checked
    page = tmp_path / "p.html"
    page.write_text(
        '<pre><span class="k">import</span> <span class="n">x</span></pre>'
        '<span class="c"><img src="gone.png"></span>'
        '<span class="x" style="background: url(https://x.example/b.png)">b</span>'
        '<span class="c"><a href="missing.html">m</a></span>'
    )
    problems = page_problems(page)
    assert len(problems) == 3, problems
    assert {"gone.png", "b.png", "missing.html"} == {
        name for name in ("gone.png", "b.png", "missing.html") if any(name in p for p in problems)
    }


def test_lessons_without_notebook_tools_run_as_scripts(tmp_path, monkeypatch, capsys):
    # what a user without the notebook extra gets: figures, tables.md and a course book that
    # links what exists, and one line saying what to install for the rest
    monkeypatch.setattr("sandbox.course.runner.missing_notebook_tools", lambda: ["nbclient"])
    monkeypatch.chdir(tmp_path)
    assert main(["lessons", "13", "--out", "o"]) == 0
    out = capsys.readouterr().out
    assert "note: notebooks and HTML pages need pip install 'physics-sandbox[notebook]'" in out
    folder = tmp_path / "o" / "13_user_and_agent_input"
    assert (folder / "tables.md").read_text().count("Table ") >= 2
    assert len(list(folder.glob("*.png"))) >= 2 and list(folder.glob("*.gif"))
    assert not list(folder.glob("*.ipynb")) and not list(folder.glob("*.html"))
    index = tmp_path / "o" / "index.html"
    assert book_problems(index) == []
    assert "13_user_and_agent_input/tables.md" in index.read_text()
