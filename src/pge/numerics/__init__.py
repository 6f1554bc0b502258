"""Numerical kernels with no dependency on the rest of the engine."""

from pge.numerics.roots import (
    evaluate,
    first_descent,
    first_descent_quadratic,
    quadratic_roots,
    sign_changes,
)

__all__ = ["evaluate", "first_descent", "first_descent_quadratic", "quadratic_roots", "sign_changes"]
