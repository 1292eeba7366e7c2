"""Installed = complete: the wheel carries the lessons and the scenes.

The wheel is built from this checkout and installed into a fresh virtual environment, which
reuses this environment's installed dependencies through a ``.pth`` file (so nothing is
downloaded but the build backend); then a new user's first command runs from an empty folder:
``sandbox lessons 10``, a lesson that reads a bundled scene. The checkout is nowhere on the path.
"""

import os
import subprocess
import sys
import sysconfig
from pathlib import Path

import nbformat
import pytest
from source_copy import clean_copy

from sandbox.course.links import book_problems

ROOT = Path(__file__).resolve().parent.parent


def run(args, **kw) -> subprocess.CompletedProcess:
    return subprocess.run([str(a) for a in args], capture_output=True, text=True, **kw)


@pytest.fixture(scope="module")
def installed(tmp_path_factory):
    """A venv with only the wheel installed in it, and the environment to run it in."""
    tmp = tmp_path_factory.mktemp("wheel")
    src = clean_copy(tmp / "src")
    built = run([sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", "-w", tmp / "dist", src])
    assert built.returncode == 0, built.stderr
    (wheel,) = (tmp / "dist").glob("physics_sandbox-*.whl")
    venv = tmp / "venv"
    assert run([sys.executable, "-m", "venv", "--without-pip", venv]).returncode == 0
    python = venv / ("Scripts" if os.name == "nt" else "bin") / "python"
    site = Path(
        run(
            [python, "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"]
        ).stdout.strip()
    )
    ours = dict.fromkeys(sysconfig.get_paths()[k] for k in ("purelib", "platlib"))
    # path lines only: this environment's packages are found, its .pth files (the editable
    # install of the checkout among them) are not run
    (site / "test_dependencies.pth").write_text("".join(f"{p}\n" for p in ours))
    install = run(
        [sys.executable, "-m", "pip", "--python", python, "install", "--no-deps", "-q", wheel]
    )
    assert install.returncode == 0, install.stderr
    env = {
        k: v
        for k, v in os.environ.items()
        if k not in ("PYTHONPATH", "SANDBOX_OUTPUTS", "VIRTUAL_ENV")
    }
    env["PATH"] = f"{python.parent}{os.pathsep}{env.get('PATH', '')}"
    # the dependencies' data files (nbconvert's page templates) sit beside their packages' prefix
    env["JUPYTER_PATH"] = os.path.join(sys.prefix, "share", "jupyter")
    # the compiled kernels would be compiled afresh for the new install (about a minute): the
    # same functions run as plain Python, which is what this test is not about
    env["SANDBOX_JIT"] = "0"
    empty = tmp / "empty"
    empty.mkdir()
    return python, env, empty


def test_the_installed_package_is_the_wheels_copy(installed):
    python, env, empty = installed
    code = "import sandbox, sandbox.bundled as b; print(sandbox.__file__); print(b.lessons_folder()); print(b.scenes_folder())"
    where = run([python, "-c", code], cwd=empty, env=env)
    assert where.returncode == 0, where.stderr
    venv = python.parent.parent.resolve()
    for line in where.stdout.split():
        assert Path(line).resolve().is_relative_to(venv), line  # not the checkout
    files = run(
        [
            python,
            "-c",
            "import sandbox.bundled as b; print(len(b.lesson_files()), len(b.scene_files()))",
        ],
        cwd=empty,
        env=env,
    )
    assert files.stdout.split() == [
        str(len(list((ROOT / "lessons").glob("[0-9][0-9]_*.py")))),
        str(len(list((ROOT / "scenes").glob("*.json")))),
    ]


def test_sandbox_lessons_10_from_an_empty_folder(installed):
    python, env, empty = installed
    result = run([python.parent / "sandbox", "lessons", "10"], cwd=empty, env=env)
    assert result.returncode == 0, result.stdout + result.stderr
    outputs = empty / "outputs"
    assert f"to {outputs}" in result.stdout.splitlines()[0]  # says where
    folder = outputs / "10_friction"
    assert {"incline.png", "stopping.png", "incline.gif", "explore_friction.png"} <= {
        p.name for p in folder.iterdir()
    }
    assert (folder / "tables.md").read_text().count("\nTable ") >= 4
    nb = nbformat.read(folder / "10_friction.ipynb", as_version=4)
    mimes = [
        m for c in nb.cells if c.cell_type == "code" for o in c.outputs for m in o.get("data", {})
    ]
    assert mimes.count("image/png") >= 3 and mimes.count("image/gif") == 1
    assert not [
        o for c in nb.cells if c.cell_type == "code" for o in c.outputs if o.output_type == "error"
    ]
    assert (folder / "10_friction.html").exists()
    assert book_problems(outputs / "index.html") == []
    assert sorted(p.name for p in empty.iterdir()) == ["outputs"]  # nothing else left behind
