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
from pge.contact.rows import (
    ARC,
    CLOSABLE,
    LAMBDA_N,
    LAMBDA_T,
    MU,
    TARGET,
    _relative,
)
from pge.contact.solve import _solve
from pge.core import layout as L
from pge.core.tuning import (
    ISLAND_ITERATIONS,
    LCP_LIMIT,
    PUSH_RATE,
    PUSH_SLOP,
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
