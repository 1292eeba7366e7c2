# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: percent
# ---

# %% [markdown]
# # 04 Collision detection: contact manifolds
#
# Slides "Collision Detection", "Collision Manifolds", "Collision Detection Output" and
# "Sphere Collision Detection Example".
#
# A collision happens when the volumes of two bodies overlap on at least one point. The area
# where they touch (the **manifold**) can be a single point, a few discrete points, a line or
# an area. The common cases are
#
# - corner with side (**vertex-face**)
# - edge with edge (**edge-edge**)
# - edge with surface (**edge-face**)
#
# and, rarely, corner with corner or corner with edge. Lines and areas of contact are
# simplified to a few discrete points. For each point the detection step must deliver
#
# - the **point of contact** $\mathbf{p}_c$ (where the collision happened),
# - the **contact normal** $\hat{\mathbf{n}}$ (the direction of the collision),
# - the **penetration distance** $p$ (for resolving the interpenetration).
#
# In the sandbox, `world.find_contacts()` runs the broadphase and the narrowphase at the
# current state without stepping and returns one `Contact` per touching pair of shapes:
# `c.a`, `c.b` (the normal points from `a` to `b`), `c.normal`, `c.points` (1 or 2 world
# points, midway between the two surfaces), `c.depths` (one per point, $> 0$ when
# overlapping) and `c.features` (ids of the touching features, see the end of the lesson).
# In 2D a "face" is an edge, so every polygon contact is a line segment at most, and the
# engine keeps at most two points per pair.
#
# The formulas live in `sandbox/narrowphase/` (`circles.py`: circle-circle and
# polygon-circle; `polygons.py`: separating axes and clipping for polygon-polygon).

# %%
import math

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.patches import Circle as CirclePatch
from matplotlib.patches import Polygon as PolygonPatch

from sandbox import Body, Box, Circle, Polygon, World
from sandbox.lessonkit import output_dir, print_table, save_figure, show_gif
from sandbox.recording import record
from sandbox.render import render_gif

# knobs
SINK = 0.08  # m, how far the shapes of each case are pushed into each other
ARROW = 0.4  # length of the drawn normals, as a fraction of the panel half-width
ZOOM = 0.75  # m, half-width of each panel around its contact points
CLOSE_UPS = {"edge-edge": 0.3, "corner-corner (rare)": 0.15}  # m, panels zoomed in further

OUT = output_dir("04_collision_detection")


# %% [markdown]
# ## The manifold cases as tiny worlds
#
# Each case is a world of two bodies (no gravity, nothing steps): one static (grey) and one
# dynamic (blue), placed so that they overlap by a few centimetres. The unit boxes are
# $1 \times 1$ m.
#
# | case | what touches | expected manifold |
# | --- | --- | --- |
# | vertex-face | a corner of a tilted box in a tilted plank | 1 point |
# | edge-edge | two boxes whose corners interlock, so their edges cross | 2 points |
# | edge-face | a small box lying on a long plank | 2 points: the small box's corners |
# | single point | the tip of a wedge on the ground | 1 point |
# | line of contact | two boxes stacked half off each other | 2 points: the ends of the shared segment |
# | corner-corner (rare) | two diamonds tip to tip | 2 points almost on top of each other |
# | circle-circle | two discs | 1 point |
# | circle-box face | a disc over the middle of a box's side | 1 point, normal = the side's normal |
# | circle-box corner | a disc over a box's corner | 1 point, normal from the corner to the centre |


# %%
def pair_world(static: tuple, dynamic: tuple) -> World:
    """A world with two bodies: ``(position, angle, shape)`` for the static and the dynamic."""
    world = World(gravity=(0.0, 0.0))
    for name, kind, (pos, angle, shape) in (
        ("A", "static", static),
        ("B", "dynamic", dynamic),
    ):
        body = world.add_body(Body(name=name, type=kind, position=pos, angle=angle))
        body.add_shape(shape)
    return world


def lowest_corner(width: float, height: float, angle: float) -> np.ndarray:
    """Lowest vertex of a centred width x height box turned by ``angle`` (body origin frame)."""
    c, s = math.cos(angle), math.sin(angle)
    corners = [(sx * width / 2, sy * height / 2) for sx in (-1, 1) for sy in (-1, 1)]
    world = np.array([(c * x - s * y, s * x + c * y) for x, y in corners])
    return world[np.argmin(world[:, 1])]


half_diag = math.sqrt(0.5)  # half the diagonal of a unit box
tilt = 0.25  # rad, the tilted plank of the vertex-face case
# vertex-face: a box at 30 degrees whose lowest corner sinks into a plank tilted by `tilt`
# (the plank's top side passes through the origin, along `along`, with outward normal `up`)
along = np.array([math.cos(tilt), math.sin(tilt)])
up = np.array([-math.sin(tilt), math.cos(tilt)])
vf_pos = tuple(0.1 * along - SINK * up - lowest_corner(1.0, 1.0, math.radians(30)))
wedge = Polygon([(-0.4, 0.5), (0.4, 0.5), (0.0, -0.3)])  # tip 0.3 m below the body origin

CASES = {
    "vertex-face": pair_world(
        (tuple(-0.15 * up), tilt, Box(3.0, 0.3)),
        (vf_pos, math.radians(30), Box(1.0, 1.0)),
    ),
    "edge-edge": pair_world(
        ((0.0, 0.0), 0.0, Box(1.0, 1.0)),
        ((0.45, 0.42 + half_diag), math.pi / 4, Box(1.0, 1.0)),
    ),
    "edge-face": pair_world(
        ((0.0, -0.15), 0.0, Box(3.0, 0.3)),
        ((0.2, 0.25 - SINK), 0.0, Box(0.8, 0.5)),
    ),
    "single point": pair_world(
        ((0.0, -0.15), 0.0, Box(3.0, 0.3)),
        ((0.0, 0.3 - SINK), 0.15, wedge),
    ),
    "line of contact": pair_world(
        ((0.0, -0.5), 0.0, Box(1.0, 1.0)),
        ((0.6, 0.5 - SINK), 0.0, Box(1.0, 1.0)),
    ),
    "corner-corner (rare)": pair_world(
        ((0.0, 0.0), math.pi / 4, Box(1.0, 1.0)),
        ((0.0, 2 * half_diag - 0.25 * SINK), math.pi / 4, Box(1.0, 1.0)),
    ),
    "circle-circle": pair_world(
        ((0.0, 0.0), 0.0, Circle(0.5)),
        ((0.7, 0.3), 0.0, Circle(0.3)),
    ),
    "circle-box face": pair_world(
        ((0.0, 0.0), 0.0, Box(1.0, 1.0)),
        ((0.15, 0.5 + 0.3 - SINK), 0.0, Circle(0.3)),
    ),
    "circle-box corner": pair_world(
        ((0.0, 0.0), 0.0, Box(1.0, 1.0)),
        ((0.5 + 0.6 * (0.3 - SINK), 0.5 + 0.8 * (0.3 - SINK)), 0.0, Circle(0.3)),
    ),
}

# %% [markdown]
# ## What the detection reports
#
# `find_contacts()` also fills `world.stats`: `pair_tests` (bounding-box tests made by the
# broadphase), `pairs` (pairs whose boxes overlap, handed to the narrowphase), `contacts`
# (manifolds found) and `contact_points`. With two bodies there is one pair to test.

# %%
found = {}
rows = []
for name, world in CASES.items():
    contacts = world.find_contacts()
    found[name] = contacts
    s = world.stats
    c = contacts[0]
    rows.append(
        (
            name,
            s["pair_tests"],
            s["pairs"],
            s["contacts"],
            s["contact_points"],
            f"({c.normal[0]:+.3f}, {c.normal[1]:+.3f})",
            " ".join(f"({p[0]:+.3f}, {p[1]:+.3f})" for p in c.points),
            " ".join(f"{d:.4f}" for d in c.depths),
        )
    )
print_table(
    [
        "case",
        "pair_tests",
        "pairs",
        "contacts",
        "points",
        "normal a->b",
        "points (m)",
        "depths (m)",
    ],
    rows,
)


# %%
def outline(body: Body, shape) -> PolygonPatch | CirclePatch:
    """A matplotlib patch of one shape at its body's current pose."""
    colour = "0.6" if body.type == "static" else "tab:blue"
    style = {"facecolor": colour, "edgecolor": "k", "alpha": 0.45, "lw": 1}
    if shape.kind == "circle":
        return CirclePatch(body.world_point(shape.offset), shape.radius, **style)
    return PolygonPatch([body.world_point(v) for v in shape.vertices], closed=True, **style)


def draw_case(ax, name: str, world: World, contacts: list, zoom: float) -> None:
    """The shapes, and per contact point: a dot, the depth as a bar along the normal (from
    one surface to the other) and the normal as an arrow starting at b's surface."""
    for body in world.bodies:
        for shape in body.shapes:
            ax.add_patch(outline(body, shape))
    pts = []
    for c in contacts:
        n = c.normal
        for k, (p, d) in enumerate(zip(c.points, c.depths, strict=True)):
            pts.append(p)
            # the point lies midway between the surfaces: they are at p -/+ (d/2) n
            lo, hi = p - 0.5 * d * n, p + 0.5 * d * n
            ax.plot([lo[0], hi[0]], [lo[1], hi[1]], color="tab:orange", lw=5, zorder=4)
            ax.annotate(
                "",
                xy=hi + ARROW * zoom * n,
                xytext=hi,
                arrowprops={"arrowstyle": "-|>", "color": "tab:red", "lw": 1.5},
                zorder=6,
            )
            ax.plot(*p, "o", color="k", ms=4, zorder=5)
            ax.annotate(
                f"p = {d:.3f}",
                p,
                xytext=(8, -14) if k == 0 else (8, 8),
                textcoords="offset points",
                fontsize=8,
                bbox={"boxstyle": "round", "fc": "w", "ec": "none", "alpha": 0.8},
            )
    centre = np.mean(pts, axis=0)
    n = contacts[0].normal
    ax.text(
        0.02,
        0.02,
        f"n = ({n[0]:+.2f}, {n[1]:+.2f})\n{len(pts)} point(s)",
        transform=ax.transAxes,
        fontsize=8,
        va="bottom",
    )
    ax.set(xlim=(centre[0] - zoom, centre[0] + zoom), ylim=(centre[1] - zoom, centre[1] + zoom))
    ax.set_aspect("equal")
    ax.set_title(name, fontsize=10)
    ax.set_xlabel("x (m)", fontsize=8)
    ax.set_ylabel("y (m)", fontsize=8)
    ax.tick_params(labelsize=7)


fig, axes = plt.subplots(3, 3, figsize=(11, 11))
for ax, (name, world) in zip(axes.flat, CASES.items(), strict=True):
    zoom = CLOSE_UPS.get(name, ZOOM)
    draw_case(ax, name, world, found[name], zoom)
fig.suptitle(
    "contact points (dots), depth p (orange bar between the two surfaces), normal n from a "
    "(grey) to b (blue) (red arrow)",
    fontsize=10,
)
fig.tight_layout()
save_figure(fig, OUT / "manifolds.png", dpi=90)

# %% [markdown]
# What the panels show:
#
# - **vertex-face** and **single point**: one corner is inside the other body; the normal is
#   the normal of the face it went through and $p$ is the corner's distance below that face.
# - **edge-edge**: the corners interlock and two pairs of edges cross. The narrowphase takes
#   the side of least penetration (separating axis test) as the *reference face*, the most
#   opposed edge of the other body as the *incident edge*, and clips that edge to the
#   reference face's side planes: one point is the blue corner, the other where the blue
#   edge leaves the grey box's top (depths $0.08$ and $0.03$ m).
# - **edge-face** and **line of contact**: the contact is a segment. The incident edge is
#   *clipped* to the side planes of the reference face, leaving its two ends: the small box's
#   corners in the first case, the ends of the shared part of the two tops in the second.
#   Two points are enough for a 2D solver to stop both sliding and tipping.
# - **corner-corner**: the rare case gets no special treatment; the same clipping gives two
#   points a few millimetres apart, with the normal of one of the faces next to the tips.
# - **circles**: always one point.
#
# ### The manifold over time
#
# A box dropped corner first onto the ground, drawn with the `contacts` and `normals` debug
# layers (filled dots: touching points; hollow: speculative points within the contact margin,
# not yet touching): it lands on one corner (vertex-face: one point, hollow while the corner is
# still within the margin above the ground), then tips onto its side (edge-face: two points).

# %%
drop = World()
ground_d = drop.add_body(Body(name="ground", type="static"))
ground_d.add_shape(Box(4.0, 0.4, offset=(0.0, -0.2)))
box_d = drop.add_body(Body(name="box", position=(0.0, 1.0), angle=0.5))
box_d.add_shape(Box(0.8, 0.5))
rec_d = record(drop, 90, draw="contacts,normals")
touching = [int(np.sum(rows[:, 6] >= 0.0)) for rows in rec_d.overlays.contacts]  # depth >= 0
first = next(k for k, p in enumerate(touching) if p)
print(
    f"touching contact points per frame: {touching[first]} at first touch (frame {first}), "
    f"{touching[-1]} at the end"
)
gif = render_gif(rec_d, OUT / "manifold_over_time.gif", fps=30, size_px=360,
                 draw="contacts,normals", view=(-1.2, 1.2, -0.3, 1.5))  # fmt: skip
show_gif(gif)
print(f"wrote {len(rec_d)} frames to {gif.name}")

# %% [markdown]
# ## The slides' circle formulas, by hand and by the engine
#
# Sphere (here: disc) 1 at $\mathbf{p}_1$ with radius $r_1$, disc 2 at $\mathbf{p}_2$ with
# radius $r_2$. They touch or overlap when
#
# $$d = |\mathbf{p}_2 - \mathbf{p}_1| \le r_1 + r_2 ,$$
#
# and then the penetration, normal and (approximate) contact point are
#
# $$p = r_1 + r_2 - d, \qquad \hat{\mathbf{n}} = \frac{1}{d}(\mathbf{p}_2 - \mathbf{p}_1),
# \qquad \mathbf{p}_c = \mathbf{p}_1 + \left(r_1 - \frac{p}{2}\right)\hat{\mathbf{n}} .$$
#
# $\mathbf{p}_c$ is the point midway between the two surfaces along the normal: disc 1's
# surface is at $\mathbf{p}_1 + r_1 \hat{\mathbf{n}}$, disc 2's at
# $\mathbf{p}_2 - r_2\hat{\mathbf{n}} = \mathbf{p}_1 + (r_1 - p)\hat{\mathbf{n}}$.
# Below, the formulas are evaluated by hand for a few pairs (one just touching, one apart)
# and compared with what `find_contacts()` returns.

# %%
CIRCLE_PAIRS = [  # (p1, r1, p2, r2)
    ((0.0, 0.0), 0.5, (0.7, 0.3), 0.3),
    ((0.0, 0.0), 1.0, (1.5, 0.0), 0.6),
    ((1.0, 1.0), 0.4, (1.2, 1.5), 0.25),
    ((-2.0, 0.5), 0.2, (-2.1, 0.35), 0.2),
    ((0.0, 0.0), 0.5, (0.3, 0.4), 0.5),  # d = 0.5, deep overlap
    ((0.0, 0.0), 0.3, (0.3, 0.4), 0.2),  # d = 0.5 = r1 + r2: just touching
    ((0.0, 0.0), 0.3, (0.6, 0.8), 0.5),  # d = 1.0 > 0.8: apart
]

rows = []
worst = 0.0
for p1, r1, p2, r2 in CIRCLE_PAIRS:
    p1, p2 = np.array(p1), np.array(p2)
    # by hand, slides "Sphere Collision Detection Example"
    d = float(np.linalg.norm(p2 - p1))
    touching = d <= r1 + r2
    world = pair_world((tuple(p1), 0.0, Circle(r1)), (tuple(p2), 0.0, Circle(r2)))
    contacts = world.find_contacts()
    if not touching:
        rows.append((d, r1 + r2, "no", "-", "-", "-", "-", "-", "-", len(contacts)))
        continue
    p = r1 + r2 - d
    n = (p2 - p1) / d
    pc = p1 + (r1 - p / 2) * n
    c = contacts[0]
    assert c.a.name == "A"  # the normal points from disc 1 to disc 2
    diff = max(abs(c.depth - p), *np.abs(c.normal - n), *np.abs(c.points[0] - pc))
    worst = max(worst, diff)
    rows.append(
        (
            d,
            r1 + r2,
            "yes",
            p,
            c.depth,
            f"({n[0]:.4f}, {n[1]:.4f})",
            f"({c.normal[0]:.4f}, {c.normal[1]:.4f})",
            f"({pc[0]:.4f}, {pc[1]:.4f})",
            f"({c.points[0][0]:.4f}, {c.points[0][1]:.4f})",
            len(contacts),
        )
    )
print_table(
    [
        "d",
        "r1+r2",
        "d<=r1+r2",
        "p hand",
        "p engine",
        "n hand",
        "n engine",
        "pc hand",
        "pc engine",
        "contacts",
    ],
    rows,
)
print(f"largest difference hand vs engine: {worst:.1e}")

# %% [markdown]
# **Circles against boxes** use the same formula once the closest point of the box is known.
# Over a side, the box acts like a disc of infinite radius (a plane): $d$ becomes the distance
# of the centre from the side, $p = r - d$ and $\hat{\mathbf{n}}$ is the side's outward
# normal. Beyond a corner, the corner acts like a disc of radius $0$ centred on the corner
# $\mathbf{v}$: $d = |\mathbf{c} - \mathbf{v}|$, $p = 0 + r - d$,
# $\hat{\mathbf{n}} = (\mathbf{c} - \mathbf{v}) / d$ and
# $\mathbf{p}_c = \mathbf{v} + (0 - p/2)\hat{\mathbf{n}}$.

# %%
rows = []
for name in ("circle-box face", "circle-box corner"):
    world = CASES[name]
    box, ball = world.body("A"), world.body("B")
    c_ball, r = np.array(ball.position), ball.shapes[0].radius
    if name.endswith("face"):
        n = np.array([0.0, 1.0])  # the top side's outward normal
        d = float(c_ball[1] - (box.position[1] + 0.5))  # distance above the top side
        p = r - d
        pc = c_ball - (r - p / 2) * n
    else:
        v = np.array(box.position) + (0.5, 0.5)  # the top right corner, a disc of radius 0
        d = float(np.linalg.norm(c_ball - v))
        p = 0.0 + r - d
        n = (c_ball - v) / d
        pc = v + (0.0 - p / 2) * n
    c = found[name][0]
    rows.append(
        (
            name,
            d,
            p,
            c.depth,
            f"({n[0]:.4f}, {n[1]:.4f})",
            f"({c.normal[0]:.4f}, {c.normal[1]:.4f})",
            f"({pc[0]:.4f}, {pc[1]:.4f})",
            f"({c.points[0][0]:.4f}, {c.points[0][1]:.4f})",
        )
    )
print_table(["case", "d", "p hand", "p engine", "n hand", "n engine", "pc hand", "pc engine"], rows)

# %% [markdown]
# ## Feature ids: which corner touches which side
#
# Each contact point also carries a **feature id** (`c.features`), an integer naming the
# pair of features that produced it. For polygons it is
# `code * 2**32 + vertex_of_a * 2**16 + vertex_of_b` (`code` 0 for two faces, 2 for two
# corners), where the vertices are the reference-face vertex whose side plane bounds the point
# and the incident vertex it came from, a's first whichever polygon holds the reference face:
# two equal boxes can swap which face is the reference from one step to the next, and the same
# point must keep its name. Circle contacts have id 0 (a circle has one feature).
#
# The id does not say *where* the point is: it says *which* features touch, so it stays the
# same from one step to the next while the same corner rests on the same side, even though
# the point moves a little. The iterative solver uses this to **warm start**: it finds each
# point of this step among the last step's points by (shapes, feature id) and starts from the
# impulse that point needed last time (`match_previous` in `sandbox/solvers/common.py`). Without stable ids a
# resting stack would have to rebuild its impulses from zero every step and would jitter.
#
# Below, the upper box of the "line of contact" case slides and turns a little, then slides
# so far that the left end of the shared segment is the lower box's corner instead of its
# own: the points move, the ids stay, because an id names the reference side plane and the
# incident vertex that bound the point whether or not the clip was active. Turned a quarter
# turn, a different side of the upper box lies on the lower one: new ids, and the solver
# would start those points from zero.


# %%
def decode(fid: int) -> str:
    code, va, vb = fid >> 32, (fid >> 16) & 0xFFFF, fid & 0xFFFF
    kind = "faces" if code == 0 else "vertex-vertex"
    return f"{fid} = {kind}, a's v{va} / b's v{vb}"


world = CASES["line of contact"]
upper = world.body("B")
rows = []
for dx, dtheta in (
    (0.0, 0.0),
    (0.03, 0.0),
    (0.06, 0.01),
    (-0.8, 0.0),
    (0.0, 0.3),
    (0.0, math.pi / 2),
):
    upper.position = (0.6 + dx, 0.5 - SINK)
    upper.angle = dtheta
    for c in world.find_contacts():
        for p, f in zip(c.points, c.features, strict=True):
            rows.append(
                (f"{dx:+.2f} m, {dtheta:.2f} rad", f"({p[0]:+.3f}, {p[1]:+.3f})", decode(f))
            )
print_table(["upper box moved by", "point (m)", "feature id"], rows)

# %% [markdown]
# ## Exercises
#
# Predict first, then run the cell under the question, then open the answer.
#
# **1.** Disc 1 (radius 0.5 m) at the origin, disc 2 (radius 0.3 m) at $(0.6, 0.45)$. Work out
# $d$, $p$, $\hat{\mathbf{n}}$ and $\mathbf{p}_c$ with the slides' formulas, then ask the engine.

# %%
(c1,) = pair_world(((0.0, 0.0), 0.0, Circle(0.5)), ((0.6, 0.45), 0.0, Circle(0.3))).find_contacts()
print(f"depth {c1.depth:.4f} m, normal ({c1.normal[0]:.4f}, {c1.normal[1]:.4f}), "
      f"point ({c1.points[0][0]:.4f}, {c1.points[0][1]:.4f})")  # fmt: skip

# %% [markdown]
# <details><summary>Answer</summary>
#
# $d = |(0.6, 0.45)| = 0.75$ m $\le 0.8$: they overlap by $p = 0.8 - 0.75 = 0.05$ m. The normal
# is $(0.6, 0.45) / 0.75 = (0.8, 0.6)$ and $\mathbf{p}_c = (0.5 - 0.025)(0.8, 0.6) = (0.38,
# 0.285)$, midway between the surfaces at $0.5$ and $0.45$ m from the origin. The engine agrees.
#
# </details>
#
# **2.** Tilt the small box of the edge-face case by 0.02 rad about its centre. How many contact
# points now, and how deep is each?

# %%
tilted = pair_world(((0.0, -0.15), 0.0, Box(3.0, 0.3)), ((0.2, 0.25 - SINK), 0.02, Box(0.8, 0.5)))
for c2 in tilted.find_contacts():
    print(f"{len(c2.points)} points, depths " + ", ".join(f"{d:.4f} m" for d in c2.depths))

# %% [markdown]
# <details><summary>Answer</summary>
#
# Still two: one body's edge is clipped against the other's face and both of its ends stay
# in contact. Turning by $\theta = 0.02$ rad lowers the left corner and raises the right one by
# $0.4\sin\theta = 0.0080$ m, and raises both by $0.25(1 - \cos\theta) = 0.00005$ m: depths
# $0.08 + 0.0080 - 0.00005 = 0.0879$ and $0.08 - 0.0080 - 0.00005 = 0.0720$ m, as the run
# prints. A manifold keeps both corners (rather than the deepest one) so that the solver can
# stop the box from tipping.
#
# </details>
#
# **3.** A disc of radius 0.3 m at $(0.65, 0.7)$ above a unit box centred at the origin. Which
# feature does it touch, and what are $p$ and $\hat{\mathbf{n}}$?

# %%
(c3,) = pair_world(
    ((0.0, 0.0), 0.0, Box(1.0, 1.0)), ((0.65, 0.7), 0.0, Circle(0.3))
).find_contacts()
print(f"depth {c3.depth:.4f} m, normal ({c3.normal[0]:.4f}, {c3.normal[1]:.4f}), "
      f"point ({c3.points[0][0]:.4f}, {c3.points[0][1]:.4f})")  # fmt: skip

# %% [markdown]
# <details><summary>Answer</summary>
#
# The centre is beyond both the top side ($y > 0.5$) and the right side ($x > 0.5$), so the
# closest feature is the corner $\mathbf{v} = (0.5, 0.5)$, a disc of radius 0:
# $d = |(0.15, 0.2)| = 0.25$ m, $p = 0.3 - 0.25 = 0.05$ m, $\hat{\mathbf{n}} = (0.6, 0.8)$
# (neither side's normal), $\mathbf{p}_c = \mathbf{v} - 0.025\,\hat{\mathbf{n}} = (0.485,
# 0.48)$.
#
# </details>
