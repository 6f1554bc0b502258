"""Small dense linear algebra for compiled code (no BLAS or LAPACK needed)."""

from __future__ import annotations

import math

import numpy as np
from pge._jit_cache import njit


@njit(cache=True)
def solve_spd(A, d, floor):
    """Solve ``A x = d`` for a small symmetric positive (semi-)definite ``A`` by Cholesky;
    a pivot below ``floor`` is raised to it, so a singular ``A`` still gives a finite ``x``."""
    n = A.shape[0]
    Lo = np.zeros((n, n))
    for i in range(n):
        for j in range(i + 1):
            total = A[i, j]
            for k in range(j):
                total -= Lo[i, k] * Lo[j, k]
            if i == j:
                Lo[i, i] = math.sqrt(max(total, floor))
            else:
                Lo[i, j] = total / Lo[j, j]
    y = np.empty(n)
    for i in range(n):
        total = d[i]
        for k in range(i):
            total -= Lo[i, k] * y[k]
        y[i] = total / Lo[i, i]
    x = np.empty(n)
    for i in range(n - 1, -1, -1):
        total = y[i]
        for k in range(i + 1, n):
            total -= Lo[k, i] * x[k]
        x[i] = total / Lo[i, i]
    return x
