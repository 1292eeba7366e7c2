"""Kernels compiled ahead for x86-64-v3 and shipped in the package (``sandbox/prebuilt.py``):
which machines take them, how they are laid out and installed, and a run that loads them
compiles nothing and steps as the machine's own code does; a wheel carries them."""

from __future__ import annotations

import io
import json
import os
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest
from numba.core.caching import _CacheLocator
from source_copy import clean_copy

from sandbox import prebuilt
from sandbox.compile_cache import WARM_FILE, kernel_sources_hash

FLAGS = "fpu sse2 " + " ".join(sorted(prebuilt.TARGET_FLAGS)) + " avx512f"


def cpuinfo(flags: str) -> str:
    return f"processor\t: 0\nmodel name\t: a processor\nflags\t\t: {flags}\n"


def test_the_target_runs_only_where_every_flag_is_there():
    assert prebuilt.runs_target(cpuinfo(FLAGS))
    assert not prebuilt.runs_target(cpuinfo(FLAGS.replace(" avx2 ", " ")))  # a v2 processor
    assert not prebuilt.runs_target(cpuinfo(FLAGS.replace("fma", "fma4")))
    assert not prebuilt.runs_target("processor\t: 0\n")  # no flags: not known to run it


def test_folder_names_are_numbas_for_every_folder_of_the_package():
    folders = {prebuilt.PACKAGE, *(p.parent for p in prebuilt.PACKAGE.rglob("*/*.py"))}
    for folder in folders:
        source = folder / "any_module.py"  # numba names the folder of a function's source file
        assert prebuilt.numba_folder_name(folder) == _CacheLocator.get_suitable_cache_subpath(
            str(source)
        )
    names = prebuilt.package_folders()
    assert len(names) == len(folders)
    for numba_name, shipped in names.items():  # and back, from the shipped name
        assert prebuilt.numba_folder_name(prebuilt.package_folder(shipped)) == numba_name
    assert names[prebuilt.numba_folder_name(prebuilt.PACKAGE / "solvers")] == "sandbox.solvers"


def shipped(archive: Path, **changes: str) -> Path:
    """An archive of shipped kernels (two fake files) whose manifest is this machine's, changed."""
    manifest = {**prebuilt.this_build(kernel_sources_hash()), **changes}
    archive.parent.mkdir(parents=True, exist_ok=True)
    with zipfile.ZipFile(archive, "w") as shipped_kernels:
        shipped_kernels.writestr(prebuilt.MANIFEST, json.dumps(manifest))
        for name, file in (
            ("sandbox.solvers", "soft.solve-1.py311.nbi"),
            ("sandbox", "step.x.nbc"),
        ):
            shipped_kernels.writestr(f"{prebuilt.KERNELS}/{name}/{file}", name)
    return archive


@pytest.mark.parametrize(
    "changes", [{}, {"numba": "0.1.0"}, {"python": "cpython-27"}, {"kernels": "0" * 16}]
)
def test_shipped_kernels_match_only_the_build_they_were_made_for(tmp_path, changes):
    archive = shipped(tmp_path / "kernels.zip", **changes)
    assert prebuilt.matches(kernel_sources_hash(), archive) == (
        not changes and prebuilt.runs_target()
    )
    assert not prebuilt.matches(kernel_sources_hash(), tmp_path / "nothing.zip")
    (tmp_path / "broken.zip").write_text("not an archive")
    assert not prebuilt.matches(kernel_sources_hash(), tmp_path / "broken.zip")


def test_install_copies_under_numbas_names_once(tmp_path):
    source = shipped(tmp_path / "kernels.zip")
    dest = tmp_path / "cache" / "numba-x-x86-64-v3"
    assert prebuilt.install(dest, source)
    solvers = dest / prebuilt.numba_folder_name(prebuilt.PACKAGE / "solvers")
    assert (solvers / "soft.solve-1.py311.nbi").read_text() == "sandbox.solvers"
    root = dest / prebuilt.numba_folder_name(prebuilt.PACKAGE)
    assert (root / "step.x.nbc").read_text() == "sandbox"
    assert (dest / WARM_FILE).exists()
    (solvers / "soft.solve-1.py311.nbi").write_text("numba's own since")
    assert prebuilt.install(dest, source)  # installed: left as it is
    assert (solvers / "soft.solve-1.py311.nbi").read_text() == "numba's own since"
    assert sorted(p.name for p in dest.parent.iterdir()) == [dest.name]  # no copy left over
    assert not prebuilt.install(tmp_path / "other", tmp_path / "missing.zip")
    assert not (tmp_path / "other").exists()


@pytest.fixture
def environ(monkeypatch):
    """The variables the shipped kernels set, unset, and after the test as they were (set first:
    monkeypatch restores only what it changed, and a variable the test sets would else stay set
    for every later test and the processes they start)."""
    for name in (*prebuilt.USERS_CHOICE, prebuilt.IN_USE, prebuilt.SWITCH):
        monkeypatch.setenv(name, "")
        monkeypatch.delenv(name)
    return os.environ


def test_use_points_numba_at_them_and_leave_takes_it_back(tmp_path, monkeypatch, environ):
    if not prebuilt.runs_target():
        pytest.skip("this processor does not run x86-64-v3 code")
    monkeypatch.setattr(prebuilt, "ARCHIVE", shipped(tmp_path / "kernels.zip"))
    native = tmp_path / "cache" / "numba-abc"
    folder = prebuilt.use(native, kernel_sources_hash())
    assert folder == tmp_path / "cache" / "numba-abc-x86-64-v3"
    assert (folder / WARM_FILE).exists()
    assert (environ["NUMBA_CPU_NAME"], environ["NUMBA_CPU_FEATURES"]) == ("x86-64-v3", "")
    assert prebuilt.use(native, kernel_sources_hash()) == folder  # a process it started
    environ[prebuilt.SWITCH] = "off"  # one that compiles for this very processor
    assert prebuilt.use(native, kernel_sources_hash()) is None
    assert "NUMBA_CPU_NAME" not in environ and prebuilt.IN_USE not in environ
    del environ[prebuilt.SWITCH]
    environ["NUMBA_CPU_NAME"] = "haswell"  # the user's own choice of target wins
    assert prebuilt.use(native, kernel_sources_hash()) is None
    assert environ["NUMBA_CPU_NAME"] == "haswell"
    prebuilt.leave()
    assert environ["NUMBA_CPU_NAME"] == "haswell"  # not ours: left alone
    del environ["NUMBA_CPU_NAME"]
    environ["NUMBA_BOUNDSCHECK"] = "1"  # array bounds checked: compiled here, so
    assert prebuilt.use(native, kernel_sources_hash()) is None


STEP = """
import json, sys
from pathlib import Path
from sandbox import prebuilt
if len(sys.argv) > 1:
    prebuilt.ARCHIVE = Path(sys.argv[1])
from sandbox import Body, Circle, World
from sandbox.compile_cache import PREBUILT
w = World(integrator="semi_implicit_euler")
ball = w.add_body(Body("ball", position=(0.0, 2.0), velocity=(1.5, 3.0), angular_velocity=2.0))
ball.add_shape(Circle(0.5))
for _ in range(50):
    w.step()
print(json.dumps([PREBUILT, *ball.position, ball.angle]))
"""


def test_a_run_that_loads_them_compiles_nothing_and_steps_the_same(tmp_path, environ):
    if not prebuilt.runs_target():
        pytest.skip("this processor does not run x86-64-v3 code")
    key = kernel_sources_hash()
    # compiled for the target into a cache of its own, then shipped
    built = prebuilt.target_environment(str(tmp_path / "built"))
    run = [sys.executable, "-c", STEP]
    subprocess.run(run, env=built, cwd=tmp_path, check=True, capture_output=True)
    prebuilt.ship(tmp_path / "built" / f"numba-{key}", tmp_path / "shipped.zip", key)
    assert prebuilt.matches(key, tmp_path / "shipped.zip")
    # a machine with an empty cache: loads them
    log = tmp_path / "compiled.log"
    env = {**environ, "NUMBA_CACHE_DIR": str(tmp_path / "empty"), "SANDBOX_COMPILE_LOG": str(log)}
    env.pop("SANDBOX_JIT", None)
    out = subprocess.run([*run, str(tmp_path / "shipped.zip")], env=env, cwd=tmp_path, check=True,
                         capture_output=True, text=True)  # fmt: skip
    loaded = json.loads(out.stdout.splitlines()[-1])
    assert loaded[0] is True
    assert not log.exists() or log.read_text().strip() == ""  # nothing compiled
    assert (tmp_path / "empty" / f"numba-{key}-x86-64-v3" / WARM_FILE).exists()
    # the same numbers as the engine's own functions, uncompiled
    plain = {**environ, "SANDBOX_JIT": "0", prebuilt.SWITCH: "off"}
    out = subprocess.run(run, env=plain, cwd=tmp_path, check=True, capture_output=True, text=True)
    assert json.loads(out.stdout.splitlines()[-1])[1:] == loaded[1:]


def test_a_wheel_carries_the_shipped_kernels_when_they_were_built(tmp_path):
    source = clean_copy(tmp_path / "src")
    shipped(source / "sandbox" / "prebuilt_kernels.zip")
    res = subprocess.run(
        [sys.executable, "-m", "pip", "wheel", str(source), "--no-deps", "-v", "-w", str(tmp_path)],
        capture_output=True,
        text=True,
    )
    assert res.returncode == 0, res.stderr[-2000:]
    assert "Warning" not in res.stdout + res.stderr  # nothing looks like a package left out
    (wheel,) = tmp_path.glob("physics_sandbox-*.whl")
    with zipfile.ZipFile(wheel) as built:
        inside = zipfile.ZipFile(io.BytesIO(built.read("sandbox/prebuilt_kernels.zip")))
    assert f"{prebuilt.KERNELS}/sandbox.solvers/soft.solve-1.py311.nbi" in inside.namelist()


WARMUP = """
import os, sys, types
from pathlib import Path
from sandbox import prebuilt
prebuilt.ARCHIVE = Path(sys.argv[1])
def warm_up(report, jobs, lessons):  # what the warmup would compile into, and for which target
    from sandbox.compile_cache import CACHE_FOLDER
    import numba
    print(CACHE_FOLDER.name, os.environ.get("NUMBA_CPU_NAME"), numba.config.CPU_NAME)
    return 0.0
fake = types.ModuleType("sandbox.warmup")  # the warmup, without importing the engine first
fake.warm_up, fake.warm_part, fake.where = warm_up, None, None
sys.modules["sandbox.warmup"] = fake
from sandbox.cli import main
main(["warmup", "--quiet"])
"""


def test_sandbox_warmup_compiles_for_the_processor_itself(tmp_path, environ):
    if not prebuilt.runs_target():
        pytest.skip("this processor does not run x86-64-v3 code")
    shipped(tmp_path / "kernels.zip")
    env = {**environ, "NUMBA_CACHE_DIR": str(tmp_path / "cache")}
    # a first run took the shipped kernels and set numba's target for what it starts
    env.update({"NUMBA_CPU_NAME": prebuilt.TARGET, "NUMBA_CPU_FEATURES": "", prebuilt.IN_USE: "1"})
    out = subprocess.run(
        [sys.executable, "-c", WARMUP, str(tmp_path / "kernels.zip")],
        env=env,
        cwd=tmp_path,
        capture_output=True,
        text=True,
        check=True,
    )
    folder, variable, target = out.stdout.split()
    assert folder == f"numba-{kernel_sources_hash()}"  # not ...-x86-64-v3
    assert (variable, target) == ("None", "None")  # numba's own choice: this processor
