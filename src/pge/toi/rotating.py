"""Time of impact for rotating bodies: circle against polygon, polygon against polygon.

Motion model (all times relative to the common origin ``t = 0``): the offset
of a's centroid from b's is ``D(t) = d + dv t + da t^2 / 2`` (world axes), a
polygon's vertices are ``centroid(t) + R(theta(t)) r_k``, turned by ``theta(t) =
theta + omega t + alpha t^2 / 2`` (constant angular acceleration; its spin is
``omega(t) = omega + alpha t``), with ``r_k`` its outline rows (vertices relative to the centroid in the unrotated frame,
see ``pge.toi.outline_rows``), and a circle's rotation does not change its
geometry. Rotation makes the gap transcendental, so it is not solved as a
polynomial: the first contact is bracketed by rigorous conservative
advancement and refined to about 1e-12 s (``pge.numerics.bracket``).

**Gap.** The features are points against convex polygons: each vertex of a
against polygon b and each vertex of b against polygon a (for a circle: its
centre against b, minus the radius). A feature's value is the point's
*signed distance* to the polygon (negative inside), a convex function of the
point. The smallest value is the distance between the shapes while they are
apart, and it reaches zero exactly when they first touch (two convex
polygons first meet at a vertex). A non-positive value at any time proves
an overlap, which is all a bracket's upper end needs.

**Bound.** Seen from b's frame, a feature point ``q(t)`` with world offset
``w(t)`` from b's centroid has ``q'' = R(-theta_b) w'' - 2 omega_b J R(-theta_b) w'
- omega_b^2 q - alpha_b J q``, and the value ``g = SD(q)`` of a convex,
1-Lipschitz ``SD`` obeys ``g'' >= grad SD . q''`` almost everywhere. With
``|w''| <= |da| + omega_a^2 R_a + |alpha_a| R_a``, ``|w'| <= |dv(t)| + |omega_a|
R_a``, ``grad SD . q <= SD + R_b`` and ``|grad SD . J q| <= |q| <= SD + R_b`` this
gives, over a window of length ``h`` in which every ``|omega|`` is at most its
value at the window's start plus ``|alpha| h``,

    g'' >= -(|da| + omega_a^2 R_a + 2 |omega_b| (V + |omega_a| R_a) + omega_b^2 (SD_max + R_b)
             + |alpha_a| R_a + |alpha_b| (SD_max + R_b))

with ``V = |dv(lo)| + |da| h`` and ``SD_max = max(SD(lo), 0) + L h`` (swap a
and b for b's vertices against a). ``L = V + |omega_a| R_a + |omega_b| R_b``
bounds every ``|g'|``, the first-order (Lipschitz) bound of classic
conservative advancement; from ``lo`` onwards ``|g'(lo + s)|`` grows by at
most ``(|da| + |alpha_a| R_a + |alpha_b| R_b) s``. From a time ``lo`` before every contact the step is
the larger of the two bounds' first zeros (minimum over the features); the
second-order one is a safe Newton step, so a transversal contact is
approached quadratically.

**Bracket.** After each step the exact gap is evaluated a little past the
Newton estimate (``newton_trial``); a non-positive value there is the
bracket's upper end. The search returns ``lo``, never later than the true
first contact, once the bracket is narrower than ``1e-12 s`` (plus a few
ulp), or the gap at ``lo`` is within the touch tolerance and either not
closing (a graze, reported as a contact with zero approach speed) or closing
within the time tolerance, or rounding leaves no certified progress.

**Tolerances.** The gap's rounding is estimated as 8 ulp of the shapes' size
(bounding radii plus radius, times ``1 + |angle| / 16``) and of the offset's
terms. Steps start from the gap minus twice that estimate; gaps below 16
times it (about 1.4e-14 x the size) count as touching. A contact time is thus
accurate to about 1e-12 s plus that rounding divided by the approach speed.

**Start.** Touching or overlapping at ``t = 0`` (gap within the touch
tolerance) and approaching at the contact patch, rotational velocity
``omega x r`` included, is an immediate contact (``t = 0.0``). Touching and
not approaching is the end of the previous contact: the features then in
contact are set aside until each has opened beyond the touch tolerance, with
steps short enough (``excursion_step``) that none can open and close again
unseen, and the next genuine contact is searched from there.

**Budget.** A search stops after ``MAX_ITERATIONS`` steps (far more than any
ordinary prediction needs) and then returns the last certified time with the
feature ``CHECKPOINT``: no contact happens before that time, predict again
from there.

Features are numbered as in the non-rotating kernels: circle against polygon
edge ``k`` is ``k``, corner ``k`` is ``-(k + 1)``; polygon against polygon, edge
``k`` of b struck by a vertex of a is ``k`` and edge ``k`` of a struck by a
vertex of b is ``n_b + k``. When nothing rotates (both angular velocities 0)
the kernels delegate to ``circle_polygon`` and ``polygon_polygon``.
"""

from __future__ import annotations

import math

import numpy as np
from pge._jit_cache import njit

from pge.numerics.bracket import (
    curvature_step,
    excursion_step,
    lipschitz_step,
    newton_trial,
    time_tolerance,
)
from pge.toi.circle_polygon import circle_polygon, circle_polygon_contact, closest_feature
from pge.toi.polygon_polygon import polygon_polygon

__all__ = [
    "CHECKPOINT",
    "MAX_ITERATIONS",
    "rotating_circle_polygon",
    "rotating_circle_polygon_contact",
    "rotating_polygon_polygon",
    "rotating_polygon_polygon_contact",
    "rotating_search",
]

#: feature returned when the iteration budget ran out: no contact before the
#: returned time, predict again from there.
CHECKPOINT = -(1 << 30)
#: iteration budget of one search.
MAX_ITERATIONS = 20000

_INF = math.inf
_ULP = 2.0**-53
#: rounding of a computed gap, in units of roundoff of the lengths involved.
_NOISE = 8.0
#: gaps below this many rounding estimates count as touching.
_TOUCH = 16.0
#: a step is taken from a gap reduced by this many rounding estimates.
_MARGIN = 2.0
#: approach rates within this many units of roundoff of the speeds involved count as zero.
_STILL = 64.0 * _ULP
#: tolerance relative to the shapes' size within which vertices count as one contact patch.
_TIE = 1e-10
#: relative tolerance within which the two ends of a patch approach equally fast.
_SAME_RATE = 1e-9


# ---------------------------------------------------------------- geometry


@njit(cache=True)
def _place(outline, start, n, theta, geo, row0):
    """Rows ``row0 ..`` of ``geo``: the outline rotated by ``theta`` (world axes, centroid at 0)."""
    c = math.cos(theta)
    s = math.sin(theta)
    for k in range(n):
        x = outline[start + k, 0]
        y = outline[start + k, 1]
        nx = outline[start + k, 2]
        ny = outline[start + k, 3]
        r = row0 + k
        geo[r, 0] = c * x - s * y
        geo[r, 1] = s * x + c * y
        geo[r, 2] = c * nx - s * ny
        geo[r, 3] = s * nx + c * ny
        geo[r, 4] = outline[start + k, 4]


@njit(cache=True)
def _reach(outline, start, n):
    """Bounding radius: the largest vertex distance from the centroid."""
    reach = 0.0
    for k in range(n):
        reach = max(reach, math.hypot(outline[start + k, 0], outline[start + k, 1]))
    return reach


@njit(cache=True)
def _signed_distance(wx, wy, geo, row0, n):
    """Signed distance of ``w`` to the polygon in ``geo`` rows ``row0 ..``: ``(sd, x, y, ux, uy, slack)``.

    ``(x, y)`` is the nearest boundary point and ``u`` the unit gradient of the
    distance (from the polygon towards ``w``; the face normal inside).
    ``slack >= 0`` when the distance is a face's plane distance (``w`` inside,
    or beside a face rather than round a corner): ``u`` is then that face's
    normal, ``sd = u . (w - vertex)``, and ``slack`` is how far ``w``'s foot
    on the face's line lies within the face (0 at or beyond an end). ``slack =
    -1`` round a corner.
    """
    smax = -_INF
    kmax = 0
    for k in range(n):
        r = row0 + k
        s = geo[r, 2] * (wx - geo[r, 0]) + geo[r, 3] * (wy - geo[r, 1])
        if s > smax:
            smax = s
            kmax = k
    if smax <= 0.0:
        r = row0 + kmax
        along = -geo[r, 3] * (wx - geo[r, 0]) + geo[r, 2] * (wy - geo[r, 1])
        slack = max(min(along, geo[r, 4] - along), 0.0)
        return smax, wx - smax * geo[r, 2], wy - smax * geo[r, 3], geo[r, 2], geo[r, 3], slack
    best = _INF
    slack = -1.0
    bx = 0.0
    by = 0.0
    bux = 1.0
    buy = 0.0
    for k in range(n):
        r = row0 + k
        nx = geo[r, 2]
        ny = geo[r, 3]
        ox = wx - geo[r, 0]
        oy = wy - geo[r, 1]
        s = nx * ox + ny * oy
        if s <= 0.0:
            continue  # only an edge facing w can hold the nearest point
        along = -ny * ox + nx * oy
        if along <= 0.0:
            dist = math.hypot(ox, oy)
            if dist < best:
                best, bx, by, bux, buy, slack = dist, geo[r, 0], geo[r, 1], ox / dist, oy / dist, -1.0
        elif along >= geo[r, 4]:
            r1 = row0 + (k + 1) % n
            ox1 = wx - geo[r1, 0]
            oy1 = wy - geo[r1, 1]
            dist = math.hypot(ox1, oy1)
            if dist < best:
                best, bx, by, bux, buy, slack = dist, geo[r1, 0], geo[r1, 1], ox1 / dist, oy1 / dist, -1.0
        elif s < best:
            best, bx, by, bux, buy, slack = s, wx - s * nx, wy - s * ny, nx, ny, min(along, geo[r, 4] - along)
    return best, bx, by, bux, buy, slack


@njit(cache=True)
def _evaluate(t, motion, outline, start_a, n_a, turn_a, start_b, n_b, turn_b, radius, circle, geo, value, rate, facing, slack):
    """Place both shapes at ``t`` and fill every feature's value and rate.

    ``motion = (dx, dy, dvx, dvy, dax, day)``, ``turn = (theta, omega, alpha)``: the
    angle ``theta + omega t + alpha t^2 / 2`` and the spin ``omega + alpha t``. ``geo``
    rows ``0 .. n_a-1`` hold a (none for a circle), the next ``n_b`` rows b.
    Features ``0 .. n_a-1`` (one, the centre, for a circle) are a's points
    against b, the rest b's vertices against a. ``facing[f]`` is the centroids'
    relative acceleration (``da``, or ``-da`` for b's vertices) along the
    gradient ``u`` of feature ``f``'s value, and ``slack[f]`` is as in
    ``_signed_distance`` (``>= 0`` when the value is a face's plane distance,
    the only case that uses ``facing``). Returns ``D(t)`` and ``D'(t)``.
    """
    dx, dy, dvx, dvy, dax, day = motion
    theta_a, omega_a, alpha_a = turn_a
    theta_b, omega_b, alpha_b = turn_b
    angle_a = theta_a + (omega_a + 0.5 * alpha_a * t) * t
    angle_b = theta_b + (omega_b + 0.5 * alpha_b * t) * t
    omega_a = omega_a + alpha_a * t
    omega_b = omega_b + alpha_b * t
    ox = dx + (dvx + 0.5 * dax * t) * t
    oy = dy + (dvy + 0.5 * day * t) * t
    vx = dvx + dax * t
    vy = dvy + day * t
    rows_a = 0 if circle else n_a
    if not circle:
        _place(outline, start_a, n_a, angle_a, geo, 0)
    _place(outline, start_b, n_b, angle_b, geo, rows_a)
    if circle:
        sd, x, y, ux, uy, slack[0] = _signed_distance(ox, oy, geo, 0, n_b)
        value[0] = sd - radius
        facing[0] = ux * dax + uy * day
        # relative velocity of the centre and of b's material point at x
        rate[0] = ux * (vx + omega_b * y) + uy * (vy - omega_b * x)
        return ox, oy, vx, vy
    for i in range(n_a):
        px = geo[i, 0]
        py = geo[i, 1]
        sd, x, y, ux, uy, slack[i] = _signed_distance(ox + px, oy + py, geo, n_a, n_b)
        value[i] = sd
        facing[i] = ux * dax + uy * day
        rate[i] = ux * (vx - omega_a * py + omega_b * y) + uy * (vy + omega_a * px - omega_b * x)
    for j in range(n_b):
        qx = geo[n_a + j, 0]
        qy = geo[n_a + j, 1]
        sd, x, y, ux, uy, slack[n_a + j] = _signed_distance(qx - ox, qy - oy, geo, 0, n_a)
        value[n_a + j] = sd
        facing[n_a + j] = -(ux * dax + uy * day)
        rate[n_a + j] = ux * (-omega_b * qy - vx + omega_a * y) + uy * (omega_b * qx - vy - omega_a * x)
    return ox, oy, vx, vy


@njit(cache=True)
def _separation(geo, n_a, n_b, ox, oy):
    """Separating-axis test on the placed shapes: ``(face, value)`` of the largest separation.

    Faces are numbered as the features (edge ``k`` of b is ``k``, edge ``k`` of a
    is ``n_b + k``); the value is negative when the shapes overlap.
    """
    best = -_INF
    face = 0
    for k in range(n_b):
        r = n_a + k
        mx = geo[r, 2]
        my = geo[r, 3]
        smin = _INF
        for i in range(n_a):
            smin = min(smin, mx * (ox + geo[i, 0] - geo[r, 0]) + my * (oy + geo[i, 1] - geo[r, 1]))
        if smin > best:
            best = smin
            face = k
    for k in range(n_a):
        mx = geo[k, 2]
        my = geo[k, 3]
        smin = _INF
        for j in range(n_b):
            r = n_a + j
            smin = min(smin, mx * (geo[r, 0] - ox - geo[k, 0]) + my * (geo[r, 1] - oy - geo[k, 1]))
        if smin > best:
            best = smin
            face = n_b + k
    return face, best


@njit(cache=True)
def _rate_at(px, py, nx, ny, ox, oy, vx, vy, omega_a, omega_b):
    """Normal relative velocity (a minus b, along ``n``) of the material points at ``p``.

    ``p`` and ``o = D`` are relative to b's centroid; ``v = D'``; a point's
    velocity is its centroid's plus ``omega x r``.
    """
    rx = px - ox
    ry = py - oy
    relx = vx - omega_a * ry + omega_b * py
    rely = vy + omega_a * rx - omega_b * px
    return nx * relx + ny * rely


@njit(cache=True)
def press_rate(px, py, nx, ny, ox, oy, vx, vy, ax, ay, omega_a, omega_b, omega_face, bend, alpha_a=0.0, alpha_b=0.0):
    """Second derivative of the gap at a contact point ``p`` with normal ``n`` (b towards
    a) while the two touch: negative when the contact is being pressed shut.

    ``p`` and ``o = D`` are relative to b's centroid, ``v = D'``, ``a = D''``;
    ``u`` and ``A`` below are the relative velocity and acceleration of the
    material points at ``p`` (a's minus b's, centripetal terms and those of the
    angular accelerations ``alpha`` included). The normal turns in one of two ways:

    - with a face, ``n`` its normal and ``omega_face`` the spin of the body
      that owns it: ``g'' = 2 omega_face (J n) . u + n . A``;
    - round a curve, ``g = |a's point - b's point| - R`` with ``bend = 1 / R``
      (a circle's centre against a corner, ``R`` its radius; two circles' centres,
      ``R`` the sum of the radii): ``g'' = n . A + bend |u_t|^2``, and
      ``omega_face = 0``.

    A circle a stands for its centre: it passes ``omega_a = 0`` and ``p = o``
    on a face (the rim point would add a spurious ``omega_b^2 r``).
    """
    rx = px - ox
    ry = py - oy
    ux = vx - omega_a * ry + omega_b * py
    uy = vy + omega_a * rx - omega_b * px
    acx = ax - omega_a * omega_a * rx + omega_b * omega_b * px - alpha_a * ry + alpha_b * py
    acy = ay - omega_a * omega_a * ry + omega_b * omega_b * py + alpha_a * rx - alpha_b * px
    slip = -ny * ux + nx * uy
    return 2.0 * omega_face * slip + nx * acx + ny * acy + bend * slip * slip


@njit(cache=True, inline="always")
def press_noise(accel, speed, spin_a, spin_b, reach_a, reach_b, still, bend):
    """Rounding of ``press_rate``: a curvature within this of 0 is neither pressed nor free.

    ``accel`` and ``speed`` are the magnitudes of the relative acceleration (the
    angular accelerations' ``|alpha| R`` included) and velocity, ``spin`` the absolute angular velocities, ``reach`` the bounding
    radii (0 and 0 for a circle a, whose spin does not count), ``bend`` as in
    ``press_rate``, ``still`` the rounding of the contact's velocities
    (``pge.core.predict.still_speed``), which the turning normal multiplies
    into the curvature.
    """
    slip = speed + spin_a * reach_a + spin_b * reach_b
    turn = 2.0 * max(spin_a, spin_b) + bend * slip
    own = _STILL * (accel + spin_a * spin_a * reach_a + spin_b * spin_b * reach_b + turn * slip)
    return own + 2.0 * (spin_a + spin_b + bend * slip) * still


@njit(cache=True)
def _patch(geo, n_a, n_b, ox, oy, vx, vy, omega_a, omega_b, face, tie):
    """Contact point (relative to b's centroid), normal (b towards a) and approach rate of a face.

    The striking polygon's vertices within ``tie`` of its support value form
    the contact patch, clipped to the struck edge. A single vertex is the
    point. Otherwise the relative normal velocity, linear along the patch, is
    taken at both ends: equal ones (within a relative 1e-9) give the middle,
    else the faster-approaching end is the point, so that "approaching
    anywhere on the patch" is exactly "the returned rate is negative".
    """
    if face < n_b:
        r = n_a + face
        bx = geo[r, 0]
        by = geo[r, 1]
        first = 0
        count = n_a
        sign = 1.0
        shift_x = ox  # a's vertices relative to b's centroid
        shift_y = oy
    else:
        r = face - n_b
        bx = ox + geo[r, 0]
        by = oy + geo[r, 1]
        first = n_a
        count = n_b
        sign = -1.0
        shift_x = 0.0
        shift_y = 0.0
    mx = geo[r, 2]
    my = geo[r, 3]
    length = geo[r, 4]
    tx = -my
    ty = mx
    smin = _INF
    for k in range(first, first + count):
        smin = min(smin, mx * (shift_x + geo[k, 0] - bx) + my * (shift_y + geo[k, 1] - by))
    u_lo = _INF
    u_hi = -_INF
    tied = 0
    px = 0.0
    py = 0.0
    for k in range(first, first + count):
        wx = shift_x + geo[k, 0]
        wy = shift_y + geo[k, 1]
        if mx * (wx - bx) + my * (wy - by) <= smin + tie:
            u = tx * (wx - bx) + ty * (wy - by)
            u_lo = min(u_lo, u)
            u_hi = max(u_hi, u)
            tied += 1
            px = wx
            py = wy
    nx = sign * mx
    ny = sign * my
    if tied == 1:
        return px, py, nx, ny, _rate_at(px, py, nx, ny, ox, oy, vx, vy, omega_a, omega_b)
    lo = max(u_lo, 0.0)
    hi = min(u_hi, length)
    if lo > hi:  # the tied vertices miss the edge (a corner contact): meet it at its nearest end
        lo = min(max(0.5 * (u_lo + u_hi), 0.0), length)
        hi = lo
    x0 = bx + lo * tx + smin * mx
    y0 = by + lo * ty + smin * my
    x1 = bx + hi * tx + smin * mx
    y1 = by + hi * ty + smin * my
    rate0 = _rate_at(x0, y0, nx, ny, ox, oy, vx, vy, omega_a, omega_b)
    rate1 = _rate_at(x1, y1, nx, ny, ox, oy, vx, vy, omega_a, omega_b)
    if abs(rate0 - rate1) <= _SAME_RATE * (abs(rate0) + abs(rate1)):
        return 0.5 * (x0 + x1), 0.5 * (y0 + y1), nx, ny, 0.5 * (rate0 + rate1)
    if rate0 < rate1:
        return x0, y0, nx, ny, rate0
    return x1, y1, nx, ny, rate1


@njit(cache=True)
def _circle_patch(ox, oy, vx, vy, radius, outline, start, n, theta, omega):
    """Circle against the placed polygon: ``(feature, px, py, nx, ny, rate)``.

    The feature is the polygon's nearest one (``closest_feature`` in its own
    frame); the point is relative to the polygon's centroid.
    """
    c = math.cos(theta)
    s = math.sin(theta)
    lx = c * ox + s * oy
    ly = -s * ox + c * oy
    feature, _, _, _ = closest_feature(lx, ly, radius, outline, start, n)
    qx, qy, mx, my = circle_polygon_contact(lx, ly, radius, 0.0, 0.0, outline, start, n, feature)
    px = c * qx - s * qy
    py = s * qx + c * qy
    nx = c * mx - s * my
    ny = s * mx + c * my
    # the circle's rotation only adds a tangential velocity at its rim
    rate = nx * (vx + omega * py) + ny * (vy - omega * px)
    return feature, px, py, nx, ny, rate


@njit(cache=True)
def _rounding(scale, angle_a, angle_b, motion, t):
    """Estimated rounding of a computed gap: a few ulp of the shapes' size, of the
    terms of the offset and of the angles (whose error a lever of the size turns
    into a length)."""
    dx, dy, dvx, dvy, dax, day = motion
    magnitude = abs(dx) + abs(dy) + (abs(dvx) + abs(dvy) + 0.5 * (abs(dax) + abs(day)) * t) * t
    return _NOISE * _ULP * (scale * (1.0 + (abs(angle_a) + abs(angle_b)) / 16.0) + 2.0 * magnitude)


# ---------------------------------------------------------------- the search


@njit(cache=True)
def _band_step(value, rate, curvature, eps, speed, accel, h, bounded):
    """Step for a feature touching within ``eps`` at the end of a contact: it may open
    (and must not close again unseen) or, pressed or turned in, sink; step no further
    than it could reach ``-eps``. ``curvature`` bounds the gap's bend over the window."""
    deeper = value + eps
    if value < 0.0:
        s = lipschitz_step(-value, speed, accel) + excursion_step(0.0, curvature, eps)
    else:
        s = excursion_step(rate, curvature, eps)
    if bounded:
        s = min(s, h)  # the bend is bounded over the window only
    if deeper > 0.0:
        sink = lipschitz_step(deeper, speed, accel)
        if bounded:
            sink = max(sink, min(h, curvature_step(deeper, rate, curvature)))
        s = min(s, sink)
    return s


@njit(cache=True)
def rotating_search(
    dx,
    dy,
    dvx,
    dvy,
    dax,
    day,
    outline,
    start_a,
    n_a,
    theta_a,
    omega_a,
    start_b,
    n_b,
    theta_b,
    omega_b,
    radius,
    circle,
    horizon,
    budget,
    still=0.0,
    alpha_a=0.0,
    alpha_b=0.0,
):
    """First contact of a (circle or polygon) with polygon b, both rotating: ``(t, feature, iterations)``.

    ``d, dv, da``: offset, velocity and acceleration of a's centroid (or
    centre) relative to b's, world axes. With ``circle`` true, a is a circle of
    ``radius`` (``start_a``, ``n_a``, ``theta_a``, ``omega_a`` unused); else a is
    the polygon in rows ``start_a ..`` and ``radius`` must be 0. ``t`` is inf
    for no contact within ``[0, horizon]``, 0.0 for touching-and-approaching
    now, else never later than the first contact and at most about 1e-12 s
    earlier. ``feature`` as in the module docstring, ``CHECKPOINT`` when
    ``budget`` iterations did not suffice (no contact before ``t`` then).
    ``iterations`` counts the conservative-advancement steps taken. A touching
    pair whose normal rate is within ``still`` (or the search's own rounding
    estimate, if larger) is not approaching. ``alpha_a``, ``alpha_b``: constant
    angular accelerations (a's is ignored for a circle); the spins at ``t`` are
    ``omega + alpha t``.
    """
    if circle:
        alpha_a = 0.0
    rows_a = 0 if circle else n_a
    count = 1 if circle else n_a + n_b
    front = 1 if circle else n_a  # features of a's points against b
    geo = np.empty((rows_a + n_b, 5))
    value = np.empty(count)
    rate = np.empty(count)
    facing = np.empty(count)
    slack = np.empty(count)
    band = np.zeros(count, np.bool_)
    reach_a = 0.0 if circle else _reach(outline, start_a, n_a)
    reach_b = _reach(outline, start_b, n_b)
    scale = reach_a + reach_b + radius
    tie = _TIE * scale
    accel = math.hypot(dax, day)
    # The spins change at |alpha| at most: corners speed up by |alpha| R, and the
    # normals' turning rate by |alpha|, which the bounds below add.
    spin_a = abs(omega_a) if not circle else 0.0
    spin_b = abs(omega_b)
    spin = spin_a * reach_a + spin_b * reach_b
    twist_a = abs(alpha_a)
    twist_b = abs(alpha_b)
    twist = twist_a * reach_a + twist_b * reach_b
    motion = (dx, dy, dvx, dvy, dax, day)
    turn_a = (theta_a, omega_a, alpha_a)
    turn_b = (theta_b, omega_b, alpha_b)

    ox, oy, vx, vy = _evaluate(
        0.0, motion, outline, start_a, n_a, turn_a, start_b, n_b, turn_b, radius, circle, geo, value, rate, facing, slack
    )
    eps = _TOUCH * _rounding(scale, theta_a, theta_b, motion, 0.0)
    gap = _INF
    for f in range(count):
        gap = min(gap, value[f])
    escape = False
    face = 0
    separation = _INF
    if circle:
        touching = gap <= eps
    else:
        face, separation = _separation(geo, n_a, n_b, ox, oy)
        touching = gap <= eps or separation <= eps
    if touching:
        if circle:
            feature, px, py, nx, ny, approach = _circle_patch(
                ox, oy, vx, vy, radius, outline, start_b, n_b, theta_b, omega_b
            )
            if feature >= 0:  # the centre against b's face
                bend = 0.0
                curvature = press_rate(
                    ox, oy, nx, ny, ox, oy, vx, vy, dax, day, 0.0, omega_b, omega_b, bend, 0.0, alpha_b
                )
            else:  # the centre round b's corner
                bend = 1.0 / radius
                curvature = press_rate(px, py, nx, ny, ox, oy, vx, vy, dax, day, 0.0, omega_b, 0.0, bend, 0.0, alpha_b)
        else:
            px, py, nx, ny, approach = _patch(geo, n_a, n_b, ox, oy, vx, vy, omega_a, omega_b, face, tie)
            feature = face
            bend = 0.0
            omega_face = omega_b if face < n_b else omega_a
            curvature = press_rate(
                px, py, nx, ny, ox, oy, vx, vy, dax, day, omega_a, omega_b, omega_face, bend, alpha_a, alpha_b
            )
        # A rate that is only rounding (a corner at the end of its sweep) is no approach:
        # reporting it would start an endless run of zero-time contacts.
        still = max(still, _STILL * (math.hypot(dvx, dvy) + spin))
        if approach < -still:
            return 0.0, feature, 0
        # Touching, not separating and pressed shut (gravity on a corner): a contact now,
        # or the shapes would sink into each other unseen.
        pressing = press_noise(accel + twist, math.hypot(dvx, dvy), spin_a, spin_b, reach_a, reach_b, still, bend)
        if approach <= still and curvature < -pressing:
            return 0.0, feature, 0
        # Touching and not approaching: the contact now ending is no new one.
        escape = True
        for f in range(count):
            band[f] = value[f] <= eps

    lo = 0.0
    hi = _INF
    widen = 1.0
    window = horizon
    iterations = 0
    found = False
    while iterations < budget:
        iterations += 1
        angle_a = theta_a + (omega_a + 0.5 * alpha_a * lo) * lo
        angle_b = theta_b + (omega_b + 0.5 * alpha_b * lo) * lo
        spin_a = abs(omega_a + alpha_a * lo) if not circle else 0.0
        spin_b = abs(omega_b + alpha_b * lo)
        spin = spin_a * reach_a + spin_b * reach_b
        noise = _rounding(scale, angle_a, angle_b, motion, lo)
        eps = _TOUCH * noise
        margin = _MARGIN * noise
        sinking = -1
        if escape:
            escape = False
            for f in range(count):
                if band[f]:
                    if value[f] > eps:
                        band[f] = False  # this part of the old contact has opened
                    elif value[f] < -eps and lo > 0.0:
                        sinking = f  # it went in instead of opening: a new contact
                    else:
                        escape = True
        if sinking >= 0:
            found = True
            break
        gap = _INF
        nearest = -1
        for f in range(count):
            if not band[f] and value[f] < gap:
                gap = value[f]
                nearest = f
        tolerance = time_tolerance(lo)
        if hi - lo <= tolerance:
            found = True
            break
        if gap <= eps and (rate[nearest] >= 0.0 or gap <= -rate[nearest] * tolerance):
            found = True  # touching: a graze, or a contact nearer than the tolerance
            break
        speed = math.hypot(vx, vy)
        h = min(window, horizon - lo)
        bounded = h < _INF
        reach = _INF
        rest_a = _INF
        rest_b = _INF
        top_a = spin_a
        top_b = spin_b
        if bounded:
            # the largest spins over the window, and the curvature bounds' parts that do
            # not grow with the signed distance (module docstring, "Bound")
            top_a = spin_a + twist_a * h
            top_b = spin_b + twist_b * h
            fastest = speed + accel * h
            reach = fastest + top_a * reach_a + top_b * reach_b  # bound on every |g'| over the window
            rest_a = (
                top_a * top_a * reach_a + 2.0 * top_b * (fastest + top_a * reach_a) + top_b * top_b * reach_b + twist
            )
            rest_b = (
                top_b * top_b * reach_b + 2.0 * top_a * (fastest + top_b * reach_b) + top_a * top_a * reach_a + twist
            )
        step = _INF
        for f in range(count):
            curvature = _INF
            flat = _INF
            turn = 0.0
            widest = 0.0
            if bounded:
                widest = max(value[f] + radius, 0.0) + reach * h
                # the spin of the body f is measured against, and its angular acceleration
                turn = top_b if f < front else top_a
                twist_f = twist_b if f < front else twist_a
                rest = rest_a if f < front else rest_b
                bent = (turn * turn + twist_f) * widest
                curvature = accel + rest + bent
                flat = curvature
                if slack[f] >= 0.0:
                    # Beside a face: the face's plane distance is a lower bound of the gap for
                    # all time, bent only by the acceleration along its normal (which turns by
                    # at most turn * h over the window) and by the spins.
                    flat = rest + bent + min(accel, max(0.0, accel * turn * h - facing[f]))
            if band[f]:
                s = _band_step(value[f], rate[f], curvature, eps, speed + spin, accel + twist, h, bounded)
                if flat < curvature:
                    # While the point stays beside the face, the gap near zero is the plane
                    # distance itself, so its milder bend bounds the excursion too.
                    beside = slack[f] / (reach + turn * widest)
                    milder = _band_step(value[f], rate[f], flat, eps, speed + spin, accel + twist, h, bounded)
                    s = max(s, min(beside, milder))
            else:
                s = lipschitz_step(value[f] - margin, speed + spin, accel + twist)
                if bounded:
                    s = max(s, min(h, curvature_step(value[f] - margin, rate[f], flat)))
            step = min(step, s)
        if step == _INF:
            return _INF, 0, iterations
        following = lo + step
        if following > horizon:
            return _INF, 0, iterations
        if not following > lo or following >= hi:
            found = True  # no representable progress: the contact is at lo to rounding
            break
        if not escape and rate[nearest] < 0.0:
            trial = newton_trial(lo, gap, rate[nearest], following, widen, tolerance)
            if following < trial < hi and trial <= horizon:
                _evaluate(
                    trial, motion, outline, start_a, n_a, turn_a, start_b, n_b, turn_b, radius, circle, geo, value, rate, facing, slack
                )
                closed = False
                for f in range(count):
                    if value[f] <= 0.0:
                        closed = True
                if closed:
                    hi = trial
                    widen = 1.0
                else:
                    widen *= 4.0
        lo = following
        window = 4.0 * step
        ox, oy, vx, vy = _evaluate(
            lo, motion, outline, start_a, n_a, turn_a, start_b, n_b, turn_b, radius, circle, geo, value, rate, facing, slack
        )
    if not found:
        return lo, CHECKPOINT, iterations
    angle_b = theta_b + (omega_b + 0.5 * alpha_b * lo) * lo
    return lo, _feature(geo, ox, oy, radius, outline, start_b, n_a, n_b, angle_b, circle), iterations


@njit(cache=True)
def _feature(geo, ox, oy, radius, outline, start_b, n_a, n_b, angle_b, circle):
    """Feature of a contact found with the shapes placed in ``geo``."""
    if circle:
        c = math.cos(angle_b)
        s = math.sin(angle_b)
        feature, _, _, _ = closest_feature(c * ox + s * oy, -s * ox + c * oy, radius, outline, start_b, n_b)
        return feature
    face, _ = _separation(geo, n_a, n_b, ox, oy)
    return face


# ---------------------------------------------------------------- kernels


@njit(cache=True)
def rotating_circle_polygon(px, py, vx, vy, ax, ay, radius, outline, start, n, theta0, omega, horizon, still=0.0, alpha=0.0):
    """First contact of a circle (a) and a translating, rotating convex polygon (b).

    ``(px, py)``, ``(vx, vy)``, ``(ax, ay)``: the circle's centre, velocity and
    acceleration relative to the polygon's centroid (world axes); the polygon
    is outline rows ``start .. start + n - 1`` at angle ``theta0 + omega t + alpha t^2 / 2``.
    Returns ``(t, feature)``: ``t`` = inf for no contact within ``[0, horizon]``,
    0.0 for touching-and-approaching now (rotation included), else at most
    about 1e-12 s before the first contact and never after it. Feature: edge
    ``k`` is ``k``, corner ``k`` is ``-(k + 1)``; ``CHECKPOINT`` if the search
    budget ran out (then ``t`` is a time before which there is no contact).
    Touching shapes closing slower than ``still`` (at least the search's own
    rounding estimate; ``pge.core.predict.still_speed``) are not approaching.
    """
    if omega == 0.0 and alpha == 0.0:
        c = math.cos(theta0)
        s = math.sin(theta0)
        return circle_polygon(
            c * px + s * py,
            -s * px + c * py,
            c * vx + s * vy,
            -s * vx + c * vy,
            c * ax + s * ay,
            -s * ax + c * ay,
            radius,
            outline,
            start,
            n,
            horizon,
            still,
        )
    t, feature, _ = rotating_search(
        px, py, vx, vy, ax, ay, outline, 0, 0, 0.0, 0.0, start, n, theta0, omega, radius, True, horizon, MAX_ITERATIONS,
        still, 0.0, alpha,
    )
    return t, feature


@njit(cache=True)
def rotating_polygon_polygon(
    dx, dy, dvx, dvy, dax, day, outline, start_a, n_a, theta_a, omega_a, start_b, n_b, theta_b, omega_b, horizon,
    still=0.0, alpha_a=0.0, alpha_b=0.0,
):
    """First contact of two translating, rotating convex polygons within ``[0, horizon]``.

    ``d, dv, da``: offset, velocity and acceleration of a's centroid relative
    to b's (world axes); each polygon is outline rows ``start .. start + n - 1``
    at angle ``theta + omega t + alpha t^2 / 2``. Returns ``(t, feature)`` with ``t`` as in
    ``rotating_circle_polygon``; feature ``k < n_b``: edge ``k`` of b struck by a
    vertex of a, ``n_b + k``: edge ``k`` of a struck by a vertex of b;
    ``CHECKPOINT`` if the search budget ran out. ``still`` as in
    ``rotating_circle_polygon``.
    """
    if omega_a == 0.0 and omega_b == 0.0 and alpha_a == 0.0 and alpha_b == 0.0:
        if theta_a == 0.0 and theta_b == 0.0:
            return polygon_polygon(dx, dy, dvx, dvy, dax, day, outline, start_a, n_a, start_b, n_b, horizon, still)
        # Work in b's frame, where a is turned by theta_a - theta_b.
        rows = np.empty((n_a + n_b, 5))
        _place(outline, start_a, n_a, theta_a - theta_b, rows, 0)
        _place(outline, start_b, n_b, 0.0, rows, n_a)
        c = math.cos(theta_b)
        s = math.sin(theta_b)
        return polygon_polygon(
            c * dx + s * dy,
            -s * dx + c * dy,
            c * dvx + s * dvy,
            -s * dvx + c * dvy,
            c * dax + s * day,
            -s * dax + c * day,
            rows,
            0,
            n_a,
            n_a,
            n_b,
            horizon,
            still,
        )
    t, feature, _ = rotating_search(
        dx,
        dy,
        dvx,
        dvy,
        dax,
        day,
        outline,
        start_a,
        n_a,
        theta_a,
        omega_a,
        start_b,
        n_b,
        theta_b,
        omega_b,
        0.0,
        False,
        horizon,
        MAX_ITERATIONS,
        still,
        alpha_a,
        alpha_b,
    )
    return t, feature


# ---------------------------------------------------------------- contact points


@njit(cache=True)
def rotating_circle_polygon_contact(cx, cy, radius, px, py, outline, start, n, theta, feature):
    """Contact point and unit normal (from the polygon towards the circle), world coordinates.

    ``(cx, cy)``: the circle's centre, ``(px, py)`` the polygon's centroid and
    ``theta`` its angle, all at the contact time. Returns ``(point_x, point_y,
    normal_x, normal_y)``: for an edge the point on the circle's rim, for a
    corner the corner. A feature outside the polygon's range (``CHECKPOINT``)
    means the polygon's nearest feature.
    """
    c = math.cos(theta)
    s = math.sin(theta)
    ox = cx - px
    oy = cy - py
    lx = c * ox + s * oy
    ly = -s * ox + c * oy
    if not -n <= feature < n:
        feature, _, _, _ = closest_feature(lx, ly, radius, outline, start, n)
    qx, qy, mx, my = circle_polygon_contact(lx, ly, radius, 0.0, 0.0, outline, start, n, feature)
    return px + c * qx - s * qy, py + s * qx + c * qy, c * mx - s * my, s * mx + c * my


@njit(cache=True)
def rotating_polygon_polygon_contact(
    ax, ay, bx, by, dvx, dvy, outline, start_a, n_a, theta_a, omega_a, start_b, n_b, theta_b, omega_b, feature
):
    """Contact point and unit normal (from b towards a), world coordinates.

    ``(ax, ay)``, ``(bx, by)``: the centroids and ``theta_a``, ``theta_b`` the
    angles at the contact time; ``(dvx, dvy)`` the velocity of a's centroid
    relative to b's and ``omega_a``, ``omega_b`` the angular velocities, which
    choose the point on a face-to-face patch: the patch is the striking
    polygon's vertices within 1e-10 x the shapes' size of the struck edge's
    line, clipped to that edge; the point is its faster-approaching end, or
    its middle when both ends approach equally fast (no relative rotation). A
    single striking vertex is the point itself. Returns ``(point_x, point_y,
    normal_x, normal_y)``. A feature outside ``0 .. n_a + n_b - 1``
    (``CHECKPOINT``) means the face of largest separation now.
    """
    geo = np.empty((n_a + n_b, 5))
    _place(outline, start_a, n_a, theta_a, geo, 0)
    _place(outline, start_b, n_b, theta_b, geo, n_a)
    ox = ax - bx
    oy = ay - by
    if not 0 <= feature < n_a + n_b:
        feature, _ = _separation(geo, n_a, n_b, ox, oy)
    tie = _TIE * (_reach(outline, start_a, n_a) + _reach(outline, start_b, n_b))
    px, py, nx, ny, _ = _patch(geo, n_a, n_b, ox, oy, dvx, dvy, omega_a, omega_b, feature, tie)
    return bx + px, by + py, nx, ny
