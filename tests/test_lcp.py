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
    every ratio test; the tie rule must not cycle."""
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


def _stewart_trinkle(W, base, blocks, mus):
    """The contact LCP as ``pge.contact.solve._exact`` builds it: ``W`` over the normal
    directions (first) and one friction direction per block, ``base`` the speeds along them
    with no impulse (targets zero), ``blocks[f]`` the normal rows of block ``f``."""
    count = W.shape[0] - len(blocks)
    nf = len(blocks)
    size = count + 3 * nf
    plus, minus, slide = count, count + nf, count + 2 * nf
    M = np.zeros((size, size))
    q = np.zeros(size)
    q[:count] = base[:count]
    M[:count, :count] = W[:count, :count]
    M[:count, plus:minus] = W[:count, count:]
    M[:count, minus:slide] = -W[:count, count:]
    q[plus:minus] = base[count:]
    q[minus:slide] = -base[count:]
    M[plus:minus, :count] = W[count:, :count]
    M[minus:slide, :count] = -W[count:, :count]
    M[plus:minus, plus:minus] = W[count:, count:]
    M[plus:minus, minus:slide] = -W[count:, count:]
    M[minus:slide, plus:minus] = -W[count:, count:]
    M[minus:slide, minus:slide] = W[count:, count:]
    for f, rows in enumerate(blocks):
        M[plus + f, slide + f] = M[minus + f, slide + f] = 1.0
        M[slide + f, plus + f] = M[slide + f, minus + f] = -1.0
        for r in rows:
            M[slide + f, r] = mus[f]
    return M, q


@st.composite
def resting_stacks(draw):
    """A stack of boxes on a fixed floor, each resting on the one below on two or three points
    of its bottom face (three: a redundant point, as a manifold can hold), drifting sideways
    and turning a little, under gravity over one step: the degenerate, rank-deficient contact
    problems of a pile, where every normal row of a block is as loaded as the next."""
    levels = draw(st.integers(1, 6))
    seed = draw(st.integers(0, 2**31 - 1))
    rng = np.random.default_rng(seed)
    h, g = 1.0 / 240.0, 9.81
    masses = rng.uniform(0.2, 5.0, levels)
    half = rng.uniform(0.02, 0.1, levels)
    inertia = masses * (2.0 * half) ** 2 / 6.0
    speeds = np.zeros((levels, 3))
    speeds[:, 0] = rng.normal(0.0, 0.05, levels)
    speeds[:, 1] = -g * h
    speeds[:, 2] = rng.normal(0.0, 0.5, levels)
    centre_y = np.cumsum(2.0 * half) - half
    directions, blocks, mus = [], [], []
    for k in range(levels):  # box k rests on box k - 1 (the floor for k = 0)
        points = [-0.9 * half[k], 0.9 * half[k]]
        if draw(st.booleans()):
            points.append(rng.uniform(-0.9, 0.9) * half[k])
        y = centre_y[k] - half[k]
        rows = []
        for x in points:
            rows.append(len(directions))
            directions.append((k, k - 1, 0.0, 1.0, x, y))
        blocks.append((rows, k, k - 1, float(np.mean(points)), y))
        mus.append(rng.choice([0.0, 0.3, 1.0]))
    friction = [(a, b, 1.0, 0.0, x, y) for (_, a, b, x, y) in blocks]
    count = len(directions)
    J = np.zeros((count + levels, 3 * levels))
    for row, (a, b, dx, dy, x, y) in enumerate(directions + friction):
        for body, sign in ((a, 1.0), (b, -1.0)):
            if body >= 0:
                rx, ry = x, y - centre_y[body]
                J[row, 3 * body : 3 * body + 3] = sign * np.array([dx, dy, rx * dy - ry * dx])
    inverse = np.repeat(1.0 / np.stack([masses, masses, inertia], axis=1), 1, axis=0).ravel()
    W = J @ np.diag(inverse) @ J.T
    base = J @ speeds.ravel()
    M, q = _stewart_trinkle(W, base, [rows for (rows, *_rest) in blocks], mus)
    return M, q, count


@settings(deadline=None, max_examples=300)
@given(resting_stacks())
def test_lemke_solves_the_degenerate_problems_of_resting_stacks(case):
    """Resting contacts make degenerate, rank-deficient problems whose ratio tests tie on
    rounding noise; Lemke's method must still end with a solution, not a false ray."""
    M, q, count = case
    z, ok = lemke(M, q, 8 * len(q) + 64)
    assert ok
    _assert_solves(M, q, z, scale=np.abs(q).max())
    assert z[:count].sum() > 0.0  # the stack is held up
