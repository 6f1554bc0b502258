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
  over the step: a velocity change at its start taken back by an equal and opposite one
  spread over it, so the velocities at the step's end are the force stage's.

Each stage is a complementarity problem (the push-out without friction), solved by
sequential impulses (projected Gauss-Seidel) and, where a few sweeps do not converge,
exactly: on the sweeps' active set (one linear solve, and a few more where principal
pivoting moves a wrong set), else by Lemke's method (``pge.numerics.lcp``) on Stewart and
Trinkle's formulation.

Stages: ``_start`` (bodies to ``t``, velocities now, travel margins), ``_collect`` (the
manifold), ``_until_contact`` (the step's length: shorter where a bouncing impact is due),
``_prepare`` (lever arms, effective masses, targets, last step's impulses),
``_impacts``, ``_end_targets`` and ``_solve`` (the forces), ``_solved_arcs`` (what a turning
pair's straight lines miss on the solved motion), ``_push_out``, ``_finish``
(accelerations from the forces and the push-out, the island's parts and the bodies that left
it, the touch).
"""

from __future__ import annotations

import math

import numpy as np

from pge._jit_cache import njit
from pge.contact.manifold import (
    KEY,
    NCOLUMNS,
    NX,
    NY,
    PX,
    PY,
    SEPARATION,
    circle_circle_points,
    circle_polygon_points,
    polygon_polygon_points,
)
from pge.core import layout as L
from pge.core.borrow import borrowed_array
from pge.core.response import combine
from pge.core.engine import touch_one
from pge.core.grid import gather
from pge.core.motion import advance, orient
from pge.numerics.lcp import lemke
from pge.core.tuning import (
    BOUNCE_WINDOW,
    CONTACT_MARGIN,
    ENERGY_ROUNDING,
    EXACT_AFTER,
    FACE_DIP,
    FACE_HYSTERESIS,
    IMPACT_ITERATIONS,
    IMPACT_LCP_LIMIT,
    ISLAND_ITERATIONS,
    LCP_LIMIT,
    MAX_TURN,
    PARALLEL,
    PUSH_RATE,
    PUSH_SLOP,
    ROW_BUDGET,
    SHORTEST_REACH_STEP,
    SET_TRIES,
    SHORTEST_STEP,
    SIMULTANEOUS,
    SOLVE_TOLERANCE,
    STEP_INSTANTS,
    FEATURE_INSTANTS,
    TOUCHING,
)

CIRCLE = 0
# columns of the solver's contact rows, after the manifold's
RAX, RAY, RBX, RBY, KN, KT, TARGET, LAMBDA_N, LAMBDA_T, MU, IMPACT = range(NCOLUMNS, NCOLUMNS + 11)
# ... each row's two bodies' inverse mass and inertia (the second's unused where it is fixed)
MA, IA, MB, IB = range(NCOLUMNS + 11, NCOLUMNS + 15)
# ... and on a pair's first row, what its sweeps use again and again: the lever arms of its
# friction (the midpoint of its two points, or its one point), the effective mass along the
# tangent there, and its two points' normal coupling ``K12`` and ``DET = K11 K22 - K12^2``
FAX, FAY, FBX, FBY, KF, K12, DET = range(NCOLUMNS + 15, NCOLUMNS + 22)
# ... and what a turning body's arc adds to a point's separation at the step's end beyond the
# straight-line motion of its contact point where it is at mid-step (``_midstep_rows``)
ARC = NCOLUMNS + 22
# ... and its point's normal speed now where the contact is now, before a turning pair's rows
# move to mid-step (there a turning body's point may close where the contact does not)
APPROACH = NCOLUMNS + 23
# ... and the most a push-out's lift may close its point (a speed, at most 0; -inf where the
# straight line is the motion) so that its gap on the step's solved motion stays above its
# floor at the step's instants (``_solved_arcs``; the straight line's own: ``_lift_floor``)
CLOSABLE = NCOLUMNS + 24
NSOLVE = NCOLUMNS + 25
# what an active set gave (``_active_set``)
SET_SOLVED, SET_MOVED, SET_WRONG = range(3)
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
def _points_at(F, I, OL, i, xi, yi, si, j, xj, yj, sj, margin, rows, count):
    """Append the manifold of bodies ``i`` at ``(xi, yi)`` and ``j`` at ``(xj, yj)`` (normal
    from j to i), their outlines (polygons) the rows of ``OL`` from ``si`` and ``sj``."""
    if I[i, L.KIND] == CIRCLE:
        if I[j, L.KIND] == CIRCLE:
            return circle_circle_points(xi, yi, F[i, L.RADIUS], xj, yj, F[j, L.RADIUS], margin, rows, count)
        return circle_polygon_points(xi, yi, F[i, L.RADIUS], xj, yj, OL, sj, I[j, L.OUTLINE_N], False, margin, rows,
                                     count)
    if I[j, L.KIND] == CIRCLE:
        return circle_polygon_points(xj, yj, F[j, L.RADIUS], xi, yi, OL, si, I[i, L.OUTLINE_N], True, margin, rows,
                                     count)
    scale = F[i, L.REACH] + F[j, L.REACH]
    return polygon_polygon_points(xi, yi, OL, si, I[i, L.OUTLINE_N], xj, yj, sj, I[j, L.OUTLINE_N], margin,
                                  FACE_HYSTERESIS * scale, FACE_DIP * scale,
                                  rows, count)


@njit(cache=True)
def _turned(F, I, OL, OB, i, spin, h, out, at):
    """Polygon ``i``'s outline rows turned on by ``spin h`` from its angle now, written into
    ``out`` from row ``at``; returns the row after them."""
    n = I[i, L.OUTLINE_N]
    start = I[i, L.OUTLINE_START]
    angle = F[i, L.ORIENT] + spin * h
    c = math.cos(angle)
    s = math.sin(angle)
    for k in range(n):
        out[at + k, :] = OL[start + k, :]
        x = OB[start + k, 0]
        y = OB[start + k, 1]
        nx = OB[start + k, 2]
        ny = OB[start + k, 3]
        out[at + k, 0] = c * x - s * y
        out[at + k, 1] = s * x + c * y
        out[at + k, 2] = c * nx - s * ny
        out[at + k, 3] = s * nx + c * ny
    return at + n


@njit(cache=True)
def _moved(F, I, OL, OB, now, pairs, c, h, outline, out):
    """The manifold of row ``c``'s pair found again with the bodies' outlines moved on for
    ``h`` at their velocities ``now`` and turned by their spins, into ``out``; returns the
    number of points and the outline scratch (grown if it had to be)."""
    i = pairs[c, 2]
    j = pairs[c, 3]
    ka = pairs[c, 0]
    kb = pairs[c, 1]
    need = I[i, L.OUTLINE_N] + I[j, L.OUTLINE_N]
    if need > outline.shape[0]:
        outline = np.empty((need, OL.shape[1]))
    at = 0
    if I[i, L.KIND] != CIRCLE:
        at = _turned(F, I, OL, OB, i, now[ka, 2], h, outline, 0)
    if I[j, L.KIND] != CIRCLE:
        _turned(F, I, OL, OB, j, now[kb, 2] if kb >= 0 else 0.0, h, outline, at)
    xj = F[j, L.X]
    yj = F[j, L.Y]
    if kb >= 0:
        xj += h * now[kb, 0]
        yj += h * now[kb, 1]
    found = _points_at(F, I, outline, i, F[i, L.X] + h * now[ka, 0], F[i, L.Y] + h * now[ka, 1], 0, j, xj, yj, at,
                       math.inf, out, 0)
    return found, outline


@njit(cache=True, inline="always")
def _match(out, found, key):
    """The index of the point with ``key`` among the first ``found`` of ``out``, or -1."""
    for q in range(found):
        if out[q, KEY] == key:
            return q
    return -1


@njit(cache=True)
def _to_midstep(F, now, rows, pairs, r, point, h):
    """Move row ``r``'s contact point and lever arms (not its normal) to where the contact
    is at mid-step (``point``, a row of the manifold moved on by ``h / 2``), with its
    bodies' reference points moved on as far; its effective masses follow."""
    ka = pairs[r, 0]
    kb = pairs[r, 1]
    i = pairs[r, 2]
    j = pairs[r, 3]
    px = point[PX]
    py = point[PY]
    rax = px - (F[i, L.X] + 0.5 * h * now[ka, 0])
    ray = py - (F[i, L.Y] + 0.5 * h * now[ka, 1])
    rbx = px - F[j, L.X]
    rby = py - F[j, L.Y]
    if kb >= 0:
        rbx -= 0.5 * h * now[kb, 0]
        rby -= 0.5 * h * now[kb, 1]
    rows[r, PX] = px
    rows[r, PY] = py
    _lever_arms(rows, r, rax, ray, rbx, rby)


@njit(cache=True, inline="always")
def _lever_arms(rows, r, rax, ray, rbx, rby):
    """Set row ``r``'s lever arms and, from them, its normal's and tangent's effective masses
    (its normal and its bodies' inverse masses and inertias already set)."""
    nx = rows[r, NX]
    ny = rows[r, NY]
    rows[r, RAX] = rax
    rows[r, RAY] = ray
    rows[r, RBX] = rbx
    rows[r, RBY] = rby
    ran = rax * ny - ray * nx
    rbn = rbx * ny - rby * nx
    rat = rax * nx + ray * ny
    rbt = rbx * nx + rby * ny
    rows[r, KN] = rows[r, MA] + rows[r, MB] + rows[r, IA] * ran * ran + rows[r, IB] * rbn * rbn
    rows[r, KT] = rows[r, MA] + rows[r, MB] + rows[r, IA] * rat * rat + rows[r, IB] * rbt * rbt


@njit(cache=True, inline="always")
def _pair_end(pairs, count, c):
    """The row after the last of the pair whose first row is ``c`` (a pair's rows are
    adjacent)."""
    d = c + 1
    while d < count and pairs[d, 2] == pairs[c, 2] and pairs[d, 3] == pairs[c, 3]:
        d += 1
    return d


@njit(cache=True, inline="always")
def _turning_pair(I, velocities, pairs, c):
    """Whether a polygon of row ``c``'s pair turns at the spins in ``velocities`` (a
    circle's spin does not move its outline)."""
    wi = velocities[pairs[c, 0], 2]
    wj = velocities[pairs[c, 1], 2] if pairs[c, 1] >= 0 else 0.0
    return (I[pairs[c, 2], L.KIND] != CIRCLE and wi != 0.0) or (I[pairs[c, 3], L.KIND] != CIRCLE and wj != 0.0)


@njit(cache=True)
def _midstep_rows(S, now, rows, pairs, count, h):
    """Where a polygon of a pair turns, the step's rows of that pair act where the contact
    is at *mid-step*, and each row's ``ARC`` is what its straight line still misses.

    The step's conditions are linear in the points' speeds: a row's separation at the end is
    its separation now plus ``h`` times the mean normal speed of its contact point, whose
    lever arms and normal are fixed over the step. A turning polygon's corners move on arcs
    and its faces turn under a neighbour, and a rolling contact's point moves along the face:
    taken where the contact is now, the straight line misses the end separation by about
    ``(spin h)^2 / 2`` of a reach, and the step's normal impulse has the lever arm of the
    start, where the true force acts on average half the contact's travel further on. Taken
    where the contact is at mid-step (the pair's manifold found again with the outlines
    moved on by ``h / 2`` at the velocities now and turned by the spins: ``_to_midstep``),
    the straight line is the midpoint rule, right to second order, and the impulse's work is
    the mean normal speed there, zero for a holding contact: a body rolling or rocking on a
    support gains no energy from the step.

    ``ARC`` is the rest: the second-order part, in ``h``, of the separation found again with
    the outlines moved on by ``h`` and by ``h / 2``, less the start's straight line
    (``2 (k(h) - 2 k(h / 2))``), less what the mid-step point's straight line adds to the
    start's, where it closes the gap (third order where the midpoint rule holds); the
    push-out takes it (``_push_out``). Not its first-order part: at a point clipped to a
    face's end (not a point of either body) that is the point sliding along a face tilted
    against the other at the tangential speed of now, which the step's friction changes. Not where it opens the gap:
    the gap over the step would then dip between its ends. Zero, and the rows left where the
    contact is now, for a pair where no polygon turns (the straight lines are then exact) and
    for a point whose features change within the step (its key is not in the moved manifold)."""
    F = S.F
    I = S.I
    OL = S.OL
    OB = S.OB
    outline = np.empty((16, OL.shape[1]))
    half = np.empty((4, NCOLUMNS))
    full = np.empty((4, NCOLUMNS))
    moved = False
    c = 0
    while c < count:
        d = _pair_end(pairs, count, c)
        for r in range(c, d):
            rows[r, ARC] = 0.0
            ux, uy = _relative(now, pairs, rows, r)
            rows[r, APPROACH] = ux * rows[r, NX] + uy * rows[r, NY]
        if _turning_pair(I, now, pairs, c):
            at_half, outline = _moved(F, I, OL, OB, now, pairs, c, 0.5 * h, outline, half)
            at_full, outline = _moved(F, I, OL, OB, now, pairs, c, h, outline, full)
            for r in range(c, d):
                q = _match(half, at_half, rows[r, KEY])
                e = _match(full, at_full, rows[r, KEY])
                if q < 0 or e < 0:
                    continue
                start = rows[r, APPROACH]
                k_full = full[e, SEPARATION] - rows[r, SEPARATION] - h * start
                k_half = half[q, SEPARATION] - rows[r, SEPARATION] - 0.5 * h * start
                _to_midstep(F, now, rows, pairs, r, half[q], h)
                moved = True
                ux, uy = _relative(now, pairs, rows, r)
                midstep = ux * rows[r, NX] + uy * rows[r, NY]
                # the second-order part of the end separation, less what the mid-step
                # point's straight line already takes
                arc = 2.0 * (k_full - 2.0 * k_half) - h * (midstep - start)
                if arc < 0.0:
                    rows[r, ARC] = arc
        c = d
    if moved:
        _pair_constants(rows, pairs, count)


@njit(cache=True)
def _deepest(out, found, key):
    """The point with ``key`` among the first ``found`` of ``out``; where there is none (the
    features changed), the deepest of them; -1 if there are none."""
    e = _match(out, found, key)
    if e < 0:
        for q in range(found):
            if e < 0 or out[q, SEPARATION] < out[e, SEPARATION]:
                e = q
    return e


@njit(cache=True, inline="always")
def _instant_ask(rows, r, out, found, s, h, u0, line, floor):
    """The end displacement that the gap of row ``r`` at the instant ``s`` into a step of
    length ``h`` (the pair's manifold moved there: the first ``found`` of ``out``) asks of
    the push-out's lift (``_solved_arcs``): the point of the same features, or where they
    changed the pair's deepest point, may be no deeper than ``floor`` (the start's overlap)
    nor than the row's straight line goes there (``line``: its gap at the end; it leaves at
    the speed the contact closes now, ``u0`` or ``APPROACH``)."""
    q = _deepest(out, found, rows[r, KEY])
    if q < 0:
        return 0.0
    leaving = max(u0, rows[r, APPROACH])
    straight = rows[r, SEPARATION] + s * leaving + (line - rows[r, SEPARATION] - h * leaving) * (s / h) ** 2
    lowest = min(floor, straight)
    if out[q, SEPARATION] < lowest:
        return (lowest - out[q, SEPARATION]) * h / (2.0 * s - s * s / h)
    return 0.0


@njit(cache=True, inline="always")
def _closable_at(rows, r, out, found, s, h, floor):
    """The least lift speed (negative: a closing one) that keeps the gap of row ``r`` at the
    instant ``s`` into a step of length ``h`` (the pair's manifold moved there on the
    solved motion: the first ``found`` of ``out``; the point of the same features, or where
    they changed the pair's deepest point) above ``floor``: a lift ``l`` has moved the point
    by ``l h (f - f^2 / 2)`` at ``f = s / h``. -inf where the pair has no point there."""
    q = _deepest(out, found, rows[r, KEY])
    if q < 0:
        return -math.inf
    f = s / h
    return (floor - out[q, SEPARATION]) / (h * (f - 0.5 * f * f))


@njit(cache=True)
def _solved_arcs(S, now, end, rows, pairs, count, h):
    """Each point's ``ARC`` found again on the step's solved motion, so that the push-out
    holds its gap at the step's end and inside it.

    At the end: a turning pair's manifold found with the outlines moved on by ``h`` at the
    mean of the velocities and spins ``now`` and at the step's ``end`` (the closed-form pose
    the contact forces bring them to), less the straight line of the point's mean normal
    speed. ``_midstep_rows`` estimates the same at the velocities of now, before the forces
    are known; a body the forces set turning faster or slower (a polygon tipping over a
    corner at 140 rad/s^2) left a few percent of its arc to every step's end (scene 113:
    2.5e-8 at each step of a polygon sliding at 0.56 m/s over a box's corner while turning
    at 1.3 rad/s). A row whose features are not in the pair's manifold at the end takes the
    pair's deepest point there (which point it became is not known; no row may end above
    the deepest); where the arc opens the gap, it is zero (as in ``_midstep_rows``).

    Inside: at the instants ``STEP_INSTANTS`` of the step, a turning pair's gaps on the same
    motion (its manifold found again at that pose) must be no deeper than the point's
    overlap at the start, nor than its straight line goes there (a speculative gap the force
    stage closes only by the step's end is the step's to close: lifting it would lift a box
    landing on another against gravity, with no work to pay for it), that line leaving at
    the speed the contact closes now where it is now (``APPROACH``): a row moved to
    mid-step may close faster where the contact does not close at all.
    The push-out's lift, a speed taken back over the step, has moved a point by
    ``lift (s - s^2 / 2h)`` at ``s``, three quarters of its end displacement at mid-step, so
    a deficit ``D`` at ``s`` asks ``D h / (2 s - s^2 / h)`` of it at the end, and the arc
    asks for the largest of these. A gap that closes and opens again within the step (a
    circle sliding at 0.7 m/s on a polygon that turns under it at 130 rad/s^2, corpus scene
    15: 7.4e-6 at mid-step) is held at these instants; between them it may dip by what its
    curve does there."""
    F = S.F
    I = S.I
    OL = S.OL
    OB = S.OB
    for r in range(count):
        rows[r, CLOSABLE] = -math.inf
    mean = 0.5 * (now + end)
    # the poses at the instants inside, under constant acceleration: moved on for s at the
    # speed of now plus half of what the step adds by then
    moving = np.empty((len(STEP_INSTANTS),) + now.shape)
    for k in range(len(STEP_INSTANTS)):
        moving[k] = now + (end - now) * (0.5 * (STEP_INSTANTS[k] * h) / h)
    outline = np.empty((16, OL.shape[1]))
    full = np.empty((4, NCOLUMNS))
    inside = np.empty((len(STEP_INSTANTS), 4, NCOLUMNS))
    found = np.zeros(len(STEP_INSTANTS), dtype=np.int64)
    fine = np.empty((FEATURE_INSTANTS - 1, 4, NCOLUMNS))
    fine_found = np.zeros(FEATURE_INSTANTS - 1, dtype=np.int64)
    c = 0
    while c < count:
        d = _pair_end(pairs, count, c)
        if not _turning_pair(I, mean, pairs, c):
            c = d
            continue  # the straight lines are the motion
        at_full, outline = _moved(F, I, OL, OB, mean, pairs, c, h, outline, full)
        changed = False  # a point of the pair changes features within the step
        for k in range(len(STEP_INSTANTS)):
            found[k], outline = _moved(F, I, OL, OB, moving[k], pairs, c, STEP_INSTANTS[k] * h, outline, inside[k])
            for r in range(c, d):
                changed = changed or _match(inside[k], found[k], rows[r, KEY]) < 0
        for r in range(c, d):
            changed = changed or _match(full, at_full, rows[r, KEY]) < 0
        if changed:
            for k in range(FEATURE_INSTANTS - 1):
                f = (k + 1.0) / FEATURE_INSTANTS
                fine_found[k], outline = _moved(F, I, OL, OB, now + (end - now) * (0.5 * f), pairs, c, f * h,
                                                outline, fine[k])
        for r in range(c, d):
            ux, uy = _relative(now, pairs, rows, r)
            wx, wy = _relative(end, pairs, rows, r)
            u0 = ux * rows[r, NX] + uy * rows[r, NY]
            u1 = wx * rows[r, NX] + wy * rows[r, NY]
            line = rows[r, SEPARATION] + 0.5 * h * (u0 + u1)
            e = _deepest(full, at_full, rows[r, KEY])
            if e >= 0:
                rows[r, ARC] = min(full[e, SEPARATION] - line, 0.0)
            floor = min(rows[r, SEPARATION], 0.0)
            asked = 0.0  # the end displacement the instants inside ask of the lift
            closable = -math.inf
            for k in range(len(STEP_INSTANTS)):
                s = STEP_INSTANTS[k] * h
                asked = max(asked, _instant_ask(rows, r, inside[k], found[k], s, h, u0, line, floor))
                closable = max(closable, _closable_at(rows, r, inside[k], found[k], s, h, floor))
            if changed:
                for k in range(FEATURE_INSTANTS - 1):
                    s = (k + 1.0) / FEATURE_INSTANTS * h
                    asked = max(asked, _instant_ask(rows, r, fine[k], fine_found[k], s, h, u0, line, floor))
                    closable = max(closable, _closable_at(rows, r, fine[k], fine_found[k], s, h, floor))
            rows[r, CLOSABLE] = min(closable, 0.0)
            if asked > 0.0:
                rows[r, ARC] = min(rows[r, ARC], -asked - line)
        c = d


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
def _pair_constants(rows, pairs, count):
    """Fill each pair's first row with its friction's lever arms and effective mass and its
    two points' normal coupling (``FAX`` to ``DET``), from the rows' arms and masses."""
    c = 0
    while c < count:
        pair = _in_block(pairs, count, c)
        if pair:
            rax, ray, rbx, rby = _midpoint(rows, c)
        else:
            rax, ray, rbx, rby = rows[c, RAX], rows[c, RAY], rows[c, RBX], rows[c, RBY]
        nx = rows[c, NX]
        ny = rows[c, NY]
        tx = -ny
        ty = nx
        rat = rax * ty - ray * tx
        rbt = rbx * ty - rby * tx
        rows[c, FAX] = rax
        rows[c, FAY] = ray
        rows[c, FBX] = rbx
        rows[c, FBY] = rby
        rows[c, KF] = rows[c, MA] + rows[c, MB] + rows[c, IA] * rat * rat + rows[c, IB] * rbt * rbt
        if pair:
            d = c + 1
            k12 = rows[c, MA] + rows[c, MB]
            k12 += rows[c, IA] * (rows[c, RAX] * ny - rows[c, RAY] * nx) * (rows[d, RAX] * ny - rows[d, RAY] * nx)
            k12 += rows[c, IB] * (rows[c, RBX] * ny - rows[c, RBY] * nx) * (rows[d, RBX] * ny - rows[d, RBY] * nx)
            rows[c, K12] = k12
            rows[c, DET] = rows[c, KN] * rows[d, KN] - k12 * k12
            c += 2
        else:
            c += 1


@njit(cache=True)
def _force_targets(rows, count, h):
    """Each row's target for the force stage over a step of length ``h``: a gap may close by
    itself, no more; an overlap stops closing (``_push_out`` moves it out)."""
    for c in range(count):
        separation = rows[c, SEPARATION]
        rows[c, TARGET] = -separation / h if separation > 0.0 else 0.0


@njit(cache=True, inline="always")
def _push_at(rows, vel, pairs, c, jx, jy, rax, ray, rbx, rby):
    """Apply the impulse ``(jx, jy)`` at lever arms ``ra`` (first body) and ``rb`` (second,
    which takes it reversed; a fixed body does not move) to the velocities ``vel`` of row
    ``c``'s two bodies."""
    ka = pairs[c, 0]
    vel[ka, 0] += jx * rows[c, MA]
    vel[ka, 1] += jy * rows[c, MA]
    vel[ka, 2] += (rax * jy - ray * jx) * rows[c, IA]
    kb = pairs[c, 1]
    if kb >= 0:
        vel[kb, 0] -= jx * rows[c, MB]
        vel[kb, 1] -= jy * rows[c, MB]
        vel[kb, 2] -= (rbx * jy - rby * jx) * rows[c, IB]


@njit(cache=True, inline="always")
def _push(rows, vel, pairs, c, jn, jt):
    """Apply impulse ``jn`` along the normal and ``jt`` along the tangent at row ``c``'s point."""
    nx = rows[c, NX]
    ny = rows[c, NY]
    _push_at(rows, vel, pairs, c, jn * nx - jt * ny, jn * ny + jt * nx, rows[c, RAX], rows[c, RAY], rows[c, RBX],
             rows[c, RBY])


@njit(cache=True, inline="always")
def _relative_at(vel, pairs, c, rax, ray, rbx, rby):
    """Relative velocity in ``vel`` (first body minus second) of row ``c``'s bodies at lever arms
    ``ra`` and ``rb``."""
    ka = pairs[c, 0]
    kb = pairs[c, 1]
    ux = vel[ka, 0] - vel[ka, 2] * ray
    uy = vel[ka, 1] + vel[ka, 2] * rax
    if kb >= 0:
        ux -= vel[kb, 0] - vel[kb, 2] * rby
        uy -= vel[kb, 1] + vel[kb, 2] * rbx
    return ux, uy


@njit(cache=True, inline="always")
def _relative(vel, pairs, rows, c):
    """Relative velocity in ``vel`` of row ``c``'s contact point (first body minus second)."""
    return _relative_at(vel, pairs, c, rows[c, RAX], rows[c, RAY], rows[c, RBX], rows[c, RBY])


@njit(cache=True, inline="always")
def _midpoint(rows, c):
    """Lever arms of the midpoint of rows ``c`` and ``c + 1`` (a pair's two points)."""
    d = c + 1
    return (
        0.5 * (rows[c, RAX] + rows[d, RAX]),
        0.5 * (rows[c, RAY] + rows[d, RAY]),
        0.5 * (rows[c, RBX] + rows[d, RBX]),
        0.5 * (rows[c, RBY] + rows[d, RBY]),
    )


@njit(cache=True, inline="always")
def _friction(vel, rows, pairs, c):
    """Row ``c``'s friction impulse, within the cone of its normal impulse; returns its change."""
    if not (rows[c, KT] > 0.0 and rows[c, MU] > 0.0):
        return 0.0
    ux, uy = _relative(vel, pairs, rows, c)
    ut = -ux * rows[c, NY] + uy * rows[c, NX]
    limit = rows[c, MU] * rows[c, LAMBDA_N]
    old = rows[c, LAMBDA_T]
    new = min(max(old - ut / rows[c, KT], -limit), limit)
    rows[c, LAMBDA_T] = new
    _push(rows, vel, pairs, c, 0.0, new - old)
    return abs(new - old)


@njit(cache=True, inline="always")
def _normal(vel, rows, pairs, c):
    """Row ``c``'s normal impulse alone (never pulling); returns its change."""
    if not rows[c, KN] > 0.0:
        return 0.0
    ux, uy = _relative(vel, pairs, rows, c)
    un = ux * rows[c, NX] + uy * rows[c, NY]
    old = rows[c, LAMBDA_N]
    new = max(old + (rows[c, TARGET] - un) / rows[c, KN], 0.0)
    rows[c, LAMBDA_N] = new
    _push(rows, vel, pairs, c, new - old, 0.0)
    return abs(new - old)


@njit(cache=True, inline="always")
def _friction_pair(vel, rows, pairs, c):
    """The friction of a pair's two points (rows ``c`` and ``c + 1``) as one impulse at their
    midpoint, within the cone of their summed normal impulses: the two points' tangential
    constraints are one (the pair slides or sticks as a whole), and solving them apart makes
    the sweeps fight over how to share it. Kept in row ``c``; returns its change."""
    d = c + 1
    tx = -rows[c, NY]
    ty = rows[c, NX]
    mu = rows[c, MU]
    kt = rows[c, KF]
    if not (kt > 0.0 and mu > 0.0):
        return 0.0
    rax, ray, rbx, rby = rows[c, FAX], rows[c, FAY], rows[c, FBX], rows[c, FBY]
    ux, uy = _relative_at(vel, pairs, c, rax, ray, rbx, rby)
    ut = ux * tx + uy * ty
    limit = mu * (rows[c, LAMBDA_N] + rows[d, LAMBDA_N])
    old = rows[c, LAMBDA_T] + rows[d, LAMBDA_T]
    new = min(max(old - ut / kt, -limit), limit)
    rows[c, LAMBDA_T] = new
    rows[d, LAMBDA_T] = 0.0
    _push_at(rows, vel, pairs, c, (new - old) * tx, (new - old) * ty, rax, ray, rbx, rby)
    return abs(new - old)


@njit(cache=True, inline="always")
def _into_cone(vel, rows, pairs, c, size):
    """Bring the friction of the pair at row ``c`` (``size`` points) back into the cone of
    its normal impulses, which the normal update that follows the friction update may have
    shrunk (a warm start that pressed harder than the step needs: gravity switched off);
    left outside, a sweep that changes nothing more would end with friction acting where
    nothing presses. Returns its change."""
    mu = rows[c, MU]
    if not mu > 0.0:
        return 0.0
    pressed = rows[c, LAMBDA_N] + (rows[c + 1, LAMBDA_N] if size == 2 else 0.0)
    limit = mu * pressed
    old = rows[c, LAMBDA_T]
    if abs(old) <= limit:
        return 0.0
    new = limit if old > 0.0 else -limit
    rows[c, LAMBDA_T] = new
    tx = -rows[c, NY]
    ty = rows[c, NX]
    if size == 2:
        _push_at(rows, vel, pairs, c, (new - old) * tx, (new - old) * ty, rows[c, FAX], rows[c, FAY], rows[c, FBX],
                 rows[c, FBY])
    else:
        _push(rows, vel, pairs, c, 0.0, new - old)
    return abs(new - old)


@njit(cache=True, inline="always")
def _normal_pair(vel, rows, pairs, c):
    """The normal impulses of rows ``c`` and ``c + 1`` (two points of one pair, sharing a
    normal) solved together: the 2x2 complementarity problem ``u = K x + b >= target``,
    ``x >= 0``, ``x (u - target) = 0``, by trying its four cases (both pushing, one, none).
    Falls back to the rows one at a time when ``K`` is too ill-conditioned or no case fits
    (rounding). Returns the largest change."""
    d = c + 1
    nx = rows[c, NX]
    ny = rows[c, NY]
    k11 = rows[c, KN]
    k22 = rows[d, KN]
    k12 = rows[c, K12]
    det = rows[c, DET]
    if not (k11 > 0.0 and k22 > 0.0 and det > 1e-6 * k11 * k22):
        return max(_normal(vel, rows, pairs, c), _normal(vel, rows, pairs, d))
    ux, uy = _relative(vel, pairs, rows, c)
    u1 = ux * nx + uy * ny
    ux, uy = _relative(vel, pairs, rows, d)
    u2 = ux * nx + uy * ny
    a1 = rows[c, LAMBDA_N]
    a2 = rows[d, LAMBDA_N]
    # u - target as a function of the new impulses x: K x + b
    b1 = u1 - rows[c, TARGET] - (k11 * a1 + k12 * a2)
    b2 = u2 - rows[d, TARGET] - (k12 * a1 + k22 * a2)
    x1 = (-k22 * b1 + k12 * b2) / det
    x2 = (k12 * b1 - k11 * b2) / det
    if not (x1 >= 0.0 and x2 >= 0.0):
        x1 = -b1 / k11
        x2 = 0.0
        if not (x1 >= 0.0 and k12 * x1 + b2 >= 0.0):
            x1 = 0.0
            x2 = -b2 / k22
            if not (x2 >= 0.0 and k12 * x2 + b1 >= 0.0):
                x1 = 0.0
                x2 = 0.0
                if not (b1 >= 0.0 and b2 >= 0.0):
                    return max(_normal(vel, rows, pairs, c), _normal(vel, rows, pairs, d))
    rows[c, LAMBDA_N] = x1
    rows[d, LAMBDA_N] = x2
    _push(rows, vel, pairs, c, x1 - a1, 0.0)
    _push(rows, vel, pairs, d, x2 - a2, 0.0)
    return max(abs(x1 - a1), abs(x2 - a2))


@njit(cache=True)
def _solve(F, vel, rows, pairs, count, speed, down_x, down_y, most, lemke_limit):
    """Sequential impulses over the pairs: the warm start, then sweeps, each pair taking
    friction at its points (within the cone of their normal impulses) then its normal
    impulses (never pulling; a pair's two points together, ``_normal_pair``), until no
    point's speed is off by more than ``SOLVE_TOLERANCE`` times ``speed`` (``_residual``).
    Sweeps converge slowly on tall stacks and piles (their rate falls with the square of the
    height), so after ``EXACT_AFTER`` that did not the problem is solved exactly
    (``_exact``, by Lemke's method too only for at most ``lemke_limit`` unknowns); where that
    cannot be done, the sweeps go on, for at most ``most`` in all. Returns the number of
    sweeps."""
    starts, sizes, blocks = _blocks(pairs, count)
    # Sweep the pairs in order of height against the acceleration (bottom to top, then back):
    # in a stack, a load then passes all the way down, and the reactions all the way up, in
    # one pair of sweeps, where an arbitrary order needs many.
    height = np.empty(blocks)
    for b in range(blocks):
        c = starts[b]
        height[b] = -(rows[c, PX] * down_x + rows[c, PY] * down_y)
    order = np.argsort(height)
    starts = starts[order]
    sizes = sizes[order]
    # The sweeps pass vel, rows and pairs (this call's arguments, which its caller keeps
    # alive) through small inlined helpers a few times per pair per sweep: borrowed, they
    # count no references there.
    return _sweeps(F, borrowed_array(vel), borrowed_array(rows), borrowed_array(pairs), count, starts, sizes, blocks,
                   speed, most, lemke_limit)


@njit(cache=True)
def _sweeps(F, vel, rows, pairs, count, starts, sizes, blocks, speed, most, lemke_limit):
    """``_solve``'s warm start and sweeps over the pairs in the order ``starts`` (first rows)
    and ``sizes`` (points); ``vel``, ``rows`` and ``pairs`` are borrowed."""
    for b in range(blocks):
        c = starts[b]
        _push(rows, vel, pairs, c, rows[c, LAMBDA_N], 0.0)
        if sizes[b] == 2:
            d = c + 1
            _push(rows, vel, pairs, d, rows[d, LAMBDA_N], 0.0)
            total = rows[c, LAMBDA_T] + rows[d, LAMBDA_T]
            limit = rows[c, MU] * (rows[c, LAMBDA_N] + rows[d, LAMBDA_N])
            total = min(max(total, -limit), limit)
            rows[c, LAMBDA_T] = total
            rows[d, LAMBDA_T] = 0.0
            _push_at(rows, vel, pairs, c, -total * rows[c, NY], total * rows[c, NX], rows[c, FAX], rows[c, FAY],
                     rows[c, FBX], rows[c, FBY])
        else:
            limit = rows[c, MU] * rows[c, LAMBDA_N]
            rows[c, LAMBDA_T] = min(max(rows[c, LAMBDA_T], -limit), limit)
            _push(rows, vel, pairs, c, 0.0, rows[c, LAMBDA_T])
    warm = rows[:count, LAMBDA_N:LAMBDA_T + 1].copy()  # the last step's answer, as started
    for sweep in range(most):
        change = 0.0
        for q in range(blocks):
            # Sweeps alternate direction (symmetric Gauss-Seidel): a load passes down a
            # stack, and a reaction up it, within one pair of sweeps.
            b = q if sweep % 2 == 0 else blocks - 1 - q
            c = starts[b]
            if sizes[b] == 2:
                change = max(change, _friction_pair(vel, rows, pairs, c))
                change = max(change, _normal_pair(vel, rows, pairs, c))
            else:
                change = max(change, _friction(vel, rows, pairs, c))
                change = max(change, _normal(vel, rows, pairs, c))
            change = max(change, _into_cone(vel, rows, pairs, c, sizes[b]))
        if change == 0.0 or _residual(vel, rows, pairs, count, starts, sizes, blocks) <= SOLVE_TOLERANCE * speed:
            return sweep + 1
        if sweep == EXACT_AFTER - 1 and _exact(F, vel, rows, pairs, count, starts, sizes, blocks, speed, warm, lemke_limit):
            return sweep + 1
    return most


@njit(cache=True, inline="always")
def _arms(rows, c):
    """Lever arms of the friction of the pair whose first row is ``c``: its point, or the
    midpoint of its two (``_pair_constants``)."""
    return rows[c, FAX], rows[c, FAY], rows[c, FBX], rows[c, FBY]


@njit(cache=True)
def _directions(F, rows, pairs, count, starts, blocks):
    """The solve's constraint directions: every row's normal, then the friction (tangent at
    the point, or at the midpoint of a pair's two points) of every block with friction.
    Returns ``(ja, jb, body_a, body_b, row, nf)``: each direction's coefficients on its two
    bodies' ``(vx, vy, spin)`` (``jb`` for the second, reversed), their local indices (-1:
    fixed), the row it belongs to, and how many friction directions there are."""
    friction = 0
    for b in range(blocks):
        if rows[starts[b], MU] > 0.0:
            friction += 1
    n = count + friction
    ja = np.zeros((n, 3))
    jb = np.zeros((n, 3))
    body_a = np.empty(n, dtype=np.int64)
    body_b = np.empty(n, dtype=np.int64)
    row = np.empty(n, dtype=np.int64)
    k = 0
    for c in range(count + blocks):
        if c < count:
            r = c
            dx = rows[r, NX]
            dy = rows[r, NY]
            rax, ray, rbx, rby = rows[r, RAX], rows[r, RAY], rows[r, RBX], rows[r, RBY]
        else:
            r = starts[c - count]
            if not rows[r, MU] > 0.0:
                continue
            dx = -rows[r, NY]
            dy = rows[r, NX]
            rax, ray, rbx, rby = _arms(rows, r)
        ja[k, 0] = dx
        ja[k, 1] = dy
        ja[k, 2] = rax * dy - ray * dx
        jb[k, 0] = -dx
        jb[k, 1] = -dy
        jb[k, 2] = -(rbx * dy - rby * dx)
        body_a[k] = pairs[r, 0]
        body_b[k] = pairs[r, 1]
        row[k] = r
        k += 1
    return ja, jb, body_a, body_b, row, friction


@njit(cache=True)
def _operator(F, vel, rows, pairs, count, ja, jb, body_a, body_b, row):
    """The contact problem along the solve's directions: ``W = J M^-1 J^T``, the speeds
    along them with no contact impulse (``base``), the impulses now, and each local body's
    inverse mass and inertia. Returns ``(W, base, impulse, inverse)``."""
    n = ja.shape[0]
    inverse = np.zeros((vel.shape[0], 3))
    for k in range(n):
        for side in range(2):
            x = body_a[k] if side == 0 else body_b[k]
            if x >= 0:
                i = pairs[row[k], 2 + side]
                inverse[x, 0] = F[i, L.INV_MASS]
                inverse[x, 1] = F[i, L.INV_MASS]
                inverse[x, 2] = F[i, L.INV_INERTIA]
    W = np.zeros((n, n))
    speeds = np.zeros(n)
    impulse = np.zeros(n)
    for k in range(n):
        for side in range(2):
            x = body_a[k] if side == 0 else body_b[k]
            if x >= 0:
                for d in range(3):
                    speeds[k] += (ja[k, d] if side == 0 else jb[k, d]) * vel[x, d]
        impulse[k] = rows[row[k], LAMBDA_N] if k < count else rows[row[k], LAMBDA_T]
        for q in range(k + 1):
            total = 0.0
            for sk in range(2):
                xk = body_a[k] if sk == 0 else body_b[k]
                if xk < 0:
                    continue
                for sq in range(2):
                    xq = body_a[q] if sq == 0 else body_b[q]
                    if xq != xk:
                        continue
                    for d in range(3):
                        left = ja[k, d] if sk == 0 else jb[k, d]
                        right = ja[q, d] if sq == 0 else jb[q, d]
                        total += left * inverse[xk, d] * right
            W[k, q] = total
            W[q, k] = total
    base = speeds.copy()
    for k in range(n):
        for q in range(n):
            base[k] -= W[k, q] * impulse[q]
    return W, base, impulse, inverse


@njit(cache=True)
def _in_block(pairs, count, first):
    """Whether row ``first + 1`` is the second point of ``first``'s pair."""
    return first + 1 < count and pairs[first + 1, 2] == pairs[first, 2] and pairs[first + 1, 3] == pairs[first, 3]


@njit(cache=True, inline="always")
def _load(normal, pairs, count, first):
    """The normal impulse (from ``normal``, indexed by row) on the pair whose first row is
    ``first``: one point's, or its two points' together."""
    if _in_block(pairs, count, first):
        return normal[first] + normal[first + 1]
    return normal[first]


@njit(cache=True)
def _cholesky_solve(A, b):
    """Solve ``A x = b`` for symmetric positive definite ``A`` (Cholesky); ``ok`` false when
    a pivot is not positive."""
    m = b.shape[0]
    C = np.zeros((m, m))
    for j in range(m):
        d = A[j, j]
        for k in range(j):
            d -= C[j, k] * C[j, k]
        if not d > 0.0:
            return b, False
        C[j, j] = math.sqrt(d)
        for i in range(j + 1, m):
            e = A[i, j]
            for k in range(j):
                e -= C[i, k] * C[j, k]
            C[i, j] = e / C[j, j]
    y = b.copy()
    for i in range(m):
        for k in range(i):
            y[i] -= C[i, k] * y[k]
        y[i] /= C[i, i]
    for i in range(m - 1, -1, -1):
        for k in range(i + 1, m):
            y[i] -= C[k, i] * y[k]
        y[i] /= C[i, i]
    return y, True


@njit(cache=True)
def _active_set(W, base, rows, pairs, row, count, nf, impulse):
    """The exact answer on the active set of ``impulse`` (the sweeps' or the last step's):
    which points push (``l > 0``), which pairs stick and which slide, and which way. On that
    set the problem is linear: a pushing point's normal speed is its target, a sticking
    pair's sliding speed zero, a sliding pair's friction ``mu`` times its normal impulses
    against the slide (``_set_system``). The answer nearest ``impulse`` among those that
    solve it (``_set_solve``) fixes the share of redundant points (a face on three points, a
    statically indeterminate pile) and leaves the rest exact.

    Returns ``(impulses, state)``: ``SET_SOLVED`` when the answer satisfies every condition
    of the problem (the set was right); ``SET_MOVED`` when it does not, with the next set to
    try (``_next_set``); ``SET_WRONG`` when the set's system cannot be solved."""
    n = count + nf
    unknown, columns, sign, slides = _set_unknowns(rows, pairs, row, count, nf, impulse)
    m = columns.shape[0]
    if m == 0:
        return impulse, SET_WRONG
    A, b = _set_system(W, base, rows, pairs, row, count, nf, unknown, columns, sign)
    start = np.empty(m)
    for j in range(m):
        start[j] = impulse[columns[j]]
    y, ok = _set_solve(A, b, start, slides)
    if not ok:
        return impulse, SET_WRONG
    fresh = np.zeros(n)
    for j in range(m):
        fresh[columns[j]] = y[j]
    for f in range(nf):
        if sign[f] != 0.0:
            first = row[count + f]
            fresh[count + f] = sign[f] * rows[first, MU] * _load(fresh, pairs, count, first)
    speeds = base.copy()
    for k in range(n):
        for q in range(n):
            speeds[k] += W[k, q] * fresh[q]
    moved = _next_set(speeds, np.abs(base).max(), rows, pairs, row, count, nf, unknown, sign, fresh)
    return fresh, SET_MOVED if moved else SET_SOLVED


@njit(cache=True)
def _next_set(speeds, scale, rows, pairs, row, count, nf, unknown, sign, fresh):
    """Check the answer ``fresh`` of an active set (``unknown``, ``sign``: ``_set_unknowns``)
    against every condition of the problem, at the ``speeds`` it gives, and where one fails
    move the set (principal pivoting), in ``fresh`` itself: a point that pulls stops
    pushing, a point without impulse that closes faster than its target pushes, a sticking
    pair whose friction leaves its cone slides, a sliding pair that slides the way its
    friction pushes sticks. Returns whether anything moved. Rounding is tolerated to 1e-9
    of ``scale``, the largest speed without contact impulses."""
    tolerance = 1e-9 * (scale + 1e-300)
    moved = False
    # friction first, against this answer's loads
    side = np.zeros(nf)  # the next set: -1 or 1 slides that way, 0 sticks
    for f in range(nf):
        k = count + f
        first = row[k]
        limit = rows[first, MU] * _load(fresh, pairs, count, first)
        if unknown[k] >= 0:
            if abs(fresh[k]) > limit * (1.0 + 1e-9):
                side[f] = 1.0 if fresh[k] > 0.0 else -1.0
                moved = True
        elif sign[f] != 0.0:
            if sign[f] * speeds[k] > tolerance:
                moved = True
            else:
                side[f] = sign[f]
    largest = 0.0
    for a in range(count):
        largest = max(largest, fresh[a])
    for a in range(count):
        if fresh[a] < 0.0:
            fresh[a] = 0.0
            moved = True
        elif unknown[a] < 0 and speeds[a] < rows[a, TARGET] - tolerance:
            # pushing from next time: any positive start will do, the solve finds its value
            fresh[a] = 1e-12 * largest if largest > 0.0 else 1.0
            moved = True
    # the friction of the next set, within the next loads: at the cone's edge where it
    # slides, strictly inside where it sticks
    for f in range(nf):
        k = count + f
        first = row[k]
        limit = rows[first, MU] * _load(fresh, pairs, count, first)
        if side[f] != 0.0:
            fresh[k] = side[f] * limit
        else:
            fresh[k] = min(max(fresh[k], -0.5 * limit), 0.5 * limit)
    return moved


@njit(cache=True)
def _set_unknowns(rows, pairs, row, count, nf, impulse):
    """The unknowns of the active set of ``impulse``: every pushing point's normal impulse
    and every sticking pair's friction (``unknown[k]``: the unknown of direction ``k``, -1
    for none; ``columns[j]``: the direction of unknown ``j``), the direction each sliding
    pair slides (``sign``, 0 where it sticks or has no friction), and whether any does."""
    n = count + nf
    unknown = -np.ones(n, dtype=np.int64)
    columns = np.empty(n, dtype=np.int64)
    m = 0
    for a in range(count):
        if impulse[a] > 0.0:
            unknown[a] = m
            columns[m] = a
            m += 1
    sign = np.zeros(nf)
    slides = False
    for f in range(nf):
        first = row[count + f]
        limit = rows[first, MU] * _load(impulse, pairs, count, first)
        if abs(impulse[count + f]) < limit * (1.0 - 1e-9):
            unknown[count + f] = m
            columns[m] = count + f
            m += 1
        elif impulse[count + f] != 0.0:
            sign[f] = 1.0 if impulse[count + f] > 0.0 else -1.0
            slides = True
    return unknown, columns[:m], sign, slides


@njit(cache=True)
def _set_system(W, base, rows, pairs, row, count, nf, unknown, columns, sign):
    """The linear problem ``A y = b`` on an active set: row ``e`` says that direction
    ``columns[e]`` reaches its target speed (a point's ``TARGET``, a sticking pair's zero);
    column ``j`` is what unknown ``j`` does to the speeds, a pushing point's normal impulse
    bringing with it the friction ``sign mu`` times it where its pair slides."""
    m = columns.shape[0]
    # the sliding friction direction a point's normal impulse drags along (-1: none)
    drags = -np.ones(count, dtype=np.int64)
    for f in range(nf):
        if sign[f] != 0.0:
            first = row[count + f]
            drags[first] = count + f
            if _in_block(pairs, count, first):
                drags[first + 1] = count + f
    A = np.empty((m, m))
    b = np.empty(m)
    for e in range(m):
        k = columns[e]
        for j in range(m):
            q = columns[j]
            total = W[k, q]
            if q < count and drags[q] >= 0:
                g = drags[q]
                total += sign[g - count] * rows[row[g], MU] * W[k, g]
            A[e, j] = total
        b[e] = (rows[k, TARGET] if k < count else 0.0) - base[k]
    return A, b


@njit(cache=True)
def _set_solve(A, b, start, slides):
    """The solution of ``A y = b`` nearest ``start``, pulled towards it by a tiny ``eps``
    (which only decides directions ``A`` leaves free). Where no pair slides, ``A`` is part
    of ``W`` (symmetric, positive semi-definite): ``(A + eps) y = b + eps start``, one
    Cholesky solve. Else in least squares, ``(A^T A + eps) y = A^T b + eps start``.
    Returns ``(y, ok)``; ``ok`` false when a pivot is not positive."""
    m = b.shape[0]
    if not slides:
        N = A.copy()
        r = b.copy()
        scale = 0.0
        for i in range(m):
            scale = max(scale, N[i, i])
        eps = 1e-12 * scale
    else:
        N = np.empty((m, m))
        r = np.zeros(m)
        scale = 0.0
        for i in range(m):
            for j in range(i + 1):
                total = 0.0
                for e in range(m):
                    total += A[e, i] * A[e, j]
                N[i, j] = total
                N[j, i] = total
            scale = max(scale, N[i, i])
            for e in range(m):
                r[i] += A[e, i] * b[e]
        eps = 1e-13 * scale
    for i in range(m):
        N[i, i] += eps
        r[i] += eps * start[i]
    return _cholesky_solve(N, r)


@njit(cache=True)
def _lemke_solve(W, base, rows, pairs, row, count, nf):
    """The problem as Stewart and Trinkle's LCP with Coulomb friction (exact in 2D),
    solved by Lemke's method. Unknowns: each row's normal impulse ``l >= 0``; each block's
    friction ``f+ - f-`` (``f+, f- >= 0``) and its sliding speed ``s >= 0``. Returns
    ``(impulses, ok)``; ``ok`` false on a ray or a budget run out."""
    size = count + 3 * nf
    M = np.zeros((size, size))
    q = np.zeros(size)
    plus = count
    minus = count + nf
    slide = count + 2 * nf
    for a in range(count):
        q[a] = base[a] - rows[a, TARGET]
        for b in range(count):
            M[a, b] = W[a, b]
        for f in range(nf):
            M[a, plus + f] = W[a, count + f]
            M[a, minus + f] = -W[a, count + f]
    for f in range(nf):
        t = count + f
        q[plus + f] = base[t]
        q[minus + f] = -base[t]
        for b in range(count):
            M[plus + f, b] = W[t, b]
            M[minus + f, b] = -W[t, b]
        for g in range(nf):
            M[plus + f, plus + g] = W[t, count + g]
            M[plus + f, minus + g] = -W[t, count + g]
            M[minus + f, plus + g] = -W[t, count + g]
            M[minus + f, minus + g] = W[t, count + g]
        M[plus + f, slide + f] = 1.0
        M[minus + f, slide + f] = 1.0
        M[slide + f, plus + f] = -1.0
        M[slide + f, minus + f] = -1.0
        first = row[t]
        mu = rows[first, MU]
        M[slide + f, first] = mu
        if _in_block(pairs, count, first):
            M[slide + f, first + 1] = mu
    z, ok = lemke(M, q, 8 * size + 64)
    fresh = np.empty(count + nf)
    for a in range(count):
        fresh[a] = z[a]
    for f in range(nf):
        fresh[count + f] = z[plus + f] - z[minus + f]
    return fresh, ok


@njit(cache=True)
def _exact(F, vel, rows, pairs, count, starts, sizes, blocks, speed, warm, lemke_limit):
    """Solve the step's contacts exactly: a pushing point reaches its target normal speed
    and no point closes faster than it; a sliding pair's friction is ``mu`` times its normal
    impulses, against the slide; a sticking pair stops sliding, within the cone. Three ways,
    in order, each answer checked (``_accept``) before the next is tried: from the sweeps'
    active set, then from the last step's (``warm``, the impulses the sweeps started from)
    (``_on_set``: one linear solve per set, right at most steps of a pile), then as a
    complementarity problem by Lemke's method (``_lemke_solve``, for at most ``lemke_limit``
    unknowns). Replaces the impulses and velocities and returns true with the first answer
    that checks out; leaves them alone otherwise (a ray, or too many unknowns: the sweeps go
    on)."""
    ja, jb, body_a, body_b, row, nf = _directions(F, rows, pairs, count, starts, blocks)
    n = ja.shape[0]
    if count + 3 * nf > LCP_LIMIT:
        return False
    W, base, impulse, inverse = _operator(F, vel, rows, pairs, count, ja, jb, body_a, body_b, row)
    if _on_set(vel, rows, pairs, count, starts, sizes, blocks, speed, ja, jb, body_a, body_b, row, nf, W, base,
               impulse, inverse, impulse):
        return True
    # the last step's active set: a pile's contacts mostly keep theirs from step to step
    last = np.empty(n)
    for k in range(n):
        last[k] = warm[row[k], 0] if k < count else warm[row[k], 1]
    if _on_set(vel, rows, pairs, count, starts, sizes, blocks, speed, ja, jb, body_a, body_b, row, nf, W, base,
               impulse, inverse, last):
        return True
    if count + 3 * nf > lemke_limit:
        return False
    fresh, ok = _lemke_solve(W, base, rows, pairs, row, count, nf)
    return ok and _accept(vel, rows, pairs, count, starts, sizes, blocks, speed, ja, jb, body_a, body_b, row, nf,
                          impulse, inverse, fresh)


@njit(cache=True)
def _on_set(vel, rows, pairs, count, starts, sizes, blocks, speed, ja, jb, body_a, body_b, row, nf, W, base,
            impulse, inverse, guess):
    """Solve on the active set of ``guess`` (``_active_set``) and take the answer if it
    checks out (``_accept``); where it breaks a condition of the problem, on the set it
    moves to, at most ``SET_TRIES`` sets in all. Returns whether an answer was taken."""
    for _ in range(SET_TRIES):
        fresh, state = _active_set(W, base, rows, pairs, row, count, nf, guess)
        if state == SET_SOLVED:
            return _accept(vel, rows, pairs, count, starts, sizes, blocks, speed, ja, jb, body_a, body_b, row, nf,
                           impulse, inverse, fresh)
        if state == SET_WRONG:
            return False
        guess = fresh
    return False


@njit(cache=True)
def _accept(vel, rows, pairs, count, starts, sizes, blocks, speed, ja, jb, body_a, body_b, row, nf, impulse,
            inverse, fresh):
    """Take the impulses ``fresh`` (from ``impulse``, along the directions ``ja``, ``jb``) if
    the velocities they give pass the sweeps' own test (``_residual`` within
    ``SOLVE_TOLERANCE`` of ``speed``): then the rows' impulses and ``vel`` are replaced and
    the answer is true; else nothing changes."""
    moved = vel.copy()
    for k in range(ja.shape[0]):
        change = fresh[k] - impulse[k]
        for side in range(2):
            x = body_a[k] if side == 0 else body_b[k]
            if x >= 0:
                for d in range(3):
                    moved[x, d] += inverse[x, d] * (ja[k, d] if side == 0 else jb[k, d]) * change
    old = rows[:count, LAMBDA_N:LAMBDA_T + 1].copy()
    for a in range(count):
        rows[a, LAMBDA_N] = fresh[a]
        rows[a, LAMBDA_T] = 0.0
    for f in range(nf):
        rows[row[count + f], LAMBDA_T] = fresh[count + f]
    if _residual(moved, rows, pairs, count, starts, sizes, blocks) <= SOLVE_TOLERANCE * speed:
        vel[:, :] = moved
        return True
    rows[:count, LAMBDA_N:LAMBDA_T + 1] = old
    return False


@njit(cache=True)
def _blocks(pairs, count):
    """The rows of each pair (one or two points, consecutive in the manifold): the first row
    and the number of rows of every block, and how many blocks."""
    starts = np.empty(count, dtype=np.int64)
    sizes = np.empty(count, dtype=np.int64)
    blocks = 0
    c = 0
    while c < count:
        starts[blocks] = c
        if _in_block(pairs, count, c):
            sizes[blocks] = 2
        else:
            sizes[blocks] = 1
        c += sizes[blocks]
        blocks += 1
    return starts[:blocks], sizes[:blocks], blocks


@njit(cache=True)
def _residual(vel, rows, pairs, count, starts, sizes, blocks):
    """How far the impulses are from solving the contacts, as a speed: the largest error of
    a pushing point's normal speed, of a point closing faster than its target, or of a
    sticking pair's (or point's) sliding speed. A friction impulse at its cone's edge to
    rounding slides: rounding relative to the problem's largest impulse as well as to the
    pair's own limit (an exact answer whose friction on a point pressed by 7e-10 fell short
    of the edge by 2.6e-18, in a pile pressed by 0.01, read as sticking and was refused)."""
    worst = 0.0
    pressed = 0.0
    for c in range(count):
        pressed = max(pressed, rows[c, LAMBDA_N])
    for c in range(count):
        ux, uy = _relative(vel, pairs, rows, c)
        gap = ux * rows[c, NX] + uy * rows[c, NY] - rows[c, TARGET]
        if rows[c, LAMBDA_N] > 0.0:
            worst = max(worst, abs(gap))
        else:
            worst = max(worst, -gap)
    for b in range(blocks):
        c = starts[b]
        if rows[c, MU] <= 0.0:
            continue
        if sizes[b] == 2:
            ux, uy = _relative_at(vel, pairs, c, rows[c, FAX], rows[c, FAY], rows[c, FBX], rows[c, FBY])
            limit = rows[c, MU] * (rows[c, LAMBDA_N] + rows[c + 1, LAMBDA_N])
        else:
            ux, uy = _relative(vel, pairs, rows, c)
            limit = rows[c, MU] * rows[c, LAMBDA_N]
        # sticking, not at the cone's edge: short of it by more than 1e-9 of the pair's own
        # limit and by more than the rounding of the problem's largest impulse
        if limit - abs(rows[c, LAMBDA_T]) > max(1e-9 * limit, 1e-12 * pressed):
            worst = max(worst, abs(-ux * rows[c, NY] + uy * rows[c, NX]))
    return worst


@njit(cache=True)
def _kinetic(F, i, vx, vy, w):
    """Kinetic energy of body ``i`` moving at ``(vx, vy)`` and turning at ``w``."""
    mass = 1.0 / F[i, L.INV_MASS]
    inertia = 1.0 / F[i, L.INV_INERTIA] if F[i, L.INV_INERTIA] > 0.0 else 0.0
    return 0.5 * (mass * (vx * vx + vy * vy) + inertia * w * w)


@njit(cache=True)
def _blend(F, members, before, soft, hard, labels):
    """For each part (``labels``), how far (0 to 1) from the inelastic answer ``soft``
    towards the answer with restitution ``hard`` the part's velocities may go before its
    kinetic energy rises above the one ``before`` (beyond rounding, 1e-13 of it): the
    largest root of a quadratic. -1 where even ``soft`` would raise it (rounding).
    Returns it at each part's root's index. With ``soft`` the velocities ``before`` it is
    the impact stage's energy guard: the share of the changes to ``hard`` to keep. Restitution
    solved for several contacts together can raise the energy (a body bouncing off one
    neighbour into another that was moving away); per part, so that one part's bounce does
    not scale back another's impacts (a point left closing sinks in mid-step)."""
    m = members.shape[0]
    energy = np.zeros(m)
    gained = np.zeros(m)  # the inelastic answer's change of the kinetic energy
    along = np.zeros(m)  # first-order change from it along hard - soft
    square = np.zeros(m)  # second-order
    for k in range(m):
        r = labels[k]
        if r < 0:
            continue
        i = members[k]
        mass = 1.0 / F[i, L.INV_MASS]
        inertia = 1.0 / F[i, L.INV_INERTIA] if F[i, L.INV_INERTIA] > 0.0 else 0.0
        energy[r] += _kinetic(F, i, before[k, 0], before[k, 1], before[k, 2])
        for q in range(3):
            weight = mass if q < 2 else inertia
            step = soft[k, q] - before[k, q]
            more = hard[k, q] - soft[k, q]
            gained[r] += weight * (before[k, q] * step + 0.5 * step * step)
            along[r] += weight * soft[k, q] * more
            square[r] += 0.5 * weight * more * more
    share = np.ones(m)
    for r in range(m):
        slack = 1e-13 * energy[r] - gained[r]
        if slack < 0.0:
            share[r] = -1.0
        elif along[r] + square[r] > slack and square[r] > 0.0:
            root = math.sqrt(along[r] * along[r] + 4.0 * square[r] * slack)
            if along[r] >= 0.0:
                largest = 2.0 * slack / (along[r] + root) if along[r] + root > 0.0 else 0.0
            else:
                largest = (root - along[r]) / (2.0 * square[r])
            share[r] = max(min(largest, 1.0), 0.0) * (1.0 - 4e-16)
    return share


@njit(cache=True, inline="always")
def _power_terms(F, i, now, end, rigid, h, sums):
    """Add body ``i``'s terms to ``sums``, the mass-weighted products that give its part's
    contact power at the step's two ends as functions of the factor ``f`` on the motion
    beyond the rigid one (``_rise``): with ``w = end - rigid`` and the contact impulse at
    ``f = 0``, ``d = rigid - now - h a_free``, the impulse is ``d + f w`` (times the mass),
    the velocity at the end ``rigid + f w`` and now ``now``. ``sums``: ``<d, rigid>``,
    ``<d, w> + <w, rigid>``, ``<w, w>``, ``<d, now>``, ``<w, now>``."""
    mass = 1.0 / F[i, L.INV_MASS]
    inertia = 1.0 / F[i, L.INV_INERTIA] if F[i, L.INV_INERTIA] > 0.0 else 0.0
    for q in range(3):
        weight = mass if q < 2 else inertia
        free = h * F[i, L.FREE_AX] if q == 0 else (h * F[i, L.FREE_AY] if q == 1 else 0.0)
        w = end[q] - rigid[q]
        d = rigid[q] - now[q] - free
        sums[0] += weight * d * rigid[q]
        sums[1] += weight * (d * w + w * rigid[q])
        sums[2] += weight * w * w
        sums[3] += weight * d * now[q]
        sums[4] += weight * w * now[q]


@njit(cache=True, inline="always")
def _interval(c0, c1, c2):
    """The interval ``(low, high)`` of ``f`` where ``c0 + c1 f + c2 f^2 <= 0`` (``c2 >= 0``;
    empty: ``low > high``), roots in the forms that do not cancel."""
    if c2 <= 0.0:
        if c1 > 0.0:
            return -math.inf, -c0 / c1
        if c1 < 0.0:
            return -c0 / c1, math.inf
        return (-math.inf, math.inf) if c0 <= 0.0 else (math.inf, -math.inf)
    disc = c1 * c1 - 4.0 * c2 * c0
    if disc < 0.0:
        return math.inf, -math.inf
    root = math.sqrt(disc)
    if c1 >= 0.0:
        low = -(c1 + root) / (2.0 * c2)
        high = -2.0 * c0 / (c1 + root) if c1 + root > 0.0 else 0.0
    else:
        high = (root - c1) / (2.0 * c2)
        low = 2.0 * c0 / (root - c1)
    return low, high


@njit(cache=True, inline="always")
def _rise(sums, f):
    """How far a part's energy rises inside the step from the lowest it was before, at the
    factor ``f`` on its motion beyond its rigid motion (``_power_terms``). The forces'
    power is linear in time over the step; at its ends (as work over the whole step)
    ``start = sums[3] + sums[4] f`` and ``end = sums[0] + sums[1] f + sums[2] f^2``. Where it
    crosses zero upwards the energy dips and comes back by ``end^2 / (2 (end - start))``;
    downwards it rises first, by ``start^2 / (2 (start - end))``."""
    start = sums[3] + sums[4] * f
    end = sums[0] + (sums[1] + sums[2] * f) * f
    if start >= 0.0 and end >= 0.0:
        return 0.5 * (start + end)
    if end > 0.0:
        return 0.5 * end * end / (end - start)
    if start > 0.0:
        return 0.5 * start * start / (start - end)
    return 0.0


@njit(cache=True, inline="always")
def _work_at(work, f):
    """The contact forces' work over the step at the factor ``f`` (``work``: its
    coefficients, ``_no_gain``)."""
    return work[0] + (work[1] + work[2] * f) * f


@njit(cache=True, inline="always")
def _rise_out(sums, work, cap, allowed, rounding):
    """The largest factor up to ``cap`` on a part's motion beyond its rigid motion at which
    its energy rises nowhere inside the step by more than ``allowed`` (``_rise``) and the
    step's work is at most ``rounding``: a step may lose energy from end to end and still
    have a collision inside it see less energy than a later one (the forces' power, linear
    in time over a step, rising through zero: a contact's approach turned round, a slip
    reversed). ``cap`` where it already holds there, or where it does not hold even at 0
    (nothing to gain from scaling); else found by bisection (both are quadratic in the
    factor, the rise a ratio of them, and where it holds at 0 and not at ``cap`` a crossing
    lies between)."""
    if _rise(sums, cap) <= allowed and _work_at(work, cap) <= rounding:
        return cap
    # a factor that holds: where the power is not positive at either end (no rise at all),
    # else 0
    low0, high0 = _interval(sums[0], sums[1], sums[2])
    low1, high1 = _interval(sums[3], sums[4], 0.0)
    low = min(cap, high0, high1)
    if low < max(low0, low1, 0.0) or _work_at(work, low) > rounding or _rise(sums, low) > allowed:
        low = 0.0
        if _rise(sums, 0.0) > allowed or _work_at(work, 0.0) > rounding:
            return cap
    high = cap
    for _ in range(60):
        middle = 0.5 * (low + high)
        if _rise(sums, middle) <= allowed and _work_at(work, middle) <= rounding:
            low = middle
        else:
            high = middle
    return low


@njit(cache=True, inline="always")
def _scale_beyond(velocities, rigid, labels, factor):
    """Scale each body's velocity and spin beyond ``rigid`` by its part's ``factor`` (the
    energy stage's and the lift's payment)."""
    for k in range(velocities.shape[0]):
        r = labels[k]
        if r >= 0 and factor[r] < 1.0:
            for q in range(3):
                velocities[k, q] = rigid[k, q] + factor[r] * (velocities[k, q] - rigid[k, q])


@njit(cache=True)
def _no_gain(F, members, now, end, rows, pairs, count, h):
    """The energy stage: over the step the contact forces may do no positive work. Each
    body's acceleration is constant over the step, so their work is exact from the
    velocities at its two ends: the kinetic energy at the end (``end``) less the one now
    (``now``), less what each body's own acceleration and gravity do over its displacement
    ``h (now + end) / 2``. A normal force does none by construction (its target bounds the
    point's mean speed, ``_end_targets``); friction can: a row that sticks at the step's end
    may have slipped at its start where the row acts (a turning body's rows act at mid-step),
    and a force constant over the step works on the slip's mean. So for each group of bodies
    the step's forces join (a part), where the work is positive beyond rounding, the part's
    velocities and spins beyond its rigid motion (none where a force joins it to a fixed
    body; else the motion of the part as one rigid body with its momentum and its angular
    momentum about its centre, which both stay) are scaled by the factor that takes the work
    out: every relative velocity at a contact scales with them (a rigid motion has none), so
    a point that sticks still sticks, and a body no force touches keeps its motion. Where
    even stopping the part's relative motion would not take it out (a point rising slower
    than the step's own acceleration stops it, held at the step's end: the float of
    docs/contact.md, "Energy"), the part is left as it is. The same factor keeps the
    energy from rising inside the step (``_rise_out``): beyond rounding without gravity,
    beyond the float's own bound ``m (|a| h)^2 / 32`` with it. Returns how many parts were
    scaled."""
    m = members.shape[0]
    labels, grounded = _force_parts(rows, pairs, count, m)
    rigid = _rigid_motion(F, members, end, labels, grounded)
    before = np.zeros(m)  # kinetic energy now
    relative = np.zeros(m)  # kinetic energy at the end beyond the rigid motion
    carried = np.zeros(m)  # the rigid motion's
    along = np.zeros(m)  # work of the bodies' own accelerations on the motion beyond it
    rest = np.zeros(m)  # their work on the rest of the displacement
    scale = np.zeros(m)
    floats = np.zeros(m)  # the float's bound on a rise inside the step (docs/contact.md, "Energy")
    present = np.zeros(m, dtype=np.bool_)
    power = np.zeros((m, 5))  # the contact impulse against the velocities (_power_terms)
    for k in range(m):
        r = labels[k]
        if r < 0:
            continue
        present[r] = True
        i = members[k]
        mass = 1.0 / F[i, L.INV_MASS]
        ax = 0.5 * h * mass * F[i, L.FREE_AX]
        ay = 0.5 * h * mass * F[i, L.FREE_AY]
        before[r] += _kinetic(F, i, now[k, 0], now[k, 1], now[k, 2])
        relative[r] += _kinetic(F, i, end[k, 0] - rigid[k, 0], end[k, 1] - rigid[k, 1], end[k, 2] - rigid[k, 2])
        carried[r] += _kinetic(F, i, rigid[k, 0], rigid[k, 1], rigid[k, 2])
        along[r] += ax * (end[k, 0] - rigid[k, 0]) + ay * (end[k, 1] - rigid[k, 1])
        rest[r] += ax * (now[k, 0] + rigid[k, 0]) + ay * (now[k, 1] + rigid[k, 1])
        scale[r] += abs(ax * (now[k, 0] + end[k, 0]) + ay * (now[k, 1] + end[k, 1]))
        _power_terms(F, i, now[k], end[k], rigid[k], h, power[r])
        floats[r] += mass * h * h * (F[i, L.FREE_AX] ** 2 + F[i, L.FREE_AY] ** 2) / 32.0
    factor = np.ones(m)
    scaled = 0
    for r in range(m):
        if not present[r]:
            continue
        kept = before[r] + rest[r] - carried[r]
        rounding = ENERGY_ROUNDING * (before[r] + scale[r])
        if relative[r] - along[r] - kept > rounding:
            factor[r] = _work_out(relative[r], along[r], kept)
        work = (-kept, -along[r], relative[r])
        factor[r] = min(factor[r], _rise_out(power[r], work, factor[r], rounding + floats[r], rounding))
        if factor[r] < 1.0:
            scaled += 1
    _scale_beyond(end, rigid, labels, factor)
    return scaled


@njit(cache=True, inline="always")
def _least_energy(relative, along):
    """The factor on a part's motion beyond its rigid motion at which its energy at the
    step's end, ``relative s^2 - along s`` plus what does not depend on ``s``, is least
    within [0, 1]."""
    if relative <= 0.0:
        return 1.0
    return min(max(0.5 * along / relative, 0.0), 1.0)


@njit(cache=True)
def _kept_motion(F, members, velocities, labels, grounded, rows, pairs, count):
    """Each body's velocity and spin in the motion its part keeps whatever its bodies do to
    each other: the part's rigid motion (``_rigid_motion``) where no force joins it to a fixed
    body; where forces do, only its momentum along a fixed face that presses it without
    friction (every such press frictionless, their normals parallel), as a translation; else
    none."""
    m = members.shape[0]
    rigid = _rigid_motion(F, members, velocities, labels, grounded)
    pressed = _pressed(rows, count)
    seen = np.zeros(m, dtype=np.bool_)
    free = grounded.copy()
    tx = np.zeros(m)
    ty = np.zeros(m)
    for c in range(count):
        if not pressed[c] or pairs[c, 1] >= 0:
            continue
        r = labels[pairs[c, 0]]
        if rows[c, LAMBDA_T] != 0.0:
            free[r] = False
        elif not seen[r]:
            seen[r] = True
            tx[r] = -rows[c, NY]
            ty[r] = rows[c, NX]
        elif abs(tx[r] * rows[c, NX] + ty[r] * rows[c, NY]) > PARALLEL:
            free[r] = False
    total = np.zeros(m)
    along = np.zeros(m)
    for k in range(m):
        r = labels[k]
        if r >= 0 and free[r] and seen[r]:
            mass = 1.0 / F[members[k], L.INV_MASS]
            total[r] += mass
            along[r] += mass * (velocities[k, 0] * tx[r] + velocities[k, 1] * ty[r])
    for k in range(m):
        r = labels[k]
        if r >= 0 and free[r] and seen[r]:
            rigid[k, 0] = along[r] / total[r] * tx[r]
            rigid[k, 1] = along[r] / total[r] * ty[r]
            rigid[k, 2] = 0.0
    return rigid


@njit(cache=True)
def _lift_paid(F, members, now, end, lift, rows, pairs, count, h):
    """The lift stage's energy: a push-out lift moves a body without leaving it a speed
    (``_push_out``), but a body lifted against its acceleration (gravity) gains the potential
    energy ``-m a . h lift / 2`` that no force paid for. A pentagon rocking in a cradle of
    circles sinks into them a little at every step as it turns (the step's straight line
    cannot follow the contact), and lifted out at every step it rocked higher and higher.
    Each part the step's forces join (``_force_parts``, as the energy stage) pays for its
    lifts from its motion at the step's end beyond the motion it keeps (``_kept_motion``:
    its momentum stays where nothing outside it acts), scaled by the factor that takes the
    gain out (``_work_out``), or as far as that motion holds (``_least_energy``; what is
    left is a still part lifted out of a depth its sinking lost before). Returns whether any
    part paid: its points then open a little less over the step, and the step finds its
    arcs and its push-out again."""
    m = members.shape[0]
    labels, grounded = _force_parts(rows, pairs, count, m)
    owed = np.zeros(m)
    scale = np.zeros(m)
    for k in range(m):
        r = labels[k]
        if r < 0:
            continue
        i = members[k]
        mass = 1.0 / F[i, L.INV_MASS]
        ax = 0.5 * h * mass * F[i, L.FREE_AX]
        ay = 0.5 * h * mass * F[i, L.FREE_AY]
        owed[r] -= ax * lift[k, 0] + ay * lift[k, 1]
        scale[r] += _kinetic(F, i, now[k, 0], now[k, 1], now[k, 2]) + abs(ax * (now[k, 0] + end[k, 0]) + ay * (now[k, 1] + end[k, 1]))
    paying = False
    for r in range(m):
        if owed[r] > ENERGY_ROUNDING * scale[r]:
            paying = True
        else:
            owed[r] = 0.0
    if not paying:
        return False
    rigid = _kept_motion(F, members, end, labels, grounded, rows, pairs, count)
    relative = np.zeros(m)
    along = np.zeros(m)
    for k in range(m):
        r = labels[k]
        if r < 0 or owed[r] == 0.0:
            continue
        i = members[k]
        mass = 1.0 / F[i, L.INV_MASS]
        relative[r] += _kinetic(F, i, end[k, 0] - rigid[k, 0], end[k, 1] - rigid[k, 1], end[k, 2] - rigid[k, 2])
        along[r] += 0.5 * h * mass * (F[i, L.FREE_AX] * (end[k, 0] - rigid[k, 0]) + F[i, L.FREE_AY] * (end[k, 1] - rigid[k, 1]))
    factor = np.ones(m)
    for r in range(m):
        if owed[r] == 0.0:
            continue
        kept = relative[r] - along[r] - owed[r]
        if kept >= 0.0:
            factor[r] = _work_out(relative[r], along[r], kept)
        else:
            factor[r] = _least_energy(relative[r], along[r])
    _scale_beyond(end, rigid, labels, factor)
    return True


@njit(cache=True)
def _pressed(rows, count):
    """Whether each row has an impulse."""
    pressed = np.empty(count, dtype=np.bool_)
    for c in range(count):
        pressed[c] = rows[c, LAMBDA_N] != 0.0 or rows[c, LAMBDA_T] != 0.0
    return pressed


@njit(cache=True)
def _force_parts(rows, pairs, count, m):
    """The parts of an island that its step's forces join (``_parts`` over the rows with an
    impulse), and whether each part (at its root's index) is joined to a fixed body."""
    pressed = _pressed(rows, count)
    labels = _parts(pairs, pressed, count, m)
    grounded = np.zeros(m, dtype=np.bool_)
    for c in range(count):
        if pressed[c] and pairs[c, 1] < 0:
            grounded[labels[pairs[c, 0]]] = True
    return labels, grounded


@njit(cache=True)
def _rigid_motion(F, members, velocities, labels, grounded):
    """Each body's velocity and spin in its part's rigid motion: the motion of the part as
    one rigid body with its momentum and its angular momentum about its centre (the bodies at
    their positions now); zero for a body in no part or in a part joined to a fixed body."""
    m = members.shape[0]
    total = np.zeros(m)
    cx = np.zeros(m)
    cy = np.zeros(m)
    px = np.zeros(m)
    py = np.zeros(m)
    for k in range(m):
        r = labels[k]
        if r >= 0 and not grounded[r]:
            i = members[k]
            mass = 1.0 / F[i, L.INV_MASS]
            total[r] += mass
            cx[r] += mass * F[i, L.X]
            cy[r] += mass * F[i, L.Y]
            px[r] += mass * velocities[k, 0]
            py[r] += mass * velocities[k, 1]
    spin = np.zeros(m)  # the part's angular momentum about its centre, then its rigid spin
    turning = np.zeros(m)  # its moment of inertia about its centre
    for r in range(m):
        if total[r] > 0.0:
            cx[r] /= total[r]
            cy[r] /= total[r]
            px[r] /= total[r]
            py[r] /= total[r]
    for k in range(m):
        r = labels[k]
        if r >= 0 and total[r] > 0.0:
            i = members[k]
            mass = 1.0 / F[i, L.INV_MASS]
            inertia = 1.0 / F[i, L.INV_INERTIA] if F[i, L.INV_INERTIA] > 0.0 else 0.0
            dx = F[i, L.X] - cx[r]
            dy = F[i, L.Y] - cy[r]
            spin[r] += mass * (dx * velocities[k, 1] - dy * velocities[k, 0]) + inertia * velocities[k, 2]
            turning[r] += mass * (dx * dx + dy * dy) + inertia
    for r in range(m):
        if turning[r] > 0.0:
            spin[r] /= turning[r]
    rigid = np.zeros((m, 3))
    for k in range(m):
        r = labels[k]
        if r >= 0 and total[r] > 0.0:
            i = members[k]
            rigid[k, 0] = px[r] - spin[r] * (F[i, L.Y] - cy[r])
            rigid[k, 1] = py[r] + spin[r] * (F[i, L.X] - cx[r])
            rigid[k, 2] = spin[r]
    return rigid


@njit(cache=True, inline="always")
def _work_out(relative, along, kept):
    """The factor on a part's motion beyond its rigid motion that takes out the positive work
    of its contact forces: the larger root of ``relative s^2 - along s - kept = 0`` (the work
    at factor ``s``: ``relative`` the kinetic energy of that motion, ``along`` what the
    bodies' own accelerations do on it, ``kept`` what the part may have beside it), in the
    form that does not cancel; 1 (unchanged) where no factor can (``kept < 0``: the float)."""
    if kept < 0.0 or relative <= 0.0:
        return 1.0
    root = math.sqrt(along * along + 4.0 * relative * kept)
    if along >= 0.0:
        return min((along + root) / (2.0 * relative), 1.0)
    return min(2.0 * kept / (root - along), 1.0)


@njit(cache=True)
def _parts(pairs, joins, count, m):
    """Each body's part of the island: union-find over the contacts between its bodies
    whose ``joins`` is set (the root's local index; -1 for a body with no such contact)."""
    parent = np.arange(m)
    touched = np.zeros(m, dtype=np.bool_)
    for c in range(count):
        if not joins[c]:
            continue
        ka = pairs[c, 0]
        kb = pairs[c, 1]
        touched[ka] = True
        if kb >= 0:
            touched[kb] = True
            ra = ka
            while parent[ra] != ra:
                ra = parent[ra]
            rb = kb
            while parent[rb] != rb:
                rb = parent[rb]
            if ra != rb:
                parent[max(ra, rb)] = min(ra, rb)
    labels = np.empty(m, dtype=np.int64)
    for k in range(m):
        r = k
        while parent[r] != r:
            r = parent[r]
        labels[k] = r if touched[k] else -1
    return labels


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


@njit(cache=True, inline="always")
def _lift_floor(start, now, end, h):
    """The least normal speed a lift may give a point whose gap moves from ``start`` with
    normal speed ``now`` to speed ``end`` over a step of length ``h`` (the force stage's
    straight line), so that the gap never goes below ``min(start, 0)`` within the step. A
    lift ``l`` (taken back linearly over the step) moves the point by ``l h (s - s^2 / 2)``
    at ``s`` of the step, front-loaded, while the forces' own opening ``h (now s + (end -
    now) s^2 / 2)`` may come late: a lift that closes the gap by the end's opening sinks the
    point by up to ``h (end - now) / 4`` on the way. The bound is the least over ``s`` in
    (0, 1] of ``-(gap(s) - floor) / (h (s - s^2 / 2))``, at the end or where its derivative
    vanishes, ``h end s^2 / 2 + g0 s - g0 = 0`` (``g0 = max(start, 0)``); with ``g0 = 0``
    the least is approached as ``s`` goes to 0, ``-now``. Returns a bound from below
    (negative: the lift may close the point by that speed)."""
    g0 = max(start, 0.0)
    least = (g0 + 0.5 * h * (now + end)) / (0.5 * h)  # at the end
    # the roots of (h end / 2) s^2 + g0 s - g0 = 0, scaled by g0 so that a gap of rounding's
    # size (or a denormal) cannot overflow them; where the first is lost below the smallest
    # double the least is the limit at s = 0
    at_zero = g0 == 0.0
    if g0 > 0.0:
        ratio = 2.0 * h * end / g0
        if 1.0 + ratio >= 0.0:
            wide = math.sqrt(1.0 + ratio)
            first = 2.0 / (1.0 + wide)
            second = -2.0 * (1.0 + wide) / ratio if ratio != 0.0 else -1.0
            at_zero = first == 0.0
            for s in (first, second):
                if 0.0 < s <= 1.0:
                    least = min(least, (g0 + h * (now * s + 0.5 * (end - now) * s * s)) / (h * (s - 0.5 * s * s)))
    if at_zero:
        least = min(least, now)
    return -least


@njit(cache=True)
def _push_out(F, now, end, rows, pairs, count, h, nominal, down_x, down_y):
    """The push-out stage: each body's velocity change ``lift`` at the step's start that
    moves its overlaps out by ``PUSH_RATE`` of their depth, taken back by an equal and
    opposite change spread over the step, so that it moves the bodies and leaves their
    velocities at the step's end (and so their energy) as the force stage found them: a
    displacement, not a speed. Kept as a speed, a push-out pumps energy into piles that are
    jammed or keep bouncing.

    Over a step a point's normal speed moves linearly from ``now`` to ``end``; the lift adds
    ``lift (1 - s / h)`` to it, so it moves the point by ``h lift / 2``. The lifts are
    normal impulses (never pulling, no friction), solved by ``_solve`` like the forces, on
    the separation ``e`` each point would have at the step's end without them: moved out by
    at least ``PUSH_RATE`` of ``-e`` per ``nominal`` step length (the island's step before
    any cut for a bounce: ``h / nominal`` of that in a step cut shorter, so that the lift,
    a speed, stays within ``2 PUSH_RATE |e| / nominal``) where ``e < 0``, closed by at most
    ``e`` where ``e >= 0``, and no deeper than its start anywhere within the step
    (``_lift_floor``: a lift is front-loaded, the forces' opening may come late). A point's
    ``ARC`` (``_midstep_rows``: what a turning body's contact adds to the straight line's
    end separation) is an overlap the step would make, not one it found: all of it is moved
    out at this step. Nothing is solved unless some point would overlap by more than
    ``PUSH_SLOP`` of its pair's smaller reach. Returns the lifts (all zero then) and the
    sweeps taken."""
    m = now.shape[0]
    lift = np.zeros((m, 3))
    need = np.empty(count)
    largest = 0.0
    for c in range(count):
        ux, uy = _relative(now, pairs, rows, c)
        wx, wy = _relative(end, pairs, rows, c)
        moved = 0.5 * h * ((ux + wx) * rows[c, NX] + (uy + wy) * rows[c, NY])
        left = rows[c, SEPARATION] + moved
        arc = rows[c, ARC]
        if left < 0.0:
            need[c] = -2.0 * (PUSH_RATE * left / nominal + arc / h)
        else:
            un = ux * rows[c, NX] + uy * rows[c, NY]
            wn = wx * rows[c, NX] + wy * rows[c, NY]
            # never a push for this: a point whose own line dips (closing now) is the force
            # stage's, and a lift does not close it further; nor further than its gaps on the
            # solved motion allow at the step's instants (a turning pair's, CLOSABLE)
            need[c] = max(-2.0 * (left + arc) / h, min(_lift_floor(rows[c, SEPARATION], un, wn, h), 0.0),
                          rows[c, CLOSABLE])
        reach = min(F[pairs[c, 2], L.REACH], F[pairs[c, 3], L.REACH])
        if left + arc < -PUSH_SLOP * reach:
            largest = max(largest, need[c])
    if not largest > 0.0:
        return lift, 0
    pushing = rows[:count].copy()
    pushing[:, TARGET] = need
    pushing[:, LAMBDA_N] = 0.0
    pushing[:, LAMBDA_T] = 0.0
    pushing[:, MU] = 0.0
    sweeps = _solve(F, lift, pushing, pairs, count, largest, down_x, down_y, ISLAND_ITERATIONS, LCP_LIMIT)
    return lift, sweeps


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
    _solved_arcs(S, now, end, rows, pairs, count, h)
    lift, pushes = _push_out(F, now, end, rows, pairs, count, h, natural, down_x, down_y)
    sweeps += pushes
    if _lift_paid(F, members, now, end, lift, rows, pairs, count, h):
        # The paid motion opens its points a little less: its arcs and the push-out again.
        _solved_arcs(S, now, end, rows, pairs, count, h)
        lift, pushes = _push_out(F, now, end, rows, pairs, count, h, natural, down_x, down_y)
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
