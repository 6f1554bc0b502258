"""Real roots of polynomials of degree at most four on an interval.

This is the leaf of the engine's numerics: it imports nothing from pge. Every
time-of-impact question the engine asks of translating bodies reduces to a *gap
polynomial* ``p(t) = c0 + c1 t + c2 t^2 + c3 t^3 + c4 t^4`` on ``[0, horizon]``
that is positive while two features are apart and zero or negative when they
touch or overlap. The functions here answer "when does the gap first close?":

* ``quadratic_roots`` is the numerically stable quadratic formula (no
  cancellation between ``-b`` and the square root).
* ``compensated_evaluate`` evaluates a polynomial as if in twice the working
  precision, with a rigorous error bound; it certifies the sign of the gap.
* ``first_descent`` finds the earliest time at which a gap polynomial passes
  from positive to non-positive. It isolates roots first: the critical points
  of ``p`` (roots of the cubic ``p'``, themselves isolated by the closed-form
  roots of the quadratic ``p''``) split the interval into pieces on which
  ``p`` is monotone; the single root of the first piece whose ends have signs
  ``+`` and ``<= 0`` is refined by a safeguarded Newton iteration that falls
  back to bisection. Closed-form Ferrari/Cardano formulas are never used: they
  lose roots in exactly the near-symmetric quartics that gravity produces.

Contact rules (Bannerman et al. 2014): a gap already non-positive at ``t = 0``
and still decreasing is an immediate contact (time 0); a gap that is
non-positive but not decreasing ("overlapping and separating") is no contact
until it has become positive and closes anew. Rounding can therefore neither
lose a contact nor start an endless loop of zero-time contacts.

Refinement keeps a bracket ``[lo, hi]`` with ``p(lo) > 0 >= p(hi)`` until its
ends are adjacent floating-point numbers. A plainly computed ``p(lo) > 0``
could still be rounding noise, so every answer (refined or from the quadratic
formula) is finally certified: the gap there, evaluated by compensated Horner
with an error bound, must be certainly positive, else the time steps back. A
returned time is therefore never later than the exact root. "No root" is
``math.inf``.

All functions are compiled with Numba (``cache=True``) and can be called from
Python as well as from other compiled code; none is recursive.
"""

from __future__ import annotations

import math

import numpy as np
from pge._jit_cache import njit

__all__ = [
    "evaluate",
    "compensated_evaluate",
    "quadratic_roots",
    "first_descent_quadratic",
    "first_descent",
    "sign_changes",
]

_MAX_REFINE_STEPS = 200
_INF = math.inf
#: a non-positive gap value this small against the other coefficients is touching, to rounding
_TOUCHING = 1e-12


@njit(cache=True)
def evaluate(c0, c1, c2, c3, c4, t):
    """Value of ``c0 + c1 t + c2 t^2 + c3 t^3 + c4 t^4`` (Horner's rule)."""
    return (((c4 * t + c3) * t + c2) * t + c1) * t + c0


_UNIT = 2.0**-53  # unit roundoff of binary64
_SPLITTER = 134217729.0  # 2^27 + 1, Veltkamp's splitting constant


@njit(cache=True, inline="always")
def _two_sum(a, b):
    """``a + b`` as a float and its exact rounding error (Knuth)."""
    s = a + b
    z = s - a
    return s, (a - (s - z)) + (b - z)


@njit(cache=True, inline="always")
def _two_product(a, b):
    """``a * b`` as a float and its exact rounding error (Dekker, without FMA)."""
    p = a * b
    c = _SPLITTER * a
    ah = c - (c - a)
    al = a - ah
    c = _SPLITTER * b
    bh = c - (c - b)
    bl = b - bh
    return p, al * bl - (((p - ah * bh) - al * bh) - ah * bl)


@njit(cache=True)
def compensated_evaluate(c0, c1, c2, c3, c4, t):
    """``p(t)`` by compensated Horner (as if in twice the precision) and an error bound.

    Returns ``(value, bound)`` with ``|value - p(t)| <= bound``, where
    ``bound = 2u|value| + (8u)^2 sum |c_k t^k|`` (Graillat, Langlois and
    Louvet's bound, rounded up), or 0 when no operation rounded at all.
    """
    s = c4
    r = 0.0
    x = abs(t)
    magnitude = abs(c4)
    exact = True
    for c in (c3, c2, c1, c0):
        p, pi = _two_product(s, t)
        s, sigma = _two_sum(p, c)
        if pi != 0.0 or sigma != 0.0:
            exact = False
        r = r * t + (pi + sigma)
        magnitude = magnitude * x + abs(c)
    if exact:
        return s, 0.0  # no operation rounded: the value is exact
    value = s + r
    gamma = 8.0 * _UNIT / (1.0 - 8.0 * _UNIT)
    return value, 2.0 * _UNIT * abs(value) + 2.0 * gamma * gamma * magnitude


@njit(cache=True)
def _not_late(t, c0, c1, c2, c3, c4, floor):
    """Step a computed root ``t`` back until the gap is certainly not negative there.

    The gap is evaluated by compensated Horner with a rigorous error bound; if
    it is not certainly positive, ``t`` moves back by the deficit over the
    slope (at least two ulps) and is checked again. A well-conditioned root is
    thus returned at most a few ulps early and never late. Never below
    ``floor``. A root beyond the largest float (a quotient that overflowed) is inf: the gap
    never closes in representable time.
    """
    if not t < _INF:
        return _INF
    for _ in range(16):
        if t <= floor:
            return floor
        value, bound = compensated_evaluate(c0, c1, c2, c3, c4, t)
        if value >= bound:
            return t  # the exact gap is certainly >= 0 here
        slope = abs(((4.0 * c4 * t + 3.0 * c3) * t + 2.0 * c2) * t + c1)
        step = 2.0 * np.spacing(abs(t))
        if slope > 0.0:
            step = max(step, 2.0 * (bound - value) / slope)
        t -= step
    return t if t > floor else floor


@njit(cache=True)
def quadratic_roots(a, b, c):
    """Real roots of ``a x^2 + b x + c = 0`` as ``(count, low, high)``.

    Uses ``q = -(b + sign(b) sqrt(b^2 - 4ac)) / 2`` and the roots ``q / a`` and
    ``c / q``, which avoids the cancellation of the textbook formula when
    ``b^2 >> 4ac``. ``a == 0`` gives the linear root (count 1, returned in both
    slots) or none; a double root is counted twice; unused slots hold inf.
    """
    if a == 0.0:
        if b == 0.0:
            return 0, _INF, _INF
        r = -c / b
        return 1, r, r
    disc = b * b - 4.0 * a * c
    if disc < 0.0:
        return 0, _INF, _INF
    q = -0.5 * (b + math.copysign(math.sqrt(disc), b))
    if q == 0.0:
        return 2, 0.0, 0.0
    r1 = q / a
    r2 = c / q
    if r1 <= r2:
        return 2, r1, r2
    return 2, r2, r1


@njit(cache=True)
def first_descent_quadratic(c0, c1, c2, horizon, immediate):
    """Earliest ``t`` in ``[0, horizon]`` where the gap ``c0 + c1 t + c2 t^2`` closes.

    Returns 0.0 for "overlapping and approaching" (``c0 <= 0`` and ``c1 < 0``,
    or ``c1 == 0`` and ``c2 < 0``: touching at rest and pressed together) when
    ``immediate`` is true; otherwise only a passage from a positive gap to a
    non-positive one counts. Returns inf when the gap does not close within
    the horizon. Stable formula: accurate to a few units in the last place.
    """
    if c0 <= 0.0:
        if c1 < 0.0 or (c1 == 0.0 and c2 < 0.0):
            return 0.0 if immediate else _INF
        # Separating (or at rest) while touching: only a concave gap can rise
        # above zero and come back down; the later root is that descent.
        if c2 >= 0.0:
            return _INF
        disc = c1 * c1 - 4.0 * c2 * c0
        if disc <= 0.0:
            # The gap never opens. Touching to rounding and pressed, separating too slowly
            # to get clear: it closes again from its peak on.
            if immediate and c0 >= -_TOUCHING * max(abs(c1), abs(c2)):
                t = c1 / (-2.0 * c2)
                return t if t <= horizon else _INF
            return _INF
        t = (c1 + math.sqrt(disc)) / (-2.0 * c2)
        return _not_late(t, c0, c1, c2, 0.0, 0.0, 0.0) if t <= horizon else _INF
    if c2 == 0.0:
        if c1 < 0.0:
            t = -c0 / c1
            return _not_late(t, c0, c1, 0.0, 0.0, 0.0, 0.0) if t <= horizon else _INF
        return _INF
    if c2 > 0.0:
        if c1 >= 0.0:
            return _INF  # both roots are negative
        disc = c1 * c1 - 4.0 * c2 * c0
        if disc < 0.0:
            return _INF
        t = 2.0 * c0 / (math.sqrt(disc) - c1)
        return _not_late(t, c0, c1, c2, 0.0, 0.0, 0.0) if t <= horizon else _INF
    # c2 < 0 < c0: exactly one positive root, where the gap descends.
    sq = math.sqrt(c1 * c1 - 4.0 * c2 * c0)
    if c1 < 0.0:
        t = 2.0 * c0 / (sq - c1)
    else:
        t = (c1 + sq) / (-2.0 * c2)
    return _not_late(t, c0, c1, c2, 0.0, 0.0, 0.0) if t <= horizon else _INF


@njit(cache=True)
def _refine(c0, c1, c2, c3, c4, lo, hi, p_lo, p_hi):
    """Root in a bracket with ``p(lo) > 0 >= p(hi)``; returns a time never after it.

    Safeguarded Newton: a step must land inside the bracket and the bracket
    must at least halve every other step, else bisect. Stops when the ends
    are adjacent floats (or ``p`` is exactly zero) and returns ``lo``.
    """
    x = lo + (hi - lo) * p_lo / (p_lo - p_hi)  # regula falsi start
    if not (lo < x < hi):
        x = 0.5 * (lo + hi)
    width_before = hi - lo
    for _ in range(_MAX_REFINE_STEPS):
        px = (((c4 * x + c3) * x + c2) * x + c1) * x + c0
        if px > 0.0:
            lo = x
        else:
            hi = x
            if px == 0.0:
                return x
        mid = 0.5 * (lo + hi)
        if mid <= lo or mid >= hi:
            break
        dpx = ((4.0 * c4 * x + 3.0 * c3) * x + 2.0 * c2) * x + c1
        x_next = x - px / dpx if dpx != 0.0 else mid
        width = hi - lo
        if not (lo < x_next < hi) or width > 0.5 * width_before:
            x_next = mid
        width_before = width
        x = x_next
    return lo


@njit(cache=True)
def _crossing(c0, c1, c2, c3, c4, lo, hi, p_lo, p_hi):
    """The sign change of ``p`` in a monotone bracket, whichever way it goes."""
    if p_lo > 0.0:
        return _refine(c0, c1, c2, c3, c4, lo, hi, p_lo, p_hi)
    return _refine(-c0, -c1, -c2, -c3, -c4, lo, hi, -p_lo, -p_hi)


@njit(cache=True)
def sign_changes(c0, c1, c2, c3, lo, hi, out):
    """Points in ``(lo, hi)`` where the cubic ``c0 + c1 t + c2 t^2 + c3 t^3`` changes sign.

    Writes them in increasing order to ``out`` (length >= 3) and returns how
    many. Even-multiplicity roots (no sign change) are not reported. The
    cubic's critical points (closed-form quadratic roots) split the interval
    into monotone pieces, each refined separately.
    """
    count = 0
    if c3 == 0.0:
        n, r1, r2 = quadratic_roots(c2, c1, c0)
        if n == 2 and r1 == r2:
            return 0
        if n >= 1 and lo < r1 < hi:
            out[count] = r1
            count += 1
        if n == 2 and lo < r2 < hi:
            out[count] = r2
            count += 1
        return count
    n, k1, k2 = quadratic_roots(3.0 * c3, 2.0 * c2, c1)
    left = lo
    p_left = evaluate(c0, c1, c2, c3, 0.0, lo)
    for piece in range(3):
        if piece == 0:
            right = k1 if (n >= 1 and lo < k1 < hi) else lo
        elif piece == 1:
            right = k2 if (n == 2 and lo < k2 < hi) else left
        else:
            right = hi
        if right <= left:
            continue
        p_right = evaluate(c0, c1, c2, c3, 0.0, right)
        if (p_left > 0.0 and p_right <= 0.0) or (p_left < 0.0 and p_right >= 0.0):
            root = _crossing(c0, c1, c2, c3, 0.0, left, right, p_left, p_right)
            if lo < root < hi and (count == 0 or root > out[count - 1]):
                out[count] = root
                count += 1
        left, p_left = right, p_right
    return count


@njit(cache=True)
def first_descent(c0, c1, c2, c3, c4, horizon, immediate):
    """Earliest ``t`` in ``[0, horizon]`` where a gap polynomial of degree <= 4 closes.

    With ``immediate`` true, a gap already non-positive and decreasing at 0
    (first derivative negative, or zero with a negative second) gives 0.0. Otherwise the answer is the first passage from ``p > 0`` to
    ``p <= 0``: root isolation on the monotone pieces between the critical
    points, safeguarded refinement, then certification by compensated
    evaluation (``_not_late``). Never later than the exact root; a few ulps
    earlier for a well-conditioned root. Returns inf if the gap does not close
    within ``[0, horizon]``.
    """
    if c4 == 0.0 and c3 == 0.0:
        return first_descent_quadratic(c0, c1, c2, horizon, immediate)
    if c0 <= 0.0 and (c1 < 0.0 or (c1 == 0.0 and c2 < 0.0)) and immediate:
        return 0.0
    if not horizon > 0.0:
        return _INF
    breaks = np.empty(4)
    count = sign_changes(c1, 2.0 * c2, 3.0 * c3, 4.0 * c4, 0.0, horizon, breaks)
    breaks[count] = horizon
    left = 0.0
    p_left = c0
    for k in range(count + 1):
        right = breaks[k]
        p_right = evaluate(c0, c1, c2, c3, c4, right)
        if p_left > 0.0 and p_right <= 0.0:
            t = _refine(c0, c1, c2, c3, c4, left, right, p_left, p_right)
            return _not_late(t, c0, c1, c2, c3, c4, 0.0)
        if (
            k == 0
            and immediate
            and count > 0
            and p_right <= 0.0
            and -_TOUCHING * max(abs(c1), abs(c2), abs(c3), abs(c4)) <= c0 <= 0.0
        ):
            # Touching to rounding and separating too slowly to get clear before the gap
            # turns down at its first peak: it closes again from there.
            return right
        left, p_left = right, p_right
    return _INF
