"""Swept boxes and pair prediction: the broad phase feeding the exact kernels.

A moving body owns a horizon ``h`` and the box its shape sweeps over
``[now, h]``, chosen so that it travels at most ``P[TRAVEL]``. A pair is
predicted over ``[now, min(h_i, h_j)]`` only if the boxes overlap and the
conservative short-circuit test cannot exclude contact; the exact kernel's
hit is queued. A HORIZON event renews the box. Invariant: a pair that first
touches at ``t <= min(h_i, h_j)`` has a valid event at or before ``t``.
"""

from __future__ import annotations

import math

import numpy as np
from pge._jit_cache import njit

from pge.broadphase.bounds import cannot_touch_before, lecture_cannot_touch, swept_range, travel_horizon
from pge.core import layout as L
from pge.core.grid import file_in_cell, gather, gather_all
from pge.core.motion import kernel_angle, orient, spin_at, state_at
from pge.core.overlap import overlap_depth
from pge.core.queue import push, set_horizon
from pge.core.tuning import MIN_TICKS
from pge.numerics.vector import magnitude
from pge.toi.circle_circle import circle_circle
from pge.toi.circle_polygon import circle_polygon
from pge.toi.polygon_polygon import polygon_polygon
from pge.toi.rotating import CHECKPOINT, rotating_circle_polygon, rotating_polygon_polygon

_INF = math.inf
CIRCLE = 0
#: the longest a swept box is made for (s): finite, so that a box is never infinite
_LONGEST_SPAN = 1e300


@njit(cache=True, inline="always")
def spinning(F, I, i):
    """True for a polygon that turns or is spun up (a circle's turning does not change its shape)."""
    return I[i, L.KIND] != CIRCLE and (F[i, L.OMEGA] != 0.0 or F[i, L.ALPHA] != 0.0)


@njit(cache=True, inline="always")
def at_or_before(now, dt):
    """``now + dt`` rounded down: the clock value at or before ``dt`` from ``now``.

    A horizon must not be rounded past the span its box was swept over: rounded up, it would
    fire after the end of the span, and a wall in the part of the path left uncovered would
    never be predicted.
    """
    t = now + dt
    if t - now > dt:
        t = np.nextafter(t, -_INF)
    return t


@njit(cache=True, inline="always")
def contact_time(now, dt, closing, allowance):
    """The clock value for a contact ``dt`` after ``now`` between bodies closing at most at
    ``closing``: ``now + dt`` rounded to nearest, unless rounding up would carry them more than
    ``allowance`` (the overlap tolerated everywhere, 1e-9 of their sizes) into each other; then
    rounded down. A body fast enough for that could otherwise be advanced past a thin wall's
    mid-line, where the wall's far face is nearer and a second contact at the same instant
    sends it through."""
    t = now + dt
    excess = (t - now) - dt
    if excess > 0.0 and excess * closing > allowance:
        t = np.nextafter(t, -_INF)
    return t


@njit(cache=True, inline="always")
def place(S, i):
    """Give body ``i`` a horizon and a swept box from now; file a moving body in the grid."""
    F = S.F
    I = S.I
    P = S.P
    Q = S.Q
    now = P[L.TIME]
    if I[i, L.KIND] != CIRCLE:
        orient(F, I, S.OL, S.OB, i, now)
    ax = F[i, L.AX]
    ay = F[i, L.AY]
    x, y, vx, vy = state_at(F, i, now)
    spin = 0.0
    twist = 0.0
    if spinning(F, I, i):
        spin = abs(spin_at(F, i, now)) * F[i, L.REACH]
        twist = abs(F[i, L.ALPHA]) * F[i, L.REACH]
    if I[i, L.FIXED] != 0 or (vx == 0.0 and vy == 0.0 and ax == 0.0 and ay == 0.0 and spin == 0.0 and twist == 0.0):
        horizon = _INF
        x0 = x
        x1 = x
        y0 = y
        y1 = y
    else:
        # A spinning polygon's corners travel |omega| R faster than its centroid: the
        # horizon bounds their path too, which keeps the rotating kernels' windows short.
        span = travel_horizon(magnitude(vx, vy) + spin, magnitude(ax, ay) + twist, P[L.TRAVEL])
        # A speed of 1e-310 (denormal, left by a long decay) overflows the span to inf, and
        # v * inf would make the box infinite, which the grid cannot file.
        span = min(span, _LONGEST_SPAN)
        # The box covers exactly [now, horizon] as the clock holds them: rounded to nearest,
        # the horizon could fire after the span swept and leave part of the path uncovered.
        horizon = at_or_before(now, span)
        if horizon - now < MIN_TICKS * (np.nextafter(now, _INF) - now):
            # The clock cannot resolve this body's travel step: refuse it before any event
            # uses the box (the loop raises); its box stays valid for the one tick it has.
            if Q[L.FAST_BODY] < 0:
                Q[L.FAST_BODY] = i
            if horizon <= now:
                horizon = np.nextafter(now, _INF)
        span = horizon - now
        x0, x1 = swept_range(x, vx, ax, span)
        y0, y1 = swept_range(y, vy, ay, span)
    margin = P[L.MARGIN]
    F[i, L.BOX_X0] = x0 + F[i, L.EXT_X0] - margin
    F[i, L.BOX_Y0] = y0 + F[i, L.EXT_Y0] - margin
    F[i, L.BOX_X1] = x1 + F[i, L.EXT_X1] + margin
    F[i, L.BOX_Y1] = y1 + F[i, L.EXT_Y1] + margin
    F[i, L.HORIZON] = horizon
    if I[i, L.FIXED] == 0:
        file_in_cell(S, i)
    set_horizon(S, i, horizon)


#: approach speeds below this many units in the last place of the velocities are rounding
STILL_ULPS = 64.0 * 2.0**-52


@njit(cache=True, inline="always")
def still_speed(F, i, j, ix, iy, ivx, ivy, jx, jy, jvx, jvy):
    """The approach speed below which touching ``i`` and ``j`` count as not approaching.

    ``collide`` computes the normal speed at the contact point from the bodies'
    velocities, spins and lever arms, the kernels from relative motion; the two
    differ by rounding of about an ulp of each term (``|v|``, and ``|omega|``
    times the lever arm, whose rounding is an ulp of the position). A kernel
    that called a slower approach "approaching" could disagree with ``collide``
    (a graze) or ask for an impulse too small to change any velocity, and the
    pair would be reported again at the same instant for ever.
    """
    spin_i = abs(F[i, L.OMEGA]) * (F[i, L.REACH] + abs(ix) + abs(iy))
    spin_j = abs(F[j, L.OMEGA]) * (F[j, L.REACH] + abs(jx) + abs(jy))
    return STILL_ULPS * (magnitude(ivx, ivy) + magnitude(jvx, jvy) + spin_i + spin_j)


@njit(cache=True, inline="always")
def predict(S, i, mark, polygons):
    """Predict body ``i`` against every candidate (skipping bodies carrying ``mark`` and
    the pairs an island's step solves: both in one island, or one in an island and the
    other fixed).

    ``polygons`` is None where no polygon can move (``pge.core.engine.run``): then no
    pair turns and no two polygons are ever predicted (two fixed bodies never are), and
    the version compiled for None has no rotating or polygon-polygon kernel in it.

    Inlined into its one caller, ``drain_predictions``: a compiled call passes every array
    of ``S`` on the stack, about 150 words, and this runs about once an event.
    """
    F = S.F
    I = S.I
    OL = S.OL
    P = S.P
    stats = S.stats
    scratch = S.scratch
    # The broad-phase switches (World.broadphase), read once per call: all zero in
    # normal runs, so each stage costs one predictable branch per pair.
    switches = S.Q[L.BROADPHASE]
    boxes = (switches & L.NO_BOXES) == 0
    short_circuit = (switches & L.NO_SHORT_CIRCUIT) == 0
    lecture = (switches & L.LECTURE_TEST) != 0
    if switches & L.NO_GRID:
        n = gather_all(S, i)
    else:
        n = gather(S, i)
    stats[L.S_CANDIDATES] += n
    now = P[L.TIME]
    iax = F[i, L.AX]
    iay = F[i, L.AY]
    ix, iy, ivx, ivy = state_at(F, i, now)
    ih = F[i, L.HORIZON]
    bx0 = F[i, L.BOX_X0]
    by0 = F[i, L.BOX_Y0]
    bx1 = F[i, L.BOX_X1]
    by1 = F[i, L.BOX_Y1]
    ifixed = I[i, L.FIXED] != 0
    ikind = I[i, L.KIND]
    iisland = I[i, L.ISLAND]
    for k in range(n):
        j = scratch[k]
        if mark != 0 and I[j, L.MARK] == mark:
            continue
        if ifixed and I[j, L.FIXED] != 0:
            continue
        if iisland >= 0 and (I[j, L.ISLAND] == iisland or I[j, L.FIXED] != 0):
            continue  # the island's step solves its contacts (pge.contact.island)
        if ifixed and I[j, L.ISLAND] >= 0:
            continue
        if boxes and (
            F[j, L.BOX_X0] > bx1 or F[j, L.BOX_X1] < bx0 or F[j, L.BOX_Y0] > by1 or F[j, L.BOX_Y1] < by0
        ):
            stats[L.S_BOX_REJECTS] += 1
            continue
        end = F[j, L.HORIZON]
        if ih < end:
            end = ih
        if end == _INF:
            continue  # neither moves: no contact can start
        window = end - now
        jx, jy, jvx, jvy = state_at(F, j, now)
        dx = ix - jx
        dy = iy - jy
        dvx = ivx - jvx
        dvy = ivy - jvy
        dax = iax - F[j, L.AX]
        day = iay - F[j, L.AY]
        if short_circuit:
            reach = F[i, L.REACH] + F[j, L.REACH]
            if lecture:
                culled = lecture_cannot_touch(dx, dy, dvx, dvy, dax, day, reach, window)
            else:
                culled = cannot_touch_before(dx, dy, dvx, dvy, dax, day, reach, window)
            if culled:
                stats[L.S_BOUND_REJECTS] += 1
                continue
        if S.Q[L.EXCUSED_N] > 0 and still_excused(S, i, j):
            continue
        stats[L.S_PREDICTIONS] += 1
        still = still_speed(F, i, j, ix, iy, ivx, ivy, jx, jy, jvx, jvy)
        jkind = I[j, L.KIND]
        first = i
        second = j
        t = _INF
        feature = 0
        general = False
        if polygons is not None:
            # Pruned from the version compiled for None (``if`` on an argument's type).
            if spinning(F, I, i) or spinning(F, I, j):
                t, feature = _predict_rotating(S, i, j, dx, dy, dvx, dvy, dax, day, now, window, still)
                if ikind != CIRCLE and jkind == CIRCLE:
                    first = j
                    second = i
                general = True
            elif ikind != CIRCLE and jkind != CIRCLE:
                t, feature = polygon_polygon(
                    dx, dy, dvx, dvy, dax, day, OL, I[i, L.OUTLINE_START], I[i, L.OUTLINE_N],
                    I[j, L.OUTLINE_START], I[j, L.OUTLINE_N], window, still,
                )
                general = True
        if not general:
            if ikind == CIRCLE and jkind == CIRCLE:
                t, feature = circle_circle(dx, dy, dvx, dvy, dax, day, F[i, L.RADIUS], F[j, L.RADIUS], window, still)
            elif ikind == CIRCLE:
                t, feature = circle_polygon(
                    dx, dy, dvx, dvy, dax, day, F[i, L.RADIUS], OL, I[j, L.OUTLINE_START], I[j, L.OUTLINE_N], window,
                    still,
                )
            else:  # a polygon and a circle (two polygons are the general version's)
                t, feature = circle_polygon(
                    -dx, -dy, -dvx, -dvy, -dax, -day, F[j, L.RADIUS], OL, I[i, L.OUTLINE_START], I[i, L.OUTLINE_N],
                    window, still,
                )
                first = j
                second = i
        if feature == CHECKPOINT:
            # The rotating search ran out of budget: no contact before now + t; look
            # again from there.
            push(S, now + t, (L.HORIZON_EVENT << L.KIND_SHIFT) | i, i, -1, I[i, L.COUNT], 0, 0)
            continue
        if t != _INF:
            stats[L.S_HITS] += 1
            if i < j:
                key = (i << L.ID_SHIFT) | j
            else:
                key = (j << L.ID_SHIFT) | i
            closing = (
                magnitude(dvx, dvy) + magnitude(dax, day) * t
                + (abs(spin_at(F, i, now)) + abs(F[i, L.ALPHA]) * t) * F[i, L.REACH]
                + (abs(spin_at(F, j, now)) + abs(F[j, L.ALPHA]) * t) * F[j, L.REACH]
            )
            allowance = P[L.OVERLAP_TOLERANCE] * (F[i, L.REACH] + F[j, L.REACH])
            when = contact_time(now, t, closing, allowance)
            push(S, when, key, first, second, I[first, L.COUNT], I[second, L.COUNT], feature)


@njit(cache=True)
def still_excused(S, i, j):
    """Whether ``i`` and ``j`` are a pair that overlapped when the run began and overlap
    still (they do not collide); a pair found apart is no longer excused."""
    excused = S.excused
    Q = S.Q
    a = min(i, j)
    b = max(i, j)
    for k in range(Q[L.EXCUSED_N]):
        if excused[k, 0] == a and excused[k, 1] == b:
            if overlap_depth(S, i, j) > 0.0:
                return True
            last = Q[L.EXCUSED_N] - 1
            excused[k, 0] = excused[last, 0]
            excused[k, 1] = excused[last, 1]
            Q[L.EXCUSED_N] = last
            return False
    return False


@njit(cache=True)
def _predict_rotating(S, i, j, dx, dy, dvx, dvy, dax, day, now, window, still):
    """First contact of ``i`` and ``j`` when a polygon among them spins: the rotating
    kernels on the unturned outlines ``OB`` and the angles, spins and angular
    accelerations now. ``d, dv, da`` are ``i`` relative to ``j``; a (polygon,
    circle) pair is turned round."""
    F = S.F
    I = S.I
    OB = S.OB
    if I[i, L.KIND] == CIRCLE:
        if I[j, L.KIND] == CIRCLE:
            return _INF, 0
        return rotating_circle_polygon(
            dx, dy, dvx, dvy, dax, day, F[i, L.RADIUS], OB, I[j, L.OUTLINE_START], I[j, L.OUTLINE_N],
            kernel_angle(F, j, now), spin_at(F, j, now), window, still, F[j, L.ALPHA],
        )
    if I[j, L.KIND] == CIRCLE:
        return rotating_circle_polygon(
            -dx, -dy, -dvx, -dvy, -dax, -day, F[j, L.RADIUS], OB, I[i, L.OUTLINE_START], I[i, L.OUTLINE_N],
            kernel_angle(F, i, now), spin_at(F, i, now), window, still, F[i, L.ALPHA],
        )
    return rotating_polygon_polygon(
        dx, dy, dvx, dvy, dax, day, OB,
        I[i, L.OUTLINE_START], I[i, L.OUTLINE_N], kernel_angle(F, i, now), spin_at(F, i, now),
        I[j, L.OUTLINE_START], I[j, L.OUTLINE_N], kernel_angle(F, j, now), spin_at(F, j, now),
        window, still, F[i, L.ALPHA], F[j, L.ALPHA],
    )


@njit(cache=True)
def new_mark(S):
    """A fresh pair-once mark."""
    Q = S.Q
    Q[L.MARK_COUNTER] += 1
    return Q[L.MARK_COUNTER]
