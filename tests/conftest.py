"""Test configuration: property-based tests draw the same examples on every run."""

from hypothesis import settings

# deterministic, like the engine: a CI run cannot fail on an example no earlier run saw
settings.register_profile("sandbox", derandomize=True, deadline=None)
settings.load_profile("sandbox")
