"""Test configuration: property-based tests draw the same examples on every run."""

import os

from hypothesis import settings

# deterministic, like the engine: a CI run cannot fail on an example no earlier run saw
settings.register_profile("sandbox", derandomize=True, deadline=None)
settings.load_profile("sandbox")

# a command run by a test never starts a background compile of the engine (sandbox.cli.first_run)
os.environ.setdefault("SANDBOX_WARMUP", "off")
# ... and runs compiled, as the tests in this process do, whether or not the compile cache was
# marked warm (tests/test_first_run.py takes this away to test the first run)
os.environ.setdefault("SANDBOX_JIT", "1")
# ... and compiles for this very processor, whether or not kernels were compiled ahead to ship
# in the package (`python -m sandbox.prebuilt`; tests/test_prebuilt.py takes this away)
os.environ.setdefault("SANDBOX_PREBUILT", "off")
