"""Exact times through the classic API: a dropped ball and a thrown ball against closed forms."""

from __future__ import annotations

import math

import pytest
from classic_support import session, walls  # noqa: F401 (session: the fixture every test uses)

import pge

pytestmark = pytest.mark.usefixtures("session")


def test_dropped_ball_first_hits_the_floor_at_the_analytic_time():
    """A dropped ball's first collision, read by pge.get_time() in on_collision, is sqrt(2h/9.81) to 1e-12."""
    floor = walls(0.01)[0]
    times = []

    def landed(ball, event):
        times.append((pge.get_time(), event.collision_between()))

    pge.circle(0.5, 0.5, 0.05, pge.rgb(1, 0.8, 0)).mass(1.0).on_collision(landed)
    pge.gravity()
    pge.run(1.0)
    first, pair = times[0]
    expected = math.sqrt(2.0 * (0.5 - 0.05 - 0.01) / 9.81)
    assert abs(first - expected) <= 1e-12
    assert pair[0] is floor


def test_bounce_with_elasticity_098_rises_to_the_predicted_time():
    """After bouncing with the default elasticity 0.98 the ball lands again 2 * 0.98 * v / g later."""
    walls(0.01)
    times = []
    pge.circle(0.5, 0.5, 0.05, pge.white()).mass(1.0).on_collision(lambda b, e: times.append(pge.get_time()))
    pge.gravity()
    pge.run(1.0)
    g = 9.81
    t1 = math.sqrt(2.0 * 0.44 / g)
    t2 = t1 + 2.0 * 0.98 * (g * t1) / g
    assert abs(times[1] - t2) <= 1e-12
