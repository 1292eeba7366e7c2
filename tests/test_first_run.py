"""A machine where the engine was never compiled: a small scene runs uncompiled at once, with a
one-line note; compiling shows a notice and a progress bar on a terminal; ``sandbox warmup``
marks the cache warm."""

import csv
import io
import os
import re
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from sandbox import compile_cache
from sandbox.cli import first_run


def run(args, env_extra, cwd):
    env = {k: v for k, v in os.environ.items() if k != "SANDBOX_JIT"}
    env.update(env_extra)
    return subprocess.run(
        [sys.executable, "-m", "sandbox", *args], cwd=cwd, env=env, capture_output=True, text=True
    )


class Terminal(io.StringIO):
    """A screen that says it is a terminal (where progress bars are drawn)."""

    def isatty(self):
        return True


def rows(path):
    with open(path, newline="") as f:
        return [[float(x) for i, x in enumerate(r) if i != 2] for r in list(csv.reader(f))[1:]]


def test_a_small_scene_on_a_cold_cache_runs_uncompiled_and_agrees(tmp_path):
    # an empty cache: drop's 240 steps run as plain Python (the note says so); the trace matches
    # the compiled engine's to 1e-9 (the same functions, rounding may differ in the last bits)
    cold = {"NUMBA_CACHE_DIR": str(tmp_path / "cache"), "SANDBOX_WARMUP": "off"}
    done = run(["simulate", "drop", "--steps", "240", "--trace", "cold.csv"], cold, tmp_path)
    assert done.returncode == 0, done.stderr
    assert "this run is plain Python" in done.stderr
    warm = run(
        ["simulate", "drop", "--steps", "240", "--trace", "warm.csv"],
        {"SANDBOX_JIT": "1"},
        tmp_path,
    )
    assert warm.returncode == 0, warm.stderr
    a, b = np.array(rows(tmp_path / "cold.csv")), np.array(rows(tmp_path / "warm.csv"))
    assert a.shape == b.shape == (482, 8)
    assert np.max(np.abs(a - b)) < 1e-9


def test_a_large_scene_compiles_and_says_so(monkeypatch):
    notes = []
    monkeypatch.setattr(first_run, "note", notes.append)
    monkeypatch.delenv("SANDBOX_JIT", raising=False)
    monkeypatch.setattr(first_run, "engine_imported", lambda: False)  # a fresh command
    monkeypatch.setattr(compile_cache, "is_warm", lambda: False)
    monkeypatch.setattr(compile_cache, "has_kernel", lambda name: False)
    from sandbox import jit

    if jit.JIT_ENABLED:
        monkeypatch.setattr(jit.NOTICE, "told", False)
    first_run.choose_engine_speed({"bodies": [{}] * 210}, 240)  # pyramid 20: 50,400
    assert "SANDBOX_JIT" not in os.environ
    assert notes and "compiling the engine" in notes[0]
    # one line: the compile notice, which would say it again, keeps only its bar
    assert not jit.JIT_ENABLED or jit.NOTICE.told


def test_a_large_scene_whose_step_is_cached_says_nothing(tmp_path, monkeypatch):
    # an earlier run compiled the pyramid's step (its index file is in the cache) but no
    # warmup finished: the next run loads it, without the "about a minute" note; a soft
    # scene needs the soft step, which is not there, and gets the note
    notes = []
    monkeypatch.setattr(first_run, "note", notes.append)
    monkeypatch.delenv("SANDBOX_JIT", raising=False)
    monkeypatch.setattr(first_run, "engine_imported", lambda: False)
    monkeypatch.setattr(compile_cache, "CACHE_FOLDER", tmp_path)
    (tmp_path / "sandbox_0123").mkdir()
    (tmp_path / "sandbox_0123" / "step.fast_step-216.py311.nbi").write_bytes(b"")
    box = {"shapes": [{"type": "box"}]}
    first_run.choose_engine_speed({"bodies": [box] * 210, "settings": {"solver": "iterative"}}, 240)
    assert notes == [] and "SANDBOX_JIT" not in os.environ
    soft = {"bodies": [box] * 210, "settings": {"solver": "soft"}}
    first_run.choose_engine_speed(soft, 240)
    assert len(notes) == 1 and "compiling the engine" in notes[0]


def test_warm_marker(tmp_path, monkeypatch):
    monkeypatch.setattr(compile_cache, "CACHE_FOLDER", tmp_path)
    assert not compile_cache.is_warm()
    compile_cache.mark_warm()
    assert compile_cache.is_warm()


def test_compile_notice_on_a_terminal(monkeypatch):
    from sandbox import jit

    if not jit.JIT_ENABLED:
        return

    screen = Terminal()
    monkeypatch.setattr(jit.sys, "stderr", screen)
    notice = jit.CompileNotice()
    notice.on_start(None)
    notice.on_start(None)  # a nested compile: the same bar
    notice.on_end(None)
    notice.on_end(None)
    text = screen.getvalue()
    assert text.count("compiling the engine for this machine, once") == 1
    assert "kernels" in text  # the progress bar
    log = io.StringIO()  # not a terminal (a notebook, a log): the line once, no bar
    monkeypatch.setattr(jit.sys, "stderr", log)
    plain = jit.CompileNotice()
    for _ in range(2):
        plain.on_start(None)
        plain.on_end(None)
    assert plain.bar is None
    assert log.getvalue().count("compiling the engine for this machine, once") == 1
    assert "kernels" not in log.getvalue()


def test_the_compile_bar_is_as_long_as_the_step_it_compiles(monkeypatch):
    # a one-call step's compile: a bar of the kernels it compiles from an empty cache (235 for
    # the iterative solver's, 232 for the soft step's); anything else: a count, no length
    from types import SimpleNamespace

    from sandbox import jit

    if not jit.JIT_ENABLED:
        return

    def event(name):
        return SimpleNamespace(
            data={"dispatcher": SimpleNamespace(py_func=SimpleNamespace(__name__=name))}
        )

    monkeypatch.setattr(jit.sys, "stderr", Terminal())
    for name, total in (
        ("fast_step", 235),
        ("soft_step", 232),
        ("place_bodies", None),
        (None, None),
    ):
        notice = jit.CompileNotice()
        notice.on_start(event(name) if name else None)
        assert notice.bar.total == total, name
        notice.on_end(None)
        assert notice.bar is None


def test_the_plain_python_note_ends_cleanly_without_a_background_warmup(monkeypatch):
    # SANDBOX_WARMUP=off: no background compile starts, and the note says no more than it is
    # (it ended in a dangling "; " before)
    notes = []
    monkeypatch.setattr(first_run, "note", notes.append)
    monkeypatch.delenv("SANDBOX_JIT", raising=False)
    monkeypatch.setenv("SANDBOX_WARMUP", "off")
    monkeypatch.setattr(first_run, "engine_imported", lambda: False)
    monkeypatch.setattr(compile_cache, "is_warm", lambda: False)
    first_run.choose_engine_speed({"bodies": [{}] * 2}, 240)
    assert os.environ.pop("SANDBOX_JIT") == "0"
    assert notes == ["the engine is not compiled for this machine yet: this run is plain Python"]


def test_a_background_warmup_locks_the_cache_with_its_own_process_id(tmp_path, monkeypatch):
    started = []
    ended = subprocess.run(  # a process id that no longer runs
        [sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True, text=True
    )

    class Warmup:
        pid = os.getpid()  # a process that lives while the test runs

        def __init__(self, args, **kw):
            started.append(args)

    monkeypatch.delenv("SANDBOX_WARMUP", raising=False)
    monkeypatch.setattr(subprocess, "Popen", Warmup)
    assert first_run.start_background_warmup(tmp_path)
    assert started == [[sys.executable, "-m", "sandbox", "warmup", "--quiet"]]
    assert (tmp_path / first_run.LOCK).read_text() == str(os.getpid())
    assert first_run.start_background_warmup(tmp_path)  # one at a time: the lock is fresh
    assert len(started) == 1
    if os.name == "posix":  # a fresh lock whose warmup was killed holds no one back
        (tmp_path / first_run.LOCK).write_text(ended.stdout.strip())
        assert first_run.start_background_warmup(tmp_path)
        assert len(started) == 2


@pytest.mark.skipif(os.name != "posix", reason="no waiting for a warmup off POSIX")
def test_a_running_warmup_is_one_whose_lock_is_fresh_and_process_alive(tmp_path):
    lock = tmp_path / first_run.LOCK
    assert first_run.running_warmup(tmp_path) is None  # no lock
    assert first_run.running_warmup(None) is None  # no cache
    lock.write_text(str(os.getpid()))
    assert first_run.running_warmup(tmp_path) == os.getpid()
    old = time.time() - first_run.STALE - 1
    os.utime(lock, (old, old))
    assert first_run.running_warmup(tmp_path) is None  # stale: a warmup that died
    ended = subprocess.run(
        [sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True, text=True
    )
    lock.write_text(ended.stdout.strip())
    assert first_run.running_warmup(tmp_path) is None  # its process is gone
    lock.write_text("not a number")
    assert first_run.running_warmup(tmp_path) is None


@pytest.mark.skipif(os.name != "posix", reason="no waiting for a warmup off POSIX")
def test_a_second_run_waits_for_the_background_warmup(tmp_path, capsys):
    # `sandbox lessons` (several) or `sandbox warmup` after `sandbox lessons 01` started a
    # background warmup: wait for it to end, rather than compile the same kernels beside it
    assert first_run.wait_for_warmup(tmp_path, poll=0.01) is False
    assert capsys.readouterr().out == ""
    warmup = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(0.6)"])
    (tmp_path / first_run.LOCK).write_text(str(warmup.pid))
    start = time.monotonic()
    try:
        waited = first_run.wait_for_warmup(tmp_path, poll=0.01)
    finally:
        warmup.wait()
    assert waited and time.monotonic() - start > 0.3
    out = capsys.readouterr().out
    assert out.startswith("the engine is compiling in the background") and out.count("\n") == 1


def test_lessons_after_a_background_warmup_do_not_warm_up_again(monkeypatch, capsys):
    from sandbox.cli import lessons

    calls, warm = [], [False]
    monkeypatch.delenv("SANDBOX_JIT", raising=False)
    monkeypatch.setattr(compile_cache, "is_warm", lambda: warm[0])
    monkeypatch.setattr(subprocess, "Popen", lambda args, **kw: calls.append(args))
    monkeypatch.setattr(
        first_run, "wait_for_warmup", lambda folder: warm.__setitem__(0, True) or True
    )
    lessons._compile_first(lessons.FEW + 1)
    assert calls == []  # it waited, and the cache is warm now
    warm[0] = False
    monkeypatch.setattr(first_run, "wait_for_warmup", lambda folder: True)  # it ended unwarm
    lessons._compile_first(lessons.FEW + 1)
    if compile_cache.CACHE_FOLDER is not None:
        assert calls == [[sys.executable, "-m", "sandbox", "warmup", "--lessons"]]


def test_the_warmup_shares_cover_every_family_once():
    from sandbox.warmup import FIRST_SHARE, SECOND_SHARE_FIRST, part, worlds

    labels = [label for label, _, _ in worlds()]
    for jobs in (1, 2, 3):
        shares = [[label for label, _, _ in part(i, jobs)] for i in range(jobs)]
        assert sorted(sum(shares, [])) == sorted(labels)
        if jobs != 2:  # dealt round-robin
            assert all(abs(len(a) - len(b)) <= 1 for a in shares for b in shares)
    # two shares as planned: the iterative step (one call, then staged) first in the first
    # share, then continuous collision (staged too), then the soft step, which reuses their
    # stages, last of the lessons' families there (the early start waits for the others); the
    # forces at the start of the second
    first, second = ([label for label, _, _ in part(i, 2)] for i in range(2))
    assert first == list(FIRST_SHARE)
    assert second[: len(SECOND_SHARE_FIRST)] == list(SECOND_SHARE_FIRST)
    assert first[:4] == [
        "iterative solver", "iterative solver, staged", "continuous collision", "soft solver"
    ]  # fmt: skip
    assert second[0] == "explicit_euler and forces"


def test_the_lessons_warmup_steps_only_the_lessons_families_and_marks_nothing(monkeypatch):
    # `sandbox warmup --lessons` (a first `sandbox lessons`): the lessons' families, shared
    # between two processes as planned, each once; the cache is not marked warm, so that the
    # background warmup after the lessons compiles the rest (the suite's cache: all loaded)
    from sandbox import warmup

    labels = [label for label, _, _ in warmup.worlds()]
    assert set(warmup.LESSON_FAMILIES) < set(labels)
    shares = [[label for label, _, _ in warmup.part(i, 2, lessons=True)] for i in range(2)]
    assert sorted(sum(shares, [])) == sorted(warmup.LESSON_FAMILIES)
    assert shares[0][0] == "iterative solver"
    marked, heard = [], []
    monkeypatch.setattr(warmup, "mark_warm", lambda: marked.append(True))
    warmup.warm_up(heard.append, jobs=1, lessons=True)
    assert sorted(line.strip().removesuffix(": ready") for line in heard) == sorted(
        warmup.LESSON_FAMILIES
    )
    assert marked == []
    warmup.warm_up(heard.append, jobs=1)
    assert marked == [True]


def test_warmup_in_two_processes_reports_every_family_once_and_marks_warm(tmp_path):
    # the cache the suite compiled: the second process's share and the pass after it load it
    done = run(["warmup", "--jobs", "2"], {}, tmp_path)
    assert done.returncode == 0, done.stderr
    from sandbox.warmup import worlds

    lines = done.stdout.splitlines()
    for label, _, _ in worlds():
        assert lines.count(f"  {label}: ready") == 1, label
    assert lines[-1].startswith("done in ") and compile_cache.is_warm()


def test_the_other_process_reports_its_families_as_it_steps_them():
    # warm_up(jobs=2): the second process's families are ready as it steps them (its lines,
    # relayed by a thread here), not only when this process loads them again at the end; every
    # family once (the suite's compile cache: loaded)
    import threading

    from sandbox.warmup import part, warm_up, worlds

    heard = []
    warm_up(lambda line: heard.append((line, threading.current_thread().name)), jobs=2)
    lines = [line for line, _ in heard]
    for label, _, _ in worlds():
        assert lines.count(f"  {label}: ready") == 1, label
    main = threading.main_thread().name
    by_line = dict(heard)
    for index in (0, 1):
        for label, _, _ in part(index, 2):
            assert (by_line[f"  {label}: ready"] == main) is (index == 0), label


def test_the_family_bar_moves_and_keeps_time_on_a_terminal():
    from sandbox.cli.warmup import FamilyBar
    from sandbox.warmup import worlds

    screen = Terminal()
    with FamilyBar(screen, tick=0.02) as bar:
        bar.ready("  iterative solver: ready")
        bar.ready("  shock solver: ready")
        drawn = len(screen.getvalue())
        time.sleep(0.2)  # redrawn by the ticker meanwhile, with no family ready
        assert len(screen.getvalue()) > drawn
    text = screen.getvalue()
    total = sum(1 for _ in worlds())
    assert f"2/{total} families" in text and "shock solver ready, " in text
    assert " kernels compiled" in text
    assert "families/s" not in text and "<" not in text  # no rate, no time left


def test_compiles_are_counted_while_listened_to():
    from sandbox import jit

    counted = jit.CompileCount()
    jit.njit(cache=False)(lambda x: x + 1)(1)
    counted.close()
    jit.njit(cache=False)(lambda x: x + 2)(1)
    assert counted.count == (1 if jit.JIT_ENABLED else 0)


def test_many_lessons_on_a_cold_cache_say_how_the_warmup_goes(monkeypatch, capsys):
    # `sandbox lessons` for more than one lesson compiles what the lessons need first, with the
    # warmup's report (a bar on a terminal, a line per family elsewhere), not --quiet: a minute
    # is never a silent wait; the rest follows in the background after the lessons
    from sandbox.cli import lessons

    calls, started = [], []
    monkeypatch.delenv("SANDBOX_JIT", raising=False)
    monkeypatch.setattr(compile_cache, "is_warm", lambda: False)
    monkeypatch.setattr(subprocess, "Popen", lambda args, **kw: calls.append(args) or "started")
    monkeypatch.setattr(first_run, "start_background_warmup", lambda f: started.append(f) or True)
    rest = lessons._compile_first(lessons.FEW + 1)
    if compile_cache.CACHE_FOLDER is None:
        assert calls == [] and rest is None
        return
    assert calls == [[sys.executable, "-m", "sandbox", "warmup", "--lessons"]]
    assert rest == "started"  # the warmup's process, which the lessons wait for
    assert "compiling what the lessons need for this machine first" in capsys.readouterr().out
    assert started == []  # not before the lessons, which need both cores
    lessons._compile_rest()
    assert started == [compile_cache.CACHE_FOLDER]
    assert "the rest of the engine compiles in the background" in capsys.readouterr().out


def test_one_lesson_on_a_cold_cache_compiles_what_it_needs(monkeypatch, capsys):
    # no warmup of every kernel first for one lesson (lesson 01 needs 13 kernels: 10.5 s from
    # an empty cache, against 74.9 s with the warmup first): the warmup runs in the background
    # for the next runs, and one line says so
    from sandbox.cli import first_run, lessons

    calls, background = [], []
    monkeypatch.delenv("SANDBOX_JIT", raising=False)
    monkeypatch.setattr(compile_cache, "is_warm", lambda: False)
    monkeypatch.setattr(subprocess, "Popen", lambda args, **kw: calls.append(args))
    monkeypatch.setattr(first_run, "start_background_warmup", lambda f: background.append(f) or 1)
    assert lessons._compile_first(lessons.FEW) is None
    assert calls == []
    out = capsys.readouterr().out
    if compile_cache.CACHE_FOLDER is not None:
        assert background == [compile_cache.CACHE_FOLDER]
        assert out == (
            "the engine is not compiled for this machine yet: the lesson compiles what it "
            "needs as it runs, once; the rest compiles in the background for the next runs\n"
        )


def _lessons(*numbers):
    from sandbox.course.catalogue import find_lessons, pick

    return pick(find_lessons(), [str(n) for n in numbers])


def test_lessons_as_quick_uncompiled_do_not_wait_for_the_compiler(monkeypatch, capsys):
    # lesson 12 on a new machine compiled for most of a minute before it ran, for a lesson that
    # takes seconds uncompiled: it runs uncompiled now, the engine compiles in the background
    from sandbox.cli import lessons

    background = []
    monkeypatch.delenv("SANDBOX_JIT", raising=False)
    monkeypatch.setattr(compile_cache, "is_warm", lambda: False)
    monkeypatch.setattr(first_run, "start_background_warmup", lambda f: background.append(f) or 1)
    assert lessons.plain_first(_lessons(12, 13))
    assert os.environ["SANDBOX_JIT"] == "0"  # what the lessons' processes (and server) inherit
    assert background == [compile_cache.CACHE_FOLDER]
    assert capsys.readouterr().out == (
        "the engine is not compiled for this machine yet: these lessons run uncompiled (plain "
        "Python), sooner than compiling would take; the engine compiles in the background for "
        "the next runs\n"
    )


def test_without_a_background_warmup_the_line_says_how_to_compile(monkeypatch, capsys):
    from sandbox.cli import lessons

    monkeypatch.delenv("SANDBOX_JIT", raising=False)
    monkeypatch.setattr(compile_cache, "is_warm", lambda: False)
    monkeypatch.setattr(first_run, "start_background_warmup", lambda f: False)  # SANDBOX_WARMUP=off
    assert lessons.plain_first(_lessons(4))
    assert capsys.readouterr().out == (
        "the engine is not compiled for this machine yet: the lesson runs uncompiled (plain "
        "Python), sooner than compiling would take (`sandbox warmup` compiles the engine ahead "
        "of a class)\n"
    )


@pytest.mark.parametrize(
    "numbers, warm, jit",
    [((12, 16), False, None), ((16,), False, None), ((12,), True, None), ((12,), False, "1")],
    ids=["with a lesson that needs the compiler", "only such", "warm cache", "SANDBOX_JIT set"],
)
def test_otherwise_lessons_run_compiled(monkeypatch, capsys, numbers, warm, jit):
    from sandbox.cli import lessons

    background = []
    monkeypatch.delenv("SANDBOX_JIT", raising=False)
    if jit is not None:
        monkeypatch.setenv("SANDBOX_JIT", jit)
    monkeypatch.setattr(compile_cache, "is_warm", lambda: warm)
    monkeypatch.setattr(first_run, "start_background_warmup", lambda f: background.append(f) or 1)
    assert not lessons.plain_first(_lessons(*numbers))
    assert os.environ.get("SANDBOX_JIT") == jit and background == []
    assert capsys.readouterr().out == ""


def test_a_lesson_on_a_new_machine_runs_uncompiled_and_compiles_nothing(tmp_path):
    # the whole command, from an empty cache: the line, then the lesson's process uncompiled
    # (compiled, lesson 17 took 43.4 s compiling what it needs; uncompiled 3.7 s)
    env = {k: v for k, v in os.environ.items() if k != "SANDBOX_JIT"}
    env.update(NUMBA_CACHE_DIR=str(tmp_path / "cache"), SANDBOX_WARMUP="off")
    cmd = [sys.executable, "-m", "sandbox", "lessons", "17", "--scripts", "--out", str(tmp_path)]
    done = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "the lesson runs uncompiled (plain Python)" in done.stdout
    line = next(s for s in done.stdout.splitlines() if s.startswith("== 17_"))
    assert ": ok in " in line and "compiled" not in line  # no kernel compiled on the way
    assert (tmp_path / "17_simultaneous_contact_lcp" / "tables.md").exists()


def test_a_warm_cache_runs_the_lessons_at_once(monkeypatch, capsys):
    from sandbox.cli import lessons

    calls = []
    monkeypatch.setattr(compile_cache, "is_warm", lambda: True)
    monkeypatch.setattr(subprocess, "Popen", lambda args, **kw: calls.append(args))
    assert lessons._compile_first(19) is None
    assert calls == [] and capsys.readouterr().out == ""


def test_compiles_go_to_the_compile_log_instead_of_the_notice(tmp_path):
    # with SANDBOX_COMPILE_LOG (set by `sandbox lessons` for each lesson) a compile is a line
    # in that file, and nothing is printed: the lesson's page stays clean, the command counts
    log = tmp_path / "lesson.compiles"
    code = "from sandbox import jit\njit.njit(cache=False)(lambda x: x + 1)(1)\n"
    env = {**os.environ, "SANDBOX_JIT": "1", compile_cache.COMPILE_LOG: str(log)}
    done = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert done.stderr == "" and done.stdout == ""
    assert log.read_text().splitlines() == ["<lambda>"]
    env.pop(compile_cache.COMPILE_LOG)
    done = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True)
    assert "note: compiling the engine for this machine" in done.stderr  # without: the notice


def test_a_lesson_run_counts_what_it_compiled(tmp_path):
    from sandbox.course.catalogue import Lesson
    from sandbox.course.runner import run_script

    path = tmp_path / "lessons" / "99_compiles.py"
    path.parent.mkdir()
    path.write_text(
        "from sandbox import jit\n"
        "jit.njit(cache=False)(lambda x: x + 1)(1)\n"
        "jit.njit(cache=False)(lambda x: x + 2)(1)\n"
    )
    logs = tmp_path / "logs"
    logs.mkdir()
    outcome = run_script(Lesson(path), tmp_path / "out", logs)
    assert outcome.ok, outcome.error
    assert outcome.compiled == (0 if os.environ.get("SANDBOX_JIT") == "0" else 2)
    assert run_script(Lesson(path), tmp_path / "out").compiled == 0  # no log: not counted


def test_the_lesson_bar_moves_keeps_time_and_counts_kernels(monkeypatch):
    from sandbox.cli.lessons import LessonBar
    from sandbox.course.catalogue import Lesson
    from sandbox.course.runner import Outcome

    screen = Terminal()
    monkeypatch.setattr(sys, "stdout", screen)
    with LessonBar(2, lambda: "18 kernels compiled", tick=0.02) as bar:
        bar.report(Outcome(Lesson(Path("01_projectile.py")), 8.1, compiled=18))
        drawn = len(screen.getvalue())
        time.sleep(0.2)  # redrawn by the ticker meanwhile, with no lesson done
        assert len(screen.getvalue()) > drawn
    text = screen.getvalue()
    assert "== 01_projectile: ok in 8.1 s, compiled 18 kernels\n" in text
    assert "1/2 lessons" in text and "18 kernels compiled]" in text
    assert "lessons/s" not in text and "<" not in text  # no rate, no time left


def test_the_warmup_in_a_log_says_no_compile_notice():
    # `sandbox warmup` reports its families itself: the first-run notice ("note: compiling the
    # engine ...") is not printed above them, also when it compiles (here: one function)
    code = (
        "import sandbox.warmup as w\n"
        "from sandbox import jit\n"
        "from sandbox.cli import main\n"
        "w.warm_up = lambda report, jobs, lessons: (\n"
        "    jit.njit(cache=False)(lambda x: x + 1)(1) or 0.0\n"
        ")\n"
        "raise SystemExit(main(['warmup']))\n"
    )
    env = {**os.environ, "SANDBOX_JIT": "1"}
    done = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert "compiling the engine for this machine" not in done.stderr
    assert done.stdout.startswith("compiling the engine into ")


def test_warmup_refuses_a_bad_share_in_one_line(tmp_path):
    for bad in ("2/2", "x/2", "1"):
        done = run(["warmup", "--part", bad], {}, tmp_path)
        assert done.returncode == 2 and "--part" in done.stderr, bad


@pytest.mark.parametrize(("bodies", "steps", "plain"), [(103, 300, True), (134, 300, False)])
def test_every_bundled_scene_at_the_default_steps_runs_uncompiled(
    monkeypatch, bodies, steps, plain
):
    # the largest bundled scene (rain: 103 bodies) at the default 300 steps is 30,900
    # body-steps, uncompiled in about 10 s against about 50 s to compile; 134 x 300 = 40,200 is
    # past the bound (PLAIN_BODY_STEPS) and compiles
    monkeypatch.setattr(first_run, "note", lambda text: None)
    monkeypatch.delenv("SANDBOX_JIT", raising=False)
    monkeypatch.setenv("SANDBOX_WARMUP", "off")
    monkeypatch.setattr(first_run, "engine_imported", lambda: False)
    monkeypatch.setattr(compile_cache, "is_warm", lambda: False)
    monkeypatch.setattr(compile_cache, "has_kernel", lambda name: False)
    first_run.choose_engine_speed({"bodies": [{}] * bodies}, steps)
    assert (os.environ.pop("SANDBOX_JIT", None) == "0") is plain


@pytest.mark.parametrize("quiet", [False, True])
def test_a_quiet_warmup_prints_no_compile_notice(quiet):
    # `sandbox warmup --quiet` prints nothing, the compile notice included: a function
    # compiled after quiet_compiles() says nothing; without it, the line
    code = (
        "from sandbox import jit\n"
        f"if {quiet}: jit.quiet_compiles()\n"
        "jit.njit(cache=False)(lambda x: x + 1)(1)\n"
    )
    env = {**os.environ, "SANDBOX_JIT": "1"}
    done = subprocess.run(
        [sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True
    )
    assert ("compiling the engine" in done.stderr) is not quiet
    assert done.stderr.strip() == "" or not quiet


def test_the_wait_shows_its_line_and_the_time_so_far_redrawn_every_tick():
    # a wait has no parts to count: the line stands in for the bar, and the clock ticks
    from sandbox.cli.progress import TickingBar

    screen = io.StringIO()
    with TickingBar(screen, 1, "", str, tick=0.05, line="waiting for the background warmup"):
        time.sleep(0.3)
    drawn = [d for d in screen.getvalue().split("\r") if d.strip()]
    assert len(drawn) >= 3  # drawn when it starts, then at least twice by the ticker
    # the time so far: 00:00 unless a busy machine holds the 0.3 s up past a second
    shown = r"waiting for the background warmup \[00:0\d\]"
    assert all(re.fullmatch(shown, d) for d in drawn), drawn


def test_a_first_run_starts_the_lessons_once_the_warmup_is_done(monkeypatch, tmp_path):
    # a first `sandbox lessons`: the kernels' server starts (without the engine) beside the
    # warmup; once the warmup says every family but the soft step's is ready, the server loads
    # those and the lessons that need no soft step start, one at a time; the others start once
    # the warmup is done and the server has loaded the rest
    import time
    from contextlib import contextmanager

    from sandbox.cli import lessons
    from sandbox.course import runner
    from sandbox.course.catalogue import find_lessons

    every = find_lessons(Path(__file__).resolve().parent.parent / "lessons")
    chosen = [lesson for lesson in every if lesson.stem[:2] in ("01", "02", "16")]
    events = []

    class Warmup:  # the warmup's process: signals early, then is done after the early lessons
        def __init__(self, early):
            self.early, self.returncode, self.start = early, None, time.monotonic()

        def poll(self):
            if not self.early.exists():
                self.early.touch()
            elif events.count("lesson") == 2 or time.monotonic() - self.start > 20:
                events.append("warmup done")
                self.returncode = 0
            return self.returncode

    @contextmanager
    def kernels(folder, outputs, engine=False):
        events.append(f"server, engine={engine}")
        yield folder / "kernels"

    def run_notebook(lesson, outputs, specs, logs=None):
        events.append("lesson")
        events.append(lesson.stem[:2])
        return runner.Outcome(lesson, 0.0)

    monkeypatch.setattr(lessons, "_compile_first", lambda chosen, early=None: Warmup(early))
    monkeypatch.setattr(lessons, "_compile_rest", lambda: events.append("rest"))
    monkeypatch.setattr(runner, "kernels", kernels)
    monkeypatch.setattr(runner, "run_notebook", run_notebook)
    monkeypatch.setattr(
        runner, "load_engine", lambda specs, early=False: events.append(f"engine, early={early}")
    )
    outcomes = lessons._run_all(chosen, tmp_path, notebooks=True, jobs=2)
    assert [o.lesson.stem for o in outcomes] == [lesson.stem for lesson in chosen]
    assert events[:2] == ["server, engine=False", "engine, early=True"]
    early = events[2 : events.index("warmup done")]
    assert sorted(e for e in early if e != "lesson") == ["01", "02"]  # no soft step before
    assert events[events.index("warmup done") :] == [
        "warmup done", "engine, early=False", "lesson", "16", "rest"
    ]  # fmt: skip


def test_the_server_loads_the_engine_only_for_more_lessons_than_run_at_once(monkeypatch, tmp_path):
    # loading it takes the server about a second before its first kernel: it pays when many
    # lessons share it, not for one lesson (`sandbox lessons 17`: 2.9 s without, 3.3 s with)
    from contextlib import contextmanager

    from sandbox.cli import lessons
    from sandbox.course import runner
    from sandbox.course.catalogue import find_lessons

    every = find_lessons(Path(__file__).resolve().parent.parent / "lessons")
    asked = []

    @contextmanager
    def kernels(folder, outputs, engine=False):
        asked.append(engine)
        yield folder / "kernels"

    monkeypatch.setattr(lessons, "_compile_first", lambda chosen, early=None: None)
    monkeypatch.setattr(compile_cache, "is_warm", lambda: True)
    monkeypatch.setattr(runner, "kernels", kernels)
    monkeypatch.setattr(runner, "run_notebook", lambda lesson, *a: runner.Outcome(lesson, 0.0))
    for chosen in (every[:1], every[:2], every[:3]):
        lessons._run_all(chosen, tmp_path, notebooks=True, jobs=2)
    assert asked == [False, False, True]


def test_a_warmup_stopped_by_a_signal_stops_its_other_share(tmp_path):
    # `kill` of the warmup (the process id in a background warmup's lock) stops the process
    # compiling the other share too: it went on compiling for a minute, unowned, while a next
    # run, seeing no warmup, started another. An empty cache, so both are busy compiling
    env = {k: v for k, v in os.environ.items() if k != "SANDBOX_JIT"}
    env["NUMBA_CACHE_DIR"] = str(tmp_path / "cache")
    parent = subprocess.Popen(
        [sys.executable, "-m", "sandbox", "warmup", "--quiet", "--jobs", "2"],
        env=env,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
    )
    children = Path(f"/proc/{parent.pid}/task/{parent.pid}/children")
    if not children.exists():
        parent.kill()
        pytest.skip("the process tree is read from /proc (Linux)")
    deadline = time.monotonic() + 60
    share = ""
    while not share and time.monotonic() < deadline:
        share = children.read_text().strip()
        time.sleep(0.1)
    assert share, "the warmup started no second share"
    time.sleep(3)  # both inside their compiles
    # a lock as a background warmup's (sandbox.cli.first_run), in the cache folder it compiles to
    lock = tmp_path / "cache" / compile_cache.CACHE_FOLDER.name / first_run.LOCK
    lock.write_text(str(parent.pid))
    parent.terminate()
    # 128 + SIGTERM, as the command line reports it (once the compile it is in returns)
    assert parent.wait(timeout=120) == 143
    assert not lock.exists()  # or the next run would start no warmup for ten minutes
    alive = Path(f"/proc/{int(share.split()[0])}")
    deadline = time.monotonic() + 60
    while alive.exists() and "Z" not in (alive / "stat").read_text().split()[2]:
        assert time.monotonic() < deadline, "the other share is still compiling"
        time.sleep(0.2)
