"""Plane-vector helpers for the event loop's hot path."""

from __future__ import annotations

import math

from pge._jit_cache import njit

#: components between these magnitudes square and sum without overflow or underflow
_SMALL = 2.0**-500
_LARGE = 2.0**500


@njit(cache=True, inline="always")
def magnitude(x, y):
    """``|(x, y)|``: ``sqrt(x^2 + y^2)`` where that is safe, else ``math.hypot``.

    The libm ``hypot`` rescales to guard against overflow and underflow and
    costs several times a square root; the loop takes about five lengths an
    event (speeds for horizons, the kernels' rounding scales). Within the
    guarded range the two agree to an ulp or so, and the callers need a
    length, not its last bit.
    """
    m = max(abs(x), abs(y))
    if _SMALL < m < _LARGE:
        return math.sqrt(x * x + y * y)
    return math.hypot(x, y)
