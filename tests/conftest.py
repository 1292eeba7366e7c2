"""Test configuration: property-based tests draw the same examples on every run."""

import os

from hypothesis import settings

# deterministic, like the engine: a CI run cannot fail on an example no earlier run saw
settings.register_profile("sandbox", derandomize=True, deadline=None)
settings.load_profile("sandbox")

# a command run by a test never starts a background compile of the engine (sandbox.cli.first_run)
os.environ.setdefault("SANDBOX_WARMUP", "off")
