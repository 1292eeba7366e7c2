"""A 2D physics sandbox for teaching physics-based animation.

>>> import sandbox
>>> world = sandbox.load_scene("scenes/drop.json")   # doctest: +SKIP
>>> world.step()                                       # doctest: +SKIP

Every public class and function is here at the top level. Rendering (matplotlib), the pymunk
bridge and the comparison load on first use, so ``import sandbox`` stays light.
"""

from importlib import import_module
from importlib.metadata import PackageNotFoundError, version

from sandbox.body import Body
from sandbox.controllers import LanderController, Scripted, Thruster, chain, lander_thrusters
from sandbox.errors import SimulationError
from sandbox.forces import Buoyancy, ConstantForce, Drag, ForceGenerator
from sandbox.joints import Joint, PinJoint, PivotJoint, SpringJoint
from sandbox.overlays import Layers
from sandbox.recording import Recording, record
from sandbox.scene import dump_scene, load_scene, read_scene_file, save_scene, validate_scene
from sandbox.scene_fields import SceneError
from sandbox.settings import Settings
from sandbox.shapes import Box, Circle, Polygon, Shape
from sandbox.trace import read_trace, run_world, write_trace
from sandbox.vec2 import Vec2
from sandbox.world import World

try:
    __version__ = version("physics-sandbox")  # one source: the package metadata
except PackageNotFoundError:  # running from a source tree that was never installed
    __version__ = "0+unknown"

# name -> module, imported on first use (they pull in matplotlib or pymunk)
_LAZY = {
    "render_gif": "sandbox.render",
    "render_png": "sandbox.render",
    "render_frames": "sandbox.render",
    "PymunkScene": "sandbox.pymunk_bridge",
    "run_pymunk": "sandbox.pymunk_bridge",
    "BridgeError": "sandbox.pymunk_bridge",
}

__all__ = [
    "Body",
    "Box",
    "Buoyancy",
    "Circle",
    "ConstantForce",
    "Drag",
    "ForceGenerator",
    "Joint",
    "LanderController",
    "Layers",
    "PinJoint",
    "PivotJoint",
    "Polygon",
    "Recording",
    "SceneError",
    "Scripted",
    "Settings",
    "Shape",
    "SimulationError",
    "SpringJoint",
    "Thruster",
    "Vec2",
    "World",
    "chain",
    "dump_scene",
    "lander_thrusters",
    "load_scene",
    "read_scene_file",
    "read_trace",
    "record",
    "run_world",
    "save_scene",
    "validate_scene",
    "write_trace",
    *_LAZY,
]


def __getattr__(name: str):
    if name in _LAZY:
        value = getattr(import_module(_LAZY[name]), name)
        globals()[name] = value  # once loaded, an ordinary attribute
        return value
    raise AttributeError(f"module 'sandbox' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted({*globals(), *_LAZY})
