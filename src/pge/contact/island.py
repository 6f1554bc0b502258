"""One step of an island: its contacts solved together, compiled.

Between steps every body of an island flies in closed form like any other body (constant
acceleration, constant angular acceleration), so its contacts with bodies outside the island
are predicted exactly. At a step, at time ``t``, the island's contacts (``pge.contact.manifold``:
every pair of its bodies, and each body with the fixed bodies near it, closer than the step's
travel) are solved together with Coulomb friction, in two stages:

* **impacts**: impulses on the velocities now, inelastic (a touching point stops closing, or
  bounces if it would bounce higher than the rest height; so does a point with a gap that
  closes within ``BOUNCE_WINDOW`` of the step fast enough to bounce, from its gap; any other
  point with a gap may close by it within the step and no faster);
* **forces**: the contact forces over the coming step, each constant, found as impulses on
  the velocities at the step's *end* (``v + h a`` without them): a touching or overlapping
  point stops closing, a gap closes by itself at most, a sticking pair stops sliding, a
  sliding one takes ``mu`` times its normal force. The forces become each body's
  acceleration and angular acceleration until the next step, so a point's normal speed is
  linear over the step and a body held still has velocity and acceleration exactly zero: a
  contact that holds does no work;
* **push-out**: overlaps are moved out by ``PUSH_RATE`` of their depth, as a displacement
  over the step (``pge.contact.pushout``).

Each stage is a complementarity problem, solved by ``pge.contact.solve`` on the contact rows
of ``pge.contact.rows``.

Stages: ``_start`` (bodies to ``t``, velocities now, travel margins), ``_collect`` (the
manifold), ``_until_contact`` (the step's length: shorter where a bouncing impact is due),
``_prepare`` (lever arms, effective masses, targets, last step's impulses),
``_impacts``, ``_end_targets`` and ``_solve`` (the forces), ``_no_gain`` (the energy stage:
``pge.contact.energy``), ``_solved_arcs`` (what a turning pair's straight lines miss on the
solved motion: ``pge.contact.arcs``), ``_push_out``, ``_lift_paid`` (the lift's payment:
``pge.contact.energy``), ``_finish`` (accelerations from the forces and the push-out, the
island's parts and the bodies that left it, the touch).
"""

from __future__ import annotations

import math

import numpy as np

from pge._jit_cache import njit
from pge.contact.arcs import _midstep_rows, _solved_arcs
from pge.contact.energy import _blend, _lift_paid, _no_gain, _parts, _pressed
from pge.contact.manifold import (
    KEY,
    NX,
    NY,
    PX,
    PY,
    SEPARATION,
)
from pge.contact.pushout import _push_out
from pge.contact.rows import (
    CIRCLE,
    IA,
    IB,
    IMPACT,
    KN,
    LAMBDA_N,
    LAMBDA_T,
    MA,
    MB,
    MU,
    NSOLVE,
    TARGET,
    _lever_arms,
    _pair_constants,
    _points_at,
    _relative,
    _relative_at,
)
from pge.contact.solve import _solve
from pge.core import layout as L
from pge.core.response import combine
from pge.core.engine import touch_one
from pge.core.grid import gather
from pge.core.motion import advance, orient
from pge.core.tuning import (
    BOUNCE_WINDOW,
    CONTACT_MARGIN,
    IMPACT_ITERATIONS,
    IMPACT_LCP_LIMIT,
    ISLAND_ITERATIONS,
    LCP_LIMIT,
    MAX_TURN,
    ROW_BUDGET,
    SHORTEST_REACH_STEP,
    SHORTEST_STEP,
    SIMULTANEOUS,
    SOLVE_TOLERANCE,
    TOUCHING,
)

# the warm-start key of a contact: (body a, body b, manifold key) in one integer
_BODY_BITS = 21
_KEY_BITS = 16


@njit(cache=True)
def _start(S, members, local, h, t):
    """Bodies to ``t`` (under the last step's contact forces), outlines turned; velocities
    now ``(vx, vy, spin)`` and each body's travel margin over a step of free flight."""
    F = S.F
    I = S.I
    m = members.shape[0]
    now = np.empty((m, 3))
    margin = np.empty(m)
    for k in range(m):
        i = members[k]
        local[i] = k
        advance(F, i, t)
        orient(F, I, S.OL, S.OB, i, t)
        ax = F[i, L.FREE_AX]
        ay = F[i, L.FREE_AY]
        now[k, 0] = F[i, L.VX]
        now[k, 1] = F[i, L.VY]
        now[k, 2] = F[i, L.OMEGA]
        travel = math.hypot(now[k, 0] + 0.5 * h * ax, now[k, 1] + 0.5 * h * ay) + abs(now[k, 2]) * F[i, L.REACH]
        margin[k] = h * travel + 0.125 * h * h * math.hypot(ax, ay)
    return now, margin


@njit(cache=True)
def _points(S, i, j, margin, rows, count):
    """Append the manifold of bodies ``i`` and ``j`` (normal from j to i)."""
    F = S.F
    I = S.I
    return _points_at(F, I, S.OL, i, F[i, L.X], F[i, L.Y], I[i, L.OUTLINE_START], j, F[j, L.X], F[j, L.Y],
                      I[j, L.OUTLINE_START], margin, rows, count)


@njit(cache=True)
def _collect(S, members, local, margin, t):
    """The island's manifold: contact rows and, per row, the two bodies' local indices (-1:
    a fixed body) and ids."""
    F = S.F
    I = S.I
    scratch = S.scratch
    m = members.shape[0]
    island = I[members[0], L.ISLAND]
    capacity = 16 + 8 * m
    rows = np.zeros((capacity, NSOLVE))
    pairs = np.empty((capacity, 4), dtype=np.int64)
    count = 0
    for k in range(m):
        i = members[k]
        own = CONTACT_MARGIN * F[i, L.REACH]
        n = gather(S, i, margin[k] + own)
        for q in range(n):
            j = scratch[q]
            if I[j, L.FIXED] != 0:
                other = -1
                pad = margin[k] + own
                orient(F, I, S.OL, S.OB, j, t)
            elif I[j, L.ISLAND] == island and local[j] > k:
                other = local[j]
                pad = margin[k] + margin[other] + CONTACT_MARGIN * min(F[i, L.REACH], F[j, L.REACH])
            else:
                continue
            if count + 2 > capacity:
                capacity *= 2
                grown = np.zeros((capacity, NSOLVE))
                grown[:count] = rows[:count]
                rows = grown
                grown_pairs = np.empty((capacity, 4), dtype=np.int64)
                grown_pairs[:count] = pairs[:count]
                pairs = grown_pairs
            before = count
            count = _points(S, i, j, pad, rows, count)
            for c in range(before, count):
                pairs[c, 0] = k
                pairs[c, 1] = other
                pairs[c, 2] = i
                pairs[c, 3] = j
    return rows, pairs, count


@njit(cache=True, inline="always")
def _contact_key(i, j, key):
    return ((i << _BODY_BITS) | j) << _KEY_BITS | key


def contact_bodies(keys):
    """The two bodies of each contact key (arrays of body ids, as ``step_island`` keyed them)."""
    pairs = keys >> _KEY_BITS
    return pairs >> _BODY_BITS, pairs & ((1 << _BODY_BITS) - 1)


@njit(cache=True, inline="always")
def _touching(gap, closing, reach, window):
    """Whether a point counts as touching now: its gap is below ``TOUCHING`` of its pair's
    reach, or it closes within ``window`` (``SIMULTANEOUS`` of the step). Corners of a face
    landing level to rounding, or on a face tilted by a rounding-sized angle, then take their
    impact together, as one face, not one after the other (which would set the body
    turning on a difference of 1e-7 in their gaps)."""
    return gap <= TOUCHING * reach or gap <= closing * window


@njit(cache=True, inline="always")
def _arrival(gap, u, a):
    """The earliest time a gap ``gap > 0`` with normal speed ``u`` (positive: opening) and
    normal acceleration ``a`` closes, the earliest root of ``gap + u t + a t^2 / 2``
    (computed stably as ``2 gap / (-u + sqrt(u^2 - 2 a gap))``); infinity if it never does."""
    discriminant = u * u - 2.0 * a * gap
    if discriminant < 0.0:
        return math.inf
    below = -u + math.sqrt(discriminant)
    if not below > 0.0:
        return math.inf
    return 2.0 * gap / below


@njit(cache=True, inline="always")
def _approach_acceleration(F, pairs, c, nx, ny):
    """Row ``c``'s relative acceleration along its normal ``(nx, ny)``, each body's as the
    last step left it (its contact forces included: a body resting on a floor does not
    fall towards the body landing on it); a fixed body does not accelerate."""
    i = pairs[c, 2]
    j = pairs[c, 3]
    ax = F[i, L.AX]
    ay = F[i, L.AY]
    if pairs[c, 1] >= 0:
        ax -= F[j, L.AX]
        ay -= F[j, L.AY]
    return ax * nx + ay * ny


@njit(cache=True, inline="always")
def _row_bounce(F, Q, rest_height, i, j, closing, reach):
    """The normal speed a point of bodies ``i`` and ``j`` closing at ``closing`` leaves with,
    ``e closing`` with their combined elasticity, if that bounces higher than the rest
    height against the stronger of their free accelerations; else 0 (it stops closing: an
    inelastic impact)."""
    if not closing > 0.0:
        return 0.0
    e = combine(F[i, L.ELASTICITY], F[j, L.ELASTICITY], Q[L.RULE])
    pressing = max(math.hypot(F[i, L.FREE_AX], F[i, L.FREE_AY]), math.hypot(F[j, L.FREE_AX], F[j, L.FREE_AY]))
    bounce = e * closing
    if bounce * bounce > 2.0 * pressing * rest_height * reach:
        return bounce
    return 0.0


@njit(cache=True)
def _prepare(S, rows, pairs, count, h, warm_keys, warm_impulses):
    """Lever arms, effective masses, friction and target normal speeds of every row, and the
    impulses the same contact took at the last step (warm start)."""
    F = S.F
    Q = S.Q
    rest_height = S.P[L.REST_HEIGHT]
    window = SIMULTANEOUS * S.P[L.CONTACT_STEP]
    early = BOUNCE_WINDOW * S.P[L.CONTACT_STEP]
    keys = np.empty(count, dtype=np.int64)
    for c in range(count):
        i = pairs[c, 2]
        j = pairs[c, 3]
        px = rows[c, PX]
        py = rows[c, PY]
        nx = rows[c, NX]
        ny = rows[c, NY]
        rax = px - F[i, L.X]
        ray = py - F[i, L.Y]
        rbx = px - F[j, L.X]
        rby = py - F[j, L.Y]
        rows[c, MA] = F[i, L.INV_MASS]
        rows[c, IA] = F[i, L.INV_INERTIA]
        rows[c, MB] = F[j, L.INV_MASS]
        rows[c, IB] = F[j, L.INV_INERTIA]
        _lever_arms(rows, c, rax, ray, rbx, rby)
        rows[c, MU] = combine(F[i, L.FRICTION], F[j, L.FRICTION], Q[L.FRICTION_RULE])
        separation = rows[c, SEPARATION]
        reach = min(F[i, L.REACH], F[j, L.REACH])
        ux = F[i, L.VX] - F[i, L.OMEGA] * ray - (F[j, L.VX] - F[j, L.OMEGA] * rby)
        uy = F[i, L.VY] + F[i, L.OMEGA] * rax - (F[j, L.VY] + F[j, L.OMEGA] * rbx)
        closing = -(ux * nx + uy * ny)
        approach = _approach_acceleration(F, pairs, c, nx, ny)
        rows[c, IMPACT] = _impact_target(F, Q, rest_height, i, j, separation, closing, approach, reach, h, window,
                                         early)
        key = _contact_key(i, j, np.int64(rows[c, KEY]))
        keys[c] = key
        rows[c, LAMBDA_N] = 0.0
        rows[c, LAMBDA_T] = 0.0
        if warm_keys.shape[0] > 0:
            at = np.searchsorted(warm_keys, key)
            if at < warm_keys.shape[0] and warm_keys[at] == key:
                rows[c, LAMBDA_N] = warm_impulses[at, 0]
                rows[c, LAMBDA_T] = warm_impulses[at, 1]
    _pair_constants(rows, pairs, count)
    return keys


@njit(cache=True, inline="always")
def _impact_target(F, Q, rest_height, i, j, separation, closing, approach, reach, h, window, early):
    """A row's target normal speed for the impact stage, on the velocities now: a touching
    point stops closing, or bounces if it closes fast enough to bounce higher than the rest
    height; so does a point whose gap closes within ``early`` (``BOUNCE_WINDOW`` of the
    step; ``approach`` is the relative acceleration along the normal,
    ``_approach_acceleration``) and that closes fast
    enough now to bounce; any other point with a gap may close by it within the step, no
    faster."""
    if _touching(separation, closing, reach, window):
        return _row_bounce(F, Q, rest_height, i, j, closing, reach)
    if _arrival(separation, -closing, approach) < early:
        bounce = _row_bounce(F, Q, rest_height, i, j, closing, reach)
        if bounce > 0.0:
            return bounce
    return -separation / h


@njit(cache=True)
def _force_targets(rows, count, h):
    """Each row's target for the force stage over a step of length ``h``: a gap may close by
    itself, no more; an overlap stops closing (``_push_out`` moves it out)."""
    for c in range(count):
        separation = rows[c, SEPARATION]
        rows[c, TARGET] = -separation / h if separation > 0.0 else 0.0


@njit(cache=True)
def _finish(S, members, local, now, end, lift, rows, pairs, count, h, speed):
    """Each body keeps the impact stage's velocity and spin ``now`` plus the push-out's
    ``lift`` and, over the step, the constant acceleration and angular acceleration that
    bring it to the force stage's velocity and spin at the step's end,
    ``(end - now - lift) / h``: the contact forces act over the step, not at its start, so a
    body held still has velocity and acceleration zero, a contact that holds does no work,
    and the push-out moves a body without leaving it a speed. Then the island's parts;
    bodies with no contact leave it (free acceleration again, no angular acceleration);
    every body touched. Returns the
    labels, the largest mean speed over ``sqrt(|a| reach)`` (a circle's spin counted only
    where it slips on a contact with friction that presses on it, beyond the solve's
    tolerance of ``speed``), and the deepest overlap of a point over the smaller reach of
    its pair."""
    F = S.F
    I = S.I
    labels = _parts(pairs, np.ones(count, dtype=np.bool_), count, members.shape[0])
    pushed = np.zeros(members.shape[0], dtype=np.bool_)
    # slipping at a contact with friction that presses on it (an impulse that changes a
    # speed by less than the solve's own tolerance is rounding, not a press)
    rubbed = np.zeros(members.shape[0], dtype=np.bool_)
    for c in range(count):
        if rows[c, LAMBDA_N] != 0.0 or rows[c, LAMBDA_T] != 0.0:
            pushed[pairs[c, 0]] = True
            if pairs[c, 1] >= 0:
                pushed[pairs[c, 1]] = True
        if rows[c, MU] > 0.0 and rows[c, LAMBDA_N] * rows[c, KN] > SOLVE_TOLERANCE * speed:
            ux, uy = _relative(end, pairs, rows, c)
            if abs(-ux * rows[c, NY] + uy * rows[c, NX]) > SOLVE_TOLERANCE * speed:
                rubbed[pairs[c, 0]] = True
                if pairs[c, 1] >= 0:
                    rubbed[pairs[c, 1]] = True
    fastest = 0.0
    for k in range(members.shape[0]):
        i = members[k]
        local[i] = -1
        lifted = lift[k, 0] != 0.0 or lift[k, 1] != 0.0 or lift[k, 2] != 0.0
        F[i, L.VX] = now[k, 0] + lift[k, 0]
        F[i, L.VY] = now[k, 1] + lift[k, 1]
        F[i, L.OMEGA] = now[k, 2] + lift[k, 2]
        if (pushed[k] or lifted) and labels[k] >= 0:
            F[i, L.AX] = (end[k, 0] - F[i, L.VX]) / h
            F[i, L.AY] = (end[k, 1] - F[i, L.VY]) / h
            F[i, L.ALPHA] = (end[k, 2] - F[i, L.OMEGA]) / h
        else:
            F[i, L.AX] = F[i, L.FREE_AX]
            F[i, L.AY] = F[i, L.FREE_AY]
            F[i, L.ALPHA] = 0.0
        reach = F[i, L.REACH]
        pull = math.hypot(F[i, L.FREE_AX], F[i, L.FREE_AY]) * reach
        speed = 0.5 * math.hypot(now[k, 0] + end[k, 0], now[k, 1] + end[k, 1])
        if I[i, L.KIND] != CIRCLE or rubbed[k]:
            # A circle's spin does not change its shape, and only friction feels it, where it
            # slips: a circle that slips nowhere (pressed by no friction, or rolling on
            # another circle turning with it) may spin on while its island sleeps.
            speed += 0.5 * abs(now[k, 2] + end[k, 2]) * reach
        if pull > 0.0:
            fastest = max(fastest, speed / math.sqrt(pull))
        elif speed > 0.0:
            fastest = math.inf
        if labels[k] < 0:
            I[i, L.ISLAND] = -1
        touch_one(S, i)
    deepest = 0.0
    for c in range(count):
        if rows[c, SEPARATION] < 0.0:
            reach = min(F[pairs[c, 2], L.REACH], F[pairs[c, 3], L.REACH])
            deepest = max(deepest, -rows[c, SEPARATION] / reach)
    return labels, fastest, deepest


@njit(cache=True)
def _impacts(F, members, now, rows, pairs, count, speed, down_x, down_y):
    """The impact stage: impulses on the velocities now (``now``, changed in place) so that
    no touching point closes (or it bounces, ``IMPACT``) and no point with a gap closes by
    more than it within the step; kinetic energy never rises (where restitution solved
    for several contacts together would raise it, ``_inelastic_where_gained``). The same
    solve as the force stage, on the ``IMPACT`` targets, from zero impulses, but its sweeps stop after
    ``IMPACT_ITERATIONS`` where the exact finish fails (more than ``IMPACT_LCP_LIMIT``
    unknowns, or an answer that fails the sweeps' test), and the approach they leave is the
    force stage's to stop (by the step's end: a point still closing sinks in mid-step).
    The rows' warm-start impulses are left as they were (their
    ``TARGET`` is the impact stage's scratch: the force stage sets it afterwards,
    ``_force_targets``). Returns the number of sweeps and each point's normal impulse."""
    struck = np.zeros(count)
    if count == 0:
        return 0, struck
    closing = False
    for c in range(count):
        ux, uy = _relative(now, pairs, rows, c)
        if ux * rows[c, NX] + uy * rows[c, NY] < rows[c, IMPACT]:
            closing = True
            break
    if not closing:
        return 0, struck
    before = now.copy()
    warm = rows[:count, LAMBDA_N:LAMBDA_T + 1].copy()
    rows[:count, TARGET] = rows[:count, IMPACT]
    rows[:count, LAMBDA_N] = 0.0
    rows[:count, LAMBDA_T] = 0.0
    sweeps = _solve(F, now, rows, pairs, count, speed, down_x, down_y, IMPACT_ITERATIONS, IMPACT_LCP_LIMIT)
    pressed = _pressed(rows, count)
    labels = _parts(pairs, pressed, count, members.shape[0])
    share = _blend(F, members, before, before, now, labels)  # the guard: towards the answer from before
    for c in range(count):
        struck[c] = rows[c, LAMBDA_N]
    if (share < 1.0).any():
        sweeps += _inelastic_where_gained(F, members, before, now, rows, pairs, count, speed, down_x, down_y,
                                          pressed, struck)
    rows[:count, LAMBDA_N:LAMBDA_T + 1] = warm
    return sweeps, struck


@njit(cache=True)
def _inelastic_where_gained(F, members, before, now, rows, pairs, count, speed, down_x, down_y, pressed, struck):
    """The impact stage's answer ``now`` (its normal impulses in ``struck``) raised the
    kinetic energy of some part of the island: restitution targets of several contacts
    solved together can (a body bouncing off one neighbour into another that was moving
    away). Solve the impacts again without restitution (every target at most zero: no
    energy gained) and, part by part, go from that answer towards the first only as far
    as the part's energy allows (``_blend``), so that every point still meets its inelastic
    target: scaling the whole answer back towards the velocities before, as a guard
    would, leaves points closing, and they sink in mid-step. Where even the inelastic
    answer gains (rounding), that part is scaled back towards the velocities before
    (``_blend`` from the velocities before). Changes ``now`` and ``struck``; returns the
    sweeps of the second solve."""
    plain = rows.copy()
    for c in range(count):
        plain[c, TARGET] = min(rows[c, IMPACT], 0.0)
        plain[c, LAMBDA_N] = 0.0
        plain[c, LAMBDA_T] = 0.0
    soft = before.copy()
    sweeps = _solve(F, soft, plain, pairs, count, speed, down_x, down_y, IMPACT_ITERATIONS, IMPACT_LCP_LIMIT)
    either = _pressed(plain, count)
    for c in range(count):
        either[c] = either[c] or pressed[c]
    labels = _parts(pairs, either, count, members.shape[0])
    share = _blend(F, members, before, soft, now, labels)
    fallback = _blend(F, members, before, before, soft, labels)
    for k in range(members.shape[0]):
        r = labels[k]
        if r < 0:
            continue
        for q in range(3):
            if share[r] >= 0.0:
                now[k, q] = soft[k, q] + share[r] * (now[k, q] - soft[k, q])
            else:
                now[k, q] = before[k, q] + fallback[r] * (soft[k, q] - before[k, q])
    for c in range(count):
        if not either[c]:
            continue
        r = labels[pairs[c, 0]]
        if share[r] >= 0.0:
            struck[c] = plain[c, LAMBDA_N] + share[r] * (struck[c] - plain[c, LAMBDA_N])
        else:
            struck[c] = fallback[r] * plain[c, LAMBDA_N]
    return sweeps


@njit(cache=True)
def _end_targets(rows, now, pairs, count):
    """Turn each row's target, a bound on the point's *mean* normal speed over the step (a
    gap may close by itself, an overlap is pushed out), into a bound on its speed at the
    step's *end*. The contact forces are constant over the step, so a point's normal speed
    is linear in time and its mean is the average of the speeds now and at the end:
    ``end >= 2 target - now``."""
    for c in range(count):
        ux, uy = _relative(now, pairs, rows, c)
        rows[c, TARGET] = 2.0 * rows[c, TARGET] - (ux * rows[c, NX] + uy * rows[c, NY])


@njit(cache=True)
def _until_contact(S, now, rows, pairs, count, h, early, shortest):
    """The step's length: ``h``, or less where a point with a gap (wider than ``TOUCHING``
    of its pair's reach) would close it sooner, with the velocities now and the accelerations
    the last step left (``_approach_acceleration``; the earliest root of
    ``s + u t + a t^2 / 2``), fast enough to bounce higher than the rest height. Stepping again when it closes lets the impact stage take
    that impact with its restitution; a step across it would let the gap close and stop
    there, an inelastic impact (which is right for a point that would not bounce, so such
    points leave the step alone). A point that touches now (``_touching``) is the impact
    stage's already, and so is one that closes within ``early[c]`` of the island's step
    (``BOUNCE_WINDOW``, or 0 for a row the step will not bounce): it bounces now if it closes fast enough now, else it arrives
    too slow to bounce but for what the window's acceleration adds, and its gap's bound
    stops it. So with the window a step is cut no shorter than it; never below
    ``shortest``, the island's floor (``step_island``)."""
    F = S.F
    Q = S.Q
    rest_height = S.P[L.REST_HEIGHT]
    window = SIMULTANEOUS * S.P[L.CONTACT_STEP]
    step = S.P[L.CONTACT_STEP]
    length = h
    for c in range(count):
        i = pairs[c, 2]
        j = pairs[c, 3]
        gap = rows[c, SEPARATION]
        reach = min(F[i, L.REACH], F[j, L.REACH])
        nx = rows[c, NX]
        ny = rows[c, NY]
        ux, uy = _relative_at(
            now, pairs, c, rows[c, PX] - F[i, L.X], rows[c, PY] - F[i, L.Y], rows[c, PX] - F[j, L.X], rows[c, PY] - F[j, L.Y]
        )
        u = ux * nx + uy * ny
        a = _approach_acceleration(F, pairs, c, nx, ny)
        if _touching(gap, -u, reach, window):
            continue  # the impact stage takes it now
        when = _arrival(gap, u, a)
        if when < early[c] * step:
            # it bounces now, from its gap, where it closes fast enough now; else it arrives
            # slower than a quarter step's acceleration gives, and its gap's bound stops it
            continue
        if when >= length:
            continue
        if _row_bounce(F, Q, rest_height, i, j, -(u + a * when), reach) > 0.0:
            length = when
    return max(length, shortest)


@njit(cache=True)
def _after_bounces(S, members, now, rows, pairs, count, h, speed, down_x, down_y, shortest):
    """The step's length once its bounces are taken: a bounce may send a body towards a gap
    that then closes within the step (a ball between two walls). Its impact comes at that
    instant, so that the impact stage takes it with its restitution too; across it, the
    gap's speculative bound would stop the body there, an inelastic impact. The bounces are
    tried on copies, without the gaps' bounds (which would hide the speed they give). The
    bounce window does not apply to a point whose speed they changed: this step's impact
    stage does not bounce it. Never below ``shortest`` (the island's floor)."""
    bounces = False
    for c in range(count):
        bounces = bounces or rows[c, IMPACT] > 0.0
    if not bounces:
        return h
    trial = rows[:count].copy()
    for c in range(count):
        if trial[c, IMPACT] < 0.0:
            trial[c, IMPACT] = -math.inf
    moved = now.copy()
    _impacts(S.F, members, moved, trial, pairs, count, speed, down_x, down_y)
    early = np.full(count, BOUNCE_WINDOW)
    for c in range(count):
        ux, uy = _relative(now, pairs, rows, c)
        wx, wy = _relative(moved, pairs, rows, c)
        if ux != wx or uy != wy:
            early[c] = 0.0
    return _until_contact(S, moved, trial, pairs, count, h, early, shortest)


@njit(cache=True)
def _turn_limit(S, members, now, h, shortest):
    """``h``, or less where a polygon turns faster than ``MAX_TURN`` a step (a circle's
    spin does not move its outline); at least ``shortest`` (the island's floor,
    ``step_island``), so that its steps per second are bounded whatever its spins."""
    I = S.I
    fastest = 0.0
    for k in range(members.shape[0]):
        if I[members[k], L.KIND] != CIRCLE:
            fastest = max(fastest, abs(now[k, 2]))
    if fastest * h <= MAX_TURN:
        return h
    return max(MAX_TURN / fastest, shortest)


@njit(cache=True)
def _within_margins(F, members, now, margin, h):
    """``h``, or less where a body moving at its velocities ``now`` (after the impacts) would
    travel within the step further than the manifold looked round it (its ``margin``, which
    ``_start`` found for the velocities before them, plus ``CONTACT_MARGIN`` of its reach, as
    in ``_collect``); at least ``SHORTEST_REACH_STEP`` of ``h`` (soundness: not the island's
    floor)."""
    length = h
    for k in range(members.shape[0]):
        i = members[k]
        ax = F[i, L.FREE_AX]
        ay = F[i, L.FREE_AY]
        reach = margin[k] + CONTACT_MARGIN * F[i, L.REACH]
        travel = math.hypot(now[k, 0] + 0.5 * h * ax, now[k, 1] + 0.5 * h * ay) + abs(now[k, 2]) * F[i, L.REACH]
        if h * travel + 0.125 * h * h * math.hypot(ax, ay) > reach:
            # over a step t <= h the travel is at most t (|v| + |w| reach + 5/8 h |a|)
            rate = math.hypot(now[k, 0], now[k, 1]) + abs(now[k, 2]) * F[i, L.REACH] + 0.625 * h * math.hypot(ax, ay)
            length = min(length, reach / rate)
    return max(length, SHORTEST_REACH_STEP * h)


@njit(cache=True, inline="always")
def _speed_scale(F, members, now, h, pull):
    """The speed the solves measure their tolerance against: what the strongest
    acceleration gives in one step, or without any, the fastest body's own speed."""
    speed = h * pull
    if not speed > 0.0:
        for k in range(members.shape[0]):
            speed = max(speed, math.hypot(now[k, 0], now[k, 1]) + abs(now[k, 2]) * F[members[k], L.REACH])
    return speed


@njit(cache=True)
def step_island(S, members, local, h, t, warm_keys, warm_impulses):
    """One step of the island made of ``members`` (body ids, all in one island) at time ``t``
    with step length ``h``; ``local`` is a scratch map of body id to position in ``members``
    (all -1, and left so). ``warm_keys`` (sorted) and ``warm_impulses`` are the last step's
    contacts and their impulses.

    Returns ``(keys, impulses, labels, fastest, deepest, sweeps, length, lift)``: this step's
    contacts (sorted) and their impulses (normal and friction of the force stage, for the
    next step's warm start, and the normal impulse of the impact stage), each member's part
    of the island (-1: it
    touches nothing and has left the island), the largest mean speed over ``sqrt(|a| reach)``
    and the deepest overlap over its pair's smaller reach (for sleep), how many sweeps the
    solve took, the step's length (``h``, or less where a gap closes sooner:
    ``_until_contact``; the next step is due after it), and each member's push-out lift
    (``_push_out``), which the step takes back over its length.
    """
    F = S.F
    now, margin = _start(S, members, local, h, t)
    rows, pairs, count = _collect(S, members, local, margin, t)
    pull = 0.0
    for k in range(members.shape[0]):
        pull = max(pull, math.hypot(F[members[k], L.FREE_AX], F[members[k], L.FREE_AY]))
    down_x = F[members[0], L.FREE_AX]
    down_y = F[members[0], L.FREE_AY]
    # The island's floor: no bounce or spin cuts its step shorter, so that a cut step (which
    # solves all of it) comes at most about ROW_BUDGET rows per h, whatever its bodies do.
    shortest = min(SHORTEST_STEP, (count + 1) / ROW_BUDGET) * h
    natural = _turn_limit(S, members, now, h, shortest)
    h = min(_until_contact(S, now, rows, pairs, count, h, np.full(count, BOUNCE_WINDOW), shortest), natural)
    keys = _prepare(S, rows, pairs, count, h, warm_keys, warm_impulses)
    speed = _speed_scale(F, members, now, h, pull)
    shorter = _after_bounces(S, members, now, rows, pairs, count, h, speed, down_x, down_y, min(shortest, h))
    if shorter < h:
        h = shorter
        keys = _prepare(S, rows, pairs, count, h, warm_keys, warm_impulses)
        speed = _speed_scale(F, members, now, h, pull)
    sweeps, struck = _impacts(F, members, now, rows, pairs, count, speed, down_x, down_y)
    # The impacts may have set a polygon turning faster than the step was cut for, or sent a
    # body further than the manifold looked (a body landing on another drives it towards a
    # floor the step did not collect): the step then ends first.
    turned = _turn_limit(S, members, now, h, min(shortest, h))
    if turned < h:
        natural = min(natural, turned)
    shorter = _within_margins(F, members, now, margin, min(h, turned))
    if shorter < h:
        h = shorter
        speed = _speed_scale(F, members, now, h, pull)
    _midstep_rows(S, now, rows, pairs, count, h)
    _force_targets(rows, count, h)
    end = np.empty_like(now)
    for k in range(members.shape[0]):
        i = members[k]
        end[k, 0] = now[k, 0] + h * F[i, L.FREE_AX]
        end[k, 1] = now[k, 1] + h * F[i, L.FREE_AY]
        end[k, 2] = now[k, 2]
    _end_targets(rows, now, pairs, count)
    sweeps += _solve(F, end, rows, pairs, count, speed, down_x, down_y, ISLAND_ITERATIONS, LCP_LIMIT)
    _no_gain(F, members, now, end, rows, pairs, count, h)
    ends = np.empty((count, 5))
    _solved_arcs(S, now, end, rows, pairs, count, h, ends)
    lift, pushes = _push_out(F, now, end, rows, pairs, count, h, natural, down_x, down_y, ends)
    sweeps += pushes
    if _lift_paid(F, members, now, end, lift, rows, pairs, count, h):
        # The paid motion opens its points a little less: its arcs and the push-out again.
        _solved_arcs(S, now, end, rows, pairs, count, h, ends)
        lift, pushes = _push_out(F, now, end, rows, pairs, count, h, natural, down_x, down_y, ends)
        sweeps += pushes
    labels, fastest, deepest = _finish(S, members, local, now, end, lift, rows, pairs, count, h, speed)
    S.stats[L.S_ISLAND_STEPS] += 1
    order = np.argsort(keys)
    impulses = np.empty((count, 3))
    for c in range(count):
        impulses[c, 0] = rows[order[c], LAMBDA_N]
        impulses[c, 1] = rows[order[c], LAMBDA_T]
        impulses[c, 2] = struck[order[c]]
    return keys[order], impulses, labels, fastest, deepest, sweeps, h, lift
