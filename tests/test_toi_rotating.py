"""pge.toi.rotating against closed forms and an independent brute-force reference.

The reference is written here from scratch in NumPy, sharing no code with the
kernels: the shapes are placed at many times at once, their exact signed gap is
the separating-axis value when they overlap and the smallest vertex-to-segment
distance when they do not. The first contact is found by branch and bound on a
fine grid: an interval ``[a, b]`` is cleared when ``(g(a) + g(b)) / 2 > L (b -
a) / 2`` for the crude Lipschitz constant ``L = max |dv(t)| + |omega_a| R_a +
|omega_b| R_b``; the others are halved until they are 1e-10 s wide, and the
first sign change is bisected to the last bit. Touches that never cross
(grazes) are ambiguous by nature; the contract allows either answer for them
when the gap stays within 1e-9.
"""

from __future__ import annotations

import math
import random

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from strategies import centred, convex_polygons

from pge.toi import circle_polygon, outline_rows, polygon_polygon
from pge.toi.rotating import (
    CHECKPOINT,
    rotating_circle_polygon,
    rotating_circle_polygon_contact,
    rotating_polygon_polygon,
    rotating_polygon_polygon_contact,
    rotating_search,
)

INF = math.inf
TAU = 2.0 * math.pi
HORIZON = 0.5
MATCH = 1e-9  # agreement with the reference (s), and the graze allowance (m)
ROUNDING = 1e-13  # the reference's own rounding of a contact time (s)


# ------------------------------------------------------------------ reference


def _place(local, theta, omega, t, x, y, alpha=0.0):
    """World vertices ``(T, n, 2)`` of a polygon at the times ``t``, turned by
    ``theta + omega t + alpha t^2 / 2``."""
    angle = theta + omega * t + 0.5 * alpha * t * t
    c = np.cos(angle)[:, None]
    s = np.sin(angle)[:, None]
    lx = local[:, 0][None, :]
    ly = local[:, 1][None, :]
    return np.stack([c * lx - s * ly + x[:, None], s * lx + c * ly + y[:, None]], axis=-1)


def _outward_normals(P):
    edge = np.roll(P, -1, axis=1) - P
    length = np.hypot(edge[..., 0], edge[..., 1])
    return np.stack([edge[..., 1] / length, -edge[..., 0] / length], axis=-1)


def _segment_distance(Q, P):
    """Smallest distance ``(T, m)`` of the points ``Q`` to the edges of the polygons ``P``."""
    start = P[:, None, :, :]
    edge = (np.roll(P, -1, axis=1) - P)[:, None, :, :]
    w = Q[:, :, None, :] - start
    u = np.clip((w * edge).sum(-1) / (edge * edge).sum(-1), 0.0, 1.0)
    off = w - u[..., None] * edge
    return np.hypot(off[..., 0], off[..., 1]).min(axis=2)


def _axis_separation(P, Q):
    """Largest separation of ``Q`` from ``P`` along ``P``'s edge normals, ``(T,)``."""
    normals = _outward_normals(P)
    s = ((Q[:, None, :, :] - P[:, :, None, :]) * normals[:, :, None, :]).sum(-1)
    return s.min(axis=2).max(axis=1)


def _offset(d, dv, da, t):
    return d[0] + dv[0] * t + 0.5 * da[0] * t * t, d[1] + dv[1] * t + 0.5 * da[1] * t * t


def polygon_gap(local_a, theta_a, omega_a, local_b, theta_b, omega_b, d, dv, da, alpha_a=0.0, alpha_b=0.0):
    """Signed gap of two polygons as a function of an array of times (b's centroid at 0)."""

    def gap(t):
        t = np.atleast_1d(np.asarray(t, float))
        x, y = _offset(d, dv, da, t)
        A = _place(local_a, theta_a, omega_a, t, x, y, alpha_a)
        B = _place(local_b, theta_b, omega_b, t, 0.0 * t, 0.0 * t, alpha_b)
        separation = np.maximum(_axis_separation(A, B), _axis_separation(B, A))
        distance = np.minimum(_segment_distance(A, B).min(axis=1), _segment_distance(B, A).min(axis=1))
        return np.where(separation <= 0.0, separation, distance)

    return gap


def circle_gap(radius, local_b, theta_b, omega_b, d, dv, da, alpha_b=0.0):
    """Signed gap of a circle (centre at ``d(t)``) and a polygon (centroid at 0)."""

    def gap(t):
        t = np.atleast_1d(np.asarray(t, float))
        x, y = _offset(d, dv, da, t)
        C = np.stack([x, y], axis=-1)[:, None, :]
        B = _place(local_b, theta_b, omega_b, t, 0.0 * t, 0.0 * t, alpha_b)
        separation = ((C - B) * _outward_normals(B)).sum(-1).max(axis=1)
        return np.where(separation <= 0.0, separation, _segment_distance(C, B)[:, 0]) - radius

    return gap


def reference_contact(gap, lipschitz, horizon, grid=4096, finest=1e-10):
    """``(t_low, t_high)`` bracketing the first contact to the last bit, or ``(inf, inf)``."""
    t = np.linspace(0.0, horizon, grid + 1)
    g = gap(t)
    assert g[0] > 0.0, "reference cases start apart"
    a, b, ga, gb = t[:-1], t[1:], g[:-1], g[1:]
    earliest = INF
    while True:
        closed = gb <= 0.0
        if closed.any():
            earliest = min(earliest, b[closed].min())
        keep = (ga > 0.0) & (a < earliest) & ~((ga + gb) > lipschitz * (b - a))
        a, b, ga, gb = a[keep], b[keep], ga[keep], gb[keep]
        if len(a) == 0 or (b - a).max() < finest:
            break
        m = 0.5 * (a + b)
        gm = gap(m)
        a, b = np.concatenate([a, m]), np.concatenate([m, b])
        ga, gb = np.concatenate([ga, gm]), np.concatenate([gm, gb])
    if earliest == INF:
        return INF, INF
    k = int(np.argmin(np.where(gb <= 0.0, a, INF)))
    lo, hi = float(a[k]), float(b[k])
    while True:
        mid = 0.5 * (lo + hi)
        if mid <= lo or mid >= hi:
            return lo, hi
        if gap(mid)[0] > 0.0:
            lo = mid
        else:
            hi = mid


def assert_agrees(t, gap, lipschitz, horizon=HORIZON):
    """The kernel's time matches the reference to 1e-9 and is never later; misses agree
    except for grazes (a reported touch must then have |gap| <= 1e-9, a skipped one a
    penetration below 1e-9)."""
    low, high = reference_contact(gap, lipschitz, horizon)
    if high == INF:
        assert t == INF or abs(gap(t)[0]) <= MATCH, f"kernel {t!r}, reference: no contact"
        return
    if t == INF:
        depth = -gap(np.linspace(low, min(low + 1e-3, horizon), 4001)).min()
        assert depth <= MATCH, f"kernel: no contact, reference {high!r} (depth {depth:.3g})"
        return
    assert t <= high + ROUNDING, f"kernel {t!r} later than the reference {high!r}"
    assert high - t <= MATCH or abs(gap(t)[0]) <= MATCH, f"kernel {t!r}, reference {high!r}"


def local_outline(vertices):
    """Vertices relative to the area centroid (anticlockwise) as an array."""
    local, _ = centred(vertices)
    return np.array(local)


def bounding(local):
    return float(np.hypot(local[:, 0], local[:, 1]).max())


def box(width, height):
    w = 0.5 * width
    h = 0.5 * height
    return np.array([(-w, -h), (w, -h), (w, h), (-w, h)])


# ------------------------------------------------------------------ strategies

spins = st.one_of(st.floats(-50.0, 50.0), st.sampled_from([-50.0, 50.0, 1e-6, -0.3]))
angles = st.floats(0.0, TAU)


@st.composite
def motions(draw, towards):
    """Relative velocity (0.1 to 3 m/s, within 0.7 rad of ``towards``) and acceleration (up to 10 m/s^2)."""
    speed = draw(st.floats(0.1, 3.0))
    heading = towards + draw(st.floats(-0.7, 0.7))
    accel = draw(st.floats(0.0, 10.0))
    direction = draw(angles)
    return (speed * math.cos(heading), speed * math.sin(heading)), (
        accel * math.cos(direction),
        accel * math.sin(direction),
    )


@st.composite
def polygon_and_wall(draw):
    """A spinning polygon beside a thin wall (fixed or moving: only relative motion counts)."""
    local_a = local_outline(draw(convex_polygons(0.05, 0.2)))
    wall = box(draw(st.floats(0.5, 2.0)), draw(st.floats(0.01, 0.05)))
    theta_b = draw(angles)
    side = draw(st.floats(-0.3, 0.3))
    height = wall[2, 1] + bounding(local_a) + draw(st.floats(1e-3, 0.2))  # from the wall's mid-plane
    c, s = math.cos(theta_b), math.sin(theta_b)
    d = (c * side - s * height, s * side + c * height)
    dv, da = draw(motions(math.atan2(-d[1], -d[0])))
    return local_a, draw(angles), draw(spins), wall, theta_b, 0.0, d, dv, da


@st.composite
def polygon_pairs(draw):
    """Two spinning polygons whose bounding circles start apart."""
    local_a = local_outline(draw(convex_polygons(0.05, 0.2)))
    local_b = local_outline(draw(convex_polygons(0.05, 0.2)))
    distance = bounding(local_a) + bounding(local_b) + draw(st.floats(1e-3, 0.3))
    direction = draw(angles)
    d = (distance * math.cos(direction), distance * math.sin(direction))
    dv, da = draw(motions(direction + math.pi))
    return local_a, draw(angles), draw(spins), local_b, draw(angles), draw(spins), d, dv, da


@st.composite
def circle_and_polygon(draw):
    """A moving circle and a spinning polygon whose bounding circles start apart."""
    radius = draw(st.floats(0.02, 0.2))
    local_b = local_outline(draw(convex_polygons(0.05, 0.2)))
    distance = radius + bounding(local_b) + draw(st.floats(1e-3, 0.2))
    direction = draw(angles)
    d = (distance * math.cos(direction), distance * math.sin(direction))
    dv, da = draw(motions(direction + math.pi))
    return radius, local_b, draw(angles), draw(spins), d, dv, da


def run_pair(case, horizon=HORIZON):
    local_a, theta_a, omega_a, local_b, theta_b, omega_b, d, dv, da = case
    outline = np.vstack([outline_rows(local_a), outline_rows(local_b)])
    na, nb = len(local_a), len(local_b)
    t, feature = rotating_polygon_polygon(
        d[0], d[1], dv[0], dv[1], da[0], da[1], outline, 0, na, theta_a, omega_a, na, nb, theta_b, omega_b, horizon
    )
    gap = polygon_gap(local_a, theta_a, omega_a, local_b, theta_b, omega_b, d, dv, da)
    lipschitz = (
        math.hypot(*dv)
        + math.hypot(*da) * horizon
        + abs(omega_a) * bounding(local_a)
        + abs(omega_b) * bounding(local_b)
    )
    return t, feature, gap, lipschitz, outline


def assert_contact_geometry(case, outline, t, feature):
    """At a reported contact the point lies on both outlines and the normal separates them."""
    local_a, theta_a, omega_a, local_b, theta_b, omega_b, d, dv, da = case
    if not 0.0 < t < INF:
        return
    x, y = _offset(d, dv, da, t)
    na, nb = len(local_a), len(local_b)
    px, py, nx, ny = rotating_polygon_polygon_contact(
        x,
        y,
        0.0,
        0.0,
        dv[0] + da[0] * t,
        dv[1] + da[1] * t,
        outline,
        0,
        na,
        theta_a + omega_a * t,
        omega_a,
        na,
        nb,
        theta_b + omega_b * t,
        omega_b,
        feature,
    )
    assert abs(math.hypot(nx, ny) - 1.0) <= 1e-12
    point = np.array([[[px, py]]])
    for local, theta, cx, cy, sign in (
        (local_a, theta_a + omega_a * t, x, y, 1.0),
        (local_b, theta_b + omega_b * t, 0.0, 0.0, -1.0),
    ):
        P = _place(local, theta, 0.0, np.zeros(1), np.array([cx]), np.array([cy]))
        assert _segment_distance(point, P)[0, 0] <= 1e-7
        # a lies on the normal's side of the point, b on the other
        assert (sign * ((P[0] - [px, py]) @ [nx, ny])).min() >= -1e-7


# ------------------------------------------------------------------ closed forms


SQUARE = 0.1  # half side
WALL_HALF = 0.05


def square_and_wall(clearance_to_centre):
    """Outline rows of a square (a) and a tall wall (b) whose face is ``c`` from the square's centre."""
    outline = np.vstack([outline_rows(box(2 * SQUARE, 2 * SQUARE)), outline_rows(box(2 * WALL_HALF, 10.0))])
    return outline, (-(clearance_to_centre + WALL_HALF), 0.0)


@pytest.mark.parametrize("omega", [3.0, -3.0, 50.0, -47.5])
@pytest.mark.parametrize("fraction", [0.75, 0.9, 0.999])
def test_square_spinning_in_place_hits_wall_when_its_corner_sweep_reaches_it(omega, fraction):
    """A square spinning in place touches a wall at distance c when a(|cos| + |sin|) of its angle reaches c."""
    c = SQUARE + fraction * (SQUARE * math.sqrt(2.0) - SQUARE)
    outline, d = square_and_wall(c)
    t, feature = rotating_polygon_polygon(
        d[0], d[1], 0.0, 0.0, 0.0, 0.0, outline, 0, 4, 0.0, omega, 4, 4, 0.0, 0.0, 1.0
    )
    exact = (math.asin(c / (SQUARE * math.sqrt(2.0))) - math.pi / 4.0) / abs(omega)
    assert exact - 1e-12 <= t <= exact + 1e-15
    assert feature == 3  # the wall's face towards the square
    theta = omega * t
    px, py, nx, ny = rotating_polygon_polygon_contact(
        0.0, 0.0, -d[0], -d[1], 0.0, 0.0, outline, 0, 4, theta, omega, 4, 4, 0.0, 0.0, feature
    )
    corner_y = SQUARE * (math.sin(abs(theta)) - math.cos(theta)) * math.copysign(1.0, omega)
    assert (nx, ny) == pytest.approx((-1.0, 0.0), abs=1e-12)
    assert (px, py) == pytest.approx((c, corner_y), abs=1e-9)


def test_rod_rotating_about_its_centroid_hits_a_circle_at_the_closed_form_angle():
    """A rod turning clockwise from vertical meets a circle at rho when sin(angle) = (r + w) / rho."""
    half_length, half_width, radius, rho, omega = 0.3, 0.01, 0.05, 0.2, -7.0
    rod = np.array(
        [(-half_width, -half_length), (half_width, -half_length), (half_width, half_length), (-half_width, half_length)]
    )
    outline = outline_rows(rod)
    t, feature = rotating_circle_polygon(rho, 0.0, 0.0, 0.0, 0.0, 0.0, radius, outline, 0, 4, 0.0, omega, 1.0)
    alpha = math.asin((radius + half_width) / rho)
    exact = (math.pi / 2.0 - alpha) / abs(omega)
    assert exact - 1e-12 <= t <= exact + 1e-15
    assert feature == 1  # the rod's long side at +x in its own frame
    px, py, nx, ny = rotating_circle_polygon_contact(rho, 0.0, radius, 0.0, 0.0, outline, 0, 4, omega * t, feature)
    assert (nx, ny) == pytest.approx((math.sin(alpha), -math.cos(alpha)), abs=1e-9)
    assert (px, py) == pytest.approx((rho - radius * nx, -radius * ny), abs=1e-12)


def test_rod_sweeping_past_a_moving_circle_matches_the_reference():
    """A spinning rod and a circle falling past it under gravity: the reference agrees."""
    rod = box(0.6, 0.02)
    outline = outline_rows(rod)
    d, dv, da = (0.25, 0.35), (0.0, -0.5), (0.0, -9.81)
    t, _ = rotating_circle_polygon(*d, *dv, *da, 0.04, outline, 0, 4, 0.4, 20.0, HORIZON)
    assert 0.0 < t < INF
    lipschitz = math.hypot(*dv) + math.hypot(*da) * HORIZON + 20.0 * bounding(rod)
    assert_agrees(t, circle_gap(0.04, rod, 0.4, 20.0, d, dv, da), lipschitz)


# ------------------------------------------------------------------ the start


def test_corner_touching_and_separating_at_start_is_not_a_contact_but_the_next_corner_is():
    """Touching a wall with a corner that is leaving: not 0, the next corner's (closed-form) arrival."""
    omega, delta = 40.0, 0.01
    c = SQUARE * math.sqrt(2.0) * math.cos(delta)
    outline, d = square_and_wall(c)
    t, _ = rotating_polygon_polygon(
        d[0], d[1], 0.0, 0.0, 0.0, 0.0, outline, 0, 4, math.pi / 4 + delta, omega, 4, 4, 0.0, 0.0, 1.0
    )
    exact = (math.pi / 2.0 - 2.0 * delta) / omega
    assert exact - 1e-11 <= t <= exact + 1e-15


def test_overlapping_and_separating_at_start_finds_the_next_genuine_contact():
    """Overlapping by 1e-9 and separating at t = 0: the next contact matches the reference."""
    omega, delta = 25.0, 0.05
    c = SQUARE * math.sqrt(2.0) * math.cos(delta) - 1e-9
    outline, d = square_and_wall(c)
    theta = math.pi / 4 + delta
    t, _ = rotating_polygon_polygon(d[0], d[1], 0.0, 0.0, 0.0, 0.0, outline, 0, 4, theta, omega, 4, 4, 0.0, 0.0, 1.0)
    gap = polygon_gap(box(0.2, 0.2), theta, omega, box(0.1, 10.0), 0.0, 0.0, d, (0.0, 0.0), (0.0, 0.0))
    assert gap(0.0)[0] < 0.0
    opened = 1e-3  # the old contact has ended by then
    assert gap(opened)[0] > 0.0
    _, high = reference_contact(lambda s: gap(np.asarray(s) + opened), omega * 0.15, 1.0 - opened)
    assert high + opened - 1e-9 <= t <= high + opened + ROUNDING


@pytest.mark.parametrize("overlap", [0.0, 1e-7])
def test_overlapping_and_approaching_at_start_is_immediate(overlap):
    """A corner touching (or 1e-7 inside) a wall and still sweeping into it gives t = 0."""
    delta = 0.01
    c = SQUARE * math.sqrt(2.0) * math.cos(delta) - overlap
    outline, d = square_and_wall(c)
    t, feature = rotating_polygon_polygon(
        d[0], d[1], 0.0, 0.0, 0.0, 0.0, outline, 0, 4, math.pi / 4 - delta, 30.0, 4, 4, 0.0, 0.0, 1.0
    )
    assert (t, feature) == (0.0, 3)


@pytest.mark.parametrize("retreat, immediate", [(0.001, True), (0.1, False)])
def test_rotation_of_the_contact_point_decides_whether_a_touch_approaches(retreat, immediate):
    """The approach speed at t = 0 includes omega x r: a slow retreat of the centroid cannot outrun the sweep."""
    omega, delta = 10.0, 0.01  # the corner sweeps into the wall at omega * R * sin(delta) = 0.014 m/s
    c = SQUARE * math.sqrt(2.0) * math.cos(delta)
    outline, d = square_and_wall(c)
    t, _ = rotating_polygon_polygon(
        d[0], d[1], -retreat, 0.0, 0.0, 0.0, outline, 0, 4, math.pi / 4 - delta, omega, 4, 4, 0.0, 0.0, 1.0
    )
    assert (t == 0.0) == immediate


def test_corner_resting_at_the_end_of_its_sweep_is_not_an_immediate_contact():
    """A corner touching at the extreme of its sweep has zero approach speed: t > 0, no zero-time loop."""
    omega = 50.0
    outline, d = square_and_wall(SQUARE * math.sqrt(2.0))
    t, _, iterations = rotating_search(
        d[0], d[1], 0.0, 0.0, 0.0, 0.0, outline, 0, 4, math.pi / 4, omega, 4, 4, 0.0, 0.0, 0.0, False, 1.0, 20000
    )
    assert t > 0.0
    # the next corner grazes the wall a quarter turn later (reported within the graze tolerance)
    assert abs(t - (math.pi / 2.0) / omega) <= 1e-7
    assert iterations < 200


def test_circle_touching_a_spinning_polygon_start_rules():
    """A circle touching a spinning polygon's edge: approaching gives 0, separating gives a later time."""
    outline = outline_rows(box(0.4, 0.4))
    radius = 0.05
    # centre above the top edge; the square turns, so its top edge's point below the centre moves
    for omega, expect_zero in ((5.0, True), (-5.0, False)):
        t, _ = rotating_circle_polygon(0.15, 0.25, 0.0, 0.0, 0.0, 0.0, radius, outline, 0, 4, 0.0, omega, 0.5)
        assert (t == 0.0) == expect_zero
        if not expect_zero:
            assert t > 0.01


# ------------------------------------------------------------------ grazes and budget


@pytest.mark.parametrize("relative", [-1e-12, 0.0, 1e-15, 1e-12, 1e-10])
def test_grazing_corner_is_reported_at_the_touch_or_skipped_and_terminates(relative):
    """A corner whose sweep just reaches (or just misses) the wall: a touch at the graze time or none, quickly."""
    omega = 50.0
    reach = SQUARE * math.sqrt(2.0)
    outline, d = square_and_wall(reach * (1.0 + relative))
    horizon = 0.75 * (math.pi / 2.0) / omega  # only the first graze, at pi / 4
    t, _, iterations = rotating_search(
        d[0], d[1], 0.0, 0.0, 0.0, 0.0, outline, 0, 4, 0.0, omega, 4, 4, 0.0, 0.0, 0.0, False, horizon, 20000
    )
    graze = (math.pi / 4.0) / omega
    assert t == INF or abs(t - graze) <= 1e-7
    if relative < -1e-14:
        assert t <= graze  # a genuine crossing must be found, never late
    assert iterations < 100


#: seed 2 of the random rotating scenes at t = 1.09 (2026-11-22): heptagon 13 touching the left
#: wall, sliding up it and leaving it at 1e-15 m/s, turning at 1.75e-14 rad/s (rounding noise).
TRACED_HEPTAGON = [
    (-0.03615980078504171, -0.004247956795715299),
    (-0.011539309460366742, -0.037974341698601116),
    (0.014703841002364555, -0.030559785663781234),
    (0.03856977011970691, -0.009112373636214064),
    (0.01961981907515773, 0.026389860107111553),
    (-0.004831308793902027, 0.04237337160338331),
    (-0.024455885803250962, 0.020749003783313704),
]
TRACED_WALL = [(-0.05000000000000001, -0.6), (0.049999999999999996, -0.6), (0.049999999999999996, 0.6), (-0.05000000000000001, 0.6)]
TRACED_MOTION = (0.0817103651725013, -0.4666187061599453, 1.0589068256626158e-15, 0.026241510775297537, 0.0, -9.81)


@pytest.mark.parametrize("omega", [1.75008102788144e-14, -1e-12, 0.0])
def test_polygon_sliding_along_a_wall_it_touches_is_searched_in_a_few_steps(omega):
    """A polygon touching a wall and sliding along it under gravity (tangent to the face) meets
    nothing new before the horizon; the search must say so in a few steps. Bounding the gap's
    bend by all of gravity took 20,000 steps and ran out of budget, 2 ms per prediction: the
    scene crawled at 65,000 events for 1 s of simulated time."""
    outline = np.vstack([outline_rows(np.array(TRACED_HEPTAGON)), outline_rows(np.array(TRACED_WALL))])
    theta = 5.6526030944678896
    horizon = 0.14663043895531436
    t, feature, iterations = rotating_search(
        *TRACED_MOTION, outline, 0, 7, theta, omega, 7, 4, 0.0, 0.0, 0.0, False, horizon, 20000, 3.73e-16
    )
    assert feature != CHECKPOINT
    assert iterations < 100
    gap = polygon_gap(np.array(TRACED_HEPTAGON), theta, omega, np.array(TRACED_WALL), 0.0, 0.0, TRACED_MOTION[:2],
                      TRACED_MOTION[2:4], TRACED_MOTION[4:])
    assert t == INF or abs(gap(t)[0]) <= MATCH
    assert gap(np.linspace(1e-3, horizon, 2001)).min() > 0.0  # the reference: nothing new


@pytest.mark.parametrize("omega", [1e-9, -1e-9, 0.005, -0.005])
@pytest.mark.parametrize("pull", [1.0, 30.0])
def test_face_leaving_a_wall_and_pulled_back_while_sliding_along_it_matches_the_reference(omega, pull):
    """A square leaving a wall it touched flat, sliding down it under gravity and pulled back
    towards it: the return contact matches the reference, found in few steps."""
    outline, d = square_and_wall(SQUARE)
    dv, da = (-1e-3, -0.05), (pull, -9.81)
    t, _, iterations = rotating_search(
        d[0], d[1], *dv, *da, outline, 0, 4, 0.0, omega, 4, 4, 0.0, 0.0, 0.0, False, 0.15, 20000
    )
    assert iterations < 200
    gap = polygon_gap(box(0.2, 0.2), 0.0, omega, box(0.1, 10.0), 0.0, 0.0, d, dv, da)
    opened = 0.5 * (1e-3 - SQUARE * abs(omega)) / pull  # near the leading corner's peak: the old contact has ended
    assert gap(opened)[0] > 0.0
    lipschitz = math.hypot(*dv) + math.hypot(*da) * 0.15 + abs(omega) * bounding(box(0.2, 0.2))
    _, high = reference_contact(lambda s: gap(np.asarray(s) + opened), lipschitz, 0.15 - opened)
    assert high < INF
    assert high + opened - MATCH <= t <= high + opened + ROUNDING


def test_exhausted_budget_returns_a_checkpoint_before_the_contact_that_resumes_correctly():
    """With a tiny budget the search stops early (CHECKPOINT, no contact before t); resuming finds the contact."""
    omega = 12.0
    c = SQUARE * 1.2
    outline, d = square_and_wall(c)
    exact = (math.asin(c / (SQUARE * math.sqrt(2.0))) - math.pi / 4.0) / omega
    t, feature, iterations = rotating_search(
        d[0], d[1], 0.0, 0.0, 0.0, 0.0, outline, 0, 4, 0.0, omega, 4, 4, 0.0, 0.0, 0.0, False, 1.0, 2
    )
    assert feature == CHECKPOINT and iterations == 2
    assert 0.0 < t < exact
    rest, feature = rotating_polygon_polygon(
        d[0], d[1], 0.0, 0.0, 0.0, 0.0, outline, 0, 4, omega * t, omega, 4, 4, 0.0, 0.0, 1.0 - t
    )
    assert feature == 3
    assert abs(t + rest - exact) <= 1e-12
    # a contact function handed the checkpoint uses the face of largest separation (here the wall's)
    args = (0.0, 0.0, -d[0], -d[1], 0.0, 0.0, outline, 0, 4, omega * exact, omega, 4, 4, 0.0, 0.0)
    assert rotating_polygon_polygon_contact(*args, CHECKPOINT) == rotating_polygon_polygon_contact(*args, 3)


# ------------------------------------------------------------------ delegation


@settings(deadline=None, max_examples=40)
@given(polygon_pairs())
def test_without_spin_the_kernels_equal_the_translating_ones_on_turned_outlines(case):
    """omega = 0 on both: the same answer as polygon_polygon / circle_polygon on outlines turned by hand."""
    local_a, theta_a, _, local_b, theta_b, _, d, dv, da = case

    def turned(local, theta):
        c, s = math.cos(theta), math.sin(theta)
        return [(c * x - s * y, s * x + c * y) for x, y in local]

    outline = np.vstack([outline_rows(local_a), outline_rows(local_b)])
    na, nb = len(local_a), len(local_b)
    t, feature = rotating_polygon_polygon(*d, *dv, *da, outline, 0, na, theta_a, 0.0, na, nb, theta_b, 0.0, HORIZON)
    world = np.vstack([outline_rows(turned(local_a, theta_a)), outline_rows(turned(local_b, theta_b))])
    expected, expected_feature = polygon_polygon(*d, *dv, *da, world, 0, na, na, nb, HORIZON)
    assert t == pytest.approx(expected, rel=1e-9, abs=1e-12)
    if t != INF:
        assert feature == expected_feature
    radius = 0.5 * bounding(local_a)
    t, feature = rotating_circle_polygon(*d, *dv, *da, radius, outline, na, nb, theta_b, 0.0, HORIZON)
    expected, expected_feature = circle_polygon(
        *d, *dv, *da, radius, outline_rows(turned(local_b, theta_b)), 0, nb, HORIZON
    )
    assert t == pytest.approx(expected, rel=1e-9, abs=1e-12)
    if t != INF:
        assert feature == expected_feature


# ------------------------------------------------------------------ against the reference


@settings(deadline=None, max_examples=60)
@given(polygon_and_wall())
def test_spinning_polygon_against_wall_matches_brute_force(case):
    """Random spinning polygons (|omega| <= 50) against fixed or moving walls under gravity-like accelerations."""
    t, feature, gap, lipschitz, outline = run_pair(case)
    assert_agrees(t, gap, lipschitz)
    assert_contact_geometry(case, outline, t, feature)


@settings(deadline=None, max_examples=60)
@given(polygon_pairs())
def test_two_spinning_polygons_match_brute_force(case):
    """Random pairs of spinning polygons with accelerations: first contact as the reference, never later."""
    t, feature, gap, lipschitz, outline = run_pair(case)
    assert_agrees(t, gap, lipschitz)
    assert_contact_geometry(case, outline, t, feature)


@settings(deadline=None, max_examples=60)
@given(circle_and_polygon())
def test_circle_against_spinning_polygon_matches_brute_force(case):
    """Random circles against spinning polygons: first contact as the reference, never later."""
    radius, local_b, theta_b, omega_b, d, dv, da = case
    outline = outline_rows(local_b)
    t, feature = rotating_circle_polygon(*d, *dv, *da, radius, outline, 0, len(local_b), theta_b, omega_b, HORIZON)
    lipschitz = math.hypot(*dv) + math.hypot(*da) * HORIZON + abs(omega_b) * bounding(local_b)
    assert_agrees(t, circle_gap(radius, local_b, theta_b, omega_b, d, dv, da), lipschitz)
    if 0.0 < t < INF:
        x, y = _offset(d, dv, da, t)
        px, py, nx, ny = rotating_circle_polygon_contact(
            x, y, radius, 0.0, 0.0, outline, 0, len(local_b), theta_b + omega_b * t, feature
        )
        assert math.hypot(px - x, py - y) == pytest.approx(radius, abs=1e-7)
        assert (x - px) * nx + (y - py) * ny == pytest.approx(radius, abs=1e-7)


def test_typical_prediction_takes_few_iterations():
    """Over 300 seeded random rotating pairs the median search is at most 20 steps and none exceeds 200."""
    rng = random.Random(7)
    counts = []
    for _ in range(300):
        la = box(rng.uniform(0.05, 0.3), rng.uniform(0.05, 0.3))
        lb = box(rng.uniform(0.05, 0.3), rng.uniform(0.05, 0.3))
        outline = np.vstack([outline_rows(la), outline_rows(lb)])
        distance = bounding(la) + bounding(lb) + rng.uniform(1e-3, 0.5)
        direction = rng.uniform(0.0, TAU)
        d = (distance * math.cos(direction), distance * math.sin(direction))
        speed = rng.uniform(0.0, 3.0)
        heading = direction + math.pi + rng.uniform(-1.0, 1.0)
        dv = (speed * math.cos(heading), speed * math.sin(heading))
        _, _, iterations = rotating_search(
            *d,
            *dv,
            0.0,
            -9.81,
            outline,
            0,
            4,
            rng.uniform(0, TAU),
            rng.uniform(-50, 50),
            4,
            4,
            rng.uniform(0, TAU),
            rng.uniform(-50, 50),
            0.0,
            False,
            HORIZON,
            20000,
        )
        counts.append(iterations)
    assert np.median(counts) <= 20
    assert max(counts) <= 200


# ------------------------------------------------------------------ angular acceleration

twists = st.one_of(st.floats(-400.0, 400.0), st.sampled_from([-400.0, 400.0, 1e-6, 0.0]))


def _angle_root(omega, alpha, angle):
    """Earliest ``t > 0`` with ``omega t + alpha t^2 / 2 = angle``, to 30 digits (mpmath)."""
    mpmath = pytest.importorskip("mpmath")
    with mpmath.workdps(30):
        w, a, phi = mpmath.mpf(omega), mpmath.mpf(alpha), mpmath.mpf(angle)
        disc = w * w + 2 * a * phi
        roots = [r for r in ((-w + mpmath.sqrt(disc)) / a, (-w - mpmath.sqrt(disc)) / a) if r > 0] if disc >= 0 else []
        return float(min(roots)) if roots else INF


@pytest.mark.parametrize(
    "omega, alpha",
    [(0.0, -30.0), (0.0, -400.0), (-2.0, -30.0), (3.0, -60.0), (-12.0, 25.0)],
)
def test_rod_turning_with_angular_acceleration_hits_the_circle_at_the_closed_form_time(omega, alpha):
    """A rod spun up (or slowing, or turning back) about its centroid meets a circle at the angle
    where sin(-angle) = (r + w) / rho; the time solves omega t + alpha t^2 / 2 = angle (mpmath)."""
    half_length, half_width, radius, rho = 0.3, 0.01, 0.05, 0.2
    rod = box(2 * half_width, 2 * half_length)
    outline = outline_rows(rod)
    t, feature = rotating_circle_polygon(
        rho, 0.0, 0.0, 0.0, 0.0, 0.0, radius, outline, 0, 4, 0.0, omega, 1.0, 0.0, alpha
    )
    touch = math.pi / 2.0 - math.asin((radius + half_width) / rho)  # clockwise angle of the touch
    # the first time the rod's angle reaches -touch (clockwise) or pi - touch... either side
    # of the rod meets the circle: its +x side at angle -touch, its -x side at angle touch - pi
    exact = min(_angle_root(omega, alpha, -touch), _angle_root(omega, alpha, touch - math.pi),
                _angle_root(omega, alpha, math.pi - touch), _angle_root(omega, alpha, touch))
    assert exact < 1.0
    assert exact - 1e-12 <= t <= exact + 1e-15
    angle = omega * t + 0.5 * alpha * t * t
    px, py, nx, ny = rotating_circle_polygon_contact(rho, 0.0, radius, 0.0, 0.0, outline, 0, 4, angle, feature)
    assert math.hypot(px - rho, py) == pytest.approx(radius, abs=1e-9)


def test_a_spin_that_stops_short_of_the_wall_turns_back_without_a_contact():
    """A square spinning towards a wall stops (omega + alpha t = 0) just before its corner would
    reach it: no contact, where a kernel ignoring alpha would report one."""
    c = SQUARE + 0.9 * (SQUARE * math.sqrt(2.0) - SQUARE)
    reach = math.asin(c / (SQUARE * math.sqrt(2.0))) - math.pi / 4.0  # angle at which the corner touches
    outline, d = square_and_wall(c)
    omega = 4.0
    alpha = -omega * omega / (2.0 * 0.98 * reach)  # stops at 98 % of that angle
    t, _ = rotating_polygon_polygon(d[0], d[1], 0.0, 0.0, 0.0, 0.0, outline, 0, 4, 0.0, omega, 4, 4, 0.0, 0.0, 0.2,
                                    0.0, alpha, 0.0)
    assert t == INF
    naive, _ = rotating_polygon_polygon(d[0], d[1], 0.0, 0.0, 0.0, 0.0, outline, 0, 4, 0.0, omega, 4, 4, 0.0, 0.0, 0.2)
    assert naive < 0.2
    # a little less braking and it does touch, at the mpmath time
    alpha = -omega * omega / (2.0 * 1.02 * reach)
    t, feature = rotating_polygon_polygon(d[0], d[1], 0.0, 0.0, 0.0, 0.0, outline, 0, 4, 0.0, omega, 4, 4, 0.0, 0.0,
                                          1.0, 0.0, alpha, 0.0)
    exact = _angle_root(omega, alpha, reach)
    assert exact - 1e-12 <= t <= exact + 1e-15
    assert feature == 3


def _with_twist(case, alpha_a, alpha_b):
    local_a, theta_a, omega_a, local_b, theta_b, omega_b, d, dv, da = case
    outline = np.vstack([outline_rows(local_a), outline_rows(local_b)])
    na, nb = len(local_a), len(local_b)
    t, feature = rotating_polygon_polygon(
        d[0], d[1], dv[0], dv[1], da[0], da[1], outline, 0, na, theta_a, omega_a, na, nb, theta_b, omega_b, HORIZON,
        0.0, alpha_a, alpha_b,
    )
    gap = polygon_gap(local_a, theta_a, omega_a, local_b, theta_b, omega_b, d, dv, da, alpha_a, alpha_b)
    lipschitz = (
        math.hypot(*dv)
        + math.hypot(*da) * HORIZON
        + (abs(omega_a) + abs(alpha_a) * HORIZON) * bounding(local_a)
        + (abs(omega_b) + abs(alpha_b) * HORIZON) * bounding(local_b)
    )
    return t, feature, gap, lipschitz


@settings(deadline=None, max_examples=60)
@given(polygon_and_wall(), twists)
def test_polygon_with_angular_acceleration_against_wall_matches_brute_force(case, alpha_a):
    """Random polygons turning with |alpha| <= 400 rad/s^2 against walls: as the reference, never later."""
    t, _, gap, lipschitz = _with_twist(case, alpha_a, 0.0)
    assert_agrees(t, gap, lipschitz)


@settings(deadline=None, max_examples=60)
@given(polygon_pairs(), twists, twists)
def test_two_polygons_with_angular_accelerations_match_brute_force(case, alpha_a, alpha_b):
    """Random pairs, both turning with angular accelerations: as the reference, never later."""
    t, _, gap, lipschitz = _with_twist(case, alpha_a, alpha_b)
    assert_agrees(t, gap, lipschitz)


@settings(deadline=None, max_examples=60)
@given(circle_and_polygon(), twists)
def test_circle_against_polygon_with_angular_acceleration_matches_brute_force(case, alpha_b):
    """Random circles against polygons turning with angular acceleration: as the reference."""
    radius, local_b, theta_b, omega_b, d, dv, da = case
    outline = outline_rows(local_b)
    t, _ = rotating_circle_polygon(
        *d, *dv, *da, radius, outline, 0, len(local_b), theta_b, omega_b, HORIZON, 0.0, alpha_b
    )
    lipschitz = (
        math.hypot(*dv) + math.hypot(*da) * HORIZON + (abs(omega_b) + abs(alpha_b) * HORIZON) * bounding(local_b)
    )
    assert_agrees(t, circle_gap(radius, local_b, theta_b, omega_b, d, dv, da, alpha_b), lipschitz)
