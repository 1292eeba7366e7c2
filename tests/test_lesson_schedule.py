"""A first `sandbox lessons` starts the lessons that need no soft-step kernel on the core the
warmup's second share leaves, before the warmup is done (sandbox.cli.lessons.Schedule): the
warmup says when every other family of the lessons is ready (sandbox.warmup.Once), and the
catalogue says which lessons need the soft step's kernels."""

import threading
from pathlib import Path

import pytest

from sandbox.cli.lessons import Schedule
from sandbox.course.catalogue import Lesson, find_lessons
from sandbox.warmup import LATE_FAMILIES, LESSON_FAMILIES, Once

ROOT = Path(__file__).resolve().parent.parent


def fake_lessons(folder: Path) -> list[Lesson]:
    """Four lessons: two that run the soft step, two that do not; the larger files first."""
    texts = {
        "01_small.py": "x = 1\n",
        "02_soft_big.py": 'solver = "soft"\n' + "# long\n" * 40,
        "03_big.py": "y = 2\n" + "# long\n" * 30,
        "04_colour.py": "colour(contacts)\n" + "# long\n" * 10,
    }
    for name, text in texts.items():
        (folder / name).write_text(text)
    return [Lesson(folder / name) for name in texts]


def test_the_bundled_lessons_that_need_the_soft_step():
    flagged = {
        lesson.stem[:2] for lesson in find_lessons(ROOT / "lessons") if lesson.needs_soft_kernels
    }
    assert flagged == {"08", "09", "16"}  # the soft step's pile, the colouring, the soft lesson


def test_the_bundled_lessons_that_run_uncompiled_on_a_new_machine():
    from sandbox.course.catalogue import PLAIN_FIRST

    lessons = find_lessons(ROOT / "lessons")
    assert PLAIN_FIRST <= {lesson.stem for lesson in lessons}  # each names a lesson there is
    plain = {lesson.stem[:2] for lesson in lessons if lesson.plain_first}
    # not the lessons that step piles, the soft step or every broadphase: minutes uncompiled
    assert plain.isdisjoint({"02", "05", "06", "08", "09", "16"}) and len(plain) == 12


def test_early_worker_runs_only_lessons_without_the_soft_step_until_late(tmp_path):
    lessons = fake_lessons(tmp_path)
    started, release = [], threading.Event()

    def run(lesson):
        started.append((lesson.stem, schedule.late.is_set()))
        release.wait(10)
        return lesson.stem

    schedule = Schedule(lessons, run, jobs=2)
    assert not started  # nothing runs before the warmup says so
    schedule.open(early=True)
    release.set()
    for stem in ("03_big", "01_small"):  # the early worker: the larger first, no soft step
        assert schedule.results[stem].result(timeout=10) == stem
    assert [s for s, _ in started] == ["03_big", "01_small"]
    assert not any(late for _, late in started)
    assert not schedule.results["02_soft_big"].done()  # waits for the soft step's kernels
    schedule.open(late=True)
    assert schedule.results["02_soft_big"].result(timeout=10) == "02_soft_big"
    assert schedule.results["04_colour"].result(timeout=10) == "04_colour"
    assert {s for s, late in started if late} == {"02_soft_big", "04_colour"}


@pytest.mark.parametrize("jobs", [1, 2, 3])
def test_every_lesson_runs_once_when_all_open_at_once(tmp_path, jobs):
    lessons = fake_lessons(tmp_path)
    runs = []
    schedule = Schedule(lessons, lambda lesson: runs.append(lesson.stem) or lesson.stem, jobs)
    schedule.open(early=True, late=True)
    assert [schedule.results[lesson.stem].result(timeout=10) for lesson in lessons] == [
        lesson.stem for lesson in lessons
    ]
    assert sorted(runs) == sorted(lesson.stem for lesson in lessons)
    if jobs == 1:  # one worker: longest first
        assert runs == ["02_soft_big", "03_big", "04_colour", "01_small"]


def test_the_warmup_signals_once_every_family_but_the_soft_steps_is_ready(tmp_path):
    signal = tmp_path / "early-ready"
    early = {f"  {label}: ready" for label in LESSON_FAMILIES if label not in LATE_FAMILIES}
    lines = []
    once = Once(lines.append, early, str(signal))
    for line in sorted(early)[:-1]:
        once(line)
        once(line)  # a family loaded again is not ready twice
    assert not signal.exists()
    for label in LATE_FAMILIES:
        once(f"  {label}: ready")
    assert not signal.exists()  # the soft step's families do not stand in for the others
    once(sorted(early)[-1])
    assert signal.exists()
    assert len(lines) == len(early) + len(LATE_FAMILIES)
    assert set(LATE_FAMILIES) <= set(LESSON_FAMILIES)


def test_a_failure_of_the_runner_itself_reaches_the_caller(tmp_path):
    # `sandbox lessons` turns a lesson's own failure into its outcome; anything the runner
    # raises besides comes out where the result is read, instead of leaving it waiting
    lessons = fake_lessons(tmp_path)

    def run(lesson):
        if lesson.stem == "03_big":
            raise RuntimeError("the runner broke")
        return lesson.stem

    schedule = Schedule(lessons, run, jobs=2)
    schedule.open(early=True, late=True)
    with pytest.raises(RuntimeError, match="the runner broke"):
        schedule.results["03_big"].result(timeout=10)
    assert schedule.results["01_small"].result(timeout=10) == "01_small"
