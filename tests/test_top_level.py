"""The package's top level: every public name there and in dir(sandbox), imported lightly."""

from __future__ import annotations

import subprocess
import sys

import sandbox

PUBLIC = (
    "World", "Body", "Circle", "Polygon", "Box", "Settings", "Vec2", "PinJoint", "PivotJoint",
    "SpringJoint", "Drag", "Buoyancy", "ConstantForce", "Thruster", "LanderController",
    "Scripted", "chain", "record", "Recording", "render_gif", "render_png", "load_scene",
    "save_scene", "validate_scene", "SceneError", "SimulationError", "run_world", "write_trace",
)  # fmt: skip


def test_every_public_name_is_at_the_top_level_and_in_dir():
    names = dir(sandbox)
    for name in PUBLIC:
        assert name in names and name in sandbox.__all__, name
        assert getattr(sandbox, name) is not None
    assert set(sandbox.__all__) <= set(names)


def test_import_is_light_and_rendering_loads_on_first_use():
    code = (
        "import sys, sandbox\n"
        "assert 'matplotlib' not in sys.modules, 'matplotlib imported by import sandbox'\n"
        "assert 'pymunk' not in sys.modules, 'pymunk imported by import sandbox'\n"
        "assert callable(sandbox.render_gif) and 'matplotlib' in sys.modules\n"
    )
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert res.returncode == 0, res.stderr
