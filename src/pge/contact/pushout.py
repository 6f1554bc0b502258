"""The island step's push-out: overlaps moved out as a displacement over the step.

Overlaps are moved out by ``PUSH_RATE`` of their depth, as a displacement over the step: a
velocity change at its start taken back by an equal and opposite one spread over it, so the
velocities at the step's end are the force stage's (``_push_out``, solved without friction by
``pge.contact.solve``). A lift never takes a gap below its start inside the step
(``_lift_floor``), nor a turning pair's gap below what its arcs allow (``ARC``,
``CLOSABLE``: ``pge.contact.arcs``).
"""

from __future__ import annotations

import math

import numpy as np

from pge._jit_cache import njit
from pge.contact.manifold import (
    NX,
    NY,
    SEPARATION,
)
from pge.contact.arcs import END_NX, END_NY, END_PX, END_PY, END_VALID, _end_arms
from pge.contact.rows import (
    ARC,
    ASKED,
    CLOSABLE,
    LAMBDA_N,
    LAMBDA_T,
    MU,
    TARGET,
    _lever_arms,
    _pair_constants,
    _relative,
)
from pge.contact.solve import _solve
from pge.core import layout as L
from pge.core.tuning import (
    ISLAND_ITERATIONS,
    LCP_LIMIT,
    PUSH_RATE,
    PUSH_SLOP,
    SOLVE_TOLERANCE,
)


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


@njit(cache=True, inline="always")
def _same_pair(pairs, a, b):
    """Whether rows ``a`` and ``b`` are of the same pair of bodies."""
    return pairs[a, 2] == pairs[b, 2] and pairs[a, 3] == pairs[b, 3]


@njit(cache=True)
def _with_ends(F, now, end, rows, pairs, count, h, ends, need, end_need, twin):
    """The push-out's rows: each row at its point with its ``need``, but for a turning pair's
    point found at the step's end (``ends``) a row there instead, at its normal and lever
    arms there (``_end_arms``), with ``end_need``, and the row at its point as well only
    where ``twin`` says; the pairs' constants follow. Returns the rows, their pairs and their
    number.

    A point's two rows are never one block of the solve (two points of a pair solved
    together, which the same point twice would make singular): the end rows go after the
    others, or before them where the row just across is the same point's; where both would
    be (the point's two rows are all there is), its end row alone holds it, with the larger
    of its two needs."""
    own = np.empty(count, dtype=np.int64)  # the rows kept at their points
    ended = np.empty(count, dtype=np.int64)  # ... and those moved to the step's end
    n_own = 0
    n_end = 0
    for r in range(count):
        if ends[r, END_VALID] == 0.0 or twin[r]:
            own[n_own] = r
            n_own += 1
        if ends[r, END_VALID] != 0.0:
            ended[n_end] = r
            n_end += 1
    total = n_own + n_end
    pushing = np.empty((total, rows.shape[1]))
    pushed = np.empty((total, pairs.shape[1]), dtype=pairs.dtype)
    after = not _twins_meet(pairs, own, n_own, ended, n_end)
    if not after and _twins_meet(pairs, ended, n_end, own, n_own):
        pushing[0] = rows[own[0]]
        pushed[0] = pairs[own[0]]
        pushing[0, TARGET] = max(need[own[0]], end_need[own[0]])
        _at_end(F, now, end, pushing, pushed, 0, h, ends, own[0])
        _pair_constants(pushing, pushed, 1)
        return pushing, pushed, 1
    at = 0 if after else n_end
    for k in range(n_own):
        r = own[k]
        pushing[at + k] = rows[r]
        pushed[at + k] = pairs[r]
        pushing[at + k, TARGET] = need[r]
    at = n_own if after else 0
    for k in range(n_end):
        r = ended[k]
        pushing[at + k] = rows[r]
        pushed[at + k] = pairs[r]
        pushing[at + k, TARGET] = end_need[r]
        _at_end(F, now, end, pushing, pushed, at + k, h, ends, r)
    _pair_constants(pushing, pushed, total)
    return pushing, pushed, total


@njit(cache=True)
def _twins_meet(pairs, first, n_first, then, n_then):
    """Whether the rows ``first`` (indices of rows) followed by the rows ``then`` would put
    one point's two rows in one block: the last of ``first``, not already in a block with
    the row before it, and the first of ``then`` are the same row."""
    if n_first == 0 or n_then == 0:
        return False
    last = first[n_first - 1]
    alone = n_first == 1 or not _same_pair(pairs, first[n_first - 2], last)
    return alone and last == then[0]


@njit(cache=True, inline="always")
def _at_end(F, now, end, pushing, pushed, k, h, ends, r):
    """Row ``k`` of ``pushing`` moved to the point ``ends`` holds for row ``r``: its normal
    and lever arms at the step's end."""
    pushing[k, NX] = ends[r, END_NX]
    pushing[k, NY] = ends[r, END_NY]
    rax, ray, rbx, rby = _end_arms(F, now, end, pushed, k, h, ends[r, END_PX], ends[r, END_PY])
    _lever_arms(pushing, k, rax, ray, rbx, rby)


@njit(cache=True)
def _push_out(F, now, end, rows, pairs, count, h, nominal, down_x, down_y, ends):
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
    a speed, stays within ``2 PUSH_RATE |e| / nominal``) where ``e < 0`` and the point
    overlapped as deep at the step's start; beyond its start's overlap, all of it (the end
    line of a point touching at the start goes below zero only where the lift's payment or
    the energy stage slowed its bodies: corpus scene 107, a triangle on a peg paid to rest,
    ended its step 3e-8 deep, a fifth of its line's 1.5e-7); closed by at most
    ``e`` where ``e >= 0``, and no deeper than its start anywhere within the step
    (``_lift_floor``: a lift is front-loaded, the forces' opening may come late). A point's
    ``ARC`` (``_midstep_rows``: what a turning body's contact adds to the straight line's
    end separation) is an overlap the step would make, not one it found: all of it is moved
    out at this step. Nothing is solved unless some point would overlap by more than
    ``PUSH_SLOP`` of its pair's smaller reach. Returns the lifts (all zero then) and the
    sweeps taken.

    A turning pair's point is held twice (``_with_ends``). At the step's end, at its normal
    and lever arms there (``ends``, from ``_solved_arcs``), for its gap there: a contact
    rolling over a round peg turns its normal by about a hundredth of a radian a step, and a
    lift solved along the start's normal moved the point sideways into the peg by its
    tangential part times that turn (corpus scene 107: a triangle on a peg ended every step
    3.7e-8 deep where the push-out's lines said 7e-9). And where its row is (mid-step), for
    the bounds inside the step (``_lift_floor``, ``CLOSABLE``): a polygon spinning at 10
    rad/s turns its corner's lever arm over a step, and held at the end's arm alone a lift
    closed the corner into the floor by 2e-8 a third of the way into the step (scene 97)."""
    m = now.shape[0]
    lift = np.zeros((m, 3))
    need = np.empty(count)
    end_need = np.empty(count)
    largest = 0.0
    for c in range(count):
        ux, uy = _relative(now, pairs, rows, c)
        wx, wy = _relative(end, pairs, rows, c)
        moved = 0.5 * h * ((ux + wx) * rows[c, NX] + (uy + wy) * rows[c, NY])
        left = rows[c, SEPARATION] + moved
        arc = rows[c, ARC]
        if left < 0.0:
            # PUSH_RATE of the overlap found at the start (or of the line's end, if less);
            # all of what the step itself would add (a payment's slowing, the energy stage's
            # scaling: a point touching at the start is not left overlapping at the end)
            kept = (1.0 - PUSH_RATE * h / nominal) * max(left, min(rows[c, SEPARATION], 0.0))
            held = 2.0 * (kept - left - arc) / h
        else:
            held = -2.0 * (left + arc) / h
        un = ux * rows[c, NX] + uy * rows[c, NY]
        wn = wx * rows[c, NX] + wy * rows[c, NY]
        # never a push for this: a point whose own line dips (closing now) is the force
        # stage's, and a lift does not close it further; nor further than its gaps on the
        # solved motion allow at the step's instants (a turning pair's, CLOSABLE)
        inside = max(min(_lift_floor(rows[c, SEPARATION], un, wn, h), 0.0), rows[c, CLOSABLE])
        if ends[c, END_VALID] != 0.0:
            need[c] = max(inside, rows[c, ASKED])
            end_need[c] = held
        elif left < 0.0:
            need[c] = held
        else:
            need[c] = max(held, inside)
        reach = min(F[pairs[c, 2], L.REACH], F[pairs[c, 3], L.REACH])
        if left + arc < -PUSH_SLOP * reach or 0.5 * h * rows[c, ASKED] > PUSH_SLOP * reach:
            largest = max(largest, held, rows[c, ASKED])
    if not largest > 0.0:
        return lift, 0
    # A turning point's row at its point holds the bounds inside the step; solved first
    # without those that ask for nothing, and again with any whose bound the lift breaks.
    twin = np.zeros(count, dtype=np.bool_)
    for c in range(count):
        twin[c] = ends[c, END_VALID] != 0.0 and rows[c, ASKED] > 0.0
    sweeps = 0
    for _ in range(2):
        pushing, pushed, total = _with_ends(F, now, end, rows, pairs, count, h, ends, need, end_need, twin)
        pushing[:, LAMBDA_N] = 0.0
        pushing[:, LAMBDA_T] = 0.0
        pushing[:, MU] = 0.0
        lift[:] = 0.0
        sweeps += _solve(F, lift, pushing, pushed, total, largest, down_x, down_y, ISLAND_ITERATIONS, LCP_LIMIT)
        broken = False
        for c in range(count):
            if ends[c, END_VALID] != 0.0 and not twin[c]:
                lx, ly = _relative(lift, pairs, rows, c)
                # a lift closes the point by at most h / 2 times its speed's shortfall: held
                # where that could pass the slop the push-out leaves
                slop = 2.0 * PUSH_SLOP * min(F[pairs[c, 2], L.REACH], F[pairs[c, 3], L.REACH]) / h
                if lx * rows[c, NX] + ly * rows[c, NY] < need[c] - max(slop, SOLVE_TOLERANCE * largest):
                    twin[c] = True
                    broken = True
        if not broken:
            break
    return lift, sweeps
