"""The compiled event loop: collisions, contact changes, horizons; plus validation.

State is one tuple ``S`` of arrays (see ``pge.core.state.EngineState``):
``(F, I, OL, P, Q, head, static_start, static_items, heap, slot_time,
slot_key, slot_data, free, stats, out, scratch, pending, group, OB, piles)``; column meanings
are in ``pge.core.layout``.

One event (``run``): pop the earliest queue entry; skip it if stale (a
body's invalidation counter moved on); advance the bodies involved to the
event time; resolve it; *touch* every body whose motion changed (new
counter, new swept box, new contact event) and queue it for prediction
against the bodies whose boxes overlap its own. Nothing else is visited, so
an event costs the same among a thousand bodies as among a hundred thousand.
"""

from __future__ import annotations

import math

import numpy as np
from pge._jit_cache import njit

from pge.core import layout as L
from pge.core.contact import (
    carry_or_release_riders,
    combine,
    contact_slip,
    detach,
    grounded,
    lowest_along,
    presses_into_neighbour,
    relative_tangential,
    release_riders,
    resettle_riders,
    schedule_contact_event,
    settle_acceleration,
    try_rest,
)
from pge.core.grid import gather
from pge.core.impulse import contact_impulse
from pge.core.motion import advance, orient
from pge.core.pile import settle_piles
from pge.core.pivot import others_pay_for_lift, pivot
from pge.core.predict import new_mark, place, predict
from pge.core.response import apply_impulse, contact_response
from pge.core.sleep import try_sleep, wake
from pge.core.queue import pop_earliest
from pge.core.tuning import CONTACT_MARGIN, STORM_SPAN, STORM_TICKS
from pge.toi.circle_circle import circle_circle_contact
from pge.toi.circle_polygon import circle_polygon_contact
from pge.toi.polygon_polygon import polygon_polygon_contact
from pge.toi.rotating import rotating_polygon_polygon_contact

_INF = math.inf
CIRCLE = 0
#: a body slower than this many of its bounding radii per second is stopped after a collision
NO_SPEED = 1e-150


# ---------------------------------------------------------------- work list


@njit(cache=True, inline="always")
def queue_prediction(S, i):
    """Ask for body ``i`` to be predicted again before the next event."""
    Q = S[4]
    pending = S[16]
    if Q[L.PENDING_DONE] == Q[L.PENDING_N]:
        Q[L.PENDING_N] = 0
        Q[L.PENDING_DONE] = 0
        Q[L.PENDING_MARK] = new_mark(S)
    pending[Q[L.PENDING_N]] = i
    Q[L.PENDING_N] += 1


@njit(cache=True)
def drain_predictions(S):
    """Predict the queued bodies, each pair once; False if event slots ran low first."""
    I = S[1]
    Q = S[4]
    pending = S[16]
    mark = Q[L.PENDING_MARK]
    while Q[L.PENDING_DONE] < Q[L.PENDING_N]:
        if Q[L.FREE_N] < Q[L.MIN_FREE]:
            return False
        i = pending[Q[L.PENDING_DONE]]
        Q[L.PENDING_DONE] += 1
        if I[i, L.MARK] == mark or I[i, L.ALIVE] == 0:
            continue
        predict(S, i, mark)
        I[i, L.MARK] = mark
    return True


@njit(cache=True, inline="always")
def touch(S, i):
    """Body ``i``'s motion or shape changed now: invalidate its events, renew its box and
    contact event, and queue it for prediction."""
    I = S[1]
    if I[i, L.ALIVE] == 0:
        return
    I[i, L.COUNT] += 1
    place(S, i)
    if I[i, L.SUPPORT] >= 0:
        schedule_contact_event(S, i)
    queue_prediction(S, i)


@njit(cache=True)
def touch_group(S, ids, count):
    """``touch`` the first ``count`` bodies of ``ids``."""
    for k in range(count):
        touch(S, ids[k])


@njit(cache=True)
def touch_one(S, i):
    """``touch`` as a call, for the places that may do without it inlined.

    Every inlined copy of ``touch`` (with ``place`` and the queue inside it) is typed and
    compiled again, seconds each on a cold start; a call costs a few nanoseconds an event.
    """
    touch(S, i)


@njit(cache=True)
def release_body(S, i, t, out):
    """Wake body ``i``'s island (if asleep) or, for a fixed body, the islands near it;
    release it from its support (if resting) and every body resting on it; the pile it
    leaves is solved again.

    The bodies whose motion changes are written to ``out``; returns how many.
    Python calls this before changing a body through the API.
    """
    I = S[1]
    stats = S[13]
    count = wake(S, i, out, 0, t)
    if I[i, L.FIXED] != 0 and stats[L.S_SLEEPS] > 0:
        # A fixed body may hold up a sleeping pile: wake every one near it.
        near = gather(S, i)
        for k in range(near):
            count = wake(S, S[15][k], out, count, t)
    if I[i, L.SUPPORT] >= 0:
        advance(S[0], i, t)
        detach(S, i)
        stats[L.S_RELEASES] += 1
        out[count] = i
        count += 1
    count = release_riders(S, i, out, count, t)
    return settle_piles(S, out, count, t)


# ------------------------------------------------------------------- response


@njit(cache=True)
def _lift_rate(F, I, OL, x, nx, ny, px, py):
    """How fast an impulse along ``(nx, ny)`` at ``(px, py)`` lifts an end of resting
    polygon ``x``'s base off its support, per unit of impulse (0: the support holds the
    base down; then the body only slides).

    The base's ends are the polygon's extreme corners on the support side.
    The ends' normal velocities are linear in the impulse, so a unit impulse
    decides: free, both ends leave or stay; else the support pushes at one
    end (a non-negative reaction that stops it) and the other may lift.
    """
    mx = F[x, L.REST_NX]
    my = F[x, L.REST_NY]
    inv_m = F[x, L.INV_MASS]
    inv_i = F[x, L.INV_INERTIA]
    cx = F[x, L.X]
    cy = F[x, L.Y]
    start = I[x, L.OUTLINE_START]
    n = I[x, L.OUTLINE_N]
    lowest = lowest_along(OL, start, n, mx, my)
    tolerance = 1e-9 * F[x, L.REACH]
    u_lo = _INF
    u_hi = -_INF
    r1 = 0.0
    r2 = 0.0
    for k in range(start, start + n):
        if OL[k, 0] * mx + OL[k, 1] * my <= lowest + tolerance:
            along = -OL[k, 0] * my + OL[k, 1] * mx
            lever = OL[k, 0] * my - OL[k, 1] * mx  # r x m
            if along < u_lo:
                u_lo = along
                r1 = lever
            if along > u_hi:
                u_hi = along
                r2 = lever
    spin = inv_i * ((px - cx) * ny - (py - cy) * nx)
    push = inv_m * (nx * mx + ny * my)
    v1 = push + spin * r1  # normal velocity of each end under the unit impulse
    v2 = push + spin * r2
    scale = 1e-12 * (abs(push) + abs(spin) * F[x, L.REACH])
    if v1 >= -scale and v2 >= -scale:
        return max(v1, v2, 0.0)
    for end in range(2):
        ra = r1 if end == 0 else r2
        rb = r2 if end == 0 else r1
        va = v1 if end == 0 else v2
        vb = v2 if end == 0 else v1
        if va < 0.0:
            reaction = -va / (inv_m + inv_i * ra * ra)
            lift = vb + reaction * (inv_m + inv_i * ra * rb)
            if lift > scale:
                return lift
    return 0.0


@njit(cache=True)
def _keeps_resting(F, I, OL, x, dx, dy, px, py, approach, rest_height):
    """True if resting body ``x`` keeps resting under an impulse along ``(dx, dy)`` at
    ``(px, py)`` from a contact closing at ``approach``: the impulse presses it into its
    support (which then absorbs the part along the rest normal and any turning) without
    lifting an end of a polygon's base, or it lifts the body slower than a bounce of the
    rest height would (the rest rule would bring it straight back). Otherwise it is
    released: pulled off its support, or tipped over by a side hit high enough."""
    if I[x, L.SUPPORT] < 0:
        return False
    mx = F[x, L.REST_NX]
    my = F[x, L.REST_NY]
    vx = F[x, L.VX]
    vy = F[x, L.VY]
    if abs(vx * mx + vy * my) > 1e-12 * math.hypot(vx, vy):
        # Its support moves along the rest normal (a tilted edge sliding by): taking
        # the impulse's normal part, it would do work on the pair.
        return False
    along = dx * mx + dy * my
    if I[x, L.KIND] == CIRCLE:
        if along <= 0.0:
            return True
        rate = F[x, L.INV_MASS] * along
    else:
        rate = _lift_rate(F, I, OL, x, dx, dy, px, py)
        if rate == 0.0:
            return True
    # The impulse is at most (1 + e) approach / k with k the body's own share of the
    # contact-space inverse mass along the normal.
    rn = (px - F[x, L.X]) * dy - (py - F[x, L.Y]) * dx
    own = F[x, L.INV_MASS] + F[x, L.INV_INERTIA] * rn * rn
    if not own > 0.0:
        return True
    s = I[x, L.SUPPORT]
    pressing = -((F[x, L.FREE_AX] - F[s, L.AX]) * mx + (F[x, L.FREE_AY] - F[s, L.AY]) * my)
    settle = math.sqrt(2.0 * max(pressing, 0.0) * rest_height * F[x, L.REACH])
    return rate * 2.0 * approach / own <= settle


@njit(cache=True)
def _laden_knock(S, a, b, keep_a, keep_b, bounce):
    """Whether a resting body carrying riders knocks into one that cannot give way (fixed,
    asleep or resting) so slowly that it would bounce off slower than the pivot rule's lift
    speed: the knock is then plastic. Each bounce would let its riders go, and their coming
    to rest again push it back, a Zeno run at one instant."""
    F = S[0]
    I = S[1]
    for x, y, keep in ((a, b, keep_a), (b, a, keep_b)):
        if keep and I[x, L.RIDER_HEAD] >= 0 and grounded(I, y):
            accel = math.hypot(F[x, L.FREE_AX], F[x, L.FREE_AY])
            if bounce * bounce < 2.0 * accel * S[3][L.REST_HEIGHT] * F[x, L.REACH]:
                return True
    return False


@njit(cache=True)
def _held(S, x, jx, jy, t):
    """Whether resting body ``x``, given the impulse ``(jx, jy)`` (of which its support takes
    the part along its rest normal), would move into a neighbour that cannot give way."""
    F = S[0]
    mx = F[x, L.REST_NX]
    my = F[x, L.REST_NY]
    along = jx * mx + jy * my
    dvx = (jx - along * mx) * F[x, L.INV_MASS]
    dvy = (jy - along * my) * F[x, L.INV_MASS]
    if dvx == 0.0 and dvy == 0.0:
        return False
    return presses_into_neighbour(S, x, dvx, dvy, False, t)


@njit(cache=True)
def contact_geometry(S, a, b, feature):
    """Contact point and unit normal (from b towards a) of ``a`` and ``b`` at their common
    reference time, with ``feature`` from the kernel; also the edge carrying a flat
    contact: ``(px, py, nx, ny, owner, edge)`` (``owner = -1``: none)."""
    F = S[0]
    I = S[1]
    OL = S[2]
    n_b = I[b, L.OUTLINE_N]
    owner = -1
    edge = 0
    if I[a, L.KIND] == CIRCLE:
        if I[b, L.KIND] == CIRCLE:
            px, py, nx, ny = circle_circle_contact(F[a, L.X], F[a, L.Y], F[a, L.RADIUS], F[b, L.X], F[b, L.Y], F[b, L.RADIUS])
        else:
            px, py, nx, ny = circle_polygon_contact(
                F[a, L.X], F[a, L.Y], F[a, L.RADIUS], F[b, L.X], F[b, L.Y], OL, I[b, L.OUTLINE_START], n_b, feature
            )
            if feature >= 0:
                owner = b
                edge = feature
        return px, py, nx, ny, owner, edge
    if F[a, L.OMEGA] != 0.0 or F[b, L.OMEGA] != 0.0:
        # The outlines are turned to now; the angular velocities pick the point of a
        # face-to-face patch (its faster-approaching end).
        px, py, nx, ny = rotating_polygon_polygon_contact(
            F[a, L.X], F[a, L.Y], F[b, L.X], F[b, L.Y], F[a, L.VX] - F[b, L.VX], F[a, L.VY] - F[b, L.VY], OL,
            I[a, L.OUTLINE_START], I[a, L.OUTLINE_N], 0.0, F[a, L.OMEGA],
            I[b, L.OUTLINE_START], n_b, 0.0, F[b, L.OMEGA], feature,
        )
    else:
        px, py, nx, ny = polygon_polygon_contact(
            F[a, L.X], F[a, L.Y], F[b, L.X], F[b, L.Y], OL, I[a, L.OUTLINE_START], I[a, L.OUTLINE_N], I[b, L.OUTLINE_START], n_b, feature
        )
    if feature < n_b:
        owner = b
        edge = feature
    else:
        owner = a
        edge = feature - n_b
    return px, py, nx, ny, owner, edge


@njit(cache=True)
def joins(S, a, b, nx, ny, leaving):
    """Whether the contact of ``a`` and ``b`` (normal ``n`` from b to a), leaving at
    ``leaving`` after its impulse, is persistent: the bodies' accelerations would bring
    them back before they had parted by the rest height (``P[REST_HEIGHT]`` times the
    smaller reach), or one of them already belongs to an island. Then the bodies join one
    island (contact model ISLANDS), whose step solves the contact from now on. With no
    acceleration anywhere (a gas, a game in space) no contact is persistent."""
    F = S[0]
    I = S[1]
    scale = max(math.hypot(F[a, L.FREE_AX], F[a, L.FREE_AY]), math.hypot(F[b, L.FREE_AX], F[b, L.FREE_AY]))
    if not scale > 0.0:
        return False
    reach = min(F[a, L.REACH], F[b, L.REACH])
    if leaving * abs(leaving) >= 2.0 * scale * S[3][L.REST_HEIGHT] * reach:
        return False
    pressing = (F[a, L.FREE_AX] - F[b, L.FREE_AX]) * nx + (F[a, L.FREE_AY] - F[b, L.FREE_AY]) * ny < 0.0
    return pressing or I[a, L.ISLAND] >= 0 or I[b, L.ISLAND] >= 0


@njit(cache=True, inline="always")
def _pair_last_hit(F, I, a, b):
    """When ``a`` and ``b`` last collided with each other, if that was either one's last
    collision (``LAST_OTHER``, ``LAST_HIT``); else -inf."""
    if I[a, L.LAST_OTHER] == b:
        return F[a, L.LAST_HIT]
    if I[b, L.LAST_OTHER] == a:
        return F[b, L.LAST_HIT]
    return -_INF


@njit(cache=True)
def collide_free(S, a, b, feature, t):
    """The impact of ``a`` and ``b`` at ``t`` in the contact model ISLANDS: one exact impulse
    at the contact point (restitution, Coulomb friction, the energy guard of
    ``pge.core.impulse``) on two free bodies; returns the normal impulse (0: a graze).

    ``out`` gets the record and ``OUT_JOIN``: ``ABSORB`` when a body of an island takes part
    and the pair closes slower than a step can follow (its approach over a step below the
    smaller reach): no impulse is applied here, and the island's step at this instant
    solves the impact together with the island's contacts (a block standing on a floor and
    hit low answers with the floor's push and friction at once, not as a free body); else
    ``JOIN`` if the contact is persistent (``joins``), ``WAKE`` if it is not but a body of an
    island took part (which may sleep), else ``NO_JOIN``; when not ``NO_JOIN`` the loop hands
    the collision to Python, which joins, absorbs or wakes the islands.
    """
    F = S[0]
    I = S[1]
    Q = S[4]
    out = S[14]
    advance(F, a, t)
    advance(F, b, t)
    orient(F, I, S[2], S[18], a, t)
    orient(F, I, S[2], S[18], b, t)
    px, py, nx, ny, _, _ = contact_geometry(S, a, b, feature)
    tx = -ny
    ty = nx
    rax = px - F[a, L.X]
    ray = py - F[a, L.Y]
    rbx = px - F[b, L.X]
    rby = py - F[b, L.Y]
    ux = F[a, L.VX] - F[a, L.OMEGA] * ray - (F[b, L.VX] - F[b, L.OMEGA] * rby)
    uy = F[a, L.VY] + F[a, L.OMEGA] * rax - (F[b, L.VY] + F[b, L.OMEGA] * rbx)
    normal_speed = ux * nx + uy * ny
    impulse = 0.0
    within = S[3][L.CONTACT_STEP]
    reach = min(F[a, L.REACH], F[b, L.REACH])
    last = _pair_last_hit(F, I, a, b)
    # At most once per pair and instant: if the island's step left the pair touching and
    # closing (its manifold did not hold them, and they parted into two islands), the same
    # impact comes again at once, and then it is one exact impulse, so that time moves on.
    absorb = (
        normal_speed < 0.0
        and (I[a, L.ISLAND] >= 0 or I[b, L.ISLAND] >= 0)
        and -normal_speed * within < reach
        and last != t
    )
    if normal_speed < 0.0 and not absorb:
        restitution = combine(F[a, L.ELASTICITY], F[b, L.ELASTICITY], Q[L.RULE])
        mu = combine(F[a, L.FRICTION], F[b, L.FRICTION], Q[L.FRICTION_RULE])
        ann, ant, att = contact_response(F, a, False, True, rax, ray, nx, ny, tx, ty)
        bnn, bnt, btt = contact_response(F, b, False, True, rbx, rby, nx, ny, tx, ty)
        knn = ann + bnn
        if knn > 0.0:
            impulse, tangential = contact_impulse(
                normal_speed, ux * tx + uy * ty, knn, ant + bnt, att + btt, restitution, mu
            )
            jx = impulse * nx + tangential * tx
            jy = impulse * ny + tangential * ty
            apply_impulse(F, a, False, True, jx, jy, rax, ray)
            apply_impulse(F, b, False, True, -jx, -jy, rbx, rby)
    ux = F[a, L.VX] - F[a, L.OMEGA] * ray - (F[b, L.VX] - F[b, L.OMEGA] * rby)
    uy = F[a, L.VY] + F[a, L.OMEGA] * rax - (F[b, L.VY] + F[b, L.OMEGA] * rbx)
    # A pair that collides again within one step of the islands and parts slowly (by less
    # than CONTACT_MARGIN of the smaller reach over a step) is a persistent contact: a ball bouncing lower and
    # lower, two polygons grinding, a body squeezed between two. Its island's step then takes
    # all its points at once, so runs of impacts that would converge on an instant end after
    # a few. A pair that parts faster is in flight (an elastic corner-then-corner hit, a ball
    # shot to and fro between two walls): its next impact is exact, as any in a gas.
    leaving = ux * nx + uy * ny
    again = leaving * within < CONTACT_MARGIN * reach and t - last <= within
    F[a, L.LAST_HIT] = t
    F[b, L.LAST_HIT] = t
    I[a, L.LAST_OTHER] = b
    I[b, L.LAST_OTHER] = a
    if absorb:
        join = L.ABSORB
    elif again or joins(S, a, b, nx, ny, leaving):
        join = L.JOIN
    elif I[a, L.ISLAND] >= 0 or I[b, L.ISLAND] >= 0:
        join = L.WAKE  # no join, but an island is hit: Python wakes it if it sleeps
    else:
        join = L.NO_JOIN
    if I[a, L.FIXED] == 0:
        touch_one(S, a)
    if I[b, L.FIXED] == 0:
        touch_one(S, b)
    out[L.OUT_TIME] = t
    out[L.OUT_A] = a
    out[L.OUT_B] = b
    out[L.OUT_PX] = px
    out[L.OUT_PY] = py
    out[L.OUT_NX] = nx
    out[L.OUT_NY] = ny
    out[L.OUT_IMPULSE] = impulse
    out[L.OUT_SPEED] = -normal_speed
    out[L.OUT_JOIN] = join
    return impulse


@njit(cache=True)
def collide(S, a, b, feature, t):
    """Resolve the contact of ``a`` and ``b`` at ``t``; returns the normal impulse (0: a graze).

    The contact record goes to ``out``. The impulse acts at the contact point
    with restitution and Coulomb friction (``pge.core.impulse``), changing
    both bodies' velocities and spins; a resting body pressed into its
    support passes the normal part on to it (it keeps resting), one pulled
    away is released first. Afterwards the slower body may come to rest.
    """
    if S[4][L.CONTACT_MODEL] == L.ISLANDS:
        return collide_free(S, a, b, feature, t)
    S[14][L.OUT_JOIN] = 0.0
    F = S[0]
    I = S[1]
    Q = S[4]
    out = S[14]
    group = S[17]
    # Something reached a sleeping pile: it wakes (at rest) and takes part as it is.
    woken = wake(S, a, group, 0, t)
    woken = wake(S, b, group, woken, t)
    advance(F, a, t)
    advance(F, b, t)
    orient(F, I, S[2], S[18], a, t)
    orient(F, I, S[2], S[18], b, t)
    px, py, nx, ny, owner, edge = contact_geometry(S, a, b, feature)
    tx = -ny
    ty = nx
    rax = px - F[a, L.X]
    ray = py - F[a, L.Y]
    rbx = px - F[b, L.X]
    rby = py - F[b, L.Y]
    wa = F[a, L.OMEGA]
    wb = F[b, L.OMEGA]
    ux = F[a, L.VX] - wa * ray - (F[b, L.VX] - wb * rby)
    uy = F[a, L.VY] + wa * rax - (F[b, L.VY] + wb * rbx)
    normal_speed = ux * nx + uy * ny
    pre = (F[a, L.VX], F[a, L.VY], wa, F[b, L.VX], F[b, L.VY], wb)
    restitution = combine(F[a, L.ELASTICITY], F[b, L.ELASTICITY], Q[L.RULE])
    mu = combine(F[a, L.FRICTION], F[b, L.FRICTION], Q[L.FRICTION_RULE])
    impulse = 0.0
    count = woken
    if normal_speed < 0.0:
        keep_a = _keeps_resting(F, I, S[2], a, nx, ny, px, py, -normal_speed, S[3][L.REST_HEIGHT])
        keep_b = _keeps_resting(F, I, S[2], b, -nx, -ny, px, py, -normal_speed, S[3][L.REST_HEIGHT])
        if I[a, L.SUPPORT] >= 0 and not keep_a:
            detach(S, a)
            S[13][L.S_RELEASES] += 1
            group[count] = a
            count += 1
        if I[b, L.SUPPORT] >= 0 and not keep_b:
            detach(S, b)
            S[13][L.S_RELEASES] += 1
            group[count] = b
            count += 1
        if _laden_knock(S, a, b, keep_a, keep_b, -normal_speed * restitution):
            restitution = 0.0
        turns_a = not keep_a or I[a, L.KIND] == CIRCLE
        turns_b = not keep_b or I[b, L.KIND] == CIRCLE
        ann, ant, att = contact_response(F, a, keep_a, turns_a, rax, ray, nx, ny, tx, ty)
        bnn, bnt, btt = contact_response(F, b, keep_b, turns_b, rbx, rby, nx, ny, tx, ty)
        knn = ann + bnn
        if knn > 0.0:
            impulse, tangential = contact_impulse(
                normal_speed, ux * tx + uy * ty, knn, ant + bnt, att + btt, restitution, mu
            )
            jx = impulse * nx + tangential * tx
            jy = impulse * ny + tangential * ty
            # A resting body the impulse would push into a neighbour that holds it (a wedge
            # against a wall) does not move: the neighbour pushes back. Moved, it would bounce
            # off the neighbour and let go of its riders, for ever at one instant.
            # Held, it may not move against the push (it would do work on the other body).
            # It still turns.
            held_a = keep_a and F[a, L.VX] * jx + F[a, L.VY] * jy >= 0.0 and _held(S, a, jx, jy, t)
            held_b = keep_b and F[b, L.VX] * jx + F[b, L.VY] * jy <= 0.0 and _held(S, b, -jx, -jy, t)
            if held_a or held_b:
                if held_a:
                    ann, ant, att = contact_response(F, a, keep_a, turns_a, rax, ray, nx, ny, tx, ty, False)
                if held_b:
                    bnn, bnt, btt = contact_response(F, b, keep_b, turns_b, rbx, rby, nx, ny, tx, ty, False)
                knn = ann + bnn
                ux = F[a, L.VX] - wa * ray - (F[b, L.VX] - wb * rby)
                uy = F[a, L.VY] + wa * rax - (F[b, L.VY] + wb * rbx)
                impulse = 0.0
                tangential = 0.0
                if knn > 0.0 and ux * nx + uy * ny < 0.0:
                    impulse, tangential = contact_impulse(
                        ux * nx + uy * ny, ux * tx + uy * ty, knn, ant + bnt, att + btt, restitution, mu
                    )
                jx = impulse * nx + tangential * tx
                jy = impulse * ny + tangential * ty
            if apply_impulse(F, a, keep_a, turns_a, jx, jy, rax, ray, not held_a):
                group[count] = a
                count += 1
            if apply_impulse(F, b, keep_b, turns_b, -jx, -jy, rbx, rby, not held_b):
                group[count] = b
                count += 1
    # A speed that a run of impulses at one instant has shrunk below any meaning (a body
    # crossing its own size in 1e150 s) is none: sequential impulses at two corners against
    # a face converge geometrically and would otherwise go on into denormal numbers.
    for k in range(woken, count):
        x = group[k]
        if I[x, L.SUPPORT] < 0:
            speed = math.hypot(F[x, L.VX], F[x, L.VY]) + abs(F[x, L.OMEGA]) * F[x, L.REACH]
            if speed < NO_SPEED * F[x, L.REACH]:
                F[x, L.VX] = 0.0
                F[x, L.VY] = 0.0
                F[x, L.OMEGA] = 0.0
    # The impulse changed these bodies: keep or end their own rest, and release what
    # rests on them.
    changed = count
    for k in range(changed):
        x = group[k]
        if I[x, L.SUPPORT] >= 0 and not settle_acceleration(S, x, t):
            detach(S, x)
            S[13][L.S_RELEASES] += 1
        if k < woken:
            count = release_riders(S, x, group, count, t)
        elif x == a:
            count = carry_or_release_riders(S, x, pre[0], pre[1], pre[2], group, count, t)
        else:
            count = carry_or_release_riders(S, x, pre[3], pre[4], pre[5], group, count, t)
    # Then the slower of a bounce may come to rest on the other (after the releases, so
    # that a rider settling on a support the impulse just nudged is not let go again).
    rested, count = try_rest(S, a, b, nx, ny, owner, edge, px, py, t, group, count)
    if not rested:
        rested, count = try_rest(S, b, a, -nx, -ny, owner, edge, px, py, t, group, count)
    if rested:
        S[13][L.S_RESTS] += 1
    else:
        redone, kicked, owed = pivot(S, a, b, px, py, nx, ny, owner, restitution, mu, pre)
        if owed:
            paid, count = others_pay_for_lift(S, a, b, pre, group, count, t)
            if not paid:
                S[13][L.S_UNPAID_LIFTS] += 1
        if redone >= 0.0:
            impulse = max(redone, 1e-300)
            for x in (a, b):
                if I[x, L.FIXED] == 0:
                    group[count] = x
                    count += 1
                    if I[x, L.SUPPORT] >= 0 and not settle_acceleration(S, x, t):
                        detach(S, x)
                        S[13][L.S_RELEASES] += 1
                    count = release_riders(S, x, group, count, t)
            if kicked:
                # A pressed contact at rest: the pile around it may sleep instead.
                _, count = try_sleep(S, a, b, group, count, t)
    if impulse == 0.0 and count == woken:
        # A graze: nothing changed, but look again from here.
        if I[a, L.FIXED] == 0:
            group[count] = a
            count += 1
        if I[b, L.FIXED] == 0:
            group[count] = b
            count += 1
    count = settle_piles(S, group, count, t)
    touch_group(S, group, count)
    out[L.OUT_TIME] = t
    out[L.OUT_A] = a
    out[L.OUT_B] = b
    out[L.OUT_PX] = px
    out[L.OUT_PY] = py
    out[L.OUT_NX] = nx
    out[L.OUT_NY] = ny
    out[L.OUT_IMPULSE] = impulse
    out[L.OUT_SPEED] = -normal_speed
    return impulse


@njit(cache=True)
def contact_change(S, r, what, t):
    """Rider ``r`` leaves its edge (LEAVE) or stops sliding (STOP_SLIDING) at ``t``."""
    F = S[0]
    I = S[1]
    group = S[17]
    s = I[r, L.SUPPORT]
    advance(F, r, t)
    advance(F, s, t)
    count = 1
    group[0] = r
    if what == L.LEAVE:
        detach(S, r)
        S[13][L.S_RELEASES] += 1
    else:
        _, rolling = contact_slip(S, r, t)
        if rolling:
            # A skidding circle's contact point stops: it rolls on at its velocity, its spin
            # matching it.
            dvx = 0.0
            dvy = 0.0
            vt, _, _ = relative_tangential(S, r, t)
            F[r, L.OMEGA] = vt / F[r, L.RADIUS]
        else:
            dvx = F[s, L.VX] - F[r, L.VX]
            dvy = F[s, L.VY] - F[r, L.VY]
            F[r, L.VX] = F[s, L.VX]
            F[r, L.VY] = F[s, L.VY]
        if settle_acceleration(S, r, t):
            # Its motion stays continuous: what rests on it keeps resting, re-settled.
            count = resettle_riders(S, r, dvx, dvy, True, group, count, t)
            count = settle_piles(S, group, count, t)
            touch_group(S, group, count)
            return
        detach(S, r)
        S[13][L.S_RELEASES] += 1
    count = release_riders(S, r, group, count, t)
    count = settle_piles(S, group, count, t)
    touch_group(S, group, count)


# ------------------------------------------------------------------- the loop


@njit(cache=True, inline="always")
def watch(S, t, kind):
    """Count an event of ``kind`` at ``t`` in the progress watch; True if it makes a storm.

    A run is a sequence of events each within ``max(STORM_SPAN, STORM_TICKS * cap)`` clock
    ticks of the run's first; ``cap`` events in one run are more than the clock can
    separate (a zero-time loop, a Zeno run converging on an instant, a clock creeping a few
    ulps per event). The count lives in the state, so returns to Python for callbacks,
    timers and frames do not restart it.
    """
    P = S[3]
    Q = S[4]
    cap = Q[L.STORM_CAP]
    tick = np.nextafter(t, _INF) - t
    span = max(STORM_SPAN, STORM_TICKS * cap * tick)
    if t - P[L.STORM_START] <= span:
        Q[L.STORM_RUN] += 1
    else:
        P[L.STORM_START] = t
        Q[L.STORM_RUN] = 0
        for k in range(5):
            Q[L.STORM_KINDS + k] = 0
    Q[L.STORM_KINDS + kind] += 1
    return Q[L.STORM_RUN] >= cap


@njit(cache=True, inline="always")
def _report(out, t, a, b, code):
    """Name the event at ``t`` between ``a`` and ``b`` (-1: none) that stopped the loop."""
    out[L.OUT_TIME] = t
    out[L.OUT_A] = a
    out[L.OUT_B] = b
    return code


@njit(cache=True)
def run(S, until, notify_all):
    """Process events up to time ``until``; return a code saying why it stopped.

    DONE: the next event is later than ``until`` (``P[TIME]`` is not moved).
    COLLIDED: a collision that Python must hear about (``notify_all`` or a
    body flagged NOTIFY); its record is in ``out``. FIRED_TIMER, FIRED_FRAME:
    ``out[OUT_ID]`` names it. NEED_SPACE: grow the event arrays, call again.
    EMPTY: no events are left. JOINED: a persistent contact (``collide_free``, record in
    ``out``) joins its bodies' islands. STORM: the progress watch (``watch``) found a run of
    events the clock cannot separate; ``out`` names the last event's bodies. TOO_FAST:
    ``Q[FAST_BODY]``'s travel step is shorter than the clock can resolve (``place``);
    nothing has used its box.
    """
    I = S[1]
    P = S[3]
    Q = S[4]
    heap = S[8]
    slot_time = S[9]
    slot_key = S[10]
    slot_data = S[11]
    stats = S[13]
    out = S[14]
    while True:
        if Q[L.FAST_BODY] >= 0:
            return _report(out, P[L.TIME], Q[L.FAST_BODY], -1, L.TOO_FAST)
        if not drain_predictions(S) or Q[L.FREE_N] < Q[L.MIN_FREE]:
            return L.NEED_SPACE
        if Q[L.HEAP_N] == 0:
            return L.EMPTY
        t = slot_time[heap[0]]
        if t > until:
            return L.DONE
        slot = pop_earliest(S)
        kind = slot_key[slot] >> L.KIND_SHIFT
        a = slot_data[slot, 0]
        b = slot_data[slot, 1]
        count_a = slot_data[slot, 2]
        count_b = slot_data[slot, 3]
        feature = slot_data[slot, 4]
        if kind == L.COLLISION or kind == L.CONTACT_EVENT or kind == L.HORIZON_EVENT:
            if I[a, L.COUNT] != count_a or (kind == L.COLLISION and I[b, L.COUNT] != count_b):
                stats[L.S_STALE] += 1
                continue
        P[L.TIME] = t
        if watch(S, t, kind):
            if kind == L.CONTACT_EVENT:
                b = I[a, L.SUPPORT]
            elif kind != L.COLLISION:
                b = -1
            if kind >= L.TIMER:
                a = -1
            return _report(out, t, a, b, L.STORM)
        if kind == L.COLLISION:
            stats[L.S_EVENTS] += 1
            impulse = collide(S, a, b, feature, t)
            if impulse == 0.0 and out[L.OUT_JOIN] != L.ABSORB:
                stats[L.S_GRAZES] += 1
            else:
                stats[L.S_COLLISIONS] += 1
                if I[a, L.FIXED] == 0 and I[b, L.FIXED] == 0:
                    stats[L.S_PAIR_COLLISIONS] += 1
            if out[L.OUT_JOIN] != 0.0:
                stats[L.S_JOINS] += 1
                return L.JOINED
            if impulse != 0.0 and (notify_all or I[a, L.NOTIFY] != 0 or I[b, L.NOTIFY] != 0):
                return L.COLLIDED
        elif kind == L.CONTACT_EVENT:
            stats[L.S_EVENTS] += 1
            stats[L.S_CONTACT_CHANGES] += 1
            contact_change(S, a, feature, t)
        elif kind == L.HORIZON_EVENT:
            stats[L.S_EVENTS] += 1
            stats[L.S_HORIZONS] += 1
            touch_one(S, a)
        elif kind == L.TIMER:
            out[L.OUT_TIME] = t
            out[L.OUT_ID] = a
            return L.FIRED_TIMER
        else:
            out[L.OUT_TIME] = t
            out[L.OUT_ID] = a
            out[L.OUT_EPOCH] = b
            return L.FIRED_FRAME
