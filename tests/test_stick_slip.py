"""Stick-slip under a growing push (lesson 10): the engine's one friction coefficient holds a box
until the push passes mu N, then slides it with friction mu N, a = (P - mu N) / m."""

import numpy as np
import pytest

from sandbox import Body, Box, World

G, DT, RAMP, MU = 9.81, 1.0 / 60.0, 2.5, 0.5  # m/s^2, s, N/s, box 0.5 x floor 1.0


def pushed_box(mu_box: float = MU, seconds: float = 3.0):
    world = World(gravity=(0.0, -G), dt=DT)
    floor = world.add_body(Body(name="floor", type="static"))
    floor.add_shape(Box(30.0, 0.5, offset=(13.0, -0.25), friction=1.0))
    box = world.add_body(Body(name="box", position=(0.0, 0.5)))
    box.add_shape(Box(1.0, 1.0, friction=mu_box))
    push, friction, v = [], [], []
    for _ in range(int(round(seconds / DT))):
        p = RAMP * (world.time + DT)
        box.apply_force((p, 0.0))
        world.step()
        push.append(p)
        friction.append(abs(float(world.manifolds.tangent_impulse.sum())) / DT)
        v.append(box.velocity[0])
    return box.mass, np.array(push), np.array(friction), np.array(v)


@pytest.mark.parametrize("mu_box", [0.3, 0.5])
def test_the_box_sticks_until_the_push_passes_mu_n_then_slides_with_mu_n(mu_box):
    m, push, friction, v = pushed_box(mu_box)
    limit = mu_box * m * G  # the contact's mu is the product mu_box x 1.0
    stuck = push < limit
    # stuck: the box creeps at most 1e-4 m/s, and once the resting contact has settled (its
    # first 10 steps start the warm-started impulses from nothing) friction balances the push
    # to 1e-6 relative
    assert np.abs(v[stuck]).max() < 1e-4
    settled = stuck & (np.arange(len(push)) >= 10)
    np.testing.assert_allclose(friction[settled], push[settled], rtol=1e-6)
    # the first step above mu N slides: break-away within one step's growth of the push
    k = int(np.argmax(v > 1e-4))
    assert push[k - 1] <= limit < push[k] + 1e-12
    assert push[k] - limit <= RAMP * DT
    # sliding: friction exactly mu N (the solver's clamp), acceleration (P - mu N) / m
    sliding = slice(k + 1, None)
    np.testing.assert_allclose(friction[sliding], limit, rtol=1e-9)
    accel = np.diff(v)[k:] / DT  # v_n - v_(n-1) over a step carries that step's push
    np.testing.assert_allclose(accel, (push[k + 1 :] - limit) / m, rtol=1e-6, atol=1e-6)
