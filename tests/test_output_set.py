"""Outputs of one command as a set: all renamed into place together, or none (sandbox.atomic)."""

from __future__ import annotations

import contextlib
import os
import signal

import pytest

from sandbox.atomic import atomic_write, atomic_write_text, make_folder, output_set


def names(folder):
    return sorted(p.name for p in folder.iterdir())


def test_files_appear_only_when_the_set_ends(tmp_path):
    with output_set() as outputs:
        atomic_write_text(tmp_path / "a.csv", "a")
        atomic_write_text(tmp_path / "b.png", "b")
        # both complete, neither in place yet: only their hidden temporaries exist
        assert not (tmp_path / "a.csv").exists() and not (tmp_path / "b.png").exists()
        assert len(names(tmp_path)) == 2 and all(n.endswith(".tmp") for n in names(tmp_path))
    assert names(tmp_path) == ["a.csv", "b.png"]
    assert (tmp_path / "a.csv").read_text() == "a" and (tmp_path / "b.png").read_text() == "b"
    assert sorted(p.name for p in outputs.written) == ["a.csv", "b.png"]


@pytest.mark.parametrize("error", [RuntimeError, KeyboardInterrupt, OSError, MemoryError])
def test_a_failure_after_one_file_writes_nothing_and_keeps_old_files(tmp_path, error):
    atomic_write_text(tmp_path / "a.csv", "old trace")
    with pytest.raises(error), output_set():
        atomic_write_text(tmp_path / "a.csv", "new trace")
        atomic_write_text(tmp_path / "b.png", "new picture")
        raise error("failed after both files were written")
    assert names(tmp_path) == ["a.csv"]  # no new picture beside the old trace, no temporaries
    assert (tmp_path / "a.csv").read_text() == "old trace"


def test_a_failure_inside_one_file_removes_the_others_too(tmp_path):
    with pytest.raises(ValueError), output_set():
        atomic_write_text(tmp_path / "a.csv", "complete")
        with atomic_write(tmp_path / "b.gif", "wb") as f:
            f.write(b"half")
            raise ValueError("encoder failed")
    assert names(tmp_path) == []


def test_a_failed_rename_puts_back_the_files_already_replaced(tmp_path):
    atomic_write_text(tmp_path / "a.csv", "old a")
    (tmp_path / "z.png").mkdir()  # a folder in the way: the second rename fails
    with pytest.raises(OSError), output_set():
        atomic_write_text(tmp_path / "a.csv", "new a")
        atomic_write_text(tmp_path / "z.png", "new z")
    assert (tmp_path / "a.csv").read_text() == "old a"
    assert names(tmp_path) == ["a.csv", "z.png"] and (tmp_path / "z.png").is_dir()


def test_folders_made_for_a_failed_set_are_removed(tmp_path):
    with pytest.raises(RuntimeError), output_set():
        out = make_folder(tmp_path / "new" / "deeper")
        atomic_write_text(out / "summary.txt", "x")
        raise RuntimeError
    assert names(tmp_path) == []
    (tmp_path / "kept").mkdir()
    (tmp_path / "kept" / "mine.txt").write_text("the user's")
    with pytest.raises(RuntimeError), output_set():
        atomic_write_text(make_folder(tmp_path / "kept") / "summary.txt", "x")
        raise RuntimeError
    assert names(tmp_path / "kept") == ["mine.txt"]  # a folder that existed stays


def test_an_inner_set_joins_the_outer_one(tmp_path):
    with pytest.raises(RuntimeError), output_set():
        with output_set():
            atomic_write_text(tmp_path / "a.txt", "inner")
        assert names(tmp_path) != ["a.txt"]  # the inner block did not commit on its own
        raise RuntimeError
    assert names(tmp_path) == []


def test_writing_one_target_twice_keeps_the_last(tmp_path):
    with output_set():
        atomic_write_text(tmp_path / "a.txt", "first")
        atomic_write_text(tmp_path / "a.txt", "second")
    assert names(tmp_path) == ["a.txt"] and (tmp_path / "a.txt").read_text() == "second"


def test_permissions_of_a_replaced_file_are_kept(tmp_path):
    target = tmp_path / "a.txt"
    atomic_write_text(target, "old")
    os.chmod(target, 0o640)
    with output_set():
        atomic_write_text(target, "new")
    assert (target.stat().st_mode & 0o777) == 0o640 and target.read_text() == "new"


def test_an_os_error_names_the_file_being_written(tmp_path):
    with pytest.raises(OSError) as info, atomic_write(tmp_path / "t.csv") as f:
        f.write("x")
        raise OSError(28, "No space left on device")
    assert info.value.filename == str(tmp_path / "t.csv")
    assert names(tmp_path) == []


def test_a_ctrl_c_just_as_the_temporary_file_is_made_leaves_nothing(tmp_path, monkeypatch):
    # a real SIGINT sent the moment the temporary file exists, before its descriptor is handed
    # back (the race an interrupted GIF render lost once in CI, when the name came back with
    # the descriptor): the file is removed, the old one stays, for a lone file and in a set
    from sandbox import atomic

    create = os.open

    def create_then_interrupt(path, *args, **kwargs):
        fd = create(path, *args, **kwargs)
        if str(path).endswith(".tmp"):
            os.kill(os.getpid(), signal.SIGINT)
        return fd

    atomic_write_text(tmp_path / "a.gif", "old animation")
    monkeypatch.setattr(atomic.os, "open", create_then_interrupt)
    for wrap in (contextlib.nullcontext, output_set):
        with pytest.raises(KeyboardInterrupt), wrap():
            atomic_write_text(tmp_path / "a.gif", "new animation")
        assert names(tmp_path) == ["a.gif"]
        assert (tmp_path / "a.gif").read_text() == "old animation"
