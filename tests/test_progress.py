"""The progress guarantee: every run returns or raises, at any speed, whatever the callbacks do.

Each scene here hung the engine once (the reproducers' scenes: a ball too fast for its
horizons, bounces below one tick of the clock, a callback that speeds a ball up at every hit,
the watchdog restarting at every return to Python). Now each either runs to its end without a
body leaving its side of a wall, or raises a clear error naming the body.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from pge import World
from pge.core import tuning
from pge.errors import EventStormError, SimulationError, TooFastError


def _lone_ball(speed, at=4.8):
    world = World(gravity=(0.0, 0.0))
    ball = world.add_circle((0.5, 0.5), 0.05, mass=1.0, name="ball")
    world.run_until(at)
    ball.velocity = (speed, 0.0)
    return world, ball


def test_a_fast_ball_alone_runs_to_the_end():
    """1e6 units/s at t = 4.8: a horizon every 2.5e-7 s, about 4e5 of them in 0.1 s."""
    world, ball = _lone_ball(1e6)
    world.run_until(4.9)
    assert world.time == 4.9
    assert ball.position[0] == pytest.approx(0.5 + 1e6 * 0.1, rel=1e-12)


def test_a_ball_too_fast_for_the_clock_is_refused_by_name():
    """1e14 units/s at t = 4.8 crosses 0.09 per tick (8.9e-16 s): it used to creep one ulp per
    horizon for ever; now the run raises before anything moves, naming the ball."""
    world, ball = _lone_ball(1e14)
    with pytest.raises(TooFastError, match=r"circle 0 'ball'.*faster than the world can represent") as caught:
        world.run_until(4.9)
    assert caught.value.bodies == (ball,)
    assert caught.value.speed == pytest.approx(1e14)
    assert caught.value.tick == math.ulp(4.8)
    assert world.time == 4.8 and ball.position == (0.5, 0.5)
    # The world is usable again once the ball is slowed down.
    ball.velocity = (1.0, 0.0)
    world.run_until(4.9)
    assert ball.position[0] == pytest.approx(0.6)


def test_the_speed_limit_follows_the_clock():
    """The same speed is representable early in a run, where the clock's ticks are finer."""
    world = World(gravity=(0.0, 0.0), elasticity=1.0)
    world.add_box(0.0, 0.0, 0.01, 1.0, fixed=True)
    world.add_box(0.99, 0.0, 0.01, 1.0, fixed=True)
    ball = world.add_circle((0.5, 0.5), 0.05, mass=1.0, velocity=(1e12, 0.0), elasticity=1.0)
    world.run_until(1e-9)
    assert 0.06 <= ball.position[0] <= 0.94
    assert world.stats["collisions"] > 1000


@pytest.mark.parametrize("with_callback", [False, True])
def test_bounces_below_one_tick_raise_with_or_without_a_callback(with_callback):
    """A ball between two walls at 1e17 units/s bounces every 9e-18 s, below one tick of the
    clock: every bounce would happen at one instant (with a callback the old watchdog restarted
    at every return to Python and the run never ended)."""
    world = World(gravity=(0.0, 0.0), elasticity=1.0)
    world.add_box(0.0, 0.0, 1.0, 0.01, fixed=True, name="floor")
    world.add_box(0.0, 0.99, 1.0, 0.01, fixed=True, name="ceiling")
    ball = world.add_circle((0.5, 0.5), 0.05, mass=1.0, name="ball")
    seen = []
    if with_callback:
        world.on_collision(seen.append)
    world.run_until(4.8)
    ball.velocity = (0.0, 1e17)
    with pytest.raises(TooFastError, match="'ball'"):
        world.run_until(4.9)
    assert seen == []


def _tunnel_case(x, vx, vy):
    """Breakout's last state (the reproducer's case A/B): a ball at ~1.7e14 units/s next to a
    0.01 wide wall at t = 4.8225."""
    t0 = 4.822518507614504
    world = World(gravity=(0.0, -9.81))
    world.add_box(0.0, 0.0, 0.01, 1.0, fixed=True, name="wall")
    ball = world.add_circle((0.5, 0.5), 0.05, mass=1.25, name="ball")
    world.set_fixed(ball, True)
    world.run_until(t0)
    world.set_fixed(ball, False)
    ball.position = (x, 0.5)
    ball.velocity = (vx, vy)
    return world, ball, t0


@pytest.mark.parametrize(
    "x, vx, vy", [(0.30906534485724, -1.7308e14, 1.0356e14), (0.3, -1.7308e14, 0.0)], ids=["oblique", "head-on"]
)
def test_breakouts_escaping_ball_is_refused_not_let_through(x, vx, vy):
    world, ball, t0 = _tunnel_case(x, vx, vy)
    with pytest.raises(TooFastError, match="'ball'"):
        for _ in world.events(until=t0 + 40 * math.ulp(t0)):
            pass
    assert ball.position[0] > 0.01 + 0.05 - 1e-9


def test_breakouts_ball_at_a_resolvable_speed_bounces_off_the_wall():
    """The control: 1e-4 of that speed bounces, on the right side of the wall."""
    world, ball, t0 = _tunnel_case(0.30906534485724, -1.7308e10, 1.0356e10)
    normals = []
    world.on_collision(lambda c: normals.append(c.normal))
    for _ in world.events(until=t0 + 40 * 1e4 * math.ulp(t0)):
        pass
    assert normals == [(1.0, 0.0)]
    assert ball.velocity[0] > 0.0 and ball.position[0] > 0.06 - 1e-9


@pytest.mark.parametrize("thick", [0.01, 1.0])
def test_a_callback_that_speeds_the_ball_up_for_ever_ends_in_a_clear_error(thick):
    """The three games' trigger without the original's damping: x1.15 per hit of the ceiling,
    so the bounces converge on t* ~ 1.712 s (Zeno) and the speed grows without bound."""
    world = World(gravity=(0.0, 0.0))
    world.add_box(0.0, 0.01 - thick, 1.0, thick, fixed=True, name="floor")
    ceiling = world.add_box(0.0, 0.99, 1.0, thick, fixed=True, name="ceiling")
    ball = world.add_circle((0.5, 0.5), 0.05, mass=1.0, velocity=(0.0, 10.0), name="ball")

    def push(collision):
        vx, vy = ball.velocity
        ball.velocity = (vx * 1.15, vy * 1.15)

    world.on_collision(push, ceiling)
    with pytest.raises(TooFastError, match="'ball'"):
        world.run_until(3.0)
    assert 1.7 < world.time < 1.72
    assert 0.06 - 1e-9 <= ball.position[1] <= 0.94 + 1e-9


def test_the_watchdog_counts_across_collision_callbacks():
    """A callback that throws the ball back into the wall at every hit makes a zero-time loop
    whose every collision returns to Python: the count must survive the returns."""
    world = World(gravity=(0.0, 0.0))
    world.add_box(0.0, 0.0, 0.1, 1.0, fixed=True, name="wall")
    ball = world.add_circle((0.15, 0.5), 0.05, mass=1.0, velocity=(-1.0, 0.0), name="ball")
    calls = [0]

    def back_in(collision):
        calls[0] += 1
        ball.velocity = (-1.0, 0.0)

    world.on_collision(back_in)
    with pytest.raises(EventStormError, match=r"'ball'.*'wall'|'wall'.*'ball'") as caught:
        world.run_until(1.0)
    cap = tuning.STORM_LIMIT + tuning.STORM_PER_BODY * world._state.n
    assert calls[0] == pytest.approx(cap, abs=2)
    assert caught.value.kinds.get("collisions", 0) >= cap
    assert set(caught.value.bodies) == {b for b in world.bodies}
    assert world.time == pytest.approx(0.0)


def test_the_watchdog_counts_timers_and_catches_a_creeping_clock():
    """A timer that fires again one tick later, for ever: the clock creeps one ulp per event.
    The old watch counted only collisions and contact changes."""
    world = World()
    world.add_circle((0.5, 0.5), 0.05, mass=1.0)

    def again(event):
        world.at_time(np.nextafter(event.time, math.inf), again)

    world.at_time(100.0, again)
    with pytest.raises(EventStormError, match="timers") as caught:
        world.run_until(200.0)
    assert caught.value.kinds == {"timers": tuning.STORM_LIMIT + tuning.STORM_PER_BODY * world._state.n + 1}
    assert 100.0 < world.time < 100.0 + 1e-6


def test_legitimate_dense_scenes_are_not_storms():
    """Forty balls landing on the floor at one instant, over and over, with a callback."""
    world = World(gravity=(0.0, -9.81), elasticity=1.0)
    world.add_box(0.0, 0.0, 1.0, 0.01, fixed=True)
    for k in range(40):
        world.add_circle((0.0125 + k * 0.025, 0.5), 0.01, mass=1.0)
    hits = []
    world.on_collision(hits.append)
    world.run_until(5.0)
    assert len(hits) > 40 * 5
    assert len({h.time for h in hits}) < len(hits)  # many at one instant


@settings(max_examples=40, deadline=None)
@given(
    speed=st.floats(1e3, 1e15),
    wall=st.floats(1e-3, 0.05),
    angle=st.floats(-1.4, 1.4),
    start=st.floats(0.0, 5.0),
)
def test_no_tunnelling_at_any_speed(speed, wall, angle, start):
    """A ball shot at a thin wall in a closed box at speeds up to 1e15, with walls down to
    1e-3 thick: it never ends on the far side of a wall, or the run raises TooFastError."""
    world = World(gravity=(0.0, -9.81), elasticity=1.0)
    world.add_box(-0.5, -0.5, 2.0, 0.5, fixed=True)  # floor
    world.add_box(-0.5, 1.0, 2.0, 0.5, fixed=True)  # ceiling
    world.add_box(-0.5, 0.0, 0.5, 1.0, fixed=True)  # left
    world.add_box(1.0, 0.0, 0.5, 1.0, fixed=True)  # right
    world.add_box(0.5 - wall / 2, 0.0, wall, 1.0, fixed=True, name="thin wall")
    ball = world.add_circle((0.25, 0.5), 0.02, mass=1.0, name="ball")
    world.set_fixed(ball, True)
    world.run_until(start)
    world.set_fixed(ball, False)
    ball.velocity = (speed * math.cos(angle), speed * math.sin(angle))
    horizon = start + 2000.0 / speed
    try:
        for _ in world.events(until=horizon):
            x, y = ball.position
            assert x < 0.5 - wall / 2 - 0.02 + 1e-9, "the ball went through the thin wall"
            assert 0.02 - 1e-9 < y < 0.98 + 1e-9 and x > 0.02 - 1e-9
    except TooFastError as error:
        assert error.bodies == (ball,)
        assert speed * math.ulp(world.time) * tuning.MIN_TICKS > 0.01  # only where the clock is too coarse
    x, y = ball.position
    assert x < 0.5 - wall / 2 - 0.02 + 1e-9


def test_simulation_errors_are_runtime_errors():
    """Code that caught the old RuntimeError('event storm ...') still catches them."""
    assert issubclass(EventStormError, SimulationError) and issubclass(TooFastError, SimulationError)
    assert issubclass(SimulationError, RuntimeError)
