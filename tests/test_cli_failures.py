"""The command line past validation: one error path, outputs as a set, interrupts, bounded runs.

Run as a hostile user would: every kind of failure inside a run, a full disk (a file-size limit
in a subprocess, and ENOSPC raised inside the PNG writer), Ctrl-C and SIGTERM while a GIF is
being rendered, a folder nobody can write to, absurd option values, scene names that are
matplotlib mathtext.
"""

from __future__ import annotations

import errno
import json
import os
import signal
import subprocess
import sys
import time
import tracemalloc
import warnings
from pathlib import Path

import pytest

from sandbox import replay
from sandbox.cli import main
from sandbox.errors import SimulationError
from sandbox.world import World

ROOT = Path(__file__).resolve().parent.parent
DROP = ROOT / "scenes" / "drop.json"
BALL = {"name": "ball", "bodies": [{"name": "ball", "shapes": [{"type": "circle", "radius": 0.5}]}]}


def run(*args) -> int:
    return main([str(a) for a in args])


def scene(tmp_path, data=None, name="s.json") -> Path:
    path = tmp_path / name
    path.write_text(json.dumps(data if data is not None else BALL))
    return path


def old_outputs(folder: Path) -> dict[str, bytes]:
    """Outputs of an earlier run, to check a failed run leaves them as they were."""
    files = {"t.csv": b"old trace\n", "a.gif": b"GIF89a old", "a.png": b"\x89PNG old"}
    for name, data in files.items():
        (folder / name).write_bytes(data)
    return files


def assert_untouched(folder: Path, files: dict[str, bytes], extra=("s.json",)) -> None:
    assert sorted(p.name for p in folder.iterdir()) == sorted([*files, *extra])  # no temporaries
    for name, data in files.items():
        assert (folder / name).read_bytes() == data


def one_error_line(err: str) -> str:
    lines = err.splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), err
    assert "Traceback" not in err
    return lines[0]


# ---------------------------------------------------------------- every failure is one line


def failing_step(exc: BaseException):
    calls = []

    def step(self, dt=None):
        calls.append(1)
        if len(calls) == 5:
            raise exc
        return original_step(self, dt)

    return step


original_step = World.step


def numba_error() -> Exception:
    from numba.core.errors import TypingError

    return TypingError("Cannot unify float64 and none\nmore lines of numba's report")


FAILURES = [
    (SimulationError("ball", 5, "spring stiffness too high for dt: try dt <= 0.004"), "ball"),
    (OSError(errno.ENOSPC, "No space left on device"), "No space left on device"),
    (OverflowError("math range error"), "OverflowError: math range error"),
    (MemoryError(), "out of memory"),
    (ZeroDivisionError("float division by zero"), "ZeroDivisionError"),
    (RuntimeError("line one\nline two"), "line one line two"),
    ("numba", "compiled kernel failed (TypingError)"),
]


@pytest.mark.parametrize(
    "exc,said",
    FAILURES,
    ids=["simulation", "disk-full", "overflow", "memory", "zero-division", "runtime", "numba"],
)
def test_a_failure_during_the_run_is_one_line_exit_1_and_writes_nothing(
    tmp_path, capsys, monkeypatch, exc, said
):
    exc = numba_error() if exc == "numba" else exc
    files = old_outputs(tmp_path)
    monkeypatch.setattr(World, "step", failing_step(exc))
    status = run(
        "simulate", scene(tmp_path), "--steps", 20, "--trace", tmp_path / "t.csv",
        "--gif", tmp_path / "a.gif", "--png", tmp_path / "a.png",
    )  # fmt: skip
    err = capsys.readouterr().err
    assert status == 1
    assert said in one_error_line(err)
    assert_untouched(tmp_path, files)


def test_sandbox_debug_adds_the_traceback(tmp_path, capsys, monkeypatch):
    monkeypatch.setattr(World, "step", failing_step(OverflowError("math range error")))
    monkeypatch.setenv("SANDBOX_DEBUG", "1")
    assert run("simulate", scene(tmp_path), "--steps", 20) == 1
    err = capsys.readouterr().err
    assert "Traceback" in err and err.splitlines()[-1].startswith("error: OverflowError")


def test_warnings_of_a_successful_run_are_one_line(tmp_path, capsys, monkeypatch):
    def noisy(self, dt=None):
        warnings.warn("overflow encountered in multiply", RuntimeWarning, stacklevel=1)
        return original_step(self, dt)

    monkeypatch.setattr(World, "step", noisy)
    assert run("simulate", scene(tmp_path), "--steps", 5) == 0
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 1 and err[0].startswith("warning: 1 warning during the run")


def test_a_name_that_is_not_unicode_is_bad_input_and_writes_nothing(tmp_path, capsys):
    # a lone surrogate: valid JSON, but no file can hold it as UTF-8
    path = tmp_path / "s.json"
    path.write_text('{"bodies": [{"name": "ball\\ud800", "mass": 1, "moment": 1}]}')
    status = run("simulate", path, "--png", tmp_path / "a.png", "--trace", tmp_path / "t.csv")
    assert status == 2
    assert one_error_line(capsys.readouterr().err).startswith("error: bodies[0].name:")
    assert [p.name for p in tmp_path.iterdir()] == ["s.json"]


# ---------------------------------------------------------------- disk full, read-only folders


def test_enospc_in_the_png_writer_leaves_the_old_outputs(tmp_path, capsys, monkeypatch):
    from PIL import Image

    def full_disk(self, fp, *args, **kwargs):
        fp.write(b"\x89PNG partial")
        raise OSError(errno.ENOSPC, "No space left on device")

    files = old_outputs(tmp_path)
    monkeypatch.setattr(Image.Image, "save", full_disk)
    status = run(
        "simulate", scene(tmp_path), "--steps", 10,
        "--trace", tmp_path / "t.csv", "--png", tmp_path / "a.png",
    )  # fmt: skip
    assert status == 1
    line = one_error_line(capsys.readouterr().err)
    assert line == f"error: {tmp_path / 'a.png'}: No space left on device"
    assert_untouched(tmp_path, files)  # the new trace was complete, and still not put in place


def limited_file_size(limit: int):
    """preexec_fn: files larger than ``limit`` bytes fail with EFBIG, as on a full disk."""

    def apply() -> None:
        import resource

        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # fail the write instead of killing
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))

    return apply


@pytest.mark.skipif(not hasattr(signal, "SIGXFSZ"), reason="POSIX file-size limits")
@pytest.mark.parametrize("steps,failing", [(400, "t.csv"), (40, "a.gif")])
def test_a_full_disk_in_a_subprocess_fails_cleanly(tmp_path, steps, failing):
    # compile and cache the kernels (and matplotlib's font list) first: under the limit, only
    # the outputs should hit it
    assert run("simulate", scene(tmp_path), "--steps", 2, "--gif", tmp_path / "warm.gif") == 0
    (tmp_path / "warm.gif").unlink()
    files = old_outputs(tmp_path)
    res = subprocess.run(
        [
            sys.executable, "-m", "sandbox", "simulate", str(scene(tmp_path)),
            "--steps", str(steps), "--trace", "t.csv", "--gif", "a.gif",
        ],
        cwd=tmp_path, capture_output=True, text=True, timeout=300,
        preexec_fn=limited_file_size(12_000),
    )  # fmt: skip
    assert res.returncode == 1, res.stderr
    line = one_error_line(res.stderr)
    assert failing in line and "File too large" in line
    assert_untouched(tmp_path, files)  # with 40 steps the trace fit: still not put in place


@pytest.mark.skipif(not Path("/proc/self").is_dir(), reason="needs a read-only /proc")
def test_a_folder_nobody_can_write_is_bad_input(capsys):
    # /proc refuses new files even to root (permission bits would not)
    assert run("simulate", DROP, "--steps", 1, "--trace", "/proc/t.csv") == 2
    line = one_error_line(capsys.readouterr().err)
    assert line.startswith("error: --trace: folder '/proc' is not writable")


@pytest.mark.skipif(os.name != "posix" or os.geteuid() == 0, reason="root writes anywhere")
def test_a_read_only_folder_is_bad_input(tmp_path, capsys):
    folder = tmp_path / "ro"
    folder.mkdir()
    folder.chmod(0o555)
    try:
        assert run("simulate", DROP, "--steps", 1, "--png", folder / "a.png") == 2
    finally:
        folder.chmod(0o755)
    assert one_error_line(capsys.readouterr().err).startswith("error: --png: folder")


# ---------------------------------------------------------------- interrupts


@pytest.mark.parametrize("signum,status", [(signal.SIGINT, 130), (signal.SIGTERM, 143)])
def test_a_signal_during_a_gif_render_exits_quietly_and_cleans_up(tmp_path, signum, status):
    files = old_outputs(tmp_path)
    proc = subprocess.Popen(
        [
            sys.executable, "-m", "sandbox", "simulate", str(scene(tmp_path)),
            "--steps", "3000", "--fps", "50", "--trace", "t.csv", "--gif", "a.gif",
        ],
        cwd=tmp_path, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
    )  # fmt: skip
    deadline = time.monotonic() + 240  # a first run on a fresh machine compiles the kernels
    while not any(p.name.startswith(".a.gif.") for p in tmp_path.iterdir()):
        assert proc.poll() is None, proc.communicate()
        assert time.monotonic() < deadline, "the GIF render never started"
        time.sleep(0.02)
    proc.send_signal(signum)  # rendering: 600 frames take seconds
    out, err = proc.communicate(timeout=120)
    assert proc.returncode == status, err
    assert err == "" and out == ""  # quietly: no traceback, no summary, no "wrote" line
    assert_untouched(tmp_path, files)  # temporaries of the trace and the GIF removed


# ---------------------------------------------------------------- bounds on options


@pytest.mark.parametrize(
    "args,field",
    [
        (["--fps", "1e-320", "--gif", "x.gif"], "--fps"),
        (["--fps", "1000", "--gif", "x.gif"], "--fps"),
        (["--fps", "inf"], "--fps"),
        (["--steps", str(10**12)], "--steps"),
        (["--steps", "9" * 5001], "--steps"),
    ],
    ids=["fps-tiny", "fps-1000", "fps-inf", "steps-1e12", "steps-5001-digits"],
)
def test_absurd_options_are_bad_input(tmp_path, capsys, args, field):
    args = [str(tmp_path / a) if a == "x.gif" else a for a in args]
    assert run("simulate", scene(tmp_path), *args) == 2
    assert one_error_line(capsys.readouterr().err).startswith(f"error: {field}:")
    assert [p.name for p in tmp_path.iterdir()] == ["s.json"]


def test_compare_steps_are_bounded(tmp_path, capsys):
    assert run("compare", scene(tmp_path), "--steps", 10**6, "--out", tmp_path / "c") == 2
    assert one_error_line(capsys.readouterr().err).startswith("error: --steps:")
    assert [p.name for p in tmp_path.iterdir()] == ["s.json"]


# ---------------------------------------------------------------- what simulate says it wrote


def test_simulate_prints_one_line_per_file_written(tmp_path, capsys):
    paths = [tmp_path / n for n in ("t.csv", "a.gif", "a.png")]
    status = run(
        "simulate", scene(tmp_path), "--steps", 10, "--fps", 10,
        "--trace", paths[0], "--gif", paths[1], "--png", paths[2],
    )  # fmt: skip
    assert status == 0
    wrote = [line for line in capsys.readouterr().out.splitlines() if line.startswith("wrote")]
    assert wrote == [
        f"wrote {paths[0]} (11 rows: steps 0-10 of 1 body)",
        f"wrote {paths[1]} (2 frames at 10 fps)",  # every 6th step of 1/60 s: steps 0 and 6
        f"wrote {paths[2]} (the state after step 10)",
    ]
    assert all(p.is_file() for p in paths)
    assert run("simulate", scene(tmp_path), "--steps", 3) == 0
    assert "wrote" not in capsys.readouterr().out


def test_a_long_run_keeps_a_bounded_number_of_frames_and_says_so(tmp_path, capsys, monkeypatch):
    from PIL import Image

    monkeypatch.setattr(replay, "MAX_FRAMES", 20)
    gif = tmp_path / "a.gif"
    assert run("simulate", scene(tmp_path), "--steps", 100, "--fps", 50, "--gif", gif) == 0
    out = capsys.readouterr().out
    # 101 steps, one frame per step at 50 fps and dt = 1/60 s: more than 20, so every
    # ceil(101 / 20) = 6th step is drawn (17 frames), shown at 50 fps: 6 / 60 * 50 = 5x
    assert f"wrote {gif} (17 frames at 50 fps, one every 6 steps to keep at most 20 frames: " in out
    assert "plays 5 times faster than real time" in out
    with Image.open(gif) as im:
        assert im.n_frames == 17


def test_memory_stays_flat_however_many_steps(tmp_path):
    """The trace streams and the PNG keeps a bounded set of frames: ten times the steps, about
    the same peak of Python allocations (the old code held every row: ~3 MB more here)."""

    def peak(steps: int) -> int:
        tracemalloc.start()
        try:
            status = run(
                "simulate", scene(tmp_path), "--steps", steps,
                "--trace", tmp_path / "t.csv", "--png", tmp_path / "a.png",
            )  # fmt: skip
            return tracemalloc.get_traced_memory()[1]
        finally:
            tracemalloc.stop()
            assert status == 0

    run("simulate", scene(tmp_path), "--steps", 1, "--png", tmp_path / "a.png")  # warm up
    small, large = peak(1000), peak(10_000)
    assert large < small + 500_000, (small, large)  # bytes; 9,000 more rows ~ 2.7 MB


# ---------------------------------------------------------------- user text is never mathtext


MATH = "$\\frac{$"


def test_mathtext_in_scene_and_body_names_is_drawn_literally(tmp_path, capsys):
    data = {"name": MATH, "bodies": [{**BALL["bodies"][0], "name": f"{MATH} ball"}]}
    gif, png = tmp_path / "a.gif", tmp_path / "a.png"
    status = run("simulate", scene(tmp_path, data), "--steps", 6, "--gif", gif, "--png", png)
    assert status == 0, capsys.readouterr().err
    assert gif.read_bytes()[:6] == b"GIF89a" and png.read_bytes()[:4] == b"\x89PNG"


def test_the_legend_and_title_hold_the_text_as_typed():
    import numpy as np

    from sandbox.frames import FrameRenderer
    from sandbox.recording import CircleOutline, Recording

    rec = Recording(["b"], ["dynamic"], [[CircleOutline(np.zeros(2), 1.0)]])
    rec.add_frame(np.zeros((1, 3)), 0.0)
    with FrameRenderer(rec, size_px=64, labels=[MATH], title=MATH) as renderer:
        renderer.frame(0)
        texts = [*renderer.ax.get_legend().get_texts(), renderer.ax.title]
        assert [t.get_text() for t in texts] == [MATH, MATH]
        assert not any(t.get_parse_math() for t in texts)


def test_compare_figures_with_mathtext_names(tmp_path, capsys):
    data = {"name": MATH, "bodies": [{**BALL["bodies"][0], "name": f"{MATH} ball"}]}
    out = tmp_path / "c"
    assert run("compare", scene(tmp_path, data), "--steps", 5, "--out", out, "--no-gif") == 0
    assert {p.name for p in out.iterdir()} >= {"deviation.png", "energy.png", "summary.txt"}


def test_an_interrupt_that_comes_back_as_another_error_still_exits_quietly(capsys):
    # Ctrl-C inside a C extension's callback (e.g. a GIF encoder writing through Python) can
    # surface as SystemError with the KeyboardInterrupt as its cause: still 130, no line;
    # a stop signal behind an error keeps its own status; a plain error is still a failure
    from sandbox.cli.exits import Stopped, run_command

    def raise_over(interrupt: BaseException):
        def command() -> int:
            try:
                raise interrupt
            except BaseException as inner:
                raise SystemError("returned a result with an exception set") from inner

        return command

    assert run_command(raise_over(KeyboardInterrupt())) == 130
    assert run_command(raise_over(Stopped(15, 143))) == 143
    assert capsys.readouterr().err == ""
    assert run_command(raise_over(ValueError("boom"))) == 1
    assert capsys.readouterr().err.startswith("error:")


@pytest.mark.parametrize(
    ("signum", "status", "then"), [(signal.SIGINT, 130, "fails"), (signal.SIGTERM, 143, "finishes")]
)
def test_an_interrupt_a_library_swallowed_exits_as_the_interrupt(capsys, signum, status, then):
    # a library catches the interrupt and fails otherwise (matplotlib once reported "Invalid
    # affine transformation matrix" mid-render), or catches everything and lets the command
    # finish: the command still exits as interrupted, quietly
    from sandbox.cli.exits import run_command

    def command() -> int:
        try:
            os.kill(os.getpid(), signum)
            time.sleep(1.0)  # the handler runs here
        except BaseException:
            if then == "fails":
                raise ValueError("Invalid affine transformation matrix") from None
        return 0

    assert run_command(command) == status
    assert capsys.readouterr().err == ""


def test_a_stop_signal_that_lands_in_a_finaliser_still_stops_the_command(capsys):
    # a signal handled while an object's __del__ runs raises inside it, and Python drops what a
    # finaliser raises (llvmlite frees LLVM's objects so, thousands of times while numba
    # compiles): a stopped warmup compiled on and exited 0. The signal comes again and stops
    # the command where the finaliser interrupted it, quietly
    from sandbox.cli.exits import run_command

    class Freed:
        def __del__(self) -> None:
            os.kill(os.getpid(), signal.SIGTERM)
            sum(range(100))  # the handler runs here, inside the finaliser

    went_on = []

    def command() -> int:
        Freed()  # freed at once
        time.sleep(1.0)
        went_on.append("finished")
        return 0

    hook = sys.unraisablehook
    assert run_command(command) == 143
    assert went_on == []
    assert sys.unraisablehook is hook
    assert capsys.readouterr().err == ""
