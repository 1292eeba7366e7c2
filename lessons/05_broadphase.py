# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: percent
# ---

# %% [markdown]
# # 05 Broadphase: which pairs are worth testing?
#
# Slides "Collision Detection Performance" and "Regular Grids".
#
# The narrowphase (exact contact points, normals, depths) is expensive, so a cheap first pass
# decides which pairs of shapes can touch at all. Each shape gets an axis-aligned bounding box
# (AABB) $[x_{min}, y_{min}, x_{max}, y_{max}]$ and two boxes overlap when
#
# $$x_{min,i} \le x_{max,j} \;\wedge\; x_{min,j} \le x_{max,i} \;\wedge\;
#   y_{min,i} \le y_{max,j} \;\wedge\; y_{min,j} \le y_{max,i}.$$
#
# The simplest broadphase tests every pair: $n(n-1)/2$ combinations, which grows as $n^2$. The
# slides' better approaches partition space or sort coordinates so most far-apart pairs are
# never looked at:
#
# - **grid**: regular cells (hashed, so empty space costs nothing); test only shapes sharing
#   a cell, each pair once
# - **quadtree**: split a square into four while a node holds too many shapes; test shapes
#   sharing a leaf
# - **kd-tree**: split at the median, across the axis of larger spread; shapes straddling the
#   line stay at the node
# - **sap** (sort and sweep, "co-ordinate sorting"): sort boxes by $x_{min}$ and sweep;
#   only boxes whose intervals overlap are tested. Swept in one piece, a box meets every box
#   of a strip across the whole world, so the engine first cuts the world into bands across
#   the sweep (each at most twice as tall as the mean box) and sweeps each band on its own,
#   along x or y, whichever has fewer overlapping intervals ("sap, one band" below is the
#   sweep without bands; "Bodies on a grid" shows a third way, turning the sweep)
#
# All five return exactly the same sorted pair list (a tested invariant), so the simulation is
# identical whichever is chosen; they differ only in how many overlap tests they make
# (`pair_tests`) and how long they take.

# %%
import math
import time

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.collections import LineCollection, PatchCollection
from matplotlib.colors import to_rgba
from matplotlib.patches import Circle, Rectangle

from sandbox.broadphase import STRATEGIES, describe, find_pairs, find_pairs_traced, shape_aabbs
from sandbox.lessonkit import output_dir, print_table, save_figure

# knobs
SIZES = (10, 30, 100, 300, 1000, 3000, 10000)  # numbers of circles in the scaling study
BRUTE_MAX = 3000  # brute force is skipped above this (10,000 circles = 50 million tests)
COVER = 0.3  # fraction of the box's area covered by circles: the density kept constant
RADII = (0.1, 0.5)  # m, circle radii drawn uniformly from this range (mixed sizes)
PICTURE_N = 120  # circles in the pictures of the structures
BUDGET = 0.15  # s of timing per strategy and size (the best of several calls is kept)
SEED = 5

OUT = output_dir("05_broadphase")
COLOUR = {
    "brute": "tab:gray",
    "grid": "tab:blue",
    "sap": "tab:orange",
    "sap, one band": "tab:brown",
    "quadtree": "tab:green",
    "kdtree": "tab:red",
}
# the scaling study's series: every strategy, and sort and sweep without its bands
SERIES = {name: (name, {}) for name in STRATEGIES} | {"sap, one band": ("sap", {"bands": False})}


def circle_aabbs(centres: np.ndarray, radii: np.ndarray) -> np.ndarray:
    """AABBs of circles, one per body, through the engine's `shape_aabbs` (no world needed)."""
    m = len(radii)
    return shape_aabbs(
        np.arange(m),  # shape_body: one body per circle
        np.zeros(m, dtype=np.int64),  # all circles
        np.asarray(radii, dtype=float),
        np.zeros((m, 2)),  # circle centred on its body's centre of mass
        np.zeros(m, dtype=np.int64),
        np.zeros(m, dtype=np.int64),
        np.zeros((0, 2)),  # no polygon vertices
        np.asarray(centres, dtype=float),
        np.tile([1.0, 0.0], (m, 1)),  # angle 0: (cos, sin) = (1, 0)
        0.0,
    )


def random_circles(n: int, rng: np.random.Generator):
    """n circles of mixed size in a square box sized so they cover COVER of its area."""
    r = rng.uniform(*RADII, n)
    side = math.sqrt(np.sum(math.pi * r * r) / COVER)
    return rng.uniform(0.0, side, (n, 2)), r, side


def draw_circles(ax, centres, radii, colour="0.35"):
    patches = [Circle(c, r) for c, r in zip(centres, radii, strict=True)]
    ax.add_collection(PatchCollection(patches, facecolor="none", edgecolor=colour, lw=0.8))
    ax.set_aspect("equal")


# %% [markdown]
# ## The slides' regular grid
#
# The slide shows nine bodies on a regular grid and lists the pairs that share a cell:
# (1,2), (3,4), (3,5), (4,5) and (5,6), with body 5 spanning two cells and 7, 8, 9 alone:
# "only 5 out of 36 possible combinations tested". The arithmetic holds:
# $9 \cdot 8 / 2 = 36$. Below, the same layout on 1 m cells, with the engine's grid counting
# what it tests. A pair sharing several cells would still be tested once (in the lower-left
# cell both occupy).

# %%
slide_centres = np.array(
    [
        [0.25, 0.25],
        [0.7, 0.7],
        [2.25, 0.25],
        [2.55, 0.35],
        [2.55, 0.8],
        [2.3, 1.7],
        [0.5, 2.5],
        [1.5, 1.5],
        [3.5, 2.5],
    ]
)
slide_radii = np.array([0.15, 0.2, 0.15, 0.18, 0.3, 0.2, 0.3, 0.3, 0.3])
slide_boxes = circle_aabbs(slide_centres, slide_radii)
pairs, tests, tested = find_pairs_traced("grid", slide_boxes, record=True, cell_size=1.0)
n_slide = len(slide_radii)
print(f"{n_slide} bodies: {n_slide * (n_slide - 1) // 2} possible pairs, grid tests {tests}")
print("tested pairs:", sorted(tuple(int(v) + 1 for v in p) for p in tested))
print("of which the boxes overlap:", [tuple(int(v) + 1 for v in p) for p in pairs])

fig, ax = plt.subplots(figsize=(4.8, 3.8))
grid_info = describe("grid", slide_boxes, cell_size=1.0)
for cx, cy in grid_info["cells"]:
    ax.add_patch(Rectangle((cx, cy), 1.0, 1.0, color="tab:blue", alpha=0.12))
for k in range(5):
    ax.plot([k, k], [0, 3], color="tab:blue", lw=0.6)
for k in range(4):
    ax.plot([0, 4], [k, k], color="tab:blue", lw=0.6)
draw_circles(ax, slide_centres, slide_radii)
for i, (x, y) in enumerate(slide_centres):
    ax.text(x, y, str(i + 1), ha="center", va="center", fontsize=9)
segments = [slide_centres[[i, j]] for i, j in tested]
ax.add_collection(LineCollection(segments, colors="tab:red", lw=1.5))
ax.set(xlim=(-0.1, 4.1), ylim=(-0.1, 3.1), xlabel="x (m)", ylabel="y (m)")
ax.set_title(f"regular grid: {tests} of {n_slide * (n_slide - 1) // 2} pairs tested (red)")
fig.tight_layout()
save_figure(fig, OUT / "slides_grid.png", dpi=100)

# %% [markdown]
# ## Cost against the number of bodies
#
# Random circles of mixed size (radius 0.1 to 0.5 m) in a square box whose side grows as
# $\sqrt{N}$, so the density stays constant and each circle has about the same number of
# neighbours whatever $N$. For each strategy: the overlap tests it makes and the time per call
# (best of several calls). Brute force is skipped above `BRUTE_MAX` circles to keep the lesson
# short: at 10,000 circles it would make 49,995,000 tests per call.

# %%
rng = np.random.default_rng(SEED)
results = {name: [] for name in SERIES}  # (N, pair_tests, ms per call, pairs)
for n in SIZES:
    centres, radii, _ = random_circles(n, rng)
    boxes = circle_aabbs(centres, radii)
    reference = None
    for name, (strategy, options) in SERIES.items():
        if name == "brute" and n > BRUTE_MAX:
            continue
        pairs, tests = find_pairs(strategy, boxes, **options)  # also compiles on a cold cache
        if reference is None:
            reference = pairs
        assert np.array_equal(pairs, reference), name  # the same list from every strategy
        best, spent, calls = math.inf, 0.0, 0
        while calls < 3 or (spent < BUDGET and calls < 200):
            t0 = time.perf_counter()
            find_pairs(strategy, boxes, **options)
            dt = time.perf_counter() - t0
            best, spent, calls = min(best, dt), spent + dt, calls + 1
        results[name].append((n, tests, 1e3 * best, len(pairs)))

for what, column in (("pair tests per call", 1), ("ms per call", 2)):  # two narrow tables
    rows = []
    for n in SIZES:
        hits = [[r for r in results[name] if r[0] == n] for name in SERIES]
        rows.append([n] + [hit[0][column] if hit else "-" for hit in hits])
    print(what)
    print_table(["N", *SERIES], rows, digits=3)
    print()

# %% [markdown]
# The growth exponent $p$ in $\text{cost} \approx c N^p$ is the slope of the log-log curve,
# fitted here by least squares over $N \ge 300$ (below that, the fixed cost of a call hides
# the growth). Brute force tests all pairs: $p = 2$ exactly for the tests. The grid, quadtree
# and kd-tree test each circle against a bounded neighbourhood, so $p \approx 1$ for the tests.
# Their time grows a little faster, $p \approx 1.1$ to $1.5$: trees are built in
# $O(N \log N)$, and a bigger world no longer fits the processor's fastest caches (brute
# force's time exponent comes out above 2 for the same reason). Sort and sweep in one band
# ("sap, one band") tests every box against all boxes whose intervals on that axis overlap its
# own: a thin strip holding about $\sqrt{N}$ boxes in a square world, so its tests grow as
# $N^{1.5}$ (572,874 tests at 10,000 circles). Cut into bands about two boxes tall, the strip
# is only a band long, a bounded neighbourhood again: $p \approx 1$ (13,470 tests, fewer than
# the grid's). Its time still grows faster than its tests: the boxes are sorted, and the
# direction is chosen by counting both directions' candidates, which sorts each band twice
# more. In a world that steps, the order is kept from step to step and the direction chosen
# once every 30 steps, so the step pays for little of that. Timings vary from run to run and
# machine to machine; the test counts do not.

# %%
fit_rows = []
for name in SERIES:
    data = np.array([r[:3] for r in results[name] if r[0] >= 300], dtype=float)
    p_tests = np.polyfit(np.log(data[:, 0]), np.log(data[:, 1]), 1)[0]
    p_time = np.polyfit(np.log(data[:, 0]), np.log(data[:, 2]), 1)[0]
    fit_rows.append([name, p_tests, p_time])
print_table(["strategy", "exponent of tests", "exponent of time"], fit_rows, digits=2)

print()
for n in (1000, 10000):
    table = []
    for name in SERIES:
        hit = [r for r in results[name] if r[0] == n]
        if hit:
            table.append([name, hit[0][1], hit[0][2], hit[0][3]])
        else:
            table.append([name, f"{n * (n - 1) // 2} (not run)", "-", "-"])
    print(f"N = {n}: all pairs n(n-1)/2 = {n * (n - 1) // 2}")
    print_table(["strategy", "pair tests", "ms per call", "overlapping pairs"], table, digits=3)
    print()

fig, axes = plt.subplots(1, 2, figsize=(9.6, 5.0))
for name in SERIES:
    data = np.array([r[:3] for r in results[name]], dtype=float)
    axes[0].loglog(data[:, 0], data[:, 1], "o-", color=COLOUR[name], label=name, ms=4)
    axes[1].loglog(data[:, 0], data[:, 2], "o-", color=COLOUR[name], label=name, ms=4)
all_n = np.array(SIZES, dtype=float)
axes[0].loglog(all_n, all_n * (all_n - 1) / 2, ":", color="0.5", label="n(n-1)/2")
axes[0].set_ylabel("AABB overlap tests per call (count)")
axes[1].set_ylabel("time per call (ms)")
for ax in axes:
    ax.set_xlabel("number of circles N (count)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=3)
axes[0].set_title("pair tests")
axes[1].set_title("time (best of several calls)")
fig.tight_layout()
save_figure(fig, OUT / "scaling.png", dpi=100)

# %% [markdown]
# ## What each structure looks like
#
# The same random world of circles, four ways: the grid's occupied cells, the quadtree's
# nodes, the kd-tree's split lines (shapes crossing a line stay at that node) and the sweep
# intervals of sort and sweep, band by band (the bands in two shades; in each band sorted by
# their lower end; a box is tested against the boxes below it in its band until one starts
# beyond its upper end, and a box that crosses two bands is in both).

# %%
centres, radii, side = random_circles(PICTURE_N, np.random.default_rng(SEED + 1))
boxes = circle_aabbs(centres, radii)
counts = {name: find_pairs(name, boxes)[1] for name in STRATEGIES}
print(f"{PICTURE_N} circles, {PICTURE_N * (PICTURE_N - 1) // 2} pairs; tests per strategy:")
print_table(["strategy", "pair tests"], [[name, counts[name]] for name in STRATEGIES])

fig, axes = plt.subplots(2, 2, figsize=(9.0, 9.0))
ax = axes[0, 0]
info = describe("grid", boxes)
h = info["cell_size"]
for cx, cy in info["cells"]:
    ax.add_patch(
        Rectangle(
            (cx * h, cy * h), h, h, fc=to_rgba(COLOUR["grid"], 0.15), ec=COLOUR["grid"], lw=0.5
        )
    )
ax.set_title(f"grid: {len(info['cells'])} cells of {h:.2f} m, {counts['grid']} tests")

ax = axes[0, 1]
info = describe("quadtree", boxes)
for (x0, y0, x1, y1), leaf in zip(info["rects"], info["leaf"], strict=True):
    ax.add_patch(
        Rectangle(
            (x0, y0),
            x1 - x0,
            y1 - y0,
            fill=False,
            lw=0.6 if leaf else 1.0,
            edgecolor=COLOUR["quadtree"],
        )
    )
ax.set_title(f"quadtree: {int(info['leaf'].sum())} leaves, {counts['quadtree']} tests")

ax = axes[1, 0]
info = describe("kdtree", boxes)
for reg, a, cut, d in zip(info["region"], info["axis"], info["split"], info["depth"], strict=True):
    if a == 0:
        ax.plot([cut, cut], [reg[1], reg[3]], color=COLOUR["kdtree"], lw=2.0 / (1 + 0.4 * d))
    elif a == 1:
        ax.plot([reg[0], reg[2]], [cut, cut], color=COLOUR["kdtree"], lw=2.0 / (1 + 0.4 * d))
kept_inner = int(info["kept"][info["axis"] >= 0].sum())
ax.set_title(f"kd-tree: {kept_inner} circles on split lines, {counts['kdtree']} tests")
for ax in (axes[0, 0], axes[0, 1], axes[1, 0]):
    draw_circles(ax, centres, radii)
    ax.set(xlim=(-0.6, side + 0.6), ylim=(-0.6, side + 0.6), xlabel="x (m)", ylabel="y (m)")

ax = axes[1, 1]
info = describe("sap", boxes)
bands = max(1, len(info["edges"]) - 1)
entries = [  # the sweep's order: band by band, a box in every band it crosses, sorted by lo
    (b, i)
    for b in range(bands)
    for i in info["order"]
    if info["band"][i, 0] <= b <= info["band"][i, 1]
]
lo_hi = np.array([info["intervals"][i] for _, i in entries])
shade = [COLOUR["sap"] if b % 2 == 0 else COLOUR["sap, one band"] for b, _ in entries]
ax.hlines(np.arange(len(entries)), lo_hi[:, 0], lo_hi[:, 1], colors=shade, lw=1.5)
ax.set_xlabel(f"position along {info['label']} (m)")
ax.set_ylabel("place in the sweep, band by band (index)")
ax.set_title(f"sort and sweep along {info['label']}, {bands} bands: {counts['sap']} tests")
fig.tight_layout()
save_figure(fig, OUT / "structures.png", dpi=90)
print("figures written to", OUT.name)

# %% [markdown]
# ## Bodies on a grid: turn the sweep, or cut it into bands
#
# Lessons often set bodies out on a grid: a stack, a pyramid, a field of balls. Then a whole
# row shares its lower end along y (and a column along x), and sort and sweep along y in one
# band tests every ball against the rest of its row, however far apart they are along x.
# One cure is to turn the sweep: along a direction turned by a small angle $\theta$ the rows
# fan out: two balls a spacing $s$ apart in a row are $s \sin\theta$ apart along it, and a
# ball's interval grows from $2r$ to $2r(\cos\theta + \sin\theta)$ only. In one band
# (`bands=False`) the engine counts the candidates along x, y and both turned by 0.15 rad (two
# sorts each) and sweeps along the fewest; a slanted test compares both axes, so it weighs a
# third more in that choice.
#
# Bands cure it better. Swept along x, the bands are horizontal and each row of the grid lies
# in a band of its own, where its balls are 10 m apart along x: no interval overlaps another
# and nothing is tested at all (swept along y, the same holds for the columns). So the
# engine's step, which sweeps in bands, chooses between x and y only (counting their
# candidates band by band, once every 30 steps) and never turns. The figure shows 6 x 6 balls
# 2 m apart in one band; the table, 1,000 balls 10 m apart (the free-body benchmark's world)
# and, for contrast, the random world above.

# %%
from sandbox.broadphase.sap import DIRECTIONS, NAMES  # noqa: E402


def lattice_boxes(side: int, spacing: float, radius: float = 0.2) -> np.ndarray:
    """AABBs of side x side circles of ``radius`` (m) on a square grid ``spacing`` m apart."""
    ij = np.array([(i % side, i // side) for i in range(side * side)], dtype=float)
    return circle_aabbs(spacing * ij, np.full(side * side, radius))


worlds = {"1000 balls on a 10 m grid": lattice_boxes(32, 10.0), "random": boxes}
rows = [  # pair tests of each sweep, one world a column
    [
        f"one band, along {NAMES[d]}",
        *(find_pairs("sap", w, axis=d, bands=False)[1] for w in worlds.values()),
    ]
    for d in range(len(DIRECTIONS))
]
rows.append(
    [
        "chosen in one band",
        *(NAMES[describe("sap", w, bands=False)["axis"]] for w in worlds.values()),
    ]
)
rows.append(
    [
        "in bands (the step)",
        *(
            f"{find_pairs('sap', w)[1]} along {NAMES[describe('sap', w)['axis']]}"
            for w in worlds.values()
        ),
    ]
)
print_table(["sweep: pair tests", *worlds], rows)

small = lattice_boxes(6, 2.0)
fig, axes = plt.subplots(1, 2, figsize=(9.0, 4.2))
for ax, d in zip(axes, (1, 3), strict=True):
    info = describe("sap", small, axis=d, bands=False)
    lo_hi = info["intervals"][info["order"]]
    ranks = np.arange(len(small))
    ax.hlines(ranks, lo_hi[:, 0], lo_hi[:, 1], color=COLOUR["sap"], lw=1.5)
    ax.set_xlabel(f"position along {info['label']} (m)")
    ax.set_ylabel("rank in the sorted order (index)")
    tests = find_pairs("sap", small, axis=d, bands=False)[1]
    ax.set_title(f"along {info['label']}: {tests} tests", fontsize=10)
fig.suptitle("36 balls on a 2 m grid, swept in one band", fontsize=11)
fig.tight_layout()
save_figure(fig, OUT / "lattice_sweep.png", dpi=90)

# %% [markdown]
# ## In a world that steps: keep the pairs while the boxes hold
#
# From one step to the next the bodies barely move, so the pairs barely change. The engine's
# sort and sweep does not sweep every step: it sweeps boxes grown by a spare margin (2 cm)
# and keeps the pairs it found while every shape's box stays inside the box it was swept with
# (Box2D's "fat" boxes). Any two shapes whose boxes overlap now had overlapping swept boxes,
# so the kept pairs hold every pair in reach; the narrowphase leaves out the extra ones. A
# falling body leaves a 2 cm margin within a step or two, so each swept box is also
# stretched along its body's velocity by `settings.box_prediction` steps of travel (2 by
# default, Box2D 2.3's `aabbMultiplier`): the longer the stretch, the rarer the sweeps, and
# the more pairs out of reach the narrowphase is handed. Below, a hundred discs rain into a
# box (the bundled scene `rain`), 180 steps at each value, beside brute force, which finds
# the exact pairs every step.

# %%
import sandbox  # noqa: E402
from sandbox.lessonkit import scene_path  # noqa: E402

PREDICTIONS = (0.0, 2.0, 8.0)  # settings.box_prediction (steps of travel)
RAIN_STEPS = 180
RAIN = scene_path("rain")  # the bundled example scene (`sandbox simulate rain`)


def rain_world(broadphase: str, prediction: float = 2.0) -> sandbox.World:
    """The bundled rain (100 discs of radius 0.2 m falling 10 m into an open box) with the
    ``broadphase`` and ``settings.box_prediction`` given."""
    w = sandbox.load_scene(RAIN)
    w.settings.broadphase = broadphase
    w.settings.box_prediction = prediction
    return w


fresh = rain_world("brute")
runs = {p: rain_world("sap", p) for p in PREDICTIONS}
swept_steps = {p: [] for p in PREDICTIONS}
handed = {p: [] for p in PREDICTIONS}
same_contacts = dict.fromkeys(PREDICTIONS, True)
for _ in range(RAIN_STEPS):
    fresh.step()
    for p, w in runs.items():
        w.step()
        swept_steps[p].append(w.stats["pair_tests"] > 0)  # a sweep tests pairs; kept: none
        handed[p].append(w.stats["pairs"])
        same_contacts[p] &= w.stats["contacts"] == fresh.stats["contacts"]
rain_rows = [
    [
        p,
        int(sum(swept_steps[p])),
        float(np.mean(handed[p])),
        same_contacts[p] and bool(np.array_equal(w.com, fresh.com)),
    ]
    for p, w in runs.items()
]
print_table(
    ["box_prediction (steps)", f"steps that swept (of {RAIN_STEPS})", "pairs a step", "as brute"],
    rain_rows,
    digits=1,
)

t_rain = np.arange(1, RAIN_STEPS + 1) * fresh.dt
fig, axes = plt.subplots(1, 2, figsize=(9.6, 4.2))
styles = {0.0: ("0.45", 1.2), 2.0: (COLOUR["sap"], 2.2), 8.0: ("tab:red", 3.4)}
for p in sorted(PREDICTIONS, reverse=True):  # the widest first: where they agree, all show
    colour, width = styles[p]
    label = f"box_prediction {p:g}"
    axes[0].plot(t_rain, np.cumsum(swept_steps[p]), color=colour, lw=width, label=label)
    axes[1].plot(t_rain, handed[p], color=colour, lw=width, label=label)
axes[0].set_ylabel("sweeps so far (count)")
axes[0].set_title("sweeps: the stretch keeps the pairs longer")
axes[1].set_ylabel("pairs handed to the narrowphase (count)")
axes[1].set_title("the price: more pairs out of reach")
for ax, corner in zip(axes, ("upper left", "lower right"), strict=True):
    ax.set_xlabel("time (s)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8, loc=corner)
fig.suptitle(f"100 discs raining into a box, sweep and prune, {RAIN_STEPS} steps", fontsize=11)
fig.tight_layout()
save_figure(fig, OUT / "kept_pairs.png", dpi=90)

# %% [markdown]
# Every run finds the same contacts as brute force and ends in the same state to the bit
# (the last column): the stretch changes only how often the boxes are swept. With the spare
# margin alone the falling discs force a sweep every step while they fall, and most steps
# after they land, as the pile settles; two steps of stretch sweep less than half as often,
# eight fewer still, while handing the narrowphase more pairs it throws away (most as the
# discs land, when the stretched boxes of fast discs reach into the pile). In the engine's
# benchmarks (`benchmarks/ab.py`) two steps made 1,000 free bodies' steps a quarter cheaper
# and left rain and pyramids as they were: there the pairs saved by sweeping less are about
# paid for by the narrowphase's extra ones.

# %% [markdown]
# ## Exercises
#
# Predict first, then run the cell under the question, then open the answer.
#
# **1.** In the slides' grid, shrink body 5 to a radius of 0.15 m (it now stays inside one
# cell). Which pairs does the grid test?

# %%
radii_e1 = slide_radii.copy()
radii_e1[4] = 0.15
_, tests_e1, tested_e1 = find_pairs_traced(
    "grid", circle_aabbs(slide_centres, radii_e1), record=True, cell_size=1.0
)
print(tests_e1, "tests:", sorted(tuple(int(v) + 1 for v in p) for p in tested_e1))

# %% [markdown]
# <details><summary>Answer</summary>
#
# Body 5's box now spans $y \in [0.65, 0.95]$, inside the cell it shares with bodies 3 and 4;
# body 6 is left alone in the cell above. The pairs are (1,2), (3,4), (3,5), (4,5): 4 tests,
# one fewer than the slide's 5. Pairs are tested per shared cell, so a body that spans cells
# costs tests in each of them.
#
# </details>
#
# **2.** Keep $N = 1000$ circles but double the coverage (`COVER` 0.3 to 0.6, so the box
# shrinks). How do the grid's and sort and sweep's test counts change?


# %%
def tests_for(n: int, cover: float, aspect: float = 1.0) -> dict:
    """Pair tests of every strategy for n circles covering ``cover`` of a w x h box, w = aspect h."""
    rng_e = np.random.default_rng(SEED)
    r = rng_e.uniform(*RADII, n)
    h = math.sqrt(np.sum(math.pi * r * r) / cover / aspect)
    boxes_e = circle_aabbs(rng_e.uniform(0.0, 1.0, (n, 2)) * (aspect * h, h), r)
    return {
        name: find_pairs(strategy, boxes_e, **options)[1]
        for name, (strategy, options) in SERIES.items()
        if name != "brute"
    }


for cover in (0.3, 0.6):
    print(f"cover {cover}: {tests_for(1000, cover)}")

# %% [markdown]
# <details><summary>Answer</summary>
#
# The grid tests each circle against its neighbours, and twice the density means about twice as
# many neighbours: 2469 to 5173 tests (x 2.1). Sort and sweep in bands does the same, for the
# same reason (a band is a neighbourhood): 1221 to 2442 (x 2.0). In one band it tests each box
# against the boxes of a strip one box wide across the world; the strip holds density x side
# boxes, and the side shrinks as $1/\sqrt{\text{density}}$, so the count grows only by
# $\sqrt{2}$: 17753 to 25176 (x 1.42), still ten times the banded count.
#
# </details>
#
# **3.** Same 1000 circles and coverage, but in a world ten times wider than high. Which
# strategy gains, and by how much?

# %%
for aspect in (1.0, 10.0):
    print(f"w / h = {aspect:g}: {tests_for(1000, COVER, aspect)}")

# %% [markdown]
# <details><summary>Answer</summary>
#
# Sort and sweep in one band gains: it sweeps along the direction with the fewest candidates
# (x here), so the strip of boxes whose x intervals overlap a given box now spans only the
# short height: $h$ shrinks by $\sqrt{10}$ and so does the count, 17753 to 5744 tests
# (x 0.32). In bands it looks at a neighbourhood, like the grid and the trees, whose size does
# not depend on the world's shape: 1221 to 1238, against 2469 to 2378 and 1208 to 1170.
#
# </details>
