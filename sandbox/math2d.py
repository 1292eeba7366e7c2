"""The ground floor: 2D vector maths and the impulse formulas every stage shares.

Nothing here imports another module of the engine; every other module may import this one.
Vectors are passed as plain floats (x, y) and a body's velocity as the triple ``(vx, vy, w)``,
so the compiled code keeps them in registers. Slide names in the comments are from the course
notes ("Collision Effects", "Collision Equation", "Torque").
"""

from __future__ import annotations

import math

from sandbox.jit import njit


@njit
def cross(ax: float, ay: float, bx: float, by: float) -> float:
    """z-component of the 2D cross product a x b (slides, "Torque": tau = r x f)."""
    return ax * by - ay * bx


@njit
def rotate(c: float, s: float, x: float, y: float) -> tuple[float, float]:
    """R q for the rotation R = [[c, -s], [s, c]] (body frame to world frame)."""
    return c * x - s * y, s * x + c * y


@njit
def unrotate(c: float, s: float, x: float, y: float) -> tuple[float, float]:
    """R^T q (world frame to body frame)."""
    return c * x + s * y, -s * x + c * y


@njit
def point_velocity(v: tuple, rx: float, ry: float) -> tuple[float, float]:
    """Velocity of the material point at r from the centre of mass: v + w x r (m/s).

    slides, "Collision Effects": v_contact = v_body + r x w. In 2D w x r = (-w r_y, w r_x); the
    slide's r x w is the same vector with the opposite sign, so we write w x r.
    """
    return v[0] - v[2] * ry, v[1] + v[2] * rx


@njit
def relative_velocity(
    va: tuple, rax: float, ray: float, vb: tuple, rbx: float, rby: float
) -> tuple[float, float]:
    """v_r = (v_b + w_b x r_b) - (v_a + w_a x r_a): b's contact point seen from a's (m/s)."""
    ax, ay = point_velocity(va, rax, ray)
    bx, by = point_velocity(vb, rbx, rby)
    return bx - ax, by - ay


@njit
def effective_mass(
    im_a: float, ii_a: float, im_b: float, ii_b: float, rn_a: float, rn_b: float
) -> float:
    """k = 1/m_a + 1/m_b + (r_a x n)^2 / I_a + (r_b x n)^2 / I_b, given rn = r x n.

    slides, "Collision Equation", step 1: the denominator of j. In 2D the slide's
    ((I^-1 (r x n)) x r) . n is (r x n)^2 / I.
    """
    return im_a + im_b + ii_a * rn_a * rn_a + ii_b * rn_b * rn_b


@njit
def inverse_or_zero(k: float) -> float:
    """1 / k, or 0 when nothing can move (k = 0)."""
    return 1.0 / k if k > 0.0 else 0.0


@njit
def receive(v: tuple, im: float, ii: float, rx: float, ry: float, px: float, py: float) -> tuple:
    """A body's velocities after the impulse P at r: v + P / m, w + (r x P) / I.

    slides, "Collision Equation", steps 3a and 3b. Body b receives +P and body a receives -P
    (the slide's step 2 gives +j n to body 1; with n pointing from a to b that would push a
    *into* b).
    """
    return v[0] + im * px, v[1] + im * py, v[2] + ii * cross(rx, ry, px, py)


@njit
def exchange(
    va: tuple, vb: tuple, mass: tuple, ra: tuple, rb: tuple, px: float, py: float
) -> tuple[tuple, tuple]:
    """-P on body a at r_a and +P on body b at r_b; ``mass`` = (1/m_a, 1/I_a, 1/m_b, 1/I_b)."""
    va = receive(va, mass[0], mass[1], ra[0], ra[1], -px, -py)
    vb = receive(vb, mass[2], mass[3], rb[0], rb[1], px, py)
    return va, vb


@njit
def speed_along(va: tuple, vb: tuple, dx: float, dy: float, rd_a: float, rd_b: float) -> float:
    """v_r . d, the relative velocity of two material points along a direction d, given
    rd = r x d for each: (v_b - v_a) . d + w_b (r_b x d) - w_a (r_a x d) (m/s), since
    (w x r) . d = w (r x d) (slides, "Collision Effects", with :func:`relative_velocity`)."""
    return (vb[0] - va[0]) * dx + (vb[1] - va[1]) * dy + vb[2] * rd_b - va[2] * rd_a


@njit
def push_along(
    va: tuple, vb: tuple, mass: tuple, dx: float, dy: float, rd_a: float, rd_b: float, j: float
) -> tuple[tuple, tuple]:
    """:func:`exchange` for P = j d, given rd = r x d for each body: r x P = j (r x d)."""
    im_a, ii_a, im_b, ii_b = mass
    va = (va[0] - im_a * j * dx, va[1] - im_a * j * dy, va[2] - ii_a * j * rd_a)
    vb = (vb[0] + im_b * j * dx, vb[1] + im_b * j * dy, vb[2] + ii_b * j * rd_b)
    return va, vb


@njit(inline="always")  # a record: nothing to count references to
def velocity(body) -> tuple[float, float, float]:
    """A BODY record's (vx, vy, w)."""
    v = body["vel"]
    return v[0], v[1], body["omega"]


@njit(inline="always")
def put_velocity(body, v: tuple) -> None:
    """Write (vx, vy, w) into a BODY record."""
    vel = body["vel"]
    vel[0], vel[1] = v[0], v[1]
    body["omega"] = v[2]


@njit
def velocity_of(bodies, i: int) -> tuple[float, float, float]:
    """Body i's (vx, vy, w)."""
    return velocity(bodies[i])


@njit
def set_velocity(bodies, i: int, v: tuple) -> None:
    """Write (vx, vy, w) back to body i."""
    put_velocity(bodies[i], v)


@njit
def take_velocities(bodies, velocities) -> None:
    """Each body's (vx, vy, w) into its row of ``velocities`` (the sweeps read them there,
    three numbers side by side, rather than from the body's whole record)."""
    for i in range(len(bodies)):
        velocities[i, 0], velocities[i, 1], velocities[i, 2] = velocity_of(bodies, i)


@njit
def put_velocities(velocities, bodies) -> None:
    """The rows of ``velocities`` back into the bodies."""
    for i in range(len(bodies)):
        set_velocity(bodies, i, (velocities[i, 0], velocities[i, 1], velocities[i, 2]))


@njit(inline="always")  # compiled into its callers: the wide position passes vectorise it
def turn_small(c: float, s: float, d: float) -> tuple[float, float]:
    """(c, s) turned by about d radians, for the small turns within the position passes: by
    atan(d), ((c, s) + d (-s, c)) / sqrt(1 + d^2), which is d to within d^3 / 3, without a
    cosine and a sine. The passes add up the exact d of every turn, and the orientation is
    turned by that total afterwards, so the step's result keeps no error."""
    scale = 1.0 / math.sqrt(1.0 + d * d)
    return (c - s * d) * scale, (s + c * d) * scale


@njit(inline="always")
def pose_of(body) -> tuple[float, float, float, float, float]:
    """A body's pose for the position passes: (x, y) of its centre of mass (m), its (cos, sin)
    and the turn the passes gave it so far (rad)."""
    com, cs = body["com"], body["cs"]
    return com[0], com[1], cs[0], cs[1], body["turn"]


@njit(inline="always")
def set_pose(body, pose: tuple) -> None:
    """Write a pose (:func:`pose_of`) back to the body."""
    com, cs = body["com"], body["cs"]
    com[0], com[1], cs[0], cs[1], body["turn"] = pose


@njit(inline="always")
def nudged(pose: tuple, dx: float, dy: float, d: float) -> tuple:
    """A pose (:func:`pose_of`) moved by (dx, dy) (m) and turned by d (rad, when not 0)."""
    x, y, c, s, turn = pose
    if d != 0.0:
        c, s = turn_small(c, s, d)
        turn += d
    return x + dx, y + dy, c, s, turn


@njit
def nudge(body, dx: float, dy: float, d: float) -> None:
    """Move a body by (dx, dy) and turn it by d radians (a position-pass correction)."""
    set_pose(body, nudged(pose_of(body), dx, dy, d))
