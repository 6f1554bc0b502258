"""Piles: the accelerations of bodies resting on one another, solved together.

A resting body has one support, which is immovable (fixed or asleep) or resting itself. The
bodies resting directly on an immovable one are the *bases* of piles: a pile is a base and
everything resting on it, directly or through others, a tree of riders. Resting polygons do
not turn, so a pile is a tree of point masses joined by contacts, each with a fixed unit
normal ``n`` (from the support towards the rider) and tangent ``t = (-n_y, n_x)``. A contact
either *sticks* (the rider's acceleration is its support's) or *slides* (the relative
acceleration lies along ``t``, and friction ``-mu N s t`` opposes the slip, of sign ``s``);
its normal force ``N`` must be positive. A circle on a face of an immovable body with friction
(``contact.rolls``; only a base can be one) turns too: its slip is ``v_t - omega R``, stuck it
*rolls* (its centre gains ``u t`` and its spin ``u / R``, the friction ``-u I / R^2`` along
``t``), and sliding its friction turns it. Riders on a moving support do not roll
(docs/rotation.md, Rolling).

``contact.settle_acceleration`` settles one rider against its support's acceleration as
given, which is exact on an immovable support; but a rider's weight and friction also load
its support (a box dropped on a box sliding on ice slows it down). Whenever a pile gains,
loses or changes a rider, it is solved again here before the event ends.

The solve is the articulated-body recursion over the tree. From the riders on top down to the
base, each rider with all that rests on it answers its support's acceleration ``a`` with a
contact force ``f = M a + c``: stuck, ``M`` is its articulated mass and ``c`` minus its
articulated weight; sliding, ``f = N d`` with ``d = n - mu s t`` and ``N`` linear in ``a``,
so ``M`` is rank one and not symmetric. Its support adds ``M`` to its own mass matrix and
``-c`` to its own weight. From the base up, each body then gets its acceleration and contact
force. A stuck contact that needs more friction than ``mu N`` starts sliding (against the
friction it needed; where friction is so strong that no sliding motion fits, Painleve's paradox,
the base sticks at once, by a tangential impact through the pile's contacts, or else with the pile
carried along if that takes energy out); a body that would
accelerate into a neighbour that cannot give way is
held to its support (the neighbour's reaction is not part of the pile), and so is a still
support under a curved contact (a curved rest needs a still support; it would slip under
the load); a contact that would pull (``N <= 0``), and a curved contact on a moving support,
is released with all that rests on it; then the pile is solved again.
Constraint forces do no work on a sticking or sliding contact (zero relative normal
velocity) and friction only takes energy out, so a pile's energy can only fall.
"""

from __future__ import annotations

import math

import numpy as np
from pge._jit_cache import njit

from pge.core import layout as L
from pge.core.contact import (
    base_of,
    combine,
    contact_slip,
    detach,
    presses_into_neighbour,
    release_riders,
    rolls,
    settle_acceleration,
)
from pge.core.motion import advance, state_at

_FINE, _SLIPS, _LETS_GO, _CURVED, _JAMS = 0, 1, 2, 3, 4


@njit(cache=True)
def _walk(I, base, order, parent, fill):
    """Visit the pile on ``base`` support first (pre-order); return how many bodies it has.

    With ``fill`` the bodies are written to ``order`` and, for each, the position of its
    support in ``order`` to ``parent`` (-1 for the base). The walk keeps no stack: it climbs
    back down through ``SUPPORT`` to the next sibling.
    """
    n = 1
    if fill:
        order[0] = base
        parent[0] = -1
    x = base
    at = 0  # position of x in order
    up = -1
    while True:
        head = I[x, L.RIDER_HEAD]
        if head >= 0:
            up = at
            x = head
        else:
            while x != base and I[x, L.RIDER_NEXT] < 0:
                x = I[x, L.SUPPORT]
                if fill:
                    at = parent[at]
            if x == base:
                return n
            if fill:
                up = parent[at]
            x = I[x, L.RIDER_NEXT]
        if fill:
            order[n] = x
            parent[n] = up
        at = n
        n += 1


@njit(cache=True)
def _frictions(F, I, Q, order, n, friction):
    """Fill ``friction`` with each contact's friction coefficient (the rider's and its
    support's, combined by the world's rule)."""
    for k in range(n):
        p = order[k]
        friction[k] = combine(F[p, L.FRICTION], F[I[p, L.SUPPORT], L.FRICTION], Q[L.FRICTION_RULE])


@njit(cache=True)
def _articulate(F, order, parent, n, slide, friction, mass, weight):
    """From the riders on top down to the base, fill each body's articulated mass matrix
    ``mass`` (row major) and weight ``weight`` (the force at zero acceleration) with all that
    rests on it, for the contact modes in ``slide`` and friction coefficients ``friction``.
    Returns the first sliding contact met (from the top) where no sliding motion fits
    (Painleve's paradox), or -1."""
    for k in range(n):
        p = order[k]
        m = 1.0 / F[p, L.INV_MASS]
        mass[k, 0] = m
        mass[k, 1] = 0.0
        mass[k, 2] = 0.0
        mass[k, 3] = m
        weight[k, 0] = m * F[p, L.FREE_AX]
        weight[k, 1] = m * F[p, L.FREE_AY]
    for k in range(n - 1, 0, -1):
        p = order[k]
        nx = F[p, L.REST_NX]
        ny = F[p, L.REST_NY]
        a00, a01, a10, a11 = mass[k, 0], mass[k, 1], mass[k, 2], mass[k, 3]
        b0, b1 = weight[k, 0], weight[k, 1]
        q = parent[k]
        if slide[k] == 0:  # f = A a - b
            mass[q, 0] += a00
            mass[q, 1] += a01
            mass[q, 2] += a10
            mass[q, 3] += a11
            weight[q, 0] += b0
            weight[q, 1] += b1
            continue
        # Sliding: A (a + u t) = b + N d, two equations for u and N; N = g . (b - A a).
        dx = nx + friction[k] * slide[k] * ny
        dy = ny - friction[k] * slide[k] * nx
        atx = -a00 * ny + a01 * nx
        aty = -a10 * ny + a11 * nx
        det = dx * aty - dy * atx
        if not det > 0.0:
            return k
        gx = -aty / det
        gy = atx / det
        wx = gx * a00 + gy * a10  # N = g . b - w . a
        wy = gx * a01 + gy * a11
        gb = gx * b0 + gy * b1
        mass[q, 0] -= dx * wx  # f = N d = (g . b) d - d (w . a)
        mass[q, 1] -= dx * wy
        mass[q, 2] -= dy * wx
        mass[q, 3] -= dy * wy
        weight[q, 0] -= dx * gb
        weight[q, 1] -= dy * gb
    return -1


@njit(cache=True)
def _sliding_response(a00, a01, a10, a11, nx, ny, mu, s, rx, ry):
    """A rider of articulated mass ``A`` sliding (sign ``s``) on a contact of normal ``n``, the
    contact force ``N d`` with ``d = n - mu s t``: solves ``A u t - N d = r`` (``r = b - A a``
    for forces, ``-A dv`` for impulses) for the relative motion ``u`` along ``t`` and ``N``.
    Returns ``(det, u, N)``; no sliding motion fits unless ``det > 0``."""
    dx = nx + mu * s * ny
    dy = ny - mu * s * nx
    atx = -a00 * ny + a01 * nx
    aty = -a10 * ny + a11 * nx
    det = dx * aty - dy * atx
    if not det > 0.0:
        return det, 0.0, 0.0
    return det, (-dy * rx + dx * ry) / det, (-aty * rx + atx * ry) / det


@njit(cache=True)
def _solve(F, I, Q, ground, order, parent, n, slide, held, acc, spin, t):
    """Solve the pile for the contact modes in ``slide`` (0: stuck, else the sign of the
    sliding), writing each body's acceleration to ``acc`` and angular acceleration to
    ``spin``. A ``held`` contact sticks whatever friction it needs (a neighbour takes the
    rest). A base that is a circle on a face with friction (``contact.rolls``) rolls when
    stuck: its contact point stays on the support while its centre moves along the face.

    Returns ``(k, what)``: the first contact (in ``order``, support first) that fails and
    how (``_SLIPS``: stuck but needing more friction than it has, with the sign it slides
    with in ``slide[k]``; ``_LETS_GO``: pulling; ``_CURVED``: curved on a support that would
    move; ``_JAMS``: sliding with friction so strong that no sliding motion fits, as in
    Painleve's paradox), or ``(-1, _FINE)``.
    """
    mass = np.empty((n, 4))
    weight = np.empty((n, 2))
    friction = np.empty(n)
    _frictions(F, I, Q, order, n, friction)
    for k in range(n):
        spin[k] = 0.0
    base = order[0]
    turning = 0.0  # I / R^2 of a stuck rolling base, else 0 (only a base can roll)
    if slide[0] == 0 and held[0] == 0 and rolls(F, I, base, friction[0]):
        radius = F[base, L.RADIUS]
        turning = 1.0 / (F[base, L.INV_INERTIA] * radius * radius)
    k = _articulate(F, order, parent, n, slide, friction, mass, weight)
    if k >= 0:
        return k, _JAMS
    for k in range(n):
        p = order[k]
        q = parent[k]
        if q < 0:
            aqx = F[ground, L.AX]
            aqy = F[ground, L.AY]
        else:
            aqx = acc[q, 0]
            aqy = acc[q, 1]
        nx = F[p, L.REST_NX]
        ny = F[p, L.REST_NY]
        a00, a01, a10, a11 = mass[k, 0], mass[k, 1], mass[k, 2], mass[k, 3]
        rx = weight[k, 0] - (a00 * aqx + a01 * aqy)  # the contact force's missing part: b - A a
        ry = weight[k, 1] - (a10 * aqx + a11 * aqy)
        if slide[k] == 0:
            normal = -(rx * nx + ry * ny)
            along = -(-rx * ny + ry * nx)
            acc[k, 0] = aqx
            acc[k, 1] = aqy
            if k == 0 and turning > 0.0:
                # Rolling: f = A (a + u t) - b with f . t = -u I / R^2: the centre gains u
                # along t = (-ny, nx), the contact force u (A t).
                atx = -a00 * ny + a01 * nx
                aty = -a10 * ny + a11 * nx
                u = -along / (-ny * atx + nx * aty + turning)
                acc[k, 0] -= u * ny
                acc[k, 1] += u * nx
                normal += u * (atx * nx + aty * ny)
                along = -u * turning
                spin[k] = u / F[p, L.RADIUS]
            if not normal > 0.0:
                return k, _LETS_GO
            if held[k] == 0 and abs(along) > friction[k] * normal:
                slide[k] = -1 if along > 0.0 else 1
                return k, _SLIPS
        else:
            det, u, normal = _sliding_response(a00, a01, a10, a11, nx, ny, friction[k], slide[k], rx, ry)
            if not det > 0.0:
                return k, _JAMS
            acc[k, 0] = aqx - u * ny
            acc[k, 1] = aqy + u * nx
            if not normal > 0.0:
                return k, _LETS_GO
            if rolls(F, I, p, friction[k]):
                # A skidding circle: the friction -mu s N t at its contact turns it.
                spin[k] = friction[k] * slide[k] * normal * F[p, L.RADIUS] * F[p, L.INV_INERTIA]
        if I[p, L.EDGE_OWNER] < 0 and q >= 0:
            # A curved contact rests only on a still support (contact.try_rest).
            _, _, svx, svy = state_at(F, order[q], t)
            if acc[q, 0] != 0.0 or acc[q, 1] != 0.0 or svx != 0.0 or svy != 0.0:
                return k, _CURVED
    return -1, _FINE


@njit(cache=True)
def _tangential_impact(a00, a01, a10, a11, nx, ny, mu, slip):
    """A body of articulated mass ``A`` (row major) sliding at ``slip`` along ``t = (-n_y, n_x)``
    on an immovable support of normal ``n`` where no sliding motion fits (Painleve): the
    velocity it has when the friction impulse along the cone's edge ``d = n - mu s t`` has
    stopped the slip (``s`` its sign), ``(ok, vx, vy)``, a velocity ``v_n n`` into the support.

    The impact goes on stuck: the support's impulse ``-v_n A n`` takes out ``v_n`` (plastic).
    ``ok`` only if the impulse along ``d`` does stop the slip, pressing into the support, and
    the stuck impulse lies in the friction cone; then friction opposes the slip and the normal
    impulse the approach all through, and no energy is gained."""
    tx = -ny
    ty = nx
    s = 1.0 if slip > 0.0 else -1.0
    dx = nx - mu * s * tx
    dy = ny - mu * s * ty
    det = a00 * a11 - a01 * a10
    if not det > 0.0:
        return False, 0.0, 0.0
    wx = (a11 * dx - a01 * dy) / det  # A^-1 d: the velocity per unit of normal impulse
    wy = (a00 * dy - a10 * dx) / det
    rate = wx * tx + wy * ty
    if not rate * s < 0.0:
        return False, 0.0, 0.0
    impulse = -slip / rate
    vn = impulse * (wx * nx + wy * ny)
    if not vn <= 0.0:
        return False, 0.0, 0.0
    qx = -vn * (a00 * nx + a01 * ny)
    qy = -vn * (a10 * nx + a11 * ny)
    qn = qx * nx + qy * ny
    if not (qn >= 0.0 and abs(qx * tx + qy * ty) <= mu * qn):
        return False, 0.0, 0.0
    return True, vn * nx, vn * ny


@njit(cache=True)
def _carry(F, order, parent, n, slide, mass, friction, dv, vel):
    """Pass the base's change of velocity ``dv[0]`` up the pile as impulses through its
    contacts in the modes ``slide`` (a stuck rider is carried along, a sliding one keeps its
    normal velocity and takes an impulse along its cone's edge), writing each body's change to
    ``dv`` and adding it to its velocity in ``vel``. False if a contact's impulse would pull, a
    stuck one's leave its friction cone, or a sliding one's slide turn round. (Riders do not
    roll: ``contact.rolls``.)"""
    for k in range(1, n):
        p = order[k]
        q = parent[k]
        nx = F[p, L.REST_NX]
        ny = F[p, L.REST_NY]
        a00, a01, a10, a11 = mass[k, 0], mass[k, 1], mass[k, 2], mass[k, 3]
        rx = -(a00 * dv[q, 0] + a01 * dv[q, 1])
        ry = -(a10 * dv[q, 0] + a11 * dv[q, 1])
        if slide[k] == 0:
            normal = -(rx * nx + ry * ny)
            along = -(-rx * ny + ry * nx)
            if not (normal >= 0.0 and abs(along) <= friction[k] * normal):
                return False
            dv[k, 0] = dv[q, 0]
            dv[k, 1] = dv[q, 1]
            continue
        _, u, normal = _sliding_response(a00, a01, a10, a11, nx, ny, friction[k], slide[k], rx, ry)
        if not normal >= 0.0:
            return False
        dv[k, 0] = dv[q, 0] - u * ny
        dv[k, 1] = dv[q, 1] + u * nx
    for k in range(n):
        vel[k, 0] += dv[k, 0]
        vel[k, 1] += dv[k, 1]
    for k in range(1, n):
        p = order[k]
        q = parent[k]
        relative = -(vel[k, 0] - vel[q, 0]) * F[p, L.REST_NY] + (vel[k, 1] - vel[q, 1]) * F[p, L.REST_NX]
        if relative * slide[k] < 0.0:
            return False
    return True


@njit(cache=True)
def _jolt(S, order, parent, n, t):
    """Painleve's tangential impact: stop the pile's base sliding on its immovable support at
    ``t`` by impulses through the pile's contacts; True if it stopped.

    Where no sliding motion fits, the support's friction and normal force become impulsive
    (Genot and Brogliato 1999; Stewart 2000): friction along the cone's edge stops the slip,
    then a stuck, plastic impulse ends the approach it made (``_tangential_impact``), the base
    left still. The riders answer through their contacts in the modes their motion gives them
    (``_carry``), so momentum changes only by the support's impulse. Refused where the impact
    is not of that form (a contact would pull or change its mode on the way), where the base
    itself rolls, or where the kinetic energy would rise (it cannot, but rounding is checked)."""
    F = S[0]
    I = S[1]
    Q = S[4]
    slide = np.empty(n, dtype=np.int64)
    vel = np.empty((n, 2))
    for k in range(n):
        p = order[k]
        slip, rolling = contact_slip(S, p, t)
        if rolling:
            return False  # only a base can roll; its spin is not part of this impact
        slide[k] = _sign(slip)
        _, _, vel[k, 0], vel[k, 1] = state_at(F, p, t)
    mass = np.empty((n, 4))
    weight = np.empty((n, 2))
    friction = np.empty(n)
    _frictions(F, I, Q, order, n, friction)
    if _articulate(F, order, parent, n, slide, friction, mass, weight) >= 0:
        return False
    base = order[0]
    nx = F[base, L.REST_NX]
    ny = F[base, L.REST_NY]
    slip = -vel[0, 0] * ny + vel[0, 1] * nx
    ok, sx, sy = _tangential_impact(mass[0, 0], mass[0, 1], mass[0, 2], mass[0, 3], nx, ny, friction[0], slip)
    if not ok:
        return False
    before = vel.copy()
    dv = np.empty((n, 2))
    for phase in range(2):  # sliding, then stuck: the base's velocity goes to v_n n, then to rest
        dv[0, 0] = (sx if phase == 0 else 0.0) - vel[0, 0]
        dv[0, 1] = (sy if phase == 0 else 0.0) - vel[0, 1]
        if not _carry(F, order, parent, n, slide, mass, friction, dv, vel):
            return False
    change = 0.0
    for k in range(n):
        change += (vel[k, 0] ** 2 + vel[k, 1] ** 2 - before[k, 0] ** 2 - before[k, 1] ** 2) / F[order[k], L.INV_MASS]
    if not change <= 0.0:
        return False
    for k in range(n):
        p = order[k]
        advance(F, p, t)
        F[p, L.VX] = vel[k, 0]
        F[p, L.VY] = vel[k, 1]
    return True


@njit(cache=True)
def _jam(F, I, order, n, t):
    """Stop the pile's base sliding on its immovable support at ``t``, the whole pile taking
    the same change of velocity (so that every contact above keeps its relative motion), if
    that does not raise the pile's kinetic energy; True if it stopped."""
    base = order[0]
    tx = -F[base, L.REST_NY]
    ty = F[base, L.REST_NX]
    _, _, vx, vy = state_at(F, base, t)
    slip = vx * tx + vy * ty
    dvx = -slip * tx
    dvy = -slip * ty
    change = 0.0
    for k in range(n):
        p = order[k]
        m = 1.0 / F[p, L.INV_MASS]
        _, _, px, py = state_at(F, p, t)
        change += m * (px * dvx + py * dvy + 0.5 * (dvx * dvx + dvy * dvy))
    if not change <= 0.0:
        return False
    for k in range(n):
        p = order[k]
        advance(F, p, t)
        F[p, L.VX] += dvx
        F[p, L.VY] += dvy
    return True


@njit(cache=True)
def _sliding_sign(S, x, t):
    """The sign of resting body ``x``'s slip on its support (``contact.contact_slip``; 0: none)."""
    slip, _ = contact_slip(S, x, t)
    return _sign(slip)


@njit(cache=True)
def _sign(value):
    """1, -1 or 0 as ``value`` is positive, negative or zero."""
    if value > 0.0:
        return 1
    if value < 0.0:
        return -1
    return 0


@njit(cache=True)
def _driven_by_friction(S, ground, order, parent, n, slide, acc, spin, t):
    """The first contact (in ``order``) that slides from rest against the direction its slip
    is accelerating in, or -1. Its friction, pointing against the slide, would push it along
    and do positive work: the slide's direction is wrong."""
    F = S[0]
    for k in range(n):
        if slide[k] == 0 or _sliding_sign(S, order[k], t) != 0:
            continue
        q = parent[k]
        aqx = F[ground, L.AX] if q < 0 else acc[q, 0]
        aqy = F[ground, L.AY] if q < 0 else acc[q, 1]
        p = order[k]
        if combine(F[p, L.FRICTION], F[S[1][p, L.SUPPORT], L.FRICTION], S[4][L.FRICTION_RULE]) == 0.0:
            continue  # no friction, no work: either way is the same motion
        along = -(acc[k, 0] - aqx) * F[p, L.REST_NY] + (acc[k, 1] - aqy) * F[p, L.REST_NX]
        along -= spin[k] * F[p, L.RADIUS]
        if along * slide[k] < 0.0:
            return k
    return -1


@njit(cache=True)
def _restart_slips(S, order, n, held, slide, t):
    """Set every contact's mode back to what its motion says (sliding with its relative
    velocity's sign, stuck when it has none; a ``held`` one stuck), after a hold changed the
    pile's loads.

    A contact found to slip in an earlier pass slid from rest in the direction the old loads
    pulled it; under the new ones that direction can be wrong, and friction would then drive
    the slide instead of opposing it (a wedge on the floor, its rider held against the floor,
    slid off from rest with friction as its engine: energy seed 3325). Each hold is made once,
    so the passes stay bounded."""
    for k in range(n):
        slide[k] = 0 if held[k] != 0 else _sliding_sign(S, order[k], t)


@njit(cache=True)
def _settle_alone(S, base, t, out, count):
    """A base with no riders (left): settled on its immovable support, exactly, by
    ``settle_acceleration``; appended to ``out`` if its motion changed."""
    F = S[0]
    I = S[1]
    ax = F[base, L.AX]
    ay = F[base, L.AY]
    alpha = F[base, L.ALPHA]
    mode = I[base, L.REST_MODE]
    advance(F, base, t)
    if not settle_acceleration(S, base, t):
        detach(S, base)
        S[13][L.S_RELEASES] += 1
    elif F[base, L.AX] == ax and F[base, L.AY] == ay and F[base, L.ALPHA] == alpha and I[base, L.REST_MODE] == mode:
        return count
    out[count] = base
    return count + 1


@njit(cache=True)
def settle_pile(S, base, t, out, count):
    """Solve the pile on ``base`` at ``t`` and give its bodies their accelerations and contact
    modes; release the riders that let go. The bodies whose motion changed are advanced to
    ``t`` and appended to ``out`` from ``count`` (all of the pile when any changed); returns
    the new count."""
    F = S[0]
    I = S[1]
    Q = S[4]
    stats = S[13]
    none = np.empty(0, dtype=np.int64)
    while True:
        n = _walk(I, base, none, none, False)
        if n < 2:
            return _settle_alone(S, base, t, out, count)
        order = np.empty(n, dtype=np.int64)
        parent = np.empty(n, dtype=np.int64)
        _walk(I, base, order, parent, True)
        ground = I[base, L.SUPPORT]
        slide = np.empty(n, dtype=np.int64)
        held = np.zeros(n, dtype=np.int64)
        _restart_slips(S, order, n, held, slide, t)
        jolted = False
        acc = np.empty((n, 2))
        spin = np.empty(n)
        stats[L.S_PILE_SOLVES] += 1
        while True:
            k, what = _solve(F, I, Q, ground, order, parent, n, slide, held, acc, spin, t)
            if what == _SLIPS:  # each pass turns one stuck contact to sliding: at most n
                continue
            if what == _JAMS:
                # No sliding motion fits (Painleve): the base sticks at once on its immovable
                # support, by a tangential impact through the pile's contacts or else all the
                # pile carried along with it, if that takes energy out; else (and above the
                # base) the contact lets go.
                if k == 0 and (_jolt(S, order, parent, n, t) or _jam(F, I, order, n, t)):
                    jolted = True
                    slide[0] = 0
                    held[0] = 1
                    continue
                what = _LETS_GO
            if what == _CURVED:
                # A curved rest needs a still support: a still one is held (it would slip
                # under the load), a moving one lets the rider go.
                q = parent[k]
                _, _, qvx, qvy = state_at(F, order[q], t)
                if held[q] == 0 and qvx == 0.0 and qvy == 0.0:
                    held[q] = 1
                    _restart_slips(S, order, n, held, slide, t)
                    continue
                what = _LETS_GO
            if what != _FINE:
                break
            backwards = _driven_by_friction(S, ground, order, parent, n, slide, acc, spin, t)
            if backwards >= 0:
                # No mode of this contact fits (the solve chose its slide under other loads):
                # it sticks, which does no work, whatever friction that takes.
                held[backwards] = 1
                _restart_slips(S, order, n, held, slide, t)
                continue
            pushed = -1
            for k in range(n):
                if held[k] == 0 and (acc[k, 0] != 0.0 or acc[k, 1] != 0.0):
                    if presses_into_neighbour(S, order[k], acc[k, 0], acc[k, 1], True, t):
                        pushed = k
                        break
            if pushed < 0:
                break
            held[pushed] = 1  # each member at most once
            _restart_slips(S, order, n, held, slide, t)
        if what == _LETS_GO:
            x = order[k]
            advance(F, x, t)
            detach(S, x)
            stats[L.S_RELEASES] += 1
            out[count] = x
            count += 1
            count = release_riders(S, x, out, count, t)
            if x == base:
                return count
            continue
        changed = False
        for k in range(n):
            p = order[k]
            mode = L.STUCK if slide[k] == 0 else L.SLIDING
            if F[p, L.AX] != acc[k, 0] or F[p, L.AY] != acc[k, 1] or F[p, L.ALPHA] != spin[k] or I[p, L.REST_MODE] != mode:
                changed = True
        if not changed and not jolted:
            return count
        for k in range(n):
            p = order[k]
            advance(F, p, t)
            F[p, L.AX] = acc[k, 0]
            F[p, L.AY] = acc[k, 1]
            F[p, L.ALPHA] = spin[k]
            I[p, L.REST_MODE] = L.STUCK if slide[k] == 0 else L.SLIDING
            out[count] = p
            count += 1
        return count


@njit(cache=True)
def settle_piles(S, out, count, t):
    """Solve again, once each, the piles marked during this event (``contact.mark_pile``);
    the bodies whose motion changed are appended to ``out`` from ``count``. Returns the new
    count."""
    I = S[1]
    Q = S[4]
    piles = S[19]
    stamp = Q[L.STAMP_COUNTER] + 1  # a fresh gather stamp marks the piles solved
    Q[L.STAMP_COUNTER] = stamp
    k = 0
    while k < Q[L.PILES_N]:  # a solve that releases a rider marks its support's pile again
        x = piles[k]
        k += 1
        if I[x, L.SUPPORT] < 0 or I[x, L.ALIVE] == 0:
            continue
        base = base_of(I, x)
        if I[base, L.STAMP] == stamp:
            continue
        I[base, L.STAMP] = stamp
        count = settle_pile(S, base, t, out, count)
    Q[L.PILES_N] = 0
    return count
