"""Rotation physics through the World: contact times, overlaps, impulses, energy, tipping, determinism.

``tests/test_toi_rotating.py`` checks the rotating kernels on their own; these tests go
through ``World`` so that they also lock the wiring: angles advancing with the bodies, the
angles reduced to ``[0, 2 pi)`` before the kernels see them, finite broad-phase horizons for
spinning bodies, angular impulses with friction, turning polygons coming to rest.

Everything is checked against geometry written here from scratch (NumPy, no engine code):

* a body's outline at time ``t`` is ``c0 + v t + a t^2 / 2 + R(theta0 + omega t) r_k`` with
  ``r_k`` its corners about the area centroid;
* the *signed gap* of two shapes is the exact distance while they are apart (smallest
  vertex-to-edge distance, or centre-to-outline distance minus the radius) and the
  separating-axis value (minus the penetration depth, exact for convex shapes) once they
  overlap;
* the first contact is found by branch and bound over the whole horizon: an interval
  ``[a, b]`` is cleared when ``(g(a) + g(b)) / 2 > L (b - a) / 2``, with ``L = max |dv| +
  |omega_a| R_a + |omega_b| R_b`` bounding how fast any gap can close; the rest are split until
  a sign change is bisected to the last bit. Fine sampling alone could step over a corner
  clipping a corner; this cannot.

Scenes that could hang the compiled event loop (it cannot be interrupted from Python) run in a
forked child with a time limit, so a livelock fails its test instead of freezing the suite.
"""

from __future__ import annotations

import math
import multiprocessing
import random
import traceback

import numpy as np
import pytest
from hypothesis import Phase, assume, example, given, settings
from hypothesis import strategies as st
from strategies import (
    TAU,
    centred,
    convex_hull,
    convex_polygons,
    regular_polygon,
    regular_polygons,
)

from pge import Collision, Frame, Stop, World
from pge.core.tuning import ISLAND_STEP

G = 9.81
MATCH = 1e-9  # the engine may report a contact this much early (s)
LATE = 1e-12  # ... and this much late, for rounding (s)
OVERLAP = 1e-9  # allowed overlap, relative to the sum of the two bounding radii
ENERGY = 1e-12  # allowed relative energy gain per collision
#: ... under gravity, between two collisions, where an island's steps may have changed the energy by
#: their integration error (docs/contact.md, "Energy": at most 2e-7 of the scene's energy scale at
#: a step's end), and a collision may fall inside a step where a point lifts off and lands again: its
#: constant contact force works while the point rises and takes the work back as it falls, up to
#: m (g h)^2 / 32 for a body of mass m on its support at the step's middle (test_islands.py,
#: test_a_point_lifting_off_within_a_step_floats_...), which over the scale's g sum m is g h^2 / 32
ISLAND_ENERGY = 2e-7 + G * ISLAND_STEP**2 / 32.0
EXACT = 1e-12  # hand-derived impulses (relative)
SCENE_EVENTS = 1500  # event budget of one random scene
WATCHDOG = 10.0  # seconds a forked scene may take before it counts as hung

# Scenes are drawn from a seed; a shrunk seed is no simpler, and each step would rerun a scene.
SCENE_SETTINGS = settings(
    max_examples=20, deadline=None, phases=(Phase.explicit, Phase.reuse, Phase.generate), print_blob=True
)


# ------------------------------------------------------------------ exact geometry


def place(local, angle, cx, cy):
    """Outlines ``(T, n, 2)`` of a polygon with corners ``local`` about its centroid, at
    angles ``angle`` and centroids ``(cx, cy)`` (arrays of length T)."""
    angle = np.asarray(angle, float)
    c, s = np.cos(angle)[:, None], np.sin(angle)[:, None]
    lx, ly = local[None, :, 0], local[None, :, 1]
    return np.stack([c * lx - s * ly + np.asarray(cx)[:, None], s * lx + c * ly + np.asarray(cy)[:, None]], -1)


def _edges(P):
    """Start points, edge vectors and unit outward normals of anticlockwise outlines."""
    edge = np.roll(P, -1, axis=1) - P
    length = np.hypot(edge[..., 0], edge[..., 1])
    normal = np.stack([edge[..., 1] / length, -edge[..., 0] / length], -1)
    return P, edge, normal


def _point_outline_distance(Q, P):
    """Smallest distance ``(T,)`` from the points ``Q (T, m, 2)`` to the edges of ``P (T, n, 2)``."""
    start, edge, _ = _edges(P)
    w = Q[:, :, None, :] - start[:, None, :, :]
    e = edge[:, None, :, :]
    u = np.clip((w * e).sum(-1) / (e * e).sum(-1), 0.0, 1.0)
    off = w - u[..., None] * e
    return np.hypot(off[..., 0], off[..., 1]).min(axis=(1, 2))


def _separation(P, Q):
    """Largest separation ``(T,)`` of ``Q`` from ``P`` along ``P``'s outward edge normals."""
    start, _, normal = _edges(P)
    s = ((Q[:, None, :, :] - start[:, :, None, :]) * normal[:, :, None, :]).sum(-1)
    return s.min(axis=2).max(axis=1)


def polygon_gap(P, Q):
    """Signed gap ``(T,)`` of two convex polygons: distance apart, minus the depth overlapping."""
    sat = np.maximum(_separation(P, Q), _separation(Q, P))
    apart = np.minimum(_point_outline_distance(P, Q), _point_outline_distance(Q, P))
    return np.where(sat > 0.0, apart, sat)


def circle_gap(C, radius, P):
    """Signed gap ``(T,)`` of circles with centres ``C (T, 2)`` and a convex polygon."""
    start, _, normal = _edges(P)
    outside = ((C[:, None, :] - start) * normal).sum(-1).max(axis=1)
    distance = _point_outline_distance(C[:, None, :], P)
    return np.where(outside > 0.0, distance, outside) - radius


def body_gap(a, b):
    """Signed gap of two World bodies now, from their public positions and vertices only."""
    if a.kind == "circle" and b.kind == "circle":
        return math.dist(a.position, b.position) - a.shape.radius - b.shape.radius
    if a.kind == "circle":
        a, b = b, a
    P = np.array([a.vertices])
    if b.kind == "circle":
        return float(circle_gap(np.array([b.position]), b.shape.radius, P)[0])
    return float(polygon_gap(P, np.array([b.vertices]))[0])


# ------------------------------------------------------------------ brute-force first contact


def first_contact(gap, horizon, lipschitz, grid=4096, split=16, finest=1e-13):
    """First time in ``[0, horizon]`` at which ``gap`` reaches 0, and where touching could not be
    ruled out before it: ``(t_cross, t_unsure)``, each inf for none.

    ``t_cross`` is bisected to adjacent floats (the last time the gap is still positive).
    ``t_unsure`` is the start of the earliest interval narrower than ``finest`` that is neither
    cleared nor closed: a graze the gap comes within about ``lipschitz * finest`` of.
    """
    t = np.linspace(0.0, horizon, grid + 1)
    g = gap(t)
    assert g[0] > 0.0, "the scene must start apart"
    a, b, ga, gb = t[:-1], t[1:], g[:-1], g[1:]
    unsure = math.inf
    hit = None
    while True:
        closed = np.flatnonzero(gb <= 0.0)
        if closed.size:
            k = closed[0]
            hit = (float(a[k]), float(b[k]))
            a, b, ga, gb = a[:k], b[:k], ga[:k], gb[:k]  # only what comes before can beat it
        open_ = (ga + gb) <= lipschitz * (b - a)
        a, b, ga, gb = a[open_], b[open_], ga[open_], gb[open_]
        tiny = (b - a) < finest
        if tiny.any():
            unsure = min(unsure, float(a[tiny].min()))
            a, b, ga, gb = a[~tiny], b[~tiny], ga[~tiny], gb[~tiny]
        if a.size == 0:
            break
        # Split every open interval into ``split`` pieces, all evaluated in one call.
        frac = np.linspace(0.0, 1.0, split + 1)
        pts = a[:, None] + (b - a)[:, None] * frac[None, :]
        gp = gap(pts[:, 1:-1].ravel()).reshape(a.size, split - 1)
        gp = np.concatenate([ga[:, None], gp, gb[:, None]], axis=1)
        a, b = pts[:, :-1].ravel(), pts[:, 1:].ravel()
        ga, gb = gp[:, :-1].ravel(), gp[:, 1:].ravel()
    if hit is None:
        return math.inf, unsure
    lo, hi = hit
    while True:
        mid = 0.5 * (lo + hi)
        if not lo < mid < hi:
            return lo, unsure
        if gap(np.array([mid]))[0] > 0.0:
            lo = mid
        else:
            hi = mid


class Motion:
    """Closed-form motion of one body: centroid ``c0 + v t + a t^2 / 2``, angle ``theta + omega t``."""

    def __init__(self, centre, velocity=(0.0, 0.0), acceleration=(0.0, 0.0), angle=0.0, omega=0.0):
        self.c, self.v, self.a = centre, velocity, acceleration
        self.angle, self.omega = angle, omega

    def centre(self, t):
        (cx, cy), (vx, vy), (ax, ay) = self.c, self.v, self.a
        return cx + (vx + 0.5 * ax * t) * t, cy + (vy + 0.5 * ay * t) * t

    def outline(self, local, t):
        cx, cy = self.centre(t)
        return place(local, self.angle + self.omega * t, cx, cy)


# ------------------------------------------------------------------ watchdog


def _child(send, fn, args):
    try:
        send.send(("ok", fn(*args)))
    except Exception:  # noqa: BLE001 (any failure, assertions included, goes to the parent)
        send.send(("error", traceback.format_exc()))


_warm = []


def guarded(fn, *args, timeout=WATCHDOG):
    """``fn(*args)`` in a forked child; fails the test if it raises or does not return in time."""
    if not _warm:
        # Load the compiled engine here once, so that every child inherits it (a single
        # frictionless bounce: nothing that could hang the parent).
        world = World(gravity=(0.0, -G))
        world.add_box(0.0, 0.0, 1.0, 0.1, fixed=True)
        world.add_polygon(regular_polygon(5, 0.05, (0.5, 0.3)), mass=1.0, angular_velocity=3.0)
        world.add_circle((0.2, 0.3), 0.05, mass=1.0)
        world.run_until(0.3)
        _warm.append(True)
    context = multiprocessing.get_context("fork")
    receive, send = context.Pipe(duplex=False)
    child = context.Process(target=_child, args=(send, fn, args), daemon=True)
    child.start()
    try:
        if not receive.poll(timeout):
            pytest.fail(f"the event loop did not return within {timeout} s (livelock?) for {fn.__name__}{args!r}")
        status, value = receive.recv()
    finally:
        if child.is_alive():
            child.kill()
        child.join()
    if status != "ok":
        pytest.fail(f"{fn.__name__}{args!r} raised in the child:\n{value}")
    return value


# ------------------------------------------------------------------ 1. first contact against brute force

OTHERS = ["wall", "circle", "polygon"]


@st.composite
def outlines(draw, min_radius=0.05, max_radius=0.2):
    """Corners of a regular or random convex polygon (3 to 8 sides) about its area centroid."""
    vertices = draw(
        st.one_of(regular_polygons(3, 8, min_radius, max_radius), convex_polygons(min_radius, max_radius, 3, 8))
    )
    return np.array(centred(vertices)[0])


angles = st.one_of(st.floats(0.0, TAU), st.floats(-100.0, 100.0))
spins = st.floats(-20.0, 20.0)


def _unit(angle):
    return math.cos(angle), math.sin(angle)


@settings(max_examples=30, deadline=None)
@given(
    other=st.sampled_from(OTHERS),
    local_a=outlines(),
    local_b=outlines(),
    radius=st.floats(0.02, 0.15),
    angle_a=angles,
    angle_b=angles,
    omega_a=spins,
    omega_b=spins,
    direction=st.floats(0.0, TAU),
    gap=st.floats(1e-3, 0.5),
    speed=st.floats(0.0, 3.0),
    aim=st.floats(-0.6, 0.6),
    speed_b=st.floats(0.0, 1.0),
    heading_b=st.floats(0.0, TAU),
    accel_a=st.tuples(st.floats(-3.0, 3.0), st.floats(-3.0, 3.0)),
    accel_b=st.tuples(st.floats(-3.0, 3.0), st.floats(-3.0, 3.0)),
)
def test_first_collision_of_a_spinning_polygon_matches_brute_force(
    other, local_a, local_b, radius, angle_a, angle_b, omega_a, omega_b, direction, gap, speed, aim, speed_b,
    heading_b, accel_a, accel_b,
):
    """A spinning polygon's first contact (wall, circle, spinning polygon) is the brute-force one, -1e-9/+1e-12 s."""
    horizon = 1.5
    reach_a = float(np.hypot(local_a[:, 0], local_a[:, 1]).max())
    u = _unit(direction)
    centre_a = (0.0, 0.0)
    velocity_a = tuple(speed * c for c in _unit(direction + aim))
    world = World(bounds=(-3.0, -3.0, 3.0, 3.0), elasticity=1.0)
    a = world.add_polygon(local_a + centre_a, mass=1.0, velocity=velocity_a, acceleration=accel_a,
                          angle=angle_a, angular_velocity=omega_a)
    motion_a = Motion(centre_a, velocity_a, accel_a, angle_a, omega_a)
    if other == "wall":
        # A fixed slab 0.2 thick and 4 long whose near face is ``gap`` beyond a's bounding circle,
        # built axis-aligned and turned into place by the ``angle`` option.
        depth = reach_a + gap + 0.1
        wx, wy = depth * u[0], depth * u[1]
        b = world.add_box(wx - 0.1, wy - 2.0, 0.2, 4.0, fixed=True, angle=direction)
        local_b = np.array([(-0.1, -2.0), (0.1, -2.0), (0.1, 2.0), (-0.1, 2.0)])
        motion_b = Motion((wx, wy), angle=direction)
        reach_b, omega_b = 0.0, 0.0  # the fixed slab neither moves nor turns
        velocity_b, accel_b = (0.0, 0.0), (0.0, 0.0)
    else:
        reach_b = radius if other == "circle" else float(np.hypot(local_b[:, 0], local_b[:, 1]).max())
        distance = reach_a + reach_b + gap
        centre_b = (distance * u[0], distance * u[1])
        velocity_b = tuple(speed_b * c for c in _unit(heading_b))
        if other == "circle":
            b = world.add_circle(centre_b, radius, mass=0.7, velocity=velocity_b, acceleration=accel_b,
                                 angular_velocity=omega_b)
            reach_b = 0.0  # a circle's turning does not move its outline
        else:
            b = world.add_polygon(local_b + centre_b, mass=0.7, velocity=velocity_b, acceleration=accel_b,
                                  angle=angle_b, angular_velocity=omega_b)
        motion_b = Motion(centre_b, velocity_b, accel_b, angle_b, omega_b)

    def gap_at(t):
        t = np.asarray(t, float)
        A = motion_a.outline(local_a, t)
        if other == "circle":
            return circle_gap(np.stack(motion_b.centre(t), -1), radius, A)
        return polygon_gap(A, motion_b.outline(local_b, t))

    # The World must start from the same geometry.
    np.testing.assert_allclose(np.array(a.vertices), motion_a.outline(local_a, np.zeros(1))[0], rtol=0, atol=1e-14)
    if other != "circle":
        np.testing.assert_allclose(np.array(b.vertices), motion_b.outline(local_b, np.zeros(1))[0], rtol=0, atol=1e-14)

    dv = math.hypot(velocity_a[0] - velocity_b[0], velocity_a[1] - velocity_b[1])
    da = math.hypot(accel_a[0] - accel_b[0], accel_a[1] - accel_b[1])
    lipschitz = 1.01 * (dv + da * horizon + abs(omega_a) * reach_a + abs(omega_b) * reach_b) + 1e-12
    t_ref, unsure = first_contact(gap_at, horizon, lipschitz)
    # No graze the reference cannot call before the crossing (the approach itself leaves the
    # last few 1e-13 s intervals before it undecided).
    assume(unsure >= t_ref - 1e-10)
    if t_ref < math.inf:
        rate = float(gap_at(np.array([t_ref - 1e-7]))[0]) / 1e-7
        assume(rate > 1e-3)  # a graze may be reported or skipped; both are allowed

    event = next(e for e in world.events(horizon) if isinstance(e, (Collision, Stop)))
    if t_ref == math.inf:
        assert isinstance(event, Stop), f"reported {event!r}, but the shapes never touch before {horizon}"
        return
    assert isinstance(event, Collision), f"no collision reported; brute force finds one at {t_ref!r}"
    assert {event.a, event.b} == {a, b}
    error = event.time - t_ref
    assert -MATCH <= error <= LATE, f"engine {event.time!r} vs brute force {t_ref!r}: off by {error:.3g} s"
    # The bodies are where the closed form puts them, and the point lies on both outlines.
    np.testing.assert_allclose(np.array(a.vertices), motion_a.outline(local_a, np.array([event.time]))[0],
                               rtol=0, atol=1e-12)
    A = np.array([a.vertices])
    point = np.array([event.point])
    assert _point_outline_distance(point[:, None, :], A)[0] < 1e-9
    if other == "circle":
        assert abs(math.dist(event.point, b.position) - radius) < 1e-9
    else:
        assert _point_outline_distance(point[:, None, :], np.array([b.vertices]))[0] < 1e-9


# ------------------------------------------------------------------ 6. spinning in place next to a wall


@settings(max_examples=30, deadline=None)
@given(
    sides=st.integers(3, 8),
    circumradius=st.floats(0.05, 0.2),
    phase=st.floats(0.1, 0.9),
    turns=st.integers(-15, 15),
    omega=st.one_of(st.floats(0.5, 20.0), st.floats(-20.0, -0.5)),
    fraction=st.floats(0.05, 0.95),
)
def test_polygon_spinning_in_place_strikes_the_wall_when_a_corner_reaches_it(
    sides, circumradius, phase, turns, omega, fraction
):
    """A regular polygon turning in place (no translation) beside a wall at x = d hits it when its
    first corner reaches the angle -acos(d / R) (anticlockwise) or +acos(d / R) (clockwise)."""
    R = circumradius
    # No corner points straight at the wall (it could only graze it); whole turns test the
    # reduction of large angles.
    angle = (phase + turns * sides) * TAU / sides
    corners = [angle + TAU * k / sides for k in range(sides)]
    reach_now = max(R * math.cos(phi) for phi in corners)
    d = reach_now + fraction * (R - reach_now)
    alpha = math.acos(d / R)
    # Corner k sits at angle phi_k + omega t; it touches x = d at angle -alpha coming from below
    # (omega > 0) or at +alpha coming from above (omega < 0).
    if omega > 0:
        expected = min(((-alpha - phi) % TAU) / omega for phi in corners)
    else:
        expected = min(((phi - alpha) % TAU) / -omega for phi in corners)
    world = World(bounds=(-1.0, -1.0, 1.0, 1.0))
    body = world.add_polygon(regular_polygon(sides, R), mass=1.0, angle=angle, angular_velocity=omega)
    wall = world.add_box(d, -1.0, 0.5, 2.0, fixed=True)
    event = next(e for e in world.events(expected + 1.0) if not isinstance(e, Frame))
    assert isinstance(event, Collision), f"no collision; expected one at {expected!r}"
    assert {event.a, event.b} == {body, wall}
    assert -MATCH <= event.time - expected <= LATE, (event.time, expected)
    assert abs(event.point[0] - d) < 1e-9
    assert abs(event.point[1] - (-1.0 if omega > 0 else 1.0) * R * math.sin(alpha)) < 1e-9
    assert body.velocity[0] < 0.0  # pushed away from the wall


# ------------------------------------------------------------------ 3. hand-derived angular response

# Solid disc, mass m, radius r, I = m r^2 / 2, on a fixed floor (normal n = (0, 1), y up,
# anticlockwise omega positive), zero gravity so the impact velocity is exactly the initial one.
#
# The contact point is r_c = (0, -r) from the centre; its velocity is v + omega x r_c =
# (v_x - omega * (-r), v_y + omega * 0) = (v_x + omega r, v_y): the slip is u_t = v_x + omega r.
# An impulse J = (J_x, J_y) at r_c changes v by J / m and omega by (r_c x J) / I =
# (0 * J_y - (-r) J_x) / I = r J_x / I = 2 J_x / (m r). The normal and tangential directions do
# not couple (r_c is parallel to n), so J_y = j_n = (1 + e) m |v_y|, and the slip becomes
# u_t' = u_t + J_x / m + r * 2 J_x / (m r) = u_t + 3 J_x / m.
#
# Sticking (u_t' = 0): J_x = -m u_t / 3, allowed while |J_x| <= mu j_n; then
#     v_x' = v_x - u_t / 3,    omega' = omega - 2 u_t / (3 r).
# Sliding (|m u_t / 3| > mu j_n): J_x = -mu j_n sign(u_t); then
#     v_x' = v_x + J_x / m,    omega' = omega + 2 J_x / (m r).
# Either way v_y' = -e v_y.
#
# A ball hitting a wall on its right (n = (-1, 0), r_c = (r, 0)): the contact point moves at
# (v_x, v_y + omega r), slip s = v_y + omega r along y; j_n = (1 + e) m v_x; J_y changes omega
# by r J_y / I = 2 J_y / (m r) and s by 3 J_y / m. Sticking: J_y = -m s / 3, omega' =
# omega - 2 s / (3 r); sliding: J_y = -mu j_n sign(s). A ball rising into the wall
# (v_y > 0, omega = 0) therefore starts turning clockwise (omega' < 0).


def floor_disc_response(vx, vy, omega, mu, e, r, m):
    """Hand-derived ``(vx', vy', omega', j_n, sticks)`` for a disc striking a fixed floor."""
    slip = vx + omega * r
    jn = (1.0 + e) * m * abs(vy)
    if m * abs(slip) / 3.0 <= mu * jn:
        return vx - slip / 3.0, -e * vy, omega - 2.0 * slip / (3.0 * r), jn, True
    jx = -mu * jn * math.copysign(1.0, slip)
    return vx + jx / m, -e * vy, omega + 2.0 * jx / (m * r), jn, False


def _strike_floor(vx, vy, omega, mu, e, r, m):
    # the disc lands within 1.5 of x = 0.5 (|vx| <= 3, at most 0.5 s): the floor reaches past
    # that on both sides, so that it meets the face, never the floor's corner
    world = World(elasticity=e, bounds=(-2.0, -1.0, 3.0, 3.0))
    world.add_box(-2.0, -0.25, 7.0, 0.25, fixed=True, friction=mu, name="floor")
    gap = 0.05
    disc = world.add_circle((0.5, r + gap), r, mass=m, velocity=(vx, vy), angular_velocity=omega, friction=mu)
    event = next(e for e in world.events(1.0) if isinstance(e, (Collision, Stop)))
    assert isinstance(event, Collision)
    return event, disc, gap / -vy


def _close(got, want, scale):
    return abs(got - want) <= EXACT * scale


@pytest.mark.parametrize(
    "vx, vy, omega, mu, e, sticks",
    [
        (1.0, -2.0, 0.0, 1.0, 0.5, True),  # rolling starts: v' = 2/3, omega' = -20/3
        (1.0, -2.0, 0.0, 0.05, 0.5, False),  # slides: J_x = -0.05 * 6
        (0.0, -2.0, 30.0, 0.2, 0.8, False),  # the spin drags the contact point +x: thrown -x
        (0.0, -2.0, 30.0, 1.0, 0.8, True),
        (0.3, -1.0, -5.0, 1.0, 1.0, True),  # already nearly rolling
        (-0.7, -0.4, 12.0, 0.3, 0.0, False),
    ],
)
def test_spinning_disc_on_a_floor_sticks_or_slides_as_derived_by_hand(vx, vy, omega, mu, e, sticks):
    """A spinning disc bouncing off a floor with friction leaves with the hand-derived velocity and
    spin, sticking (v' = v - u/3, w' = w - 2u/(3r)) or sliding (J_t = -mu j_n sign u)."""
    r, m = 0.1, 2.0
    want_vx, want_vy, want_w, jn, want_sticks = floor_disc_response(vx, vy, omega, mu, e, r, m)
    assert want_sticks == sticks  # the case is the one intended
    event, disc, when = _strike_floor(vx, vy, omega, mu, e, r, m)
    scale = abs(vx) + abs(vy) + abs(omega) * r
    assert _close(event.time, when, when)
    assert _close(event.impulse, jn, jn)
    assert _close(event.approach_speed, -vy, -vy)
    got_vx, got_vy = disc.velocity
    assert _close(got_vx, want_vx, scale), (got_vx, want_vx)
    assert _close(got_vy, want_vy, scale), (got_vy, want_vy)
    assert _close(disc.angular_velocity, want_w, scale / r), (disc.angular_velocity, want_w)


@settings(max_examples=40, deadline=None)
@given(
    vx=st.floats(-3.0, 3.0),
    vy=st.floats(-3.0, -0.1),
    omega=st.floats(-40.0, 40.0),
    mu=st.floats(0.0, 1.5),
    e=st.floats(0.0, 1.0),
    r=st.floats(0.02, 0.2),
    m=st.floats(0.1, 10.0),
)
def test_disc_on_floor_matches_the_hand_derivation_for_any_spin(vx, vy, omega, mu, e, r, m):
    """For any spin, slip, friction and elasticity the disc's bounce follows the hand-derived stick/slide rule."""
    want_vx, want_vy, want_w, jn, sticks = floor_disc_response(vx, vy, omega, mu, e, r, m)
    slip = vx + omega * r
    assume(abs(m * abs(slip) / 3.0 - mu * jn) > 1e-9 * jn)  # not on the stick/slide boundary
    event, disc, _ = _strike_floor(vx, vy, omega, mu, e, r, m)
    scale = abs(vx) + abs(vy) + abs(omega) * r
    got_vx, got_vy = disc.velocity
    assert _close(event.impulse, jn, jn)
    assert _close(got_vx, want_vx, scale), (sticks, got_vx, want_vx)
    assert _close(got_vy, want_vy, scale), (sticks, got_vy, want_vy)
    assert _close(disc.angular_velocity, want_w, scale / r), (sticks, disc.angular_velocity, want_w)


@pytest.mark.parametrize("side", [1.0, -1.0])  # wall on the right, wall on the left
@pytest.mark.parametrize("vy", [0.8, -0.8])
@pytest.mark.parametrize("mu", [1.0, 0.1])
def test_ball_hitting_a_wall_with_friction_starts_spinning(side, vy, mu):
    """A non-spinning ball striking a wall obliquely with friction leaves spinning: stuck, omega' =
    -side * 2 v_y / (3 r); sliding, omega' = -side * 2 mu j_n sign(v_y) / (m r) (side = +1: wall on its right)."""
    r, m, e, vx = 0.1, 1.5, 0.6, 2.0
    world = World(elasticity=e, bounds=(-2.0, -2.0, 2.0, 2.0))
    x_wall = side * 0.5
    world.add_box(x_wall if side > 0 else x_wall - 0.3, -2.0, 0.3, 4.0, fixed=True, friction=mu)
    ball = world.add_circle((x_wall - side * (r + 0.1), 0.0), r, mass=m, velocity=(side * vx, vy))
    event = next(e for e in world.events(1.0) if isinstance(e, (Collision, Stop)))
    assert isinstance(event, Collision)
    jn = (1.0 + e) * m * vx
    # The contact point is at (side r, 0): its velocity is (v_x, v_y + side omega r), the slip
    # s = v_y (omega = 0), and J_y turns the ball by side r J_y / I = side 2 J_y / (m r).
    if m * abs(vy) / 3.0 <= mu * jn:
        want = -side * 2.0 * vy / (3.0 * r)
        want_vy = vy - vy / 3.0
    else:
        jy = -mu * jn * math.copysign(1.0, vy)
        want = side * 2.0 * jy / (m * r)
        want_vy = vy + jy / m
    assert ball.angular_velocity != 0.0
    assert math.copysign(1.0, ball.angular_velocity) == -side * math.copysign(1.0, vy)
    assert _close(ball.angular_velocity, want, abs(want))
    assert _close(ball.velocity[1], want_vy, abs(vy))
    assert _close(ball.velocity[0], -side * e * vx, vx)


# ------------------------------------------------------------------ random scenes (2 and 4)


def _random_outline(rng, reach):
    """Corners (world-free, about 0) of a regular or random convex polygon of circumradius <= reach."""
    sides = rng.randint(3, 8)
    if rng.random() < 0.5:
        return regular_polygon(sides, reach, (0.0, 0.0), rng.uniform(0.0, TAU))
    start = rng.uniform(0.0, TAU)
    weights = [rng.uniform(1.0, 1.8) for _ in range(sides)]
    total = sum(weights)
    points, angle = [], start
    for w in weights:
        rad = rng.uniform(0.6 * reach, reach)
        points.append((rad * math.cos(angle), rad * math.sin(angle)))
        angle += TAU * w / total
    hull = convex_hull(points)
    return hull if len(hull) >= 3 else regular_polygon(3, reach)


def build_spinning_scene(seed, count, elastic, gravity, friction, frame_rate=10.0):
    """A unit box of four fixed walls holding ``count`` circles and spinning polygons.

    ``elastic``: every elasticity 1, else each body's in [0, 0.95]; ``friction``: each body's
    coefficient in [0, 1], else 0 everywhere. Returns ``(world, walls, bodies)``.
    """
    rng = random.Random(seed)
    world = World(gravity=(0.0, -G if gravity else 0.0), elasticity=1.0, frame_rate=frame_rate)
    walls = [
        world.add_box(-0.1, -0.1, 1.2, 0.1, fixed=True, name="floor"),
        world.add_box(-0.1, 1.0, 1.2, 0.1, fixed=True, name="ceiling"),
        world.add_box(-0.1, -0.1, 0.1, 1.2, fixed=True, name="left"),
        world.add_box(1.0, -0.1, 0.1, 1.2, fixed=True, name="right"),
    ]
    placed, bodies = [], []
    for _ in range(count):
        reach = rng.uniform(0.03, 0.07)
        for _ in range(10000):
            cx, cy = rng.uniform(reach + 2e-3, 1 - reach - 2e-3), rng.uniform(reach + 2e-3, 1 - reach - 2e-3)
            if all(math.hypot(cx - x, cy - y) > reach + s + 2e-3 for x, y, s in placed):
                break
        else:
            raise RuntimeError(f"cannot place a body (seed {seed})")
        placed.append((cx, cy, reach))
        heading, speed = rng.uniform(0.0, TAU), rng.uniform(0.0, 1.5)
        options = {
            "mass": rng.uniform(0.5, 2.0),
            "velocity": (speed * math.cos(heading), speed * math.sin(heading)),
            "angular_velocity": rng.uniform(-20.0, 20.0),
            "elasticity": 1.0 if elastic else rng.uniform(0.0, 0.95),
            "friction": rng.uniform(0.0, 1.0) if friction else 0.0,
        }
        if rng.random() < 0.35:
            bodies.append(world.add_circle((cx, cy), reach, **options))
        else:
            corners = [(cx + x, cy + y) for x, y in _random_outline(rng, reach)]
            bodies.append(world.add_polygon(corners, **options))
    for wall in walls:
        wall.friction = rng.uniform(0.0, 1.0) if friction else 0.0
    return world, walls, bodies


def _extent_beyond_box(body):
    """How far a body reaches outside the unit square (negative: inside by that much)."""
    if body.kind == "circle":
        x, y = body.position
        r = body.shape.radius
        return max(-(x - r), x + r - 1.0, -(y - r), y + r - 1.0)
    v = np.array(body.vertices)
    return float(max(-v[:, 0].min(), v[:, 0].max() - 1.0, -v[:, 1].min(), v[:, 1].max() - 1.0))


WALL_REACH = math.hypot(0.6, 0.05)


def worst_overlap(world, bodies, within_islands=None):
    """``(relative depth, description)`` of the deepest overlap now, walls included, from public
    positions and vertices; the depth is relative to the sum of the two bounding radii.
    ``within_islands`` True or False: only pairs whose contact an island's step solves (both
    bodies in one island, or a body of an island and a wall), or only the others."""
    reach = np.array([b.bounding_radius for b in bodies])
    pos = world.positions(bodies)
    worst, what = -math.inf, ""
    islands = world._islands

    def island(body):
        return None if islands is None else islands.of(body.id)

    def counted(a, b=None):
        if within_islands is None:
            return True
        inside = island(a) is not None and (b is None or island(b) is island(a))
        return inside == within_islands

    # Walls: the box's inside is the unit square, so reaching out of it is overlapping a wall.
    near = np.flatnonzero((pos - reach[:, None] < 0.0).any(1) | (pos + reach[:, None] > 1.0).any(1))
    for i in near:
        depth = _extent_beyond_box(bodies[i]) / (reach[i] + WALL_REACH)
        if depth > worst and counted(bodies[i]):
            worst, what = depth, f"{bodies[i].label()} reaches out of the box"
    distance = np.hypot(*(pos[:, None, :] - pos[None, :, :]).transpose(2, 0, 1))
    close = np.argwhere(np.triu(distance < reach[:, None] + reach[None, :], 1))
    for i, j in close:
        depth = -body_gap(bodies[i], bodies[j]) / (reach[i] + reach[j])
        if depth > worst and counted(bodies[i], bodies[j]):
            worst, what = depth, f"{bodies[i].label()} and {bodies[j].label()}"
    return worst, what


#: the random spinning scenes of the overlap tests (``build_spinning_scene``'s arguments)
SPINNING_SCENES = {
    "seed": st.integers(0, 2**32 - 1),
    "count": st.integers(5, 15),
    "elastic": st.booleans(),
    "gravity": st.booleans(),
    "friction": st.booleans(),
}

#: the deepest overlap an island's step may leave between bodies whose
#: contact it solves (docs/contact.md, "Exact and integrated"), relative to the sum of the
#: two bounding radii: about MAX_TURN^2 / 2 of a reach per step, pushed out at the next; a
#: contact that changes feature within a step (a turning polygon sliding fast past a circle,
#: a polygon spinning at 34 rad/s whose next corner comes round) leaves more (measured: at
#: most 5.8e-4 in 110 random scenes, most below 6e-5)
ISLAND_OVERLAP = 1e-3


def beyond_bounds(world, bodies):
    """The deepest overlaps now as ``(outside, inside, failure)``: relative depths of pairs no
    island holds and of pairs an island's step holds, and a description of the first beyond its
    bound (``OVERLAP``, ``ISLAND_OVERLAP``), or None."""
    outside, what_out = worst_overlap(world, bodies, within_islands=False)
    inside, what_in = worst_overlap(world, bodies, within_islands=True)
    failure = None
    if outside > OVERLAP:
        failure = f"{outside:.3g} ({what_out})"
    elif inside > ISLAND_OVERLAP:
        failure = f"{inside:.3g} within an island ({what_in})"
    return outside, inside, failure


def run_overlap_scene(seed, count, elastic, gravity, friction):
    """Run a scene for 10 s (or SCENE_EVENTS events), checking overlaps at every event and frame."""
    world, _, bodies = build_spinning_scene(seed, count, elastic, gravity, friction)
    worst, first_bad, events, end = [-math.inf, -math.inf], None, 0, 0.0
    for event in world.events(10.0):
        events += 1
        end = event.time
        outside, inside, failure = beyond_bounds(world, bodies)
        worst = [max(worst[0], outside), max(worst[1], inside)]
        if failure and first_bad is None:
            first_bad = f"{failure} at {event!r}"
        if events >= SCENE_EVENTS:
            break
    return {"worst": worst, "first_bad": first_bad, "events": events, "end": end, "stats": world.stats}


@SCENE_SETTINGS
@given(**SPINNING_SCENES)
@example(seed=0, count=5, elastic=False, gravity=False, friction=False)  # 4.7e-3 before MAX_TURN
def test_random_rotating_scenes_never_overlap_and_stay_in_the_box(seed, count, elastic, gravity, friction):
    """Circles and spinning polygons in a closed box, at every event and frame of their first 10 s
    or 1500 events: pairs whose contact no island solves never overlap by more than 1e-9 of their
    sizes; pairs an island's step holds, by no more than ``ISLAND_OVERLAP`` (its integration
    error); nothing leaves the box by more than either (the fixed scenes below run the whole 10 s)."""
    # the overlap checks at every event cost more than the run (scene 2860 of 14 bodies: 1.1 s
    # of running, 8 s of checking), so the watchdog is the fixed scenes' 60 s, not WATCHDOG
    result = guarded(run_overlap_scene, seed, count, elastic, gravity, friction, timeout=60.0)
    assert result["first_bad"] is None, f"overlap {result['first_bad']}; {result['events']} events"
    assert result["worst"][0] <= OVERLAP and result["worst"][1] <= ISLAND_OVERLAP


@pytest.mark.parametrize(
    "seed, count, elastic, gravity, friction",
    [
        (1, 10, False, True, False),  # settling flat turned a polygon into a wedged circle (8.2e-6)
        (6, 10, False, True, False),  # the same (3.1e-5)
        (8, 10, False, False, False),  # three circles at one instant: an event storm
        (11, 10, False, True, False),  # a circle released at a corner, separating by rounding
        (13, 10, False, True, False),  # and pressed on: no contact was predicted (2.4e-5)
        (4294967294, 12, False, False, True),  # a circle squeezed between two: an event storm
        (660, 12, False, True, True),  # a corner missed beside an edge plane that rounded clear (3e-9)
    ],
)
def test_surveyed_scenes_that_overlapped_or_stormed(seed, count, elastic, gravity, friction):
    """Scenes of ``tools/repro/survey.py overlap`` that overlapped or stormed under the former
    resting-contact rules, over the first 1500 events, within the bounds of
    ``test_random_rotating_scenes_never_overlap_and_stay_in_the_box``. Seed 11 also covers a step
    after an impact that set a polygon spinning faster: it is cut to ``MAX_TURN`` too (0.0039
    of the reaches when it was not)."""
    result = guarded(run_overlap_scene, seed, count, elastic, gravity, friction, timeout=60.0)
    assert result["first_bad"] is None, f"overlap {result['first_bad']}; {result['events']} events"
    assert result["events"] >= 1000 or result["end"] >= 10.0


def run_scene_to(seed, count, elastic, gravity, friction, end):
    """Run a scene to ``end`` with no checks; returns its time and event count."""
    world, _, _ = build_spinning_scene(seed, count, elastic, gravity, friction)
    world.run_until(end)
    return {"end": world.time, "events": world.stats["events"]}


@pytest.mark.parametrize(
    "seed",
    [
        212,  # riders on two faces of one sliding polygon released each other (rest nudges)
        250,  # the same (tools/repro/repro_rider_pingpong.py)
        289,  # the same, at t = 0.54
        339,  # the same, at t = 0.30
        369,  # a rider leaving its edge at the end, judged on the edge by the kernel (t = 0.23),
              # then a support pinned on a wall nudged by rests (t = 0.98)
        488,  # a rider leaving its edge at the end, met by the edge's plane 1e-17 s later (t = 0.72)
    ],
)
def test_surveyed_scenes_that_stormed_at_one_instant_run_on(seed):
    """Scenes of ``survey.py overlap --seeds 200 400 --count 12`` (inelastic, gravity, no friction)
    that ended in the event-storm error under the former resting-contact rules (riders on a
    sliding support, a circle sliding off an edge's end) run to t = 1 s."""
    result = guarded(run_scene_to, seed, 12, False, True, False, 1.0, timeout=60.0)
    assert result["end"] == 1.0


@pytest.mark.parametrize("seed, count", [(748, 15), (104, 10), (183, 10)])
def test_a_face_meeting_a_wall_at_one_instant_stops_instead_of_decaying_for_ever(seed, count):
    """Surveyed scenes without gravity (inelastic, friction) where a polygon meets a wall with a
    face: its two corners collide in turn at one instant, the velocity shrinking by a constant
    factor each time, down into denormal numbers (a NaN swept box, then a circle 6% inside it in
    seed 748), or, with the box kept finite, until the event-storm error (104 and 183 are scenes of
    ``survey.py energy``). Such a run of impacts now joins the pair into an island, whose step
    takes both corners at once."""
    result = guarded(run_scene_to, seed, count, False, False, True, 10.0, timeout=60.0)
    assert result["end"] == 10.0


def run_full_scene(seed, count, elastic, gravity, friction):
    """Run a scene to t = 10 s with no event budget, checking overlaps at every event."""
    world, _, bodies = build_spinning_scene(seed, count, elastic, gravity, friction)
    first_bad, events = None, 0
    for event in world.events(10.0):
        events += 1
        failure = beyond_bounds(world, bodies)[2]
        if failure and first_bad is None:
            first_bad = f"{failure} at {event!r}"
    return {"first_bad": first_bad, "events": events, "end": world.time}


FULL_SETTINGS = [
    (elastic, gravity, friction)
    for elastic in (False, True)
    for gravity in (False, True)
    for friction in (False, True)
    if (elastic, gravity, friction) != (False, True, False)  # 2e5 events: checked by hand (notes)
]


@pytest.mark.parametrize("seed", [1, 3])
@pytest.mark.parametrize("elastic, gravity, friction", FULL_SETTINGS)
def test_random_rotating_scenes_run_the_full_10_s_without_overlap(seed, elastic, gravity, friction):
    """The issue's "no overlaps beyond 1e-9 in random rotating scenes over 10 s", on fixed scenes run
    to the end (the random draws above stop after 1500 events): every event, 10 bodies."""
    result = guarded(run_full_scene, seed, 10, elastic, gravity, friction, timeout=60.0)
    assert result["end"] == 10.0
    assert result["first_bad"] is None, f"overlap {result['first_bad']}; {result['events']} events"


def run_sampled_scene(seed, count, elastic, gravity, friction, sample=0.01):
    """Run a scene to t = 10 s, checking overlaps every ``sample`` seconds (for scenes of 1e5 events
    and more, where a check at every event would cost minutes)."""
    world, _, bodies = build_spinning_scene(seed, count, elastic, gravity, friction)
    first_bad = None
    for k in range(1, round(10.0 / sample) + 1):
        world.run_until(k * sample)
        failure = beyond_bounds(world, bodies)[2]
        if failure and first_bad is None:
            first_bad = f"{failure} by t = {k * sample:.2f}"
    return {"first_bad": first_bad, "events": world.stats["events"], "end": world.time}


def test_inelastic_frictionless_piles_run_the_full_10_s_without_overlap():
    """The setting left out above, sampled every 0.01 s: seed 0 is the squeeze of four bodies on a
    frictionless floor that overlapped by 3.3e-6 at t = 8.107 (tools/repro/repro_squeeze_overlap.py:
    circle_polygon lost a contact touching to rounding and pushed back), 1.4e5 events."""
    result = guarded(run_sampled_scene, 0, 10, False, True, False, timeout=120.0)
    assert result["end"] == 10.0
    assert result["first_bad"] is None, f"overlap {result['first_bad']}; {result['events']} events"


def mechanical_energy(world, bodies, masses):
    """Kinetic (with rotation) plus gravitational potential energy of ``bodies`` (zero at y = 0)."""
    return world.kinetic_energy() - world.gravity[1] * float(masses @ world.positions(bodies)[:, 1])


def run_energy_scene(seed, count, gravity):
    """Run a frictional, partly inelastic spinning scene; compare the energy after each collision
    with the one after the previous: relative to it without gravity, else to the scene's scale
    (its initial energy plus sum m g x the box height, as potential energy has no natural zero)."""
    world, _, bodies = build_spinning_scene(seed, count, elastic=False, gravity=gravity, friction=True,
                                            frame_rate=None)
    masses = np.array([b.mass for b in bodies])
    before = mechanical_energy(world, bodies, masses)
    scale = before + G * masses.sum() if gravity else None
    worst, first_bad, collisions = -math.inf, None, 0
    for event in world.events(10.0):
        if not isinstance(event, Collision):
            continue
        collisions += 1
        now = mechanical_energy(world, bodies, masses)
        gain = (now - before) / (scale or before)
        worst = max(worst, gain)
        if gain > ENERGY and first_bad is None:
            first_bad = f"+{gain:.3g} relative ({now - before:.3g} J) at {event!r}"
        before = now
        if collisions >= SCENE_EVENTS:
            break
    return {"worst": worst, "first_bad": first_bad, "collisions": collisions}


@SCENE_SETTINGS
@given(seed=st.integers(0, 2**32 - 1), count=st.integers(5, 12))
def test_energy_never_increases_at_collisions_without_gravity(seed, count):
    """With friction 0..1, elasticities 0..0.95 and spins, no collision raises the kinetic energy
    (rotation included) by more than 1e-12 of itself."""
    result = guarded(run_energy_scene, seed, count, False)
    assert result["first_bad"] is None, f"energy gain {result['first_bad']}"


@pytest.mark.parametrize(
    "seed, count, gravity",
    [(22701449, 9, False), (60789, 12, False), (266105701, 12, False), (1777590724, 12, False), (58, 10, True),
     (170, 10, True)],
)
def test_spinning_scenes_with_islands_gain_no_energy_at_collisions(seed, count, gravity):
    """Scenes that gained energy between collisions: an island's step
    cut short (by a bounce) pushed an overlap out with a lift as large as the overlap over the
    short step, and the lift showed as kinetic energy (+7.9 % in the first scene). The
    push-out's rate is now per natural step: without gravity no collision shows a gain; with
    it, none beyond a step's integration error (docs/contact.md, "Energy": 2e-7 of the
    scene's energy). In the second, a circle riding a turning polygon without gravity gained
    1e-11 of the scene's energy at every step (friction stopping at each step's end a slip
    its point had at the start), +1.2e-10 by a collision 15 steps later: the energy stage
    takes such work out. In the third and fourth, a collision inside a step saw less energy
    than the step's end (+2.6e-7 and +1.6e-7): a spinning polygon rubbing a circle, whose
    forces' power rose through zero in each step (the energy stage now keeps it non-positive
    at both ends)."""
    result = guarded(run_energy_scene, seed, count, gravity)
    assert result["worst"] <= (ISLAND_ENERGY if gravity else ENERGY), f"energy gain {result['first_bad']}"
    assert result["collisions"] > 50


def energy_inside_steps(seed, count, start, stop, samples):
    """The kinetic energy of a spinning scene without gravity at ``samples`` times from
    ``start`` to ``stop``, most of them inside island steps."""
    world, _, _ = build_spinning_scene(seed, count, elastic=False, gravity=False, friction=True, frame_rate=None)
    world.run_until(start)
    energies = []
    for t in np.linspace(start, stop, samples):
        world.run_until(float(t))
        energies.append(world.kinetic_energy())
    return energies


def test_energy_falls_all_through_an_island_step():
    """A spinning polygon rubbing a circle, no gravity, no collision in the window: the
    kinetic energy sampled 20 times a step never rises. It used to dip by 7e-7 of itself in
    the middle of each step and come back by its end (the forces' power, linear in time over
    a step, negative at its start and positive at its end)."""
    energies = guarded(energy_inside_steps, 266105701, 12, 0.3026, 0.3120, 700)
    rises = np.diff(energies) / energies[0]
    assert rises.max() <= ENERGY
    assert energies[-1] < energies[0]


@pytest.mark.parametrize(
    "seed",
    [
        12,  # a neighbour leans on the side the corner tips to: the corner slides as it tips
        15,  # the same
        3,  # a polygon on a corner pinched between a wall and a polygon pressing down on it
        36,  # the corner body itself resting: the bodies pressing on the pair pay
        58,  # a resting circle pressed by a free polygon's face: the same
        96,  # the same
        76,  # nothing in the pile round the pair can pay: the richest bodies of the world do
        119,  # the same
        170,  # the same, out of two free bodies and a resting circle's spin
        198,  # a tip whose corner slid up a sloping face (it must not: the slide's work counts)
        141,  # a ball coming to rest on the side of a sliding box (the box takes its share)
        155,  # piles whose free bodies had less kinetic energy than a lift of the rules needed
    ],
)
def test_surveyed_scenes_where_a_lift_went_unpaid_gain_no_energy(seed):
    """Surveyed scenes (``survey.py energy --gravity``, 10 bodies) where a collision gained energy
    (+5e-9 to +9e-7 of the scene's energy scale) under the former resting-contact rules, mostly a
    lift of a corner pressed shut by spin that nothing paid for. Islands solve such contacts
    with the floor's push: no step gains energy, and a collision that falls inside an
    island's step sees at most what the step's constant forces lend and take back within it
    (``ISLAND_ENERGY``; docs/contact.md, "Energy": seed 58 shows +2.3e-9 of its scale at a
    collision 0.9 ms into a step, back below the step's start at the next one)."""
    result = guarded(run_energy_scene, seed, 10, True)
    assert result["worst"] <= ISLAND_ENERGY, f"energy gain {result['first_bad']}"


@SCENE_SETTINGS
@given(seed=st.integers(0, 2**32 - 1), count=st.integers(5, 12))
@example(seed=3325, count=5)  # a slide chosen under old loads, driven by its friction
@example(seed=3992, count=9)  # +2.9e-7 between two collisions, inside the step of a corner lifting off
def test_energy_never_increases_at_collisions_under_gravity(seed, count):
    """Under gravity, kinetic plus potential energy, compared from one collision to the next, never
    rises by more than the islands' integration error in between (``ISLAND_ENERGY`` of the scene's
    energy scale: its initial energy plus sum m g x the box height)."""
    result = guarded(run_energy_scene, seed, count, True)
    assert result["worst"] <= ISLAND_ENERGY, f"energy gain {result['first_bad']}"


# ------------------------------------------------------------------ 5. a tilted box tips over and lies flat


BOX_WIDTH, BOX_HEIGHT, BOX_DROP = 0.2, 0.1, 0.25


def drop_tilted_box(tilt_degrees, mu):
    """Drop a 0.2 x 0.1 box turned by ``tilt_degrees`` onto a floor (top face y = 0) from
    ``BOX_DROP`` under gravity; returns what the test checks, as plain values."""
    world = World(gravity=(0.0, -G), elasticity=0.5, bounds=(-1.0, -1.0, 3.0, 3.0))
    floor = world.add_box(-1.0, -0.25, 6.0, 0.25, fixed=True, friction=mu, name="floor")
    cx, cy = 1.0, BOX_DROP + 0.5 * math.hypot(BOX_WIDTH, BOX_HEIGHT)
    box = world.add_box(cx - BOX_WIDTH / 2, cy - BOX_HEIGHT / 2, BOX_WIDTH, BOX_HEIGHT, mass=1.0,
                        angle=math.radians(tilt_degrees), friction=mu)
    first = next(e for e in world.events(5.0) if isinstance(e, (Collision, Stop)))
    seen = {
        "first": None if isinstance(first, Stop) else (first.time, {first.a.name, first.b.name}, first.point),
        "spin_after_first": box.angular_velocity,
    }
    seen["collisions"] = sum(1 for e in world.events(10.0) if isinstance(e, Collision))
    seen["resting"] = box.resting_on is floor
    seen["angle"], seen["spin"], seen["vertices"] = box.angle, box.angular_velocity, box.vertices
    seen["later"] = [e.time for e in world.events(world.time + 5.0) if isinstance(e, Collision)]
    seen["resting_later"] = box.resting_on is floor and box.angular_velocity == 0.0
    return seen


@pytest.mark.parametrize("tilt_degrees", [30.0, -30.0, 20.0, 70.0])
@pytest.mark.parametrize("mu", [0.0, 0.5])
def test_box_dropped_on_a_corner_turns_and_comes_to_rest_flat(tilt_degrees, mu):
    """A box dropped tilted first strikes the floor with its lowest corner at sqrt(2 h / g), starts
    turning (frictionless: towards the side its centroid overhangs), and ends resting flat on a face."""
    tilt = math.radians(tilt_degrees)
    cx, cy = 1.0, BOX_DROP + 0.5 * math.hypot(BOX_WIDTH, BOX_HEIGHT)
    c, s = math.cos(tilt), math.sin(tilt)
    half_w, half_h = BOX_WIDTH / 2, BOX_HEIGHT / 2
    corners = [(c * x - s * y, s * x + c * y) for x in (-half_w, half_w) for y in (-half_h, half_h)]
    low = min(corners, key=lambda p: p[1])
    seen = guarded(drop_tilted_box, tilt_degrees, mu)
    assert seen["first"] is not None, "the box never reached the floor"
    time, names, point = seen["first"]
    assert names == {None, "floor"}
    assert abs(time - math.sqrt(2.0 * (cy + low[1]) / G)) < 1e-12
    assert math.dist(point, (cx + low[0], 0.0)) < 1e-9  # the lowest corner, nothing else
    assert seen["spin_after_first"] != 0.0
    if mu == 0.0:
        # The floor's push J_y > 0 at the corner, x_r across from the centroid, has the
        # torque x_r J_y: it lifts that corner's side and lowers the other.
        assert math.copysign(1.0, seen["spin_after_first"]) == math.copysign(1.0, low[0])
    assert seen["resting"], f"not resting on the floor after {seen['collisions']} more collisions"
    quarter = seen["angle"] / (math.pi / 2)
    assert abs(quarter - round(quarter)) * (math.pi / 2) < 1e-9, seen["angle"]
    assert seen["spin"] == 0.0
    ys = sorted(y for _, y in seen["vertices"])
    assert -1e-9 <= ys[0] and ys[1] <= 1e-9  # a whole face on the floor, none of it below
    assert seen["later"] == []
    assert seen["resting_later"]


# ------------------------------------------------------------------ 7. determinism


def _hex(values):
    return tuple(float(v).hex() for v in values)


def trace(seed):
    """Bit-exact record of every event of a spinning, frictional, inelastic scene under gravity,
    and the final state (positions, velocities, angles, spins)."""
    world, _, bodies = build_spinning_scene(seed, 10, elastic=False, gravity=True, friction=True, frame_rate=20.0)
    records = []
    for event in world.events(3.0):
        if isinstance(event, Collision):
            records.append(("c", event.time.hex(), event.a.id, event.b.id, _hex(event.point), _hex(event.normal),
                            event.impulse.hex(), event.approach_speed.hex()))
        else:
            records.append((event.kind, float(event.time).hex()))
        if len(records) >= SCENE_EVENTS:
            break
    state = [(b.id, _hex(b.position), _hex(b.velocity), b.angle.hex(), b.angular_velocity.hex()) for b in bodies]
    return records, state, world.stats


def traces(seed, count):
    """``count`` traces of scene ``seed``, one after another in this process."""
    return [trace(seed) for _ in range(count)]


@pytest.mark.parametrize("seed", [3, 11])
def test_same_rotating_scene_gives_a_bit_identical_event_trace(seed):
    """A spinning, frictional scene run twice in one process and again in another gives the same
    events and final state to the bit."""
    first, second = guarded(traces, seed, 2)
    (third,) = guarded(traces, seed, 1)
    assert sum(1 for r in first[0] if r[0] == "c") > 50  # a trace worth comparing
    assert first == second
    assert first == third


@pytest.mark.parametrize("tilt_degrees", [30.0, -50.0, 5.0])
def test_box_set_down_still_on_a_corner_tips_over_and_lies_flat(tilt_degrees):
    """A box set down at rest on one corner (no spin, no speed) with its centroid beside the corner
    tips over: it is not allowed to rest balanced on the corner (it did, for ever, when it came to
    rest without turning), and ends resting flat on a face."""
    world = World(gravity=(0.0, -G), elasticity=0.5, bounds=(-1.0, -1.0, 3.0, 3.0))
    floor = world.add_box(-1.0, -0.25, 6.0, 0.25, fixed=True, friction=0.8, name="floor")
    tilt = math.radians(tilt_degrees)
    c, s = math.cos(tilt), math.sin(tilt)
    corners = [(c * x - s * y, s * x + c * y) for x in (-BOX_WIDTH / 2, BOX_WIDTH / 2) for y in (-BOX_HEIGHT / 2, BOX_HEIGHT / 2)]
    low = min(y for _, y in corners)
    box = world.add_box(1.0 - BOX_WIDTH / 2, -low - BOX_HEIGHT / 2 - 1e-12, BOX_WIDTH, BOX_HEIGHT, mass=1.0,
                        angle=tilt, friction=0.8)
    masses = np.array([1.0])
    scale = mechanical_energy(world, [box], masses) + G
    before = mechanical_energy(world, [box], masses)
    for event in world.events(3.0):
        if isinstance(event, Collision):
            now = mechanical_energy(world, [box], masses)
            assert now - before <= ENERGY * scale, f"gained {now - before:.3g} J at {event!r}"
            before = now
    # It turned by the push of the floor at its corner alone, and lies on a face asleep.
    assert box.resting_on is floor and box.asleep and box.angular_velocity == 0.0
    quarter = box.angle / (math.pi / 2)
    assert abs(quarter - round(quarter)) * (math.pi / 2) < 1e-9, box.angle
    ys = sorted(y for _, y in box.vertices)
    assert -1e-9 <= ys[0] and ys[1] <= 1e-9
