"""A spring's energy under the three integrators lesson 01 plots, against closed forms.

x'' = -w^2 x, E = v^2 / 2 + w^2 x^2 / 2, h = dt, y = w h:
- explicit Euler multiplies E by exactly 1 + y^2 every step;
- semi-implicit Euler keeps the shadow energy E - w^2 h x v / 2 exactly, so E / E0 stays within
  [1 / (1 + y/2), 1 / (1 - y/2)];
- RK4 multiplies E by |R(iy)|^2 = 1 - y^6 / 72 + y^8 / 576 every step.
pymunk's DampedSpring (force at the position after the move) keeps E + w^2 h x v / 2.
"""

import numpy as np
import pymunk
import pytest

from sandbox import integrators

W, H, STEPS = 2.0, 0.05, 400
Y = W * H


def spring(p, v, phi, w):
    return -(W**2) * p, np.zeros_like(w)


def run(method: str) -> tuple[np.ndarray, np.ndarray]:
    """Positions and velocities (STEPS + 1, 2) of the sandbox integrator ``method``."""
    p, v = np.array([1.0, 0.0]), np.array([0.0, 0.0])
    ps, vs = [p], [v]
    for _ in range(STEPS):
        p, v, _, _ = integrators.integrate(method, p, v, 0.0, 0.0, spring, H)
        ps.append(p)
        vs.append(v)
    return np.array(ps), np.array(vs)


def energy(p, v):
    return 0.5 * np.sum(v * v, axis=-1) + 0.5 * W**2 * np.sum(p * p, axis=-1)


def test_explicit_euler_multiplies_the_energy_by_1_plus_w2h2_every_step():
    p, v = run("explicit_euler")
    ratio = energy(p, v) / energy(p[0], v[0])
    # exact algebra; only rounding differs (relative 1e-12 after 400 steps)
    np.testing.assert_allclose(ratio, (1 + Y**2) ** np.arange(STEPS + 1), rtol=1e-12)
    assert ratio[-1] > 50.0  # 1.01^400 = 53.5: it grows, whatever the step


def test_semi_implicit_euler_keeps_its_shadow_energy_and_stays_bounded():
    p, v = run("semi_implicit_euler")
    shadow = energy(p, v) - 0.5 * W**2 * H * p[:, 0] * v[:, 0]
    np.testing.assert_allclose(shadow, shadow[0], rtol=1e-13)  # conserved to rounding
    ratio = energy(p, v) / energy(p[0], v[0])
    assert ratio.min() >= 1 / (1 + Y / 2) - 1e-12
    assert ratio.max() <= 1 / (1 - Y / 2) + 1e-12
    assert ratio.max() - ratio.min() > 0.09  # and it does wobble: the bound is nearly reached


def test_rk4_loses_energy_at_the_closed_form_rate():
    p, v = run("rk4")
    ratio = energy(p, v) / energy(p[0], v[0])
    per_step = 1 - Y**6 / 72 + Y**8 / 576
    np.testing.assert_allclose(ratio, per_step ** np.arange(STEPS + 1), rtol=1e-13)
    assert abs(ratio[-1] - 1) == pytest.approx(5.55e-6, rel=0.01)  # 400 y^6 / 72


def test_pymunk_spring_is_the_other_symplectic_euler():
    space = pymunk.Space()
    anchor = pymunk.Body(body_type=pymunk.Body.STATIC)
    anchor.position = (-2.0, 0.0)
    bob = pymunk.Body(1.0, float("inf"))
    bob.position = (1.0, 0.0)
    space.add(bob, pymunk.DampedSpring(anchor, bob, (0, 0), (0, 0), 2.0, W**2, 0.0))
    shadows = []
    for _ in range(STEPS):
        space.step(H)
        x, vx = bob.position.x, bob.velocity.x
        shadows.append(0.5 * vx * vx + 0.5 * W**2 * x * x + 0.5 * W**2 * H * x * vx)
    # x' = x + v h, then v' = v - w^2 x' h keeps this quantity (Chipmunk computes in doubles)
    np.testing.assert_allclose(shadows, 0.5 * W**2, rtol=1e-12)
