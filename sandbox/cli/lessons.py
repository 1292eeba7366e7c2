"""``sandbox lessons [NAME ...] [--out DIR]``: run lessons into ``outputs/``, as executed
notebooks with their HTML pages when the notebook tools are installed (else as scripts), and
write the course book ``outputs/index.html``."""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import threading
import time
from concurrent.futures import Future
from pathlib import Path

from sandbox.cli.common import CliError, field_type
from sandbox.fieldspec import Field

JOBS = Field("jobs", "integer", "lessons run at a time", None, "", lo=1, hi=64)
FEW = 1  # lessons that compile what they need as they run, on a first run (no warmup first)


def add_parser(sub) -> None:
    """The ``lessons`` command and its options."""
    les = sub.add_parser(
        "lessons",
        help="run lessons into ./outputs (notebooks, pages, figures)",
        description="Run lessons (all, or those named) into ./outputs (inside a checkout, its\n"
        "outputs/): figures, animations, tables.md, the executed notebook and its HTML page per\n"
        "lesson, and the course book outputs/index.html.",
        epilog="examples:\n  sandbox lessons\n  sandbox lessons 01 07\n  sandbox lessons friction"
        "\n  sandbox lessons 10 --out course/",
    )
    les.add_argument(
        "names", nargs="*", metavar="NAME", help="a number (10), a file stem or part of a name"
    )
    les.add_argument("--out", metavar="DIR", help="write here instead of ./outputs")
    les.add_argument(
        "--jobs",
        type=field_type(JOBS, "--jobs"),
        default=None,
        help="lessons run at a time (default: 2, or 1 on a single core)",
    )
    les.add_argument(
        "--scripts",
        action="store_true",
        help="run as plain scripts: figures and tables only, no notebooks or pages",
    )
    les.set_defaults(func=run)


def default_outputs() -> Path:
    """``./outputs``, or the checkout's ``outputs/`` when the working folder is inside one."""
    from sandbox.lessonkit import repo_root

    root = repo_root()
    inside = (root / "lessons").is_dir() and (root / "pyproject.toml").is_file()
    return (root if inside else Path.cwd()) / "outputs"


def output_folder(out: str | None) -> Path:
    """The folder to write to (created); ``--out`` must be a folder in an existing one."""
    folder = Path(out) if out else default_outputs()
    if folder.exists() and not folder.is_dir():
        raise CliError("--out", f"{str(folder)!r} is not a folder")
    if not folder.exists() and not folder.absolute().parent.is_dir():
        raise CliError("--out", f"folder {str(folder.absolute().parent)!r} does not exist")
    folder.mkdir(exist_ok=True)
    if not os.access(folder, os.W_OK):
        raise CliError("--out", f"folder {str(folder)!r} is not writable")
    return folder.resolve()


def run(args: argparse.Namespace) -> int:
    """Run each lesson (a notebook or a script, in its own process), then the course book."""
    from sandbox.bundled import lessons_folder
    from sandbox.course.book import write_book
    from sandbox.course.catalogue import find_lessons, pick
    from sandbox.course.links import book_problems
    from sandbox.course.runner import INSTALL_HINT, missing_notebook_tools

    lessons = find_lessons()
    try:
        chosen = pick(lessons, args.names)
    except LookupError as err:
        where = "NAME" if lessons else "lessons"
        message = str(err) if lessons else f"no lesson found in {lessons_folder()}"
        raise CliError(where, message) from None
    outputs = output_folder(args.out)
    missing = [] if args.scripts else missing_notebook_tools()
    notebooks = not args.scripts and not missing
    jobs = args.jobs or min(2, os.cpu_count() or 1)
    kind = "executed notebooks with HTML pages" if notebooks else "scripts"
    jobs = min(jobs, len(chosen))
    count = f"{len(chosen)} lesson" + ("s" if len(chosen) > 1 else "")
    at_a_time = f", {jobs} at a time" if jobs > 1 else ""
    print(f"writing {count} to {outputs} as {kind}{at_a_time}", flush=True)
    if missing:
        print(f"note: notebooks and HTML pages need {INSTALL_HINT} (missing: {', '.join(missing)})")
    outcomes = _run_all(chosen, outputs, notebooks, jobs)
    note = "" if notebooks or args.scripts else f"Notebooks and pages need {INSTALL_HINT}."
    book = write_book(lessons, outputs, note)
    failed = [o.lesson.stem for o in outcomes if not o.ok]
    print(f"course book: {book}")
    problems = book_problems(book)
    if problems:
        print(f"warning: course book: {len(problems)} problems, e.g. {problems[0]}")
    if failed:
        print(f"error: lessons: {len(failed)} failed: {', '.join(failed)}", file=sys.stderr)
        return 1
    return 0


def _compile_first(chosen: int, early: Path | None = None) -> subprocess.Popen | None:
    """On a machine where the engine was never compiled: for more than :data:`FEW` lesson,
    start compiling what the lessons need once before them (``sandbox warmup --lessons``: on a
    terminal its progress bar, elsewhere a line per family of kernels ready), rather than in
    each lesson's process, the same kernels at the same time; the rest of the engine is left
    for a background warmup after the lessons (:func:`_compile_rest`). Returns the warmup's
    process (the lessons wait for it), or None.
    A single lesson (one that takes seconds uncompiled runs so instead, :func:`plain_first`)
    compiles what it needs itself as it runs, while the warmup compiles the rest in the
    background at a low priority (as a small scene's first run does,
    :func:`sandbox.cli.first_run.start_background_warmup`): on two cores it takes the other
    core, and compiles ahead what the lesson needs later. Either way one line says so first.

    Measured from an empty cache (``sandbox lessons NAME``, notebooks, the project's 2-core
    machine): lesson 01 10.5 s (13 kernels), against 74.9 s with the warmup first; lesson 16,
    the one that needs the most (both solvers), 83.8 s against 92.2. Two lessons that each
    need a solver do better with the warmup first (09 and 16: 80.7 s, against 105.2 s each
    compiling what it needs), which shares the compiling out between the two cores without
    compiling anything twice. All lessons: the lessons' kernels alone take 53.5 s to compile,
    every kernel 62 s.

    If a background warmup (an earlier run's) is compiling, it is waited for
    (:func:`sandbox.cli.first_run.wait_for_warmup`) instead of being run again beside it: all
    lessons right after ``sandbox lessons 01`` took 191.8 s, and 125.3 s waiting.

    ``early``: a file the warmup creates once every family of the lessons but the soft step's
    is ready (:data:`sandbox.warmup.EARLY_READY`), so that the lessons that need none of those
    start then (:func:`_run_all`)."""
    from sandbox.compile_cache import CACHE_FOLDER, is_warm

    if os.environ.get("SANDBOX_JIT") == "0" or CACHE_FOLDER is None or is_warm():
        return None
    if chosen <= FEW:
        from sandbox.cli.first_run import start_background_warmup

        later = (
            "; the rest compiles in the background for the next runs"
            if start_background_warmup(CACHE_FOLDER)
            else " (`sandbox warmup` compiles everything ahead of a class)"
        )
        print(
            "the engine is not compiled for this machine yet: the lesson compiles what it "
            f"needs as it runs, once{later}",
            flush=True,
        )
        return None
    from sandbox.cli.first_run import wait_for_warmup

    if wait_for_warmup(CACHE_FOLDER) and is_warm():
        return None
    print(
        "compiling what the lessons need for this machine first, once (about a minute; the "
        "rest of the engine compiles in the background after them)",
        flush=True,
    )
    from sandbox.warmup import EARLY_READY

    env = dict(os.environ, **({EARLY_READY: str(early)} if early is not None else {}))
    return subprocess.Popen([sys.executable, "-m", "sandbox", "warmup", "--lessons"], env=env)


def plain_first(chosen) -> bool:
    """On a machine where the engine is not compiled yet (the cache is not warm), when every
    chosen lesson takes seconds uncompiled (:attr:`sandbox.course.catalogue.Lesson.plain_first`):
    run them uncompiled (``SANDBOX_JIT=0`` for the lessons' processes, set here), saying so in
    one line, while ``sandbox warmup`` compiles the engine in the background for the next runs
    (as a small scene's first run does, :func:`sandbox.cli.first_run.choose_engine_speed`).
    Returns whether it did. ``SANDBOX_JIT`` set by the user decides alone.

    Measured on the project's 2-core machine from an empty cache, one lesson: ``sandbox lessons
    04`` took 37.2 s compiling its 168 kernels as it ran, ``12`` 39.5 s and ``19`` 45.7 s;
    uncompiled, 4.0, 8.3 and 8.0 s (compiled from a warm cache, 4.9, 6.7 and 4.7 s). All twelve
    together: 52.2 s uncompiled, 70.6 s with the lessons' warmup first.
    Uncompiled code costs more CPU time in some of these lessons, so among lessons that wait for
    the compiler anyway they run compiled: lessons 12, 13 and 19 took 21 to 23 CPU-s uncompiled
    against 13 to 16 compiled, about what compiling the kernels only they need costs."""
    from sandbox.compile_cache import is_warm

    if "SANDBOX_JIT" in os.environ or not all(lesson.plain_first for lesson in chosen):
        return False
    if is_warm():  # read after the names: it looks for the cache's marker on disk
        return False
    from sandbox.cli.first_run import run_uncompiled

    later = (
        "; the engine compiles in the background for the next runs"
        if run_uncompiled()  # SANDBOX_JIT=0 for every process the lessons run in
        else " (`sandbox warmup` compiles the engine ahead of a class)"
    )
    which = "these lessons run" if len(chosen) > 1 else "the lesson runs"
    print(
        f"the engine is not compiled for this machine yet: {which} uncompiled (plain Python), "
        f"sooner than compiling would take{later}",
        flush=True,
    )
    return True


def _compile_rest() -> None:
    """After lessons that compiled only what they need: the rest of the engine in a
    background warmup, for the next runs (one line says so, or how to do it by hand)."""
    from sandbox.cli.first_run import start_background_warmup
    from sandbox.compile_cache import CACHE_FOLDER

    if start_background_warmup(CACHE_FOLDER):
        print("the rest of the engine compiles in the background for the next runs", flush=True)
    else:
        print("`sandbox warmup` compiles the rest of the engine ahead of a class", flush=True)


def _run_all(chosen, outputs: Path, notebooks: bool, jobs: int) -> list:
    """Run the lessons, ``jobs`` at a time; one line per lesson, in course order, saying how
    many kernels it compiled if any; on a terminal, a progress bar over the lessons below them.

    The engine is compiled first where that is sooner (:func:`_compile_first`), so that the
    lessons load its kernels instead of each compiling them at the same time; what the lessons
    do not need is compiled in the background after them (:func:`_compile_rest`). The longest
    lessons start first (by the size of their source), so that no core idles at the end waiting
    on one long lesson. Each lesson writes only its own folder, so the outputs do not depend on
    ``jobs`` or the order. The kernels a lesson compiles are counted in a log
    (:func:`sandbox.course.runner.compile_log`) rather than announced in its page.

    While the warmup compiles, the lessons' kernel server imports its libraries (the lessons'
    first kernels would otherwise wait for it), and loads the compiled engine once the warmup
    is done. The warmup's second share ends a few seconds before its first, which compiles the
    soft step last: from then on, one lesson at a time that does not need the soft step
    (:attr:`sandbox.course.catalogue.Lesson.needs_soft_kernels`) runs on the core it left, its
    kernel started with the rest of the engine loaded (:class:`Schedule`).
    """
    from contextlib import ExitStack

    from sandbox.compile_cache import is_warm
    from sandbox.course.runner import (
        Outcome,
        compiled_in,
        kernels,
        load_engine,
        run_notebook,
        run_script,
    )

    with ExitStack() as stack:
        tmp = stack.enter_context(tempfile.TemporaryDirectory(prefix="sandbox-kernel-"))
        early = Path(tmp) / "early-ready"
        plain = plain_first(chosen)  # then nothing is compiled first, nor in the lessons
        warmup = None if plain else _compile_first(len(chosen), early if jobs > 1 else None)
        # kernels start with the compiled engine: at once when it is in the cache, else once
        # the warmup has compiled it (the server imports its libraries meanwhile); only for more
        # lessons than run at a time, as the server loads it before the first kernel starts
        # (about a second; `sandbox lessons 17`: 2.9 s without, 3.3 s with)
        engine = warmup is None and is_warm() and len(chosen) > jobs
        specs = stack.enter_context(kernels(Path(tmp), outputs, engine)) if notebooks else None
        logs = Path(tmp) / "compiles"
        logs.mkdir()

        def one(lesson) -> Outcome:
            try:
                if specs is not None:
                    return run_notebook(lesson, outputs, specs, logs)
                return run_script(lesson, outputs, logs)
            except Exception as err:  # the runner's own failure: one line, the others go on
                return Outcome(lesson, 0.0, f"{type(err).__name__}: {err}")

        def compiled() -> str:
            count = sum(compiled_in(log) for log in logs.glob("*.compiles"))
            return f"{count} kernels compiled" if count else ""

        schedule = Schedule(chosen, one, jobs)
        with LessonBar(len(chosen), compiled) as bar:
            if warmup is None:
                schedule.open(early=True, late=True)
            else:
                while warmup.poll() is None:  # the first lessons start once the rest is ready
                    if early.exists() and not schedule.early.is_set():
                        if specs is not None:
                            load_engine(specs, early=True)
                        schedule.open(early=True)
                    time.sleep(0.1)
                if warmup.returncode == 0 and specs is not None:
                    load_engine(specs)  # what the warmup compiled, once, for every kernel
                schedule.open(early=True, late=True)
            outcomes = [bar.report(schedule.results[lesson.stem].result()) for lesson in chosen]
    if warmup is not None:
        _compile_rest()
    return outcomes


class Schedule:
    """Worker threads running ``run(lesson)`` for each lesson, longest first (by the size of
    its source). One worker starts once :meth:`open` says ``early``, and runs only lessons that
    do not need the soft step's kernels until it says ``late``; the others start then, and from
    then on every lesson may run. ``results[stem]`` is each lesson's future."""

    def __init__(self, lessons, run, jobs: int) -> None:
        self.pending = sorted(lessons, key=lambda lesson: -lesson.path.stat().st_size)
        self.soft = {lesson.stem for lesson in lessons if lesson.needs_soft_kernels}  # read once
        self.results = {lesson.stem: Future() for lesson in lessons}
        self.run, self.lock = run, threading.Lock()
        self.early, self.late = threading.Event(), threading.Event()
        for k in range(jobs):
            gate = self.early if k == 0 else self.late
            threading.Thread(target=self._work, args=(gate,), daemon=True).start()

    def open(self, early: bool = False, late: bool = False) -> None:
        """Let the early worker (``early``), then every worker and every lesson (``late``) go."""
        if late:
            self.late.set()
        if early or late:
            self.early.set()

    def _next(self):
        """The next lesson to run, or None when none is left; waits while only lessons that
        need the soft step's kernels are left and those are not loaded yet."""
        while True:
            with self.lock:
                if not self.pending:
                    return None
                late = self.late.is_set()
                for i, lesson in enumerate(self.pending):
                    if late or lesson.stem not in self.soft:
                        return self.pending.pop(i)
            self.late.wait()

    def _work(self, gate: threading.Event) -> None:
        gate.wait()
        while (lesson := self._next()) is not None:
            try:
                self.results[lesson.stem].set_result(self.run(lesson))
            except BaseException as err:  # reported where the result is read, not lost here
                self.results[lesson.stem].set_exception(err)


class LessonBar:
    """Where the lessons' lines go: printed as each is reported, and on a terminal above a
    progress bar over the lessons (:class:`sandbox.cli.progress.TickingBar`) that shows the time
    so far and, on a first run, how many kernels the lessons have compiled (``compiled()``)."""

    def __init__(self, total: int, compiled, tick: float = 1.0) -> None:
        self.bar = None
        if sys.stdout.isatty():
            from sandbox.cli.progress import TickingBar

            self.bar = TickingBar(sys.stdout, total, "lessons", compiled, tick)

    def report(self, outcome):
        """The lesson's line (``== NN_name: ok in 4.2 s``), and the bar moved on."""
        status = "ok" if outcome.ok else f"FAILED: {outcome.error}"
        kernels = f", compiled {outcome.compiled} kernels" if outcome.compiled else ""
        line = f"== {outcome.lesson.stem}: {status} in {outcome.seconds:.1f} s{kernels}"
        if self.bar is None:
            print(line, flush=True)
        else:
            self.bar.write(line)
            self.bar.advance()
        return outcome

    def __enter__(self) -> LessonBar:
        return self

    def __exit__(self, *exc: object) -> None:
        if self.bar is not None:
            self.bar.__exit__(*exc)
