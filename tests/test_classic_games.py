"""The original's velocity damping on get/put, and game scenes in the style of the three PGE
games that hung (breakout, snooker, trapped: a callback speeds the ball up at every hit of an
obstacle, tuned against that damping). The scenes are written here, not taken from the games."""

from __future__ import annotations

import math

import pytest
from classic_support import session, walls  # noqa: F401  (fixture)

from pge.errors import SimulationError


def test_reads_and_writes_damp_both_components_as_the_original(session):
    pge = session
    pge.batch()
    ball = pge.circle(0.5, 0.5, 0.05, pge.rgb(1, 0, 0)).mass(1.0)
    ball.velocity(1.0, 0.5)
    assert ball.get_xvel() == pytest.approx(0.98)
    assert ball.get_yvel() == pytest.approx(0.5 * 0.98 * 0.98)  # the first read damped it too
    ball.put_xvel(2.0)
    assert ball._velocity() == pytest.approx((2.0 * 0.98, 0.5 * 0.98**3))


def test_small_components_are_set_to_zero_when_damped(session):
    pge = session
    pge.batch()
    ball = pge.circle(0.5, 0.5, 0.05, pge.rgb(1, 0, 0)).mass(1.0)
    ball.velocity(0.0101, 3.0)
    assert ball.get_yvel() == pytest.approx(3.0 * 0.98)
    assert ball._velocity()[0] == 0.0  # 0.0101 * 0.98 < 0.01


def test_velocity_damping_off_makes_reads_exact(session):
    pge = session
    pge.batch()
    pge.velocity_damping(1.0)
    ball = pge.circle(0.5, 0.5, 0.05, pge.rgb(1, 0, 0)).mass(1.0)
    ball.velocity(1.0, 0.004)
    for _ in range(5):
        assert ball.get_xvel() == 1.0 and ball.get_yvel() == 0.004
    ball.put_yvel(0.5)
    assert ball._velocity() == (1.0, 0.5)


@pytest.mark.parametrize("bad", [0.0, 1.5, -0.98, float("nan")])
def test_velocity_damping_rejects_factors_outside_0_1(session, bad):
    with pytest.raises(ValueError, match="velocity_damping"):
        session.velocity_damping(bad)
    assert session.classic._STATE.damping == 0.98


def test_velocity_damping_rejects_non_numbers(session):
    with pytest.raises(TypeError, match="velocity_damping"):
        session.velocity_damping("0.9")


def _speeder(pge, hits):
    """A callback as the games' obstacles have: the other body goes 15 % faster."""

    def push(obj, event):
        hits.append(pge.get_time())
        for other in event.collision_between():
            if other != obj:
                other.put_xvel(other.get_xvel() * 1.15)
                other.put_yvel(other.get_yvel() * 1.15)

    return push


def _breakout_like(pge, damping):
    """Walls, a row of bricks that vanish when hit, two fixed triangles that speed the ball up,
    gravity and a heavy ball: breakout's kind of scene."""
    pge.batch()
    pge.velocity_damping(damping)
    colour = pge.rgb(0.3, 0.3, 0.8)
    walls(0.01)
    hits = []
    push = _speeder(pge, hits)
    pge.poly3(0.15, 0.35, 0.35, 0.35, 0.25, 0.45, colour).on_collision(push).fix()
    pge.poly3(0.65, 0.35, 0.85, 0.35, 0.75, 0.45, colour).on_collision(push).fix()
    bricks = []

    def knock(obj, event):
        if obj in bricks:
            bricks.remove(obj)
            obj.rm()

    for k in range(8):
        bricks.append(pge.box(0.05 + 0.11 * k, 0.05, 0.09, 0.06, colour).fix().on_collision(knock))
    ball = pge.circle(0.21, 0.8, 0.04, pge.rgb(0.9, 0.7, 0.1)).mass(1.25)
    ball.velocity(0.7, 0.0)
    pge.gravity()
    return ball, hits, bricks


def test_a_breakout_like_game_runs_to_its_end_with_the_original_damping(session):
    pge = session
    ball, hits, bricks = _breakout_like(pge, 0.98)
    pge.run(20.0)
    assert pge.get_time() == pytest.approx(20.0)
    assert len(hits) >= 3  # the triangles were hit and sped the ball up
    x, y = ball.get_xpos(), ball.get_ypos()
    assert 0.01 < x < 0.99 and 0.01 < y < 0.99
    speed = math.hypot(*ball._velocity())
    assert speed < 100.0  # damping wins over the 1.15: an ordinary speed, as in the original


def test_the_same_game_without_damping_ends_in_a_clear_error_or_at_its_end(session):
    """Without the damping the speed-ups may win; then the run must raise a SimulationError
    naming the ball, never hang or let it out of the walls."""
    pge = session
    ball, hits, bricks = _breakout_like(pge, 1.0)
    try:
        pge.run(20.0)
    except SimulationError as error:
        assert "circle" in str(error)
    x, y = ball.get_xpos(), ball.get_ypos()
    assert 0.01 < x < 0.99 and 0.01 < y < 0.99


def test_a_snooker_like_table_runs_to_its_end(session):
    """Cushions, a rack of balls struck by a cue ball, two fixed bumpers that speed balls up, no
    gravity: snooker's kind of scene."""
    pge = session
    pge.batch()
    cloth = pge.rgb(0.1, 0.5, 0.2)
    walls(0.02)
    hits = []
    push = _speeder(pge, hits)
    pge.poly3(0.45, 0.85, 0.55, 0.85, 0.5, 0.93, cloth).on_collision(push).fix()
    pge.poly3(0.45, 0.15, 0.55, 0.15, 0.5, 0.07, cloth).on_collision(push).fix()
    balls = []
    for row in range(4):
        for k in range(row + 1):
            balls.append(pge.circle(0.6 + row * 0.052, 0.5 + (k - row / 2) * 0.06, 0.025, cloth).mass(0.5))
    cue = pge.circle(0.2, 0.52, 0.025, pge.rgb(1, 1, 1)).mass(0.5)
    cue.velocity(3.0, 0.0)
    pge.run(15.0)
    assert pge.get_time() == pytest.approx(15.0)
    for ball in balls + [cue]:
        assert 0.02 < ball.get_xpos() < 0.98 and 0.02 < ball.get_ypos() < 0.98


def test_a_trapped_like_scene_runs_to_its_end(session):
    """A ball shut in a small fixed box, ramps, and triangles that speed the free balls up,
    under gravity: trapped's kind of scene (its boxed ball bounces in a tight space)."""
    pge = session
    pge.batch()
    wood = pge.rgb(0.5, 0.35, 0.2)
    walls(0.01)
    hits = []
    push = _speeder(pge, hits)
    pge.poly3(0.2, 0.3, 0.4, 0.3, 0.3, 0.4, wood).on_collision(push).fix()
    pge.poly3(0.6, 0.3, 0.8, 0.3, 0.7, 0.4, wood).on_collision(push).fix()
    pge.poly4(0.3, 0.5, 0.85, 0.52, 0.85, 0.53, 0.3, 0.51, wood).fix()
    pge.box(0.1, 0.08, 0.2, 0.01, wood).fix()
    pge.box(0.1, 0.08, 0.01, 0.2, wood).fix()
    pge.box(0.29, 0.08, 0.01, 0.2, wood).fix()
    pge.box(0.1, 0.27, 0.2, 0.01, wood).fix()
    inside = pge.circle(0.16, 0.14, 0.04, wood).mass(1.5)
    inside.velocity(0.8, 1.1)
    free = [pge.circle(x, 0.8, 0.04, wood).mass(1.0) for x in (0.2, 0.55, 0.8)]
    pge.gravity()
    pge.run(18.0)
    assert pge.get_time() == pytest.approx(18.0)
    assert 0.11 < inside.get_xpos() < 0.29 and 0.09 < inside.get_ypos() < 0.27
    for ball in free:
        assert 0.01 < ball.get_xpos() < 0.99 and 0.01 < ball.get_ypos() < 0.99
