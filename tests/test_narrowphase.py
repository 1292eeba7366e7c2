"""Narrowphase manifolds against hand-computed configurations (slides, "Collision Detection
Output" and "Sphere Collision Detection Example")."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from sandbox.contact import Contact, Manifolds, contacts_from_manifolds
from sandbox.geometry import box_vertices, edge_normals, make_ccw
from sandbox.narrowphase import collide
from sandbox.records import BODY, SHAPE, VERTEX

TOL = 1e-12  # exact arithmetic up to round-off


def circle(radius, offset=(0.0, 0.0), friction=0.5, restitution=0.0):
    return {"kind": 0, "radius": radius, "center": offset, "mu": friction, "e": restitution}


def polygon(vertices, friction=0.5, restitution=0.0):
    return {"kind": 1, "verts": make_ccw(vertices), "mu": friction, "e": restitution}


def box(width, height, offset=(0.0, 0.0), angle=0.0, **material):
    return polygon(box_vertices(width, height, offset, angle), **material)


def scene(*bodies):
    """Flattened arrays for bodies given as (com, angle, [shapes]); shape geometry is relative
    to the centre of mass, in the body frame (docs/architecture.md)."""
    body, kind, radius, center, vstart, vcount, verts, mu, e = ([] for _ in range(9))
    com, cs = [], []
    nv = 0
    for b, (pos, angle, shapes) in enumerate(bodies):
        com.append(pos)
        cs.append((math.cos(angle), math.sin(angle)))
        for s in shapes:
            body.append(b)
            kind.append(s["kind"])
            mu.append(s["mu"])
            e.append(s["e"])
            if s["kind"] == 0:
                radius.append(s["radius"])
                center.append(s["center"])
                vstart.append(0)
                vcount.append(0)
            else:
                v = np.asarray(s["verts"], dtype=float)
                radius.append(0.0)
                center.append(v.mean(axis=0))
                vstart.append(nv)
                vcount.append(len(v))
                verts.append(v)
                nv += len(v)
    v = np.concatenate(verts) if verts else np.zeros((0, 2))
    n = np.concatenate([edge_normals(x) for x in verts]) if verts else np.zeros((0, 2))
    shapes = np.zeros(len(body), dtype=SHAPE)
    shapes["body"], shapes["kind"], shapes["radius"] = body, kind, radius
    shapes["center"] = np.array(center, dtype=float).reshape(-1, 2)
    shapes["first_vertex"], shapes["vertex_count"] = vstart, vcount
    shapes["friction"], shapes["restitution"] = mu, e
    shapes["bound"] = np.inf  # no bounding-circle test
    vertices = np.zeros(len(v), dtype=VERTEX)
    vertices["point"], vertices["normal"] = v, n
    records = np.zeros(len(com), dtype=BODY)
    records["com"], records["cs"] = com, cs
    return {"shapes": shapes, "vertices": vertices, "bodies": records}


def run(arrays, pairs=((0, 1),), margin=0.0) -> Manifolds:
    return collide(np.array(pairs, dtype=np.int64).reshape(-1, 2), margin=margin, **arrays)


def points_of(m, k=0):
    return m.point[k, : m.count[k]]


GROUND = ((0.0, 0.5), 0.0, [box(2.0, 1.0)])  # top face y = 1, x in [-1, 1]


# --- circles ---------------------------------------------------------------------------------


def test_circle_circle_slides_formulas():
    # p1 = (0, 0), r1 = 1.5; p2 = (1.2, 1.6), r2 = 1: d = 2, p = r1 + r2 - d = 0.5,
    # n = (p2 - p1) / d = (0.6, 0.8), p_c = p1 + (r1 - p/2) n = 1.25 n = (0.75, 1.0)
    m = run(scene(((0, 0), 0.0, [circle(1.5)]), ((1.2, 1.6), 0.0, [circle(1.0)])))
    assert len(m) == 1 and m.count[0] == 1
    np.testing.assert_allclose(m.normal[0], [0.6, 0.8], atol=TOL)
    np.testing.assert_allclose(m.depth[0, 0], 0.5, atol=TOL)
    np.testing.assert_allclose(m.point[0, 0], [0.75, 1.0], atol=TOL)
    assert (m.a[0], m.b[0], m.sa[0], m.sb[0]) == (0, 1, 0, 1)


def test_circles_apart_touching_and_margin():
    far = scene(((0, 0), 0.0, [circle(1.0)]), ((2.01, 0), 0.0, [circle(1.0)]))
    assert len(run(far)) == 0  # gap 0.01 > margin 0
    m = run(far, margin=0.02)  # speculative: gap 0.01 within the margin, depth = -0.01
    np.testing.assert_allclose(m.depth[0, 0], -0.01, atol=1e-12)
    touching = run(scene(((0, 0), 0.0, [circle(1.0)]), ((2.0, 0), 0.0, [circle(1.0)])))
    assert len(touching) == 1 and touching.depth[0, 0] == 0.0  # d = r1 + r2 counts (<=)


def test_circle_on_box_face():
    # circle r = 0.5 at (0.3, 1.4) over the face y = 1: depth 0.1, normal (0, 1), point midway
    # between the face (0.3, 1.0) and the circle's lowest point (0.3, 0.9)
    m = run(scene(GROUND, ((0.3, 1.4), 0.0, [circle(0.5)])))
    np.testing.assert_allclose(m.normal[0], [0.0, 1.0], atol=TOL)
    np.testing.assert_allclose(m.depth[0, 0], 0.1, atol=TOL)
    np.testing.assert_allclose(m.point[0, 0], [0.3, 0.95], atol=TOL)


def test_circle_on_box_corner_uses_vertex_region():
    # centre (1.3, 1.3) beyond the corner (1, 1): n = (1, 1)/sqrt2, d = 0.3 sqrt2,
    # depth = 0.5 - 0.3 sqrt2; point midway between the corner and c - r n
    m = run(scene(GROUND, ((1.3, 1.3), 0.0, [circle(0.5)])))
    s = 1 / math.sqrt(2)
    np.testing.assert_allclose(m.normal[0], [s, s], atol=TOL)
    np.testing.assert_allclose(m.depth[0, 0], 0.5 - 0.3 * math.sqrt(2), atol=TOL)
    deepest = 1.3 - 0.5 * s
    np.testing.assert_allclose(m.point[0, 0], [(1 + deepest) / 2] * 2, atol=TOL)


def test_circle_as_shape_a_flips_normal():
    # the circle is body 0: normal from the circle down into the box
    m = run(scene(((0.3, 1.4), 0.0, [circle(0.5)]), GROUND))
    np.testing.assert_allclose(m.normal[0], [0.0, -1.0], atol=TOL)
    np.testing.assert_allclose(m.depth[0, 0], 0.1, atol=TOL)


# --- polygons --------------------------------------------------------------------------------


def test_box_resting_on_box_two_points():
    # 1 x 1 box centred (0.3, 1.4): bottom face y = 0.9, 0.1 below the top face y = 1
    m = run(scene(GROUND, ((0.3, 1.4), 0.0, [box(1.0, 1.0)])))
    assert m.count[0] == 2
    np.testing.assert_allclose(m.normal[0], [0.0, 1.0], atol=TOL)
    np.testing.assert_allclose(m.depth[0], [0.1, 0.1], atol=1e-12)
    pts = sorted(map(tuple, points_of(m)))
    np.testing.assert_allclose(pts, [(-0.2, 0.95), (0.8, 0.95)], atol=1e-12)


def test_edge_to_edge_with_offset_clips_to_overlap():
    # box [0, 2] x [0.9, 1.9] on the ground [-1, 1] x [0, 1]: clipping to the ground's side
    # planes leaves the overlap interval x in [0, 1], both points 0.1 deep
    m = run(scene(GROUND, ((1.0, 1.4), 0.0, [box(2.0, 1.0)])))
    assert m.count[0] == 2
    np.testing.assert_allclose(m.normal[0], [0.0, 1.0], atol=TOL)
    np.testing.assert_allclose(sorted(points_of(m)[:, 0]), [0.0, 1.0], atol=1e-12)
    np.testing.assert_allclose(points_of(m)[:, 1], [0.95, 0.95], atol=1e-12)


def test_rotated_box_corner_into_face_one_point():
    # unit box turned 45 deg, its lowest corner 0.1 below y = 1 at x = 0.2
    h = math.sqrt(0.5)
    m = run(scene(GROUND, ((0.2, 0.9 + h), math.pi / 4, [box(1.0, 1.0)])))
    assert m.count[0] == 1
    np.testing.assert_allclose(m.normal[0], [0.0, 1.0], atol=TOL)
    np.testing.assert_allclose(m.depth[0, 0], 0.1, atol=1e-12)
    np.testing.assert_allclose(m.point[0, 0], [0.2, 0.95], atol=1e-12)


def test_polygon_against_triangle():
    # triangle apex (0, 0.9) pointing down into the face y = 1, base y = 1.9, half width 0.5:
    # its side normals separate by -0.94, so the ground's top face is the reference: one point
    tri = polygon([(0.0, -0.6), (0.5, 0.4), (-0.5, 0.4)])
    m = run(scene(GROUND, ((0.0, 1.5), 0.0, [tri])))
    assert m.count[0] == 1
    np.testing.assert_allclose(m.normal[0], [0.0, 1.0], atol=TOL)
    np.testing.assert_allclose(m.depth[0, 0], 0.1, atol=1e-12)
    np.testing.assert_allclose(m.point[0, 0], [0.0, 0.95], atol=1e-12)


def test_separated_boxes_corner_to_corner_speculative():
    # unit boxes with a diagonal gap (0.01, 0.01) between corners: vertex-vertex contact with
    # normal along the diagonal and depth = -0.01 sqrt2, only when the margin covers it
    arrays = scene(((0, 0), 0.0, [box(1, 1)]), ((1.01, 1.01), 0.0, [box(1, 1)]))
    assert len(run(arrays)) == 0
    m = run(arrays, margin=0.02)
    s = 1 / math.sqrt(2)
    np.testing.assert_allclose(m.normal[0], [s, s], atol=1e-9)
    np.testing.assert_allclose(m.depth[0, 0], -0.01 * math.sqrt(2), atol=1e-12)
    np.testing.assert_allclose(m.point[0, 0], [0.505, 0.505], atol=1e-12)


# --- degenerate cases ------------------------------------------------------------------------


@pytest.mark.parametrize(
    "shapes_a, shapes_b",
    [
        ([circle(0.5)], [circle(0.3)]),
        ([box(1, 1)], [box(1, 1)]),
        ([box(1, 2)], [circle(0.3)]),
        ([circle(0.3)], [box(2, 1, angle=0.3)]),
    ],
)
def test_coincident_centres_give_valid_normals(shapes_a, shapes_b):
    m = run(scene(((1.0, 2.0), 0.0, shapes_a), ((1.0, 2.0), 0.0, shapes_b)))
    assert len(m) == 1 and np.all(np.isfinite(m.point)) and np.all(np.isfinite(m.depth))
    assert abs(np.hypot(*m.normal[0]) - 1.0) < 1e-12  # unit normal, never NaN
    assert np.all(m.depth[0, : m.count[0]] > 0)


def test_coincident_circles_normal_flips_with_the_pair():
    arrays = scene(((0, 0), 0.0, [circle(0.5)]), ((0, 0), 0.0, [circle(0.5)]))
    forward, backward = run(arrays), run(arrays, pairs=((1, 0),))
    np.testing.assert_allclose(forward.normal[0], -backward.normal[0], atol=0)


def test_touching_boxes_give_zero_depth_contacts():
    m = run(scene(GROUND, ((0.0, 1.5), 0.0, [box(1.0, 1.0)])))
    assert m.count[0] == 2 and np.all(np.isfinite(m.point))
    np.testing.assert_allclose(m.depth[0], [0.0, 0.0], atol=1e-15)


# --- bodies and shapes -----------------------------------------------------------------------


def test_offset_and_rotated_shapes_on_a_body():
    # body at (2, 0) turned 90 deg; a circle r = 0.5 at body-frame (1, 0) -> world (2, 1);
    # a 0.2 x 0.2 box at body-frame (-1, 0) -> world (2, -1). Ground: big box top at y = 0.6
    ground = ((2.0, -10.0), 0.0, [box(10.0, 21.2)])  # top face y = 0.6, covers both shapes
    body = ((2.0, 0.0), math.pi / 2, [circle(0.5, offset=(1.0, 0.0)), box(0.2, 0.2, (-1.0, 0.0))])
    arrays = scene(ground, body)
    m = run(arrays, pairs=((0, 1), (0, 2)))
    assert len(m) == 2 and list(m.sb) == [1, 2]
    # circle bottom at y = 0.5: depth 0.1, point midway (2, 0.55)
    np.testing.assert_allclose(m.depth[0, 0], 0.1, atol=1e-12)
    np.testing.assert_allclose(m.point[0, 0], [2.0, 0.55], atol=1e-12)
    # small box spans y in [-1.1, -0.9], fully inside: depth 0.6 + 1.1 = 1.7 below the top face
    np.testing.assert_allclose(m.normal[1], [0.0, 1.0], atol=1e-12)
    np.testing.assert_allclose(m.depth[1], [1.7, 1.7], atol=1e-12)
    np.testing.assert_allclose(sorted(points_of(m, 1)[:, 0]), [1.9, 2.1], atol=1e-12)


def test_body_with_two_shapes_one_manifold_per_shape_pair():
    # two circles r = 0.25 at x = -0.5 and 0.5 on one body, 0.05 into the ground face y = 1
    body = ((0.0, 1.2), 0.0, [circle(0.25, (-0.5, 0.0)), circle(0.25, (0.5, 0.0))])
    arrays = scene(GROUND, body)
    m = run(arrays, pairs=((0, 1), (0, 2), (1, 2)))  # (1, 2): same body, never a contact
    assert len(m) == 2 and list(m.sa) == [0, 0] and list(m.sb) == [1, 2]
    assert list(m.a) == [0, 0] and list(m.b) == [1, 1]
    np.testing.assert_allclose(m.depth[:, 0], [0.05, 0.05], atol=1e-12)
    np.testing.assert_allclose(m.point[:, 0, 0], [-0.5, 0.5], atol=1e-12)


def test_material_products_and_zeroed_impulses():
    arrays = scene(
        ((0, 0), 0.0, [circle(1.0, friction=0.4, restitution=0.5)]),
        ((1.5, 0), 0.0, [circle(1.0, friction=0.5, restitution=0.8)]),
    )
    m = run(arrays)
    np.testing.assert_allclose([m.friction[0], m.restitution[0]], [0.2, 0.4], atol=TOL)
    assert m.normal_impulse.shape == (1, 2) and not m.normal_impulse.any()
    assert m.tangent_impulse.shape == (1, 2) and not m.tangent_impulse.any()
    assert len(m.select(np.array([False]))) == 0 and len(m.select([0])) == 1


def test_feature_ids_stable_under_small_perturbation():
    base = run(scene(GROUND, ((0.3, 1.4), 0.0, [box(1.0, 1.0)])))
    moved = run(scene(GROUND, ((0.3003, 1.4002), 0.002, [box(1.0, 1.0)])))
    assert moved.count[0] == 2
    assert sorted(base.feature[0]) == sorted(moved.feature[0])
    # a box nearly level with a near-tie of separations keeps the same reference face
    tilted = run(scene(((0, 0), 0.0, [box(1, 1)]), ((0.0, 0.99), 1e-4, [box(1, 1)])))
    level = run(scene(((0, 0), 0.0, [box(1, 1)]), ((0.0, 0.99), -1e-4, [box(1, 1)])))
    assert sorted(tilted.feature[0]) == sorted(level.feature[0])


def test_contacts_from_manifolds():
    arrays = scene(GROUND, ((0.3, 1.4), 0.0, [box(1.0, 1.0)]))
    m = run(arrays)
    m.records["points"]["normal_impulse"][0] = [1.5, 2.5]
    contacts = contacts_from_manifolds(m, ["ground", "box"])
    assert len(contacts) == 1 and isinstance(contacts[0], Contact)
    c = contacts[0]
    assert (c.a, c.b, c.shape_a, c.shape_b) == ("ground", "box", 0, 1)
    assert len(c.points) == 2 and c.impulses == [1.5, 2.5]
    np.testing.assert_allclose(c.normal, [0.0, 1.0], atol=TOL)
    np.testing.assert_allclose(c.depth, 0.1, atol=1e-12)
    assert contacts_from_manifolds(Manifolds.empty(), []) == []


def test_contacts_from_manifolds_read_every_record_as_it_stands():
    """The contacts of a settled heap of boxes and discs (one- and two-point manifolds, impulses
    from the solver) carry each record's fields exactly, as Python floats and ints."""
    import sandbox

    world = sandbox.World(gravity=(0.0, -9.81))
    floor = world.add_body(sandbox.Body("floor", type="static", position=(0.0, -0.5)))
    floor.add_shape(sandbox.Box(20.0, 1.0))
    for i in range(12):
        body = world.add_body(
            sandbox.Body(f"b{i}", position=(0.45 * (i % 4), 0.6 + 1.1 * (i // 4)))
        )
        body.add_shape(sandbox.Circle(0.4) if i % 3 == 0 else sandbox.Box(0.8, 0.8))
    for _ in range(90):
        world.step()
    m = world.manifolds
    assert len(m) >= 10 and set(m.count.tolist()) == {1, 2}
    shapes = [shape for body in world.bodies for shape in body.shapes]
    contacts = contacts_from_manifolds(m, world.bodies)
    assert len(contacts) == len(m)
    for k, c in enumerate(contacts):
        rec, n = m.records[k], int(m.count[k])
        assert (c.a, c.b) == (world.bodies[rec["a"]], world.bodies[rec["b"]])
        assert (c.shape_a, c.shape_b) == (shapes[rec["shape_a"]], shapes[rec["shape_b"]])
        assert c.normal == tuple(rec["normal"].tolist()) and type(c.normal[0]) is float
        assert c.points == [tuple(rec["points"]["point"][j].tolist()) for j in range(n)]
        assert c.depths == rec["points"]["depth"][:n].tolist()
        assert c.impulses == m.normal_impulse[k, :n].tolist()
        assert c.tangent_impulses == m.tangent_impulse[k, :n].tolist()
        assert c.features == rec["points"]["feature"][:n].tolist()
        assert (c.friction, c.restitution) == (rec["friction"], rec["restitution"])
        assert all(type(x) is float for x in c.depths + c.impulses + [c.friction])
        assert all(type(f) is int for f in c.features)
    assert any(c.impulses[0] > 0.0 for c in contacts)
    # shapes that do not cover the records' indices: the indices instead
    few = contacts_from_manifolds(m, world.bodies, shapes=shapes[:1])
    assert all(type(c.shape_a) is int and type(c.shape_b) is int for c in few)


# --- symmetry --------------------------------------------------------------------------------

coord = st.floats(-1.0, 1.0, allow_nan=False)
size = st.floats(0.2, 2.0, allow_nan=False)
angle = st.floats(-math.pi, math.pi, allow_nan=False)
shape = st.one_of(
    st.builds(lambda r: circle(r), size.map(lambda s: 0.5 * s)),
    st.builds(lambda w, h, a: box(w, h, angle=a), size, size, angle),
)


@settings(max_examples=150, deadline=None)
@given(shape, shape, coord, coord, angle, coord, coord, angle)
def test_swapping_a_and_b_flips_normal_keeps_points(sa, sb, xa, ya, ta, xb, yb, tb):
    arrays = scene(((xa, ya), ta, [sa]), ((xb, yb), tb, [sb]))
    forward = run(arrays, margin=0.02)
    backward = run(arrays, pairs=((1, 0),), margin=0.02)
    assert len(forward) == len(backward)
    if len(forward) == 0:
        return
    assert forward.count[0] == backward.count[0]
    np.testing.assert_allclose(forward.normal[0], -backward.normal[0], atol=1e-12)
    assert abs(np.hypot(*forward.normal[0]) - 1.0) < 1e-12
    k = forward.count[0]
    f = sorted(zip(*points_of(forward).T, forward.depth[0, :k], strict=True))
    b = sorted(zip(*points_of(backward).T, backward.depth[0, :k], strict=True))
    np.testing.assert_allclose(f, b, atol=1e-12)
