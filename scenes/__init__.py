"""The example scenes, shipped inside the package as ``sandbox.scenes`` (package data)."""
