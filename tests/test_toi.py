"""Time-of-impact kernels against a brute-force reference.

The reference computes the exact distance between the two shapes (point-segment
distances, and the separating-axis value when they overlap) independently of
the engine, samples it finely over [0, H], refines every local minimum between
samples (a dip can hide between two samples) and bisects the first sign change.
The kernel's time must match it to 1e-9 and must not be later: at the returned
time the shapes may not overlap by more than 1e-12. Misses must agree, except
for grazing contacts whose deepest overlap is within 1e-9 of zero, which may go
either way.
"""

from __future__ import annotations

import math
from decimal import Decimal

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from strategies import (
    centred,
    convex_polygons,
    radii,
    regular_polygon,
    regular_polygons,
    vectors,
)

from pge.toi import (
    circle_circle,
    circle_circle_contact,
    circle_polygon,
    circle_polygon_contact,
    outline_rows,
    polygon_polygon,
    polygon_polygon_contact,
)

INF = math.inf
SAMPLES = 4001
TIME_TOL = 1e-9  # kernel time vs reference time
GRAZE = 1e-9  # a dip no deeper than this may be reported or not
LATE = 1e-12  # overlap allowed at the reported time ("never later")
ON_SHAPE = 1e-9  # contact point on both shapes


# ------------------------------------------------------------------ independent geometry


def _edges(local):
    """Vertices, unit outward normals, edge vectors and lengths of an anticlockwise polygon."""
    v = np.asarray(local, dtype=float)
    e = np.roll(v, -1, axis=0) - v
    length = np.hypot(e[:, 0], e[:, 1])
    normal = np.stack([e[:, 1] / length, -e[:, 0] / length], axis=1)
    return v, normal, e, length


def point_polygon_signed_distance(points, local):
    """Signed distance of points (..., 2) to the polygon (negative inside)."""
    v, normal, e, length = _edges(local)
    q = points[..., None, :] - v  # (..., n, 2)
    s = np.einsum("...nk,nk->...n", q, normal)
    u = np.clip(np.einsum("...nk,nk->...n", q, e) / (length * length), 0.0, 1.0)
    foot = q - u[..., None] * e
    outside = np.min(np.hypot(foot[..., 0], foot[..., 1]), axis=-1)
    inside = np.max(s, axis=-1)
    return np.where(inside > 0.0, outside, inside)


def circle_circle_gap(ts, d, v, a, ra, rb):
    ts = np.asarray(ts, dtype=float)[:, None]
    p = np.asarray(d) + np.asarray(v) * ts + 0.5 * np.asarray(a) * ts * ts
    return np.hypot(p[:, 0], p[:, 1]) - (ra + rb)


def circle_polygon_gap(ts, p0, v, a, radius, local):
    ts = np.asarray(ts, dtype=float)[:, None]
    c = np.asarray(p0) + np.asarray(v) * ts + 0.5 * np.asarray(a) * ts * ts
    return point_polygon_signed_distance(c, local) - radius


def _vertices_to_edges(P, V, E, length):
    """Smallest distance from points P (T, m, 2) to the segments V + u E (T or 1, n, 2): shape (T,)."""
    q = P[:, :, None, :] - V[:, None, :, :]
    u = np.clip(np.einsum("tijk,tjk->tij", q, np.broadcast_to(E, V.shape)) / (length * length), 0.0, 1.0)
    foot = q - u[..., None] * E
    return np.min(np.hypot(foot[..., 0], foot[..., 1]), axis=(1, 2))


def polygon_polygon_distance(offsets, local_a, local_b):
    """Distance between polygon a (centroid at ``offsets``, shape (T, 2)) and b (at the origin);
    when they overlap, the (negative) largest separation over all edge normals."""
    va, na, ea, la = _edges(local_a)
    vb, nb, eb, lb = _edges(local_b)
    T = offsets.shape[0]
    A = offsets[:, None, :] + va[None, :, :]  # a's vertices, (T, na, 2)
    B = np.broadcast_to(vb[None, :, :], (T,) + vb.shape)
    # separating axes: b's edges (a's vertices against them), then a's edges (b's vertices)
    sep_b = np.max(np.min(np.einsum("tik,jk->tij", A, nb), axis=1) - np.sum(vb * nb, axis=1), axis=1)
    sep_a = np.max(np.min(vb @ na.T, axis=0)[None, :] - np.einsum("tjk,jk->tj", A, na), axis=1)
    sat = np.maximum(sep_a, sep_b)
    dist = np.minimum(
        _vertices_to_edges(A, vb[None, :, :], eb[None, :, :], lb),
        _vertices_to_edges(B, A, ea[None, :, :], la),
    )
    return np.where(sat > 0.0, dist, sat)


def polygon_polygon_gap(ts, d, v, a, local_a, local_b):
    ts = np.asarray(ts, dtype=float)[:, None]
    offsets = np.asarray(d) + np.asarray(v) * ts + 0.5 * np.asarray(a) * ts * ts
    return polygon_polygon_distance(offsets, local_a, local_b)


def _golden_min(f, lo, hi, iterations=80):
    """Minimum of a unimodal-ish scalar function on [lo, hi]: (t, value)."""
    ratio = (math.sqrt(5.0) - 1.0) / 2.0
    x1 = hi - ratio * (hi - lo)
    x2 = lo + ratio * (hi - lo)
    f1, f2 = f(x1), f(x2)
    for _ in range(iterations):
        if f1 <= f2:
            hi, x2, f2 = x2, x1, f1
            x1 = hi - ratio * (hi - lo)
            f1 = f(x1)
        else:
            lo, x1, f1 = x1, x2, f2
            x2 = lo + ratio * (hi - lo)
            f2 = f(x2)
    return (x1, f1) if f1 <= f2 else (x2, f2)


def _dips(values, stop):
    """Indices j < stop of sampled local minima that a dip below zero could hide next to: strict
    minima whose value is within a few sample-to-sample changes of zero."""
    j = np.arange(1, max(1, min(stop, values.size - 1)))
    if j.size == 0:
        return j
    left = values[j - 1] - values[j]
    right = values[j + 1] - values[j]
    is_min = (left >= 0.0) & (right >= 0.0) & ((left > 0.0) | (right > 0.0))
    near = values[j] <= 4.0 * np.maximum(left, right) + 1e-12
    return j[is_min & near]


def reference_contact(gap, horizon):
    """(first contact time or inf, depth of the first dip): brute-force scan and bisection.

    ``gap(ts)`` maps an array of times to gaps. The depth is the most negative
    gap of the first dip (0 if none); a dip no deeper than GRAZE is a graze.
    """

    def g(t):
        return float(gap(np.array([t]))[0])

    ts = np.linspace(0.0, horizon, SAMPLES)
    values = gap(ts)
    assert values[0] > 0.0, "reference expects the shapes apart at t = 0"
    hits = np.nonzero(values <= 0.0)[0]
    first = hits[0] if hits.size else SAMPLES
    bracket = None
    # a dip between samples: refine local minima of the samples before the first hit
    for j in _dips(values, first):
        t_min, v_min = _golden_min(g, ts[j - 1], ts[j + 1])
        if v_min <= 0.0:
            bracket = (ts[j - 1], t_min, v_min)
            break
    if bracket is None and first < SAMPLES:
        bracket = (ts[first - 1], ts[first], None)
    if bracket is None:
        # no contact: report how close the closest approach came (negative never)
        return INF, 0.0
    lo, hi, v_min = bracket
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        if g(mid) > 0.0:
            lo = mid
        else:
            hi = mid
    t_ref = hi
    # depth of the first dip
    if v_min is None:
        k = first
        while k + 1 < SAMPLES and values[k + 1] <= 0.0:
            k += 1
        left = ts[first - 1]
        right = ts[min(k + 1, SAMPLES - 1)]
        _, v_min = _golden_min(g, left, right)
        v_min = min(v_min, float(np.min(values[first : k + 1])))
    return t_ref, v_min


def closest_approach(gap, horizon):
    """Smallest gap over [0, horizon] (samples plus refinement of every sampled local minimum)."""
    ts = np.linspace(0.0, horizon, SAMPLES)
    values = gap(ts)
    best = float(np.min(values))
    for j in _dips(values, SAMPLES):
        best = min(best, _golden_min(lambda t: float(gap(np.array([t]))[0]), ts[j - 1], ts[j + 1])[1])
    return best


def check_against_reference(t, gap, horizon, label=""):
    """The kernel's time agrees with the brute-force reference (see the module docstring)."""
    t_ref, depth = reference_contact(gap, horizon)
    if t_ref == INF:
        if t != INF:
            # the scan missed nothing it could see: only a graze may be reported
            value = float(gap(np.array([t]))[0])
            assert value <= GRAZE, f"{label}: kernel contact at {t!r} but the gap there is {value:.3g}"
            assert closest_approach(gap, horizon) >= -GRAZE, f"{label}: kernel {t!r}, reference none"
            assert value >= -LATE
        return t_ref
    grazing = depth >= -GRAZE
    if t == INF:
        assert grazing, f"{label}: kernel missed a contact at {t_ref!r} (dip depth {depth:.3g})"
        return t_ref
    value = float(gap(np.array([t]))[0])
    assert value >= -LATE, f"{label}: kernel time {t!r} is late: the shapes overlap by {-value:.3g} there"
    if grazing:
        assert value <= GRAZE, f"{label}: kernel time {t!r} is not at a contact (gap {value:.3g})"
        before = np.linspace(0.0, t, 1001)
        assert np.all(gap(before)[:-1] > -LATE), f"{label}: shapes overlapped before the kernel's time"
    else:
        assert abs(t - t_ref) <= TIME_TOL, f"{label}: kernel {t!r}, reference {t_ref!r}"
    return t_ref


# ------------------------------------------------------------------ contact-function checks


def _support_max(points, n):
    return max(n[0] * x + n[1] * y for x, y in points)


def _support_min(points, n):
    return min(n[0] * x + n[1] * y for x, y in points)


def check_circle_circle_contact(a, ra, b, rb):
    px, py, nx, ny = circle_circle_contact(a[0], a[1], ra, b[0], b[1], rb)
    assert abs(math.hypot(nx, ny) - 1.0) <= 1e-12
    # from b towards a
    ab = (a[0] - b[0], a[1] - b[1])
    assert nx * ab[0] + ny * ab[1] > 0.0
    assert abs(math.hypot(px - a[0], py - a[1]) - ra) <= ON_SHAPE
    assert abs(math.hypot(px - b[0], py - b[1]) - rb) <= ON_SHAPE


def check_circle_polygon_contact(c, radius, local, feature):
    """Circle (a) centred at c, polygon (b) with centroid at the origin, at their contact time."""
    rows = outline_rows(local)
    px, py, nx, ny = circle_polygon_contact(c[0], c[1], radius, 0.0, 0.0, rows, 0, len(local), feature)
    assert abs(math.hypot(nx, ny) - 1.0) <= 1e-12
    point = np.array([[px, py]])
    # on both shapes
    assert abs(math.hypot(px - c[0], py - c[1]) - radius) <= ON_SHAPE
    assert abs(point_polygon_signed_distance(point, local)[0]) <= ON_SHAPE
    # the normal separates them, pointing from the polygon (b) towards the circle (a)
    plane = nx * px + ny * py
    assert _support_max(local, (nx, ny)) <= plane + ON_SHAPE
    assert nx * c[0] + ny * c[1] - radius >= plane - ON_SHAPE


def check_polygon_polygon_contact(d, local_a, local_b, feature):
    """Polygon a with centroid at d, polygon b at the origin, at their contact time."""
    rows = np.vstack([outline_rows(local_a), outline_rows(local_b)])
    na, nb = len(local_a), len(local_b)
    px, py, nx, ny = polygon_polygon_contact(d[0], d[1], 0.0, 0.0, rows, 0, na, na, nb, feature)
    assert abs(math.hypot(nx, ny) - 1.0) <= 1e-12
    world_a = [(d[0] + x, d[1] + y) for x, y in local_a]
    point = np.array([[px, py]])
    assert abs(point_polygon_signed_distance(point - np.asarray(d), local_a)[0]) <= ON_SHAPE
    assert abs(point_polygon_signed_distance(point, local_b)[0]) <= ON_SHAPE
    plane = nx * px + ny * py
    assert _support_max(local_b, (nx, ny)) <= plane + ON_SHAPE
    assert _support_min(world_a, (nx, ny)) >= plane - ON_SHAPE


# ------------------------------------------------------------------ strategies


@st.composite
def approach(draw, reach, accelerate):
    """(d, v, a, horizon): a start ``reach + gap`` away, heading roughly at the other body."""
    gap = draw(st.floats(1e-3, 1.0))
    bearing = draw(st.floats(0.0, 2.0 * math.pi))
    distance = reach + gap
    d = (distance * math.cos(bearing), distance * math.sin(bearing))
    speed = draw(st.floats(0.0, 3.0))
    aim = bearing + math.pi + draw(st.floats(-0.6, 0.6))  # towards the other, give or take
    v = (speed * math.cos(aim), speed * math.sin(aim))
    a = draw(vectors(10.0)) if accelerate else (0.0, 0.0)
    horizon = draw(st.floats(0.05, 2.0))
    return d, v, a, horizon


def polygon_shapes():
    return st.one_of(convex_polygons(0.03, 0.25), regular_polygons(3, 8, 0.03, 0.25))


# ------------------------------------------------------------------ circle-circle


@settings(deadline=None, max_examples=120)
@given(radii(0.01, 0.3), radii(0.01, 0.3), st.booleans(), st.data())
def test_circle_circle_matches_brute_force(ra, rb, accelerate, data):
    """circle_circle's time matches a fine scan of |d(t)| - R to 1e-9, never late; misses agree."""
    d, v, a, horizon = data.draw(approach(ra + rb, accelerate))
    gap = lambda ts: circle_circle_gap(ts, d, v, a, ra, rb)
    t, feature = circle_circle(*d, *v, *a, ra, rb, horizon)
    assert feature == 0
    check_against_reference(t, gap, horizon, f"d={d} v={v} a={a} H={horizon}")
    if t != INF:
        p = np.asarray(d) + np.asarray(v) * t + 0.5 * np.asarray(a) * t * t
        check_circle_circle_contact(tuple(p), ra, (0.0, 0.0), rb)


def test_circle_circle_head_on_time():
    """Head-on circles close at (D - R) / v; the same with both shifted and with gravity on both."""
    t, _ = circle_circle(-1.0, 0.0, 2.0, 0.0, 0.0, 0.0, 0.2, 0.3, 10.0)
    assert t == pytest.approx(0.25, rel=1e-15, abs=0.0) and t <= 0.25
    # equal gravity on both: no relative acceleration, same answer
    t, _ = circle_circle(0.0, 1.0, 0.0, -2.0, 0.0, 0.0, 0.2, 0.3, 10.0)
    assert t == pytest.approx(0.25, rel=1e-15, abs=0.0)
    # relative acceleration from rest: D - R = a t^2 / 2
    t, _ = circle_circle(0.0, 1.0, 0.0, 0.0, 0.0, -4.0, 0.2, 0.3, 10.0)
    assert t == pytest.approx(0.5, rel=1e-14, abs=0.0) and t <= 0.5


def test_circle_circle_immediate_and_separating_rules():
    """Overlapping and approaching gives 0.0; overlapping and separating is no contact; resting pressed gives 0.0."""
    assert circle_circle(0.45, 0.0, -1.0, 0.0, 0.0, 0.0, 0.25, 0.25, 1.0)[0] == 0.0
    assert circle_circle(0.45, 0.0, 1.0, 0.0, 0.0, 0.0, 0.25, 0.25, 1.0)[0] == INF
    assert circle_circle(0.5, 0.0, -1.0, 0.0, 0.0, 0.0, 0.25, 0.25, 1.0)[0] == 0.0  # touching, approaching
    assert circle_circle(0.5, 0.0, 1.0, 0.0, 0.0, 0.0, 0.25, 0.25, 1.0)[0] == INF  # touching, leaving
    # touching, at rest relative to each other, accelerated together
    assert circle_circle(0.0, 0.5, 0.0, 0.0, 0.0, -9.81, 0.25, 0.25, 1.0)[0] == 0.0
    # touching, separating now but pulled back: contact again later (concave gap)
    t, _ = circle_circle(0.0, 0.5, 0.0, 1.0, 0.0, -9.81, 0.25, 0.25, 1.0)
    assert t == pytest.approx(2.0 / 9.81, rel=1e-12) and t <= 2.0 / 9.81 + 1e-15


def test_circle_circle_exact_tangent_pass_and_horizon():
    """A pass exactly tangent touches at the closest approach; horizon before the contact means a miss."""
    # b at origin, a moves along y = R (tangent line): |d| = R at x = 0
    t, _ = circle_circle(-1.0, 0.5, 1.0, 0.0, 0.0, 0.0, 0.25, 0.25, 5.0)
    assert t == INF or abs(t - 1.0) <= 1e-7
    # clear miss by 1e-6
    assert circle_circle(-1.0, 0.5 + 1e-6, 1.0, 0.0, 0.0, 0.0, 0.25, 0.25, 5.0)[0] == INF
    # horizon
    assert circle_circle(-1.0, 0.0, 2.0, 0.0, 0.0, 0.0, 0.2, 0.3, 0.2499)[0] == INF
    assert circle_circle(-1.0, 0.0, 2.0, 0.0, 0.0, 0.0, 0.2, 0.3, 0.25)[0] <= 0.25


# ------------------------------------------------------------------ circle-polygon


@settings(deadline=None, max_examples=120)
@given(radii(0.01, 0.2), polygon_shapes(), st.booleans(), st.data())
def test_circle_polygon_matches_brute_force(radius, vertices, accelerate, data):
    """circle_polygon's time matches a fine scan of the point-polygon distance minus r, never late."""
    local, _ = centred(vertices)
    reach = radius + max(math.hypot(x, y) for x, y in local)
    d, v, a, horizon = data.draw(approach(reach, accelerate))
    gap = lambda ts: circle_polygon_gap(ts, d, v, a, radius, local)
    assume(gap(np.array([0.0]))[0] > 1e-6)
    rows = outline_rows(local)
    t, feature = circle_polygon(*d, *v, *a, radius, rows, 0, len(local), horizon)
    check_against_reference(t, gap, horizon, f"d={d} v={v} a={a} H={horizon} poly={local}")
    if t != INF:
        assert -len(local) <= feature < len(local)
        c = np.asarray(d) + np.asarray(v) * t + 0.5 * np.asarray(a) * t * t
        check_circle_polygon_contact(tuple(c), radius, local, feature)


@settings(deadline=None, max_examples=60)
@given(radii(0.01, 0.2), polygon_shapes(), st.data())
def test_circle_polygon_aimed_at_corners(radius, vertices, data):
    """Circles aimed straight at a corner (the corner-disc quartic case) hit it at the brute-force time."""
    local, _ = centred(vertices)
    k = data.draw(st.integers(0, len(local) - 1))
    cx, cy = local[k]
    length = math.hypot(cx, cy)
    ux, uy = cx / length, cy / length
    distance = length + radius + data.draw(st.floats(1e-3, 0.5))
    offset = data.draw(st.floats(-0.5, 0.5)) * radius  # miss the corner's axis a little
    d = (ux * distance - uy * offset, uy * distance + ux * offset)
    speed = data.draw(st.floats(0.1, 3.0))
    v = (-ux * speed, -uy * speed)
    a = data.draw(st.one_of(st.just((0.0, 0.0)), vectors(10.0)))
    horizon = 2.0
    gap = lambda ts: circle_polygon_gap(ts, d, v, a, radius, local)
    assume(gap(np.array([0.0]))[0] > 1e-6)
    t, feature = circle_polygon(*d, *v, *a, radius, outline_rows(local), 0, len(local), horizon)
    check_against_reference(t, gap, horizon, f"corner {k} d={d} v={v} a={a}")
    if t != INF:
        c = np.asarray(d) + np.asarray(v) * t + 0.5 * np.asarray(a) * t * t
        check_circle_polygon_contact(tuple(c), radius, local, feature)


def test_circle_polygon_edge_and_corner_features():
    """A circle dropping onto a square's top edge reports that edge; one aimed at a corner reports the corner."""
    square = [(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)]
    rows = outline_rows(square)
    # straight down onto the top edge (edge 2 runs from (0.5, 0.5) to (-0.5, 0.5))
    t, feature = circle_polygon(0.1, 1.0, 0.0, -1.0, 0.0, 0.0, 0.25, rows, 0, 4, 5.0)
    assert t == pytest.approx(0.25, rel=1e-15) and t <= 0.25
    assert feature == 2
    px, py, nx, ny = circle_polygon_contact(0.1, 0.75, 0.25, 0.0, 0.0, rows, 0, 4, feature)
    assert (nx, ny) == (0.0, 1.0) and (px, py) == pytest.approx((0.1, 0.5), abs=1e-15)
    # diagonally at the corner (0.5, 0.5)
    s = 1.0 / math.sqrt(2.0)
    t, feature = circle_polygon(1.5, 1.5, -s, -s, 0.0, 0.0, 0.25, rows, 0, 4, 5.0)
    expected = math.hypot(1.0, 1.0) - 0.25
    assert t == pytest.approx(expected, rel=1e-14) and t <= expected + 1e-15
    assert feature == -(2 + 1)
    c = 1.5 - s * t
    px, py, nx, ny = circle_polygon_contact(c, c, 0.25, 0.0, 0.0, rows, 0, 4, feature)
    assert (px, py) == (0.5, 0.5)
    assert (nx, ny) == pytest.approx((s, s), abs=1e-12)


def test_circle_polygon_immediate_and_separating_rules():
    """Overlapping and approaching gives 0.0, overlapping and leaving is no contact; resting pressed gives 0.0."""
    rows = outline_rows([(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)])
    assert circle_polygon(0.0, 0.7, 0.0, -1.0, 0.0, 0.0, 0.25, rows, 0, 4, 1.0)[0] == 0.0
    assert circle_polygon(0.0, 0.7, 0.0, 1.0, 0.0, 0.0, 0.25, rows, 0, 4, 1.0)[0] == INF
    assert circle_polygon(0.0, 0.75, 0.0, 0.0, 0.0, -9.81, 0.25, rows, 0, 4, 1.0)[0] == 0.0
    t, _ = circle_polygon(0.0, 0.75, 0.0, 1.0, 0.0, -9.81, 0.25, rows, 0, 4, 1.0)
    assert t == pytest.approx(2.0 / 9.81, rel=1e-12)


def test_circle_polygon_touching_to_rounding_and_separating_too_slowly_recloses_at_the_peak():
    """A circle a rounding error inside an edge or a corner, leaving at 1e-9 but pushed back by its
    acceleration, never gets clear: the contact is its gap's peak, not "never" (the squeeze overlap
    of tools/repro/repro_squeeze_overlap.py: the circle then drifted into the polygon unseen)."""
    rows = outline_rows([(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)])
    inside = np.nextafter(0.75, 0.0)  # 1.1e-16 into the top edge
    t, feature = circle_polygon(0.0, inside, 0.0, 1e-9, 0.0, -9.81, 0.25, rows, 0, 4, 1.0)
    assert feature == 2
    assert t == pytest.approx(1e-9 / 9.81, rel=1e-9)
    # The traced corner: gap -6.5e-19 (squared units), opening at 3.1e-10, pressed back.
    s = 1.0 / math.sqrt(2.0)
    for nudge in (-1, 0, 1):
        c = 0.5 + 0.25 * s
        for _ in range(abs(nudge)):
            c = np.nextafter(c, c + nudge)
        t, feature = circle_polygon(c, c, 1e-9 * s, 1e-9 * s, -9.81 * s, -9.81 * s, 0.25, rows, 0, 4, 1.0)
        gap = float(Decimal(2).sqrt() * (Decimal(c) - Decimal("0.5")) - Decimal("0.25"))  # exact to 1e-28
        # The kernel's squared distance rounds by ~1e-17 (units of 0.25^2), so its gap may be off by 1e-16.
        closes = (1e-9 + math.sqrt(max(1e-18 + 2.0 * 9.81 * (gap + 1e-16), 0.0))) / 9.81
        assert feature == -3
        assert 0.0 < t <= closes * (1.0 + 1e-12)
    # A circle touching and leaving fast enough to get clear is not in contact at the peak.
    assert circle_polygon(0.0, inside, 0.0, 1.0, 0.0, 0.0, 0.25, rows, 0, 4, 1.0)[0] == INF


@pytest.mark.parametrize("vx", [1.0, 0.3, 0.24])
def test_a_circle_bouncing_off_an_edge_near_its_end_meets_the_corner_not_the_edge_s_plane(vx):
    """A circle touching a square's top edge 0.05 from its end and leaving it (up at 1, along
    towards the end at ``vx``, gravity down) comes back to the edge's plane 2 / 9.81 s later,
    past the edge's end for the first two: it then meets the corner (0.3) or nothing (1.0),
    never the plane beyond the edge. The kernel's reclosing of a touching, separating circle
    took the plane's time without looking where the foot was: in a random scene of
    ``test_properties.py`` an elastic ball bouncing along a fixed hexagon's face collided
    with the face's line 1.8 mm past its end, 5.5e-5 short of the corner (found 2026-12-06)."""
    square = [(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)]
    rows = outline_rows(square)
    radius, horizon, start = 0.25, 1.0, (-0.45, 0.75)  # the top edge runs from x = 0.5 to -0.5
    v, a = (-vx, 1.0), (0.0, -9.81)
    t, feature = circle_polygon(*start, *v, *a, radius, rows, 0, 4, horizon)
    # the reference from just after the start, where the circle is clear of the edge
    shift = 1e-3
    moved = tuple(np.asarray(start) + np.asarray(v) * shift + 0.5 * np.asarray(a) * shift**2)
    speed = tuple(np.asarray(v) + np.asarray(a) * shift)

    def gap(ts):
        return circle_polygon_gap(ts, moved, speed, a, radius, square)

    t_ref = check_against_reference(t - shift if t != INF else INF, gap, horizon - shift, f"vx={vx}")
    landing = 2.0 / 9.81
    if vx * landing > 0.05:  # past the end when it comes down: the corner, or nothing
        assert t == INF or feature == -(3 + 1)
        assert (t == INF) == (t_ref == INF)
    else:
        assert feature == 2 and t == pytest.approx(landing, rel=1e-12)


def test_circle_sliding_off_an_edge_end_within_rounding_is_judged_at_the_corner():
    """A circle touching an edge that it is sliding off at one end, to rounding (5e-17 short of
    the end), flies off if it is fast enough (v_t^2 > a_n R), as past the end: no contact now, and
    no reclosing on the edge's plane. The contact code measured the same position from world
    coordinates, found it past the end and let the rider leave; the kernel found it on the edge,
    pressed, and the rider came back to rest, for ever at one instant (an event storm, survey seed
    369)."""
    rows = outline_rows([(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)])
    for end, direction in ((-0.5, -1.0), (0.5, 1.0)):  # the top edge runs from x = 0.5 to -0.5
        x = end - direction * 5e-17
        for leaving in (0.0, 1e-9):
            fast = circle_polygon(x, 0.75, 2.0 * direction, leaving, 0.0, -9.81, 0.25, rows, 0, 4, 1.0)
            assert fast[0] == INF, (end, leaving, fast)
            # Approaching or leaving within the kernels' band of "not moving" (``still``).
            for vn in (-1e-17, 1e-17):
                drift = circle_polygon(x, 0.75, 2.0 * direction, vn, 0.0, -9.81, 0.25, rows, 0, 4, 1.0, 1e-14)
                assert drift[0] == INF, (end, vn, drift)
        # Slower than sqrt(a_n R) the corner carries it: pressed, in contact now.
        slow = circle_polygon(x, 0.75, 1.0 * direction, 0.0, 0.0, -9.81, 0.25, rows, 0, 4, 1.0)
        assert slow[0] == 0.0
        # Well inside the edge it is pressed whatever its speed.
        assert circle_polygon(end - direction * 0.1, 0.75, 2.0 * direction, 0.0, 0.0, -9.81, 0.25, rows, 0, 4, 1.0)[0] == 0.0


#: survey seed 660 (friction): a circle that just left the end of polygon 11's edge 5 at its corner
TRACED_CORNER_ROWS = np.array([
    [-0.05872332263830532, -0.019190201019319317, -0.5506946027220777, -0.8347068075275133, 0.04909781962774536],
    [-0.017741038360268312, -0.04622810529374078, 3.885780586188048e-16, -1.0, 0.05537794512580242],
    [0.037636906765534106, -0.046228105293740746, 0.9819939738526915, -0.1889122423693061, 0.0438873798234251],
    [0.045927770099690776, -0.0031309627789530975, 0.988393800660551, 0.1519134451448944, 0.04454564742841628],
    [0.03916068733263026, 0.04089767898570417, 0.3714359170104008, 0.9284585933441742, 0.04118436195596501],
    [0.0009227125632176522, 0.056195030235306295, -0.5500603941578706, 0.8351248785534342, 0.038737224914448386],
    [-0.03142770768895812, 0.03488721703028274, -0.892724327470795, 0.4506032347218743, 0.06057571904958663],
])
TRACED_CORNER_CIRCLE = (-0.05487764163550768, 0.07048989529469447, -0.44466199455718125, -0.292879494162379,
                        3.9693945253423673, -9.81, 0.04263156227135892)


def test_circle_touching_a_corner_beside_an_edge_plane_that_rounds_clear_is_pressed_now():
    """A circle touching a corner (distance exactly its radius) at the border of the edge it just
    slid off, where that edge's plane distance rounds 7e-18 above the radius: the whole-shape test
    of "touching now" must still run. It is pressed onto the corner (v_t^2 / R = 6.6 < 10.4, normal
    speed 1e-15, within ``still``), so the contact is now; the kernel skipped the test, answered a
    contact 0.077 s later, and the circle sank 3e-9 into the polygon (survey seed 660, friction)."""
    t, feature = circle_polygon(*TRACED_CORNER_CIRCLE, TRACED_CORNER_ROWS, 0, 7, 1.0, 1e-14)
    assert (t, feature) == (0.0, -7)


# ------------------------------------------------------------------ polygon-polygon


@settings(deadline=None, max_examples=120)
@given(polygon_shapes(), polygon_shapes(), st.booleans(), st.data())
def test_polygon_polygon_matches_brute_force(vertices_a, vertices_b, accelerate, data):
    """polygon_polygon's time matches a fine scan of the polygons' distance (SAT when overlapping)."""
    local_a, _ = centred(vertices_a)
    local_b, _ = centred(vertices_b)
    reach = max(math.hypot(x, y) for x, y in local_a) + max(math.hypot(x, y) for x, y in local_b)
    d, v, a, horizon = data.draw(approach(reach, accelerate))
    gap = lambda ts: polygon_polygon_gap(ts, d, v, a, local_a, local_b)
    assume(gap(np.array([0.0]))[0] > 1e-6)
    rows = np.vstack([outline_rows(local_a), outline_rows(local_b)])
    na, nb = len(local_a), len(local_b)
    t, feature = polygon_polygon(*d, *v, *a, rows, 0, na, na, nb, horizon)
    check_against_reference(t, gap, horizon, f"d={d} v={v} a={a} H={horizon} A={local_a} B={local_b}")
    if t != INF:
        assert 0 <= feature < na + nb
        offset = tuple(np.asarray(d) + np.asarray(v) * t + 0.5 * np.asarray(a) * t * t)
        check_polygon_polygon_contact(offset, local_a, local_b, feature)


def test_polygon_polygon_flat_landing_and_corner_hit():
    """A square falling flat onto another lands at the analytic time; a diamond's corner hits a face."""
    square = regular_polygon(4, math.sqrt(0.5), angle=math.pi / 4)  # unit square
    rows = np.vstack([outline_rows(square), outline_rows(square)])
    # a above b by 1.5 (gap 0.5), falling from rest under a = -4: 0.5 = 2 t^2
    t, feature = polygon_polygon(0.0, 1.5, 0.0, 0.0, 0.0, -4.0, rows, 0, 4, 4, 4, 5.0)
    assert t == pytest.approx(0.5, rel=1e-14) and t <= 0.5
    px, py, nx, ny = polygon_polygon_contact(0.0, 1.0, 0.0, 0.0, rows, 0, 4, 4, 4, feature)
    assert (nx, ny) == pytest.approx((0.0, 1.0), abs=1e-15)
    assert abs(py - 0.5) <= 1e-15 and -0.5 - 1e-15 <= px <= 0.5 + 1e-15
    # a diamond (corner down) falling onto the square, moving sideways a little
    diamond = regular_polygon(4, 0.5, angle=-math.pi / 2)
    rows = np.vstack([outline_rows(diamond), outline_rows(square)])
    t, feature = polygon_polygon(0.1, 1.5, 0.2, -1.0, 0.0, 0.0, rows, 0, 4, 4, 4, 5.0)
    assert t == pytest.approx(0.5, rel=1e-14) and t <= 0.5
    px, py, nx, ny = polygon_polygon_contact(0.2, 1.0, 0.0, 0.0, rows, 0, 4, 4, 4, feature)
    assert (px, py) == pytest.approx((0.2, 0.5), abs=1e-15)
    assert (nx, ny) == pytest.approx((0.0, 1.0), abs=1e-15)


def test_polygon_polygon_immediate_and_separating_rules():
    """Overlapping and approaching gives 0.0, overlapping and leaving is no contact; resting pressed gives 0.0."""
    square = regular_polygon(4, math.sqrt(0.5), angle=math.pi / 4)
    rows = np.vstack([outline_rows(square), outline_rows(square)])
    assert polygon_polygon(0.0, 0.99, 0.0, -1.0, 0.0, 0.0, rows, 0, 4, 4, 4, 1.0)[0] == 0.0
    assert polygon_polygon(0.0, 0.99, 0.0, 1.0, 0.0, 0.0, rows, 0, 4, 4, 4, 1.0)[0] == INF
    assert polygon_polygon(0.0, 1.0, 0.0, 0.0, 0.0, -9.81, rows, 0, 4, 4, 4, 1.0)[0] == 0.0
    t, _ = polygon_polygon(0.0, 1.0, 0.0, 1.0, 0.0, -9.81, rows, 0, 4, 4, 4, 1.0)
    assert t == pytest.approx(2.0 / 9.81, rel=1e-12)
