"""3D orientation, quaternion algebra, inertia tensors and the free rigid body against theory.

Tolerances: algebra identities, conversions, rotations and closed forms of quantities of order 1
to 1e-12 (TOL); the finite-difference check of phi' to 1e-7 (central difference, h = 1e-5); point
masses on a lattice to 1e-12 relative against their own closed form and to 2% against the
continuous solids (40 cells per side); free-body tolerances are stated at each test.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from sandbox import inertia3d as inr
from sandbox import rigid3d as rb
from sandbox import rotation3d as r3

TOL = 1e-12
RNG = np.random.default_rng(20240315)
I, J, K, ONE = np.eye(4)[1], np.eye(4)[2], np.eye(4)[3], np.eye(4)[0]


def random_quats(n: int) -> np.ndarray:
    return RNG.normal(size=(n, 4)) * RNG.uniform(0.2, 3.0, size=(n, 1))  # not unit on purpose


def random_scaled_axes(n: int, max_angle: float = np.pi - 1e-6) -> np.ndarray:
    d = RNG.normal(size=(n, 3))
    return d / r3.norm(d)[:, None] * RNG.uniform(0.0, max_angle, size=(n, 1))


# ---------------------------------------------------------------- quaternion algebra


def test_hamilton_units():
    # i j = k, j k = i, k i = j, j i = -k, i i = j j = k k = -1 (hand: the multiplication rule)
    assert np.allclose(r3.qmul(I, J), K, atol=TOL)
    assert np.allclose(r3.qmul(J, K), I, atol=TOL)
    assert np.allclose(r3.qmul(K, I), J, atol=TOL)
    assert np.allclose(r3.qmul(J, I), -K, atol=TOL)
    for u in (I, J, K):
        assert np.allclose(r3.qmul(u, u), -ONE, atol=TOL)


def test_norm_conjugate_product_identities():
    p, q, r = random_quats(50), random_quats(50), random_quats(50)
    # |pq| = |p||q|; (pq)* = q* p*; (pq)r = p(qr); q q* = [|q|^2, 0]
    np.testing.assert_allclose(r3.qnorm(r3.qmul(p, q)), r3.qnorm(p) * r3.qnorm(q), rtol=TOL)
    np.testing.assert_allclose(
        r3.qconj(r3.qmul(p, q)), r3.qmul(r3.qconj(q), r3.qconj(p)), atol=TOL * 10
    )
    np.testing.assert_allclose(
        r3.qmul(r3.qmul(p, q), r), r3.qmul(p, r3.qmul(q, r)), rtol=TOL, atol=TOL * 100
    )
    qq = r3.qmul(q, r3.qconj(q))
    np.testing.assert_allclose(qq[:, 0], r3.qnorm(q) ** 2, rtol=TOL)
    np.testing.assert_allclose(qq[:, 1:], 0.0, atol=TOL * 10)


def test_inverse_is_conjugate_over_norm_squared():
    q = np.array([1.0, 2.0, 3.0, 4.0])  # |q|^2 = 30
    np.testing.assert_allclose(r3.qmul(q, r3.qinv(q)), ONE, atol=TOL)
    np.testing.assert_allclose(r3.qmul(r3.qinv(q), q), ONE, atol=TOL)
    # the slides' q*/|q| leaves q q^-1 = [|q|, 0, 0, 0] = [sqrt(30), 0, 0, 0] (hand-computed)
    slides = r3.qconj(q) / r3.qnorm(q)
    np.testing.assert_allclose(r3.qmul(q, slides), [math.sqrt(30.0), 0, 0, 0], atol=TOL)
    many = random_quats(50)
    np.testing.assert_allclose(r3.qmul(many, r3.qinv(many)), np.tile(ONE, (50, 1)), atol=TOL)


def test_rotation_quaternion_slides_example():
    # slides: phi = [0 0 pi/2] is 90 degrees anticlockwise about z, so x -> y and y -> -x
    q = r3.quat_from_axis_angle([0.0, 0.0, 1.0], np.pi / 2)
    assert abs(r3.qnorm(q) - 1.0) < TOL
    np.testing.assert_allclose(r3.qrotate(q, [1.0, 0.0, 0.0]), [0, 1, 0], atol=TOL)
    np.testing.assert_allclose(r3.qrotate(q, [0.0, 1.0, 0.0]), [-1, 0, 0], atol=TOL)
    # slides: omega = [4 pi, 3 pi, 0] is 5 pi rad/s about the axis y = 3x/4
    w = np.array([4 * np.pi, 3 * np.pi, 0.0])
    assert abs(r3.norm(w) - 5 * np.pi) < TOL
    assert abs(w[1] - 0.75 * w[0]) < TOL


# ---------------------------------------------------------------- conversions and agreement


def test_slides_matrix_formula_is_a_rotation_and_matches_quaternion():
    phi = random_scaled_axes(200)
    axis, angle = phi / r3.norm(phi)[:, None], r3.norm(phi)
    m = r3.axis_angle_matrix(axis, angle)
    np.testing.assert_allclose(m, r3.quat_to_matrix(r3.scaled_axis_to_quat(phi)), atol=TOL)
    assert np.max(r3.orthogonality_error(m)) < TOL
    np.testing.assert_allclose(np.linalg.det(m), 1.0, atol=TOL)


def test_conversions_round_trip():
    edge = [np.zeros(3), [1e-9, 0, 0], *(np.eye(3) * (np.pi - 1e-7)), [0.0, -2.0, 1.0]]
    phi = np.vstack([random_scaled_axes(300), edge])
    q = r3.scaled_axis_to_quat(phi)
    m = r3.scaled_axis_to_matrix(phi)
    np.testing.assert_allclose(r3.quat_to_scaled_axis(q), phi, atol=TOL * 10)
    np.testing.assert_allclose(r3.matrix_to_scaled_axis(m), phi, atol=TOL * 10)
    np.testing.assert_allclose(r3.matrix_to_quat(m), r3.qcanonical(q), atol=TOL)
    np.testing.assert_allclose(r3.quat_to_matrix(r3.matrix_to_quat(m)), m, atol=TOL)
    # a half turn: phi and -phi are the same rotation, so compare matrices
    half = np.eye(3) * np.pi
    back = r3.scaled_axis_to_matrix(r3.matrix_to_scaled_axis(r3.scaled_axis_to_matrix(half)))
    np.testing.assert_allclose(back, r3.scaled_axis_to_matrix(half), atol=TOL)


@pytest.mark.parametrize("cls", r3.REPRESENTATIONS)
def test_rotate_matrix_and_quaternion_agree_across_representations(cls):
    phi = random_scaled_axes(100)
    v = RNG.normal(size=(100, 3))
    m = r3.scaled_axis_to_matrix(phi)
    for o in (
        cls.from_scaled_axis(phi),
        cls.from_matrix(m),
        cls.from_quaternion(-3.0 * r3.scaled_axis_to_quat(phi)),
    ):
        np.testing.assert_allclose(o.rotate(v), r3.matvec(m, v), atol=TOL * 10)
        np.testing.assert_allclose(o.matrix(), m, atol=TOL)
        np.testing.assert_allclose(o.quaternion(), r3.matrix_to_quat(m), atol=TOL)
        assert np.max(o.drift()) < TOL
    one = cls.from_scaled_axis(phi[0])  # a single orientation, not a stack
    np.testing.assert_allclose(one.rotate(v[0]), m[0] @ v[0], atol=TOL)


def test_exact_updates_agree_across_representations():
    omegas = RNG.normal(size=(200, 3)) * 3.0  # a changing world angular velocity (rad/s)
    start = random_scaled_axes(1)[0]
    reps = [cls.from_scaled_axis(start) for cls in r3.REPRESENTATIONS]
    ref = r3.scaled_axis_to_quat(start)
    for w in omegas:
        ref = r3.qmul(r3.scaled_axis_to_quat(w * 0.01), ref)
        for o in reps:
            o.integrate_exact(w, 0.01)
    for o in reps:
        assert r3.angle_between(o.quaternion(), ref) < 1e-10  # 200 compositions of rounding


# ---------------------------------------------------------------- the slides' update rules


def test_scaled_axis_update_is_exact_only_for_a_fixed_axis():
    w = np.array([1.0, 2.0, 3.0])
    fixed = r3.ScaledAxis(0.3 * w)  # phi parallel to omega
    for _ in range(1000):
        fixed.integrate(w, 1e-3)
    exact = r3.qmul(r3.scaled_axis_to_quat(w * 1.0), r3.scaled_axis_to_quat(0.3 * w))
    assert r3.angle_between(fixed.quaternion(), exact) < 1e-12
    # not fixed: 90 degrees about x, then spin about z for a quarter turn
    start, w = np.array([np.pi / 2, 0.0, 0.0]), np.array([0.0, 0.0, 1.0])
    rz, rx = (
        r3.axis_angle_matrix([0, 0, 1.0], np.pi / 2),
        r3.axis_angle_matrix([1.0, 0, 0], np.pi / 2),
    )
    exact = r3.matrix_to_quat(rz @ rx)  # a 120 degree turn about (1, 1, 1)
    np.testing.assert_allclose(exact, [0.5, 0.5, 0.5, 0.5], atol=TOL)
    slides = r3.ScaledAxis(start).integrate(w, np.pi / 2)  # phi = [pi/2, 0, pi/2]
    assert r3.angle_between(slides.quaternion(), exact) > 0.5  # rad: plainly wrong
    good = r3.ScaledAxis(start).integrate_exact(w, np.pi / 2)
    assert r3.angle_between(good.quaternion(), exact) < TOL


def test_scaled_axis_rate_matches_finite_difference():
    phi, w, h = random_scaled_axes(20, 3.0), RNG.normal(size=(20, 3)), 1e-5
    q = r3.scaled_axis_to_quat(phi)
    fwd = r3.quat_to_scaled_axis(r3.qmul(r3.scaled_axis_to_quat(w * h), q))
    bwd = r3.quat_to_scaled_axis(r3.qmul(r3.scaled_axis_to_quat(-w * h), q))
    np.testing.assert_allclose(r3.scaled_axis_rate(phi, w), (fwd - bwd) / (2 * h), atol=1e-7)
    par = np.array([0.4, -0.8, 1.2])  # parallel to omega: the slides' phi' = omega holds
    np.testing.assert_allclose(r3.scaled_axis_rate(par, par * 2.0), par * 2.0, atol=TOL)


def test_quaternion_slides_update_grows_the_norm_by_a_known_factor():
    w, dt, n = np.array([0.0, 3.0, 4.0]), 1e-2, 500  # |w| = 5 rad/s
    q = r3.Quaternion.identity()
    for _ in range(n):
        q.integrate(w, dt)
    # [0 w] q is orthogonal to q in R^4, so |q| grows by sqrt(1 + (|w| dt / 2)^2) every step
    grow = (1.0 + (5.0 * dt / 2) ** 2) ** (n / 2)
    assert abs(r3.qnorm(q.data) / grow - 1.0) < TOL
    assert abs(q.drift() - (grow - 1.0)) < TOL
    # and each step turns by 2 atan(|w| dt / 2) instead of |w| dt
    angle = n * 2 * math.atan(5.0 * dt / 2)
    assert abs(r3.angle_between(q.quaternion(), r3.quat_from_axis_angle(w, angle))) < 1e-10
    q.renormalise()
    assert q.drift() < TOL


def test_renormalise_each_representation():
    m = r3.scaled_axis_to_matrix(np.array([0.3, -1.0, 2.0]))
    bent = m + 1e-3 * RNG.normal(size=(3, 3))
    mat = r3.RotationMatrix(bent)
    assert mat.drift() > 1e-4
    assert mat.renormalise().drift() < TOL
    np.testing.assert_allclose(mat.data, m, atol=1e-2)  # nearest rotation of a small bend
    # a 3/2 turn about z is the same as a -1/2 turn: |phi| is brought back to pi/2
    sa = r3.ScaledAxis([0.0, 0.0, 1.5 * np.pi]).renormalise()
    np.testing.assert_allclose(sa.data, [0.0, 0.0, -0.5 * np.pi], atol=TOL)


# ---------------------------------------------------------------- inertia tensors


def test_solid_tensors_closed_forms():
    # hand-computed: 2/5 * 2 * 0.5^2 = 0.2; 12/12 (2^2 + 3^2) = 13 ...; 12/12 (3 + 4) = 7, 12/2 = 6
    np.testing.assert_allclose(inr.sphere(2.0, 0.5), 0.2 * np.eye(3), rtol=TOL)
    np.testing.assert_allclose(
        inr.cuboid(12.0, 1.0, 2.0, 3.0), np.diag([13.0, 10.0, 5.0]), rtol=TOL
    )
    np.testing.assert_allclose(inr.cylinder(12.0, 1.0, 2.0), np.diag([7.0, 6.0, 7.0]), rtol=TOL)


def test_box_of_point_masses_sum_is_the_cuboid_times_known_factor():
    for n in (1, 2, 5):
        masses, pos = inr.box_of_point_masses(3.0, 0.4, 0.3, 0.2, n)
        want = inr.cuboid(3.0, 0.4, 0.3, 0.2) * (1.0 - 1.0 / n**2)
        np.testing.assert_allclose(inr.point_masses(masses, pos), want, rtol=TOL, atol=TOL)


def test_lattice_sums_approach_sphere_and_cylinder():
    masses, pos = inr.lattice_point_masses(
        3.0, (0.5, 0.5, 0.5), 40, lambda p: np.sum(p * p, 1) <= 0.25
    )
    np.testing.assert_allclose(
        inr.point_masses(masses, pos), inr.sphere(3.0, 0.5), rtol=0.02, atol=1e-12
    )
    inside = lambda p: p[:, 0] ** 2 + p[:, 2] ** 2 <= 0.16  # noqa: E731
    masses, pos = inr.lattice_point_masses(3.0, (0.4, 0.6, 0.4), 40, inside)
    np.testing.assert_allclose(
        inr.point_masses(masses, pos), inr.cylinder(3.0, 0.4, 1.2), rtol=0.02, atol=1e-12
    )


def test_point_masses_products_parallel_axis_and_rotation():
    masses, pos = RNG.uniform(0.5, 2.0, 7), RNG.normal(size=(7, 3))
    t = inr.point_masses(masses, pos)
    # the slides' component integrals, as sums: I_xx = sum m (y^2 + z^2), I_xy = -sum m x y
    x, y, z = pos.T
    assert abs(t[0, 0] - np.sum(masses * (y * y + z * z))) < TOL * 10
    assert abs(t[0, 1] - -np.sum(masses * x * y)) < TOL * 10
    assert abs(t[1, 2] - -np.sum(masses * y * z)) < TOL * 10
    c = inr.centre_of_mass(masses, pos)
    about_c = inr.point_masses(masses, pos - c)
    np.testing.assert_allclose(inr.parallel_axis(about_c, masses.sum(), c), t, atol=TOL * 10)
    rot = r3.scaled_axis_to_matrix(np.array([0.3, 1.1, -0.4]))
    np.testing.assert_allclose(
        inr.point_masses(masses, pos @ rot.T), inr.rotate_tensor(t, rot), atol=TOL * 10
    )
    moments, _ = inr.principal_axes(inr.rotate_tensor(inr.cuboid(12.0, 1.0, 2.0, 3.0), rot))
    np.testing.assert_allclose(moments, [5.0, 10.0, 13.0], rtol=TOL)


# ---------------------------------------------------------------- the free rigid body

BOX = inr.cuboid(1.0, 0.3, 0.2, 0.1)  # moments 0.00417 < 0.00833 < 0.01083 kg m^2
RACKET = np.array([0.05, 6.0, 0.05])  # rad/s, mostly about the intermediate axis y


def test_axisymmetric_body_precesses_at_the_closed_form_rate():
    # I1 = I2 = 1, I3 = 2: w1 = a cos(W t), w2 = a sin(W t), W = (I3 - I1)/I1 w3 = 2 rad/s
    w = rb.integrate_omega(np.diag([1.0, 1.0, 2.0]), np.array([0.3, 0.0, 2.0]), 1e-3, 2000)
    t = np.arange(2001) * 1e-3
    want = np.stack([0.3 * np.cos(2 * t), 0.3 * np.sin(2 * t), np.full_like(t, 2.0)], 1)
    assert np.max(np.abs(w - want)) < 1e-10  # RK4 error ~ (W dt)^4 W t, far below this


def test_tennis_racket_flip_interval_matches_elliptic_closed_form():
    half = rb.omega_period(np.diag(BOX), RACKET) / 2  # Jacobi sn: w_y changes sign every T/2
    dt = 2e-3
    w = rb.integrate_omega(BOX, RACKET, dt, int(1.6 * 2 * half / dt))
    times = rb.sign_change_times(np.arange(len(w)) * dt, w[:, 1])
    assert len(times) >= 2
    assert abs((times[1] - times[0]) / half - 1.0) < 1e-6  # RK4 at w dt = 0.012


def test_stable_axes_stay_inside_the_conservation_bound():
    # E and |L| conserved: sum I_i (I3 - I_i) w_i^2 = 2 E I3 - |L|^2 is constant, so spinning
    # about the largest axis, |w1| <= sqrt(C / (I1 (I3 - I1))) for ever
    i1, _, i3 = np.diag(BOX)
    w0 = np.array([0.05, 0.05, 6.0])
    c = np.sum(np.diag(BOX) * (i3 - np.diag(BOX)) * w0**2)
    w = rb.integrate_omega(BOX, w0, 2e-3, 3000)
    assert np.max(np.abs(w[:, 0])) <= math.sqrt(c / (i1 * (i3 - i1))) * (1 + 1e-9)
    assert np.min(w[:, 2]) > 5.9  # never flips
    w = rb.integrate_omega(BOX, RACKET, 2e-3, 3000)
    assert np.min(w[:, 1]) < -5.9  # the intermediate axis does flip


def test_full_tensor_gives_the_rotated_motion():
    q = r3.scaled_axis_to_matrix(np.array([0.4, -0.7, 1.0]))
    full = inr.rotate_tensor(BOX, q)  # every product of inertia non-zero
    assert np.min(np.abs(full[np.triu_indices(3, 1)])) > 1e-5
    w = rb.integrate_omega(BOX, RACKET, 2e-3, 500)
    wf = rb.integrate_omega(full, q @ RACKET, 2e-3, 500)
    np.testing.assert_allclose(wf, w @ q.T, atol=1e-10)  # same body, axes turned by q


@pytest.mark.parametrize("cls", r3.REPRESENTATIONS)
def test_rk4_conserves_energy_and_momentum(cls):
    tr = rb.simulate(BOX, RACKET, cls.identity(), 2e-3, 1500, "rk4")  # 3 s, through a flip
    assert tr.energy_error().max() < 1e-9  # RK4 on w: measured 6e-12
    assert tr.momentum_error().max() < 2e-5  # midpoint orientation, second order: measured 5.7e-6
    assert tr.drift.max() < 1e-12  # exact rotations: rounding only


def test_explicit_euler_is_first_order_and_scaled_axis_update_breaks_momentum():
    errors = []
    for dt in (4e-3, 2e-3):
        tr = rb.simulate(BOX, RACKET, r3.RotationMatrix.identity(), dt, round(1.0 / dt), "euler")
        errors.append(tr.energy_error()[-1])
    assert 1.7 < errors[0] / errors[1] < 2.3  # halving dt halves the error after 1 s
    # through the flip (3 s): the same w history, three orientation rules
    sa = rb.simulate(BOX, RACKET, r3.ScaledAxis.identity(), 2e-3, 1500, "euler")
    assert sa.momentum_error().max() > 1.0  # phi + w dt with a moving axis: L turned away
    mat = rb.simulate(BOX, RACKET, r3.RotationMatrix.identity(), 2e-3, 1500, "euler")
    quat = rb.simulate(
        BOX, RACKET, r3.Quaternion.identity(), 2e-3, 1500, "euler", renormalise_every=1
    )
    assert mat.momentum_error().max() < 0.01  # first-order error only: measured 6.0e-3
    # q + dt/2 [0 w] q, renormalised, differs from the exact R(w dt) only at second order in dt
    diff = np.abs(quat.momentum - mat.momentum).max() / np.linalg.norm(mat.momentum[0])
    assert diff < 3e-5  # measured 1.0e-5 (2.4e-6 at dt / 2)
