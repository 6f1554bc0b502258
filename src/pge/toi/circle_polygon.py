"""Circle against convex polygon under constant relative acceleration.

The disc touches the polygon when its centre reaches the polygon grown by the
radius: a union of the polygon, one slab per edge and one disc per corner.
The first entry into that union is the earliest of (a) a crossing of an edge's
offset line with the foot inside the edge (a quadratic per edge) and (b) an
entry into a corner disc (a quartic per corner, quadratic without relative
acceleration). Features: edge ``k`` is ``k``, corner ``k`` is ``-(k + 1)``.

Polygons are rows ``start .. start + n - 1`` of an outline array (columns
``VX, VY, NX, NY, LENGTH``: vertex relative to the centroid, unit outward
normal of the edge from this vertex to the next, edge length).
"""

from __future__ import annotations

import math

from pge._jit_cache import njit

from pge.numerics.roots import first_descent, first_descent_quadratic

_INF = math.inf
_EXTENT_TOLERANCE = 1e-12


@njit(cache=True)
def closest_feature(px, py, radius, outline, start, n):
    """Feature nearest to a centre at ``(px, py)``: ``(feature, nx, ny, gap)``.

    The normal points from the polygon towards the centre; the gap is the
    distance minus ``radius`` (negative when overlapping). For a centre inside
    the polygon the nearest feature is the face of least penetration.
    """
    best_s = -_INF
    best_k = 0
    for k in range(n):
        row = start + k
        s = outline[row, 2] * (px - outline[row, 0]) + outline[row, 3] * (py - outline[row, 1])
        if s > best_s:
            best_s = s
            best_k = k
    if best_s <= 0.0:
        row = start + best_k
        return best_k, outline[row, 2], outline[row, 3], best_s - radius
    feature = -1
    fnx = 1.0
    fny = 0.0
    dist = _INF
    for k in range(n):
        row = start + k
        nx = outline[row, 2]
        ny = outline[row, 3]
        ox = px - outline[row, 0]
        oy = py - outline[row, 1]
        s = nx * ox + ny * oy
        if s > 0.0:
            u = -ny * ox + nx * oy
            if 0.0 <= u <= outline[row, 4] and s < dist:
                feature, fnx, fny, dist = k, nx, ny, s
        d = math.hypot(ox, oy)
        if d < dist and d > 0.0:
            feature, fnx, fny, dist = -(k + 1), ox / d, oy / d, d
    return feature, fnx, fny, dist - radius


@njit(cache=True)
def _sliding_off(px, py, vx, vy, outline, start, n, feature):
    """The corner feature (``-(k + 1)``) a circle touching edge ``feature`` is sliding off
    at, or ``feature`` itself when it is not at an end of the edge moving outwards.

    "At an end" has a tolerance of ``_EXTENT_TOLERANCE`` of the edge's length: a position
    measured from world coordinates may round to either side of the end.
    """
    if feature < 0:
        return feature
    row = start + feature
    tx = -outline[row, 3]
    ty = outline[row, 2]
    vt = tx * vx + ty * vy
    u = tx * (px - outline[row, 0]) + ty * (py - outline[row, 1])
    tolerance = _EXTENT_TOLERANCE * outline[row, 4]
    if u >= outline[row, 4] - tolerance and vt > 0.0:
        return -((feature + 1) % n + 1)
    if u <= tolerance and vt < 0.0:
        return -(feature + 1)
    return feature


@njit(cache=True)
def _pressed(px, py, vx, vy, ax, ay, radius, outline, start, n, feature, nx, ny):
    """Whether a circle touching a feature at zero normal speed is pushed into it.

    On a flat edge that is the normal acceleration. Around a corner (or at the
    end of an edge that the circle is sliding off) the path must also turn:
    the distance's second derivative gains ``v_t^2 / R`` (centripetal), so a
    fast enough circle flies off instead of pressing.
    """
    accel = nx * ax + ny * ay
    vt = -ny * vx + nx * vy
    if _sliding_off(px, py, vx, vy, outline, start, n, feature) < 0:
        accel += vt * vt / radius
    return accel < 0.0


@njit(cache=True, inline="always")
def _on_edge(px, py, vx, vy, ax, ay, outline, row, t):
    """Whether a circle whose centre meets the offset plane of the edge in ``row`` at ``t``
    meets the edge there: its foot within the edge (to ``_EXTENT_TOLERANCE`` of its length),
    and not at an end it is sliding off (the corner's to judge)."""
    nx = outline[row, 2]
    ny = outline[row, 3]
    u = -ny * (px + (vx + 0.5 * ax * t) * t - outline[row, 0]) + nx * (py + (vy + 0.5 * ay * t) * t - outline[row, 1])
    length = outline[row, 4]
    tolerance = _EXTENT_TOLERANCE * length
    vt = -ny * (vx + ax * t) + nx * (vy + ay * t)
    if (u >= length - tolerance and vt > 0.0) or (u <= tolerance and vt < 0.0):
        return False
    return -tolerance <= u <= length + tolerance


@njit(cache=True)
def _reclosing(px, py, vx, vy, ax, ay, radius, outline, start, feature, horizon):
    """When a circle touching ``feature`` (to rounding) and separating from it touches it again.

    A gap that is zero to rounding, opening too slowly, and pressed shut by the
    acceleration never becomes positive: it peaks and closes at once. The
    feature's own gap function (``first_descent`` with ``immediate``) returns
    that peak; inf when the gap opens for real or does not close within ``horizon``.
    """
    if feature >= 0:
        row = start + feature
        nx = outline[row, 2]
        ny = outline[row, 3]
        s0 = nx * (px - outline[row, 0]) + ny * (py - outline[row, 1]) - radius
        return first_descent_quadratic(s0, nx * vx + ny * vy, 0.5 * (nx * ax + ny * ay), horizon, True)
    row = start - feature - 1
    ox = px - outline[row, 0]
    oy = py - outline[row, 1]
    return first_descent(
        ox * ox + oy * oy - radius * radius,
        2.0 * (ox * vx + oy * vy),
        vx * vx + vy * vy + ox * ax + oy * ay,
        vx * ax + vy * ay,
        0.25 * (ax * ax + ay * ay),
        horizon,
        True,
    )


@njit(cache=True)
def circle_polygon(px, py, vx, vy, ax, ay, radius, outline, start, n, horizon, still=0.0):
    """First contact of a circle and a convex polygon within ``[0, horizon]``.

    ``(px, py)``, ``(vx, vy)``, ``(ax, ay)``: the circle's centre, velocity and
    acceleration relative to the polygon's centroid. Returns
    ``(t, feature)``; t = inf for no contact. Touching shapes closing or
    separating slower than ``still`` (``pge.core.predict.still_speed``) are at
    rest relative to each other: a contact now only if pressed together.
    """
    best_t = horizon
    best_feature = 0
    found = False
    # Overlap at t = 0 is judged for the shape as a whole, by its nearest feature.
    max_s = -_INF
    for k in range(n):
        row = start + k
        s = outline[row, 2] * (px - outline[row, 0]) + outline[row, 3] * (py - outline[row, 1])
        if s > max_s:
            max_s = s
    # (With a tolerance: at a corner on the border of an edge's region that edge's plane
    # distance is the corner distance, and the two round differently.)
    if max_s <= radius * (1.0 + _EXTENT_TOLERANCE):
        feature, nx, ny, gap = closest_feature(px, py, radius, outline, start, n)
        closing = nx * vx + ny * vy
        if abs(closing) <= still:
            closing = 0.0  # neither approaching nor separating, to rounding
        if gap <= 0.0 and (closing < 0.0 or (closing == 0.0 and _pressed(px, py, vx, vy, ax, ay, radius, outline, start, n, feature, nx, ny))):
            return 0.0, feature
        if gap <= 0.0 and closing > 0.0:
            # A circle sliding off the end of an edge is judged against the corner there.
            feature = _sliding_off(px, py, vx, vy, outline, start, n, feature)
            reclose = _reclosing(px, py, vx, vy, ax, ay, radius, outline, start, feature, horizon)
            # An edge's reclosing is on its plane: where the circle has slid past the edge's
            # end by then, the corner there is what it meets (the loop over corners below).
            meets = feature < 0 or _on_edge(px, py, vx, vy, ax, ay, outline, start + feature, reclose)
            if 0.0 < reclose < _INF and meets:
                best_t = reclose
                best_feature = feature
                found = True
    hax = 0.5 * ax
    hay = 0.5 * ay
    for k in range(n):
        row = start + k
        nx = outline[row, 2]
        ny = outline[row, 3]
        x0 = outline[row, 0]
        y0 = outline[row, 1]
        s0 = nx * (px - x0) + ny * (py - y0) - radius
        s1 = nx * vx + ny * vy
        s2 = nx * hax + ny * hay
        if s0 > 0.0 and s1 >= 0.0 and s2 >= 0.0:
            continue
        t = first_descent_quadratic(s0, s1, s2, best_t, False)
        if t != _INF and _on_edge(px, py, vx, vy, ax, ay, outline, row, t):
            best_t = t
            best_feature = k
            found = True
    speed = math.hypot(vx, vy)
    accel = math.hypot(ax, ay)
    rr = radius * radius
    for k in range(n):
        row = start + k
        ox = px - outline[row, 0]
        oy = py - outline[row, 1]
        reach = radius + (speed + 0.5 * accel * best_t) * best_t
        dist2 = ox * ox + oy * oy
        if dist2 > reach * reach * (1.0 + 1e-12):
            continue
        c1 = 2.0 * (ox * vx + oy * vy)
        c2 = vx * vx + vy * vy
        if ax == 0.0 and ay == 0.0:
            t = first_descent_quadratic(dist2 - rr, c1, c2, best_t, False)
        else:
            t = first_descent(
                dist2 - rr, c1, c2 + ox * ax + oy * ay, vx * ax + vy * ay, 0.25 * (ax * ax + ay * ay), best_t, False
            )
        if t != _INF and (not found or t < best_t):
            best_t = t
            best_feature = -(k + 1)
            found = True
    if not found:
        return _INF, 0
    return best_t, best_feature


@njit(cache=True)
def circle_polygon_contact(cx, cy, radius, px, py, outline, start, n, feature):
    """Contact point and unit normal (from the polygon towards the circle).

    ``(cx, cy)`` is the circle's centre and ``(px, py)`` the polygon's centroid
    at the contact time. Returns ``(point_x, point_y, normal_x, normal_y)``.
    """
    if feature >= 0:
        row = start + feature
        nx = outline[row, 2]
        ny = outline[row, 3]
        return cx - nx * radius, cy - ny * radius, nx, ny
    row = start - feature - 1
    qx = px + outline[row, 0]
    qy = py + outline[row, 1]
    ox = cx - qx
    oy = cy - qy
    dist = math.hypot(ox, oy)
    if dist == 0.0:
        # The centre sits on the corner: use the nearest face's normal.
        _, nx, ny, _ = closest_feature(cx - px, cy - py, radius, outline, start, n)
        return qx, qy, nx, ny
    return qx, qy, ox / dist, oy / dist
