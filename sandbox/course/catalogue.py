"""Which lessons exist (``NN_name.py`` in the bundled lessons folder), what each is called and
how it opens, and picking lessons by number, file stem or a unique part of the name."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

# what a lesson's source says when it runs the soft step's kernels (Lesson.needs_soft_kernels)
SOFT_KERNEL_NAMES = ('"soft"', "'soft'", "solve_joints_direct", "solve_joints_soft", "colour(")

# the lessons that take seconds uncompiled (plain Python, ``SANDBOX_JIT=0``) and write the same
# files to the byte: on a machine where the engine is not compiled yet, these run uncompiled
# rather than wait for the compiler (:func:`sandbox.cli.lessons.plain_first`). Measured on the
# project's 2-core machine, ``sandbox lessons NN`` (a notebook), from an empty cache: 3.7 to
# 19.0 s uncompiled, against 36 to 52 s compiling what the lesson needs for the ten that step
# contacts (5.8 and 8.7 s for the other two), and 0.8 to 1.7 times as long as compiled from a
# warm cache (docs/architecture.md has the table); the other lessons take 40 s to over two
# minutes uncompiled (the pyramids, the soft step, every broadphase)
PLAIN_FIRST = frozenset(
    {
        "01_projectile",
        "03_forces_and_inertia",
        "04_collision_detection",
        "07_collision_response",
        "10_friction",
        "11_joints",
        "12_springs_and_buoyancy",
        "13_user_and_agent_input",
        "14_pymunk_side_by_side",
        "17_simultaneous_contact_lcp",
        "18_fixed_timestep",
        "19_soft_bodies",
    }
)


@dataclass(frozen=True)
class Lesson:
    """One lesson file: ``path`` is ``.../NN_name.py``."""

    path: Path

    @property
    def stem(self) -> str:
        return self.path.stem

    @property
    def number(self) -> int:
        return int(self.stem.split("_", 1)[0])

    @property
    def title(self) -> str:
        """The first Markdown heading (``# 10 Friction``), or the file stem."""
        return self.intro()[0]

    @property
    def opening(self) -> str:
        """The first paragraph after the title (Markdown), or ""."""
        return self.intro()[1]

    @property
    def needs_soft_kernels(self) -> bool:
        """Whether the lesson runs the soft step or calls the kernels a first run's warmup
        compiles after it (:data:`sandbox.warmup.LATE_FAMILIES`): its source names the solver
        ``"soft"``, the soft step's joint passes or the colouring. The others can start before
        those are compiled (:mod:`sandbox.cli.lessons`)."""
        source = self.path.read_text(encoding="utf-8")
        return any(name in source for name in SOFT_KERNEL_NAMES)

    @property
    def plain_first(self) -> bool:
        """Whether the lesson runs uncompiled while the engine is not compiled for the machine
        (:data:`PLAIN_FIRST`): seconds uncompiled, the same files written."""
        return self.stem in PLAIN_FIRST

    def intro(self) -> tuple[str, str]:
        """``(title, opening paragraph)`` read from the first Markdown cell of the file."""
        return read_intro(self.path.read_text(encoding="utf-8"), self.stem)


def read_intro(source: str, fallback: str) -> tuple[str, str]:
    """Title and opening paragraph of a jupytext percent-format lesson's first Markdown cell."""
    lines = source.splitlines()
    start = next((i for i, s in enumerate(lines) if s.startswith("# %% [markdown]")), None)
    if start is None:
        return fallback, ""
    text = []
    for line in lines[start + 1 :]:
        if not line.startswith("#") or line.startswith("# %%"):
            break
        text.append(line[2:] if line.startswith("# ") else line[1:])
    title, paragraph = fallback, []
    for line in text:
        if title == fallback and not paragraph and line.startswith("# "):
            title = line[2:].strip()
        elif line.strip():
            paragraph.append(line.strip())
        elif paragraph:
            break
    return title, _whole_sentences(" ".join(paragraph))


def _whole_sentences(text: str) -> str:
    """``text`` cut after its last full stop when it runs on into a formula or a list."""
    if not text or text.rstrip("\"')").endswith((".", "!", "?")):
        return text
    cut = max(text.rfind(". "), text.rfind('". '), text.rfind(".) "))
    return text[: text.index(" ", cut + 1)].rstrip() if cut > 0 else text


def find_lessons(folder: Path | None = None) -> list[Lesson]:
    """Every lesson, in course order (default folder: the bundled lessons)."""
    if folder is None:
        from sandbox.bundled import lessons_folder

        folder = lessons_folder()
    return [Lesson(p) for p in sorted(folder.glob("[0-9][0-9]_*.py"))]


def pick(lessons: Sequence[Lesson], names: Sequence[str]) -> list[Lesson]:
    """The lessons named by ``names`` (all when empty), each given by its number (``10``), its
    file stem (``10_friction``) or a part of its name found in no other lesson (``friction``).

    Raises ``LookupError`` with one line naming the lessons there are.
    """
    if not lessons:
        raise LookupError("no lesson found")
    if not names:
        return list(lessons)
    listing = ", ".join(lesson.stem for lesson in lessons)
    picked: list[Lesson] = []
    for name in names:
        key = name.strip().lower().removesuffix(".py")
        if key.isdigit():
            match = [lesson for lesson in lessons if lesson.number == int(key)]
        else:
            match = [lesson for lesson in lessons if lesson.stem == key]
            match = match or [lesson for lesson in lessons if key and key in lesson.stem.lower()]
        if not match:
            raise LookupError(f"no lesson matches {name!r}; the lessons are {listing}")
        if len(match) > 1:
            found = ", ".join(lesson.stem for lesson in match)
            raise LookupError(f"{name!r} matches {found}: give one number or a longer name")
        picked += [lesson for lesson in match if lesson not in picked]
    return picked
