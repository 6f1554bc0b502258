"""Circle against circle under constant relative acceleration."""

from __future__ import annotations

import math

from pge._jit_cache import njit

from pge.numerics.roots import first_descent, first_descent_quadratic


@njit(cache=True)
def circle_circle(dx, dy, dvx, dvy, dax, day, radius_a, radius_b, horizon, still=0.0):
    """First contact of two circles within ``[0, horizon]``: ``(t, 0)``, t = inf for none.

    ``(dx, dy)``, ``(dvx, dvy)`` and ``(dax, day)`` are the offset, velocity and
    acceleration of circle a relative to circle b. The gap function is
    ``|d(t)|^2 - (ra + rb)^2``: a quadratic when the relative acceleration is
    zero (equal gravity on both bodies), a quartic otherwise. Touching circles
    closing or separating slower than ``still`` (the rounding noise of the
    approach speed, ``pge.core.predict.still_speed``) are at rest relative to
    each other: a contact now only if pressed together.
    """
    reach = radius_a + radius_b
    c0 = dx * dx + dy * dy - reach * reach
    c1 = 2.0 * (dx * dvx + dy * dvy)
    if c0 <= 0.0 and abs(c1) <= 2.0 * reach * still:
        c1 = 0.0  # neither approaching nor separating, to rounding
    c2 = dvx * dvx + dvy * dvy
    if dax == 0.0 and day == 0.0:
        return first_descent_quadratic(c0, c1, c2, horizon, True), 0
    t = first_descent(
        c0,
        c1,
        c2 + dx * dax + dy * day,
        dvx * dax + dvy * day,
        0.25 * (dax * dax + day * day),
        horizon,
        True,
    )
    return t, 0


@njit(cache=True)
def circle_circle_contact(ax, ay, radius_a, bx, by, radius_b):
    """Contact point and unit normal (from b towards a) of two touching circles.

    Returns ``(px, py, nx, ny)``. Coincident centres have no defined normal;
    the x axis is used then.
    """
    nx = ax - bx
    ny = ay - by
    length = math.hypot(nx, ny)
    if length == 0.0:
        return ax, ay, 1.0, 0.0
    nx /= length
    ny /= length
    return bx + nx * radius_b, by + ny * radius_b, nx, ny
