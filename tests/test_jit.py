"""The compiled-code cache is keyed by the kernel sources, so an edited kernel never runs stale."""

from sandbox import compile_cache as jit
from sandbox import jit as compiled


def test_cache_key_changes_when_any_kernel_module_changes(tmp_path, monkeypatch):
    (tmp_path / "a.py").write_text("@njit\ndef f(x):\n    return x\n")
    (tmp_path / "sub").mkdir()
    (tmp_path / "sub" / "b.py").write_text("@njit\ndef g(x):\n    return 2 * x\n")
    (tmp_path / "plain.py").write_text("def h():\n    return 1\n")
    monkeypatch.setattr(jit, "_PACKAGE", tmp_path)
    before = jit.kernel_sources_hash()
    assert jit.kernel_sources_hash() == before  # stable
    (tmp_path / "plain.py").write_text("def h():\n    return 2\n")
    assert jit.kernel_sources_hash() == before  # modules without kernels do not count
    (tmp_path / "sub" / "b.py").write_text("@njit\ndef g(x):\n    return 3 * x\n")
    assert jit.kernel_sources_hash() != before  # a kernel in another module changed


def test_cache_key_covers_intrinsics_and_the_compiler_settings(tmp_path, monkeypatch):
    (tmp_path / "bits.py").write_text("@intrinsic\ndef f(typingctx, x):\n    pass\n")
    (tmp_path / "vector_width.py").write_text("WIDE = '-prefer-256-bit'\n")
    (tmp_path / "plain.py").write_text("def h():\n    return 1\n")
    monkeypatch.setattr(jit, "_PACKAGE", tmp_path)
    before = jit.kernel_sources_hash()
    (tmp_path / "bits.py").write_text("@intrinsic\ndef f(typingctx, y):\n    pass\n")
    after_intrinsic = jit.kernel_sources_hash()
    assert after_intrinsic != before  # compiled into the kernels that call it
    (tmp_path / "vector_width.py").write_text("WIDE = ''\n")
    assert jit.kernel_sources_hash() != after_intrinsic  # how every kernel compiles
    assert "vector_width.py" in jit.COMPILER_SETTINGS and "jit.py" in jit.COMPILER_SETTINGS


def test_numba_cache_lives_in_the_keyed_folder():
    if not compiled.JIT_ENABLED:
        return
    import numba

    assert numba.config.CACHE_DIR.endswith(f"numba-{jit.kernel_sources_hash()}")


# --- a locked-down machine: where the cache goes when the usual folders are not writable -------
# "Not writable" is made with a file where a folder should be: that stops root too, for whom
# permission bits change nothing.

import json  # noqa: E402
import os  # noqa: E402
import shutil  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
from pathlib import Path  # noqa: E402

import pytest  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent


def locked_down(tmp_path, monkeypatch):
    """No writable package ``__pycache__``, no writable home; a fresh temporary folder."""
    package = tmp_path / "pkg"
    package.mkdir()
    (package / "__pycache__").write_text("a file, not a folder")
    (tmp_path / "home").write_text("a file, not a folder")
    (tmp_path / "tmp").mkdir()
    monkeypatch.setattr(jit, "_PACKAGE", package)
    monkeypatch.setenv("HOME", str(tmp_path / "home"))
    monkeypatch.delenv("XDG_CACHE_HOME", raising=False)
    monkeypatch.delenv("NUMBA_CACHE_DIR", raising=False)
    monkeypatch.setattr(jit.tempfile, "tempdir", str(tmp_path / "tmp"))
    return tmp_path / "tmp"


def test_cache_falls_back_to_a_private_temporary_folder(tmp_path, monkeypatch):
    tmp = locked_down(tmp_path, monkeypatch)
    folder, note = jit.choose_cache_folder("abc")
    assert folder is not None and folder.parent.parent == tmp and folder.name == "numba-abc"
    assert folder.is_dir() and (folder.parent.stat().st_mode & 0o077) == 0  # private
    assert note.startswith("compile cache in") and "not writable" in note
    assert "\n" not in note


def test_no_cache_when_the_temporary_folder_is_not_ours(tmp_path, monkeypatch):
    tmp = locked_down(tmp_path, monkeypatch)
    user = str(os.getuid()) if hasattr(os, "getuid") else "user"
    (tmp / f"physics-sandbox-{user}").write_text("planted")  # never load code from it
    folder, note = jit.choose_cache_folder("abc")
    assert folder is None and note.startswith("no writable folder for the compile cache")


def test_the_users_cache_folder_is_used_quietly(tmp_path, monkeypatch):
    locked_down(tmp_path, monkeypatch)
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    folder, note = jit.choose_cache_folder("abc")
    assert folder == tmp_path / "cache" / "physics-sandbox" / "numba-abc" and note is None


def read_only_install(tmp_path) -> dict:
    """A copy of the package whose folder and home are not writable; returns the environment."""
    shutil.copytree(
        ROOT / "sandbox",
        tmp_path / "site" / "sandbox",
        ignore=shutil.ignore_patterns("__pycache__"),
    )
    (tmp_path / "site" / "sandbox" / "__pycache__").write_text("not a folder")
    (tmp_path / "home").write_text("not a folder")
    (tmp_path / "tmp").mkdir()
    env = {k: v for k, v in os.environ.items() if not k.startswith(("NUMBA_", "XDG_", "MPL"))}
    env.update(
        PYTHONPATH=str(tmp_path / "site"),
        HOME=str(tmp_path / "home"),
        TMPDIR=str(tmp_path / "tmp"),
        PYTHONDONTWRITEBYTECODE="1",
        SANDBOX_JIT="1",
    )
    return env


def test_a_bad_scene_on_a_locked_down_machine_is_one_line_and_compiles_nothing(tmp_path):
    env = read_only_install(tmp_path)
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps({"bodies": [{"name": "a", "shapes": [{"type": "circle"}]}]}))
    res = subprocess.run(
        [sys.executable, "-m", "sandbox", "simulate", str(bad), "--trace", "t.csv"],
        cwd=tmp_path, env=env, capture_output=True, text=True, timeout=120,
    )  # fmt: skip
    assert res.returncode == 2
    assert res.stderr.startswith("error: bodies[0].shapes[0].radius:")
    assert res.stderr.count("\n") == 1  # no note, no numba error: validation ran first
    assert not (tmp_path / "t.csv").exists()
    compiled = list((tmp_path / "tmp").rglob("*.nbi"))
    assert compiled == []  # nothing was compiled (or cached) for a scene that was refused


@pytest.mark.skipif(not compiled.JIT_ENABLED, reason="numba switched off")
def test_kernels_compile_and_cache_on_a_locked_down_machine(tmp_path):
    env = read_only_install(tmp_path)
    (tmp_path / "kernel.py").write_text(
        "from sandbox.jit import njit\n\n\n@njit\ndef twice(x):\n    return 2.0 * x\n"
    )
    env["PYTHONPATH"] += os.pathsep + str(tmp_path)
    code = (
        "import kernel, sandbox.jit as j\n"
        "print(kernel.twice(21.0)); print(j.CACHE_FOLDER); print(j.take_cache_note())"
    )
    res = subprocess.run(
        [sys.executable, "-c", code],
        cwd=tmp_path, env=env, capture_output=True, text=True, timeout=120,
    )  # fmt: skip
    assert res.returncode == 0, res.stderr
    value, folder, note = res.stdout.splitlines()
    assert value == "42.0" and note.startswith("compile cache in")
    assert Path(folder).parent.parent == tmp_path / "tmp"
    assert list(Path(folder).rglob("*twice*.nbi"))  # the kernel was cached there


@pytest.mark.skipif(not compiled.JIT_ENABLED, reason="nothing compiles")
def test_compiled_functions_have_no_c_callable_twin():
    # numba's cfunc wrapper (for passing a function as a first-class value, which the engine
    # never does) is left out: the function's own code is all the library holds
    import numba

    @compiled.njit(cache=False)
    def twice(x):
        return 2.0 * x

    @numba.njit(cache=False)
    def twice_with_twin(x):
        return 2.0 * x

    assert twice(1.5) == twice_with_twin(1.5) == 3.0
    ours = twice.overloads[twice.signatures[0]].library.get_llvm_str()
    numbas = twice_with_twin.overloads[twice_with_twin.signatures[0]].library.get_llvm_str()
    assert "cfunc." in numbas  # numba's own default, as this test expects it
    assert "cfunc." not in ours
    assert "cpython" in ours  # its Python entry stays


# --- the interpreter's settings while compiling (sandbox.jit.WhileCompiling) --------------------


@pytest.mark.skipif(not compiled.JIT_ENABLED, reason="nothing compiles")
def test_collections_are_rarer_only_while_compiling():
    import gc

    import numba

    seen = []

    class Seen(numba.core.event.Listener):
        def on_start(self, event):
            seen.append(gc.get_threshold())

        def on_end(self, event):
            pass

    before = gc.get_threshold()
    listener = Seen()
    numba.core.event.register("numba:compile", listener)
    try:
        compiled.njit(cache=False)(lambda x: x + 1)(1)
        assert gc.get_threshold() == before  # as it was once the compile ended
        with pytest.raises(numba.TypingError):  # a compile that fails ends as well
            compiled.njit(cache=False)(lambda x: x.nothing)(1)
        assert gc.get_threshold() == before
    finally:
        numba.core.event.unregister("numba:compile", listener)
    young, middle, full = before
    rules = compiled.WhileCompiling
    assert seen and seen[0] == (max(young, rules.YOUNG), middle, full * rules.RARER)


@pytest.mark.skipif(not compiled.JIT_ENABLED, reason="nothing compiles")
def test_a_warmup_keeps_the_compile_settings_from_start_to_end():
    """``compiling_process`` (every ``sandbox warmup`` process): the collector's settings of a
    compile hold between compiles too, not only during each."""
    code = (
        "import gc; gc.set_threshold(700, 10, 10)\n"
        "from sandbox import jit\n"
        "jit.compiling_process()\n"
        "held = gc.get_threshold()\n"
        "jit.njit(cache=False)(lambda x: x + 1)(1)\n"
        "print((held, gc.get_threshold()))\n"
    )
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env)
    assert out.returncode == 0, out.stderr
    rules = compiled.WhileCompiling
    expected = (rules.YOUNG, 10, 10 * rules.RARER)
    assert out.stdout.strip() == str((expected, expected))
