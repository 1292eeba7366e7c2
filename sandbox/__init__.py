"""A 2D physics sandbox for teaching physics-based animation.

>>> import sandbox
>>> world = sandbox.load_scene("scenes/drop.json")   # doctest: +SKIP
>>> world.step()                                       # doctest: +SKIP
"""

from sandbox.body import Body
from sandbox.errors import SimulationError
from sandbox.settings import Settings
from sandbox.shapes import Box, Circle, Polygon
from sandbox.vec2 import Vec2
from sandbox.world import World

__all__ = [
    "Body",
    "Box",
    "Circle",
    "Polygon",
    "SceneError",
    "Settings",
    "SimulationError",
    "Vec2",
    "World",
    "load_scene",
]
__version__ = "0.1.0"


def __getattr__(name: str):
    # scene loading lives in sandbox.scene; imported on first use
    if name in ("load_scene", "SceneError", "save_scene", "validate_scene"):
        from sandbox import scene

        return getattr(scene, name)
    raise AttributeError(f"module 'sandbox' has no attribute {name!r}")
