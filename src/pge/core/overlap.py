"""Overlap of two bodies now: the validation of a scene, and the check a teleport must pass.

``overlap_depth`` measures how far two bodies interpenetrate at ``P[TIME]``
(negative when apart); ``find_overlap`` looks for a pair among some bodies and
their grid neighbours that overlaps by more than a tolerance. The World uses
them to refuse bodies placed into others.
"""

from __future__ import annotations

import math

from pge._jit_cache import njit

from pge.core import layout as L
from pge.core.grid import gather
from pge.core.motion import orient, state_at
from pge.toi.circle_polygon import closest_feature
from pge.toi.polygon_polygon import minkowski_faces

_INF = math.inf
CIRCLE = 0


@njit(cache=True)
def overlap_depth(S, i, j):
    """Overlap depth of bodies ``i`` and ``j`` at ``P[TIME]`` (negative: apart; for two
    polygons a lower bound on the distance)."""
    return nearest_normal(S, i, j)[2]


@njit(cache=True)
def nearest_normal(S, i, j):
    """``(nx, ny, depth)`` of bodies ``i`` and ``j`` at ``P[TIME]``: the unit normal of their
    nearest features, from ``j`` towards ``i``, and the overlap depth as ``overlap_depth``."""
    F = S.F
    I = S.I
    OL = S.OL
    P = S.P
    orient(F, I, OL, S.OB, i, P[L.TIME])
    orient(F, I, OL, S.OB, j, P[L.TIME])
    xi, yi, _, _ = state_at(F, i, P[L.TIME])
    xj, yj, _, _ = state_at(F, j, P[L.TIME])
    dx = xi - xj
    dy = yi - yj
    if I[i, L.KIND] == CIRCLE and I[j, L.KIND] == CIRCLE:
        d = math.hypot(dx, dy)
        if d == 0.0:
            return 1.0, 0.0, F[i, L.RADIUS] + F[j, L.RADIUS]
        return dx / d, dy / d, F[i, L.RADIUS] + F[j, L.RADIUS] - d
    if I[i, L.KIND] == CIRCLE:
        _, nx, ny, gap = closest_feature(dx, dy, F[i, L.RADIUS], OL, I[j, L.OUTLINE_START], I[j, L.OUTLINE_N])
        return nx, ny, -gap
    if I[j, L.KIND] == CIRCLE:
        _, nx, ny, gap = closest_feature(-dx, -dy, F[j, L.RADIUS], OL, I[i, L.OUTLINE_START], I[i, L.OUTLINE_N])
        return -nx, -ny, -gap
    faces = minkowski_faces(OL, I[i, L.OUTLINE_START], I[i, L.OUTLINE_N], I[j, L.OUTLINE_START], I[j, L.OUTLINE_N])
    best = -_INF
    best_f = 0
    for f in range(faces.shape[0]):
        s = faces[f, 0] * dx + faces[f, 1] * dy + faces[f, 2]
        if s > best:
            best = s
            best_f = f
    return faces[best_f, 0], faces[best_f, 1], -best


@njit(cache=True)
def find_overlap(S, ids, tolerance):
    """First pair ``(i, j, depth)`` among ``ids`` and their neighbours overlapping by more
    than ``tolerance`` times their bounding radii; ``(-1, -1, 0.0)`` when there is none."""
    F = S.F
    I = S.I
    scratch = S.scratch
    for k in range(ids.shape[0]):
        i = ids[k]
        n = gather(S, i)
        for m in range(n):
            j = scratch[m]
            if I[i, L.FIXED] != 0 and I[j, L.FIXED] != 0:
                continue
            depth = overlap_depth(S, i, j)
            if depth > tolerance * (F[i, L.REACH] + F[j, L.REACH]):
                return i, j, depth
    return -1, -1, 0.0
