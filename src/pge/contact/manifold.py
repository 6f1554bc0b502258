"""Contact manifolds: where two bodies touch now, as at most two points.

Every function takes the bodies' reference points and (for polygons) outline rows turned to
the current angle, and appends rows ``(px, py, nx, ny, separation, key)`` to ``out``: the
point midway between the two surfaces, the unit normal from the second body towards the first,
the signed distance along it (negative: overlapping) and an integer naming the features that
touch, so that a step can start from the impulses the same point took at the last step.
Points further apart than ``margin`` are left out.
"""

from __future__ import annotations

import math

from pge._jit_cache import njit
from pge.toi.circle_polygon import closest_feature

_INF = math.inf
_CORNER_KEY = 1 << 14  # keys of corner points, apart from the clipped points' (below 2**14)
#: columns of a manifold row
PX, PY, NX, NY, SEPARATION, KEY = 0, 1, 2, 3, 4, 5
NCOLUMNS = 6


@njit(cache=True)
def circle_circle_points(ax, ay, ra, bx, by, rb, margin, out, count):
    """Append the contact point of circles a and b (normal from b to a); returns the new count."""
    dx = ax - bx
    dy = ay - by
    d = math.hypot(dx, dy)
    separation = d - ra - rb
    if separation > margin:
        return count
    if d > 0.0:
        nx = dx / d
        ny = dy / d
    else:
        nx = 0.0
        ny = 1.0
    out[count, PX] = bx + nx * (rb + 0.5 * separation)
    out[count, PY] = by + ny * (rb + 0.5 * separation)
    out[count, NX] = nx
    out[count, NY] = ny
    out[count, SEPARATION] = separation
    out[count, KEY] = 0.0
    return count + 1


@njit(cache=True)
def circle_polygon_points(cx, cy, r, px, py, OL, start, n, flip, margin, out, count):
    """Append the contact point of a circle and a polygon; the normal runs from the polygon
    to the circle, or the other way round if ``flip`` (the polygon is the first body)."""
    feature, nx, ny, gap = closest_feature(cx - px, cy - py, r, OL, start, n)
    if gap > margin:
        return count
    out[count, PX] = cx - nx * (r + 0.5 * gap)
    out[count, PY] = cy - ny * (r + 0.5 * gap)
    if flip:
        nx = -nx
        ny = -ny
    out[count, NX] = nx
    out[count, NY] = ny
    out[count, SEPARATION] = gap
    out[count, KEY] = float(feature + 64)
    return count + 1


@njit(cache=True)
def _deepest_face(OL, s1, n1, x1, y1, s2, n2, x2, y2):
    """The face of polygon 1 along whose normal polygon 2 lies furthest out:
    ``(separation, face)``."""
    best = -_INF
    face = 0
    for k in range(n1):
        nx = OL[s1 + k, 2]
        ny = OL[s1 + k, 3]
        vx = x1 + OL[s1 + k, 0]
        vy = y1 + OL[s1 + k, 1]
        least = _INF
        for q in range(n2):
            d = nx * (x2 + OL[s2 + q, 0] - vx) + ny * (y2 + OL[s2 + q, 1] - vy)
            if d < least:
                least = d
        if least > best:
            best = least
            face = k
    return best, face


@njit(cache=True)
def polygon_polygon_points(ax, ay, OL, sa, na, bx, by, sb, nb, margin, tolerance, dip, out, count):
    """Append up to two contact points of polygons a and b (normal from b to a).

    The reference face is the face of either polygon with the largest separation (a's unless
    b's is larger by more than ``tolerance``, so that the choice does not flicker between
    steps); the points are the ends of the other polygon's most opposed face, clipped to the
    reference face's width. Where the incident face dips towards the reference face's line
    beyond the face's end by more than ``dip`` (``_face_points``), the reference polygon's
    corner meets the incident face, and a clipped point's separation is no gap: its speed
    along the normal is not the rate at which it closes (the clip slides along the incident
    face). Then the reference is the face with the larger separation (the separating-axis
    bound of the distance), whatever the hysteresis, and a clipped point's separation is at
    most its clipped-away end's: along that face's normal no vertex of the other polygon
    lies closer, so a translation that keeps every point's separation is a translation that
    keeps the two apart."""
    sep_a, face_a = _deepest_face(OL, sa, na, ax, ay, sb, nb, bx, by)
    if sep_a > margin:
        return count
    sep_b, face_b = _deepest_face(OL, sb, nb, bx, by, sa, na, ax, ay)
    if sep_b > margin:
        return count
    found, dipped = _either_face(OL, sa, na, ax, ay, face_a, sb, nb, bx, by, face_b, sep_b > sep_a + tolerance,
                                 False, margin, dip, out, count)
    if not dipped:
        return found
    found, _ = _either_face(OL, sa, na, ax, ay, face_a, sb, nb, bx, by, face_b, sep_b > sep_a, True, margin, dip,
                            out, count)
    return found


@njit(cache=True)
def _either_face(OL, sa, na, ax, ay, face_a, sb, nb, bx, by, face_b, on_b, cap, margin, dip, out, count):
    """``_face_points`` with b's face ``face_b`` as the reference if ``on_b``, else a's."""
    if on_b:
        return _face_points(OL, sb, nb, bx, by, face_b, sa, na, ax, ay, 1.0, 0, cap, margin, dip, out, count)
    return _face_points(OL, sa, na, ax, ay, face_a, sb, nb, bx, by, -1.0, 1, cap, margin, dip, out, count)


@njit(cache=True)
def _face_points(OL, rs, rn, rx, ry, face, js, jn, jx, jy, sign, owner, cap, margin, dip, out, count):
    """Append the points of reference face ``face`` of the polygon at rows ``rs`` (``rn``
    of them, at ``(rx, ry)``) against the other polygon's most opposed face, clipped to the
    reference face's width; returns the new count and whether a clipped-away end of the
    incident face lies closer to the reference face's line than its clipped point, by more
    than ``dip``. With ``cap``, a clipped point's separation is at most its clipped-away
    end's."""
    nx = OL[rs + face, 2]
    ny = OL[rs + face, 3]
    v1x = rx + OL[rs + face, 0]
    v1y = ry + OL[rs + face, 1]
    tx = -ny
    ty = nx
    width = OL[rs + face, 4]
    # The incident face: the other polygon's face most opposed to the reference normal.
    incident = 0
    least = _INF
    for q in range(jn):
        d = OL[js + q, 2] * nx + OL[js + q, 3] * ny
        if d < least:
            least = d
            incident = q
    nxt = incident + 1 if incident + 1 < jn else 0
    w1x = jx + OL[js + incident, 0]
    w1y = jy + OL[js + incident, 1]
    w2x = jx + OL[js + nxt, 0]
    w2y = jy + OL[js + nxt, 1]
    # Clip the incident segment to the reference face's span [0, width] along its tangent.
    u1 = (w1x - v1x) * tx + (w1y - v1y) * ty
    u2 = (w2x - v1x) * tx + (w2y - v1y) * ty
    dipped = False
    cap1 = _INF
    cap2 = _INF
    for end in range(2):
        lo = 0.0 if end == 0 else width
        if end == 0:
            outside1 = u1 < lo
            outside2 = u2 < lo
        else:
            outside1 = u1 > lo
            outside2 = u2 > lo
        if outside1 and outside2:
            return _corner_point(OL, rs, rn, rx, ry, face, js, jn, jx, jy, sign, owner, out, count), False
        if outside1 or outside2:
            f = (lo - u1) / (u2 - u1)
            cx = w1x + f * (w2x - w1x)
            cy = w1y + f * (w2y - w1y)
            clipped = (cx - v1x) * nx + (cy - v1y) * ny
            if outside1:
                away = (w1x - v1x) * nx + (w1y - v1y) * ny
                w1x, w1y, u1 = cx, cy, lo
                if cap:
                    cap1 = away
            else:
                away = (w2x - v1x) * nx + (w2y - v1y) * ny
                w2x, w2y, u2 = cx, cy, lo
                if cap:
                    cap2 = away
            dipped = dipped or away < clipped - dip
    before = count
    for end in range(2):
        wx = w1x if end == 0 else w2x
        wy = w1y if end == 0 else w2y
        separation = min((wx - v1x) * nx + (wy - v1y) * ny, cap1 if end == 0 else cap2)
        if separation > margin:
            continue
        out[count, PX] = wx - 0.5 * separation * nx
        out[count, PY] = wy - 0.5 * separation * ny
        out[count, NX] = sign * nx
        out[count, NY] = sign * ny
        out[count, SEPARATION] = separation
        out[count, KEY] = float(((owner * 64 + face) * 64 + incident) * 2 + end)
        count += 1
    if count == before:
        return _corner_point(OL, rs, rn, rx, ry, face, js, jn, jx, jy, sign, owner, out, count), dipped
    return count, dipped


@njit(cache=True)
def _corner_point(OL, rs, rn, rx, ry, face, js, jn, jx, jy, sign, owner, out, count):
    """Append the one point of a corner contact whose incident face clips away (two corners
    meeting, a sharp corner beside the reference face's end): the other polygon's deepest
    vertex along the reference normal, whose separation is the separating-axis value that
    admitted the pair, so the manifold is never empty when the polygons are within the
    margin. The point lies midway to the reference face's line, clamped to the face."""
    nx = OL[rs + face, 2]
    ny = OL[rs + face, 3]
    v1x = rx + OL[rs + face, 0]
    v1y = ry + OL[rs + face, 1]
    deepest = 0
    least = _INF
    for q in range(jn):
        d = (jx + OL[js + q, 0] - v1x) * nx + (jy + OL[js + q, 1] - v1y) * ny
        if d < least:
            least = d
            deepest = q
    wx = jx + OL[js + deepest, 0]
    wy = jy + OL[js + deepest, 1]
    tx = -ny
    ty = nx
    along = min(max((wx - v1x) * tx + (wy - v1y) * ty, 0.0), OL[rs + face, 4])
    fx = v1x + along * tx  # the nearest point of the reference face to the vertex
    fy = v1y + along * ty
    out[count, PX] = 0.5 * (wx + fx)
    out[count, PY] = 0.5 * (wy + fy)
    out[count, NX] = sign * nx
    out[count, NY] = sign * ny
    out[count, SEPARATION] = least
    out[count, KEY] = float(_CORNER_KEY + (owner * 64 + face) * 64 + deepest)
    return count + 1
