"""Conservative bounds on where a body can be within a time horizon.

The lecture's short-circuit test ("no collision in the next frame if S^2 < W")
is not conservative: it compares against D^2 - R^2 instead of (D - R)^2, looks
at the displacement only at the end of the frame, and mixes signs in its x
term. The test here is the corrected one. For every t in [0, H] the relative
displacement obeys |dv t + da t^2 / 2| <= |dv| H + |da| H^2 / 2 =: B (triangle
inequality; the bound grows with t), so the reference points stay at least
D - B apart, and bodies whose bounding circles have radii summing to R cannot
touch while R + B < D.
"""

from __future__ import annotations

import math

from pge._jit_cache import njit

#: relative safety factor against rounding in the bounds below.
SAFETY = 1.0 + 1e-9
#: longest horizon given to a moving body, in seconds: keeps the arithmetic finite for
#: bodies that crawl (a subnormal speed would otherwise give an infinite horizon).
MAX_HORIZON = 1e9


@njit(cache=True)
def travel_horizon(speed, accel, distance):
    """Time ``H`` in which a body can travel at most ``distance``.

    Solves ``speed * H + accel * H^2 / 2 = distance`` for ``H >= 0`` (stable
    form). A body with neither speed nor acceleration never leaves: ``inf``.
    """
    if accel == 0.0:
        if speed == 0.0:
            return math.inf
        return distance / speed
    return 2.0 * distance / (speed + math.sqrt(speed * speed + 2.0 * accel * distance))


@njit(cache=True)
def swept_range(x, v, a, horizon):
    """Smallest interval ``(lo, hi)`` holding ``x + v t + a t^2 / 2`` for t in ``[0, horizon]``.

    The extremes are at the ends or where the velocity changes sign.
    """
    end = x + (v + 0.5 * a * horizon) * horizon
    if x <= end:
        lo, hi = x, end
    else:
        lo, hi = end, x
    if a != 0.0:
        turn = -v / a
        if 0.0 < turn < horizon:
            mid = x + 0.5 * v * turn
            if mid < lo:
                lo = mid
            elif mid > hi:
                hi = mid
    return lo, hi


@njit(cache=True)
def cannot_touch_before(dx, dy, dvx, dvy, dax, day, reach, horizon):
    """True when two bodies provably cannot touch within ``[0, horizon]``.

    ``(dx, dy)``, ``(dvx, dvy)``, ``(dax, day)``: relative offset, velocity and
    acceleration of their reference points; ``reach``: the sum of their
    bounding radii about those points. Sound for any horizon: False only means
    "maybe". Costs two square roots and no root finding.
    """
    bound = (math.sqrt(dvx * dvx + dvy * dvy) + 0.5 * math.sqrt(dax * dax + day * day) * horizon) * horizon
    limit = (reach + bound) * SAFETY
    return limit * limit < dx * dx + dy * dy


@njit(cache=True)
def lecture_cannot_touch(dx, dy, dvx, dvy, dax, day, reach, horizon):
    """The lecture's short-circuit test as its slides write it (unsound: measurement only).

    Same arguments as ``cannot_touch_before`` (``d, dv, da``: body ``i`` relative to
    body ``j``), with the frame ``t = horizon``. The slides' ``W = (x_i - x_j)^2 +
    (y_i - y_j)^2 - (r_i + r_j)^2`` and ``S = |(d - c) t + (e - f) t^2 / 2, (k - l) t +
    (m - n) t^2 / 2|`` (``c, d``: x velocities of ``i, j``; ``e, f``: x accelerations;
    ``k, l`` and ``m, n`` the same along y) take the x velocity as ``j - i``
    (``d - c = -dvx``) but every other term as ``i - j``; "no collision" when
    ``S^2 < W``. Used only when ``World.broadphase`` asks for
    ``short_circuit="lecture"``, to count the contacts it loses; see
    docs/broadphase.md for why it is wrong.
    """
    sx = -dvx * horizon + 0.5 * dax * horizon * horizon
    sy = dvy * horizon + 0.5 * day * horizon * horizon
    w = dx * dx + dy * dy - reach * reach
    return sx * sx + sy * sy < w
