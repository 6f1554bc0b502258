"""pge.numerics.lcp (Lemke's method) against enumeration and a closed-form friction case.

Small problems are checked against every choice of active set (for a positive definite M
the solution is unique, so the two must agree); larger ones by the conditions themselves.
The contact problems of the islands (Stewart and Trinkle's form with friction) are tried on
a block on a slope, where sticking or sliding, and the friction impulse, are known in closed
form.
"""

from __future__ import annotations

import itertools
import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from pge.numerics.lcp import lemke


def _enumerate(M, q):
    """Every solution of LCP(M, q) by trying all 2^n active sets (n <= 8)."""
    n = len(q)
    found = []
    for mask in itertools.product((False, True), repeat=n):
        active = [i for i in range(n) if mask[i]]
        z = np.zeros(n)
        if active:
            sub = M[np.ix_(active, active)]
            try:
                z[active] = np.linalg.solve(sub, -q[active])
            except np.linalg.LinAlgError:
                continue
        w = M @ z + q
        if (z >= -1e-9).all() and (w >= -1e-9).all():
            found.append(z)
    return found


def _assert_solves(M, q, z, scale=1.0):
    w = M @ z + q
    tolerance = 1e-9 * scale
    assert (z >= 0.0).all()
    assert w.min() >= -tolerance, w.min()
    assert np.abs(z * w).max() <= tolerance * max(1.0, np.abs(z).max()), np.abs(z * w).max()


@st.composite
def positive_definite(draw, most=8):
    n = draw(st.integers(1, most))
    seed = draw(st.integers(0, 2**31 - 1))
    rng = np.random.default_rng(seed)
    A = rng.normal(size=(n, n))
    skew = rng.normal(size=(n, n))
    M = A @ A.T + 0.1 * np.eye(n) + 0.5 * (skew - skew.T)  # positive definite, not symmetric
    q = rng.normal(size=n) * 3.0
    return M, q


@settings(deadline=None, max_examples=200)
@given(positive_definite())
def test_lemke_finds_the_unique_solution_of_positive_definite_problems(case):
    M, q = case
    z, ok = lemke(M, q, 1000)
    assert ok
    _assert_solves(M, q, z, scale=np.abs(q).max() + np.abs(M).max())
    solutions = _enumerate(M, q)
    assert solutions, "a positive definite LCP has a solution"
    assert np.allclose(z, solutions[0], atol=1e-8)


def test_a_non_negative_q_needs_no_pivot():
    M = np.array([[2.0, 1.0], [1.0, 2.0]])
    z, ok = lemke(M, np.array([0.0, 3.0]), 0)
    assert ok and (z == 0.0).all()


def test_degenerate_problem_with_ties_terminates():
    """Many equal entries (a resting stack: every contact as loaded as the next) give ties in
    every ratio test; the lexicographic rule must not cycle."""
    n = 12
    M = np.eye(n) * 2.0 + np.diag(np.full(n - 1, -1.0), 1) + np.diag(np.full(n - 1, -1.0), -1)
    q = -np.ones(n)
    z, ok = lemke(M, q, 10 * n)
    assert ok
    _assert_solves(M, q, z)


def test_a_ray_is_reported_not_a_wrong_answer():
    """LCP(M, q) with M = -I and q < 0 has no solution: Lemke ends on a ray."""
    z, ok = lemke(-np.eye(2), np.array([-1.0, -2.0]), 100)
    assert not ok


def _block_on_slope(angle, mu, speed):
    """Stewart-Trinkle LCP of a point mass (m = 1) on a slope after one step h: unknowns the
    normal impulse l, friction f+ and f- along the slope, and the sliding speed s."""
    h, g = 1.0 / 240.0, 9.81
    # speeds at the step's end with no contact impulse: along the normal and the slope (down)
    vn = -h * g * math.cos(angle)
    vt = speed + h * g * math.sin(angle)
    M = np.array(
        [
            [1.0, 0.0, 0.0, 0.0],
            [0.0, 1.0, -1.0, 1.0],
            [0.0, -1.0, 1.0, 1.0],
            [mu, -1.0, -1.0, 0.0],
        ]
    )
    # friction f+ acts along +t (down the slope); f- up the slope
    q = np.array([vn, vt, -vt, 0.0])
    return M, q, h, g


def test_block_on_a_slope_sticks_or_slides_as_coulomb_says():
    for angle in (0.2, 0.5):
        for mu in (0.3, 0.8):
            M, q, h, g = _block_on_slope(angle, mu, 0.0)
            z, ok = lemke(M, q, 100)
            assert ok
            _assert_solves(M, q, z)
            normal = h * g * math.cos(angle)
            assert math.isclose(z[0], normal, rel_tol=1e-12)
            friction = z[1] - z[2]
            if math.tan(angle) <= mu:  # sticks: friction holds the slope's pull
                assert math.isclose(friction, -h * g * math.sin(angle), rel_tol=1e-12)
                assert z[3] == 0.0
            else:  # slides down: friction mu N up the slope, sliding at g (sin - mu cos) h
                assert math.isclose(friction, -mu * normal, rel_tol=1e-12)
                assert math.isclose(z[3], h * g * (math.sin(angle) - mu * math.cos(angle)), rel_tol=1e-9)


def test_a_sliding_block_is_slowed_by_mu_n_and_stopped_when_that_suffices():
    angle, mu = 0.0, 0.5
    for speed in (0.001, 1.0):
        M, q, h, g = _block_on_slope(angle, mu, speed)
        z, ok = lemke(M, q, 100)
        assert ok
        friction = z[1] - z[2]
        if speed < mu * g * h:
            assert math.isclose(friction, -speed, rel_tol=1e-12)  # stopped within the step
        else:
            assert math.isclose(friction, -mu * g * h, rel_tol=1e-12)
