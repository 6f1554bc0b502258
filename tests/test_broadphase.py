"""The broad phase's bounds: the short-circuit test is conservative, the lecture's is not.

``cannot_touch_before`` may only answer True ("provably no contact within
[0, H]") when the bounding circles really stay apart; a fine time scan of
their centre distance (with every sampled local minimum refined) is the
judge. The lecture's test (reference section 9) is implemented here exactly as
written, to show that it culls the three counterexamples while ours does not.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from strategies import vectors

from pge.broadphase import cannot_touch_before, swept_range, travel_horizon

SAMPLES = 20001


def centre_distance(ts, d, v, a):
    ts = np.asarray(ts, dtype=float)[:, None]
    p = np.asarray(d) + np.asarray(v) * ts + 0.5 * np.asarray(a) * ts * ts
    return np.hypot(p[:, 0], p[:, 1])


def closest_distance(d, v, a, horizon):
    """Smallest centre distance over [0, horizon]: fine scan plus a golden-section refinement
    around the best sample (|d(t)| has at most a few local minima)."""
    ts = np.linspace(0.0, horizon, SAMPLES)
    values = centre_distance(ts, d, v, a)
    best = float(values.min())
    for j in np.nonzero((values[1:-1] <= values[:-2]) & (values[1:-1] <= values[2:]))[0][:50] + 1:
        lo, hi = ts[j - 1], ts[j + 1]
        for _ in range(60):
            m1, m2 = lo + (hi - lo) / 3.0, hi - (hi - lo) / 3.0
            f1, f2 = centre_distance([m1, m2], d, v, a)
            if f1 <= f2:
                hi = m2
            else:
                lo = m1
        best = min(best, float(centre_distance([0.5 * (lo + hi)], d, v, a)[0]))
    return best


def lecture_culls(xi, yi, xj, yj, ri, rj, vi, vj, ai, aj, fps):
    """The lecture's short-circuit test, verbatim: "if S^2 < W there is no collision in the next frame".

    W = (xi-xj)^2 + (yi-yj)^2 - (ri+rj)^2 and
    S^2 = ((d-c)t + (e-f)t^2/2)^2 + ((k-l)t + (m-n)t^2/2)^2 with t = 1/fps,
    c = vxi, d = vxj, e = axi, f = axj, k = vyi, l = vyj, m = ayi, n = ayj.
    """
    t = 1.0 / fps
    c, k = vi
    d, l = vj
    e, m = ai
    f, n = aj
    W = (xi - xj) ** 2 + (yi - yj) ** 2 - (ri + rj) ** 2
    S2 = ((d - c) * t + (e - f) * t * t / 2.0) ** 2 + ((k - l) * t + (m - n) * t * t / 2.0) ** 2
    return S2 < W


# The three counterexamples of reference section 9.1: body i and body j, fps = 100.
COUNTEREXAMPLES = [
    (
        "1: W = D^2 - R^2 is compared instead of (D - R)^2 (snooker scale)",
        {
            "xi": 0.0, "yi": 0.0, "xj": 0.045, "yj": 0.0, "ri": 0.02, "rj": 0.02,
            "vi": (1.0, 0.0), "vj": (0.0, 0.0), "ai": (0.0, 0.0), "aj": (0.0, 0.0), "fps": 100.0,
        },
    ),
    (
        "2: only t = T is looked at; the ball rises and falls back within the frame",
        {
            "xi": 0.0, "yi": 0.0, "xj": 0.0, "yj": 0.0401, "ri": 0.02, "rj": 0.02,
            "vi": (0.0, 9.81 * 0.005), "vj": (0.0, 0.0), "ai": (0.0, -9.81), "aj": (0.0, 0.0), "fps": 100.0,
        },
    ),
    (
        "3: the x term mixes j - i velocity with i - j acceleration",
        {
            "xi": 0.0, "yi": 0.0, "xj": 0.045, "yj": 0.0, "ri": 0.02, "rj": 0.02,
            "vi": (0.5, 0.0), "vj": (0.0, 0.0), "ai": (20.0, 0.0), "aj": (0.0, 0.0), "fps": 100.0,
        },
    ),
]


def _relative(case):
    d = (case["xi"] - case["xj"], case["yi"] - case["yj"])
    v = (case["vi"][0] - case["vj"][0], case["vi"][1] - case["vj"][1])
    a = (case["ai"][0] - case["aj"][0], case["ai"][1] - case["aj"][1])
    return d, v, a, case["ri"] + case["rj"], 1.0 / case["fps"]


@pytest.mark.parametrize("label,case", COUNTEREXAMPLES, ids=[c[0][:1] for c in COUNTEREXAMPLES])
def test_lecture_counterexamples_are_culled_by_the_lecture_but_not_by_ours(label, case):
    """Each counterexample touches within the frame; the lecture's test culls it, cannot_touch_before does not."""
    d, v, a, reach, frame = _relative(case)
    assert closest_distance(d, v, a, frame) < reach, f"{label}: must collide within the frame"
    assert lecture_culls(**case), f"{label}: the lecture's test should (wrongly) cull it"
    assert not cannot_touch_before(*d, *v, *a, reach, frame)


def test_counterexample_contact_times_match_the_reference_notes():
    """The counterexamples touch where section 9.1 says: t = 0.005, t ~ 0.0029 and t ~ 0.0085."""
    expected = [0.005, 0.0029, 0.0085]
    for (label, case), when in zip(COUNTEREXAMPLES, expected):
        d, v, a, reach, frame = _relative(case)
        ts = np.linspace(0.0, frame, SAMPLES)
        first = ts[np.argmax(centre_distance(ts, d, v, a) <= reach)]
        assert first == pytest.approx(when, abs=1e-4), label


@settings(deadline=None, max_examples=400)
@given(
    d=vectors(2.0, 0.0),
    v=vectors(5.0),
    a=st.one_of(st.just((0.0, 0.0)), vectors(50.0)),
    reach=st.floats(1e-3, 0.5),
    horizon=st.floats(1e-4, 1.0),
)
def test_cannot_touch_before_is_conservative(d, v, a, reach, horizon):
    """cannot_touch_before never answers True when the bounding circles come within reach in [0, H]."""
    if cannot_touch_before(*d, *v, *a, reach, horizon):
        assert closest_distance(d, v, a, horizon) > reach


@st.composite
def near_misses(draw):
    """Relative motions whose closest approach is within a few percent of the reach: the hard cases."""
    reach = draw(st.floats(1e-3, 0.5))
    horizon = draw(st.floats(1e-3, 1.0))
    v = draw(vectors(5.0))
    a = draw(st.one_of(st.just((0.0, 0.0)), vectors(50.0)))
    # put the start where the bound is tight: D = R + |v| H + |a| H^2 / 2, scaled a little
    bound = math.hypot(*v) * horizon + 0.5 * math.hypot(*a) * horizon * horizon
    distance = (reach + bound) * draw(st.floats(0.9, 1.1))
    assume(distance > 0.0)
    bearing = draw(st.floats(0.0, 2.0 * math.pi))
    d = (distance * math.cos(bearing), distance * math.sin(bearing))
    return d, v, a, reach, horizon


@settings(deadline=None, max_examples=300)
@given(near_misses())
def test_cannot_touch_before_is_conservative_near_its_bound(case):
    """Near the edge of the bound (start distance ~ R + B) a True answer still means no contact."""
    d, v, a, reach, horizon = case
    if cannot_touch_before(*d, *v, *a, reach, horizon):
        assert closest_distance(d, v, a, horizon) > reach


@settings(deadline=None, max_examples=200)
@given(
    v=st.one_of(st.just((0.0, 0.0)), vectors(5.0, 1e-6)),
    a=st.one_of(st.just((0.0, 0.0)), vectors(50.0, 1e-6)),
    reach=st.floats(1e-3, 0.5),
    gap=st.floats(1e-3, 1.0),
    bearing=st.floats(0.0, 2.0 * math.pi),
)
def test_cannot_touch_before_culls_up_to_the_travel_horizon(v, a, reach, gap, bearing):
    """With D = R + gap, the test culls every horizon a bit below travel_horizon(|v|, |a|, gap) and none above."""
    d = ((reach + gap) * math.cos(bearing), (reach + gap) * math.sin(bearing))
    horizon = travel_horizon(math.hypot(*v), math.hypot(*a), gap)
    assume(0.0 < horizon < math.inf)
    assert cannot_touch_before(*d, *v, *a, reach, 0.999 * horizon)
    assert not cannot_touch_before(*d, *v, *a, reach, 1.001 * horizon)


def test_cannot_touch_before_never_culls_touching_or_overlapping_pairs():
    """Bounding circles already touching or overlapping are never culled, whatever the motion."""
    assert not cannot_touch_before(0.3, 0.0, 1.0, 0.0, 0.0, 0.0, 0.3, 0.0)
    assert not cannot_touch_before(0.1, 0.0, 1.0, 0.0, 0.0, 0.0, 0.3, 1e-6)
    assert not cannot_touch_before(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.3, 1.0)
    # at rest and apart: culled for any horizon
    assert cannot_touch_before(1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.3, 1e6)


# ------------------------------------------------------------------ swept_range, travel_horizon


@settings(deadline=None, max_examples=300)
@given(
    x=st.floats(-10.0, 10.0),
    v=st.floats(-10.0, 10.0),
    a=st.floats(-50.0, 50.0),
    horizon=st.floats(0.0, 3.0),
)
def test_swept_range_contains_the_sampled_trajectory_and_is_tight(x, v, a, horizon):
    """swept_range(x, v, a, H) holds x + v t + a t^2 / 2 for all sampled t in [0, H], and no more."""
    lo, hi = swept_range(x, v, a, horizon)
    ts = np.linspace(0.0, horizon, 2001)
    path = x + v * ts + 0.5 * a * ts * ts
    scale = abs(x) + abs(v) * horizon + abs(a) * horizon * horizon
    slack = 1e-12 * (1.0 + scale)
    assert lo <= hi
    assert np.all(path >= lo - slack) and np.all(path <= hi + slack)
    # tight: the ends are reached (up to the sampling step near a turning point)
    step = horizon / 2000.0
    resolution = slack + abs(a) * step * step + 1e-15
    assert lo >= path.min() - resolution
    assert hi <= path.max() + resolution


def test_swept_range_turning_point():
    """A body thrown up and falling back: the range reaches the apex, not just the end points."""
    lo, hi = swept_range(0.0, 1.0, -2.0, 1.0)  # x(t) = t - t^2: apex 0.25 at t = 0.5, back to 0 at 1
    assert (lo, hi) == (0.0, 0.25)
    lo, hi = swept_range(1.0, -1.0, 2.0, 2.0)  # dips to 0.75 at t = 0.5, ends at 3
    assert (lo, hi) == (0.75, 3.0)
    assert swept_range(0.5, 0.0, 0.0, 10.0) == (0.5, 0.5)


@settings(deadline=None, max_examples=300)
@given(
    speed=st.one_of(st.just(0.0), st.floats(1e-9, 10.0)),
    accel=st.one_of(st.just(0.0), st.floats(1e-9, 100.0)),
    distance=st.floats(1e-6, 10.0),
)
def test_travel_horizon_inverts_the_distance_bound(speed, accel, distance):
    """H = travel_horizon(s, a, D) solves s H + a H^2 / 2 = D (relative 1e-12); inf only when nothing moves."""
    horizon = travel_horizon(speed, accel, distance)
    if speed == 0.0 and accel == 0.0:
        assert horizon == math.inf
        return
    assert 0.0 < horizon < math.inf
    travelled = speed * horizon + 0.5 * accel * horizon * horizon
    assert travelled == pytest.approx(distance, rel=1e-12)


def test_travel_horizon_simple_cases():
    """Constant speed: D / s; from rest: sqrt(2 D / a); nothing moving: inf."""
    assert travel_horizon(2.0, 0.0, 1.0) == 0.5
    assert travel_horizon(0.0, 8.0, 1.0) == 0.5
    assert travel_horizon(0.0, 0.0, 1.0) == math.inf
    assert travel_horizon(1.0, 2.0, 2.0) == pytest.approx(1.0, rel=1e-15)


@pytest.mark.parametrize("speed", [1e-310, 5e-324, 1e-300])
def test_a_body_slower_than_any_normal_float_gets_a_finite_swept_box(speed):
    """A speed so small (denormal, as a long geometric decay leaves) that the travel horizon
    overflows to inf must still give a finite horizon and box: ``v * inf`` made the box's corner
    NaN and the grid lost the body, which a circle then passed through unseen (survey seed 748,
    15 bodies, no gravity, friction: an overlap of 6% of the sizes)."""
    from pge import World
    from pge.core import layout as L

    world = World()
    body = world.add_circle((0.5, 0.5), 0.05, mass=1.0, velocity=(speed, -speed))
    world.run_until(0.1)
    row = world._state.F[body.id]
    box = [row[L.BOX_X0], row[L.BOX_Y0], row[L.BOX_X1], row[L.BOX_Y1]]
    assert all(math.isfinite(v) for v in box), box
    assert box[0] < 0.45 < 0.55 < box[2] and box[1] < 0.45 < 0.55 < box[3]
    assert math.isfinite(row[L.HORIZON])
