"""Contact manifolds of the islands model (pge.contact.manifold).

The one property the island step relies on: when two polygons are within the margin by the
separating-axis test, their manifold has a point. An empty manifold for a pair that touches
would drop the pair from its island at the same instant as its collision joined it, and the
two would collide and join again for ever at that instant.
"""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from pge.contact.manifold import NCOLUMNS, SEPARATION, polygon_polygon_points

MARGIN = 1e-3


def outline(n: int, radius: float, turn: float) -> np.ndarray:
    """Outline rows (vertex, unit normal of the face from it to the next, face length) of a
    regular polygon turned by ``turn``, about its centre."""
    angles = [turn + 2.0 * math.pi * k / n for k in range(n)]
    vertices = [(radius * math.cos(a), radius * math.sin(a)) for a in angles]
    rows = np.zeros((n, 5))
    for k in range(n):
        x0, y0 = vertices[k]
        x1, y1 = vertices[(k + 1) % n]
        length = math.hypot(x1 - x0, y1 - y0)
        rows[k] = (x0, y0, (y1 - y0) / length, -(x1 - x0) / length, length)
    return rows


def separating_axis(a: np.ndarray, ax, ay, b: np.ndarray, bx, by) -> float:
    """The largest separation of b's vertices beyond one of a's faces."""
    best = -math.inf
    for x, y, nx, ny, _ in a:
        least = min(nx * (bx + u - ax - x) + ny * (by + v - ay - y) for u, v, *_ in b)
        best = max(best, least)
    return best


def manifold(a, ax, ay, b, bx, by):
    OL = np.vstack([a, b])
    out = np.zeros((4, NCOLUMNS))
    count = polygon_polygon_points(ax, ay, OL, 0, a.shape[0], bx, by, a.shape[0], b.shape[0], MARGIN, 1e-3, out, 0)
    return out[:count]


def test_two_corners_meeting_head_on_make_a_point_where_they_meet():
    triangle = outline(3, 1.0, 0.0)  # a corner pointing right, at (1, 0)
    diamond = outline(4, 0.2, 0.0)  # a corner pointing left, at (-0.2, 0) from its centre
    for apart in (0.0, 1e-13, 1e-9, 1e-6):  # touching, and within the margin
        rows = manifold(triangle, 0.0, 0.0, diamond, 1.2 + apart, 0.0)
        assert rows.shape[0] >= 1
        for row in rows:
            # The separating-axis value: a lower bound of the distance, never more.
            assert -1e-15 <= row[SEPARATION] <= apart + 1e-15
            assert math.hypot(row[0] - 1.0 - 0.5 * apart, row[1]) < 1e-12


@settings(max_examples=300, deadline=None)
@given(
    na=st.integers(3, 6),
    nb=st.integers(3, 6),
    ra=st.floats(0.2, 2.0),
    rb=st.floats(0.2, 2.0),
    turn_a=st.floats(0.0, 2.0 * math.pi),
    turn_b=st.floats(0.0, 2.0 * math.pi),
    direction=st.floats(0.0, 2.0 * math.pi),
    gap=st.floats(-0.5, 1.0) | st.floats(-1e-9, 1e-9),
)
def test_polygons_within_the_margin_always_have_a_manifold_point(na, nb, ra, rb, turn_a, turn_b, direction, gap):
    a = outline(na, ra, turn_a)
    b = outline(nb, rb, turn_b)
    # Slide b in from far away along ``direction`` until the separating axis reads ``gap``.
    ux, uy = math.cos(direction), math.sin(direction)
    lo, hi = 0.0, 2.0 * (ra + rb) + 2.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if max(separating_axis(a, 0, 0, b, mid * ux, mid * uy), separating_axis(b, mid * ux, mid * uy, a, 0, 0)) > gap:
            hi = mid
        else:
            lo = mid
    bx, by = hi * ux, hi * uy
    sat = max(separating_axis(a, 0, 0, b, bx, by), separating_axis(b, bx, by, a, 0, 0))
    rows = manifold(a, 0.0, 0.0, b, bx, by)
    if sat <= MARGIN:
        assert rows.shape[0] >= 1
        assert rows[:, SEPARATION].min() <= MARGIN
    else:
        assert rows.shape[0] == 0
