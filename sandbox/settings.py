"""World settings: the swappable strategies (contract values) and the solver's teaching switches."""

from __future__ import annotations

from dataclasses import asdict, dataclass, fields

ORIENTATIONS = ("angle", "matrix", "complex")
INTEGRATORS = ("explicit_euler", "semi_implicit_euler", "verlet", "rk4", "analytic")
BROADPHASES = ("brute", "grid", "sap", "quadtree", "kdtree")
SOLVERS = ("pairwise", "shock", "iterative")
PENETRATIONS = ("half", "mass_weighted", "impulse")

CHOICES = {
    "orientation": ORIENTATIONS,
    "integrator": INTEGRATORS,
    "broadphase": BROADPHASES,
    "solver": SOLVERS,
    "penetration": PENETRATIONS,
}

# the keys a scene file's "settings" object carries
SCENE_KEYS = ("orientation", "integrator", "broadphase", "solver", "iterations", "penetration")


@dataclass
class Settings:
    """Every world setting. The first six are the scene-file contract; the rest are extensions.

    Teaching switches in the spirit of box2d-lite: ``accumulate_impulses``, ``warm_start`` and
    ``position_correction`` can each be turned off to see what they buy.
    """

    orientation: str = "complex"
    integrator: str = "semi_implicit_euler"
    broadphase: str = "sap"
    solver: str = "iterative"
    iterations: int = 10
    penetration: str = "impulse"
    renormalise: bool = True  # renormalise matrix / complex orientations every step
    accumulate_impulses: bool = True
    warm_start: bool = True
    position_correction: bool = True
    position_iterations: int = 3  # passes of the position-level (impulse) penetration fix
    slop: float = 0.005  # m of allowed overlap before position correction acts
    baumgarte: float = 0.2  # fraction of the remaining overlap removed per step
    restitution_threshold: float = 1.0  # m/s: slower impacts do not bounce
    contact_margin: float = 0.02  # m: contacts are created this far before touching
    sleep: bool = False

    def __post_init__(self) -> None:
        for key, choices in CHOICES.items():
            value = getattr(self, key)
            if value not in choices:
                raise ValueError(
                    f"settings.{key}: expected one of {', '.join(choices)}, got {value!r}"
                )
        if int(self.iterations) < 1:
            raise ValueError("settings.iterations: must be >= 1")

    def __setattr__(self, name: str, value) -> None:
        old = self.__dict__.get(name)
        object.__setattr__(self, name, value)
        observer = self.__dict__.get("_observer")
        if observer is not None and not name.startswith("_"):
            observer(name, old, value)

    def scene_dict(self) -> dict:
        """The contract part, as written to a scene file."""
        return {k: getattr(self, k) for k in SCENE_KEYS}

    def as_dict(self) -> dict:
        return asdict(self)

    @classmethod
    def names(cls) -> tuple[str, ...]:
        return tuple(f.name for f in fields(cls))
