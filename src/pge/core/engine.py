"""The compiled event loop: collisions and horizons; timers and frames go back to Python.

State is one named tuple ``S`` of arrays (``pge.core.state.State``: ``S.F``, ``S.I``,
``S.heap_time``, ...); column meanings are in ``pge.core.layout``.

One event (``run``): pop the earliest queue entry; skip it if stale (a
body's invalidation counter moved on); advance the bodies involved to the
event time; resolve it; *touch* every body whose motion changed (new
counter, new swept box) and queue it for prediction
against the bodies whose boxes overlap its own. Nothing else is visited, so
an event costs the same among a thousand bodies as among a hundred thousand.
"""

from __future__ import annotations

import math

import numpy as np
from pge._jit_cache import njit

from pge.core import layout as L
from pge.core.borrow import borrowed
from pge.contact.manifold import NCOLUMNS, NX, NY, PX, PY, SEPARATION, polygon_polygon_points
from pge.core.impulse import contact_impulse, patch_impulse
from pge.core.motion import advance, orient
from pge.core.predict import new_mark, place, predict
from pge.core.prefetch import prefetch_row
from pge.core.queue import next_is_horizon, pop_earliest
from pge.core.response import apply_impulse, combine, contact_response
from pge.core.tuning import CONTACT_MARGIN, FACE_DIP, FACE_HYSTERESIS, SIMULTANEOUS, STORM_SPAN, STORM_TICKS, TOUCHING
from pge.toi.circle_circle import circle_circle_contact
from pge.toi.circle_polygon import circle_polygon_contact
from pge.toi.polygon_polygon import polygon_polygon_contact
from pge.toi.rotating import rotating_polygon_polygon_contact

_INF = math.inf
CIRCLE = 0
#: the bits of a queue key that hold one body id (``pge.core.layout``, ``ID_SHIFT``)
_ID_MASK = (1 << L.ID_SHIFT) - 1


# ---------------------------------------------------------------- work list


@njit(cache=True, inline="always")
def queue_prediction(S, i):
    """Ask for body ``i`` to be predicted again before the next event."""
    Q = S.Q
    pending = S.pending
    if Q[L.PENDING_DONE] == Q[L.PENDING_N]:
        Q[L.PENDING_N] = 0
        Q[L.PENDING_DONE] = 0
        Q[L.PENDING_MARK] = new_mark(S)
    pending[Q[L.PENDING_N]] = i
    Q[L.PENDING_N] += 1


@njit(cache=True)
def drain_predictions(S, polygons):
    """Predict the queued bodies, each pair once; False if event slots ran low first.
    ``polygons``: None where no polygon can move (``predict``)."""
    I = S.I
    Q = S.Q
    pending = S.pending
    mark = Q[L.PENDING_MARK]
    while Q[L.PENDING_DONE] < Q[L.PENDING_N]:
        if Q[L.FREE_N] < Q[L.MIN_FREE]:
            return False
        i = pending[Q[L.PENDING_DONE]]
        Q[L.PENDING_DONE] += 1
        if I[i, L.MARK] == mark or I[i, L.ALIVE] == 0:
            continue
        predict(S, i, mark, polygons)
        I[i, L.MARK] = mark
    return True


@njit(cache=True, inline="always")
def touch(S, i):
    """Body ``i``'s motion or shape changed now: invalidate its events, renew its box and
    queue it for prediction."""
    I = S.I
    if I[i, L.ALIVE] == 0:
        return
    I[i, L.COUNT] += 1
    place(S, i)
    queue_prediction(S, i)


@njit(cache=True)
def touch_one(S, i):
    """``touch`` as a call, for the places that may do without it inlined.

    Every inlined copy of ``touch`` (with ``place`` and the queue inside it) is typed and
    compiled again, seconds each on a cold start; a call costs a few nanoseconds an event.
    """
    touch(S, i)


@njit(cache=True)
def touch_group(S, ids, count):
    """``touch`` the first ``count`` bodies of ``ids`` (through ``touch_one``: no copy of
    ``touch`` of its own to compile)."""
    for k in range(count):
        touch_one(S, ids[k])


# ------------------------------------------------------------------- response


@njit(cache=True)
def contact_geometry(S, a, b, feature, polygons):
    """Contact point and unit normal (from b towards a) of ``a`` and ``b`` at their common
    reference time, with ``feature`` from the kernel: ``(px, py, nx, ny)``. ``a`` is the
    circle of a circle and a polygon; two polygons meet only where ``polygons`` is not None
    (``predict``)."""
    F = S.F
    I = S.I
    OL = S.OL
    n_b = I[b, L.OUTLINE_N]
    if I[a, L.KIND] == CIRCLE:
        if I[b, L.KIND] == CIRCLE:
            px, py, nx, ny = circle_circle_contact(F[a, L.X], F[a, L.Y], F[a, L.RADIUS], F[b, L.X], F[b, L.Y], F[b, L.RADIUS])
        else:
            px, py, nx, ny = circle_polygon_contact(
                F[a, L.X], F[a, L.Y], F[a, L.RADIUS], F[b, L.X], F[b, L.Y], OL, I[b, L.OUTLINE_START], n_b, feature
            )
        return px, py, nx, ny
    if polygons is not None:
        # Pruned from the version compiled for None (``if`` on an argument's type).
        if F[a, L.OMEGA] != 0.0 or F[b, L.OMEGA] != 0.0:
            # The outlines are turned to now; the angular velocities pick the point of a
            # face-to-face patch (its faster-approaching end).
            return rotating_polygon_polygon_contact(
                F[a, L.X], F[a, L.Y], F[b, L.X], F[b, L.Y], F[a, L.VX] - F[b, L.VX], F[a, L.VY] - F[b, L.VY], OL,
                I[a, L.OUTLINE_START], I[a, L.OUTLINE_N], 0.0, F[a, L.OMEGA],
                I[b, L.OUTLINE_START], n_b, 0.0, F[b, L.OMEGA], feature,
            )
        return polygon_polygon_contact(
            F[a, L.X], F[a, L.Y], F[b, L.X], F[b, L.Y], OL, I[a, L.OUTLINE_START], I[a, L.OUTLINE_N], I[b, L.OUTLINE_START], n_b, feature
        )
    return 0.0, 0.0, 0.0, 0.0  # never: no two polygons meet in a world whose polygons cannot move


@njit(cache=True)
def face_patch(S, a, b, nx, ny, reach):
    """Whether polygons ``a`` and ``b``, colliding now with normal ``n``, meet face to face:
    their manifold (``pge.contact.manifold``) has two points along ``n`` and both touch as an
    island's step counts touching (``TOUCHING`` of the smaller reach, or closing within
    ``SIMULTANEOUS`` of the island step), so that a face landing flat to rounding lands as a
    face. Both ends must be closing (where one separates, the impact is the other's alone).
    Returns ``(found, x1, y1, x2, y2)``, the two points."""
    F = S.F
    I = S.I
    OL = S.OL
    rows = np.empty((4, NCOLUMNS))
    count = polygon_polygon_points(
        F[a, L.X], F[a, L.Y], OL, I[a, L.OUTLINE_START], I[a, L.OUTLINE_N],
        F[b, L.X], F[b, L.Y], I[b, L.OUTLINE_START], I[b, L.OUTLINE_N],
        reach, FACE_HYSTERESIS * (F[a, L.REACH] + F[b, L.REACH]), FACE_DIP * (F[a, L.REACH] + F[b, L.REACH]), rows, 0,
    )
    if count != 2 or rows[0, NX] * nx + rows[0, NY] * ny < 1.0 - 1e-9:
        return False, 0.0, 0.0, 0.0, 0.0
    window = SIMULTANEOUS * S.P[L.CONTACT_STEP]
    for k in range(2):
        rax = rows[k, PX] - F[a, L.X]
        ray = rows[k, PY] - F[a, L.Y]
        rbx = rows[k, PX] - F[b, L.X]
        rby = rows[k, PY] - F[b, L.Y]
        ux = F[a, L.VX] - F[a, L.OMEGA] * ray - (F[b, L.VX] - F[b, L.OMEGA] * rby)
        uy = F[a, L.VY] + F[a, L.OMEGA] * rax - (F[b, L.VY] + F[b, L.OMEGA] * rbx)
        closing = -(ux * nx + uy * ny)
        gap = rows[k, SEPARATION]
        if not closing > 0.0 or not (gap <= TOUCHING * reach or gap <= closing * window):
            return False, 0.0, 0.0, 0.0, 0.0
    return True, rows[0, PX], rows[0, PY], rows[1, PX], rows[1, PY]


@njit(cache=True, inline="always")
def _cross(rx, ry, dx, dy):
    return rx * dy - ry * dx


@njit(cache=True)
def patch_collide(F, a, b, x1, y1, x2, y2, nx, ny, restitution, mu):
    """The impact of a face on a face at points ``(x1, y1)`` and ``(x2, y2)``
    (``pge.core.impulse.patch_impulse``: both ends together, friction at their midpoint),
    applied to ``a`` and (opposite) ``b``. Returns the two normal impulses and the friction
    impulse."""
    tx = -ny
    ty = nx
    mx = 0.5 * (x1 + x2)
    my = 0.5 * (y1 + y2)
    u1 = 0.0
    u2 = 0.0
    ut = 0.0
    k11 = k12 = k22 = k1t = k2t = ktt = 0.0
    for x, side in ((a, 1.0), (b, -1.0)):
        m = F[x, L.INV_MASS]
        inertia = F[x, L.INV_INERTIA]
        cx = F[x, L.X]
        cy = F[x, L.Y]
        c1 = _cross(x1 - cx, y1 - cy, nx, ny)
        c2 = _cross(x2 - cx, y2 - cy, nx, ny)
        cm = _cross(mx - cx, my - cy, tx, ty)
        k11 += m + inertia * c1 * c1
        k12 += m + inertia * c1 * c2
        k22 += m + inertia * c2 * c2
        k1t += inertia * c1 * cm
        k2t += inertia * c2 * cm
        ktt += m + inertia * cm * cm
        w = F[x, L.OMEGA]
        u1 += side * ((F[x, L.VX] - w * (y1 - cy)) * nx + (F[x, L.VY] + w * (x1 - cx)) * ny)
        u2 += side * ((F[x, L.VX] - w * (y2 - cy)) * nx + (F[x, L.VY] + w * (x2 - cx)) * ny)
        ut += side * ((F[x, L.VX] - w * (my - cy)) * tx + (F[x, L.VY] + w * (mx - cx)) * ty)
    l1, l2, jt = patch_impulse(u1, u2, ut, k11, k12, k22, k1t, k2t, ktt, restitution, mu)
    for x, side in ((a, 1.0), (b, -1.0)):
        cx = F[x, L.X]
        cy = F[x, L.Y]
        apply_impulse(F, x, side * l1 * nx, side * l1 * ny, x1 - cx, y1 - cy)
        apply_impulse(F, x, side * l2 * nx, side * l2 * ny, x2 - cx, y2 - cy)
        apply_impulse(F, x, side * jt * tx, side * jt * ty, mx - cx, my - cy)
    return l1, l2, jt


@njit(cache=True, inline="always")
def _record_patch(out, x1, y1, x2, y2, l1, l2, jt):
    """A face patch's ends and impulses into the loop's record (``Collision.patch``)."""
    out[L.OUT_X1] = x1
    out[L.OUT_Y1] = y1
    out[L.OUT_X2] = x2
    out[L.OUT_Y2] = y2
    out[L.OUT_L1] = l1
    out[L.OUT_L2] = l2
    out[L.OUT_JT] = jt


@njit(cache=True)
def patch_impact(S, a, b, nx, ny, reach, restitution, mu):
    """Where two polygons meet face to face (``face_patch``), their impact at both ends of
    the patch (``patch_collide``), recorded in ``out``: ``(True, normal impulse)``; else
    ``(False, 0.0)``, and the impact is one point's."""
    if S.I[a, L.KIND] == CIRCLE or S.I[b, L.KIND] == CIRCLE:
        return False, 0.0
    found, x1, y1, x2, y2 = face_patch(S, a, b, nx, ny, reach)
    if not found:
        return False, 0.0
    l1, l2, jt = patch_collide(S.F, a, b, x1, y1, x2, y2, nx, ny, restitution, mu)
    _record_patch(S.out, x1, y1, x2, y2, l1, l2, jt)
    return True, l1 + l2


@njit(cache=True)
def point_collide(F, a, b, rax, ray, rbx, rby, nx, ny, ux, uy, restitution, mu):
    """The impact of ``a`` and ``b`` at one point (lever arms ``r_a``, ``r_b``, normal ``n``,
    relative velocity ``u`` there, approaching): one exact impulse
    (``pge.core.impulse.contact_impulse``), applied to ``a`` and (opposite) ``b``. Returns
    its normal part (0 where neither body can be moved)."""
    tx = -ny
    ty = nx
    ann, ant, att = contact_response(F, a, rax, ray, nx, ny, tx, ty)
    bnn, bnt, btt = contact_response(F, b, rbx, rby, nx, ny, tx, ty)
    knn = ann + bnn
    if not knn > 0.0:
        return 0.0
    impulse, tangential = contact_impulse(
        ux * nx + uy * ny, ux * tx + uy * ty, knn, ant + bnt, att + btt, restitution, mu
    )
    jx = impulse * nx + tangential * tx
    jy = impulse * ny + tangential * ty
    apply_impulse(F, a, jx, jy, rax, ray)
    apply_impulse(F, b, -jx, -jy, rbx, rby)
    return impulse


@njit(cache=True)
def joins(S, a, b, nx, ny, leaving):
    """Whether the contact of ``a`` and ``b`` (normal ``n`` from b to a), leaving at
    ``leaving`` after its impulse, is persistent: the bodies' accelerations would bring
    them back before they had parted by the rest height (``P[REST_HEIGHT]`` times the
    smaller reach), or one of them already belongs to an island. Then the bodies join one
    island, whose step solves the contact from now on. With no
    acceleration anywhere (a gas, a game in space) no contact is persistent."""
    F = S.F
    I = S.I
    scale = max(math.hypot(F[a, L.FREE_AX], F[a, L.FREE_AY]), math.hypot(F[b, L.FREE_AX], F[b, L.FREE_AY]))
    if not scale > 0.0:
        return False
    reach = min(F[a, L.REACH], F[b, L.REACH])
    if leaving * abs(leaving) >= 2.0 * scale * S.P[L.REST_HEIGHT] * reach:
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
def collide(S, a, b, feature, t, polygons):
    """The impact of ``a`` and ``b`` at ``t``: one exact impulse
    at the contact point (restitution, Coulomb friction, the energy guard of
    ``pge.core.impulse``: ``point_collide``), or where a face meets a face both its ends
    together (``face_patch``, ``patch_collide``), on two free bodies; returns the normal
    impulse (0: a graze).

    ``out`` gets the record and ``OUT_JOIN``: ``ABSORB`` when a body of an island takes part
    and the pair closes slower than a step can follow (its approach over a step below the
    smaller reach): no impulse is applied here, and the island's step at this instant
    solves the impact together with the island's contacts (a block standing on a floor and
    hit low answers with the floor's push and friction at once, not as a free body); else
    ``JOIN`` if the contact is persistent (``joins``), ``WAKE`` if it is not but a body of an
    island took part (which may sleep), else ``NO_JOIN``; when not ``NO_JOIN`` the loop hands
    the collision to Python, which joins, absorbs or wakes the islands.
    """
    F = S.F
    I = S.I
    Q = S.Q
    out = S.out
    advance(F, a, t)
    advance(F, b, t)
    orient(F, I, S.OL, S.OB, a, t)
    orient(F, I, S.OL, S.OB, b, t)
    px, py, nx, ny = contact_geometry(S, a, b, feature, polygons)
    rax = px - F[a, L.X]
    ray = py - F[a, L.Y]
    rbx = px - F[b, L.X]
    rby = py - F[b, L.Y]
    ux = F[a, L.VX] - F[a, L.OMEGA] * ray - (F[b, L.VX] - F[b, L.OMEGA] * rby)
    uy = F[a, L.VY] + F[a, L.OMEGA] * rax - (F[b, L.VY] + F[b, L.OMEGA] * rbx)
    normal_speed = ux * nx + uy * ny
    impulse = 0.0
    within = S.P[L.CONTACT_STEP]
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
    patch = False
    restitution = combine(F[a, L.ELASTICITY], F[b, L.ELASTICITY], Q[L.RULE])
    mu = combine(F[a, L.FRICTION], F[b, L.FRICTION], Q[L.FRICTION_RULE])
    if normal_speed < 0.0 and not absorb:
        if polygons is not None:
            # Pruned from the version compiled for None (``if`` on an argument's type).
            patch, impulse = patch_impact(S, a, b, nx, ny, reach, restitution, mu)
        if not patch:
            impulse = point_collide(F, a, b, rax, ray, rbx, rby, nx, ny, ux, uy, restitution, mu)
    ux = F[a, L.VX] - F[a, L.OMEGA] * ray - (F[b, L.VX] - F[b, L.OMEGA] * rby)
    uy = F[a, L.VY] + F[a, L.OMEGA] * rax - (F[b, L.VY] + F[b, L.OMEGA] * rbx)
    # A pair that collides again within one step of the islands and parts slowly (by less
    # than CONTACT_MARGIN of the smaller reach over a step) is a persistent contact: a ball bouncing lower and
    # lower, two polygons grinding, a body squeezed between two. Its island's step then takes
    # all its points at once, so runs of impacts that would converge on an instant end after
    # a few. A pair that parts faster is in flight (an elastic corner-then-corner hit, a ball
    # shot to and fro between two walls): its next impact is exact, as any in a gas. So is a
    # pair whose impacts lose nothing (restitution 1, no friction): runs of impacts converge
    # on an instant only by losing energy at each (elastic hard discs make finitely many
    # collisions in finite time), so a lossless pair that meets again is not held.
    leaving = ux * nx + uy * ny
    lossless = restitution == 1.0 and mu == 0.0
    again = leaving * within < CONTACT_MARGIN * reach and t - last <= within and not lossless
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
    out[L.OUT_PATCH] = 1.0 if patch else 0.0
    return impulse


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
    P = S.P
    Q = S.Q
    cap = Q[L.STORM_CAP]
    tick = np.nextafter(t, _INF) - t
    span = max(STORM_SPAN, STORM_TICKS * cap * tick)
    if t - P[L.STORM_START] <= span:
        Q[L.STORM_RUN] += 1
    else:
        P[L.STORM_START] = t
        Q[L.STORM_RUN] = 0
        for k in range(L.NKINDS):
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


@njit(cache=True, inline="always")
def ask_ahead(S, horizon):
    """Start loading what the next event may read first (``pge.core.prefetch``): the
    earliest slot's data and its bodies' rows (named by its key), and, with ``horizon``
    (the current event is not the horizons' first, so that one stays a candidate), the
    rows of the body whose horizon is first."""
    F = S.F
    I = S.I
    if S.Q[L.HEAP_N] > 0:
        key = S.heap_entry[0, 0]
        prefetch_row(S.slot_data, S.heap_entry[0, 1])
        kind = key >> L.KIND_SHIFT
        if kind == L.COLLISION or kind == L.HORIZON_EVENT:
            last = key & _ID_MASK  # the body of a horizon; the larger of a collision's two
            prefetch_row(I, last)
            prefetch_row(F, last)
            if kind == L.COLLISION:
                first = (key >> L.ID_SHIFT) & _ID_MASK
                prefetch_row(I, first)
                prefetch_row(F, first)
    if horizon and S.Q[L.HORIZON_N] > 0:
        prefetch_row(I, S.horizon_index[0, 0])
        prefetch_row(F, S.horizon_index[0, 0])


@njit(cache=True)
def run(S, until, notify_all, polygons):
    """Process events up to time ``until``; return a code saying why it stopped.

    DONE: the next event is later than ``until`` (``P[TIME]`` is not moved).
    COLLIDED: a collision that Python must hear about (``notify_all`` or a
    body flagged NOTIFY); its record is in ``out``. FIRED_TIMER, FIRED_FRAME:
    ``out[OUT_ID]`` names it. NEED_SPACE: grow the event arrays, call again.
    EMPTY: no events are left. JOINED: a persistent contact (``collide``, record in
    ``out``) joins its bodies' islands. STORM: the progress watch (``watch``) found a run of
    events the clock cannot separate; ``out`` names the last event's bodies. TOO_FAST:
    ``Q[FAST_BODY]``'s travel step is shorter than the clock can resolve (``place``);
    nothing has used its box.

    The loop works on the state ``borrowed``: its arrays without reference counts
    (``pge.core.borrow``; the caller holds them). ``polygons`` is None when no polygon can
    move (every polygon fixed: a gas of discs in a box): the version compiled for None
    leaves out the kernels of turning polygons and of two polygons meeting, most of a
    cold start's compiling for such a world; the World passes True as soon as a polygon
    may move.
    """
    S = borrowed(S)
    I = S.I
    P = S.P
    Q = S.Q
    heap_time = S.heap_time
    slot_data = S.slot_data
    stats = S.stats
    out = S.out
    while True:
        if Q[L.FAST_BODY] >= 0:
            return _report(out, P[L.TIME], Q[L.FAST_BODY], -1, L.TOO_FAST)
        # The call only where bodies wait (after a stale pop none do): a call passes all of S.
        pending = Q[L.PENDING_DONE] < Q[L.PENDING_N]
        if (pending and not drain_predictions(S, polygons)) or Q[L.FREE_N] < Q[L.MIN_FREE]:
            return L.NEED_SPACE
        if Q[L.HEAP_N] == 0 and Q[L.HORIZON_N] == 0:
            return L.EMPTY
        horizon = next_is_horizon(S)
        if horizon:
            # The horizon stays first in its heap until ``touch`` moves it to the next one.
            t = S.horizon_time[0]
            if t > until:
                return L.DONE
            kind = L.HORIZON_EVENT
            a = S.horizon_index[0, 0]
            b = -1
            count_a = count_b = feature = 0
        else:
            if heap_time[0] > until:
                return L.DONE
            slot, t, key = pop_earliest(S)
            kind = key >> L.KIND_SHIFT
            a = slot_data[slot, 0]
            b = slot_data[slot, 1]
            count_a = slot_data[slot, 2]
            count_b = slot_data[slot, 3]
            feature = slot_data[slot, 4]
        ask_ahead(S, not horizon)
        if not horizon and (kind == L.COLLISION or kind == L.HORIZON_EVENT):
            if I[a, L.COUNT] != count_a or (kind == L.COLLISION and I[b, L.COUNT] != count_b):
                stats[L.S_STALE] += 1
                continue
        P[L.TIME] = t
        if watch(S, t, kind):
            if kind != L.COLLISION:
                b = -1
            if kind >= L.TIMER:
                a = -1
            return _report(out, t, a, b, L.STORM)
        if kind == L.COLLISION:
            stats[L.S_EVENTS] += 1
            impulse = collide(S, a, b, feature, t, polygons)
            if impulse == 0.0 and out[L.OUT_JOIN] != L.ABSORB:
                stats[L.S_GRAZES] += 1
            else:
                stats[L.S_COLLISIONS] += 1
                if I[a, L.FIXED] == 0 and I[b, L.FIXED] == 0:
                    stats[L.S_PAIR_COLLISIONS] += 1
            if out[L.OUT_JOIN] != L.NO_JOIN:
                if out[L.OUT_JOIN] != L.WAKE:
                    stats[L.S_JOINS] += 1
                return L.JOINED
            if impulse != 0.0 and (notify_all or I[a, L.NOTIFY] != 0 or I[b, L.NOTIFY] != 0):
                return L.COLLIDED
        elif kind == L.HORIZON_EVENT:
            stats[L.S_EVENTS] += 1
            stats[L.S_HORIZONS] += 1
            touch(S, a)  # inlined: most events are horizons
        elif kind == L.TIMER:
            out[L.OUT_TIME] = t
            out[L.OUT_ID] = a
            return L.FIRED_TIMER
        else:
            out[L.OUT_TIME] = t
            out[L.OUT_ID] = a
            out[L.OUT_EPOCH] = b
            return L.FIRED_FRAME
