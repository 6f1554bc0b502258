"""Resting and sliding contact: how bouncing ends without a Zeno storm.

With elasticity below 1 under gravity a bouncing body would collide
infinitely often in finite time. When a collision leaves two bodies closing
so slowly that the next bounce would rise less than ``P[REST_HEIGHT]`` times
the upper body's bounding radius, and the free accelerations press them together, the
upper body (the *rider*) comes to rest on the other (its *support*, which
must be fixed or resting itself): their relative normal velocity is set to
zero and the normal part of the rider's relative acceleration is cancelled.
The rider then slides along the contact with constant acceleration (Coulomb
friction decelerating it), so its motion stays closed-form.

A flat contact (an edge carries the other body) is left when the contact
region slides off the end of the edge (a LEAVE event); a sliding contact with
friction stops when the relative tangential velocity reaches zero (a
STOP_SLIDING event), after which static friction may hold it. On a curved
contact (circle on circle, circle on a corner) a balanced body (no tangential
relative motion) rests for good; one moving sideways slides along the tangent
line for a short step (``CURVED_STEP`` of its bounding radius, never into the
other body) and is then released, so rolling over a corner becomes a short
sequence of steps until it flies off. Any change to a support's motion
releases its riders, which settle again at once.
"""

from __future__ import annotations

import math

from pge._jit_cache import njit

from pge.core import layout as L
from pge.core.grid import gather
from pge.core.motion import advance, orient, spin_at, state_at
from pge.core.overlap import nearest_normal, overlap_depth
from pge.core.predict import STILL_ULPS
from pge.core.queue import push
from pge.core.response import apply_impulse, contact_response
from pge.numerics.roots import first_descent_quadratic

_INF = math.inf
_BALANCE_TOLERANCE = 1e-12
#: a body pressed onto a curved feature slides along the tangent for this many bounding
#: radii before it is released and the contact is looked at afresh.
CURVED_STEP = 0.02
CURVED_STEPPING = -2  # EDGE_OWNER value of a curved contact that is being stepped over
#: settling flat may not push a polygon into a neighbour by more than this many bounding radii
_TURN_OVERLAP = 1e-12


@njit(cache=True, inline="always")
def grounded(I, s):
    """True if body ``s`` cannot give way: fixed, asleep, or resting on a grounded body."""
    return I[s, L.FIXED] != 0 or I[s, L.SUPPORT] >= 0 or I[s, L.SLEEP_NEXT] >= 0


@njit(cache=True, inline="always")
def combine(ea, eb, rule):
    """Combine two bodies' coefficients: 0 min, 1 max, 2 mean, 3 geometric mean."""
    if rule == 0:
        return min(ea, eb)
    if rule == 1:
        return max(ea, eb)
    if rule == 2:
        return 0.5 * (ea + eb)
    if ea == eb:
        return ea
    return math.sqrt(ea * eb)


@njit(cache=True)
def relative_tangential(S, r, t):
    """Rider ``r``'s tangential velocity and free tangential acceleration relative to its
    support, and the pressing normal acceleration, at time ``t``: ``(vt, at, an)``."""
    F = S[0]
    I = S[1]
    s = I[r, L.SUPPORT]
    mx = F[r, L.REST_NX]
    my = F[r, L.REST_NY]
    _, _, rvx, rvy = state_at(F, r, t)
    _, _, svx, svy = state_at(F, s, t)
    rel_ax = F[r, L.FREE_AX] - F[s, L.AX]
    rel_ay = F[r, L.FREE_AY] - F[s, L.AY]
    vt = -(rvx - svx) * my + (rvy - svy) * mx
    at = -rel_ax * my + rel_ay * mx
    an = rel_ax * mx + rel_ay * my
    return vt, at, an


@njit(cache=True, inline="always")
def rolls(F, I, r, mu):
    """Whether resting rider ``r``'s spin takes part in its friction (friction ``mu``): a
    circle on a flat contact with an immovable body (fixed or asleep), which rolls or skids.
    A polygon rests without turning, and a circle on a curved contact, on a body that can
    move, or without friction keeps its spin."""
    s = I[r, L.SUPPORT]
    return (
        mu > 0.0
        and I[r, L.KIND] == 0
        and I[r, L.EDGE_OWNER] >= 0
        and F[r, L.INV_INERTIA] > 0.0
        and (I[s, L.FIXED] != 0 or I[s, L.SLEEP_NEXT] >= 0)
    )


@njit(cache=True, inline="always")
def roll_ratio(F, r):
    """``m R^2 / I`` of circle ``r`` (2 for a uniform disc): a rolling circle's tangential
    acceleration is ``ratio / (1 + ratio)`` of a frictionless slide's."""
    radius = F[r, L.RADIUS]
    return radius * radius * F[r, L.INV_INERTIA] / F[r, L.INV_MASS]


@njit(cache=True)
def contact_slip(S, r, t):
    """Resting rider ``r``'s slip at ``t``: the velocity of its contact point along the tangent
    relative to its support, ``vt - omega R`` for a rolling circle (``rolls``), ``vt`` for
    any other body; and whether its spin takes part: ``(slip, rolling)``. A rolling circle's
    slip within rounding of its speeds (``STILL_ULPS``) is exactly 0."""
    F = S[0]
    I = S[1]
    vt, _, _ = relative_tangential(S, r, t)
    mu = combine(F[r, L.FRICTION], F[I[r, L.SUPPORT], L.FRICTION], S[4][L.FRICTION_RULE])
    if not rolls(F, I, r, mu):
        return vt, False
    return rolling_slip(F, r, vt, t), True


@njit(cache=True, inline="always")
def rolling_slip(F, r, vt, t):
    """The slip ``vt - omega R`` at ``t`` of circle ``r`` whose centre moves at ``vt`` along
    its rest's tangent relative to its support; exactly 0 within rounding of the two terms."""
    turn = spin_at(F, r, t) * F[r, L.RADIUS]
    slip = vt - turn
    if abs(slip) <= STILL_ULPS * (abs(vt) + abs(turn)):
        return 0.0
    return slip


@njit(cache=True, inline="always")
def mark_pile(S, x):
    """Note that the pile holding resting body ``x`` must be solved again before the event
    ends (``pge.core.pile.settle_piles``): a rider arrived, left or changed on it."""
    Q = S[4]
    piles = S[19]
    k = Q[L.PILES_N]
    if k > 0 and piles[k - 1] == x:
        return
    if k < piles.shape[0]:
        piles[k] = x
        Q[L.PILES_N] = k + 1


@njit(cache=True)
def settle_acceleration(S, r, t):
    """Set resting rider ``r``'s acceleration from its free one, its support's and friction.

    This takes the support's acceleration as given: exact on an immovable
    support; in a pile the whole pile is solved again before the event ends
    (``pge.core.pile``), so that riders load their supports. Returns False
    when the free accelerations no longer press the two together (the caller
    then releases the rider).
    """
    F = S[0]
    I = S[1]
    Q = S[4]
    s = I[r, L.SUPPORT]
    mark_pile(S, r)
    vt, at, an = relative_tangential(S, r, t)
    if not an < 0.0:
        return False
    mu = combine(F[r, L.FRICTION], F[s, L.FRICTION], Q[L.FRICTION_RULE])
    limit = -mu * an
    F[r, L.ALPHA] = 0.0  # r is at t: its spin changes from now on
    if rolls(F, I, r, mu):
        # A circle on a face: friction acts at its contact point, whose slip is vt - omega R,
        # and turns it as it pushes it (torque -R f along the tangent).
        slip = rolling_slip(F, r, vt, t)
        ratio = roll_ratio(F, r)
        radius = F[r, L.RADIUS]
        if slip == 0.0 and abs(at) <= limit * (1.0 + ratio):
            I[r, L.REST_MODE] = L.STUCK  # rolls: its contact point stays on the support
            at_eff = at * ratio / (1.0 + ratio)
            F[r, L.ALPHA] = at_eff / radius
        else:
            I[r, L.REST_MODE] = L.SLIDING  # skids: friction against the slip
            push = math.copysign(limit, at if slip == 0.0 else slip)
            at_eff = at - push
            F[r, L.ALPHA] = push * ratio / radius
    elif vt == 0.0:
        if abs(at) <= limit:
            I[r, L.REST_MODE] = L.STUCK
            at_eff = 0.0
        else:
            I[r, L.REST_MODE] = L.SLIDING
            at_eff = at - math.copysign(limit, at)
    else:
        I[r, L.REST_MODE] = L.SLIDING
        at_eff = at - math.copysign(limit, vt)
    mx = F[r, L.REST_NX]
    my = F[r, L.REST_NY]
    F[r, L.AX] = F[s, L.AX] - at_eff * my
    F[r, L.AY] = F[s, L.AY] + at_eff * mx
    return True


@njit(cache=True)
def _settle_turning(S, r, s, mx, my, owner, px, py, vn, an, height, t):
    """Let turning polygon ``r`` come to rest flat on ``s``'s edge, if it qualifies.

    A rocking polygon would strike its support ever faster, like a bouncing
    ball. It settles when the edge of ``r`` next to the contact corner lies
    within ``height`` of the support's edge (its far end is lifted by no
    more) and its remaining normal and turning energy could lift it no higher
    than ``height``. It is then turned about the contact corner until that
    edge lies flat, and stops turning, unless the turn would push it into a
    neighbour. Returns True if it settled.
    """
    F = S[0]
    I = S[1]
    OL = S[2]
    if owner != s:
        return False  # the support touches r with a corner: r balances on a point
    start = I[r, L.OUTLINE_START]
    n = I[r, L.OUTLINE_N]
    cx = F[r, L.X]
    cy = F[r, L.Y]
    corner = 0
    best = _INF
    for k in range(n):
        d = math.hypot(cx + OL[start + k, 0] - px, cy + OL[start + k, 1] - py)
        if d < best:
            best = d
            corner = k
    # The edge beside the corner whose outward normal is closest to -m.
    before = (corner + n - 1) % n
    if -(OL[start + corner, 2] * mx + OL[start + corner, 3] * my) >= -(OL[start + before, 2] * mx + OL[start + before, 3] * my):
        edge_row = start + corner
        far = start + (corner + 1) % n
    else:
        edge_row = start + before
        far = start + before
    lift = (OL[far, 0] - OL[start + corner, 0]) * mx + (OL[far, 1] - OL[start + corner, 1]) * my
    if not lift <= height:
        return False
    inertia = F[r, L.INV_MASS] / F[r, L.INV_INERTIA] if F[r, L.INV_INERTIA] > 0.0 else 0.0
    omega = F[r, L.OMEGA]
    energy = 0.5 * omega * omega * inertia
    if vn > 0.0:
        energy += 0.5 * vn * vn
    if not energy <= -an * height:
        return False
    # Turn by delta about the corner so that the edge's normal becomes -m.
    enx = OL[edge_row, 2]
    eny = OL[edge_row, 3]
    delta = math.atan2(-(enx * my - eny * mx), -(enx * mx + eny * my))
    qx = cx + OL[start + corner, 0]
    qy = cy + OL[start + corner, 1]
    c = math.cos(delta)
    sn = math.sin(delta)
    ox = cx - qx
    oy = cy - qy
    new_x = qx + c * ox - sn * oy
    new_y = qy + sn * ox + c * oy
    # Turning must not raise the centroid against the pressing acceleration by more
    # than the spin it stops could pay for (else the body tips the other way).
    if -an * ((new_x - cx) * mx + (new_y - cy) * my) > 0.5 * omega * omega * inertia:
        return False
    if not turn_if_clear(S, r, qx, qy, c, sn, delta, 0.0, 0.0, s, -1.0, t):
        return False
    F[r, L.OMEGA] = 0.0
    return True


@njit(cache=True, inline="always")
def lowest_along(OL, start, n, mx, my):
    """The least ``v . m`` over a polygon's outline rows ``start ..`` (its vertices relative to
    the centroid): how far its lowest corners reach towards a support below (normal ``m``)."""
    lowest = _INF
    for k in range(start, start + n):
        lowest = min(lowest, OL[k, 0] * mx + OL[k, 1] * my)
    return lowest


@njit(cache=True)
def turn_if_clear(S, x, qx, qy, c, sn, delta, slide_x, slide_y, other, other_tolerance, t):
    """Turn body ``x`` by ``delta`` (``c``, ``sn`` its cosine and sine) about the point ``q``,
    which stays put, then move it by ``slide``, unless that pushes it into a neighbour
    (other than ``other``) by more than 1e-12 of their sizes or, when ``other_tolerance >= 0``,
    into ``other`` by more than that many of their sizes; then it is left as it was.
    Returns whether it moved."""
    F = S[0]
    I = S[1]
    old_x = F[x, L.X]
    old_y = F[x, L.Y]
    old_angle = F[x, L.ANGLE]
    ox = old_x - qx
    oy = old_y - qy
    F[x, L.X] = qx + c * ox - sn * oy + slide_x
    F[x, L.Y] = qy + sn * ox + c * oy + slide_y
    F[x, L.ANGLE] = old_angle + delta
    orient(F, I, S[2], S[18], x, t)
    if pushes_into_neighbour(S, x, other) or (
        other_tolerance >= 0.0 and overlap_depth(S, x, other) > other_tolerance * (F[x, L.REACH] + F[other, L.REACH])
    ):
        F[x, L.X] = old_x
        F[x, L.Y] = old_y
        F[x, L.ANGLE] = old_angle
        orient(F, I, S[2], S[18], x, t)
        return False
    return True


@njit(cache=True)
def _on_one_corner(S, r, mx, my):
    """Whether polygon ``r`` meets a support below it (unit normal ``m`` from the support
    towards ``r``) with a single corner rather than an edge."""
    F = S[0]
    I = S[1]
    OL = S[2]
    start = I[r, L.OUTLINE_START]
    n = I[r, L.OUTLINE_N]
    lowest = lowest_along(OL, start, n, mx, my)
    tolerance = 1e-9 * F[r, L.REACH]
    count = 0
    for k in range(start, start + n):
        if OL[k, 0] * mx + OL[k, 1] * my <= lowest + tolerance:
            count += 1
    return count == 1


@njit(cache=True)
def pushes_into_neighbour(S, r, s):
    """Whether ``r``, just turned by hand, overlaps a body other than its support ``s``.

    The turn moves ``r``'s corners by up to its bounding radius, so the search
    box is widened by that much for the look-up (and restored).
    """
    F = S[0]
    reach = F[r, L.REACH]
    box = (F[r, L.BOX_X0], F[r, L.BOX_Y0], F[r, L.BOX_X1], F[r, L.BOX_Y1])
    F[r, L.BOX_X0] -= reach
    F[r, L.BOX_Y0] -= reach
    F[r, L.BOX_X1] += reach
    F[r, L.BOX_Y1] += reach
    n = gather(S, r)
    F[r, L.BOX_X0], F[r, L.BOX_Y0], F[r, L.BOX_X1], F[r, L.BOX_Y1] = box
    scratch = S[15]
    for k in range(n):
        j = scratch[k]
        if j != s and overlap_depth(S, r, j) > _TURN_OVERLAP * (reach + F[j, L.REACH]):
            return True
    return False


@njit(cache=True)
def _wedged(S, r, s, ax, ay, height, loose, t):
    """Whether rider ``r``, resting on ``s`` with acceleration ``(ax, ay)``, would be pressed
    into another body it touches (within ``height``) and is not leaving (to rounding):
    wedged between two bodies, it has no single support to rest on.

    Only a neighbour that cannot give way (fixed, resting or asleep) wedges a rider, unless
    the rest is ``loose`` (the support's face moves along its normal, so that any push from
    the side releases the rider again); a free body leaning on a rider is its own business."""
    F = S[0]
    I = S[1]
    scratch = S[15]
    n = gather(S, r)
    _, _, rvx, rvy = state_at(F, r, t)
    for k in range(n):
        j = scratch[k]
        if j == s or not (loose or grounded(I, j)):
            continue
        nx, ny, depth = nearest_normal(S, r, j)
        if depth < -height:
            continue
        an = (ax - F[j, L.AX]) * nx + (ay - F[j, L.AY]) * ny
        if not an < 0.0:
            continue
        _, _, jvx, jvy = state_at(F, j, t)
        vn = (rvx - jvx) * nx + (rvy - jvy) * ny
        if vn <= STILL_ULPS * (math.hypot(rvx, rvy) + math.hypot(jvx, jvy)):
            return True  # not leaving it (a neighbour sliding away is stopped by its friction)
    return False


@njit(cache=True)
def base_of(I, x):
    """The base of the pile holding resting body ``x``: the body of its chain of supports
    that rests on an immovable one (``pge.core.pile``)."""
    while I[I[x, L.SUPPORT], L.SUPPORT] >= 0:
        x = I[x, L.SUPPORT]
    return x


@njit(cache=True)
def presses_into_neighbour(S, p, dx, dy, accelerations, t):
    """Whether resting body ``p``, moved along ``(dx, dy)``, would press into a body it touches
    (within the rest height) and is not leaving, that cannot give way: fixed, asleep, or
    resting in another pile. With ``accelerations``, ``(dx, dy)`` is an acceleration (the
    neighbour's own is taken off) and ``p`` must not be leaving the neighbour; else it is a
    change of ``p``'s velocity, after which ``p`` must not be leaving it.

    Such a neighbour pushes back with whatever force it takes (a wedge on the floor pushed
    into a wall by its rider stays put), which neither a pile's solve nor a rest's plastic
    impulse knows of: the caller holds ``p`` instead."""
    F = S[0]
    I = S[1]
    scratch = S[15]
    s = I[p, L.SUPPORT]
    base = base_of(I, p)
    height = S[3][L.REST_HEIGHT] * F[p, L.REACH]
    _, _, pvx, pvy = state_at(F, p, t)
    n = gather(S, p)
    for k in range(n):
        j = scratch[k]
        if j == s or I[j, L.SUPPORT] == p or not grounded(I, j):
            continue
        if I[j, L.SUPPORT] >= 0 and base_of(I, j) == base:
            continue
        nx, ny, depth = nearest_normal(S, p, j)
        if depth < -height:
            continue
        press = dx * nx + dy * ny
        if accelerations:
            press -= F[j, L.AX] * nx + F[j, L.AY] * ny
        if not press < 0.0:
            continue
        _, _, jvx, jvy = state_at(F, j, t)
        vx = pvx if accelerations else pvx + dx
        vy = pvy if accelerations else pvy + dy
        if (vx - jvx) * nx + (vy - jvy) * ny <= STILL_ULPS * (math.hypot(vx, vy) + math.hypot(jvx, jvy)):
            return True
    return False


@njit(cache=True)
def _leaving_edge_end(S, r, s, owner, edge):
    """Whether the circle of the pair ``r``, ``s`` (the one not owning the carrying edge) lies
    at an end of ``owner``'s edge ``edge`` to rounding (1e-12 of its length) and moves off
    it. Both bodies are at the same reference time."""
    F = S[0]
    I = S[1]
    OL = S[2]
    other = s if owner == r else r
    if I[other, L.KIND] != 0:
        return False
    row = I[owner, L.OUTLINE_START] + edge
    tx = -OL[row, 3]
    ty = OL[row, 2]
    u = (F[other, L.X] - F[owner, L.X] - OL[row, 0]) * tx + (F[other, L.Y] - F[owner, L.Y] - OL[row, 1]) * ty
    along = (F[other, L.VX] - F[owner, L.VX]) * tx + (F[other, L.VY] - F[owner, L.VY]) * ty
    length = OL[row, 4]
    return (u <= 1e-12 * length and along < 0.0) or (u >= (1.0 - 1e-12) * length and along > 0.0)


@njit(cache=True)
def try_rest(S, r, s, mx, my, owner, edge, px, py, t, out, count):
    """Let rider ``r`` come to rest on ``s`` after a bounce, if it qualifies.

    ``(mx, my)`` is the unit contact normal from ``s`` towards ``r`` and
    ``(px, py)`` the contact point; ``owner``/``edge`` name the edge carrying
    a flat contact (``owner = -1`` for a curved one). Both bodies are at time
    ``t``. A turning polygon must first settle flat (``_settle_turning``).
    Returns ``(rested, count)``: whether ``r`` now rests; the bodies whose
    motion changed (``r``, and a movable support with what rested on it) are
    appended to ``out`` from index ``count``.
    """
    F = S[0]
    I = S[1]
    P = S[3]
    if I[r, L.FIXED] != 0 or I[r, L.SUPPORT] >= 0 or not grounded(I, s):
        return False, count
    if I[s, L.KIND] != 0 and F[s, L.OMEGA] != 0.0:
        return False, count
    if owner < 0 and (F[s, L.VX] != 0.0 or F[s, L.VY] != 0.0 or F[s, L.AX] != 0.0 or F[s, L.AY] != 0.0):
        # A moving curved support turns the contact under the rider, which resting with a
        # fixed normal would ignore: carried up the support's face at no cost to the
        # support, it would gain energy. It bounces (the pivot rule) until the support stops.
        return False, count
    rel_vx = F[r, L.VX] - F[s, L.VX]
    rel_vy = F[r, L.VY] - F[s, L.VY]
    rel_ax = F[r, L.FREE_AX] - F[s, L.AX]
    rel_ay = F[r, L.FREE_AY] - F[s, L.AY]
    vn = rel_vx * mx + rel_vy * my
    an = rel_ax * mx + rel_ay * my
    if not an < 0.0:
        return False, count
    height = P[L.REST_HEIGHT] * F[r, L.REACH]
    if vn > 0.0 and vn * vn > -2.0 * an * height:
        return False, count
    loose = abs(F[s, L.VX] * mx + F[s, L.VY] * my) > 1e-12 * math.hypot(F[s, L.VX], F[s, L.VY])
    if _wedged(S, r, s, F[r, L.FREE_AX] - an * mx, F[r, L.FREE_AY] - an * my, height, loose, t):
        # Resting here would press it into a neighbour, and resting there into this one: a
        # body wedged between two would swap supports for ever at one instant. It bounces
        # under the pivot rule instead.
        return False, count
    if owner >= 0 and I[s, L.FIXED] == 0 and _leaving_edge_end(S, r, s, owner, edge):
        # A circle at the very end of a movable support's edge, moving off: it would leave at
        # once, which unloads the support, whose changed acceleration may press the circle
        # back onto the edge's end at the same instant, for ever. It bounces (the pivot rule).
        return False, count
    if I[r, L.KIND] != 0 and (F[r, L.OMEGA] != 0.0 or (owner == s and _on_one_corner(S, r, mx, my))):
        # A polygon on one corner rests only once turned flat (a still one too: balanced on a
        # corner it would never tip).
        if not _settle_turning(S, r, s, mx, my, owner, px, py, vn, an, height, t):
            return False, count
    if owner < 0:
        vt = -rel_vx * my + rel_vy * mx
        at = -rel_ax * my + rel_ay * mx
        if abs(vt) > _BALANCE_TOLERANCE * abs(vn) + 1e-300 or abs(at) > _BALANCE_TOLERANCE * abs(an):
            owner = CURVED_STEPPING
    # Stop the relative normal motion with a plastic impulse, of which a movable support takes
    # its share (then what rests on it is let go first): coming to rest conserves momentum
    # and never gains energy, even on a moving support. A resting support moves only across
    # its own rest normal, whichever way the impulse points: its support takes the rest (a
    # support taken as immovable while it slides would do work on the rider).
    vn = (F[r, L.VX] - F[s, L.VX]) * mx + (F[r, L.VY] - F[s, L.VY]) * my
    keep_s = I[s, L.SUPPORT] >= 0
    turns_s = not keep_s or I[s, L.KIND] == 0
    rsx = px - F[s, L.X]
    rsy = py - F[s, L.Y]
    k_s = 0.0
    if I[s, L.FIXED] == 0 and owner >= 0:  # a curved rest keeps its support still
        k_s = contact_response(F, s, keep_s, turns_s, rsx, rsy, mx, my, -my, mx)[0]
        if keep_s:
            # The impulse would move s across its own rest normal, along vn m: not into a
            # neighbour that holds it (else s bounces off it, letting r go, for ever).
            sx = -F[s, L.REST_NY]
            sy = F[s, L.REST_NX]
            along = F[s, L.INV_MASS] * vn / (F[r, L.INV_MASS] + k_s) * (mx * sx + my * sy)
            if along != 0.0 and presses_into_neighbour(S, s, along * sx, along * sy, False, t):
                k_s = 0.0
    k_r = F[r, L.INV_MASS]
    if k_s > 1e-12 * k_r and vn != 0.0:
        j = -vn / (k_r + k_s)
        svx = F[s, L.VX]
        svy = F[s, L.VY]
        sw = F[s, L.OMEGA]
        if apply_impulse(F, s, keep_s, turns_s, -j * mx, -j * my, rsx, rsy):
            out[count] = s
            count += 1
            if keep_s:
                # Its pile is solved again before the event ends, r's load with it; settled
                # alone now it would drop the loads its other riders put on it, and r could be
                # refused a rest the pile allows (energy seed 766 at 6 bodies: a ball on one face
                # of a box sliding on the floor kept the box pushed towards a ball on its other
                # face; alone it slowed down, the second ball was not pressed on and was let go,
                # a rounding impulse later it touched again, for ever at one instant).
                mark_pile(S, s)
        count = carry_or_release_riders(S, s, svx, svy, sw, out, count, t)
        F[r, L.VX] += j * k_r * mx
        F[r, L.VY] += j * k_r * my
        vn = (F[r, L.VX] - F[s, L.VX]) * mx + (F[r, L.VY] - F[s, L.VY]) * my
    F[r, L.VX] -= vn * mx
    F[r, L.VY] -= vn * my
    F[r, L.REST_NX] = mx
    F[r, L.REST_NY] = my
    I[r, L.SUPPORT] = s
    I[r, L.EDGE_OWNER] = owner
    I[r, L.EDGE_INDEX] = edge
    first = I[s, L.RIDER_HEAD]
    I[r, L.RIDER_NEXT] = first
    I[r, L.RIDER_PREV] = -1
    if first >= 0:
        I[first, L.RIDER_PREV] = r
    I[s, L.RIDER_HEAD] = r
    out[count] = r  # its motion changed either way
    if not settle_acceleration(S, r, t):
        detach(S, r)
        return False, count + 1
    return True, count + 1


@njit(cache=True, inline="always")
def detach(S, r):
    """Take rider ``r`` off its support's rider list and give it its free acceleration
    (a resting support is marked: its pile lost a load)."""
    F = S[0]
    I = S[1]
    s = I[r, L.SUPPORT]
    if s < 0:
        return
    if I[s, L.SUPPORT] >= 0:
        mark_pile(S, s)
    before = I[r, L.RIDER_PREV]
    after = I[r, L.RIDER_NEXT]
    if before >= 0:
        I[before, L.RIDER_NEXT] = after
    else:
        I[s, L.RIDER_HEAD] = after
    if after >= 0:
        I[after, L.RIDER_PREV] = before
    I[r, L.SUPPORT] = -1
    I[r, L.REST_MODE] = L.NOT_RESTING
    I[r, L.EDGE_OWNER] = -1
    F[r, L.AX] = F[r, L.FREE_AX]
    F[r, L.AY] = F[r, L.FREE_AY]
    F[r, L.ALPHA] = 0.0  # every caller has advanced r to now


@njit(cache=True, inline="always")
def append_riders(I, s, out, count):
    """Append the bodies resting directly on ``s`` to ``out`` from ``count``; returns the
    new count."""
    r = I[s, L.RIDER_HEAD]
    while r >= 0:
        out[count] = r
        count += 1
        r = I[r, L.RIDER_NEXT]
    return count


@njit(cache=True)
def release_riders(S, s, out, count, t):
    """Release every body resting on ``s``, directly or through others.

    The released bodies are advanced to ``t`` and appended to ``out`` from
    index ``count``; returns the new count.
    """
    F = S[0]
    I = S[1]
    stats = S[13]
    k = count
    count = append_riders(I, s, out, count)
    while k < count:
        r = out[k]
        k += 1
        advance(F, r, t)
        count = append_riders(I, r, out, count)
        detach(S, r)
        stats[L.S_RELEASES] += 1
    return count


@njit(cache=True)
def resettle_riders(S, s, dvx, dvy, always, out, count, t):
    """Carry the bodies resting on ``s`` (directly or through others) over a velocity change
    ``(dvx, dvy)`` of ``s`` that only rounding could tell from none, releasing the rest.

    A carried rider takes the same change, so its motion relative to its support is
    kept exactly, and its acceleration is settled afresh; one that is no longer pressed
    on is released with all that rests on it. Without ``always`` (``s`` was struck) a
    rider is carried only if the change is within the rounding speed of the rider and
    its support (``STILL_ULPS`` of their speeds, the kernels' band of "not moving"):
    a rest or a collision of rounding size (1e-16) on one rider nudges the support by
    an ulp, and releasing its other riders for that would have them fall back at once,
    rest again and nudge the support back, for ever at one instant. With ``always``
    (``s`` stopped sliding, its motion continuous) every rider is carried. The riders are
    advanced to ``t`` and appended to ``out`` from ``count``; returns the new count.
    """
    F = S[0]
    I = S[1]
    stats = S[13]
    change = math.hypot(dvx, dvy)
    k = count
    count = append_riders(I, s, out, count)
    while k < count:
        r = out[k]
        k += 1
        support = I[r, L.SUPPORT]
        if support < 0:
            continue  # released with its support below
        advance(F, r, t)
        _, _, svx, svy = state_at(F, support, t)
        small = change <= STILL_ULPS * (math.hypot(F[r, L.VX], F[r, L.VY]) + math.hypot(svx - dvx, svy - dvy))
        if always or small:
            F[r, L.VX] += dvx
            F[r, L.VY] += dvy
            if settle_acceleration(S, r, t):
                count = append_riders(I, r, out, count)
                continue
        detach(S, r)
        stats[L.S_RELEASES] += 1
        count = release_riders(S, r, out, count, t)
    return count


@njit(cache=True)
def carry_or_release_riders(S, s, vx0, vy0, w0, out, count, t):
    """After ``s``'s velocity changed from ``(vx0, vy0, w0)`` at ``t``: carry what rests on it
    over a change within rounding (``resettle_riders``), release it otherwise (a turn of
    ``s`` always releases). Returns the new count of ``out``.
    """
    F = S[0]
    if F[s, L.OMEGA] != w0:
        return release_riders(S, s, out, count, t)
    return resettle_riders(S, s, F[s, L.VX] - vx0, F[s, L.VY] - vy0, False, out, count, t)


@njit(cache=True)
def _contact_span(S, r, t):
    """Where the flat contact of rider ``r`` lies along its edge at ``t``.

    Returns ``(low, high, length, tx, ty, other, owner)``: the other body's
    contact extent as tangential coordinates from the edge's first vertex,
    the edge length and unit tangent, and which body is the edge's owner.
    """
    F = S[0]
    I = S[1]
    OL = S[2]
    owner = I[r, L.EDGE_OWNER]
    other = I[r, L.SUPPORT] if owner == r else r
    row = I[owner, L.OUTLINE_START] + I[r, L.EDGE_INDEX]
    nx = OL[row, 2]
    ny = OL[row, 3]
    tx = -ny
    ty = nx
    ox, oy, _, _ = state_at(F, owner, t)
    qx = ox + OL[row, 0]
    qy = oy + OL[row, 1]
    px, py, _, _ = state_at(F, other, t)
    if I[other, L.KIND] == 0:
        u = (px - qx) * tx + (py - qy) * ty
        return u, u, OL[row, 4], tx, ty, other, owner
    start = I[other, L.OUTLINE_START]
    n = I[other, L.OUTLINE_N]
    lowest = _INF
    for k in range(n):
        lowest = min(lowest, nx * OL[start + k, 0] + ny * OL[start + k, 1])
    tolerance = 1e-9 * F[other, L.REACH]
    low = _INF
    high = -_INF
    for k in range(n):
        if nx * OL[start + k, 0] + ny * OL[start + k, 1] <= lowest + tolerance:
            u = (px + OL[start + k, 0] - qx) * tx + (py + OL[start + k, 1] - qy) * ty
            low = min(low, u)
            high = max(high, u)
    return low, high, OL[row, 4], tx, ty, other, owner


@njit(cache=True)
def schedule_contact_event(S, r):
    """Queue the next change of rider ``r``'s contact: leaving its edge or stopping."""
    F = S[0]
    I = S[1]
    P = S[3]
    now = P[L.TIME]
    best = _INF
    what = L.LEAVE
    if I[r, L.EDGE_OWNER] >= 0:
        low, high, length, tx, ty, other, owner = _contact_span(S, r, now)
        _, _, ovx, ovy = state_at(F, other, now)
        _, _, wvx, wvy = state_at(F, owner, now)
        dv = (ovx - wvx) * tx + (ovy - wvy) * ty
        da = 0.5 * ((F[other, L.AX] - F[owner, L.AX]) * tx + (F[other, L.AY] - F[owner, L.AY]) * ty)
        if high < 0.0 or low > length:
            best = 0.0
        else:
            best = min(
                first_descent_quadratic(high, dv, da, _INF, True),
                first_descent_quadratic(length - low, -dv, -da, _INF, True),
            )
        if now + best == now and I[other, L.KIND] == 0:
            # A circle at the very end of its edge (to rounding: leaving could not move
            # time on), moving off. Fast enough to clear the
            # corner (v^2 >= a_n R) it flies; slower, the corner carries it on as a
            # curved contact (leaving at once would only bring it straight back).
            vt, _, an = relative_tangential(S, r, now)
            if vt * vt < -an * F[other, L.RADIUS]:
                I[r, L.EDGE_OWNER] = CURVED_STEPPING
                if F[r, L.ALPHA] != 0.0:
                    advance(F, r, now)
                    F[r, L.ALPHA] = 0.0  # on a curved contact it keeps its spin
                best = _INF
    if I[r, L.EDGE_OWNER] == CURVED_STEPPING:
        s = I[r, L.SUPPORT]
        vt, _, _ = relative_tangential(S, r, now)
        half_at = 0.5 * (-(F[r, L.AX] - F[s, L.AX]) * F[r, L.REST_NY] + (F[r, L.AY] - F[s, L.AY]) * F[r, L.REST_NX])
        step = CURVED_STEP * F[r, L.REACH]
        best = min(
            first_descent_quadratic(step, -vt, -half_at, _INF, False),
            first_descent_quadratic(step, vt, half_at, _INF, False),
        )
    if I[r, L.REST_MODE] == L.SLIDING:
        slip, rolling = contact_slip(S, r, now)
        s = I[r, L.SUPPORT]
        rate = -(F[r, L.AX] - F[s, L.AX]) * F[r, L.REST_NY] + (F[r, L.AY] - F[s, L.AY]) * F[r, L.REST_NX]
        if rolling:
            rate -= F[r, L.ALPHA] * F[r, L.RADIUS]
        if slip != 0.0 and rate != 0.0 and (slip > 0.0) != (rate > 0.0):
            stop = -slip / rate
            if stop < best:
                best = stop
                what = L.STOP_SLIDING
    if best != _INF:
        push(S, now + best, (L.CONTACT_EVENT << L.KIND_SHIFT) | r, r, -1, I[r, L.COUNT], 0, what)
