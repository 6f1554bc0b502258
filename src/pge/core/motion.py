"""Closed-form constant-acceleration motion of one body row ("delayed states")."""

from __future__ import annotations

from numba import njit

from pge.core import layout as L


@njit(cache=True, inline="always")
def state_at(F, i, t):
    """Position and velocity ``(x, y, vx, vy)`` of body ``i`` at time ``t``, in closed form."""
    dt = t - F[i, L.T0]
    ax = F[i, L.AX]
    ay = F[i, L.AY]
    return (
        F[i, L.X] + (F[i, L.VX] + 0.5 * ax * dt) * dt,
        F[i, L.Y] + (F[i, L.VY] + 0.5 * ay * dt) * dt,
        F[i, L.VX] + ax * dt,
        F[i, L.VY] + ay * dt,
    )


@njit(cache=True)
def advance(F, i, t):
    """Move body ``i``'s reference state forward to time ``t`` (no change of motion)."""
    dt = t - F[i, L.T0]
    if dt != 0.0:
        ax = F[i, L.AX]
        ay = F[i, L.AY]
        F[i, L.X] += (F[i, L.VX] + 0.5 * ax * dt) * dt
        F[i, L.Y] += (F[i, L.VY] + 0.5 * ay * dt) * dt
        F[i, L.VX] += ax * dt
        F[i, L.VY] += ay * dt
        F[i, L.T0] = t
