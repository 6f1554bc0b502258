"""Time-of-impact kernels, one module per pair of shape kinds.

Every kernel is a pure compiled function of the relative motion of two bodies
that translate with constant acceleration, taken at a common time origin: the
offset ``d = position_a - position_b``, the relative velocity and the relative
acceleration, plus the two shapes and a ``horizon``. It returns
``(t, feature)``: ``t`` is the time of first contact from the origin (0.0
means "overlapping and approaching": collide now; ``inf`` means no contact
within ``[0, horizon]``) and ``feature`` an integer naming the touching
features, which the matching ``*_contact`` function turns into a contact
point and normal. An optional last argument ``still`` is the approach speed
below which touching shapes count as not approaching (the rounding noise of
the contact's velocities): the engine's collision response must agree with
the kernel on "approaching", or a contact could be reported again and again
at one instant.

Polygons are passed as rows of an *outline array* (see ``outline_rows``).
The engine dispatches on the two shape kinds through ``PAIR_KERNELS``; a
(polygon, circle) pair is swapped to (circle, polygon) first.
"""

from __future__ import annotations

import numpy as np

from pge.geometry import edge_normals
from pge.toi.circle_circle import circle_circle, circle_circle_contact
from pge.toi.circle_polygon import circle_polygon, circle_polygon_contact, closest_feature
from pge.toi.polygon_polygon import polygon_polygon, polygon_polygon_contact

CIRCLE = 0
POLYGON = 1

#: kernel and contact function for each ordered pair of shape kinds; a pair
#: absent here is handled by swapping the bodies (see ``SWAPPED``).
PAIR_KERNELS = {
    (CIRCLE, CIRCLE): (circle_circle, circle_circle_contact),
    (CIRCLE, POLYGON): (circle_polygon, circle_polygon_contact),
    (POLYGON, POLYGON): (polygon_polygon, polygon_polygon_contact),
}

#: ordered pairs handled by swapping the two bodies.
SWAPPED = {(POLYGON, CIRCLE): (CIRCLE, POLYGON)}


def outline_rows(vertices) -> np.ndarray:
    """Outline array rows for an anticlockwise convex polygon given relative to its centroid.

    Columns: vertex x, vertex y, unit outward normal x, y of the edge from this
    vertex to the next, and that edge's length.
    """
    vertices = [(float(x), float(y)) for x, y in vertices]
    normals = edge_normals(vertices)
    n = len(vertices)
    rows = np.empty((n, 5))
    for k, ((x, y), (nx, ny)) in enumerate(zip(vertices, normals)):
        x1, y1 = vertices[(k + 1) % n]
        rows[k] = (x, y, nx, ny, np.hypot(x1 - x, y1 - y))
    return rows


__all__ = [
    "CIRCLE",
    "POLYGON",
    "PAIR_KERNELS",
    "SWAPPED",
    "outline_rows",
    "circle_circle",
    "circle_circle_contact",
    "circle_polygon",
    "circle_polygon_contact",
    "closest_feature",
    "polygon_polygon",
    "polygon_polygon_contact",
]
