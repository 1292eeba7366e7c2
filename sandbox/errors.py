"""Errors a user meets: a run that failed after its input was accepted.

(Bad input is :class:`sandbox.scene_fields.SceneError`, a ``ValueError`` naming the field.)
"""

from __future__ import annotations


class SimulationError(RuntimeError):
    """A run that diverged: a body's state stopped being finite, or energy exploded.

    ``body`` names the body, ``step`` the step at which it was found, ``cause`` a likely cause
    and what to try (for example "spring stiffness too high for dt: try dt <= 0.004").
    """

    def __init__(self, body: str, step: int, cause: str) -> None:
        super().__init__(f"body {body!r} diverged at step {step}: {cause}")
        self.body, self.step, self.cause = body, step, cause
