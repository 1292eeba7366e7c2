"""A 2D physics sandbox for teaching physics-based animation.

>>> import sandbox
>>> world = sandbox.load_scene("scenes/drop.json")   # doctest: +SKIP
>>> world.step()                                       # doctest: +SKIP

Every public class and function is here at the top level, loaded on first use, so
``import sandbox`` stays light.
"""

from importlib import import_module
from importlib.metadata import PackageNotFoundError, version

from sandbox.errors import SimulationError
from sandbox.scene_fields import SceneError
from sandbox.vec2 import Vec2

try:
    __version__ = version("physics-sandbox")  # one source: the package metadata
except PackageNotFoundError:  # running from a source tree that was never installed
    __version__ = "0+unknown"

# name -> module, imported on first use: the engine (numba), rendering (matplotlib) and the
# pymunk bridge load only when asked for, so ``import sandbox`` stays light and the command
# line can decide how the engine runs (compiled or not) before anything is compiled
_LAZY = {
    "Body": "sandbox.body",
    "LanderController": "sandbox.controllers",
    "Scripted": "sandbox.controllers",
    "Thruster": "sandbox.controllers",
    "chain": "sandbox.controllers",
    "lander_thrusters": "sandbox.controllers",
    "Buoyancy": "sandbox.forces",
    "ConstantForce": "sandbox.forces",
    "Drag": "sandbox.forces",
    "ForceGenerator": "sandbox.forces",
    "Joint": "sandbox.joints",
    "PinJoint": "sandbox.joints",
    "PivotJoint": "sandbox.joints",
    "SpringJoint": "sandbox.joints",
    "Layers": "sandbox.overlays",
    "Recording": "sandbox.recording",
    "record": "sandbox.recording",
    "dump_scene": "sandbox.scene",
    "load_scene": "sandbox.scene",
    "read_scene_file": "sandbox.scene",
    "save_scene": "sandbox.scene",
    "validate_scene": "sandbox.scene",
    "Settings": "sandbox.settings",
    "Box": "sandbox.shapes",
    "Circle": "sandbox.shapes",
    "Polygon": "sandbox.shapes",
    "Shape": "sandbox.shapes",
    "read_trace": "sandbox.trace",
    "run_world": "sandbox.trace",
    "write_trace": "sandbox.trace",
    "World": "sandbox.world",
    "render_gif": "sandbox.render",
    "render_png": "sandbox.render",
    "render_frames": "sandbox.render",
    "PymunkScene": "sandbox.pymunk_bridge",
    "run_pymunk": "sandbox.pymunk_bridge",
    "BridgeError": "sandbox.pymunk_bridge",
}

__all__ = [
    "SceneError",
    "SimulationError",
    "Vec2",
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
    "Scripted",
    "Settings",
    "Shape",
    "SpringJoint",
    "Thruster",
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
