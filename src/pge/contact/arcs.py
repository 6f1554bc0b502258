"""The island step's turning pairs: what their contacts' straight lines miss over a step.

The step's conditions are linear in the points' speeds, exact where no polygon of a pair
turns. Where one does, its corners move on arcs and its faces turn under a neighbour: before
the solve, the pair's rows move to where the contact is at mid-step and each row's ``ARC``
holds what its straight line still misses (``_midstep_rows``); after it, ``ARC`` and
``CLOSABLE`` are found again on the step's solved motion, at its end and at instants inside
it (``_solved_arcs``), for the push-out (``pge.contact.pushout``) to take. Both find the
pair's manifold again with the outlines moved on and turned (``_moved``).
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
)
from pge.contact.rows import (
    APPROACH,
    ARC,
    ASKED,
    CIRCLE,
    CLOSABLE,
    _lever_arms,
    _pair_constants,
    _pair_end,
    _points_at,
    _relative,
)
from pge.core import layout as L
from pge.core.tuning import (
    END_TURN,
    FEATURE_INSTANTS,
    INSTANT_REFINEMENTS,
    STEP_INSTANTS,
)

#: the columns of ``_solved_arcs``'s ``ends``: whether the row's pair turns and its point was
#: found at the step's end, and that point and its normal there
END_VALID, END_PX, END_PY, END_NX, END_NY = range(5)


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
def _turning_pair(I, velocities, pairs, c):
    """Whether a polygon of row ``c``'s pair turns at the spins in ``velocities`` (a
    circle's spin does not move its outline)."""
    return _turning_rate(I, velocities, pairs, c) > 0.0


@njit(cache=True, inline="always")
def _turning_rate(I, velocities, pairs, c):
    """The faster spin in ``velocities`` of row ``c``'s polygons (a circle's spin does not
    move its outline)."""
    rate = 0.0
    if I[pairs[c, 2], L.KIND] != CIRCLE:
        rate = abs(velocities[pairs[c, 0], 2])
    if pairs[c, 1] >= 0 and I[pairs[c, 3], L.KIND] != CIRCLE:
        rate = max(rate, abs(velocities[pairs[c, 1], 2]))
    return rate


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
def _most_asked(S, now, end, rows, pairs, c, r, h, u0, line, floor, below, above, outline, scratch):
    """The most that row ``r``'s gap asks of the lift (``_instant_ask``) at an instant
    between the fractions ``below`` and ``above`` of the step (the sampled instants either
    side of the one that asked most), by ``INSTANT_REFINEMENTS`` golden-section steps on the
    solved motion; returns it and the outline scratch. A gap's dip is flat near its deepest
    while the lift's displacement, ``l h (f - f^2 / 2)``, still rises, so the most asked lies
    between the instants: a polygon sliding past a fixed corner at 0.5 m/s, held at a
    quarter, half and three quarters of the step, dipped 3.4e-8 at 0.41 of it (corpus scene
    97)."""
    golden = 0.5 * (math.sqrt(5.0) - 1.0)
    a = below
    b = above
    x1 = b - golden * (b - a)
    x2 = a + golden * (b - a)
    f1, outline = _ask_at(S, now, end, rows, pairs, c, r, h, u0, line, floor, x1, outline, scratch)
    f2, outline = _ask_at(S, now, end, rows, pairs, c, r, h, u0, line, floor, x2, outline, scratch)
    most = max(f1, f2)
    for _ in range(INSTANT_REFINEMENTS - 2):
        if f1 > f2:
            b = x2
            x2 = x1
            f2 = f1
            x1 = b - golden * (b - a)
            f1, outline = _ask_at(S, now, end, rows, pairs, c, r, h, u0, line, floor, x1, outline, scratch)
            most = max(most, f1)
        else:
            a = x1
            x1 = x2
            f1 = f2
            x2 = a + golden * (b - a)
            f2, outline = _ask_at(S, now, end, rows, pairs, c, r, h, u0, line, floor, x2, outline, scratch)
            most = max(most, f2)
    return most, outline


@njit(cache=True)
def _ask_at(S, now, end, rows, pairs, c, r, h, u0, line, floor, f, outline, scratch):
    """``_instant_ask`` of row ``r`` at the fraction ``f`` of the step, its pair's manifold
    found there on the solved motion (the pose under constant acceleration: moved on at the
    velocity ``now`` plus half of what the step adds by then); returns it and the outline
    scratch."""
    if not 0.0 < f < 1.0:
        return 0.0, outline
    found, outline = _moved(S.F, S.I, S.OL, S.OB, now + (end - now) * (0.5 * f), pairs, c, f * h, outline, scratch)
    return _instant_ask(rows, r, scratch, found, f * h, h, u0, line, floor), outline


@njit(cache=True)
def _solved_arcs(S, now, end, rows, pairs, count, h, ends):
    """Each point's ``ARC`` found again on the step's solved motion, so that the push-out
    holds its gap at the step's end and inside it; each turning pair's point at the end in
    ``ends`` (``END_VALID`` 1, its point and normal there, where a polygon of the pair turns
    by more than ``END_TURN`` over the step and the point's features stay; 0 for the others:
    a point whose features changed is held by the pair's deepest, which may be
    the other row's too).

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
    asks for the largest of these, found between the instants either side of the one that
    asked most (``_most_asked``). A gap that closes and opens again within the step (a
    circle sliding at 0.7 m/s on a polygon that turns under it at 130 rad/s^2, corpus scene
    15: 7.4e-6 at mid-step) is so held where it asks most. Where the push-out holds the
    point at the end in a row of its own (``ends``), what the instants ask is the row's
    own, ``ASKED`` (a lift speed at its point, which is nearer the instants' poses than the
    end's); else it is in ``ARC``."""
    F = S.F
    I = S.I
    OL = S.OL
    OB = S.OB
    for r in range(count):
        rows[r, CLOSABLE] = -math.inf
        rows[r, ASKED] = 0.0
        ends[r, END_VALID] = 0.0
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
    scratch = np.empty((4, NCOLUMNS))
    fine_found = np.zeros(FEATURE_INSTANTS - 1, dtype=np.int64)
    c = 0
    while c < count:
        d = _pair_end(pairs, count, c)
        if not _turning_pair(I, mean, pairs, c):
            c = d
            continue  # the straight lines are the motion
        at_full, outline = _moved(F, I, OL, OB, mean, pairs, c, h, outline, full)
        turn = h * _turning_rate(I, mean, pairs, c)
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
            if e >= 0 and full[e, KEY] == rows[r, KEY] and turn > END_TURN:
                ends[r, END_VALID] = 1.0
                ends[r, END_PX] = full[e, PX]
                ends[r, END_PY] = full[e, PY]
                ends[r, END_NX] = full[e, NX]
                ends[r, END_NY] = full[e, NY]
            floor = min(rows[r, SEPARATION], 0.0)
            asked = 0.0  # the end displacement the instants inside ask of the lift
            at = 0.0  # where (a fraction of the step) and between which sampled instants
            below = 0.0
            above = 1.0
            closable = -math.inf
            for k in range(len(STEP_INSTANTS)):
                s = STEP_INSTANTS[k] * h
                ask = _instant_ask(rows, r, inside[k], found[k], s, h, u0, line, floor)
                if ask > asked:
                    asked = ask
                    at = STEP_INSTANTS[k]
                    below = STEP_INSTANTS[k - 1] if k > 0 else 0.0
                    above = STEP_INSTANTS[k + 1] if k + 1 < len(STEP_INSTANTS) else 1.0
                closable = max(closable, _closable_at(rows, r, inside[k], found[k], s, h, floor))
            if changed:
                for k in range(FEATURE_INSTANTS - 1):
                    f = (k + 1.0) / FEATURE_INSTANTS
                    ask = _instant_ask(rows, r, fine[k], fine_found[k], f * h, h, u0, line, floor)
                    if ask > asked:
                        asked = ask
                        at = f
                        below = f - 1.0 / FEATURE_INSTANTS
                        above = f + 1.0 / FEATURE_INSTANTS
                    closable = max(closable, _closable_at(rows, r, fine[k], fine_found[k], f * h, h, floor))
            rows[r, CLOSABLE] = min(closable, 0.0)
            if asked > 0.0:
                most, outline = _most_asked(S, now, end, rows, pairs, c, r, h, u0, line, floor, below, above,
                                            outline, scratch)
                asked = max(asked, most)
                if ends[r, END_VALID] != 0.0:
                    rows[r, ASKED] = 2.0 * asked / h  # the row's own: the end has a row of its own
                else:
                    rows[r, ARC] = min(rows[r, ARC], -asked - line)
        c = d


@njit(cache=True, inline="always")
def _end_arms(F, now, end, pairs, p, h, px, py):
    """The lever arms of the point ``(px, py)`` at the step's end, for the bodies of row
    ``p`` of ``pairs``, from their centres where the solved motion brings them (moved on at
    the mean of the velocities ``now`` and at the ``end``)."""
    ka = pairs[p, 0]
    kb = pairs[p, 1]
    i = pairs[p, 2]
    j = pairs[p, 3]
    rax = px - (F[i, L.X] + 0.5 * h * (now[ka, 0] + end[ka, 0]))
    ray = py - (F[i, L.Y] + 0.5 * h * (now[ka, 1] + end[ka, 1]))
    rbx = px - F[j, L.X]
    rby = py - F[j, L.Y]
    if kb >= 0:
        rbx -= 0.5 * h * (now[kb, 0] + end[kb, 0])
        rby -= 0.5 * h * (now[kb, 1] + end[kb, 1])
    return rax, ray, rbx, rby
