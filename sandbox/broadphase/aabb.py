"""Axis-aligned bounding boxes: what every broadphase works on, and the pair list it returns.

An AABB is the row ``[xmin, ymin, xmax, ymax]`` (metres, world frame). Two boxes overlap when
they overlap on both axes; touching boxes (a shared edge or corner) count as overlapping, so the
test uses ``<=`` (slides, "Collision Detection Performance": the cheap test that decides which
pairs reach the exact, expensive narrowphase).

The helpers below the public functions are shared by the strategy modules: the filter (static-
static and same-body pairs are never reported), the overlap test, a growable pair buffer and the
final sort into the one pair list all strategies return.
"""

from __future__ import annotations

import numpy as np

from sandbox.jit import njit
from sandbox.math2d import rotate
from sandbox.records import BODY, CIRCLE, SHAPE, VERTEX
from sandbox.sorting import sort_in_place


@njit
def shape_box(shape, vertices, body, margin: float) -> tuple[float, float, float, float]:
    """The world AABB ``(xmin, ymin, xmax, ymax)`` of one shape record, grown by ``margin`` (m).

    A body-frame point q (about the centre of mass) lies at ``com + R(cs) q``. Circles: centre
    +- radius. Polygons: the extremes of the turned vertices.
    """
    c, s = body["cs"][0], body["cs"][1]
    px, py = body["com"][0], body["com"][1]
    grow = shape["radius"] + margin
    if shape["kind"] == CIRCLE:
        x, y = rotate(c, s, shape["center"][0], shape["center"][1])
        return px + x - grow, py + y - grow, px + x + grow, py + y + grow
    x0 = y0 = np.inf
    x1 = y1 = -np.inf
    first = shape["first_vertex"]
    for v in range(first, first + shape["vertex_count"]):
        q = vertices[v]["point"]
        x, y = rotate(c, s, q[0], q[1])
        x0, y0 = min(x0, px + x), min(y0, py + y)
        x1, y1 = max(x1, px + x), max(y1, py + y)
    return x0 - grow, y0 - grow, x1 + grow, y1 + grow


@njit
def aabbs_into(shapes, vertices, bodies, margin: float, out) -> None:
    """Every shape's AABB into ``out`` (m, 4) ``[xmin, ymin, xmax, ymax]``."""
    for k in range(shapes.shape[0]):
        box = shape_box(shapes[k], vertices, bodies[shapes[k]["body"]], margin)
        out[k, 0], out[k, 1], out[k, 2], out[k, 3] = box


def shape_aabbs(
    shape_body: np.ndarray,
    shape_kind: np.ndarray,
    shape_radius: np.ndarray,
    shape_center: np.ndarray,
    shape_vstart: np.ndarray,
    shape_vcount: np.ndarray,
    verts: np.ndarray,
    com: np.ndarray,
    cs: np.ndarray,
    margin: float = 0.0,
) -> np.ndarray:
    """World AABBs ``(m, 4)`` of shapes given as flat arrays (geometry about each body's centre
    of mass, body frame; ``com`` (n, 2) and ``cs`` (n, 2) = (cos, sin) place the bodies), grown
    by ``margin`` (m): :func:`shape_box` for each, for lessons and tests without a world."""
    m = len(shape_body)
    shapes = np.zeros(m, dtype=SHAPE)
    shapes["body"], shapes["kind"], shapes["radius"] = shape_body, shape_kind, shape_radius
    shapes["center"] = np.reshape(shape_center, (-1, 2))
    shapes["first_vertex"], shapes["vertex_count"] = shape_vstart, shape_vcount
    vertices = np.zeros(len(verts), dtype=VERTEX)
    vertices["point"] = np.reshape(verts, (-1, 2))
    bodies = np.zeros(len(com), dtype=BODY)
    bodies["com"], bodies["cs"] = com, cs
    out = np.empty((m, 4))
    aabbs_into(shapes, vertices, bodies, float(margin), out)
    return out


def swept_aabbs(aabb0: np.ndarray, aabb1: np.ndarray) -> np.ndarray:
    """Union of the boxes at the start and at the end of a step (continuous collision):
    ``[min(xmin0, xmin1), min(ymin0, ymin1), max(xmax0, xmax1), max(ymax0, ymax1)]``."""
    a0 = np.asarray(aabb0, dtype=np.float64)
    a1 = np.asarray(aabb1, dtype=np.float64)
    out = np.empty(np.broadcast_shapes(a0.shape, a1.shape))
    np.minimum(a0[..., :2], a1[..., :2], out=out[..., :2])
    np.maximum(a0[..., 2:], a1[..., 2:], out=out[..., 2:])
    return out


def check_tree_options(name: str, capacity: int, max_depth: int) -> tuple[int, int]:
    """Leaf ``capacity`` (>= 1) and ``max_depth`` (>= 0) of the quadtree and kd-tree, as ints."""
    if int(capacity) < 1 or int(max_depth) < 0:
        raise ValueError(f"{name} needs capacity >= 1 and max_depth >= 0")
    return int(capacity), int(max_depth)


# ---- shared by the strategy kernels ----------------------------------------------------------
# Each kernel spells out the same five lines per candidate pair (skip, count, record, test,
# keep). Folding them into one inlined helper returning (k, tests) was measured to make the grid
# about 1.5x and the quadtree about 2.5x slower at 10,000 boxes, so the repetition stays.


@njit
def skip_pair(static: np.ndarray, body: np.ndarray, i: int, j: int) -> bool:
    """Pairs never reported, decided without an overlap test: one body, or both static (two
    flags sharing a bit: see :mod:`sandbox.broadphase`)."""
    if body[i] == body[j]:
        return True
    return (static[i] & static[j]) != 0


@njit
def overlap(aabb: np.ndarray, i: int, j: int) -> bool:
    """The AABB-vs-AABB test: overlap on x and on y, touching included (``<=``)."""
    return (
        aabb[i, 0] <= aabb[j, 2]
        and aabb[j, 0] <= aabb[i, 2]
        and aabb[i, 1] <= aabb[j, 3]
        and aabb[j, 1] <= aabb[i, 3]
    )


@njit
def put_pair(buf: np.ndarray, k: int, i: int, j: int) -> None:
    """Write pair ``(min(i, j), max(i, j))`` at row ``k`` of ``buf`` if it fits.

    Kernels keep counting past the end of the buffer; :func:`collect` then runs them again with
    a buffer of the exact size (a growing array reassigned inside a hot loop makes numba's loop
    several times slower, so the buffer is grown between runs instead).
    """
    if k < buf.shape[0]:
        if i < j:
            buf[k, 0] = i
            buf[k, 1] = j
        else:
            buf[k, 0] = j
            buf[k, 1] = i


def collect(kernel, m: int, record: bool, *args):
    """Run ``kernel(*args, pairs_buf, tested_buf) -> (k, tests)`` and return
    ``(pairs sorted, tests, tested)``; reruns once with exact sizes if a buffer was too small."""
    buf = np.empty((4 * m + 64, 2), dtype=np.int64)
    tested = np.empty((16 * m + 64 if record else 0, 2), dtype=np.int64)
    k, tests = kernel(*args, buf, tested)
    if k > len(buf) or (record and tests > len(tested)):
        buf = np.empty((k, 2), dtype=np.int64)
        tested = np.empty((tests if record else 0, 2), dtype=np.int64)
        k, tests = kernel(*args, buf, tested)
    return sort_pairs(buf, k, m), int(tests), tested[: tests if record else 0].copy()


@njit
def sort_pairs(buf: np.ndarray, k: int, m: int) -> np.ndarray:
    """Rows ``buf[:k]`` (each ``i < j``) sorted lexicographically, as a new ``(k, 2)`` array."""
    out = np.empty((k, 2), dtype=np.int64)
    sort_pairs_into(buf, k, m, np.empty(m + 1, dtype=np.int64), out)
    return out


@njit
def sort_pairs_into(buf: np.ndarray, k: int, m: int, count: np.ndarray, out: np.ndarray) -> None:
    """Rows ``buf[:k]`` (each ``i < j``) sorted lexicographically into ``out[:k]``; ``count``
    (m + 1) is scratch.

    Counting sort on the first index (O(m + k)), then each run of equal first index sorted by
    the second (insertion sort for the usual short runs).
    """
    count[:] = 0
    for r in range(k):
        count[buf[r, 0] + 1] += 1
    for i in range(m):
        count[i + 1] += count[i]
    for r in range(k):  # count[i] runs ahead as run i fills, ending where run i + 1 starts
        i = buf[r, 0]
        out[count[i], 0] = i
        out[count[i], 1] = buf[r, 1]
        count[i] += 1
    for i in range(m):
        lo, hi = (count[i - 1] if i > 0 else 0), count[i]
        if hi - lo > 32:
            sort_in_place(out[lo:hi, 1])
        else:
            for a in range(lo + 1, hi):
                v = out[a, 1]
                b = a - 1
                while b >= lo and out[b, 1] > v:
                    out[b + 1, 1] = out[b, 1]
                    b -= 1
                out[b + 1, 1] = v
