"""The compiled event loop: queue, grid, prediction and response over arrays.

State is one tuple ``S`` of arrays (see ``pge.core.state.EngineState``):
``(F, I, OL, P, Q, head, static_start, static_items, heap, slot_time,
slot_key, slot_data, free, stats, out, scratch)``; column meanings are in
``pge.core.layout``.

One event (``run``): pop the earliest queue entry; skip it if stale (a
body's invalidation counter moved on); advance the bodies involved to the
event time; resolve it; give the moving bodies involved new swept boxes and
predict them again against the bodies whose boxes overlap theirs. Nothing
else is touched, so an event costs the same in a world of a thousand bodies
as in one of a hundred thousand.

Broad phase. A moving body owns a horizon ``h`` and the box its shape sweeps
over ``[now, h]``, chosen so that it travels at most ``P[TRAVEL]``; it sits
in the grid cell that holds its box's lower-left corner (cells are at least
as wide as any moving box, so a query scans the box's cells plus one row and
column below). Fixed bodies keep their own box, registered in every cell it
covers (``static_start``/``static_items``). A pair is predicted over
``[now, min(h_i, h_j)]`` only if the boxes overlap and the conservative
short-circuit test cannot exclude contact. A HORIZON event renews the box.
Invariant: a pair that first touches at ``t <= min(h_i, h_j)`` has a valid
event at or before ``t`` in the queue.

Queue. A binary heap of event slots ordered by ``(time, key, slot)``; the key
holds the kind in its top bits (so equal times pop as collision, horizon,
timer, frame) and, for a collision, the two body ids, smaller first.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from pge.broadphase.bounds import cannot_touch_before, swept_range, travel_horizon
from pge.core.layout import (
    AX,
    AY,
    BOX_X0,
    BOX_X1,
    BOX_Y0,
    BOX_Y1,
    CELL,
    COLLIDED,
    COLLISION,
    COUNT,
    DONE,
    ELASTICITY,
    EMPTY,
    EXT_X0,
    EXT_X1,
    EXT_Y0,
    EXT_Y1,
    FIRED_FRAME,
    FIRED_TIMER,
    FIXED,
    FREE_N,
    GRID_NX,
    GRID_NY,
    GRID_X0,
    GRID_Y0,
    HEAP_N,
    HORIZON,
    HORIZON_EVENT,
    ID_SHIFT,
    INV_CELL,
    INV_MASS,
    KIND,
    KIND_SHIFT,
    MARGIN,
    MARK,
    MARK_COUNTER,
    MIN_FREE,
    NEED_SPACE,
    NEXT,
    NOTIFY,
    OUT_A,
    OUT_B,
    OUT_EPOCH,
    OUT_ID,
    OUT_IMPULSE,
    OUT_NX,
    OUT_NY,
    OUT_PX,
    OUT_PY,
    OUT_SPEED,
    OUT_TIME,
    OUTLINE_N,
    OUTLINE_START,
    PREV,
    RADIUS,
    REACH,
    RULE,
    S_BOUND_REJECTS,
    S_BOX_REJECTS,
    S_CANDIDATES,
    S_COLLISIONS,
    S_EVENTS,
    S_GRAZES,
    S_HITS,
    S_HORIZONS,
    S_PAIR_COLLISIONS,
    S_PREDICTIONS,
    S_STALE,
    STAMP,
    STAMP_COUNTER,
    T0,
    TIME,
    TIMER,
    TRAVEL,
    VX,
    VY,
    X,
    Y,
)
from pge.toi.circle_circle import circle_circle, circle_circle_contact
from pge.toi.circle_polygon import circle_polygon, circle_polygon_contact, closest_feature
from pge.toi.polygon_polygon import minkowski_faces, polygon_polygon, polygon_polygon_contact

_INF = math.inf
CIRCLE = 0

# ------------------------------------------------------------------- the queue


@njit(cache=True, inline="always")
def _earlier(slot_time, slot_key, s1, s2):
    t1 = slot_time[s1]
    t2 = slot_time[s2]
    if t1 != t2:
        return t1 < t2
    k1 = slot_key[s1]
    k2 = slot_key[s2]
    if k1 != k2:
        return k1 < k2
    return s1 < s2


@njit(cache=True)
def push(S, t, key, a, b, count_a, count_b, feature):
    """Queue an event; the caller guarantees a free slot (``Q[MIN_FREE]``)."""
    Q = S[4]
    heap = S[8]
    slot_time = S[9]
    slot_key = S[10]
    slot_data = S[11]
    free = S[12]
    n_free = Q[FREE_N] - 1
    slot = free[n_free]
    Q[FREE_N] = n_free
    slot_time[slot] = t
    slot_key[slot] = key
    slot_data[slot, 0] = a
    slot_data[slot, 1] = b
    slot_data[slot, 2] = count_a
    slot_data[slot, 3] = count_b
    slot_data[slot, 4] = feature
    i = Q[HEAP_N]
    Q[HEAP_N] = i + 1
    while i > 0:
        parent = (i - 1) >> 1
        above = heap[parent]
        if _earlier(slot_time, slot_key, above, slot):
            break
        heap[i] = above
        i = parent
    heap[i] = slot


@njit(cache=True)
def _pop(S):
    """Remove and return the earliest slot (the caller releases it)."""
    Q = S[4]
    heap = S[8]
    slot_time = S[9]
    slot_key = S[10]
    top = heap[0]
    n = Q[HEAP_N] - 1
    Q[HEAP_N] = n
    if n > 0:
        last = heap[n]
        i = 0
        while True:
            child = 2 * i + 1
            if child >= n:
                break
            if child + 1 < n and _earlier(slot_time, slot_key, heap[child + 1], heap[child]):
                child += 1
            if _earlier(slot_time, slot_key, last, heap[child]):
                break
            heap[i] = heap[child]
            i = child
        heap[i] = last
    return top


# -------------------------------------------------------------------- the grid


@njit(cache=True, inline="always")
def _cell_index(P, value, origin, count):
    f = (value - origin) * P[INV_CELL]
    if f <= 0.0:
        return 0
    if f >= count - 1:
        return count - 1
    return int(f)


@njit(cache=True)
def _unlink(S, i):
    I = S[1]
    head = S[5]
    c = I[i, CELL]
    if c < 0:
        return
    before = I[i, PREV]
    after = I[i, NEXT]
    if before >= 0:
        I[before, NEXT] = after
    else:
        head[c] = after
    if after >= 0:
        I[after, PREV] = before
    I[i, CELL] = -1


@njit(cache=True)
def _link(S, i, c):
    I = S[1]
    head = S[5]
    first = head[c]
    I[i, NEXT] = first
    I[i, PREV] = -1
    if first >= 0:
        I[first, PREV] = i
    head[c] = i
    I[i, CELL] = c


@njit(cache=True)
def unlink(S, i):
    """Take body ``i`` out of the grid (removal, or on becoming fixed)."""
    _unlink(S, i)


@njit(cache=True, inline="always")
def state_at(F, i, t):
    """Position and velocity ``(x, y, vx, vy)`` of body ``i`` at time ``t``, in closed form."""
    dt = t - F[i, T0]
    ax = F[i, AX]
    ay = F[i, AY]
    return (
        F[i, X] + (F[i, VX] + 0.5 * ax * dt) * dt,
        F[i, Y] + (F[i, VY] + 0.5 * ay * dt) * dt,
        F[i, VX] + ax * dt,
        F[i, VY] + ay * dt,
    )


@njit(cache=True)
def advance(F, i, t):
    """Move body ``i``'s reference state forward to time ``t`` (closed form)."""
    dt = t - F[i, T0]
    if dt != 0.0:
        ax = F[i, AX]
        ay = F[i, AY]
        F[i, X] += (F[i, VX] + 0.5 * ax * dt) * dt
        F[i, Y] += (F[i, VY] + 0.5 * ay * dt) * dt
        F[i, VX] += ax * dt
        F[i, VY] += ay * dt
        F[i, T0] = t


@njit(cache=True)
def place(S, i):
    """Give body ``i`` a horizon and a swept box from now; file a moving body in the grid."""
    F = S[0]
    I = S[1]
    P = S[3]
    Q = S[4]
    now = P[TIME]
    ax = F[i, AX]
    ay = F[i, AY]
    x, y, vx, vy = state_at(F, i, now)
    if I[i, FIXED] != 0 or (vx == 0.0 and vy == 0.0 and ax == 0.0 and ay == 0.0):
        horizon = _INF
        x0 = x
        x1 = x
        y0 = y
        y1 = y
    else:
        span = travel_horizon(math.hypot(vx, vy), math.hypot(ax, ay), P[TRAVEL])
        horizon = now + span
        if horizon <= now:
            horizon = np.nextafter(now, _INF)
            span = horizon - now
        x0, x1 = swept_range(x, vx, ax, span)
        y0, y1 = swept_range(y, vy, ay, span)
    margin = P[MARGIN]
    F[i, BOX_X0] = x0 + F[i, EXT_X0] - margin
    F[i, BOX_Y0] = y0 + F[i, EXT_Y0] - margin
    F[i, BOX_X1] = x1 + F[i, EXT_X1] + margin
    F[i, BOX_Y1] = y1 + F[i, EXT_Y1] + margin
    F[i, HORIZON] = horizon
    if I[i, FIXED] == 0:
        c = _cell_index(P, F[i, BOX_X0], P[GRID_X0], Q[GRID_NX]) * Q[GRID_NY] + _cell_index(
            P, F[i, BOX_Y0], P[GRID_Y0], Q[GRID_NY]
        )
        if c != I[i, CELL]:
            _unlink(S, i)
            _link(S, i, c)
    if horizon != _INF:
        push(S, horizon, (HORIZON_EVENT << KIND_SHIFT) | i, i, -1, I[i, COUNT], 0, 0)


@njit(cache=True)
def gather(S, i):
    """Write into ``scratch`` every body whose box may overlap body ``i``'s; return how many.

    Moving bodies come from the linked lists of the box's cells and of one
    more row and column below; fixed bodies (only for a moving ``i``) from
    the static lists, de-duplicated by stamp.
    """
    F = S[0]
    I = S[1]
    P = S[3]
    Q = S[4]
    head = S[5]
    static_start = S[6]
    static_items = S[7]
    scratch = S[15]
    stamp = Q[STAMP_COUNTER] + 1
    Q[STAMP_COUNTER] = stamp
    nx = Q[GRID_NX]
    ny = Q[GRID_NY]
    ix0 = _cell_index(P, F[i, BOX_X0], P[GRID_X0], nx) - 1
    iy0 = _cell_index(P, F[i, BOX_Y0], P[GRID_Y0], ny) - 1
    ix1 = _cell_index(P, F[i, BOX_X1], P[GRID_X0], nx)
    iy1 = _cell_index(P, F[i, BOX_Y1], P[GRID_Y0], ny)
    if ix0 < 0:
        ix0 = 0
    if iy0 < 0:
        iy0 = 0
    moving = I[i, FIXED] == 0
    count = 0
    for ix in range(ix0, ix1 + 1):
        for iy in range(iy0, iy1 + 1):
            c = ix * ny + iy
            j = head[c]
            while j >= 0:
                if j != i:
                    scratch[count] = j
                    count += 1
                j = I[j, NEXT]
            if moving:
                for k in range(static_start[c], static_start[c + 1]):
                    j = static_items[k]
                    if I[j, STAMP] != stamp:
                        I[j, STAMP] = stamp
                        scratch[count] = j
                        count += 1
    return count


@njit(cache=True, inline="always")
def _combine(ea, eb, rule):
    if rule == 0:
        return min(ea, eb)
    if rule == 1:
        return max(ea, eb)
    if rule == 2:
        return 0.5 * (ea + eb)
    if ea == eb:
        return ea
    return math.sqrt(ea * eb)


# ----------------------------------------------------------------- prediction


@njit(cache=True)
def predict(S, i, mark):
    """Predict body ``i`` against every candidate (skipping bodies carrying ``mark``)."""
    F = S[0]
    I = S[1]
    OL = S[2]
    P = S[3]
    stats = S[13]
    scratch = S[15]
    n = gather(S, i)
    stats[S_CANDIDATES] += n
    now = P[TIME]
    iax = F[i, AX]
    iay = F[i, AY]
    ix, iy, ivx, ivy = state_at(F, i, now)
    ih = F[i, HORIZON]
    bx0 = F[i, BOX_X0]
    by0 = F[i, BOX_Y0]
    bx1 = F[i, BOX_X1]
    by1 = F[i, BOX_Y1]
    ifixed = I[i, FIXED] != 0
    ikind = I[i, KIND]
    for k in range(n):
        j = scratch[k]
        if mark != 0 and I[j, MARK] == mark:
            continue
        if ifixed and I[j, FIXED] != 0:
            continue
        if F[j, BOX_X0] > bx1 or F[j, BOX_X1] < bx0 or F[j, BOX_Y0] > by1 or F[j, BOX_Y1] < by0:
            stats[S_BOX_REJECTS] += 1
            continue
        end = F[j, HORIZON]
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
        dax = iax - F[j, AX]
        day = iay - F[j, AY]
        if cannot_touch_before(dx, dy, dvx, dvy, dax, day, F[i, REACH] + F[j, REACH], window):
            stats[S_BOUND_REJECTS] += 1
            continue
        stats[S_PREDICTIONS] += 1
        jkind = I[j, KIND]
        first = i
        second = j
        if ikind == CIRCLE:
            if jkind == CIRCLE:
                t, feature = circle_circle(dx, dy, dvx, dvy, dax, day, F[i, RADIUS], F[j, RADIUS], window)
            else:
                t, feature = circle_polygon(
                    dx, dy, dvx, dvy, dax, day, F[i, RADIUS], OL, I[j, OUTLINE_START], I[j, OUTLINE_N], window
                )
        elif jkind == CIRCLE:
            t, feature = circle_polygon(
                -dx, -dy, -dvx, -dvy, -dax, -day, F[j, RADIUS], OL, I[i, OUTLINE_START], I[i, OUTLINE_N], window
            )
            first = j
            second = i
        else:
            t, feature = polygon_polygon(
                dx,
                dy,
                dvx,
                dvy,
                dax,
                day,
                OL,
                I[i, OUTLINE_START],
                I[i, OUTLINE_N],
                I[j, OUTLINE_START],
                I[j, OUTLINE_N],
                window,
            )
        if t != _INF:
            stats[S_HITS] += 1
            if i < j:
                key = (i << ID_SHIFT) | j
            else:
                key = (j << ID_SHIFT) | i
            push(S, now + t, key, first, second, I[first, COUNT], I[second, COUNT], feature)


@njit(cache=True)
def place_group(S, ids, start):
    """Invalidate and place ``ids[start:]`` (their motion changed now).

    Stops early when event slots run low; returns how many were done.
    """
    I = S[1]
    Q = S[4]
    k = start
    while k < ids.shape[0] and Q[FREE_N] >= Q[MIN_FREE]:
        i = ids[k]
        I[i, COUNT] += 1
        place(S, i)
        k += 1
    return k


@njit(cache=True)
def predict_group(S, ids, start, mark):
    """Predict ``ids[start:]`` against their neighbours, each pair once (pass the same
    fresh ``mark`` when resuming). Stops early when event slots run low; returns
    how many were done."""
    I = S[1]
    Q = S[4]
    k = start
    while k < ids.shape[0] and Q[FREE_N] >= Q[MIN_FREE]:
        i = ids[k]
        predict(S, i, mark)
        I[i, MARK] = mark
        k += 1
    return k


@njit(cache=True)
def new_mark(S):
    """A fresh pair-once mark."""
    Q = S[4]
    Q[MARK_COUNTER] += 1
    return Q[MARK_COUNTER]


# ------------------------------------------------------------------- response


@njit(cache=True)
def collide(S, a, b, feature, t):
    """Resolve the contact of ``a`` and ``b`` at ``t``; returns the impulse (0: a graze).

    The contact record goes to ``out``. Only moving bodies change motion, so
    only they are invalidated, placed and predicted again.
    """
    F = S[0]
    I = S[1]
    OL = S[2]
    Q = S[4]
    out = S[14]
    advance(F, a, t)
    advance(F, b, t)
    if I[a, KIND] == CIRCLE:
        if I[b, KIND] == CIRCLE:
            px, py, nx, ny = circle_circle_contact(F[a, X], F[a, Y], F[a, RADIUS], F[b, X], F[b, Y], F[b, RADIUS])
        else:
            px, py, nx, ny = circle_polygon_contact(
                F[a, X], F[a, Y], F[a, RADIUS], F[b, X], F[b, Y], OL, I[b, OUTLINE_START], I[b, OUTLINE_N], feature
            )
    else:
        px, py, nx, ny = polygon_polygon_contact(
            F[a, X],
            F[a, Y],
            F[b, X],
            F[b, Y],
            OL,
            I[a, OUTLINE_START],
            I[a, OUTLINE_N],
            I[b, OUTLINE_START],
            I[b, OUTLINE_N],
            feature,
        )
    normal_speed = (F[a, VX] - F[b, VX]) * nx + (F[a, VY] - F[b, VY]) * ny
    impulse = 0.0
    if normal_speed < 0.0:
        restitution = _combine(F[a, ELASTICITY], F[b, ELASTICITY], Q[RULE])
        ima = F[a, INV_MASS]
        imb = F[b, INV_MASS]
        impulse = -(1.0 + restitution) * normal_speed / (ima + imb)
        F[a, VX] += impulse * nx * ima
        F[a, VY] += impulse * ny * ima
        F[b, VX] -= impulse * nx * imb
        F[b, VY] -= impulse * ny * imb
    mark = Q[MARK_COUNTER] + 1
    Q[MARK_COUNTER] = mark
    a_moves = I[a, FIXED] == 0
    b_moves = I[b, FIXED] == 0
    if a_moves:
        I[a, COUNT] += 1
        place(S, a)
    if b_moves:
        I[b, COUNT] += 1
        place(S, b)
    if a_moves:
        predict(S, a, mark)
        I[a, MARK] = mark
    if b_moves:
        predict(S, b, mark)
    out[OUT_TIME] = t
    out[OUT_A] = a
    out[OUT_B] = b
    out[OUT_PX] = px
    out[OUT_PY] = py
    out[OUT_NX] = nx
    out[OUT_NY] = ny
    out[OUT_IMPULSE] = impulse
    out[OUT_SPEED] = -normal_speed
    return impulse


# ------------------------------------------------------------------- the loop


@njit(cache=True)
def run(S, until, notify_all):
    """Process events up to time ``until``; return a code saying why it stopped.

    DONE: the next event is later than ``until`` (``P[TIME]`` is not moved).
    COLLIDED: a collision that Python must hear about (``notify_all`` or a
    body flagged NOTIFY); its record is in ``out``. FIRED_TIMER, FIRED_FRAME:
    ``out[OUT_ID]`` names it. NEED_SPACE: grow the event arrays, call again.
    EMPTY: no events are left.
    """
    I = S[1]
    P = S[3]
    Q = S[4]
    heap = S[8]
    slot_time = S[9]
    slot_key = S[10]
    slot_data = S[11]
    free = S[12]
    stats = S[13]
    out = S[14]
    while True:
        if Q[FREE_N] < Q[MIN_FREE]:
            return NEED_SPACE
        if Q[HEAP_N] == 0:
            return EMPTY
        t = slot_time[heap[0]]
        if t > until:
            return DONE
        slot = _pop(S)
        kind = slot_key[slot] >> KIND_SHIFT
        a = slot_data[slot, 0]
        b = slot_data[slot, 1]
        count_a = slot_data[slot, 2]
        count_b = slot_data[slot, 3]
        feature = slot_data[slot, 4]
        free[Q[FREE_N]] = slot
        Q[FREE_N] += 1
        if kind == COLLISION:
            if I[a, COUNT] != count_a or I[b, COUNT] != count_b:
                stats[S_STALE] += 1
                continue
            P[TIME] = t
            stats[S_EVENTS] += 1
            if collide(S, a, b, feature, t) == 0.0:
                stats[S_GRAZES] += 1
                continue
            stats[S_COLLISIONS] += 1
            if I[a, FIXED] == 0 and I[b, FIXED] == 0:
                stats[S_PAIR_COLLISIONS] += 1
            if notify_all or I[a, NOTIFY] != 0 or I[b, NOTIFY] != 0:
                return COLLIDED
        elif kind == HORIZON_EVENT:
            if I[a, COUNT] != count_a:
                stats[S_STALE] += 1
                continue
            P[TIME] = t
            stats[S_EVENTS] += 1
            stats[S_HORIZONS] += 1
            I[a, COUNT] += 1
            place(S, a)
            predict(S, a, 0)
        elif kind == TIMER:
            P[TIME] = t
            out[OUT_TIME] = t
            out[OUT_ID] = a
            return FIRED_TIMER
        else:
            P[TIME] = t
            out[OUT_TIME] = t
            out[OUT_ID] = a
            out[OUT_EPOCH] = b
            return FIRED_FRAME


# --------------------------------------------------------------- validation


@njit(cache=True)
def overlap_depth(S, i, j):
    """Overlap depth of bodies ``i`` and ``j`` at ``P[TIME]`` (negative: apart; for two
    polygons a lower bound on the distance)."""
    F = S[0]
    I = S[1]
    OL = S[2]
    P = S[3]
    xi, yi, _, _ = state_at(F, i, P[TIME])
    xj, yj, _, _ = state_at(F, j, P[TIME])
    if I[i, KIND] == CIRCLE and I[j, KIND] == CIRCLE:
        return F[i, RADIUS] + F[j, RADIUS] - math.hypot(xi - xj, yi - yj)
    if I[i, KIND] == CIRCLE:
        return -closest_feature(xi - xj, yi - yj, F[i, RADIUS], OL, I[j, OUTLINE_START], I[j, OUTLINE_N])[3]
    if I[j, KIND] == CIRCLE:
        return -closest_feature(xj - xi, yj - yi, F[j, RADIUS], OL, I[i, OUTLINE_START], I[i, OUTLINE_N])[3]
    faces = minkowski_faces(OL, I[i, OUTLINE_START], I[i, OUTLINE_N], I[j, OUTLINE_START], I[j, OUTLINE_N])
    best = -_INF
    for f in range(faces.shape[0]):
        s = faces[f, 0] * (xi - xj) + faces[f, 1] * (yi - yj) + faces[f, 2]
        if s > best:
            best = s
    return -best


@njit(cache=True)
def find_overlap(S, ids, tolerance):
    """First pair ``(i, j, depth)`` among ``ids`` and their neighbours overlapping by more
    than ``tolerance`` times their bounding radii; ``(-1, -1, 0.0)`` when there is none."""
    F = S[0]
    I = S[1]
    scratch = S[15]
    for k in range(ids.shape[0]):
        i = ids[k]
        n = gather(S, i)
        for m in range(n):
            j = scratch[m]
            if I[i, FIXED] != 0 and I[j, FIXED] != 0:
                continue
            depth = overlap_depth(S, i, j)
            if depth > tolerance * (F[i, REACH] + F[j, REACH]):
                return i, j, depth
    return -1, -1, 0.0
