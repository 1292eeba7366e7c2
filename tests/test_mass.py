"""Mass properties against closed forms and the slides' worked examples.

Tolerances: closed forms and hand-computed cases to 1e-12 relative (REL); coordinates that may be
zero to 1e-12 times the shape's size (absolute); the split-polygon property to 1e-9 relative
(random shapes sum many more rounded terms).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from sandbox.geometry import box_vertices, rotation
from sandbox.mass import (
    MassProperties,
    box_mass_properties,
    center_of_mass,
    circle_mass_properties,
    combine,
    moment_of_inertia,
    parallel_axis,
    parallel_axis_to_centroid,
    polygon_mass_properties,
)

REL = 1e-12  # closed forms and hand-computed figures


def close(a: float, b: float, rel: float = REL) -> bool:
    return math.isclose(a, b, rel_tol=rel, abs_tol=0.0)


def same_props(p: MassProperties, q: MassProperties, rel: float = REL, size: float = 1.0) -> None:
    assert close(p.mass, q.mass, rel)
    assert close(p.area, q.area, rel)
    assert close(p.moment, q.moment, rel)
    np.testing.assert_allclose(p.centroid, q.centroid, rtol=0, atol=rel * size)


def regular_polygon(n: int, radius: float, center=(0.0, 0.0)) -> np.ndarray:
    k = np.arange(n)
    return np.asarray(center) + radius * np.stack(
        [np.cos(2 * np.pi * k / n), np.sin(2 * np.pi * k / n)], axis=1
    )


# ---------------------------------------------------------------- slides' worked examples

# slides, "Centre of Mass Example": m1 = 1 kg at 0 m, m2 = 2 kg at 0.6 m
M_EX, X_EX = [1.0, 2.0], [0.0, 0.6]


def test_slide_centre_of_mass_example():
    # c = (1 x 0 + 2 x 0.6) / (1 + 2) = 1.2 / 3 = 0.4 m (the slide's figure is right)
    assert close(center_of_mass(M_EX, X_EX), 0.4)
    # the same masses placed in the plane, on a line through (1, -2) at 30 degrees
    u = np.array([math.cos(math.pi / 6), math.sin(math.pi / 6)])
    pts = np.array([1.0, -2.0]) + np.outer(X_EX, u)
    np.testing.assert_allclose(center_of_mass(M_EX, pts), [1.0, -2.0] + 0.4 * u, rtol=0, atol=REL)


def test_slide_moment_of_inertia_example_corrected():
    # about the centre of mass c = 0.4 m the distances are 0.4 m and 0.2 m:
    # I = 1 x 0.4^2 + 2 x 0.2^2 = 0.24 kg m^2 (the slide swapped them and wrote 0.36)
    assert close(moment_of_inertia(M_EX, X_EX, axis=0.4), 0.24)
    # 0.36 kg m^2 is the moment about either point 0.2 m from c: x = 0.2 or x = 0.6 (through m2)
    assert close(moment_of_inertia(M_EX, X_EX, axis=0.2), 0.36)
    assert close(moment_of_inertia(M_EX, X_EX, axis=0.6), 0.36)
    # I(a) = 3 a^2 - 2.4 a + 0.72 is smallest at the centre of mass; about m1 it is 0.72
    assert close(moment_of_inertia(M_EX, X_EX, axis=0.0), 0.72)
    for a in np.linspace(-1, 2, 31):
        assert moment_of_inertia(M_EX, X_EX, axis=a) >= 0.24 - 1e-15
    # parallel axis theorem links them: 0.36 = 0.24 + 3 x 0.2^2
    assert close(parallel_axis(0.24, 3.0, 0.2), 0.36)


def test_point_masses_in_the_plane():
    # hand-computed: unit masses at the corners of a 2 x 2 square centred on (1, 1)
    m = [1.0, 1.0, 1.0, 1.0]
    r = [(0.0, 0.0), (2.0, 0.0), (2.0, 2.0), (0.0, 2.0)]
    np.testing.assert_allclose(center_of_mass(m, r), [1.0, 1.0], rtol=0, atol=REL)
    assert close(moment_of_inertia(m, r, axis=(1.0, 1.0)), 4 * 2.0)  # each at distance sqrt(2)
    assert close(moment_of_inertia(m, r), 0 + 4 + 8 + 4)  # about the origin


# ---------------------------------------------------------------- parallel axis


def test_parallel_axis_round_trip():
    i_cm, mass, d = 0.7, 2.5, (0.3, -1.1)
    i_axis = parallel_axis(i_cm, mass, d)
    assert close(i_axis, 0.7 + 2.5 * (0.09 + 1.21))
    assert close(parallel_axis_to_centroid(i_axis, mass, d), i_cm)
    # a shape's moment about a point, by the theorem, equals the polygon computed about it
    box = box_mass_properties(2.0, 1.0, density=3.0, offset=(1.0, -2.0))
    assert close(box.moment_about((0.0, 0.0)), 2.5 + 6.0 * 5.0)
    with pytest.raises(ValueError):
        parallel_axis_to_centroid(1.0, 1.0, 2.0)  # would be 1 - 4 < 0


# ---------------------------------------------------------------- standard shapes


def test_circle_closed_form():
    r, rho = 0.75, 2.0
    c = circle_mass_properties(r, rho, offset=(0.5, -0.25))
    assert close(c.area, math.pi * r**2)
    assert close(c.mass, rho * math.pi * r**2)
    assert close(c.moment, 0.5 * c.mass * r**2)  # I = m r^2 / 2
    np.testing.assert_array_equal(c.centroid, [0.5, -0.25])
    heavy = circle_mass_properties(r, rho, mass=3.0)  # mass overrides density
    assert close(heavy.mass, 3.0) and close(heavy.moment, 1.5 * r**2)
    assert close(heavy.density, 3.0 / (math.pi * r**2))


def test_box_closed_form_and_polygon():
    w, h, rho = 2.0, 0.5, 4.0
    b = box_mass_properties(w, h, rho)
    assert close(b.mass, rho * w * h)
    assert close(b.moment, b.mass * (w * w + h * h) / 12)  # I = m (w^2 + h^2) / 12
    same_props(polygon_mass_properties(box_vertices(w, h), rho), b, size=w)


def test_rotated_offset_box():
    w, h, rho, off, ang = 2.0, 1.0, 3.0, (1.0, -2.0), 0.7
    b = box_mass_properties(w, h, rho, offset=off, angle=ang)
    assert close(b.mass, 6.0) and close(b.moment, 6.0 * 5.0 / 12)  # rotation does not change I
    np.testing.assert_array_equal(b.centroid, off)
    same_props(polygon_mass_properties(box_vertices(w, h, off, ang), rho), b, size=w)
    by_mass = box_mass_properties(w, h, offset=off, angle=ang, mass=1.5)
    assert close(by_mass.moment, 1.5 * 5.0 / 12)


def test_right_triangle():
    a, b, rho = 3.0, 2.0, 1.5
    t = polygon_mass_properties([(0, 0), (a, 0), (0, b)], rho)
    assert close(t.area, a * b / 2)
    np.testing.assert_allclose(t.centroid, [a / 3, b / 3], rtol=REL, atol=0)  # at a third
    assert close(t.moment, t.mass * (a * a + b * b) / 18)  # I = m (a^2 + b^2) / 18


@pytest.mark.parametrize("n", [3, 4, 5, 6, 8, 12, 50])
def test_regular_polygon_closed_form(n):
    R, rho = 1.3, 2.0
    p = polygon_mass_properties(regular_polygon(n, R, (0.4, 0.9)), rho)
    area = 0.5 * n * R * R * math.sin(2 * math.pi / n)
    assert close(p.area, area)
    # regular n-gon about its centre: I = m R^2 (1 + 2 cos^2(pi / n)) / 6
    assert close(p.moment, p.mass * R * R * (1 + 2 * math.cos(math.pi / n) ** 2) / 6)
    np.testing.assert_allclose(p.centroid, [0.4, 0.9], rtol=0, atol=REL * R)


def test_regular_polygon_approaches_circle():
    R = 1.0
    disc = circle_mass_properties(R, 1.0)
    sides = (16, 64, 256, 1024)
    errors = []
    for n in sides:
        p = polygon_mass_properties(regular_polygon(n, R), 1.0)
        assert p.moment < disc.moment  # the inscribed polygon misses mass at the rim
        errors.append((disc.moment - p.moment) / disc.moment)
    # the gap shrinks like 1/n^2: 4x the sides -> 1/16 the error (to within 3 %)
    for e0, e1 in zip(errors, errors[1:], strict=False):
        assert 15.5 < e0 / e1 < 16.5
    # series of the closed forms: (I_disc - I_n) / I_disc = (4 pi^2 / 3) / n^2 + O(1 / n^4)
    assert math.isclose(errors[-1] * sides[-1] ** 2, 4 * math.pi**2 / 3, rel_tol=1e-4)


def test_l_shape_two_boxes_vs_one_polygon():
    # 3 x 1 foot plus a 1 x 2 upright; hand-computed: m = 5, c = (1.1, 1.1), I = 217/30
    parts = [
        box_mass_properties(3.0, 1.0, offset=(1.5, 0.5)),
        box_mass_properties(1.0, 2.0, offset=(0.5, 2.0)),
    ]
    whole = combine(parts)
    poly = polygon_mass_properties([(0, 0), (3, 0), (3, 1), (1, 1), (1, 3), (0, 3)])
    assert close(whole.mass, 5.0)
    np.testing.assert_allclose(whole.centroid, [1.1, 1.1], rtol=REL, atol=0)
    assert close(whole.moment, 217 / 30)
    same_props(poly, whole, size=3.0)


def test_cw_and_ccw_agree():
    ccw = regular_polygon(7, 0.8, (2.0, -1.0)) @ np.diag([1.5, 0.6]).T  # an irregular heptagon
    p, q = polygon_mass_properties(ccw, 2.0), polygon_mass_properties(ccw[::-1], 2.0)
    same_props(p, q, size=2.0)
    assert p.area > 0 and p.moment > 0


def test_bad_input_is_rejected():
    with pytest.raises(ValueError):
        circle_mass_properties(0.0, 1.0)
    with pytest.raises(ValueError):
        box_mass_properties(1.0, -1.0, 1.0)
    with pytest.raises(ValueError):
        polygon_mass_properties([(0, 0), (1, 1), (2, 2)], 1.0)  # zero area
    with pytest.raises(ValueError):
        circle_mass_properties(1.0, float("nan"))
    with pytest.raises(ValueError):
        combine([])
    with pytest.raises(ValueError):
        center_of_mass([0.0, 0.0], [0.0, 1.0])


# ---------------------------------------------------------------- property: split = whole


def clip(poly: np.ndarray, point: np.ndarray, normal: np.ndarray) -> np.ndarray:
    """The part of a convex polygon where (x - point) . normal <= 0 (Sutherland-Hodgman)."""
    out = []
    s = (poly - point) @ normal
    for i in range(len(poly)):
        j = (i + 1) % len(poly)
        if s[i] <= 0:
            out.append(poly[i])
        if (s[i] < 0 < s[j]) or (s[j] < 0 < s[i]):
            t = s[i] / (s[i] - s[j])
            out.append(poly[i] + t * (poly[j] - poly[i]))
    return np.array(out)


@settings(max_examples=60, deadline=None)
@given(
    # gap weights in [1, 1.8] give every gap between 0.36 and 2.98 rad: always a convex polygon
    weights=st.lists(st.floats(1.0, 1.8), min_size=3, max_size=10),
    start=st.floats(0.0, 2 * math.pi),
    scale=st.tuples(st.floats(0.2, 3.0), st.floats(0.2, 3.0)),
    turn=st.floats(-math.pi, math.pi),
    shift=st.tuples(st.floats(-5.0, 5.0), st.floats(-5.0, 5.0)),
    cut=st.floats(0.0, math.pi),
    density=st.floats(0.1, 10.0),
)
def test_polygon_split_in_two_combines_to_the_whole(
    weights, start, scale, turn, shift, cut, density
):
    w = np.asarray(weights)
    a = start + 2 * math.pi * np.concatenate([[0.0], np.cumsum(w[:-1])]) / w.sum()
    gaps = np.diff(np.concatenate([a, [a[0] + 2 * math.pi]]))
    assert gaps.min() > 0.05 and gaps.max() < math.pi - 0.05  # a proper convex polygon
    # points on an ellipse (a circle stretched, turned and moved) are a convex polygon
    poly = np.stack([np.cos(a), np.sin(a)], axis=1) * np.asarray(scale) @ rotation(turn).T
    poly = poly + np.asarray(shift)
    whole = polygon_mass_properties(poly, density)
    # cut by a line through the vertex mean (inside the polygon)
    point, normal = poly.mean(axis=0), np.array([math.cos(cut), math.sin(cut)])
    left, right = clip(poly, point, normal), clip(poly, point, -normal)
    halves = [polygon_mass_properties(h, density) for h in (left, right)]
    assume(min(h.area for h in halves) > 1e-3 * whole.area)
    size = float(np.max(np.ptp(poly, axis=0))) + float(np.abs(shift).max())
    same_props(combine(halves), whole, rel=1e-9, size=size)


def test_a_box_shape_and_a_body_of_one_shape_take_the_closed_forms():
    # a Box's mass properties are the rectangle's closed form (not its polygon's fan), and a
    # body of one shape has exactly that shape's: combining one part changes nothing
    from sandbox import Body, Box

    box = Box(2.0, 0.5, offset=(1.0, -2.0), angle=0.7, density=4.0)
    closed = box_mass_properties(2.0, 0.5, 4.0, offset=(1.0, -2.0), angle=0.7)
    # by hand: m = rho w h = 4 kg, I = m (w^2 + h^2) / 12 about the centroid, at the offset
    assert closed.mass == pytest.approx(4.0, rel=1e-15)
    assert closed.moment == pytest.approx(4.0 * (2.0**2 + 0.5**2) / 12.0, rel=1e-15)
    np.testing.assert_allclose(closed.centroid, (1.0, -2.0), rtol=0, atol=1e-15)
    got = box.mass_properties()
    assert (got.mass, got.moment, got.area) == (closed.mass, closed.moment, closed.area)
    np.testing.assert_array_equal(got.centroid, closed.centroid)
    # one part combined is that part: the centroid exactly (m c / m can round it off)
    alone = combine([got])
    assert (alone.mass, alone.moment, alone.area) == (closed.mass, closed.moment, closed.area)
    np.testing.assert_array_equal(alone.centroid, closed.centroid)
    body = Body("b")
    body.add_shape(box)
    mass, centroid, moment = body.mass_properties()
    assert (mass, moment) == (closed.mass, closed.moment)
    np.testing.assert_array_equal(centroid, closed.centroid)
