"""The pivot rule: a pressed contact that cannot rest neither converges (Zeno) nor gains energy.

See ``pivot``. The lift it gives a contact nearly at rest is paid for out of the
pair's own kinetic energy: first out of the contact's slip (``paid_lift``), else out of
the bodies' motion that a contact impulse cannot reach, with momentum and angular
momentum kept (``lift_from_motion``).
"""

from __future__ import annotations

import math

import numpy as np
from pge._jit_cache import njit

from pge.core import layout as L
from pge.core.contact import combine, detach, relative_tangential, rolls, settle_acceleration, turn_if_clear
from pge.core.grid import gather
from pge.core.impulse import contact_impulse
from pge.core.motion import advance, spin_at, state_at
from pge.core.overlap import nearest_normal
from pge.core.predict import still_speed
from pge.core.response import apply_impulse, contact_response
from pge.numerics.linalg import solve_spd
from pge.toi.rotating import press_noise, press_rate

CIRCLE = 0
#: a pressed corner slower than this fraction of the pivot speed is lifted to it
KICK = 0.1
#: a lift paid for by the bodies may be this much slower than the pivot speed, no slower
SLOWEST = 1e-3


@njit(cache=True)
def paid_lift(un, ut, knn, knt, ktt, jn, jt, target):
    """The impulse ``(jn, jt)`` topped up so that the contact leaves at ``target`` along the
    normal, with the lift paid for out of the contact's slip: returns ``(jn, jt, paid)``.

    In contact space (relative contact-point velocity ``w``, inverse mass
    ``K``) the pair's kinetic energy that an impulse there can change is
    ``w^T K^-1 w / 2``. With the normal part fixed at ``target`` it is least,
    ``target^2 / (2 k_nn)``, at the slip ``w_t* = k_nt target / k_nn``. The
    slip after a plain normal top-up is moved towards ``w_t*`` just far enough
    that the energy is no more than before the collision. ``paid`` is False
    when even ``w_t*`` costs more (the contact barely moves at all): then the
    lift gains at most ``target^2 / (2 k_nn)``, about ``m |g''| h``.
    """
    leaving = un + knn * jn + knt * jt
    if leaving < target:
        jn += (target - leaving) / knn
    slip = ut + knt * jn + ktt * jt
    det = knn * ktt - knt * knt
    if not det > 1e-12 * knn * ktt:
        # No independent slip: the energy is target^2 / (2 k_nn) whatever the slip.
        return jn, jt, target * target <= un * un
    before = (ktt * un * un - 2.0 * knt * un * ut + knn * ut * ut) / det  # 2 E(u)
    after = (ktt * target * target - 2.0 * knt * target * slip + knn * slip * slip) / det
    if after <= before:
        return jn, jt, True
    cheapest = knt * target / knn
    reserve = det * (knn * before - target * target)
    if reserve < 0.0:
        slip = cheapest
        paid = False
    else:
        # The slip on slip's side of the cheapest one at which the energy is ``before``
        # (shrunk a little, so that rounding cannot leave it above).
        half_width = math.sqrt(reserve) / knn * (1.0 - 1e-9)
        slip = cheapest + half_width if slip > cheapest else cheapest - half_width
        paid = True
    # The impulse that makes the contact-space velocity (target, slip): j = K^-1 (w - u).
    dn = target - un
    dt = slip - ut
    jn = (ktt * dn - knt * dt) / det
    jt = (knn * dt - knt * dn) / det
    return jn, jt, paid


@njit(cache=True)
def pivot(S, a, b, px, py, nx, ny, owner, restitution, mu, pre):
    """Keep a pressed contact that cannot rest from a Zeno run of ever smaller bounces.

    A polygon rocking on a corner under gravity strikes it ever more gently
    and often, converging on a contact that lasts (the body pivots), which
    has no closed form; so does a body wedged between two others that each
    rest on something else. Instead, while the contact is pressed shut
    (``press_rate`` < 0), with ``v_min = sqrt(2 |g''| h)`` the speed that lifts
    the corner by ``h = rest_height x`` the smaller bounding radius (but no
    less than twice the pair's rounding speed, ``still_speed``, which the
    kernels would take for no motion at all), it leaves
    at ``max(e u, v_min)`` when it came in at ``u >= v_min``; elastically
    (``u``) when ``KICK v_min <= u < v_min``; and at ``v_min`` when it came in
    slower still (a corner nearly at rest and pressed down), the only case
    that gains energy, at most ``m |g''| h``. Slow pressed bounces therefore
    neither converge nor gain energy, and a pivot takes events at intervals
    of about ``2 v_min / |g''|``. The bounce is then done again from the velocities before it
    (``pre``), through ``contact_impulse`` with the restitution this asks for,
    so friction and the energy guard apply as in any collision; a lift the
    pair cannot pay for is not given to riders that static friction would hold
    on supports at rest: they stop instead (``_holds_at_rest``). ``owner`` is the
    body whose face the contact is on (``-1``: a circle round a corner or a circle),
    which says how the normal turns (``press_rate``). Returns the
    new normal impulse, or -1.0 if the rule does not apply; whether the contact
    was lifted from (nearly) at rest; and whether that lift is still unpaid (the caller
    may let other bodies pay: ``others_pay_for_lift``).
    """
    F = S[0]
    I = S[1]
    P = S[3]
    keep_a = I[a, L.SUPPORT] >= 0  # still resting: it was pressed into its support
    keep_b = I[b, L.SUPPORT] >= 0
    turns_a = not keep_a or I[a, L.KIND] == CIRCLE
    turns_b = not keep_b or I[b, L.KIND] == CIRCLE
    va_x, va_y, wa, vb_x, vb_y, wb = pre
    rax = px - F[a, L.X]
    ray = py - F[a, L.Y]
    rbx = px - F[b, L.X]
    rby = py - F[b, L.Y]
    spin_a = wa if I[a, L.KIND] != CIRCLE else 0.0
    spin_b = wb if I[b, L.KIND] != CIRCLE else 0.0
    dax = F[a, L.AX] - F[b, L.AX]
    day = F[a, L.AY] - F[b, L.AY]
    ox = F[a, L.X] - F[b, L.X]
    oy = F[a, L.Y] - F[b, L.Y]
    # How the normal turns (see press_rate): with the face's owner, or round a curve.
    point_x = rbx
    point_y = rby
    bend = 0.0
    omega_face = spin_b if owner == b else spin_a
    if I[a, L.KIND] == CIRCLE:
        if owner == b:  # the centre against b's face
            point_x = ox
            point_y = oy
        elif I[b, L.KIND] == CIRCLE:  # centre against centre
            point_x = 0.0
            point_y = 0.0
            bend = 1.0 / (F[a, L.RADIUS] + F[b, L.RADIUS])
            omega_face = 0.0
        else:  # the centre round b's corner
            bend = 1.0 / F[a, L.RADIUS]
            omega_face = 0.0
    curvature = press_rate(
        point_x, point_y, nx, ny, ox, oy, va_x - vb_x, va_y - vb_y, dax, day, spin_a, spin_b, omega_face, bend
    )
    # Within rounding of "pressed" counts as pressed: the kernel may have judged it so.
    still = still_speed(F, a, b, F[a, L.X], F[a, L.Y], va_x, va_y, F[b, L.X], F[b, L.Y], vb_x, vb_y)
    noise = press_noise(
        math.hypot(dax, day), math.hypot(va_x - vb_x, va_y - vb_y), abs(spin_a), abs(spin_b),
        F[a, L.REACH] if I[a, L.KIND] != CIRCLE else 0.0, F[b, L.REACH], still, bend,
    )
    if not curvature < noise:
        return -1.0, False, False
    ux = va_x - wa * ray - (vb_x - wb * rby)
    uy = va_y + wa * rax - (vb_y + wb * rbx)
    un = ux * nx + uy * ny
    ut = -ux * ny + uy * nx
    approach = max(-un, 0.0)
    floor = math.sqrt(max(-2.0 * curvature, 0.0) * P[L.REST_HEIGHT] * min(F[a, L.REACH], F[b, L.REACH]))
    floor = max(floor, 2.0 * still)  # the kernels would take a slower lift for rounding
    kick = False
    if approach >= floor:
        target = max(restitution * approach, floor)  # never more than it came in with
    elif approach >= KICK * floor:
        target = approach  # elastic: slow pressed bounces neither die out nor gain
    else:
        target = floor  # (nearly) at rest on a pressed corner: lift it
        kick = True
    now_x = F[a, L.VX] - F[a, L.OMEGA] * ray - (F[b, L.VX] - F[b, L.OMEGA] * rby)
    now_y = F[a, L.VY] + F[a, L.OMEGA] * rax - (F[b, L.VY] + F[b, L.OMEGA] * rbx)
    if now_x * nx + now_y * ny >= target:
        return -1.0, False, False
    # Bounce again from the velocities before the collision.
    F[a, L.VX] = va_x
    F[a, L.VY] = va_y
    F[a, L.OMEGA] = wa
    F[b, L.VX] = vb_x
    F[b, L.VY] = vb_y
    F[b, L.OMEGA] = wb
    tx = -ny
    ty = nx
    ann, ant, att = contact_response(F, a, keep_a, turns_a, rax, ray, nx, ny, tx, ty)
    bnn, bnt, btt = contact_response(F, b, keep_b, turns_b, rbx, rby, nx, ny, tx, ty)
    knn = ann + bnn
    if not knn > 0.0:
        return -1.0, False, False
    knt = ant + bnt
    ktt = att + btt
    jn = 0.0
    jt = 0.0
    if un < 0.0:
        jn, jt = contact_impulse(un, ut, knn, knt, ktt, 1.0 if kick else target / approach, mu)
    paid = True
    if kick:
        jn, jt, paid = paid_lift(un, ut, knn, knt, ktt, jn, jt, target)
        S[13][L.S_PIVOT_LIFTS] += 1
    jx = jn * nx + jt * tx
    jy = jn * ny + jt * ty
    apply_impulse(F, a, keep_a, turns_a, jx, jy, rax, ray)
    apply_impulse(F, b, keep_b, turns_b, -jx, -jy, rbx, rby)
    if not paid and _holds_at_rest(S, a) and _holds_at_rest(S, b):
        # Riders on supports at rest, pressed together too gently to pay for a lift:
        # friction would stop them within a rest height, so they stop now.
        for x in (a, b):
            if I[x, L.SUPPORT] >= 0:
                F[x, L.VX] = 0.0
                F[x, L.VY] = 0.0
                F[x, L.OMEGA] = 0.0
        S[13][L.S_STOPS] += 1
        return jn, kick, False
    if not paid:
        # What the bodies that took part may spend: their energy before the bounce, less
        # what a kept-resting one has now (fixed bodies keep theirs).
        budget = 0.0
        for x in (a, b):
            if F[x, L.INV_MASS] > 0.0:
                if x == a:
                    budget += _kinetic(F, x, va_x, va_y, wa)
                else:
                    budget += _kinetic(F, x, vb_x, vb_y, wb)
                if I[x, L.SUPPORT] >= 0:
                    budget -= _kinetic(F, x, F[x, L.VX], F[x, L.VY], F[x, L.OMEGA])
        free_a = a if not keep_a else -1
        free_b = b if not keep_b else -1
        if not lift_from_motion(F, free_a, free_b, px, py, nx, ny, budget, SLOWEST * target):
            if tip_to_pay(S, a, b, owner, px, py, nx, ny, pre):
                S[13][L.S_TIPS] += 1
            else:
                return jn, kick, True
    return jn, kick, False


#: a turn that pays for a lift may be no larger than this (radians)
_LARGEST_TIP = 0.01
#: a turn may not push the body into another by more than this many bounding radii
_TIP_OVERLAP = 1e-12
#: slides of the corner along the face (in units of the tip's arc at the bounding radius)
#: tried when the tip alone would push into a neighbour
_TIP_SLIDES = (0.5, 1.0, 2.0)


@njit(cache=True)
def tip_to_pay(S, a, b, owner, px, py, nx, ny, pre):
    """Pay for a lift the pair's motion cannot pay for by tipping the body that stands on a
    corner: turn it about that corner ``p`` (which stays where it is) in the direction its
    weight turns it, just far enough that the work its acceleration does equals the kinetic
    energy the lift gave (``pre``: velocities and spins before it). A polygon standing on a
    corner in a pile that cannot hold it tips or slides under contact forces acting over time,
    which impulses cannot do; the lifts imitate that motion and the turn is the part of it
    that releases the energy they cost. Refused (False, nothing changed) for a curved
    contact, a circle, a fixed or resting body, a turn larger than ``_LARGEST_TIP`` or one
    that would push the body into a neighbour."""
    F = S[0]
    I = S[1]
    if owner < 0:
        return False
    x = b if owner == a else a  # its corner touches the other's face
    other = owner
    if I[x, L.KIND] == CIRCLE or I[x, L.FIXED] != 0 or I[x, L.SUPPORT] >= 0 or not F[x, L.INV_MASS] > 0.0:
        return False
    gain = lift_gain(F, a, b, pre)
    if not gain > 0.0:
        return True
    mass = 1.0 / F[x, L.INV_MASS]
    ax = F[x, L.FREE_AX]
    ay = F[x, L.FREE_AY]
    rx = F[x, L.X] - px
    ry = F[x, L.Y] - py
    torque = rx * ay - ry * ax  # the work of a turn by d is about mass * d * torque
    if torque == 0.0:
        return False
    delta = gain / (mass * torque)
    work = 0.0
    c = 1.0
    s = 0.0
    for _ in range(8):
        if not abs(delta) <= _LARGEST_TIP:
            return False
        c = math.cos(delta)
        s = math.sin(delta)
        work = mass * (ax * (c * rx - s * ry - rx) + ay * (s * rx + c * ry - ry))
        if work >= gain:
            break
        delta *= (gain / work if work > 0.0 else 2.0) * (1.0 + 1e-9)
    if not work >= gain:
        return False
    if turn_if_clear(S, x, px, py, c, s, delta, 0.0, 0.0, other, _TIP_OVERLAP, F[x, L.T0]):
        return True
    # A neighbour leans on the side it tips to: the corner slides along the face under it as
    # far as the tipping side moves, one way or the other, if the turn and the slide together
    # still do the work (uphill on a sloping face the slide costs some).
    tx = -ny
    ty = nx
    for scale in _TIP_SLIDES:
        for sign in (1.0, -1.0):
            step = sign * scale * abs(delta) * F[x, L.REACH]
            if not work + mass * step * (ax * tx + ay * ty) >= gain:
                continue
            if turn_if_clear(S, x, px, py, c, s, delta, step * tx, step * ty, other, _TIP_OVERLAP, F[x, L.T0]):
                return True
    return False


#: at most this many bodies of the pile round an unpaid lift are searched for payers
_LARGEST_PILE = 64


@njit(cache=True)
def others_pay_for_lift(S, a, b, pre, out, count, t):
    """Pay for a lift that neither the pair's motion nor a move of the pair could pay for out of
    the kinetic energy of other bodies (``_payable``: a free body's motion, a resting circle's
    spin), taking it from as near the pair as can pay.

    First the pile round the pair, ring by ring: bodies within a rest height of a body already
    in it, through free and resting bodies, never through fixed or sleeping ones. In a pile
    that cannot hold still its bodies are what press the pair together, and the contact
    forces acting over time that the lifts imitate would take the energy from them. Once the
    bodies found so far have more energy than the lift gave, each is slowed by the same
    factor. If the pile (at most ``_LARGEST_PILE`` bodies) is too poor, the richest bodies of
    the world pay, fewest first (counted in ``stats['far_payments']``). The slowed bodies are
    advanced to ``t`` and appended to ``out`` from ``count``. Returns ``(paid, count)``;
    nothing changes when all of them together are too poor."""
    F = S[0]
    I = S[1]
    P = S[3]
    scratch = S[15]
    gain = lift_gain(F, a, b, pre)
    if not gain > 0.0:
        return True, count
    pile = np.empty(_LARGEST_PILE, dtype=np.int64)
    pile[0] = a
    pile[1] = b
    size = 2
    ring_start = 0
    total = 0.0
    while ring_start < size and not total > gain:
        ring_end = size
        for k in range(ring_start, ring_end):
            x = pile[k]
            if I[x, L.FIXED] != 0:
                continue
            m = gather(S, x)
            for q in range(m):
                j = scratch[q]
                if I[j, L.FIXED] != 0 or I[j, L.SLEEP_NEXT] >= 0 or size == _LARGEST_PILE:
                    continue
                seen = False
                for r in range(size):
                    seen = seen or pile[r] == j
                if seen:
                    continue
                _, _, depth = nearest_normal(S, x, j)
                if depth < -P[L.REST_HEIGHT] * (F[x, L.REACH] + F[j, L.REACH]):
                    continue
                pile[size] = j
                total += _payable(F, I, j, t)
                size += 1
        ring_start = ring_end
    if total > gain:
        return True, _pay(S, pile[2:size], gain / total, out, count, t)
    # The pile is too poor: the richest bodies anywhere pay, as few as will do.
    candidates = np.empty(I.shape[0], dtype=np.int64)
    energies = np.empty(I.shape[0])
    n = 0
    for j in range(I.shape[0]):
        if j == a or j == b or I[j, L.ALIVE] == 0:
            continue
        energy = _payable(F, I, j, t)
        if energy > 0.0:
            candidates[n] = j
            energies[n] = energy
            n += 1
    order = np.argsort(-energies[:n], kind="mergesort")  # stable: deterministic among equals
    total = 0.0
    used = 0
    while used < n and not total > gain:
        total += energies[order[used]]
        used += 1
    if not total > gain:
        return False, count
    S[13][L.S_FAR_PAYMENTS] += 1
    return True, _pay(S, candidates[order[:used]], gain / total, out, count, t)


@njit(cache=True)
def _payable(F, I, j, t):
    """The kinetic energy body ``j`` can give up to pay for a lift at ``t`` without changing
    what it rests on: all of a free body's (velocity and spin), a resting circle's spin (a
    rolling one then skids, and its friction only takes more energy out), nothing of a
    fixed, sleeping or resting polygon."""
    if I[j, L.FIXED] != 0 or I[j, L.SLEEP_NEXT] >= 0 or not F[j, L.INV_MASS] > 0.0:
        return 0.0
    if I[j, L.SUPPORT] >= 0:
        if I[j, L.KIND] != CIRCLE:
            return 0.0
        return _kinetic(F, j, 0.0, 0.0, spin_at(F, j, t))
    _, _, vx, vy = state_at(F, j, t)
    return _kinetic(F, j, vx, vy, F[j, L.OMEGA])


@njit(cache=True)
def _pay(S, payers, share, out, count, t):
    """Slow every body of ``payers`` by the factor that takes ``share`` of its payable energy
    (``_payable``) away; append those that changed to ``out`` from ``count``. A resting
    circle whose spin changed is settled again (its slip changed)."""
    F = S[0]
    I = S[1]
    factor = math.sqrt(1.0 - share) * (1.0 - 1e-12)
    for j in payers:
        if not _payable(F, I, j, t) > 0.0:
            continue
        advance(F, j, t)
        if I[j, L.SUPPORT] < 0:
            F[j, L.VX] *= factor
            F[j, L.VY] *= factor
        F[j, L.OMEGA] *= factor
        if I[j, L.SUPPORT] >= 0 and not settle_acceleration(S, j, t):
            detach(S, j)
            S[13][L.S_RELEASES] += 1
        out[count] = j
        count += 1
    return count


@njit(cache=True)
def _holds_at_rest(S, x):
    """True if body ``x`` would stay where it is if it stopped: fixed and not moving, or
    resting on a support that is at rest (no velocity, spin or acceleration) and held there
    by static friction."""
    F = S[0]
    I = S[1]
    Q = S[4]
    if I[x, L.FIXED] != 0:
        return F[x, L.VX] == 0.0 and F[x, L.VY] == 0.0 and F[x, L.OMEGA] == 0.0
    s = I[x, L.SUPPORT]
    if s < 0:
        return False
    if F[s, L.VX] != 0.0 or F[s, L.VY] != 0.0 or F[s, L.OMEGA] != 0.0 or F[s, L.AX] != 0.0 or F[s, L.AY] != 0.0:
        return False
    _, at, an = relative_tangential(S, x, S[3][L.TIME])
    mu = combine(F[x, L.FRICTION], F[s, L.FRICTION], Q[L.FRICTION_RULE])
    if rolls(F, I, x, mu):
        return an < 0.0 and at == 0.0  # friction cannot hold a circle on a slope: it rolls
    return an < 0.0 and abs(at) <= -mu * an


@njit(cache=True)
def lift_gain(F, a, b, pre):
    """The kinetic energy the bodies ``a`` and ``b`` have gained since ``pre`` (their
    velocities and spins then); fixed bodies count for nothing."""
    va_x, va_y, wa, vb_x, vb_y, wb = pre
    gain = 0.0
    for y in (a, b):
        if F[y, L.INV_MASS] > 0.0:
            gain += _kinetic(F, y, F[y, L.VX], F[y, L.VY], F[y, L.OMEGA])
            if y == a:
                gain -= _kinetic(F, y, va_x, va_y, wa)
            else:
                gain -= _kinetic(F, y, vb_x, vb_y, wb)
    return gain


@njit(cache=True)
def _kinetic(F, x, vx, vy, w):
    """Kinetic energy of body ``x`` (not fixed) at velocity ``(vx, vy)`` and spin ``w``."""
    spin = 0.5 * w * w / F[x, L.INV_INERTIA] if F[x, L.INV_INERTIA] > 0.0 else 0.0
    return 0.5 * (vx * vx + vy * vy) / F[x, L.INV_MASS] + spin


@njit(cache=True)
def lift_from_motion(F, a, b, px, py, nx, ny, budget, slowest):
    """Bring the kinetic energy of the free bodies among ``a`` and ``b`` (``-1``: not free)
    down to ``budget`` without changing what the lift set: their relative normal velocity
    at the contact ``(px, py)``, and, when both are free, their total momentum and angular
    momentum. If that costs more than the budget, the contact leaves slower instead, as
    fast as the budget allows, but not slower than ``slowest``; False (nothing changed)
    if even that is impossible.

    With ``v`` the free bodies' velocities and spins, ``M`` their masses and
    inertias and ``C v = d`` the kept quantities, the least energy is at
    ``v* = M^-1 C^T lam`` with ``(C M^-1 C^T) lam = d`` and equals ``lam . d / 2``.
    Along the segment from ``v*`` to the present ``v`` the energy is
    ``E* + s^2 (E - E*)`` (``v*`` is the M-orthogonal projection), so the state
    at ``s = sqrt((budget - E*) / (E - E*))`` spends exactly the budget. This
    is the work a lasting pivot contact does between the bodies' motions,
    which single impulses at the contact point cannot do.
    """
    ids = np.empty(2, dtype=np.int64)
    signs = np.empty(2)
    n = 0
    if a >= 0 and F[a, L.INV_MASS] > 0.0 and F[a, L.INV_INERTIA] > 0.0:
        ids[n] = a
        signs[n] = 1.0
        n += 1
    if b >= 0 and F[b, L.INV_MASS] > 0.0 and F[b, L.INV_INERTIA] > 0.0:
        ids[n] = b
        signs[n] = -1.0
        n += 1
    if n == 0:
        return False
    dof = 3 * n
    rows = 4 if n == 2 else 1
    v = np.empty(dof)
    w = np.empty(dof)  # inverse masses
    C = np.zeros((rows, dof))
    for k in range(n):
        x = ids[k]
        v[3 * k] = F[x, L.VX]
        v[3 * k + 1] = F[x, L.VY]
        v[3 * k + 2] = F[x, L.OMEGA]
        w[3 * k] = F[x, L.INV_MASS]
        w[3 * k + 1] = F[x, L.INV_MASS]
        w[3 * k + 2] = F[x, L.INV_INERTIA]
        rx = px - F[x, L.X]
        ry = py - F[x, L.Y]
        # relative normal velocity at the contact: n . (v + w x r), a's minus b's
        C[0, 3 * k] = signs[k] * nx
        C[0, 3 * k + 1] = signs[k] * ny
        C[0, 3 * k + 2] = signs[k] * (rx * ny - ry * nx)
        if n == 2:
            m = 1.0 / F[x, L.INV_MASS]
            C[1, 3 * k] = m
            C[2, 3 * k + 1] = m
            # angular momentum about the contact point (centroid at -r from it)
            C[3, 3 * k] = m * ry
            C[3, 3 * k + 1] = -m * rx
            C[3, 3 * k + 2] = 1.0 / F[x, L.INV_INERTIA]
    energy = 0.0
    for q in range(dof):
        energy += 0.5 * v[q] * v[q] / w[q]
    if energy <= budget:
        return True
    d = np.zeros(rows)
    A = np.zeros((rows, rows))
    for i in range(rows):
        for q in range(dof):
            d[i] += C[i, q] * v[q]
            for j in range(rows):
                A[i, j] += C[i, q] * w[q] * C[j, q]
    lam = solve_spd(A, d, 1e-300)
    least = 0.0
    for i in range(rows):
        least += 0.5 * lam[i] * d[i]
    if least < budget:
        s = math.sqrt((budget - least) / (energy - least)) * (1.0 - 1e-9)
    else:
        # Not even the cheapest state leaves at this speed: leave as fast as the budget
        # allows. The least energy at leaving speed u is the quadratic
        # (d0^T A^-1 d0 + 2 u (A^-1 d0)_0 + u^2 (A^-1)_00) / 2, d0 = d without its speed.
        spent = budget * (1.0 - 1e-9)
        d[0] = 0.0
        base = solve_spd(A, d, 1e-300)
        unit = np.zeros(rows)
        unit[0] = 1.0
        column = solve_spd(A, unit, 1e-300)
        c0 = 0.0
        for i in range(rows):
            c0 += base[i] * d[i]
        qa = column[0]
        qb = base[0]
        disc = qb * qb - qa * (c0 - 2.0 * spent)
        if not (qa > 0.0 and disc >= 0.0):
            return False
        speed = (-qb + math.sqrt(disc)) / qa
        if not speed >= slowest:
            return False
        d[0] = speed
        lam = solve_spd(A, d, 1e-300)
        s = 0.0
    best = np.zeros(dof)
    for q in range(dof):
        for i in range(rows):
            best[q] += w[q] * C[i, q] * lam[i]
    for k in range(n):
        x = ids[k]
        F[x, L.VX] = best[3 * k] + s * (v[3 * k] - best[3 * k])
        F[x, L.VY] = best[3 * k + 1] + s * (v[3 * k + 1] - best[3 * k + 1])
        F[x, L.OMEGA] = best[3 * k + 2] + s * (v[3 * k + 2] - best[3 * k + 2])
    return True
