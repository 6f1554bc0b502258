"""Convex polygon against convex polygon, both translating with constant acceleration.

Polygon a overlaps polygon b exactly when the offset ``d = pos_a - pos_b``
lies in the Minkowski difference ``B - A`` of their outlines. That set is a
convex polygon whose faces carry the edge normals of both outlines, so the
first contact is the first time ``d(t)`` enters it through one face: per face
a quadratic ``s(t) = g . d(t) + h`` (the distance of the other polygon's
support vertex from the edge's line) and a check that the entry point lies on
the face (every other face value is <= 0 there). Without rotation the support
vertex of each face is fixed, so a pair costs ``n_a + n_b`` quadratics.

Features: edge ``k`` of b struck by a vertex of a is ``k``; edge ``k`` of a
struck by a vertex of b is ``n_b + k``. Outline arrays as in
``pge.toi.circle_polygon``.
"""

from __future__ import annotations

import math

import numpy as np
from pge._jit_cache import njit

from pge.numerics.roots import first_descent_quadratic

_INF = math.inf
_EXTENT_TOLERANCE = 1e-12


@njit(cache=True)
def _support(outline, start, n, gx, gy):
    """Index (0-based within the polygon) of the vertex minimising ``g . v``."""
    best = _INF
    best_k = 0
    for k in range(n):
        value = gx * outline[start + k, 0] + gy * outline[start + k, 1]
        if value < best:
            best = value
            best_k = k
    return best_k


@njit(cache=True)
def minkowski_faces(outline, start_a, n_a, start_b, n_b):
    """Face records ``(gx, gy, h)``, ``s = g . d + h`` for ``d = pos_a - pos_b``."""
    faces = np.empty((n_a + n_b, 3))
    for k in range(n_b):
        row = start_b + k
        mx = outline[row, 2]
        my = outline[row, 3]
        s = start_a + _support(outline, start_a, n_a, mx, my)
        faces[k, 0] = mx
        faces[k, 1] = my
        faces[k, 2] = mx * (outline[s, 0] - outline[row, 0]) + my * (outline[s, 1] - outline[row, 1])
    for k in range(n_a):
        row = start_a + k
        nx = outline[row, 2]
        ny = outline[row, 3]
        s = start_b + _support(outline, start_b, n_b, nx, ny)
        faces[n_b + k, 0] = -nx
        faces[n_b + k, 1] = -ny
        faces[n_b + k, 2] = nx * (outline[s, 0] - outline[row, 0]) + ny * (outline[s, 1] - outline[row, 1])
    return faces


@njit(cache=True)
def polygon_polygon(dx, dy, dvx, dvy, dax, day, outline, start_a, n_a, start_b, n_b, horizon, still=0.0):
    """First contact of two translating convex polygons within ``[0, horizon]``.

    ``(dx, dy)``, ``(dvx, dvy)``, ``(dax, day)``: offset, velocity and
    acceleration of a's centroid relative to b's. Returns ``(t, feature)``;
    t = inf for no contact. Touching shapes closing or separating slower
    than ``still`` (``pge.core.predict.still_speed``) are at rest relative to
    each other: a contact now only if pressed together.
    """
    faces = minkowski_faces(outline, start_a, n_a, start_b, n_b)
    count = n_a + n_b
    best_s = -_INF
    best_f = 0
    for f in range(count):
        s = faces[f, 0] * dx + faces[f, 1] * dy + faces[f, 2]
        if s > best_s:
            best_s = s
            best_f = f
    closing = faces[best_f, 0] * dvx + faces[best_f, 1] * dvy
    if best_s <= 0.0 and abs(closing) <= still:
        closing = 0.0  # neither approaching nor separating, to rounding
    pressing = faces[best_f, 0] * dax + faces[best_f, 1] * day
    if best_s <= 0.0 and (closing < 0.0 or (closing == 0.0 and pressing < 0.0)):
        return 0.0, best_f
    reach = 0.0
    for k in range(n_a):
        reach = max(reach, math.hypot(outline[start_a + k, 0], outline[start_a + k, 1]))
    for k in range(n_b):
        reach = max(reach, math.hypot(outline[start_b + k, 0], outline[start_b + k, 1]))
    tolerance = _EXTENT_TOLERANCE * reach
    if -tolerance <= best_s <= 0.0 and pressing < 0.0 and closing * closing <= 2.0 * pressing * best_s:
        # Touching to rounding, pressed, and separating too slowly for the gap ever to
        # open: the contact closes again from the gap's peak on.
        t = closing / -pressing
        if t <= horizon:
            return t, best_f
    hax = 0.5 * dax
    hay = 0.5 * day
    best_t = horizon
    best_feature = 0
    found = False
    for f in range(count):
        gx = faces[f, 0]
        gy = faces[f, 1]
        s0 = gx * dx + gy * dy + faces[f, 2]
        s1 = gx * dvx + gy * dvy
        s2 = gx * hax + gy * hay
        if s0 > 0.0 and s1 >= 0.0 and s2 >= 0.0:
            continue
        t = first_descent_quadratic(s0, s1, s2, best_t, False)
        if t == _INF or (found and t >= best_t):
            continue
        qx = dx + (dvx + hax * t) * t
        qy = dy + (dvy + hay * t) * t
        inside = True
        for g in range(count):
            if g != f and faces[g, 0] * qx + faces[g, 1] * qy + faces[g, 2] > tolerance:
                inside = False
                break
        if inside:
            best_t = t
            best_feature = f
            found = True
    if not found:
        return _INF, 0
    return best_t, best_feature


@njit(cache=True)
def _face_contact(outline, start_e, n_e, edge, ex, ey, start_o, n_o, ox, oy):
    """Contact point of polygon o (centroid ``(ox, oy)``) touching edge ``edge`` of polygon
    e (centroid ``(ex, ey)``): o's nearest vertex, or the middle of the overlap when an
    edge of o lies along the edge."""
    row = start_e + edge
    nx = outline[row, 2]
    ny = outline[row, 3]
    tx = -ny
    ty = nx
    qx = ex + outline[row, 0]
    qy = ey + outline[row, 1]
    length = outline[row, 4]
    lowest = _INF
    for k in range(n_o):
        lowest = min(lowest, nx * outline[start_o + k, 0] + ny * outline[start_o + k, 1])
    reach = 0.0
    for k in range(n_o):
        reach = max(reach, math.hypot(outline[start_o + k, 0], outline[start_o + k, 1]))
    tolerance = 1e-9 * reach
    low = _INF
    high = -_INF
    for k in range(n_o):
        vx = outline[start_o + k, 0]
        vy = outline[start_o + k, 1]
        if nx * vx + ny * vy <= lowest + tolerance:
            u = (ox + vx - qx) * tx + (oy + vy - qy) * ty
            low = min(low, u)
            high = max(high, u)
    low = max(low, 0.0)
    high = min(high, length)
    u = 0.5 * (low + high) if low <= high else (low if low > length else high)
    return qx + u * tx, qy + u * ty


@njit(cache=True)
def polygon_polygon_contact(ax, ay, bx, by, outline, start_a, n_a, start_b, n_b, feature):
    """Contact point and unit normal (pointing from b towards a).

    ``(ax, ay)`` and ``(bx, by)`` are the centroids at the contact time. The
    point lies on the struck edge: the striking vertex, or the middle of the
    shared stretch when two edges meet flat. Returns
    ``(point_x, point_y, normal_x, normal_y)``.
    """
    if feature < n_b:
        mx = outline[start_b + feature, 2]
        my = outline[start_b + feature, 3]
        px, py = _face_contact(outline, start_b, n_b, feature, bx, by, start_a, n_a, ax, ay)
        return px, py, mx, my
    edge = feature - n_b
    nx = outline[start_a + edge, 2]
    ny = outline[start_a + edge, 3]
    px, py = _face_contact(outline, start_a, n_a, edge, ax, ay, start_b, n_b, bx, by)
    return px, py, -nx, -ny
