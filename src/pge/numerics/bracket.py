"""Rigorous steps towards the first zero of a general (non-polynomial) gap function.

This is a leaf of the engine's numerics: it imports nothing from pge. The
rotating time-of-impact kernels ask "when does a gap ``g(t)`` first reach
zero?" for a ``g`` built from sines, cosines and polynomials. No closed form
exists, so the answer is bracketed by *conservative advancement*: from a time
``lo`` known to precede every zero, step by a length over which a bound on
``g`` proves it stays positive. The bounds, each a one-line formula here:

* ``lipschitz_step``: first order. If ``|g'(lo + s)| <= speed + accel * s``
  then ``g(lo + s) >= g - speed * s - accel * s^2 / 2``, which stays positive
  up to the positive root of that quadratic. Valid for every ``s``; converges
  only linearly towards a zero (ratio ``1 - |g'| / bound`` per step).
* ``curvature_step``: second order. If ``g'' >= -curvature`` (almost
  everywhere, as for a convex distance function composed with a curved path)
  then ``g(lo + s) >= g + g'(lo) s - curvature s^2 / 2``. Near a transversal
  zero this is a safe Newton step: the remaining distance shrinks
  quadratically (``r' ~ (curvature + g'') r^2 / (2 |g'|)``), yet the step never
  passes the zero.
* ``excursion_step``: a step during which a gap that starts (numerically) at
  contact cannot open beyond ``2 * band`` and close again to ``band`` unseen:
  ``g`` rises for at least ``max(g', 0) / curvature`` and falls from a peak
  ``H`` to ``H - band`` in no less than ``sqrt(2 band / curvature)``.
* ``newton_trial``: a point slightly past the Newton estimate of the zero,
  where the caller evaluates the exact gap; a non-positive value there closes
  the bracket from above (no rigour needed: the sign is exact).
* ``time_tolerance``: the bracket width at which a zero counts as found,
  ``1e-12 s`` plus a few units in the last place of ``t``.

Every step is computed in floating point from a gap already reduced by a
rounding margin (the caller's job) and is then shrunk by a few units in the
last place, so a rounded step is never longer than the exact one. All
functions are compiled with Numba (``cache=True``); none is recursive.
"""

from __future__ import annotations

import math

from pge._jit_cache import njit

__all__ = [
    "TIME_TOLERANCE",
    "curvature_step",
    "excursion_step",
    "lipschitz_step",
    "newton_trial",
    "time_tolerance",
]

#: absolute part of the time tolerance of a bracketed zero (seconds).
TIME_TOLERANCE = 1e-12

_INF = math.inf
_SHRINK = 1.0 - 8.0 * 2.0**-53  # absorbs the rounding of a step formula


@njit(cache=True)
def lipschitz_step(gap, speed, accel):
    """Length ``s`` over which ``gap - speed * s - accel * s^2 / 2`` stays positive.

    ``speed >= 0`` bounds the rate of change of the gap now and ``accel >= 0``
    how fast that bound grows. Returns 0.0 for ``gap <= 0`` and inf when both
    bounds are zero. Cancellation-free form ``2 gap / (speed + sqrt(...))``.
    """
    if not gap > 0.0:
        return 0.0
    denominator = speed + math.hypot(speed, math.sqrt(2.0 * accel * gap))  # hypot: no underflow
    if denominator == 0.0:
        return _INF
    return 2.0 * gap / denominator * _SHRINK


@njit(cache=True)
def curvature_step(gap, rate, curvature):
    """First positive zero of the lower bound ``gap + rate * s - curvature * s^2 / 2``.

    ``rate`` is the exact derivative of the gap now and ``curvature >= 0``
    bounds ``-g''`` over the step. Returns 0.0 for ``gap <= 0``; inf when the
    bound never reaches zero (``curvature == 0`` and ``rate >= 0``). Both
    branches avoid cancellation.
    """
    if not gap > 0.0:
        return 0.0
    if not curvature > 0.0:
        if rate >= 0.0:
            return _INF
        return gap / -rate * _SHRINK
    root = math.hypot(rate, math.sqrt(2.0 * curvature * gap))
    if rate >= 0.0:
        return (rate + root) / curvature * _SHRINK
    return 2.0 * gap / (root - rate) * _SHRINK


@njit(cache=True)
def excursion_step(rate, curvature, band):
    """Length of a step during which a gap starting within ``band`` of zero cannot
    rise above ``2 * band`` and fall back to ``band`` or below.

    With ``g'' >= -curvature`` the gap keeps rising for ``max(rate, 0) /
    curvature`` and needs ``sqrt(2 band / curvature)`` to fall by ``band``
    from any peak. Inf when ``curvature <= 0`` (a convex gap never turns down).
    """
    if not curvature > 0.0:
        return _INF
    rise = rate / curvature if rate > 0.0 else 0.0
    return (rise + math.sqrt(2.0 * band / curvature)) * _SHRINK


@njit(cache=True)
def newton_trial(lo, gap, rate, certified, widen, tolerance):
    """Trial upper end of a bracket: past the Newton estimate ``lo + gap / -rate``.

    ``certified`` is the time the rigorous step reached; the trial lies beyond
    the Newton point by ``widen`` times their distance (at least half the
    ``tolerance``), so a caller that multiplies ``widen`` after each failed
    trial overtakes a Newton iteration that keeps undershooting. Inf when the
    gap is not closing (``rate >= 0``).
    """
    if not rate < 0.0:
        return _INF
    newton = lo + gap / -rate
    return newton + widen * max(newton - certified, 0.5 * tolerance)


@njit(cache=True)
def time_tolerance(t):
    """Width at which a bracket ``[lo, hi]`` near time ``t`` is accepted: 1e-12 s + 4 ulp."""
    return TIME_TOLERANCE + 8.0 * 2.0**-53 * abs(t)
