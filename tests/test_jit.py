"""The compiled-code cache is keyed by the kernel sources, so an edited kernel never runs stale."""

from sandbox import jit


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


def test_numba_cache_lives_in_the_keyed_folder():
    if not jit.JIT_ENABLED:
        return
    import numba

    assert numba.config.CACHE_DIR.endswith(f"numba-{jit.kernel_sources_hash()}")
