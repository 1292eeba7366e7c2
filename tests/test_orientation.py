"""The three 2D orientation representations (slides, "2D Angular Motion", options 1-3)."""

import math

import numpy as np
import pytest

from sandbox import orientation as o

NAMES = ("angle", "matrix", "complex")


@pytest.mark.parametrize("phi", [0.0, 3.0, -3.0, 3.2, -3.2, 7.0, -100.0, math.pi, -math.pi])
def test_wrap_angle_stays_in_range_and_is_equivalent(phi):
    w = o.wrap_angle(phi)
    assert -math.pi <= w <= math.pi
    assert math.cos(w) == pytest.approx(math.cos(phi), abs=1e-12)
    assert math.sin(w) == pytest.approx(math.sin(phi), abs=1e-12)


def test_three_representations_agree_after_10000_steps_with_renormalisation():
    omega, dt = 1.3, 1.0 / 60.0
    reps = [o.make_orientation(n, 0.2) for n in NAMES]
    for _ in range(10_000):
        for r in reps:
            r.integrate(omega, dt)
            r.renormalise()
    exact = o.wrap_angle(0.2 + omega * dt * 10_000)
    for r in reps:  # DoD: the same angle to 1e-9 rad
        assert abs(o.wrap_angle(r.angle() - exact)) < 1e-9, r.name


def test_world_array_kernels_agree_with_the_classes():
    rng = np.random.default_rng(1)
    angles = rng.uniform(-3, 3, 8)
    dphi = rng.uniform(-0.5, 0.5, 8)
    results = []
    for name in NAMES:
        kind = o.NAMES[name]
        rot = np.zeros((8, 4))
        o.set_angles(kind, rot, angles)
        for _ in range(100):
            o.integrate_rotations(kind, rot, dphi, True)
        cs = np.zeros((8, 2))
        o.cos_sin(kind, rot, cs)
        results.append(o.angles_of(kind, rot))
        np.testing.assert_allclose(cs[:, 0] ** 2 + cs[:, 1] ** 2, 1.0, atol=1e-12)
    for r in results[1:]:
        diff = np.angle(np.exp(1j * (r - results[0])))
        assert np.max(np.abs(diff)) < 1e-10


def test_drift_grows_without_renormalisation_and_vanishes_with_it():
    # a rotation matrix or complex number perturbed by rounding drifts; renormalising fixes it
    for name in ("matrix", "complex"):
        r = o.make_orientation(name, 0.0)
        if name == "matrix":
            r.m *= 1.001
        else:
            r.z *= 1.001
        assert r.drift() > 9e-4
        r.renormalise()
        assert r.drift() < 1e-14
    assert o.make_orientation("angle", 5.0).drift() == 0.0


@pytest.mark.parametrize("name", NAMES)
def test_rotate_and_matrix(name):
    r = o.make_orientation(name, math.pi / 2)
    np.testing.assert_allclose(r.rotate([1.0, 0.0]), [0.0, 1.0], atol=1e-15)
    np.testing.assert_allclose(r.matrix(), [[0, -1], [1, 0]], atol=1e-15)
