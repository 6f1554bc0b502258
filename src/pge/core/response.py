"""How two bodies answer an impulse at a contact: the combined coefficients of the pair, each
body's share of the contact-space inverse mass, and the velocity change an impulse gives it."""

from __future__ import annotations

import math

from pge._jit_cache import njit

from pge.core import layout as L


@njit(cache=True, inline="always")
def combine(ea, eb, rule):
    """Combine two bodies' coefficients: 0 min, 1 max, 2 mean, 3 geometric mean."""
    if rule == 0:
        return min(ea, eb)
    if rule == 1:
        return max(ea, eb)
    if rule == 2:
        return 0.5 * (ea + eb)
    if ea == eb:
        return ea
    return math.sqrt(ea * eb)


@njit(cache=True, inline="always")
def contact_response(F, x, rx, ry, nx, ny, tx, ty):
    """Body ``x``'s share ``(k_nn, k_nt, k_tt)`` of the contact-space inverse mass at lever
    arm ``(rx, ry)``, normal ``n`` and tangent ``t``."""
    m = F[x, L.INV_MASS]
    inertia = F[x, L.INV_INERTIA]
    rn = rx * ny - ry * nx
    rt = rx * ty - ry * tx
    return inertia * rn * rn + m, inertia * rn * rt, inertia * rt * rt + m


@njit(cache=True, inline="always")
def apply_impulse(F, x, jx, jy, rx, ry):
    """Give body ``x`` the impulse ``(jx, jy)`` at lever arm ``(rx, ry)``."""
    F[x, L.VX] += jx * F[x, L.INV_MASS]
    F[x, L.VY] += jy * F[x, L.INV_MASS]
    F[x, L.OMEGA] += (rx * jy - ry * jx) * F[x, L.INV_INERTIA]
