"""Simultaneous contact as an LCP (lesson 17): the exact solution by enumeration against the closed
form, the engine's iterative solver against projected Gauss-Seidel and its convergence rate
m_B / (m_A + m_B), and the block solver against the exact two-point answer."""

import numpy as np
import pytest

from sandbox import Body, Box, Circle, World, lcp

G, DT, M_A = 9.81, 1.0 / 60.0, 1.0


def stack(sweeps: int, m_b: float, speed: float) -> World:
    world = World(gravity=(0.0, -G), dt=DT, iterations=sweeps)
    world.settings.warm_start = False
    ground = world.add_body(Body("ground", type="static"))
    ground.add_shape(Box(4.0, 1.0, offset=(0.0, -0.5), friction=0.0))
    a = world.add_body(Body("A", position=(0.0, 0.5)))
    a.add_shape(Circle(0.5, mass=M_A, friction=0.0))
    b = world.add_body(Body("B", position=(0.0, 1.5), velocity=(0.0, -speed)))
    b.add_shape(Circle(0.5, mass=m_b, friction=0.0))
    return world


def stack_problem(m_b: float, speed: float):
    a = np.array([[1 / M_A, -1 / M_A], [-1 / M_A, 1 / M_A + 1 / m_b]])
    return a, np.array([-G * DT, -speed])


def test_enumeration_finds_the_closed_form_and_drops_a_separating_contact():
    a, b = stack_problem(10.0, 2.0)
    lam, active = lcp.solve_by_enumeration(a, b)
    closed = [(M_A + 10.0) * G * DT + 10.0 * 2.0, 10.0 * (2.0 + G * DT)]  # the ground stops both
    np.testing.assert_allclose(lam, closed, rtol=1e-12)
    assert active == (0, 1)
    lam, active = lcp.solve_by_enumeration(*stack_problem(10.0, -2.0))  # B leaving upwards
    np.testing.assert_allclose(lam, [M_A * G * DT, 0.0], atol=1e-12)
    assert active == (0,)


@pytest.mark.parametrize("sweeps", [1, 10, 50])
def test_the_engine_sweeps_exactly_as_projected_gauss_seidel(sweeps):
    world = stack(sweeps, 10.0, 2.0)
    world.step()
    engine = world.manifolds.normal_impulse[:, 0]
    expected = lcp.projected_gauss_seidel(*stack_problem(10.0, 2.0), sweeps)[-1]
    np.testing.assert_allclose(engine, expected, rtol=1e-9)  # the same arithmetic, rounding only


@pytest.mark.parametrize("ratio", [1.0, 10.0])
def test_sweeps_converge_to_the_lcp_at_the_gauss_seidel_rate(ratio):
    a, b = stack_problem(ratio * M_A, 2.0)
    exact, _ = lcp.solve_by_enumeration(a, b)
    world = stack(400, ratio * M_A, 2.0)
    world.step()
    np.testing.assert_allclose(world.manifolds.normal_impulse[:, 0], exact, rtol=1e-9)
    err = np.abs(lcp.projected_gauss_seidel(a, b, 30) - exact).max(axis=1)
    factor = np.exp(np.polyfit(np.arange(5, 25), np.log(err[5:25]), 1)[0])
    assert factor == pytest.approx(ratio / (1.0 + ratio), rel=1e-3)  # rho = a12 a21 / (a11 a22)


def test_the_block_solver_gives_the_exact_two_point_answer_in_one_iteration():
    world = World(gravity=(0.0, -G), dt=DT, iterations=1)
    world.settings.warm_start = False
    ground = world.add_body(Body("ground", type="static"))
    ground.add_shape(Box(4.0, 1.0, offset=(0.0, -0.5), friction=0.0))
    box = world.add_body(
        Body("box", position=(0.0, 0.25), velocity=(0, -1.0), angular_velocity=3.0)
    )
    box.add_shape(Box(1.0, 0.5, friction=0.0))
    (contact,) = world.find_contacts()
    n = np.asarray(contact.normal)
    r = np.asarray(contact.points) - np.asarray(box.center_of_mass)
    rxn = r[:, 0] * n[1] - r[:, 1] * n[0]
    a = 1.0 / box.mass + np.outer(rxn, rxn) / box.moment
    v = np.asarray(box.velocity) + np.array([0.0, -G * DT])
    b = (v + box.angular_velocity * np.stack([-r[:, 1], r[:, 0]], axis=1)) @ n
    exact, active = lcp.solve_by_enumeration(a, b)
    assert active == (0, 1) and b[0] > 0  # the separating corner must push too
    world.step()
    np.testing.assert_allclose(world.manifolds.normal_impulse[0], exact, rtol=1e-9)
    one_sweep = lcp.projected_gauss_seidel(a, b, 1)[-1]
    assert np.abs(one_sweep - exact).max() > 0.1  # point by point, one sweep is far off
