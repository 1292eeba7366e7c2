"""World settings: the swappable strategies (contract values) and the solver's teaching switches.

Every setting is one dataclass field whose metadata holds its :class:`~sandbox.fieldspec.Field`
(type, unit, valid range, one-line doc). That one description is what the scene-file validator,
the JSON Schema, the reference docs, ``sandbox simulate --set KEY=VALUE`` and assignments such as
``world.settings.slop = 0.01`` check against: adding a setting means adding one field here.

Assignments are validated (``world.settings.slop = -1`` raises :class:`SceneError` with path
``settings.slop``, the message a scene file gets). After a successful assignment the optional
hook ``settings._observer(name, old, new)`` is called, so a world can adapt mid-run.
"""

from __future__ import annotations

import dataclasses
import difflib
from collections.abc import Callable
from dataclasses import dataclass, fields
from typing import Any, ClassVar

from sandbox.fieldspec import Field, Range, check_value
from sandbox.scene_fields import SceneError

ORIENTATIONS = ("angle", "matrix", "complex")
INTEGRATORS = ("explicit_euler", "semi_implicit_euler", "verlet", "rk4", "analytic")
BROADPHASES = ("brute", "grid", "sap", "quadtree", "kdtree")
SOLVERS = ("pairwise", "shock", "iterative", "soft")
PENETRATIONS = ("half", "mass_weighted", "impulse")
JOINT_SOLVERS = ("auto", "direct", "sweeps")  # sandbox.joints.solve.AUTO, DIRECT, SWEEPS

CHOICES = {
    "orientation": ORIENTATIONS,
    "integrator": INTEGRATORS,
    "broadphase": BROADPHASES,
    "solver": SOLVERS,
    "penetration": PENETRATIONS,
    "joint_solver": JOINT_SOLVERS,
}

# the keys a scene file's "settings" object always carries (the design's contract); the other
# settings are written only when they differ from their defaults
SCENE_KEYS = ("orientation", "integrator", "broadphase", "solver", "iterations", "penetration")

_HERTZ = Range(1e-3, 1e6, "Hz")
_SPEED = Range(1e-6, 1e6, "m/s")


def _setting(default: Any, kind: str, doc: str, rng: Range | None = None, **kw) -> Any:
    """A dataclass field carrying its :class:`Field` (name filled in below) as metadata.

    ``pymunk=True`` marks a setting the pymunk bridge honours (the others only apply to this
    engine). ``rng`` gives the valid range and unit of numbers and integers.
    """
    pymunk = kw.pop("pymunk", False)
    if rng is not None:
        kw.update(lo=rng.lo, hi=rng.hi, unit=rng.unit)
    spec = Field("", kind, doc, default, **kw)
    return dataclasses.field(default=default, metadata={"spec": spec, "pymunk": pymunk})


@dataclass
class Settings:
    """Every world setting, each validated on assignment (see the module docstring).

    The first six are the scene-file contract; the rest are teaching switches and tuning in the
    spirit of box2d-lite (``accumulate_impulses``, ``warm_start`` and ``position_correction`` can
    each be turned off to see what they buy) and of Box2D v3's soft step.
    """

    orientation: str = _setting(
        "complex",
        "choice",
        "how orientations are stored: an angle, a 2x2 rotation matrix or a unit complex number",
        choices=ORIENTATIONS,
    )
    integrator: str = _setting(
        "semi_implicit_euler",
        "choice",
        "how free motion is integrated; analytic moves bodies on closed-form paths (no contacts)",
        choices=INTEGRATORS,
    )
    broadphase: str = _setting(
        "sap",
        "choice",
        "how candidate pairs are found (every broadphase gives the same pairs)",
        choices=BROADPHASES,
    )
    solver: str = _setting(
        "iterative",
        "choice",
        "contact solver: pairwise (each contact once), shock propagation, "
        "iterative (sequential impulses) or soft (soft step with substeps)",
        choices=SOLVERS,
    )
    iterations: int = _setting(
        10, "integer", "velocity iterations of the solver per step", Range(1, 1000), pymunk=True
    )
    penetration: str = _setting(
        "impulse",
        "choice",
        "how remaining overlap is removed: half each, mass-weighted, or by position impulses",
        choices=PENETRATIONS,
    )
    robust_positions: bool = _setting(
        True,
        "boolean",
        "position passes from the ground up, a lower body held under a much heavier one, and "
        "overlap present at the start of a step pushed out at most at max_push_speed: overlapping "
        "spawns and heavy-on-light stacks hold (off: the slides' classic pass; the soft "
        "step's passes hold no lighter body, its contacts carry their own sag: see hold_ratio)",
    )
    renormalise: bool = _setting(
        True, "boolean", "renormalise matrix and complex orientations every step"
    )
    accumulate_impulses: bool = _setting(
        True, "boolean", "clamp the accumulated impulse, not each increment (box2d-lite)"
    )
    warm_start: bool = _setting(
        True, "boolean", "start each step's solver from the previous step's impulses"
    )
    position_correction: bool = _setting(
        True, "boolean", "remove remaining overlap after the velocity solve"
    )
    position_iterations: int = _setting(
        3, "integer", "passes of the position-level overlap fix per step", Range(0, 1000)
    )
    position_tolerance: float = _setting(
        0.015,
        "number",
        "the position passes stop once no point overlaps more than this (Box2D's three slops; "
        "0: every pass runs while anything overlaps beyond the slop)",
        Range(0.0, 1.0, "m"),
        ge=0.0,
    )
    position_stall: float = _setting(
        0.005,
        "number",
        "the position passes also stop once a pass takes out less than this fraction of the "
        "overlap the pass before met: a pile its own load presses together, where the passes "
        "only push against each other (0: only position_tolerance stops them)",
        Range(0.0, 1.0),
        ge=0.0,
    )
    slop: float = _setting(
        0.005,
        "number",
        "overlap allowed before position correction acts",
        Range(0.0, 1.0, "m"),
        ge=0.0,
    )
    baumgarte: float = _setting(
        0.2, "number", "fraction of the remaining overlap removed per step", Range(0.0, 1.0)
    )
    restitution_threshold: float = _setting(
        1.0, "number", "impacts slower than this do not bounce", Range(0.0, 1e3, "m/s"), ge=0.0
    )
    contact_margin: float = _setting(
        0.02,
        "number",
        "contacts are created this far before shapes touch",
        Range(0.0, 1.0, "m"),
        ge=0.0,
    )
    speculative: bool = _setting(
        False,
        "boolean",
        "contacts also reach as far as the two bodies can close in one step (speculative "
        "contacts): a fast body meets a surface in the step it gets there, and does not pass "
        "through a thin wall (off: contact_margin alone, as the tunnelling lesson shows; the "
        "pairwise solver resolves only overlapping points and ignores them)",
    )
    box_prediction: float = _setting(
        2.0,
        "number",
        "sweep and prune (broadphase sap) stretches each shape's box along its velocity by "
        "this many steps of travel and keeps the pairs it found until a shape leaves its box "
        "(Box2D 2.3's aabbMultiplier; 0: a 2 cm spare margin alone); only how often it sweeps "
        "changes, not the pairs or any result",
        Range(0.0, 16.0, "steps"),
        ge=0.0,
    )
    sleep: bool = _setting(
        False, "boolean", "let bodies that have come to rest sleep until something touches them"
    )
    substeps: int = _setting(
        4, "integer", "substeps per step of the soft solver (solver: soft)", Range(1, 64)
    )
    contact_hertz: float = _setting(
        60.0,
        "number",
        "stiffness of soft contacts, as a frequency, at most an eighth of the substep rate "
        "(solver: soft; contacts with a static body twice as stiff)",
        _HERTZ,
        gt=0.0,
    )
    contact_damping_ratio: float = _setting(
        10.0, "number", "damping ratio of soft contacts (solver: soft)", Range(0.0, 1e3), ge=0.0
    )
    joint_hertz: float = _setting(
        120.0, "number", "stiffness of soft joints, as a frequency (solver: soft)", _HERTZ, gt=0.0
    )
    joint_damping_ratio: float = _setting(
        5.0, "number", "damping ratio of soft joints (solver: soft)", Range(0.0, 1e3), ge=0.0
    )
    joint_solver: str = _setting(
        "auto",
        "choice",
        "how the soft step solves its joints: all together by one linear solve per pass "
        "(direct), one at a time, iterations times per substep (sweeps), or direct where that "
        "is cheaper, as along chains and trees, and sweeps for a wide net of joints (auto) "
        "(solver: soft)",
        choices=JOINT_SOLVERS,
    )
    hold_ratio: float = _setting(
        10.0,
        "number",
        "a soft contact holds the lower body still when one more than this many times heavier "
        "rests on it, so a light box is not squeezed out from under a heavy one (shock "
        "propagation where the masses differ that much; 0: never) (solver: soft)",
        Range(0.0, 1e9),
        ge=0.0,
    )
    sag_recovery_time: float = _setting(
        1.0,
        "number",
        "time in which a soft contact takes back the sag its load presses into it, so a tall pile "
        "stands at its full height (0: the sag stays, as in Box2D's soft step) (solver: soft)",
        Range(0.0, 1e3, "s"),
        ge=0.0,
    )
    max_push_speed: float = _setting(
        3.0, "number", "fastest speed at which overlapping bodies are pushed apart", _SPEED, gt=0.0
    )

    _observer: ClassVar[Callable[[str, Any, Any], None] | None] = None

    def __setattr__(self, name: str, value: Any) -> None:
        spec = FIELDS.get(name)
        if spec is None:
            if name.startswith("_"):  # private state such as the observer hook
                object.__setattr__(self, name, value)
                return
            raise unknown_setting(name, f"settings.{name}")
        value = check_value(spec, value, f"settings.{name}")
        had = name in self.__dict__
        old = self.__dict__.get(name)
        object.__setattr__(self, name, value)
        if had and self._observer is not None:
            self._observer(name, old, value)

    def __getstate__(self) -> dict:
        """Copies and pickles carry the settings, not the observer (it belongs to one world)."""
        return {name: self.__dict__[name] for name in FIELDS}

    # --- scene files ----------------------------------------------------------------------------
    def scene_dict(self, full: bool = False) -> dict:
        """The ``settings`` object of a scene file: the six contract keys, then every other
        setting that differs from its default (all of them when ``full``)."""
        out = {k: getattr(self, k) for k in SCENE_KEYS}
        for name, spec in FIELDS.items():
            value = getattr(self, name)
            if name not in out and (full or value != spec.default):
                out[name] = value
        return out

    def as_dict(self) -> dict:
        """Every setting by name."""
        return {name: getattr(self, name) for name in FIELDS}

    def changed(self) -> dict:
        """The settings that differ from their defaults."""
        return {k: v for k, v in self.as_dict().items() if v != FIELDS[k].default}

    @classmethod
    def names(cls) -> tuple[str, ...]:
        """Every setting's name, in declaration order."""
        return tuple(f.name for f in fields(cls))

    @classmethod
    def fields(cls) -> tuple[Field, ...]:
        """Every setting's :class:`Field` (type, unit, range, default, doc)."""
        return tuple(FIELDS.values())

    @classmethod
    def spec(cls, name: str) -> Field:
        """The :class:`Field` of one setting (SceneError with a did-you-mean if unknown)."""
        if name not in FIELDS:
            raise unknown_setting(name, f"settings.{name}")
        return FIELDS[name]


FIELDS: dict[str, Field] = {
    f.name: dataclasses.replace(f.metadata["spec"], name=f.name) for f in fields(Settings)
}
PYMUNK_HONOURS = tuple(f.name for f in fields(Settings) if f.metadata["pymunk"])


# the scene's own fields that a setting could be taken for (``--set gravity=0,-1.62``)
SCENE_LEVEL = {
    "gravity": 'the scene\'s own, beside its settings: "gravity": [0, -1.62] in the file',
    "dt": "the scene's own, beside its settings; on the command line, --dt",
}


def unknown_setting(name: str, path: str) -> SceneError:
    """The error for a setting that does not exist, with a did-you-mean when one is close, or
    where to set it when it is the scene's own field (gravity, dt)."""
    if name in SCENE_LEVEL:
        return SceneError(path, f"unknown setting ({name} is {SCENE_LEVEL[name]})")
    close = difflib.get_close_matches(name, tuple(FIELDS), n=1)
    hint = f" (did you mean {close[0]!r}?)" if close else ""
    return SceneError(path, f"unknown setting{hint}")


_TRUE = ("true", "yes", "on", "1")
_FALSE = ("false", "no", "off", "0")


def parse_setting(name: str, text: str, path: str | None = None) -> Any:
    """The value of setting ``name`` written as command-line text (``--set KEY=VALUE``).

    Booleans: true/false (also yes/no, on/off, 1/0); numbers and integers as Python writes them;
    choices by name. Raises :class:`SceneError` naming ``path`` (default ``settings.<name>``).
    """
    path = path or f"settings.{name}"
    if name not in FIELDS:
        raise unknown_setting(name, path)
    spec = FIELDS[name]
    word = text.strip()
    value: Any = word
    if spec.kind == "boolean":
        if word.lower() in _TRUE:
            value = True
        elif word.lower() in _FALSE:
            value = False
    elif spec.kind == "integer":
        try:
            value = int(word)
        except ValueError:
            pass  # the check below says what was expected
    elif spec.kind == "number":
        try:
            value = float(word)
        except ValueError:
            pass
    return check_value(spec, value, path)


def pymunk_ignores(settings: dict) -> list[str]:
    """``key=value`` for every setting in ``settings`` that differs from its default and that
    the pymunk bridge cannot honour (it honours only ``iterations``, besides dt and gravity)."""
    out = []
    for name, value in settings.items():
        spec = FIELDS.get(name)
        if spec is not None and name not in PYMUNK_HONOURS and value != spec.default:
            shown = str(value).lower() if isinstance(value, bool) else value
            out.append(f"{name}={shown}")
    return out
