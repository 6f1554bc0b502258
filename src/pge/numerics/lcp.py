"""Linear complementarity problems by Lemke's complementary pivoting, compiled.

The problem ``LCP(M, q)``: find ``z >= 0`` with ``w = M z + q >= 0`` and ``z . w = 0``.
Lemke's method adds an artificial variable ``z0`` with covering vector ``e = 1``
(``w = M z + q + e z0``), starts from the almost complementary basis where ``z0`` makes
every ``w`` non-negative, and pivots: each variable that leaves the basis brings its
complement in, until ``z0`` leaves (a solution) or the entering column has no positive
entry (a ray: the method gives up). For the contact problems of ``pge.contact.solve``
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

from pge._jit_cache import njit

__all__ = ["lemke"]

#: pivot entries below this times the largest entry of their column count as zero
_PIVOT = 1e-11
#: right-hand sides within this times the largest ``|q|`` of zero are ties in the ratio test
_ZERO = 1e-12


@njit(cache=True)
def _pivot(D, r, c):
    """Exchange the basic variable of row ``r`` with the non-basic one of column ``c`` in the
    condensed tableau ``D`` (only the non-basic columns and the right-hand side; a basic
    variable's column is a unit column and is not kept). Column ``c`` then holds the variable
    that left."""
    n, width = D.shape
    p = D[r, c]
    # the pivot row apart, so that the row updates below read one array and write another
    # (which lets the compiler vectorise them)
    row = np.empty(width)
    for k in range(width):
        row[k] = D[r, k] / p
    row[c] = 1.0 / p
    for i in range(n):
        if i == r:
            continue
        f = D[i, c]
        if f != 0.0:
            target = D[i]
            for k in range(width):
                target[k] -= f * row[k]
            target[c] = -(f * row[c])
    D[r, :] = row


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
    # Condensed tableau [-M | -e | q] of w - M z - e z0 = q: the w are basic (row i holds
    # w_i), column j < n holds z_j, column n holds z0, column n + 1 the right-hand side.
    # Variables are numbered w 0..n-1, z n..2n-1, z0 2n.
    width = n + 2
    D = np.zeros((n, width))
    for i in range(n):
        for j in range(n):
            D[i, j] = -M[i, j]
        D[i, n] = -1.0
        D[i, n + 1] = q[i]
    z0 = 2 * n
    basis = np.arange(n)
    slot = -np.ones(2 * n + 1, dtype=np.int64)  # the column of each non-basic variable
    for j in range(n):
        slot[n + j] = j
    slot[z0] = n
    zero = 0.0
    for i in range(n):
        zero = max(zero, abs(q[i]))
    zero *= _ZERO
    entering = z0
    r = worst
    for _ in range(budget + 1):
        c = slot[entering]
        _pivot(D, r, c)
        leaving = basis[r]
        basis[r] = entering
        slot[entering] = -1
        slot[leaving] = c
        if leaving == z0:
            for i in range(n):
                if basis[i] >= n and basis[i] < 2 * n:
                    z[basis[i] - n] = max(D[i, n + 1], 0.0)
            return z, True
        entering = leaving + n if leaving < n else leaving - n  # the complement
        r = _leaving(D, slot[entering], basis, z0, zero)
        if r < 0:
            return z, False
    return z, False
