"""The course's lessons, shipped inside the package as ``sandbox.lessons`` (package data)."""
