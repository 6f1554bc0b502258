"""Closed-form motion of one body row ("delayed states"): position, velocity, angle.

Between events a body moves with constant acceleration and turns with
constant angular acceleration: at time ``t`` its reference point is at
``X + VX dt + AX dt^2 / 2`` and its angle is ``ANGLE + OMEGA dt + ALPHA dt^2 / 2``,
with ``dt = t - T0``. ``ALPHA`` is nonzero for a body that an island's contact
forces turn (``pge.contact``); the rotating kernels take it. A polygon's outline rows in ``OL`` are turned to the angle
``ORIENT``; ``orient`` turns them to the body's angle now (from the unturned
rows in ``OB``, never incrementally, so no rounding accumulates).
"""

from __future__ import annotations

import math

import numpy as np
from pge._jit_cache import njit

from pge.core import layout as L

_TWO_PI = 2.0 * math.pi
POLYGON = 1


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


@njit(cache=True, inline="always")
def angle_at(F, i, t):
    """Angle of body ``i`` at time ``t``."""
    dt = t - F[i, L.T0]
    return F[i, L.ANGLE] + (F[i, L.OMEGA] + 0.5 * F[i, L.ALPHA] * dt) * dt


@njit(cache=True, inline="always")
def spin_at(F, i, t):
    """Angular velocity of body ``i`` at time ``t``."""
    return F[i, L.OMEGA] + F[i, L.ALPHA] * (t - F[i, L.T0])


@njit(cache=True, inline="always")
def kernel_angle(F, i, t):
    """Angle of body ``i`` at ``t`` reduced to ``[0, 2 pi)``, as the rotating kernels want it
    (their rounding estimates grow with the angle's size)."""
    angle = np.fmod(angle_at(F, i, t), _TWO_PI)
    if angle < 0.0:
        angle += _TWO_PI
    return angle


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
        alpha = F[i, L.ALPHA]
        F[i, L.ANGLE] += (F[i, L.OMEGA] + 0.5 * alpha * dt) * dt
        F[i, L.OMEGA] += alpha * dt
        F[i, L.T0] = t


@njit(cache=True)
def orient(F, I, OL, OB, i, t):
    """Turn polygon ``i``'s outline rows in ``OL`` to its angle at ``t`` and set its box
    extents: the turned outline's box while it does not spin, the bounding circle's box
    (valid at any angle) while it does."""
    if I[i, L.KIND] != POLYGON:
        return
    angle = angle_at(F, i, t)
    start = I[i, L.OUTLINE_START]
    n = I[i, L.OUTLINE_N]
    if angle != F[i, L.ORIENT]:
        c = math.cos(angle)
        s = math.sin(angle)
        for k in range(start, start + n):
            x = OB[k, 0]
            y = OB[k, 1]
            nx = OB[k, 2]
            ny = OB[k, 3]
            OL[k, 0] = c * x - s * y
            OL[k, 1] = s * x + c * y
            OL[k, 2] = c * nx - s * ny
            OL[k, 3] = s * nx + c * ny
        F[i, L.ORIENT] = angle
    if F[i, L.OMEGA] != 0.0 or F[i, L.ALPHA] != 0.0:
        reach = F[i, L.REACH]
        F[i, L.EXT_X0] = -reach
        F[i, L.EXT_Y0] = -reach
        F[i, L.EXT_X1] = reach
        F[i, L.EXT_Y1] = reach
        return
    x0 = math.inf
    y0 = math.inf
    x1 = -math.inf
    y1 = -math.inf
    for k in range(start, start + n):
        x0 = min(x0, OL[k, 0])
        y0 = min(y0, OL[k, 1])
        x1 = max(x1, OL[k, 0])
        y1 = max(y1, OL[k, 1])
    F[i, L.EXT_X0] = x0
    F[i, L.EXT_Y0] = y0
    F[i, L.EXT_X1] = x1
    F[i, L.EXT_Y1] = y1
