"""How a body answers an impulse at a contact: its share of the contact-space inverse mass,
and the velocity change an impulse gives it.

A body kept resting (pressed into its support by the impulse) moves only across its
rest normal: its support takes the part along it. A resting polygon's base is held
flat by its support, so it does not turn; a resting circle does (its support pushes
through its centre).
"""

from __future__ import annotations

from pge._jit_cache import njit

from pge.core import layout as L


@njit(cache=True, inline="always")
def contact_response(F, x, keep, turns, rx, ry, nx, ny, tx, ty, moves=True):
    """Body ``x``'s share ``(k_nn, k_nt, k_tt)`` of the contact-space inverse mass at lever
    arm ``(rx, ry)``, normal ``n`` and tangent ``t``; a body kept resting moves only
    across its rest normal, and turns only if ``turns`` (a resting circle spins freely:
    its support pushes through its centre; a resting polygon's base is held flat). A body
    that does not ``move`` (held by a neighbour) only turns."""
    m = F[x, L.INV_MASS] if moves else 0.0
    inertia = F[x, L.INV_INERTIA] if turns else 0.0
    rn = rx * ny - ry * nx
    rt = rx * ty - ry * tx
    knn = inertia * rn * rn
    knt = inertia * rn * rt
    ktt = inertia * rt * rt
    if keep:
        mx = F[x, L.REST_NX]
        my = F[x, L.REST_NY]
        pn = nx * mx + ny * my
        pt = tx * mx + ty * my
        return knn + m * (1.0 - pn * pn), knt - m * pn * pt, ktt + m * (1.0 - pt * pt)
    return knn + m, knt, ktt + m


@njit(cache=True, inline="always")
def apply_impulse(F, x, keep, turns, jx, jy, rx, ry, moves=True):
    """Give body ``x`` the impulse ``(jx, jy)`` at lever arm ``(rx, ry)`` (see ``contact_response``
    for ``keep``, ``turns`` and ``moves``); True if its motion changed."""
    dw = (rx * jy - ry * jx) * F[x, L.INV_INERTIA] if turns else 0.0
    if not moves:
        jx = 0.0
        jy = 0.0
    if keep:
        mx = F[x, L.REST_NX]
        my = F[x, L.REST_NY]
        along = jx * mx + jy * my
        jx -= along * mx
        jy -= along * my
    dvx = jx * F[x, L.INV_MASS]
    dvy = jy * F[x, L.INV_MASS]
    if dvx == 0.0 and dvy == 0.0 and dw == 0.0:
        return False
    F[x, L.VX] += dvx
    F[x, L.VY] += dvy
    F[x, L.OMEGA] += dw
    return True
