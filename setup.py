"""Packaging beyond pyproject.toml: the top-level ``lessons/`` and ``scenes/`` folders ship inside
the package as ``sandbox.lessons`` and ``sandbox.scenes`` (package data read with
``importlib.resources``), so an installed copy runs every lesson from any folder."""

from setuptools import find_packages, setup

BUNDLED = {"sandbox.lessons": "lessons", "sandbox.scenes": "scenes"}

setup(
    packages=[*find_packages(include=["sandbox", "sandbox.*"]), *BUNDLED],
    package_dir=BUNDLED,
)
