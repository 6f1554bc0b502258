"""Plane geometry of convex shapes: validation, mass properties and overlap depth.

Pure functions of numbers and tuples; nothing here knows about bodies or the
world. Polygons are given as vertex lists; internally they are kept
anticlockwise, relative to their area centroid.
"""

from __future__ import annotations

import math
import numbers
from typing import Sequence

__all__ = [
    "Vec",
    "check_number",
    "check_vector",
    "polygon_properties",
    "edge_normals",
    "rotate_points",
    "circle_circle_depth",
    "circle_polygon_depth",
    "polygon_polygon_depth",
]

Vec = tuple[float, float]


def check_number(owner: str, what: str, value) -> float:
    """``value`` as a finite float, or a TypeError/ValueError naming ``owner`` and ``what``."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError(f"{owner}: {what} must be a number, got {type(value).__name__} {value!r}")
    value = float(value)
    if not math.isfinite(value):
        raise ValueError(f"{owner}: {what} must be finite, got {value!r}")
    return value


def check_vector(owner: str, what: str, value) -> Vec:
    """``value`` as a pair of finite floats, or a clear TypeError/ValueError."""
    if isinstance(value, (str, bytes)):
        raise TypeError(f"{owner}: {what} must be a pair of numbers (x, y), got {value!r}")
    try:
        items = tuple(value)
    except TypeError:
        raise TypeError(
            f"{owner}: {what} must be a pair of numbers (x, y), got {value!r}"
        ) from None
    if len(items) != 2:
        raise ValueError(
            f"{owner}: {what} must be a pair of numbers (x, y), got {len(items)} values"
        )
    return (check_number(owner, f"{what}[0]", items[0]), check_number(owner, f"{what}[1]", items[1]))


def polygon_properties(points: Sequence, owner: str = "polygon"):
    """Validate a convex polygon and compute its mass properties.

    ``points`` are the vertices in order (clockwise or anticlockwise). Raises
    ValueError naming ``owner`` for fewer than 3 distinct vertices, repeated
    consecutive vertices, zero area, a non-convex outline or a self-intersecting
    (star-shaped) outline; TypeError for values that are not numbers.

    Returns ``(centroid, local_vertices, area, inertia_per_mass,
    bounding_radius)`` where ``local_vertices`` are anticlockwise and relative
    to the area centroid, ``inertia_per_mass`` is the polar moment of a uniform
    lamina about its centroid divided by its mass, and ``bounding_radius`` is
    the largest vertex distance from the centroid.
    """
    try:
        raw = list(points)
    except TypeError:
        raise TypeError(f"{owner}: vertices must be a sequence of (x, y) pairs") from None
    pts = [check_vector(owner, f"vertex {k}", p) for k, p in enumerate(raw)]
    n = len(pts)
    if len(set(pts)) < 3:
        raise ValueError(f"{owner}: needs at least 3 distinct vertices, got {len(set(pts))}")
    for k in range(n):
        if pts[k] == pts[(k + 1) % n]:
            raise ValueError(
                f"{owner}: vertex {(k + 1) % n} repeats vertex {k}; give each corner once"
            )
    crossing = None if _collinear(pts) else _edges_crossing(pts)
    if crossing is not None:
        raise ValueError(
            f"{owner}: is self-intersecting (edges {crossing[0]} and {crossing[1]} cross)"
        )
    ox, oy = pts[0]
    rel = [(x - ox, y - oy) for x, y in pts]
    scale = max(max(abs(x), abs(y)) for x, y in rel)
    twice_area = 0.0
    cx = cy = 0.0
    for k in range(n):
        x0, y0 = rel[k]
        x1, y1 = rel[(k + 1) % n]
        cross = x0 * y1 - x1 * y0
        twice_area += cross
        cx += (x0 + x1) * cross
        cy += (y0 + y1) * cross
    if abs(twice_area) <= 1e-12 * scale * scale:
        raise ValueError(f"{owner}: has zero area (its vertices are collinear)")
    orientation = 1.0 if twice_area > 0.0 else -1.0
    turning = 0.0
    for k in range(n):
        ax, ay = rel[k - 1]
        bx, by = rel[k]
        cx_, cy_ = rel[(k + 1) % n]
        e0x, e0y = bx - ax, by - ay
        e1x, e1y = cx_ - bx, cy_ - by
        cross = e0x * e1y - e0y * e1x
        tolerance = 1e-12 * math.hypot(e0x, e0y) * math.hypot(e1x, e1y)
        if cross * orientation < -tolerance:
            raise ValueError(
                f"{owner}: is not convex (the outline turns the other way at vertex {k})"
            )
        turning += math.atan2(cross, e0x * e1x + e0y * e1y)
    if abs(turning) > 3.0 * math.pi:
        raise ValueError(f"{owner}: is self-intersecting (its outline winds around more than once)")
    centroid_rel = (cx / (3.0 * twice_area), cy / (3.0 * twice_area))
    local = [(x - centroid_rel[0], y - centroid_rel[1]) for x, y in rel]
    if orientation < 0.0:
        local.reverse()
    num = 0.0
    den = 0.0
    for k in range(n):
        x0, y0 = local[k]
        x1, y1 = local[(k + 1) % n]
        cross = x0 * y1 - x1 * y0
        num += cross * (x0 * x0 + y0 * y0 + x0 * x1 + y0 * y1 + x1 * x1 + y1 * y1)
        den += cross
    inertia_per_mass = num / (6.0 * den)
    centroid = (ox + centroid_rel[0], oy + centroid_rel[1])
    bounding_radius = max(math.hypot(x, y) for x, y in local)
    return centroid, tuple(local), 0.5 * abs(twice_area), inertia_per_mass, bounding_radius


def _edges_crossing(pts):
    """The first pair of non-adjacent edges ``(k, m)`` that intersect, or None.

    Edge ``k`` runs from vertex ``k`` to vertex ``k + 1``. Exact orientation
    tests on the given coordinates; touching counts as crossing.
    """
    n = len(pts)

    def orient(a, b, c):
        value = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
        return (value > 0) - (value < 0)

    def on_segment(a, b, c):
        return min(a[0], b[0]) <= c[0] <= max(a[0], b[0]) and min(a[1], b[1]) <= c[1] <= max(a[1], b[1])

    for k in range(n):
        a, b = pts[k], pts[(k + 1) % n]
        for m in range(k + 2, n):
            if k == 0 and m == n - 1:
                continue  # adjacent through the closing vertex
            c, d = pts[m], pts[(m + 1) % n]
            o1, o2, o3, o4 = orient(a, b, c), orient(a, b, d), orient(c, d, a), orient(c, d, b)
            if o1 != o2 and o3 != o4:
                return k, m
            if (o1 == 0 and on_segment(a, b, c)) or (o2 == 0 and on_segment(a, b, d)):
                if not (o1 == o2 == o3 == o4 == 0 and not _overlap_1d(a, b, c, d)):
                    return k, m
            if (o3 == 0 and on_segment(c, d, a)) or (o4 == 0 and on_segment(c, d, b)):
                return k, m
    return None


def _collinear(pts) -> bool:
    """Whether all points lie on one line (relative to their spread)."""
    ox, oy = pts[0]
    far = max(pts, key=lambda p: (p[0] - ox) ** 2 + (p[1] - oy) ** 2)
    dx, dy = far[0] - ox, far[1] - oy
    scale = dx * dx + dy * dy
    return all(abs(dx * (y - oy) - dy * (x - ox)) <= 1e-12 * scale for x, y in pts)


def _overlap_1d(a, b, c, d) -> bool:
    """Whether collinear segments ab and cd share a point."""
    axis = 0 if abs(b[0] - a[0]) + abs(d[0] - c[0]) > 0 else 1
    lo1, hi1 = sorted((a[axis], b[axis]))
    lo2, hi2 = sorted((c[axis], d[axis]))
    return lo1 <= hi2 and lo2 <= hi1


def rotate_points(points: Sequence[Vec], angle: float) -> tuple[Vec, ...]:
    """Points rotated anticlockwise by ``angle`` radians about the origin."""
    if angle == 0.0:
        return tuple((float(x), float(y)) for x, y in points)
    c = math.cos(angle)
    s = math.sin(angle)
    return tuple((c * x - s * y, s * x + c * y) for x, y in points)


def edge_normals(vertices: Sequence[Vec]) -> tuple[Vec, ...]:
    """Unit outward normals of the edges of an anticlockwise polygon.

    Normal ``k`` belongs to the edge from vertex ``k`` to vertex ``k + 1``.
    """
    n = len(vertices)
    normals = []
    for k in range(n):
        x0, y0 = vertices[k]
        x1, y1 = vertices[(k + 1) % n]
        ex, ey = x1 - x0, y1 - y0
        length = math.hypot(ex, ey)
        normals.append((ey / length, -ex / length))
    return tuple(normals)


def circle_circle_depth(ax: float, ay: float, ra: float, bx: float, by: float, rb: float) -> float:
    """How far two circles overlap (positive) or are apart (negative)."""
    return ra + rb - math.hypot(ax - bx, ay - by)


def circle_polygon_depth(
    cx: float, cy: float, r: float, px: float, py: float, vertices: Sequence[Vec]
) -> float:
    """Overlap depth (positive) or clearance (negative) of a circle and a convex polygon.

    ``vertices`` are anticlockwise and relative to the polygon position
    ``(px, py)``. The value is ``r`` minus the signed distance from the circle's
    centre to the polygon (negative inside).
    """
    qx, qy = cx - px, cy - py
    n = len(vertices)
    best_face = -math.inf
    outside_distance = math.inf
    inside = True
    for k in range(n):
        x0, y0 = vertices[k]
        x1, y1 = vertices[(k + 1) % n]
        ex, ey = x1 - x0, y1 - y0
        length = math.hypot(ex, ey)
        nx, ny = ey / length, -ex / length
        s = nx * (qx - x0) + ny * (qy - y0)
        best_face = max(best_face, s)
        if s > 0.0:
            inside = False
        u = (ex * (qx - x0) + ey * (qy - y0)) / (length * length)
        u = min(1.0, max(0.0, u))
        d = math.hypot(qx - (x0 + u * ex), qy - (y0 + u * ey))
        outside_distance = min(outside_distance, d)
    signed = best_face if inside else outside_distance
    return r - signed


def polygon_polygon_depth(
    ax: float, ay: float, a_vertices: Sequence[Vec], bx: float, by: float, b_vertices: Sequence[Vec]
) -> float:
    """Overlap depth of two convex polygons by the separating-axis theorem.

    Positive: the smallest translation that separates them. Zero or negative:
    they do not overlap (the value is minus the largest separation along an
    edge normal, a lower bound on their distance).
    """
    best = -math.inf
    for (ox, oy, own), (tx, ty, other) in (
        ((ax, ay, a_vertices), (bx, by, b_vertices)),
        ((bx, by, b_vertices), (ax, ay, a_vertices)),
    ):
        for (nx, ny), (vx, vy) in zip(edge_normals(own), own):
            support = min(nx * (tx + x) + ny * (ty + y) for x, y in other)
            best = max(best, support - (nx * (ox + vx) + ny * (oy + vy)))
    return -best

