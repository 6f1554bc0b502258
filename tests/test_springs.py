"""Springs (pge.springs): periods, energy, damping, tension-only ropes, when(), removal, bad input, classic API.

Most scenes are a ball of mass m on a spring of stiffness k from a fixed anchor, moving
along x with no gravity: displacement x(t) from the rest position, w = sqrt(k / m).
Positions are sampled every millisecond; between samples the motion is smooth enough
that linear interpolation finds zero crossings to about 1e-7 s.
"""

from __future__ import annotations

import math

import pytest
from classic_support import session  # noqa: F401 (fixture of the classic-API tests)

import pge
from pge import World
from pge.springs import LengthReached, Spring

K, M = 100.0, 1.0
W = math.sqrt(K / M)
PERIOD = 2.0 * math.pi / W
REST = 0.3
ANCHOR = (0.2, 0.5)
SAMPLE = 1e-3


def oscillator(displacement=0.1, velocity=0.0, damping=0.0, two_sided=True, interval=None, **world_options):
    """An anchored ball REST + displacement from the anchor along x: (world, anchor, ball, spring)."""
    world = World(**world_options)
    anchor = world.add_circle(ANCHOR, 0.02, fixed=True)
    ball = world.add_circle((ANCHOR[0] + REST + displacement, 0.5), 0.02, mass=M, velocity=(velocity, 0.0))
    spring = world.add_spring(anchor, ball, K, damping, rest_length=REST, two_sided=two_sided)
    if interval is not None:
        world.spring_interval = interval
    return world, anchor, ball, spring


def displacements(world, ball, until, step=SAMPLE):
    """``[(t, x)]``: the ball's displacement from the rest position every ``step`` seconds."""
    out = []
    for n in range(1, int(round(until / step)) + 1):
        world.run_until(n * step)
        out.append((world.time, ball.position[0] - ANCHOR[0] - REST))
    return out


def upward_crossings(samples):
    """Times where the displacement passes zero going up (linear interpolation)."""
    times = []
    for (t0, x0), (t1, x1) in zip(samples, samples[1:]):
        if x0 < 0.0 <= x1:
            times.append(t0 + (t1 - t0) * (-x0) / (x1 - x0))
    return times


def measured_period(interval, periods=10):
    world, _, ball, _ = oscillator(interval=interval)
    crossings = upward_crossings(displacements(world, ball, periods * PERIOD))
    return (crossings[-1] - crossings[0]) / (len(crossings) - 1)


# ------------------------------------------------------------------ accuracy


def test_period_is_2pi_sqrt_m_over_k_and_the_error_shrinks_with_the_interval():
    """Undamped two-sided oscillator: period error is -(w h)^2 / 24 (leapfrog), 4x smaller per halving."""
    intervals = [0.01, 0.005, 0.0025]
    errors = [(measured_period(h) - PERIOD) / PERIOD for h in intervals]
    for h, error in zip(intervals, errors):
        predicted = -((W * h) ** 2) / 24.0
        assert abs(error - predicted) < 0.05 * abs(predicted), (h, error, predicted)
    assert abs(errors[0]) < 5e-4
    for coarse, fine in zip(errors, errors[1:]):
        assert 3.6 < coarse / fine < 4.4


def test_energy_of_an_undamped_hanging_spring_stays_bounded_for_100_periods():
    """Kinetic + spring + gravity energy of a two-sided spring under gravity: an O((w h)^2) ripple, no drift."""
    g = 9.81
    world = World(gravity=(0.0, -g))
    anchor = world.add_circle((0.5, 0.9), 0.02, fixed=True)
    ball = world.add_circle((0.5, 0.55), 0.02, mass=M)
    spring = world.add_spring(anchor, ball, K, 0.0, rest_length=REST, two_sided=True)
    h = world.spring_interval
    assert h == 0.01

    def energy():
        vx, vy = ball.velocity
        stretch = spring.length - REST
        return 0.5 * M * (vx * vx + vy * vy) + 0.5 * K * stretch * stretch + M * g * ball.position[1]

    equilibrium = 0.9 - REST - M * g / K
    swing = 0.5 * K * (0.55 - equilibrium) ** 2  # energy of the oscillation
    start = energy()
    deviations = []
    steps = int(100 * PERIOD / h)
    for n in range(1, steps + 1):
        world.run_until(n * h)
        deviations.append((energy() - start) / swing)
    assert max(abs(d) for d in deviations) < 0.5 * (W * h) ** 2  # measured: 0.0025 = (w h)^2 / 4
    tenth = steps // 10
    early = sum(deviations[:tenth]) / tenth
    late = sum(deviations[-tenth:]) / tenth
    assert abs(late - early) < 1e-4  # no drift


def test_start_sampled_forces_would_gain_energy(monkeypatch):
    """Why the midpoint sample: the force held from the interval's start (PGE's way) grows the amplitude
    by exp(pi w h / 2) per period; the midpoint sample keeps it."""
    import pge.springs as springs

    def peak():
        world, _, ball, _ = oscillator(interval=0.005)
        return max(abs(x) for _, x in displacements(world, ball, 5 * PERIOD, step=0.005))

    assert peak() < 0.1 * 1.001
    original = springs.accelerations
    monkeypatch.setattr(springs, "accelerations", lambda world, table, step: original(world, table, 0.0))
    assert peak() == pytest.approx(0.1 * math.exp(5 * math.pi * W * 0.005 / 2), rel=0.02)


def damped_error(interval, damping=1.0, until=3.0, amplitude=0.1):
    world, _, ball, _ = oscillator(displacement=amplitude, damping=damping, interval=interval)
    gamma = damping / (2.0 * M)
    wd = math.sqrt(K / M - gamma * gamma)
    worst = 0.0
    for t, x in displacements(world, ball, until):
        exact = amplitude * math.exp(-gamma * t) * (math.cos(wd * t) + gamma / wd * math.sin(wd * t))
        worst = max(worst, abs(x - exact))
    return worst / amplitude


def test_damping_follows_the_analytic_damped_oscillator():
    """x(t) = A e^(-g t) (cos wd t + g/wd sin wd t) within 0.31 (w h)^2 A over 3 s, second order in h."""
    errors = [damped_error(h) for h in (0.01, 0.005, 0.0025)]
    assert errors[0] < 0.005  # measured 0.0031
    assert errors[2] < 3e-4  # measured 1.9e-4
    for coarse, fine in zip(errors, errors[1:]):
        assert 3.5 < coarse / fine < 4.5


def test_heavy_damping_is_stable_and_settles_at_rest_length():
    """A damper far beyond critical (d h / m = 5) neither oscillates nor blows up: it creeps back to rest."""
    world, _, ball, spring = oscillator(displacement=0.1, damping=500.0, interval=0.01)
    samples = displacements(world, ball, 2.0, step=0.01)
    xs = [x for _, x in samples]
    assert all(0.0 <= x <= 0.1 for x in xs)
    assert all(b <= a + 1e-15 for a, b in zip(xs, xs[1:]))  # monotone: overdamped
    world.run_until(60.0)
    assert abs(spring.length - REST) < 1e-6


# --------------------------------------------------------- tension-only ropes


def test_slack_rope_exerts_nothing_and_the_ball_moves_ballistically():
    """Tension-only (default): a ball thrown towards the anchor flies straight at constant speed."""
    world, _, ball, spring = oscillator(displacement=0.0, velocity=-0.5, two_sided=False)
    assert not spring.two_sided
    for t in (0.1, 0.3, 0.5):
        world.run_until(t)
        assert ball.position == pytest.approx((ANCHOR[0] + REST - 0.5 * t, 0.5), abs=1e-14)
        assert ball.velocity == (-0.5, 0.0)
        assert ball.total_acceleration == (0.0, 0.0)


def test_two_sided_spring_pushes_back_the_same_throw():
    """The same throw on a two-sided spring: simple harmonic motion x = v/w sin(w t)."""
    world, _, ball, _ = oscillator(displacement=0.0, velocity=-0.5, two_sided=True, interval=0.001)
    world.run_until(0.1)
    x = ball.position[0] - ANCHOR[0] - REST
    assert x == pytest.approx(-0.5 / W * math.sin(W * 0.1), rel=1e-4)
    assert ball.total_acceleration[0] > 0.0


def test_taut_rope_pulls_and_then_goes_slack():
    """A stretched rope pulls the ball in; once shorter than its rest length it lets go (constant speed)."""
    world, _, ball, spring = oscillator(displacement=0.05, two_sided=False, interval=0.001)
    world.run_until(0.01)
    assert ball.total_acceleration[0] < 0.0
    world.run_until(PERIOD / 4 + 0.01)  # past the rest length: slack now
    assert spring.length < REST
    speed = ball.velocity[0]
    assert speed == pytest.approx(-0.05 * W, rel=1e-3)
    world.run_until(PERIOD / 4 + 0.05)
    assert ball.velocity[0] == speed and ball.total_acceleration == (0.0, 0.0)


# ------------------------------------------------------------------- when()


def test_when_fires_once_at_the_length_shortening_then_stretching():
    """when(l): one call per registration, at a time where the length is l to 1e-9 relative, both ways."""
    world, _, _, spring = oscillator(displacement=0.1, interval=0.01)
    calls = []

    def reached(event):
        calls.append((event, world.time, spring.length))

    watch = spring.when(REST + 0.05, reached)  # shortening through it first, at T/6
    assert spring.pending == (watch,)
    world.run_until(PERIOD / 2)  # the ball is at its shortest now
    assert len(calls) == 1
    event, time, length = calls[0]
    assert isinstance(event, LengthReached) and event.kind == "spring"
    assert event.spring is spring and event.length == REST + 0.05 and event.watch_id == watch
    assert event.time == time
    assert abs(length - (REST + 0.05)) <= 1e-9 * length
    assert time == pytest.approx(PERIOD / 6, abs=2e-4)
    assert spring.pending == ()

    spring.when(REST + 0.05, reached)  # stretching through it next, at T/2 + T/3
    world.run_until(3 * PERIOD)
    assert len(calls) == 2
    _, time, length = calls[1]
    assert abs(length - (REST + 0.05)) <= 1e-9 * length
    assert time == pytest.approx(PERIOD / 2 + PERIOD / 3, abs=3e-4)


def test_when_rearmed_in_its_callback_fires_at_every_crossing():
    """A callback that asks again for the same length gets the next crossing, never the same one twice."""
    world, _, _, spring = oscillator(displacement=0.1, interval=0.01)
    times = {}

    def arm(length):
        def reached(event):
            times[length].append(event.time)
            assert abs(spring.length - length) <= 1e-12 * length  # measured: 3e-15 at worst
            arm(length)

        spring.when(length, reached)

    for length in (0.22, 0.3, 0.38):
        times[length] = []
        arm(length)
    world.run_until(10 * PERIOD + 0.01)
    for length, seen in times.items():
        assert len(seen) == 20, length  # twice per period
        assert all(b - a > 0.01 for a, b in zip(seen, seen[1:]))


def test_when_at_an_exact_length_waits_for_the_next_time():
    """A when() for the length the spring has right now fires when it comes back to it, not at once."""
    world, _, _, spring = oscillator(displacement=0.1, interval=0.01)
    calls = []
    spring.when(spring.length, lambda event: calls.append(event.time))
    world.run_until(1.5 * PERIOD)
    assert len(calls) == 1
    assert calls[0] == pytest.approx(PERIOD, abs=5e-4)


def test_when_never_reached_never_fires_and_can_be_cancelled():
    """A length outside the swing never fires; cancel_when forgets a pending when."""
    world, _, _, spring = oscillator(displacement=0.1, interval=0.01)
    calls = []
    spring.when(REST + 0.2, calls.append)
    cancelled = spring.when(REST, calls.append)
    assert spring.cancel_when(cancelled) is True
    assert spring.cancel_when(cancelled) is False
    world.run_until(2 * PERIOD)
    assert calls == []


def bouncer(interval, start=0.5, stiffness=1.0):
    """A ball on a two-sided spring from the anchor at x=0.2 (rest length 0.3), at x=``start`` moving right
    at 1 towards a wall it hits at x=0.55 (elasticity 1)."""
    world = World(elasticity=1.0)
    anchor = world.add_circle(ANCHOR, 0.02, fixed=True)
    world.add_box(0.6, 0.3, 0.05, 0.4, fixed=True)
    ball = world.add_circle((start, 0.5), 0.05, mass=1.0, velocity=(1.0, 0.0))
    spring = world.add_spring(anchor, ball, stiffness, 0.0, rest_length=REST, two_sided=True)
    world.spring_interval = interval
    return world, ball, spring


def test_when_is_recomputed_after_a_collision_mid_interval():
    """Within one long interval the ball bounces off a wall: a length only reached on the way back fires
    at that length, and one the wall stops the ball from reaching never fires."""
    world, ball, spring = bouncer(interval=0.5)
    hits, calls = [], []
    world.on_collision(lambda c: hits.append(c.time))
    spring.when(0.28, lambda e: calls.append((0.28, e.time, spring.length)))
    spring.when(0.40, lambda e: calls.append((0.40, e.time, spring.length)))  # beyond the wall
    world.run_until(0.3)
    assert len(hits) == 1 and hits[0] < 0.06
    assert [c[0] for c in calls] == [0.28]
    _, time, length = calls[0]
    assert hits[0] < time < 0.5  # after the bounce, in the same interval
    assert abs(length - 0.28) <= 1e-9 * 0.28
    assert world.overlap_depth(ball, world.bodies[1]) < 1e-12


@pytest.mark.parametrize("start", [0.49, 0.5, 0.508])
def test_collision_refresh_keeps_the_bounce_accurate(start):
    """At a bounce the forces are sampled again for the rest of the interval: with h = 0.02 the velocity
    after the bounce is within k v h^2 / 8 of a run with h = 1e-4, wherever in the interval the bounce falls
    (the pre-bounce sample held to the end of the interval is off by up to k v h^2: 3.8e-3 from 0.49)."""
    k, h = 20.0, 0.02
    velocities = []
    for interval in (h, 1e-4):
        world, ball, _ = bouncer(interval, start, stiffness=k)
        world.run_until(0.3)
        velocities.append(ball.velocity[0])
    assert abs(velocities[0] - velocities[1]) < k * h * h / 8.0  # measured up to 4.4e-4


# ------------------------------------------------------------------ chains


def test_chain_under_gravity_settles_at_the_analytic_rest_lengths():
    """N masses hanging in a damped chain: spring j carries the weight below it, l0 + (N - j) m g / k."""
    g, n, m, k, l0 = 9.81, 4, 0.05, 50.0, 0.1
    world = World(gravity=(0.0, -g))
    top = world.add_box(0.4, 0.95, 0.2, 0.05, fixed=True)
    above, y, springs = top, 0.975, []
    for _ in range(n):
        y -= l0
        ball = world.add_circle((0.5, y), 0.02, mass=m)
        springs.append(world.add_spring(above, ball, k, 2.0, rest_length=l0))
        above = ball
    world.run_until(10.0)
    for j, spring in enumerate(springs):
        expected = l0 + (n - j) * m * g / k
        assert abs(spring.length - expected) < 1e-9, (j, spring.length, expected)
    assert all(b.velocity == pytest.approx((0.0, 0.0), abs=1e-8) for b in world.bodies[1:])


def test_a_body_on_two_springs_feels_their_sum():
    """A ball between two anchors on equal two-sided springs oscillates with sqrt(2k/m)."""
    world = World()
    left = world.add_circle((0.1, 0.5), 0.02, fixed=True)
    right = world.add_circle((0.9, 0.5), 0.02, fixed=True)
    ball = world.add_circle((0.55, 0.5), 0.02, mass=M)
    world.add_spring(left, ball, K, rest_length=0.4, two_sided=True)
    world.add_spring(ball, right, K, rest_length=0.4, two_sided=True)
    world.spring_interval = 0.001
    w2 = math.sqrt(2 * K / M)
    world.run_until(0.2)
    assert ball.position[0] - 0.5 == pytest.approx(0.05 * math.cos(w2 * 0.2), rel=1e-4)


def test_two_free_bodies_keep_their_momentum_and_swing_with_the_reduced_mass():
    """Equal and opposite forces: total momentum is kept exactly; the pair oscillates with sqrt(k / mu)."""
    world = World()
    a = world.add_circle((0.3, 0.5), 0.02, mass=1.0, velocity=(0.1, 0.05))
    b = world.add_circle((0.7, 0.5), 0.02, mass=3.0, velocity=(0.1, 0.05))
    spring = world.add_spring(a, b, 30.0, rest_length=0.3, two_sided=True)
    world.spring_interval = 0.001
    momentum = world.momentum()
    mu = 1.0 * 3.0 / 4.0
    world.run_until(0.25)
    assert world.momentum() == pytest.approx(momentum, abs=1e-14)
    w = math.sqrt(30.0 / mu)
    assert spring.length - 0.3 == pytest.approx(0.1 * math.cos(w * 0.25), abs=1e-6)


# ----------------------------------------------------------- removal, setup


def test_a_removed_body_takes_its_springs_with_it():
    """Removing the middle of a chain removes both its springs; the lower ball then falls freely."""
    g = 9.81
    world = World(gravity=(0.0, -g))
    top = world.add_circle((0.5, 0.9), 0.02, fixed=True)
    middle = world.add_circle((0.5, 0.7), 0.02, mass=1.0)
    bottom = world.add_circle((0.5, 0.5), 0.02, mass=1.0)
    upper = world.add_spring(top, middle, 50.0, 1.0)
    lower = world.add_spring(middle, bottom, 50.0, 1.0)
    world.run_until(0.05)
    assert bottom.total_acceleration[1] != -g
    world.remove(middle)
    assert world.springs == ()
    assert not upper.alive and not lower.alive
    with pytest.raises(ValueError, match="spring 2 has been removed"):
        _ = lower.length
    assert bottom.total_acceleration == (0.0, -g)
    y, vy, t = bottom.position[1], bottom.velocity[1], world.time
    world.run_until(0.2)
    dt = world.time - t
    assert bottom.position[1] == pytest.approx(y + vy * dt - 0.5 * g * dt * dt, abs=1e-12)


def test_remove_spring_lets_go_and_the_handle_fails_loudly():
    """remove_spring: the spring leaves world.springs, its ends lose its force, using it raises."""
    world, anchor, ball, spring = oscillator(displacement=0.1, interval=1e-4)  # forces ~ those of now
    other = world.add_spring(anchor, ball, 10.0, two_sided=True, name="weak")
    world.run_until(0.05)
    world.remove_spring(spring)
    assert world.springs == (other,)
    assert ball.total_acceleration[0] == pytest.approx(-10.0 * (other.length - other.rest_length), rel=1e-2)
    world.remove_spring(other)
    assert world.springs == () and ball.total_acceleration == (0.0, 0.0)
    for use in (lambda: spring.stiffness, lambda: spring.when(0.3, print), lambda: world.remove_spring(spring)):
        with pytest.raises(ValueError, match="has been removed"):
            use()
    world.run_until(0.2)  # nothing left to refresh


def test_changing_the_interval_mid_run_refreshes_at_the_new_pace():
    """Setting spring_interval while running refreshes now and then every new interval."""
    world, _, _, _ = oscillator(interval=0.01)
    world.run_until(0.055)
    world.spring_interval = 0.002
    system = world._springs
    assert system._next == pytest.approx(0.057, abs=1e-12)
    world.run_until(0.06)
    assert system._next == pytest.approx(0.061, abs=1e-12)


def test_a_spring_added_while_running_takes_effect_at_once():
    """A spring made in a callback mid-run pulls from that moment."""
    world = World()
    anchor = world.add_circle(ANCHOR, 0.02, fixed=True)
    ball = world.add_circle((0.5, 0.5), 0.02, mass=M, velocity=(0.5, 0.0))
    made = []
    world.at_time(0.1, lambda timer: made.append(world.add_spring(anchor, ball, K)))  # rest: the length then
    world.run_until(0.1)
    assert ball.velocity == (0.5, 0.0)
    world.run_until(0.1 + 1e-9)
    assert made and made[0].rest_length == pytest.approx(0.35)
    world.run_until(0.11)
    assert ball.total_acceleration[0] < 0.0
    world.run_until(0.1 + PERIOD / 4)
    assert ball.velocity[0] == pytest.approx(0.0, abs=2e-3)  # a quarter swing later it stops


def test_a_crossing_made_by_a_call_between_refreshes_fires_by_the_next_refresh():
    """A velocity set between refreshes is not heard of at once: a crossing it causes fires at the next
    refresh at the latest, and once."""
    world, _, ball, spring = oscillator(displacement=0.0, interval=0.5, two_sided=False)
    calls = []
    spring.when(REST - 0.05, lambda event: calls.append(event.time))
    world.run_until(0.01)
    ball.velocity = (-1.0, 0.0)  # reaches REST - 0.05 at t = 0.06
    world.run_until(1.2)
    assert len(calls) == 1 and 0.06 <= calls[0] <= 0.5 + 1e-12


def test_interval_follows_the_frame_rate_and_validates():
    """Default interval: the frame period, else 0.01 s; a set interval must be positive and finite."""
    assert World().spring_interval == 0.01
    world = World(frame_rate=50)
    assert world.spring_interval == 0.02
    world.frame_rate = 200
    assert world.spring_interval == 0.005
    world.spring_interval = 0.001
    assert world.spring_interval == 0.001
    for bad, error in ((0.0, ValueError), (-1.0, ValueError), (math.inf, ValueError), ("1", TypeError)):
        with pytest.raises(error, match="spring_interval"):
            world.spring_interval = bad
    assert world.spring_interval == 0.001


def test_spring_handle_views():
    """A spring reports its ends, parameters and length; rest length defaults to the distance now."""
    world = World()
    a = world.add_circle((0.2, 0.5), 0.02, fixed=True)
    b = world.add_circle((0.5, 0.9), 0.02, mass=1.0)
    spring = world.add_spring(a, b, 3.0, 0.5, name="rope")
    assert isinstance(spring, Spring)
    assert (spring.a, spring.b) == (a, b)
    assert (spring.stiffness, spring.damping, spring.two_sided, spring.name) == (3.0, 0.5, False, "rope")
    assert spring.rest_length == spring.length == pytest.approx(0.5)
    assert world.springs == (spring,) and spring.alive
    assert "rope" in repr(spring) and spring.label() == "spring 1 'rope'"


def test_sprung_bodies_never_overlap_what_they_hit():
    """Every refresh re-predicts: a hanging ball swinging into a wall is never found overlapping it."""
    world = World(gravity=(0.0, -9.81), elasticity=0.9)
    anchor = world.add_circle((0.5, 0.9), 0.02, fixed=True)
    wall = world.add_box(0.62, 0.2, 0.05, 0.6, fixed=True)
    ball = world.add_circle((0.3, 0.6), 0.04, mass=1.0, velocity=(1.5, 0.0))
    world.add_spring(anchor, ball, 200.0, 0.5, rest_length=0.3)
    hits = []
    world.on_collision(lambda c: hits.append(c), ball)
    for n in range(1, 2001):
        world.run_until(n * 1e-3)
        assert world.overlap_depth(ball, wall) <= 1e-12
    assert hits


# --------------------------------------------------------------- bad input


@pytest.mark.parametrize(
    ("args", "options", "error", "message"),
    [
        (("a", "not a body", 1.0), {}, TypeError, "add_spring: b must be a Body"),
        (("a", "a", 1.0), {}, ValueError, "two different bodies"),
        (("a", "b", -1.0), {}, ValueError, "stiffness must not be negative"),
        (("a", "b", math.nan), {}, ValueError, "stiffness must be finite"),
        (("a", "b", "1"), {}, TypeError, "stiffness must be a number"),
        (("a", "b", 1.0, -0.5), {}, ValueError, "damping must not be negative"),
        (("a", "b", 1.0, math.inf), {}, ValueError, "damping must be finite"),
        (("a", "b", 1.0), {"rest_length": -0.1}, ValueError, "rest_length must not be negative"),
        (("a", "b", 1.0), {"rest_length": math.inf}, ValueError, "rest_length must be finite"),
        (("a", "b", 1.0), {"two_sided": 1}, TypeError, "two_sided must be True or False"),
        (("a", "b", 1.0), {"name": "rope", "stiffness": -2.0}, ValueError, "add_spring 'rope': stiffness"),
    ],
)
def test_bad_spring_input_raises_and_leaves_the_world_unchanged(args, options, error, message):
    """Bad ends or parameters raise naming the problem; no spring, no watch, no acceleration is left."""
    world = World()
    bodies = {"a": world.add_circle((0.2, 0.5), 0.02, fixed=True), "b": world.add_circle((0.6, 0.5), 0.02, mass=1)}
    args = [bodies.get(x, x) if isinstance(x, str) else x for x in args]
    if "stiffness" in options:
        args[2] = options.pop("stiffness")
    with pytest.raises(error, match=message):
        world.add_spring(*args, **options)
    assert world.springs == ()
    assert world._watchers == {} and world._timers == {}
    assert bodies["b"].total_acceleration == (0.0, 0.0)
    world.run_until(0.1)


def test_ends_from_another_world_or_removed_are_refused():
    """A body of another world, or a removed body, cannot take a spring."""
    world, other = World(), World()
    a = world.add_circle((0.2, 0.5), 0.02, fixed=True)
    stranger = other.add_circle((0.6, 0.5), 0.02, mass=1)
    with pytest.raises(ValueError, match="belongs to another world"):
        world.add_spring(a, stranger, 1.0)
    gone = world.add_circle((0.6, 0.5), 0.02, mass=1)
    world.remove(gone)
    with pytest.raises(ValueError, match="has been removed"):
        world.add_spring(a, gone, 1.0)
    with pytest.raises(TypeError, match="expected a Spring"):
        world.remove_spring(a)
    assert world.springs == ()


def test_bad_when_input():
    """when() needs a positive finite length and a callable."""
    _, _, _, spring = oscillator()
    for bad, error in ((0.0, ValueError), (-1.0, ValueError), (math.nan, ValueError), (None, TypeError)):
        with pytest.raises(error, match="spring 1: when"):
            spring.when(bad, print)
    with pytest.raises(TypeError, match="callback must be callable"):
        spring.when(0.3, 5)
    assert spring.pending == ()


# ------------------------------------------------------------ classic facade


@pytest.mark.usefixtures("session")
def test_classic_spring_when_snaps_the_rope():
    """A PGE-style script: spring(...).draw(...).when(l, p) calls p(event, spring) once, headless; the
    event is a function event whose id comes from the at_time counter; rm() snaps the rope."""
    pge.batch()
    anchor = pge.box(0.45, 0.9, 0.1, 0.05, pge.white()).fix()
    ball = pge.circle(0.5, 0.6, 0.03, pge.rgb(1, 0, 0)).mass(1)
    seen = []

    def snap(e, s):
        seen.append((e, s, pge.get_time(), s.spring.length))
        s.rm()

    timer = pge.at_time(0.05, lambda e, o: None)
    rope = pge.spring(anchor, ball, 100.0, 0.0, 0.2)
    assert rope.type == pge.spring_t
    assert rope.draw(pge.white(), 0.01) is rope and rope.end(pge.white()) is rope and rope.mid(pge.white()) is rope
    assert rope.when(0.3, snap) is rope
    pge.gravity()
    pge.run(1.0)
    assert len(seen) == 1
    event, obj, time, length = seen[0]
    assert obj is rope and rope.deleted
    assert event.type == pge.function_event and event.get_time() == time
    assert event.get_timer_id() > timer
    assert abs(length - 0.3) < 1e-9
    assert ball.get_yvel() < 0.0  # snapped: falling freely
    rope.rm()  # a second rm does nothing


@pytest.mark.usefixtures("session")
def test_classic_spring_errors():
    """Spring methods on other objects, springs on colours or massless objects, bad values: clear errors."""
    pge.batch()
    anchor = pge.box(0.45, 0.9, 0.1, 0.05, pge.white()).fix()
    ball = pge.circle(0.5, 0.6, 0.03, pge.white()).mass(1)
    loose = pge.circle(0.2, 0.2, 0.03, pge.white())
    with pytest.raises(TypeError, match="draw: you cannot draw a spring on a circle object"):
        ball.draw(pge.white(), 0.01)
    with pytest.raises(TypeError, match="when: you cannot"):
        ball.when(0.3, print)
    with pytest.raises(TypeError, match="spring: you cannot attach a spring to a colour object"):
        pge.spring(anchor, pge.white(), 1.0, 0.0)
    with pytest.raises(ValueError, match="must be fixed or have a mass"):
        pge.spring(anchor, loose, 1.0, 0.0)
    with pytest.raises(ValueError, match="two different objects"):
        pge.spring(ball, ball, 1.0, 0.0)
    with pytest.raises(ValueError, match="spring: k must not be negative"):
        pge.spring(anchor, ball, -1.0, 0.0)
    with pytest.raises(ValueError, match="spring: l must not be negative"):
        pge.spring(anchor, ball, 1.0, 0.0, -0.1)
    with pytest.raises(TypeError, match="spring: ob2 must be a pge box or circle object"):
        pge.spring(anchor, 3, 1.0, 0.0)
    assert pge.classic._STATE.world.springs == ()
    rope = pge.spring(anchor, ball, 1.0, 0.0)
    with pytest.raises(TypeError, match="first parameter to draw is expected to be a colour"):
        rope.draw(0.01, pge.white())
    with pytest.raises(ValueError, match="when: l must be positive"):
        rope.when(0.0, print)
    with pytest.raises(TypeError, match="you cannot give a velocity to a spring object"):
        rope.velocity(1, 0)
    ball.rm()  # the spring goes with its end
    assert rope.deleted
    with pytest.raises(ValueError, match="object has been deleted"):
        rope.when(0.3, print)
    loose.mass(1)
    pge.run(0.1)


@pytest.mark.usefixtures("session")
def test_classic_at_cancel_cancels_a_when():
    """at_cancel(id) of a when's timer id: the callback never runs."""
    pge.batch()
    anchor = pge.box(0.45, 0.9, 0.1, 0.05, pge.white()).fix()
    ball = pge.circle(0.5, 0.6, 0.03, pge.white()).mass(1)
    calls = []
    rope = pge.spring(anchor, ball, 100.0, 0.0, 0.2).when(0.3, lambda e, s: calls.append(e.get_timer_id()))
    pge.gravity()
    watch = rope.spring.pending[0]
    pge.at_cancel(watch)
    assert rope.spring.pending == ()
    pge.run(0.5)
    assert calls == []


class _Capture:
    """A display that keeps the polygons drawn (for the spring bands)."""

    draws = True

    def __init__(self):
        self.polygons = []

    def begin_frame(self, background):
        pass

    def circles(self, xs, ys, radii, colours, index=None):
        pass

    def circle(self, x, y, r, colour):
        pass

    def polygon(self, points, colour):
        self.polygons.append((list(points), colour))

    def text(self, x, y, s, colour, size):
        pass

    def end_frame(self):
        pass


@pytest.mark.usefixtures("session")
def test_classic_drawn_spring_is_a_band_between_the_centres():
    """draw(c, w): a filled 4-gon w wide from centre to centre, in c, drawn after the level-0 objects."""
    from pge.classic import frames

    pge.batch()
    anchor = pge.circle(0.5, 0.9, 0.02, pge.white()).fix()
    ball = pge.circle(0.5, 0.5, 0.02, pge.white()).mass(1)
    pge.spring(anchor, ball, 10.0, 0.0).draw(pge.rgb(1, 0, 0), 0.02)
    pge.spring(anchor, ball, 10.0, 0.0)  # never drawn: invisible
    display = _Capture()
    frames.compose(display)
    assert len(display.polygons) == 1
    points, colour = display.polygons[0]
    assert colour == (255, 0, 0, 255)
    expected = [(0.51, 0.9), (0.51, 0.5), (0.49, 0.5), (0.49, 0.9)]
    flat = [v for point in sorted(points) for v in point]
    assert flat == pytest.approx([v for point in sorted(expected) for v in point], abs=1e-12)
