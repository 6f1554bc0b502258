"""pge.numerics.bracket: each step is checked exactly (mpmath, 60 digits) against the bound it inverts.

A step is correct when the bound, evaluated exactly at the returned (rounded)
step, is still positive (the step never passes the bound's zero) and when the
step is within a few ulp of that zero (it does not waste progress).
"""

from __future__ import annotations

import math

import mpmath
from hypothesis import given, settings
from hypothesis import strategies as st

from pge.numerics.bracket import (
    TIME_TOLERANCE,
    curvature_step,
    excursion_step,
    lipschitz_step,
    newton_trial,
    time_tolerance,
)

mpmath.mp.dps = 60
INF = math.inf

# zero or normal magnitudes: a bound built from subnormal numbers is not tight enough to compare
gaps = st.floats(1e-15, 10.0)
speeds = st.one_of(st.just(0.0), st.floats(1e-12, 100.0))
curvatures = st.one_of(st.just(0.0), st.floats(1e-12, 1e5))
rates = st.one_of(st.just(0.0), st.floats(1e-12, 100.0), st.floats(-100.0, -1e-12))


def exact(x):
    return mpmath.mpf(x)


@settings(deadline=None, max_examples=300)
@given(gaps, speeds, st.one_of(st.just(0.0), st.floats(1e-12, 1e3)))
def test_lipschitz_step_never_passes_the_zero_of_its_bound_and_nearly_reaches_it(gap, speed, accel):
    """gap - speed s - accel s^2 / 2 stays positive at the step and is within 1e-14 of zero there."""
    s = lipschitz_step(gap, speed, accel)
    if speed == 0.0 and accel == 0.0:
        assert s == INF
        return
    bound = exact(gap) - exact(speed) * exact(s) - exact(accel) * exact(s) ** 2 / 2
    assert bound >= 0
    assert bound <= 1e-14 * gap


@settings(deadline=None, max_examples=300)
@given(gaps, rates, curvatures)
def test_curvature_step_never_passes_the_zero_of_its_bound_and_nearly_reaches_it(gap, rate, curvature):
    """gap + rate s - curvature s^2 / 2 stays positive at the step and is within 1e-13 of zero there."""
    s = curvature_step(gap, rate, curvature)
    if curvature == 0.0 and rate >= 0.0:
        assert s == INF
        return
    bound = exact(gap) + exact(rate) * exact(s) - exact(curvature) * exact(s) ** 2 / 2
    assert bound >= 0
    # the zero's sensitivity to rounding is |bound'| = |rate - curvature s|
    slope = abs(exact(rate) - exact(curvature) * exact(s))
    assert bound <= 1e-13 * (gap + slope * s)


def test_steps_from_a_closed_gap_are_zero():
    """A gap that is already zero or negative allows no step."""
    assert lipschitz_step(0.0, 1.0, 1.0) == 0.0
    assert lipschitz_step(-1e-9, 1.0, 1.0) == 0.0
    assert curvature_step(0.0, 5.0, 1.0) == 0.0
    assert curvature_step(-1.0, 5.0, 1.0) == 0.0


@settings(deadline=None, max_examples=300)
@given(st.floats(0.0, 100.0), st.floats(1e-3, 1e5), st.floats(1e-15, 1e-6))
def test_excursion_step_ends_before_the_worst_case_gap_can_open_and_close_again(rate, curvature, band):
    """The worst gap (g'' = -curvature) rising from 0 above 2 band is still above band when the step ends."""
    s = excursion_step(rate, curvature, band)
    peak = exact(rate) ** 2 / (2 * exact(curvature))
    if peak <= 2 * exact(band):
        return  # it never opens beyond 2 band: nothing to miss
    # the later time at which the worst case falls back to band
    back = (exact(rate) + mpmath.sqrt(exact(rate) ** 2 - 2 * exact(curvature) * exact(band))) / exact(curvature)
    assert exact(s) < back


def test_excursion_step_without_curvature_is_unbounded():
    """A gap that cannot turn down (curvature 0) never closes again: inf."""
    assert excursion_step(1.0, 0.0, 1e-12) == INF


def test_newton_trial_lies_past_the_newton_point_and_only_for_a_closing_gap():
    """The trial is beyond lo + gap / -rate by widen x its distance from the certified time (at least tol / 2)."""
    assert newton_trial(1.0, 0.5, 0.0, 1.1, 1.0, 1e-12) == INF
    assert newton_trial(1.0, 0.5, 2.0, 1.1, 1.0, 1e-12) == INF
    newton = 1.0 + 0.5 / 2.0
    assert newton_trial(1.0, 0.5, -2.0, 1.2, 1.0, 1e-12) == newton + (newton - 1.2)
    assert newton_trial(1.0, 0.5, -2.0, 1.2, 4.0, 1e-12) == newton + 4.0 * (newton - 1.2)
    assert newton_trial(1.0, 0.5, -2.0, newton, 1.0, 1e-12) == newton + 0.5e-12


def test_time_tolerance_is_absolute_near_zero_and_a_few_ulp_far_out():
    """1e-12 s near t = 0; never below 4 ulp of t for large t."""
    assert time_tolerance(0.0) == TIME_TOLERANCE
    assert time_tolerance(1.0) <= 1.1 * TIME_TOLERANCE
    big = 1e6
    assert time_tolerance(big) >= 4.0 * (math.nextafter(big, INF) - big)
