"""Tunnelling of a fast bullet through a thin wall, and continuous collision (ccd) stopping it
(slides, "Retroactive Collision Detection": the tunnelling problem; "Conservative
Advancement"). The numbers lesson 06 shows.

Geometry of ``scenes/bullet.json``: wall h = 0.1 m thick centred on x = 5, bullet r = 0.05 m,
dt = 1/60 s. Without ccd the bullet is only seen at x0 + k v dt; its centre overlaps the wall
on a band h + 2r wide, so some start positions miss it once v dt > h + 2r.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

import sandbox
from sandbox import Body, Box, Circle, World

SCENE = json.loads((Path(__file__).resolve().parent.parent / "scenes" / "bullet.json").read_text())
WALL_X, H, R, DT = 5.0, 0.1, 0.05, 1.0 / 60.0
FACE = WALL_X - H / 2  # the wall's front face
SLOP = 0.005  # m of overlap the solver leaves in a resting contact (settings.slop)


def test_scene_geometry_is_what_the_tests_assume():
    wall, bullet = SCENE["bodies"]
    assert wall["position"] == [WALL_X, 0] and wall["shapes"][0]["width"] == H
    assert bullet["shapes"][0]["radius"] == R and bullet["velocity"] == [200, 0]


SOLVERS = ["iterative", "soft"]  # the soft step moves the bodies once per substep


def shot(
    speed: float, degrees: float, ccd: bool, restitution: float = 0.0, solver: str = "iterative"
) -> World:
    """The bullet scene with a 400 m tall wall (the bullet cannot slide off its end), the
    bullet at ``speed`` m/s, ``degrees`` from +x, starting half a step's travel (in x) before
    the wall's centre line: the two samples around the wall are v_x dt / 2 from its middle,
    the luckiest case for tunnelling, so every shot here tunnels without ccd."""
    scene = json.loads(json.dumps(SCENE))
    wall, bullet = scene["bodies"]
    wall["shapes"][0]["height"] = 400.0
    wall["shapes"][0]["restitution"] = 1.0
    bullet["shapes"][0]["restitution"] = restitution
    vx, vy = speed * math.cos(math.radians(degrees)), speed * math.sin(math.radians(degrees))
    bullet["position"] = [WALL_X - 0.5 * vx * DT, 0.0]
    bullet["velocity"] = [vx, vy]
    bullet["ccd"] = ccd
    scene["settings"] = {"solver": solver}
    return sandbox.load_scene(scene)


@pytest.mark.parametrize("solver", SOLVERS)
def test_the_scene_bullet_tunnels_without_ccd_and_stops_at_the_wall_with_it(solver):
    # 200 m/s * 1/60 s = 3.33 m per step: samples at x = 3.33 and 6.67, none in the wall.
    # Under the soft step the bullet is stopped in its first substep (0.83 m each) that would
    # reach the wall, and stays there through the later ones, which see no contact yet
    settings = {"settings": {"solver": solver}}
    free = sandbox.load_scene(
        {**SCENE, **settings, "bodies": [SCENE["bodies"][0], {**SCENE["bodies"][1], "ccd": False}]}
    )
    caught = sandbox.load_scene({**SCENE, **settings})
    for _ in range(10):
        free.step()
        assert free.stats["contacts"] == 0  # never detected
        caught.step()
        assert caught.body("bullet").position[0] + R <= FACE + SLOP
    assert free.body("bullet").position[0] == pytest.approx(10 * 200 * DT, abs=1e-9)
    # ccd: cut 0.005 m short of the wall (a quarter of the contact margin), then the contact
    # (restitution 0) stops it against the face: x = 5 - 0.05 - 0.05 = 4.9 (1e-9)
    assert caught.body("bullet").position[0] == pytest.approx(FACE - R, abs=1e-9)
    assert caught.body("bullet").velocity[0] == pytest.approx(0.0, abs=1e-9)


@pytest.mark.parametrize("restitution", [0.0, 1.0])
@pytest.mark.parametrize("speed", [50.0, 100.0, 200.0, 300.0, 400.0])
def test_ccd_never_lets_the_bullet_through_at_any_speed_or_angle(speed, restitution):
    check_shots(speed, restitution, "iterative", (-30.0, -15.0, 0.0, 15.0, 30.0))


@pytest.mark.parametrize("restitution", [0.0, 1.0])
@pytest.mark.parametrize("speed", [50.0, 100.0, 200.0, 300.0, 400.0])
def test_ccd_stops_a_straight_bullet_under_the_soft_step(speed, restitution):
    # the soft step moves the bodies once per substep and finds contacts once per step: a
    # bullet stopped at its impact in one substep stays there through the later ones
    # (sandbox.toi.hold_stopped); before, it went on through the wall in the next substep
    check_shots(speed, restitution, "soft", (0.0,))


def test_ccd_stops_an_oblique_bullet_under_the_soft_step():
    # a bullet at 50 m/s, 30 degrees off the normal, slides down the wall spinning at 330 to
    # 400 rad/s; the soft step measures a circle's separation at its centre
    # (sandbox.solvers.soft.anchor): measured at a material point, the point swung off the
    # contact by r (1 - cos w h) a substep, the contact read as open and the bullet sank 3 cm
    # into the wall before it was pushed out
    check_shots(50.0, 0.0, "soft", (-30.0, -15.0, 15.0, 30.0))


def test_an_oblique_bullet_under_the_soft_step_never_gets_through():
    for degrees in (-30.0, -15.0, 15.0, 30.0):
        caught = shot(50.0, degrees, ccd=True, solver="soft")
        for _ in range(30):
            caught.step()
            assert caught.body("bullet").position[0] < WALL_X, degrees  # short of the middle


def check_shots(speed: float, restitution: float, solver: str, angles) -> None:
    """Shots at ``speed`` from each of ``angles`` (degrees): without ccd each tunnels; with it
    the bullet's front stays within the slop of the wall's face at every step, and it ends
    stopped (e = 0) or bounced straight back (e = 1)."""
    for degrees in angles:
        free = shot(speed, degrees, ccd=False, restitution=restitution, solver=solver)
        caught = shot(speed, degrees, ccd=True, restitution=restitution, solver=solver)
        for _ in range(30):
            free.step()
            caught.step()
            # ccd: the bullet's front stays in front of the face at every step, up to the
            # solver's allowed overlap (SLOP); without ccd it ends metres behind the wall
            assert caught.body("bullet").position[0] + R <= FACE + SLOP, (speed, degrees)
        assert free.body("bullet").position[0] - R > WALL_X + H / 2, (speed, degrees)
        vx = caught.body("bullet").velocity[0]
        if restitution == 1.0:  # e = 1 x 1: bounced straight back at the same normal speed
            # (the normal speed after the bounce, 1e-6 relative)
            assert vx == pytest.approx(-speed * math.cos(math.radians(degrees)), rel=1e-6)
        else:  # e = 0: stopped against the wall
            assert vx == pytest.approx(0.0, abs=1e-6)


PHASES = 32  # start positions per speed, spread over one step's travel
SWEEP_STEP = 0.01  # m: the speed grid is v dt = (k + 1/2) SWEEP_STEP
ROW = 0.15  # m between bullets: > 2 r + contact margin, so they never touch each other


def sweep(dt: float, margin: float | None = None, ccd: bool = False, solver: str = "iterative"):
    """PHASES bullets per swept speed, all in one world (one per row) against one tall wall.
    Returns the speeds (m/s), and per speed and start: wall ever in the step's contacts,
    bullet behind the wall at the end."""
    vdt = (np.arange(5, 35) + 0.5) * SWEEP_STEP
    settings = {"solver": solver, **({} if margin is None else {"contact_margin": margin})}
    w = World(gravity=(0.0, 0.0), dt=dt, **settings)
    n = len(vdt) * PHASES
    wall = w.add_body(Body("wall", type="static", position=(WALL_X, 0.0)))
    wall.add_shape(Box(H, ROW * (n + 2)))
    shots = []
    for step in vdt:
        for j in range(PHASES):
            x0 = FACE - R - 1e-6 - (1 + j / PHASES) * step  # first sample short of touching
            y = ROW * (len(shots) + 1.5 - 0.5 * (n + 2))
            b = w.add_body(Body(position=(x0, y), velocity=(step / dt, 0.0), ccd=ccd))
            b.add_shape(Circle(R))
            shots.append(b.index)
    seen = np.zeros(len(w.bodies), dtype=bool)
    for _ in range(math.ceil(0.25 / vdt[0]) + 3):  # the slowest bullet ends past the wall
        w.step()
        m = w.manifolds
        if m is not None and len(m):
            hit = (m.a == wall.index) | (m.b == wall.index)
            seen[m.a[hit]] = seen[m.b[hit]] = True
    behind = w.com[shots, 0] > WALL_X
    return vdt / dt, seen[shots].reshape(-1, PHASES), behind.reshape(-1, PHASES)


def first_failing(speeds: np.ndarray, failed: np.ndarray) -> float:
    rows = failed.any(axis=1)
    assert rows.any() and not rows[0]  # the sweep brackets the boundary
    return float(speeds[np.argmax(rows)])


@pytest.mark.parametrize("dt", [1.0 / 30.0, 1.0 / 60.0, 1.0 / 120.0])
def test_tunnelling_threshold_is_thickness_plus_diameter_over_dt(dt):
    # pure retroactive detection (no speculative margin): the wall is missed by some start
    # position from v dt > h + 2r on; measured within one sweep step (SWEEP_STEP / dt)
    speeds, seen, _ = sweep(dt, margin=0.0)
    v_missed = first_failing(speeds, ~seen)
    assert abs(v_missed - (H + 2 * R) / dt) <= SWEEP_STEP / dt
    # and the fraction of missed starts follows 1 - (h + 2r) / (v dt), within one phase
    # step (1/PHASES) plus its rounding
    theory = np.clip(1.0 - (H + 2 * R) / (speeds * dt), 0.0, None)
    assert np.max(np.abs((~seen).mean(axis=1) - theory)) <= 1.5 / PHASES


def test_with_default_settings_the_bullet_is_pushed_through_from_half_the_wall_on():
    # caught on the back half of the wall, the bullet is pushed out behind it; the speculative
    # margin m catches it m earlier: it ends behind the wall once v dt > h/2 + r + m
    # (measured within one sweep step)
    world = World()
    m = world.settings.contact_margin
    speeds, _, behind = sweep(DT)
    v_behind = first_failing(speeds, behind)
    assert abs(v_behind - (H / 2 + R + m) / DT) <= SWEEP_STEP / DT


@pytest.mark.parametrize("solver", SOLVERS)
def test_no_swept_bullet_gets_through_with_ccd(solver):
    _, _, behind = sweep(DT, ccd=True, solver=solver)
    assert not behind.any()
