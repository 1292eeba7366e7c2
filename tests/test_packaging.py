"""The wheel: built without a deprecation warning, carrying py.typed, the licence and the schema;
one version for the package metadata, ``sandbox.__version__`` and ``sandbox --version``."""

from __future__ import annotations

import re
import subprocess
import sys
import tomllib
import zipfile
from pathlib import Path

from source_copy import clean_copy

import sandbox

ROOT = Path(__file__).resolve().parent.parent


def test_wheel_builds_quietly_and_carries_its_data(tmp_path):
    res = subprocess.run(
        [sys.executable, "-m", "pip", "wheel", str(clean_copy(tmp_path / "src")), "--no-deps", "-v"]
        + ["-w", str(tmp_path)],
        capture_output=True,
        text=True,
    )
    assert res.returncode == 0, res.stderr[-2000:]
    log = res.stdout + res.stderr
    assert not re.search(r"deprecat", log, re.I), [x for x in log.splitlines() if "eprecat" in x]
    (wheel,) = tmp_path.glob("physics_sandbox-*.whl")
    names = zipfile.ZipFile(wheel).namelist()
    for wanted in ("sandbox/py.typed", "sandbox/scene.schema.json"):
        assert wanted in names
    assert any(n.endswith(".dist-info/licenses/LICENSE") for n in names)
    metadata = zipfile.ZipFile(wheel).read(next(n for n in names if n.endswith("METADATA")))
    assert b"License-Expression: MIT" in metadata
    assert f"-{sandbox.__version__}-" in wheel.name  # the installed version is the built one


def test_one_version_and_the_declared_extras():
    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    assert project["version"] == sandbox.__version__
    assert project["license"] == "MIT" and project["license-files"] == ["LICENSE"]
    extras = project["optional-dependencies"]
    assert {"test", "dev", "docs", "bench"} <= set(extras)
    assert any(d.startswith("jsonschema") for d in extras["test"])
    assert not any(d.startswith("ruff") for d in extras["test"])  # linting is for developers
    # the version literal is written once in the project: pyproject.toml
    literal = re.compile(r"__version__\s*=\s*[\"']\d+\.\d")
    assert not [p for p in (ROOT / "sandbox").rglob("*.py") if literal.search(p.read_text())]
