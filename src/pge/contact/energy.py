"""The island step's energy: what its contact forces and its push-out may add to the
island's energy, accounted per part (the bodies the step's forces join: ``_parts``,
union-find over the rows that join them).

The impact stage keeps of its restitution the share that raises no part's kinetic energy
(``_blend``). The energy stage (``_no_gain``): over the step the contact forces may do no
positive work, and the energy may rise nowhere inside the step; where they would, the part's
velocities and spins beyond its rigid motion (``_rigid_motion``) are scaled back
(``_scale_beyond``). The lift's payment (``_lift_paid``): the potential energy a push-out
lift gains against the bodies' accelerations is paid from the part's motion at the step's
end beyond the motion it keeps (``_kept_motion``).
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
    LAMBDA_N,
    LAMBDA_T,
)
from pge.core import layout as L
from pge.core.tuning import (
    ENERGY_ROUNDING,
    PARALLEL,
)


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
def _kept_motion(F, members, velocities, labels, grounded, rows, pairs, count, h):
    """Each body's velocity and spin in the motion its part keeps whatever its bodies do to
    each other: the part's rigid motion (``_rigid_motion``) where no force joins it to a fixed
    body; where forces do, only its momentum along a fixed face that presses it without
    friction (every such press frictionless, their normals parallel), as a translation, unless
    that translation would reach another fixed body a point of the part touches within the
    step ``h`` (a box resting on ice against a wall keeps no momentum into the wall); else
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
    for c in range(count):
        if pairs[c, 1] >= 0:
            continue
        r = labels[pairs[c, 0]]
        if r < 0 or not (free[r] and seen[r]):
            continue
        across = tx[r] * rows[c, NX] + ty[r] * rows[c, NY]
        closing = along[r] / total[r] * across
        if abs(across) > PARALLEL and closing < 0.0 and rows[c, SEPARATION] + h * closing < 0.0:
            free[r] = False
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
    gain out (``_paid_factor``), or as far as that motion holds (``_least_energy``; what is
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
    rigid = _kept_motion(F, members, end, labels, grounded, rows, pairs, count, h)
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
        factor[r] = _paid_factor(relative[r], along[r], relative[r] - along[r] - owed[r])
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
    of its contact forces (``_largest_paying``: the work at factor ``s`` is
    ``relative s^2 - along s - kept``, ``relative`` the kinetic energy of that motion,
    ``along`` what the bodies' own accelerations do on it, ``kept`` what the part may have
    beside it); 1 (unchanged) where no factor in [0, 1] can (the float)."""
    factor = _largest_paying(relative, along, kept)
    return factor if factor >= 0.0 else 1.0


@njit(cache=True, inline="always")
def _paid_factor(relative, along, kept):
    """The factor on a part's motion beyond the motion it keeps that pays its lift's debt
    with the least change (``_largest_paying``; ``kept`` is ``relative - along`` less the
    debt, so that ``s = 1`` owes it); where no factor pays it all, the one of least energy
    (``_least_energy``)."""
    factor = _largest_paying(relative, along, kept)
    return factor if factor >= 0.0 else _least_energy(relative, along)


@njit(cache=True, inline="always")
def _largest_paying(relative, along, kept):
    """The largest ``s`` in [0, 1] at which ``relative s^2 - along s`` (a part's energy at the
    step's end as a function of the factor on its motion beyond the motion it keeps, less
    what does not depend on ``s``) is at most ``kept``: the larger root of
    ``relative s^2 - along s - kept``, in the form that does not cancel, or 1 where ``s = 1``
    already is; -1 where no ``s`` in [0, 1] is. ``kept`` may be negative where the bodies'
    own accelerations work on that motion (``along > 0``, gravity on a falling body): the
    parabola then dips below zero, and a root may still lie in [0, 1]."""
    if relative <= 0.0:
        return 1.0 if -along <= kept else -1.0
    disc = along * along + 4.0 * relative * kept
    if disc < 0.0:
        return -1.0
    root = math.sqrt(disc)
    larger = (along + root) / (2.0 * relative) if along >= 0.0 else 2.0 * kept / (root - along)
    smaller = (along - root) / (2.0 * relative)
    if larger < 0.0 or smaller > 1.0:
        return -1.0
    return min(larger, 1.0)


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
