"""pge.numerics against 50-digit references (mpmath).

The reference for ``first_descent`` works on the *given* floating-point
coefficients, taken exactly: it isolates the real roots of that polynomial in
[0, H] at 60 digits (roots of the derivative split the interval into monotone
pieces, each sign change is bisected) and applies the contact rule ("first
passage from p > 0 to p <= 0 in [0, H]"; 0.0 for overlapping and closing,
i.e. c0 <= 0 and c1 < 0, or c1 == 0 and c2 < 0, when ``immediate``).

Accuracy tests allow a computed root to be late by what double-precision
evaluation of p can explain (``rounding_allowance``); the documented "never
later than the exact root" contract is checked exactly, in tests of its own:
the returned double, as a rational number, must not exceed the exact root.
"""

from __future__ import annotations

import math

import mpmath
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from pge.numerics import first_descent, first_descent_quadratic, quadratic_roots

mp = mpmath.mp
mp.dps = 50
U = 2.0**-53  # unit roundoff
INF = math.inf


# ------------------------------------------------------------------ reference


def _trim(coeffs):
    """Ascending mpf coefficients without leading (highest-order) zeros."""
    c = [mpmath.mpf(x) for x in coeffs]
    while c and c[-1] == 0:
        c.pop()
    return c


def _value(c, t):
    return mpmath.polyval(c, t, asc=True) if c else mpmath.mpf(0)


def _derivative(c):
    return [k * ck for k, ck in enumerate(c)][1:]


def _quadratic_real_roots(c):
    """Real roots of c0 + c1 t + c2 t^2 (c2 != 0), stable formula in working precision."""
    c0, c1, c2 = c
    disc = c1 * c1 - 4 * c2 * c0
    if disc < 0:
        return []
    q = -(c1 + (mpmath.sqrt(disc) if c1 >= 0 else -mpmath.sqrt(disc))) / 2
    if q == 0:
        return [mpmath.mpf(0), mpmath.mpf(0)]
    return sorted([q / c2, c0 / q])


def _roots_in(c, lo, hi):
    """Sorted real roots in [lo, hi] of the ascending polynomial c (no leading zero): roots of the
    derivative split [lo, hi] into monotone pieces, each sign change is bisected to ~1e-60; a
    critical point where |p| is below 1e-45 of the size of the terms counts as a (double) root."""
    degree = len(c) - 1
    if degree <= 0:
        return []
    if degree == 1:
        r = -c[0] / c[1]
        return [r] if lo <= r <= hi else []
    if degree == 2:
        return [r for r in _quadratic_real_roots(c) if lo <= r <= hi]
    points = [lo] + [r for r in _roots_in(_derivative(c), lo, hi) if lo < r < hi] + [hi]
    roots = []

    def is_zero(t, value):
        size = sum(abs(ck) * abs(t) ** k for k, ck in enumerate(c))
        return abs(value) <= mpmath.mpf(10) ** -45 * size

    values = [_value(c, t) for t in points]
    for k, (t, v) in enumerate(zip(points, values)):
        if is_zero(t, v):
            roots.append(t)
            values[k] = mpmath.mpf(0)
    for k in range(len(points) - 1):
        a, b = points[k], points[k + 1]
        fa, fb = values[k], values[k + 1]
        if fa == 0 or fb == 0 or (fa > 0) == (fb > 0):
            continue
        for _ in range(400):
            m = (a + b) / 2
            if m == a or m == b or b - a <= mpmath.mpf(10) ** -58 * (1 + abs(m)):
                break
            fm = _value(c, m)
            if fm == 0:
                a = b = m
                break
            if (fm > 0) == (fa > 0):
                a, fa = m, fm
            else:
                b = m
        roots.append((a + b) / 2)
    return sorted(roots)


def reference_real_roots(coeffs, lo=-mpmath.inf, hi=mpmath.inf):
    """Real roots (sorted) in [lo, hi] of the exact polynomial with these coefficients (60 digits).

    Infinite ends are only allowed for degree <= 2.
    """
    with mpmath.workdps(60):
        c = _trim(coeffs)
        if len(c) > 3:
            assert lo > -mpmath.inf and hi < mpmath.inf
        return [+r for r in _roots_in(c, mpmath.mpf(lo), mpmath.mpf(hi))]


def reference_first_descent(coeffs, horizon, immediate):
    """Exact contact rule on the exact polynomial: 50-digit time, or inf."""
    c = _trim(coeffs) or [mpmath.mpf(0)]
    c0 = c[0]
    c1 = c[1] if len(c) > 1 else mpmath.mpf(0)
    c2 = c[2] if len(c) > 2 else mpmath.mpf(0)
    if immediate and c0 <= 0 and (c1 < 0 or (c1 == 0 and c2 < 0)):
        return mpmath.mpf(0)
    H = mpmath.mpf(horizon)
    previous = mpmath.mpf(0)
    for r in reference_real_roots(coeffs, 0, H):
        if r <= 0:
            continue
        if c0 > 0:
            return r  # positive before the first root: that root is the first passage
        if r > previous and _value(c, (previous + r) / 2) > 0:
            return r
        previous = max(previous, r)
    return INF


def rounding_allowance(coeffs, root):
    """How far rounding alone may move a computed simple root: forward error bound of a solver
    that decides signs by evaluating p in double precision (Horner, error <= 8 u sum |c_i| t^i),
    plus a few ulps of the root itself."""
    c = [mpmath.mpf(x) for x in coeffs]
    r = mpmath.mpf(root)
    size = sum(abs(ck) * abs(r) ** k for k, ck in enumerate(c))
    slope = abs(sum(k * ck * r ** (k - 1) for k, ck in enumerate(c) if k))
    if slope == 0:
        return mpmath.inf
    return 8 * U * size / slope + 4 * U * abs(r)


def assert_matches(t, ref, rel, label="", coeffs=None):
    """``t`` is within ``rel`` (relative) of the reference, and not later than it by more than
    rounding allows (the strict "never later" rule has tests of its own below)."""
    if ref == INF:
        assert t == INF, f"{label}: engine {t!r}, reference: no contact"
        return
    assert t != INF, f"{label}: engine missed the contact at {mpmath.nstr(ref, 20)}"
    late = mpmath.mpf(t) - ref
    if late > 0:
        allowance = rounding_allowance(coeffs, ref) if coeffs is not None else 4 * U * abs(ref)
        assert late <= allowance, (
            f"{label}: engine {t!r} is later than the root {mpmath.nstr(ref, 25)} by {mpmath.nstr(late, 3)}, "
            f"more than rounding explains ({mpmath.nstr(allowance, 3)})"
        )
    error = abs(late)
    assert error <= rel * max(abs(ref), mpmath.mpf(1e-300)), (
        f"{label}: engine {t!r}, reference {mpmath.nstr(ref, 25)}, relative error {mpmath.nstr(error / ref, 3)}"
    )


def lateness(t, ref):
    """How much later than the exact root ``ref`` the double ``t`` is (<= 0: not late; the
    reference's own 1e-45 uncertainty is not counted)."""
    if ref == INF or t == INF:
        return mpmath.mpf(0)
    excess = mpmath.mpf(t) - ref
    return excess if excess > mpmath.mpf(10) ** -45 * (1 + abs(ref)) else mpmath.mpf(0)


def _multiply(c, q):
    """Product of two ascending coefficient lists (50 digits)."""
    out = [mpmath.mpf(0)] * (len(c) + len(q) - 1)
    for i, ci in enumerate(c):
        for j, qj in enumerate(q):
            out[i + j] += ci * qj
    return out


def poly_from_factors(roots, pairs=(), scale=1.0):
    """Ascending float coefficients (c0..c4) of ``scale * prod(t - r) * prod((t - alpha)^2 + beta^2)``.

    Formed in 50 digits and rounded once: the rounded coefficients are the input
    under test, and the reference works on them, not on the intended roots.
    """
    c = [mpmath.mpf(scale)]
    for r in roots:
        c = _multiply(c, [-mpmath.mpf(r), mpmath.mpf(1)])
    for alpha, beta in pairs:
        alpha, beta = mpmath.mpf(alpha), mpmath.mpf(beta)
        c = _multiply(c, [alpha * alpha + beta * beta, -2 * alpha, mpmath.mpf(1)])
    return [float(x) for x in c] + [0.0] * (5 - len(c))


def poly_from_roots(roots, scale=1.0):
    """Ascending float coefficients (c0..c4) of ``scale * prod(t - r)``."""
    return poly_from_factors(roots, (), scale)


def gap_from_roots(roots, pairs=(), size=1.0):
    """Like ``poly_from_factors`` with the sign chosen so that the gap is positive at t = 0
    (or, with a root at 0, just after it)."""
    sign = 1.0
    for r in roots:
        if r > 0:
            sign = -sign
    return poly_from_factors(roots, pairs, sign * size)


def gravity_quartic(d, v, a, reach):
    """Float coefficients of |d + v t + a t^2 / 2|^2 - reach^2, formed as the engine forms them."""
    dx, dy = d
    dvx, dvy = v
    dax, day = a
    return [
        dx * dx + dy * dy - reach * reach,
        2.0 * (dx * dvx + dy * dvy),
        dvx * dvx + dvy * dvy + dx * dax + dy * day,
        dvx * dax + dvy * day,
        0.25 * (dax * dax + day * day),
    ]


def exact_distance(d, v, a, t):
    """50-digit |d + v t + a t^2 / 2| at the double ``t``."""
    t = mpmath.mpf(t)
    x = mpmath.mpf(d[0]) + mpmath.mpf(v[0]) * t + mpmath.mpf(a[0]) * t * t / 2
    y = mpmath.mpf(d[1]) + mpmath.mpf(v[1]) * t + mpmath.mpf(a[1]) * t * t / 2
    return mpmath.sqrt(x * x + y * y)


def exact_contact_time(d, v, a, reach, horizon):
    """First descent of the exact geometric gap (coefficients formed in 50 digits from the exact inputs)."""
    m = [mpmath.mpf(x) for x in (*d, *v, *a, reach)]
    dx, dy, dvx, dvy, dax, day, R = m
    coeffs = [
        dx * dx + dy * dy - R * R,
        2 * (dx * dvx + dy * dvy),
        dvx * dvx + dvy * dvy + dx * dax + dy * day,
        dvx * dax + dvy * day,
        (dax * dax + day * day) / 4,
    ]
    return reference_first_descent(coeffs, horizon, True)


# ------------------------------------------------------------------ quadratic_roots


QUADRATIC_CASES = [
    # label, (a, b, c)
    ("b^2 >> 4ac, small root 1e-8", (1.0, -1e8, 1.0)),
    ("b^2 >> 4ac, b positive (two negative roots)", (1.0, 1e8, 1.0)),
    ("b^2 >> 4ac, 1e-12 root", (2.0, -3e12, 4.5)),
    ("b^2 >> 4ac, tiny a", (1e-10, -1.0, 1e-3)),
    ("ordinary roots 2 and 3", (1.0, -5.0, 6.0)),
    ("near-double roots 1 -+ 1e-7 (exact discriminant)", (1.0, -2.0, 1.0 - 1e-14)),
    ("near-double roots 0.5 -+ 2^-26", (4.0, -4.0, 1.0 - 2.0**-50)),
    ("roots of opposite sign", (3.0, 1.0, -7.0)),
    ("zero root", (2.0, -5.0, 0.0)),
    ("large scale", (1e150, -3e150, 2e150)),
    ("small scale", (1e-150, -3e-150, 2e-150)),
]


@pytest.mark.parametrize("label,abc", QUADRATIC_CASES, ids=[c[0] for c in QUADRATIC_CASES])
def test_quadratic_roots_hard_cases_match_50_digit_roots(label, abc):
    """The stable quadratic formula returns both real roots to a few ulps, also when b^2 >> 4ac."""
    a, b, c = abc
    count, lo, hi = quadratic_roots(a, b, c)
    ref = reference_real_roots([c, b, a])
    assert count == 2 and len(ref) == 2
    assert lo <= hi
    for got, want in zip((lo, hi), ref):
        if want == 0:
            assert got == 0.0
        else:
            assert abs(mpmath.mpf(got) - want) <= 8 * U * abs(want), (label, got, want)


def test_quadratic_roots_exact_double_root_is_counted_twice():
    """(x - 1)^2 gives count 2 with both slots exactly 1."""
    assert quadratic_roots(1.0, -2.0, 1.0) == (2, 1.0, 1.0)
    assert quadratic_roots(9.0, -6.0, 1.0) == (2, pytest.approx(1 / 3, rel=4 * U), pytest.approx(1 / 3, rel=4 * U))


def test_quadratic_roots_linear_and_degenerate_cases():
    """a = 0 gives the linear root in both slots; a = b = 0 and a negative discriminant give none."""
    assert quadratic_roots(0.0, 2.0, 1.0) == (1, -0.5, -0.5)
    assert quadratic_roots(0.0, -4.0, 1.0) == (1, 0.25, 0.25)
    assert quadratic_roots(0.0, 0.0, 1.0) == (0, INF, INF)
    assert quadratic_roots(1.0, 0.0, 1.0) == (0, INF, INF)
    assert quadratic_roots(1.0, -2.0, 1.0 + 1e-15)[0] == 0


@settings(deadline=None, max_examples=150)
@given(
    st.floats(-1e3, 1e3).filter(lambda x: abs(x) > 1e-6),
    st.floats(-1e6, 1e6).filter(lambda x: x == 0.0 or abs(x) > 1e-100),
    st.floats(-1e3, 1e3).filter(lambda x: x == 0.0 or abs(x) > 1e-100),
)
def test_quadratic_roots_are_backward_stable(a, b, c):
    """Every returned root is an exact root of a quadratic within a few ulps of the given one."""
    count, lo, hi = quadratic_roots(a, b, c)
    disc = mpmath.mpf(b) ** 2 - 4 * mpmath.mpf(a) * mpmath.mpf(c)
    if count == 0:
        # Only a discriminant that rounding can flip may be reported as negative.
        assert disc < 8 * U * (b * b + 4 * abs(a * c))
        return
    assert count == 2 and lo <= hi
    for r in (lo, hi):
        r = mpmath.mpf(r)
        residual = abs(a * r * r + b * r + c)
        scale = abs(a) * r * r + abs(b) * abs(r) + abs(c)
        # backward error: the root of the given quadratic up to a relative perturbation
        # of the coefficients of 8 u, plus the effect of rounding the root itself
        assert residual <= 8 * U * scale + (2 * abs(a * r) + abs(b)) * abs(r) * 2 * U


# ------------------------------------------------------------------ first_descent: labelled hard cases


def _wshape(constant):
    """Quartic whose derivative is (t - 1)(t - 2)(t - 3): Cardano's three-real-root cubic."""
    return [constant, -6.0, 5.5, -2.0, 0.25]


HARD_CASES = [
    # label, coefficients (c0..c4), horizon, immediate, relative tolerance
    ("cubic -(t-1)(t-2)(t-3): descent at 1", gap_from_roots([1, 2, 3]), 5.0, True, 1e-14),
    ("cubic (t-1)(t-2)(t-3): overlapping and separating, descent at 2", poly_from_roots([1, 2, 3]), 5.0, True, 1e-14),
    ("cubic (t-1)(t-2)(t-3) with immediate off", poly_from_roots([1, 2, 3]), 5.0, False, 1e-14),
    ("W quartic (derivative (t-1)(t-2)(t-3)), four real roots", _wshape(2.2), 5.0, True, 1e-14),
    ("W quartic (C = 2): roots 2 -+ sqrt2, touching zero from below at 2", _wshape(2.0), 5.0, True, 1e-14),
    ("W quartic, 1e-7 above zero at both minima: miss", _wshape(2.2500001), 5.0, True, 0.0),
    ("W quartic, horizon before the first root: miss", _wshape(2.2), 0.5, True, 0.0),
    ("near-double roots 0.5, 0.5 + 1e-6 (then 3, 4)", gap_from_roots([0.5, 0.5 + 1e-6, 3, 4]), 5.0, True, 1e-9),
    ("near-double roots 0.5, 0.5 + 1e-4 (then 3, 4)", gap_from_roots([0.5, 0.5 + 1e-4, 3, 4]), 5.0, True, 1e-11),
    # three roots within 2e-4: the root is only defined to ~5e-7 in double evaluation (see rounding_allowance)
    ("clustered roots 1, 1 + 1e-4, 1 + 2e-4 (then 7)", gap_from_roots([1, 1 + 1e-4, 1 + 2e-4, 7]), 5.0, True, 1e-6),
    ("complex pair 1 +- 0.5i and roots 0.3, 2", gap_from_roots([0.3, 2.0], [(1.0, 0.5)]), 5.0, True, 1e-14),
    ("near miss: complex pair 0.4 +- 1e-3i, then roots 2, 6", gap_from_roots([2.0, 6.0], [(0.4, 1e-3)]), 5.0, True, 1e-14),
    ("negative leading coefficient: -(t+1)(t-0.5)((t-1)^2+1)", gap_from_roots([-1.0, 0.5], [(1.0, 1.0)]), 5.0, True, 1e-14),
    ("coefficients of size 1e-8", gap_from_roots([0.25, 0.75, 1.5, 2.5], size=1e-8), 5.0, True, 1e-14),
    ("coefficients of size 1e8", gap_from_roots([0.25, 0.75, 1.5, 2.5], size=1e8), 5.0, True, 1e-14),
    ("root 1e-9 after 0", gap_from_roots([1e-9, 2, 3, -1]), 5.0, True, 1e-12),
    ("root 1e-12 inside the horizon", gap_from_roots([2.0 - 1e-12, 3, 4, -1]), 2.0, True, 1e-14),
    ("root exactly at the horizon", gap_from_roots([2.0, 3, 4, -1]), 2.0, True, 1e-14),
    ("root 1e-9 beyond the horizon: miss", gap_from_roots([2.0 + 1e-9, 3, 4, -1]), 2.0, True, 0.0),
    ("zero horizon, positive gap: miss", gap_from_roots([0.5, 1, 2, 3]), 0.0, True, 0.0),
    ("touching at 0 and opening (c0 = 0, c1 > 0), descent at 1", gap_from_roots([0, 1, 2, 3]), 5.0, True, 1e-14),
    ("no real roots: miss", [5.0, 0.0, 1.0, 0.0, 1.0], 10.0, True, 0.0),
]


def _check_hard_case(coeffs, horizon, immediate, rel, label):
    t = first_descent(*coeffs, horizon, immediate)
    ref = reference_first_descent(coeffs, horizon, immediate)
    assert_matches(t, ref, rel, label, coeffs)
    return t, ref


@pytest.mark.parametrize(
    "label,coeffs,horizon,immediate,rel", HARD_CASES, ids=[case[0] for case in HARD_CASES]
)
def test_first_descent_hard_cases_match_50_digit_reference(label, coeffs, horizon, immediate, rel):
    """first_descent finds the first passage from > 0 to <= 0 on labelled hard polynomials."""
    _check_hard_case(coeffs, horizon, immediate, rel, label)


def test_first_descent_hard_case_list_covers_hits_and_misses():
    """The labelled list exercises both outcomes (a guard against a list that only ever says 'inf')."""
    refs = [reference_first_descent(c, h, i) for _, c, h, i, _ in HARD_CASES]
    assert sum(r == INF for r in refs) >= 5
    assert sum(r != INF for r in refs) >= 12


def test_first_descent_double_root_tangency_is_found_and_never_late():
    """A gap that touches zero at a double root (tangency) is a contact at that root, found early not late."""
    cases = [
        (gap_from_roots([1, 1, -1, -2]), 1.0),  # (t-1)^2 (t+1)(t+2): exact coefficients
        (_wshape(2.25), 1.0),  # W quartic: double roots at 1 and 3
        (gap_from_roots([0.5, 0.5, 3]), 0.5),  # cubic: double root at 0.5, then a crossing at 3
        ([0.25, -1.0, 1.0, 0.0, 0.0], 0.5),  # quadratic (t - 0.5)^2
        (gap_from_roots([0.75, 0.75], [(2.0, 1.0)]), 0.75),  # quartic touching zero once, no other root
    ]
    for coeffs, root in cases:
        t = first_descent(*coeffs, 5.0, True)
        # A double root is only determined to about sqrt(u) by double arithmetic.
        assert root - 1e-7 <= t <= root, (coeffs, t)


def test_first_descent_immediate_rule():
    """Overlapping (c0 <= 0) and closing (c1 < 0, or c1 == 0 < -c2) gives 0.0 only when immediate is set."""
    cases = [
        [0.0, 0.0, -1.0, 0.0, 0.5],  # touching at rest, pressed together (quartic path)
        [-1e-12, 0.0, -1.0, 0.0, 0.0],  # touching at rest, pressed together (quadratic path)
        [-1e-3, -1.0, 1.0, 0.5, 0.25],  # overlapping, approaching, then opening for ever
        [0.0, -1e-12, 0.0, 0.0, 1.0],  # just touching and approaching
        [-1.0, -2.0, 0.0, 0.0, 0.0],  # linear (quadratic path)
        [0.0, -1.0, 0.0, 0.0, 0.0],  # linear, touching
        [-1e-3, -1.0, -2.0, 0.0, 0.0],  # concave quadratic
        [-0.1, -1.0, 2.0, -0.5, 0.01],  # quartic: dips, opens, then closes again later
    ]
    for coeffs in cases:
        assert first_descent(*coeffs, 10.0, True) == 0.0
        t = first_descent(*coeffs, 10.0, False)
        assert t != 0.0
        assert_matches(t, reference_first_descent(coeffs, 10.0, False), 1e-12, str(coeffs), coeffs)
    assert reference_first_descent(cases[-1], 10.0, False) != INF  # the last case does close again


def test_first_descent_overlapping_and_separating_is_not_a_contact():
    """A non-positive gap that is opening (c1 >= 0) is no contact until it has opened and closes again."""
    # opening for ever: never a contact
    assert first_descent(-1e-9, 1.0, 0.0, 0.0, 1.0, 10.0, True) == INF
    assert first_descent(0.0, 0.0, 1.0, 0.0, 1.0, 10.0, True) == INF
    assert first_descent_quadratic(-1e-9, 1.0, 1.0, 10.0, True) == INF
    assert first_descent_quadratic(0.0, 0.0, 1.0, 10.0, True) == INF
    # opens, then closes again at the later root
    coeffs = gap_from_roots([0.0, 2.0, 5.0, -3.0])  # p(0) = 0, p > 0 on (0, 2)
    assert_matches(first_descent(*coeffs, 10.0, True), reference_first_descent(coeffs, 10.0, True), 1e-14, "", coeffs)
    quad = [-1e-3, 1.0, -1.0]
    assert_matches(first_descent_quadratic(*quad, 10.0, True), reference_first_descent(quad, 10.0, True), 1e-14, "", quad)
    # a gap that is negative and only touches zero from below never "passes from > 0"
    assert first_descent(*gap_from_roots([1.0, 1.0, -2.0, 4.0], size=-1.0), 10.0, True) == INF


def test_first_descent_quadratic_path_matches_reference_on_hard_cases():
    """The quadratic path (c3 = c4 = 0) is the stable formula: accurate to a few ulps."""
    cases = [
        ([1.0, -1e8, 1.0], 1.0),  # b^2 >> 4ac: root 1e-8
        ([1e-12, -1.0, 1e-6], 1.0),  # small first root, large second
        ([6.0, -5.0, 1.0], 10.0),  # roots 2, 3
        ([1.0, 1e-3, -1.0], 10.0),  # concave: one positive root
        ([1.0, -3.0, 0.0], 10.0),  # linear
        ([1.0 - 1e-14, -2.0, 1.0], 10.0),  # near-double roots 1 -+ 1e-7
        ([2.0, -1.0, 0.0], 1.0),  # linear root beyond the horizon: miss
    ]
    for coeffs, horizon in cases:
        t = first_descent(*coeffs, 0.0, 0.0, horizon, True)
        assert t == first_descent_quadratic(*coeffs, horizon, True)
        assert_matches(t, reference_first_descent(coeffs, horizon, True), 1e-14, str(coeffs), coeffs)


def test_first_descent_horizon_limits():
    """A root at the horizon counts, one just beyond it does not, and a zero horizon sees nothing ahead."""
    coeffs = gap_from_roots([1.0, 3.0, 4.0, -1.0])
    t = first_descent(*coeffs, 1.0, True)
    assert 1.0 - 4 * U <= t <= 1.0
    assert first_descent(*coeffs, 1.0 - 1e-12, True) == INF
    assert first_descent(*coeffs, 0.0, True) == INF
    assert first_descent(*coeffs, 0.5, True) == INF
    assert first_descent_quadratic(1.0, -1.0, 0.0, 1.0, True) == 1.0
    assert first_descent_quadratic(1.0, -1.0, 0.0, 1.0 - 1e-12, True) == INF
    assert first_descent_quadratic(1.0, -1.0, 0.0, 0.0, True) == INF


# ------------------------------------------------------------------ gravity quartics


GRAVITY_CASES = [
    # label, d (ball minus target), v, a, reach, horizon
    ("ball thrown up 0.5 from 1e-6 above a circle", (1e-4, 0.30000100), (1e-3, 0.5), (0.0, -9.81), 0.3, 1.0),
    ("ball thrown up 1e-3 from 1e-9 above a circle", (0.0, 0.250000001), (2e-5, 1e-3), (0.0, -9.81), 0.25, 1.0),
    ("ball thrown up 1e-4 from 1e-12 above a circle", (3e-7, 0.1 + 1e-12), (1e-6, 1e-4), (0.0, -9.81), 0.1, 1.0),
    ("ball thrown up 0.5 from 1e-3 above a corner (r = 0.05)", (0.01, 0.051), (0.05, 0.5), (0.0, -9.81), 0.05, 2.0),
    ("ball thrown up 0.3 just off a corner's top", (0.02, 0.0505), (0.0, 0.3), (0.0, -9.81), 0.05, 1.0),
    ("ball thrown up 1 onto a circle, sideways 1e-8", (1e-8, 0.2 + 1e-7), (1e-8, 1.0), (0.0, -9.81), 0.2, 1.0),
    ("ball thrown up slowly under strong gravity", (1e-3, 0.0400001), (1e-4, 0.05), (0.0, -981.0), 0.04, 0.1),
    ("ball thrown up, tilted gravity", (0.0, 0.12 + 1e-8), (0.0, 0.7), (0.3, -9.81), 0.12, 1.0),
    ("lecture's game-scale case (gap 1e-4, u = g/200)", (0.0, -0.0401), (0.0, 9.81 * 0.005), (0.0, -9.81), 0.04, 0.01),
]


@pytest.mark.parametrize(
    "label,d,v,a,reach,horizon", GRAVITY_CASES, ids=[case[0] for case in GRAVITY_CASES]
)
def test_first_descent_gravity_quartics(label, d, v, a, reach, horizon):
    """Near-symmetric gravity quartics (the Ferrari failure case): contact found, distance error < 1e-12."""
    coeffs = gravity_quartic(d, v, a, reach)
    t = first_descent(*coeffs, horizon, True)
    ref = reference_first_descent(coeffs, horizon, True)
    assert ref != INF, "case must have a contact"
    assert_matches(t, ref, 1e-9, label, coeffs)
    distance = exact_distance(d, v, a, t)
    assert abs(distance - reach) <= 1e-12 * reach, f"{label}: distance {mpmath.nstr(distance, 20)} vs {reach}"


@st.composite
def thrown_balls(draw):
    """(d, v, a, reach, horizon): a ball thrown slightly upward from just above a circle or corner.

    'Slightly': it rises at most a few times the contact distance, the regime in
    which the expanded gap polynomial keeps its relative accuracy.
    """
    reach = draw(st.floats(0.02, 0.5))
    gap = reach * draw(st.floats(1e-12, 1e-1))
    g = draw(st.floats(1.0, 100.0))
    rise = reach * draw(st.floats(1e-6, 4.0))  # apex height above the start
    up = math.sqrt(2.0 * g * rise)
    side = up * draw(st.floats(-0.1, 0.1))
    angle = math.pi / 2 + draw(st.floats(-0.6, 0.6))  # where on the circle it starts
    d = ((reach + gap) * math.cos(angle), (reach + gap) * math.sin(angle))
    return d, (side, up), (0.0, -g), reach, 4.0 * up / g + 1.0


@settings(deadline=None, max_examples=60)
@given(thrown_balls())
def test_first_descent_random_thrown_ball_falls_back(case):
    """A ball thrown slightly upward from just above a circle/corner comes back: distance error < 1e-12."""
    d, v, a, reach, horizon = case
    coeffs = gravity_quartic(d, v, a, reach)
    ref = reference_first_descent(coeffs, horizon, True)
    assume(ref != INF)
    t = first_descent(*coeffs, horizon, True)
    assert_matches(t, ref, 1e-9, str(case), coeffs)
    distance = exact_distance(d, v, a, t)
    assert abs(distance - reach) <= 1e-12 * reach


# ------------------------------------------------------------------ property tests from random roots


@st.composite
def polynomials_from_roots(draw):
    """(coefficients, horizon): a random real polynomial of degree 2..4 with random real roots.

    Some roots may be replaced by complex pairs. Roots are kept 1e-2 apart and
    1e-6 away from 0 and from the horizon, so that every root is well
    conditioned and its side of the interval is not a matter of rounding.
    """
    degree = draw(st.integers(2, 4))
    n_complex = draw(st.integers(0, degree // 2))
    roots = draw(st.lists(st.floats(-1.0, 3.0), min_size=degree - 2 * n_complex, max_size=degree - 2 * n_complex))
    scale = draw(st.floats(0.1, 10.0)) * draw(st.sampled_from([1.0, -1.0]))
    # complex pairs alpha +- i beta enter as real factors (t - alpha)^2 + beta^2
    pairs = [(draw(st.floats(-1.0, 3.0)), draw(st.floats(1e-2, 2.0))) for _ in range(n_complex)]
    coeffs = poly_from_factors(roots, pairs, scale)
    horizon = draw(st.floats(0.5, 2.5))
    assume(all(abs(r) > 1e-6 and abs(r - horizon) > 1e-6 for r in roots))
    assume(all(abs(r - s) > 1e-2 for i, r in enumerate(roots) for s in roots[i + 1 :]))
    return coeffs, horizon


@settings(deadline=None, max_examples=300)
@given(polynomials_from_roots(), st.booleans())
def test_first_descent_property_random_real_roots(case, immediate):
    """For random polynomials the answer is the first descending root in [0, H] to relative 1e-9."""
    coeffs, horizon = case
    t = first_descent(*coeffs, horizon, immediate)
    ref = reference_first_descent(coeffs, horizon, immediate)
    assert_matches(t, ref, 1e-9, f"{coeffs} H={horizon}", coeffs)


@settings(deadline=None, max_examples=200)
@given(
    st.floats(-10.0, 10.0).filter(lambda x: x == 0.0 or abs(x) > 1e-100),
    st.floats(-10.0, 10.0).filter(lambda x: x == 0.0 or abs(x) > 1e-100),
    st.floats(-10.0, 10.0).filter(lambda x: x == 0.0 or abs(x) > 1e-100),
    st.floats(0.0, 5.0),
    st.booleans(),
)
def test_first_descent_quadratic_property(c0, c1, c2, horizon, immediate):
    """first_descent_quadratic follows the contact rule on random quadratics, to relative 1e-9."""
    ref = reference_first_descent([c0, c1, c2], horizon, immediate)
    # a root within rounding of 0 or of the horizon can go either way, and so can a (near-)double root
    for r in reference_real_roots([c0, c1, c2]):
        assume(abs(r - horizon) > 1e-9 and abs(r) > 1e-9)
    assume(abs(c1 * c1 - 4 * c0 * c2) > 1e-6)
    t = first_descent_quadratic(c0, c1, c2, horizon, immediate)
    assert_matches(t, ref, 1e-9, f"{(c0, c1, c2)} H={horizon}", [c0, c1, c2])


# ------------------------------------------------------------------ "never later": exact


def test_first_descent_is_never_later_than_the_exact_root_on_the_labelled_cases():
    """Documented contract: the returned time is never later than the exact root (checked exactly)."""
    late = []
    cases = [(label, c, h, i) for label, c, h, i, _ in HARD_CASES]
    cases += [(label, gravity_quartic(d, v, a, r), h, True) for label, d, v, a, r, h in GRAVITY_CASES]
    cases += [("linear 1 - 5t (root 1/5)", [1.0, -5.0, 0.0, 0.0, 0.0], 1.0, True)]
    for label, coeffs, horizon, immediate in cases:
        t = first_descent(*coeffs, horizon, immediate)
        excess = lateness(t, reference_first_descent(coeffs, horizon, immediate))
        if excess > 0:
            late.append(f"{label}: {t!r} is {mpmath.nstr(excess, 3)} after the root")
    assert not late, "first_descent returned times later than the exact root:\n" + "\n".join(late)


@st.composite
def thrown_ball_quartics(draw):
    d, v, a, reach, horizon = draw(thrown_balls())
    return gravity_quartic(d, v, a, reach), horizon


@settings(deadline=None, max_examples=300)
@given(st.one_of(polynomials_from_roots(), thrown_ball_quartics()), st.booleans())
def test_first_descent_is_never_later_than_the_exact_root_property(case, immediate):
    """Documented contract on random polynomials and thrown-ball quartics: never later than the exact root."""
    coeffs, horizon = case
    t = first_descent(*coeffs, horizon, immediate)
    ref = reference_first_descent(coeffs, horizon, immediate)
    assert lateness(t, ref) <= 0, f"{t!r} is later than the root {mpmath.nstr(ref, 25)}"


@pytest.mark.parametrize("c2", [-4.9e-320, -5e-324, -1e-310])
def test_first_descent_quadratic_with_a_subnormal_curvature_is_never_now(c2):
    """A gap opening at speed 1 and curving down by a subnormal amount (a friction coefficient of
    1e-320 gave such a deceleration) closes after more than the largest float: the root
    overflows, and it must read as 'never', not as 'now' (it once gave 0, an event storm)."""
    assert first_descent_quadratic(2.7, 1.0, c2, math.inf, True) == math.inf
    assert first_descent_quadratic(2.7, 1.0, c2, 10.0, True) == math.inf
