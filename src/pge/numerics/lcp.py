"""Linear complementarity problems by Lemke's complementary pivoting, compiled.

The problem ``LCP(M, q)``: find ``z >= 0`` with ``w = M z + q >= 0`` and ``z . w = 0``.
Lemke's method adds an artificial variable ``z0`` with covering vector ``e = 1``
(``w = M z + q + e z0``), starts from the almost complementary basis where ``z0`` makes
every ``w`` non-negative, and pivots: each variable that leaves the basis brings its
complement in, until ``z0`` leaves (a solution) or the entering column has no positive
entry (a ray: the method gives up). For the contact problems of ``pge.contact.island``
(Stewart and Trinkle's formulation with Coulomb friction, exact in 2D) the matrix is
copositive-plus on the part that matters and the method ends with a solution; the caller
still checks the answer and keeps another solver for a ray or a pivot budget run out.

Ties in the ratio test are the rule, not the exception, in contact problems: resting contacts
make degenerate bases, whose zero right-hand sides rounding turns into tiny numbers of either
sign. So a right-hand side within ``_ZERO`` of the problem's scale counts as zero, and a tie
goes to the row with the largest pivot entry (the numerically safest choice). A
lexicographic rule, which in exact arithmetic rules out cycling, here broke ties on rounding
noise and ended on false rays in most of the problems of a 20-body pile; the pivot budget
bounds the run instead.

Leaf module: imports nothing from pge.
"""

from __future__ import annotations

import numpy as np
from numba import njit

__all__ = ["lemke"]

#: pivot entries below this times the largest entry of their column count as zero
_PIVOT = 1e-11
#: right-hand sides within this times the largest ``|q|`` of zero are ties in the ratio test
_ZERO = 1e-12


@njit(cache=True)
def _pivot(T, r, col):
    """Make column ``col`` a unit column with its 1 in row ``r``."""
    n, width = T.shape
    p = T[r, col]
    for k in range(width):
        T[r, k] /= p
    for i in range(n):
        if i != r:
            f = T[i, col]
            if f != 0.0:
                for k in range(width):
                    T[i, k] -= f * T[r, k]
            T[i, col] = 0.0
    T[r, col] = 1.0


@njit(cache=True)
def _leaving(T, col, basis, z0, zero):
    """Row of the ratio test for entering column ``col``: the smallest ``rhs / T[i, col]``
    over positive entries, ratios within ``zero / T[i, col]`` of it counting as ties (a
    right-hand side that rounding left a little above or below zero is zero). A tie goes to
    ``z0``'s row, else to the largest pivot entry. -1 when the column has no positive entry
    (a ray)."""
    n = T.shape[0]
    rhs = T.shape[1] - 1
    largest = 0.0
    for i in range(n):
        largest = max(largest, abs(T[i, col]))
    floor = _PIVOT * largest
    bound = np.inf
    for i in range(n):
        if T[i, col] > floor:
            bound = min(bound, (max(T[i, rhs], 0.0) + zero) / T[i, col])
    if bound == np.inf:
        return -1
    best = -1
    for i in range(n):
        if T[i, col] > floor and max(T[i, rhs], 0.0) / T[i, col] <= bound:
            if basis[i] == z0:
                return i
            if best < 0 or T[i, col] > T[best, col]:
                best = i
    return best


@njit(cache=True)
def lemke(M, q, budget):
    """Solve ``LCP(M, q)`` by Lemke's method: ``(z, ok)``.

    ``M`` is ``n x n``, ``q`` of length ``n``; at most ``budget`` pivots. ``ok`` is false
    when the method ended on a ray or ran out of pivots (``z`` is then zero). With ``q >= 0``
    the answer is ``z = 0`` at once.
    """
    n = q.shape[0]
    z = np.zeros(n)
    worst = 0
    for i in range(n):
        if q[i] < q[worst]:
            worst = i
    if n == 0 or q[worst] >= 0.0:
        return z, True
    # Tableau [I | -M | -e | q] for w - M z - e z0 = q; variables 0..n-1 are w,
    # n..2n-1 are z, 2n is z0, column 2n+1 the right-hand side.
    width = 2 * n + 2
    T = np.zeros((n, width))
    for i in range(n):
        T[i, i] = 1.0
        for j in range(n):
            T[i, n + j] = -M[i, j]
        T[i, 2 * n] = -1.0
        T[i, 2 * n + 1] = q[i]
    z0 = 2 * n
    basis = np.arange(n)
    zero = 0.0
    for i in range(n):
        zero = max(zero, abs(q[i]))
    zero *= _ZERO
    _pivot(T, worst, z0)
    leaving = basis[worst]
    basis[worst] = z0
    for _ in range(budget):
        entering = leaving + n if leaving < n else leaving - n  # the complement
        r = _leaving(T, entering, basis, z0, zero)
        if r < 0:
            return z, False
        _pivot(T, r, entering)
        leaving = basis[r]
        basis[r] = entering
        if leaving == z0:
            for i in range(n):
                if basis[i] >= n and basis[i] < 2 * n:
                    z[basis[i] - n] = max(T[i, 2 * n + 1], 0.0)
            return z, True
    return z, False
