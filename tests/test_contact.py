"""Resting and sliding contact (docs/contact.md): how bouncing ends, and what a body in contact does.

Scenes are hand-built with closed-form answers (helpers in contact_scenes.py). A body at rest is
asleep (no events, no island steps), ``resting_on`` names the body it pressed on hardest at its
island's last step, and a bounce that ends in contact is a join.

Tolerances follow docs/contact.md, "Exact and integrated": free flight, impacts between bodies
not in one island, and motion under constant contact forces (resting, stacking, sliding) are
exact, and are held to CLOSE (1e-9) or EXACT (1e-12). What happens *within* one step (a body
leaving a face, a slide stopping, friction turning round) happens at a step, so it is late by at
most one step h = ISLAND_STEP; those tests bound the error by that step and say so.
"""

from __future__ import annotations

import itertools
import math

import pytest

from pge import World
from pge.core.tuning import ISLAND_STEP
from contact_scenes import (
    CLOSE,
    EXACT,
    G,
    V_LEFT,
    V_RIGHT,
    along,
    collision_times,
    energy,
    floor_world,
    settle_time,
    slope_scene,
)

H = ISLAND_STEP


def islands_world(**options) -> World:
    return World(**options)


def islands_floor_world(elasticity=0.5, floor_friction=0.0, **options):
    return floor_world(elasticity=elasticity, floor_friction=floor_friction, **options)


def islands_slope_scene(angle_deg, shape, mu, velocity=0.0, on_ramp=False):
    """``contact_scenes.slope_scene``."""
    return slope_scene(angle_deg, shape, mu, velocity=velocity, on_ramp=on_ramp)


def island_bounces(h0: float, e: float, rest_height: float, reach: float) -> int:
    """The collision at which a ball dropped from gap h0 joins the floor's island: the first k
    whose bounce would rise less than rest_height * reach, or which comes less than one step
    after the one before (docs/contact.md: "persistent" impacts)."""
    v0 = math.sqrt(2.0 * G * h0)
    k = 1
    while True:
        low = e ** (2 * k) * h0 <= rest_height * reach
        quick = k >= 2 and 2.0 * v0 * e ** (k - 1) / G < H
        if low or quick:
            return k
        k += 1


def assert_silent(world: World, until: float) -> None:
    """Running on to ``until`` makes no event and no island step."""
    events, steps = world.stats["events"], world.stats["island_steps"]
    world.run_until(until)
    assert world.stats["events"] == events
    assert world.stats["island_steps"] == steps


# ------------------------------------------------------------------ a dropped body settles


@pytest.mark.parametrize("shape", ["circle", "box"])
@pytest.mark.parametrize("rest_height", [1e-4, 1e-2, 1e-7])
def test_half_elastic_drop_bounces_at_the_free_flight_times_then_joins_the_floor_and_sleeps(shape, rest_height):
    """A body (e = 0.5 on a 0.5 floor) bounces at exactly the closed-form times until the bounce
    that rest_height (or the step) makes persistent, joins the floor's island there, lies at
    exactly its half height, falls asleep, and then makes no event or step for 200 s."""
    world, floor = islands_floor_world(elasticity=0.5, rest_height=rest_height)
    if shape == "circle":
        body = world.add_circle((0.5, 0.5), 0.0625, mass=1.0, name="ball")
    else:
        body = world.add_box(0.4375, 0.4375, 0.125, 0.125, mass=1.0, name="box")
    half = 0.0625
    h0 = 0.5 - half
    n = island_bounces(h0, 0.5, rest_height, body.bounding_radius)
    times = collision_times(world, body)
    world.run_until(2.0)
    assert len(times) == n
    for k, time in enumerate(times):
        assert abs(time - settle_time(h0, 0.5, k + 1)) <= CLOSE
    assert world.stats["joins"] == 1
    assert body.asleep and body.resting_on is floor
    assert body.velocity == (0.0, 0.0) and body.angular_velocity == 0.0
    x, y = body.position
    assert abs(y - half) <= EXACT and x == 0.5
    assert_silent(world, 200.0)
    assert body.position == (x, y) and body.asleep and body.resting_on is floor


def test_default_elasticity_drop_settles_after_a_few_hundred_bounces_in_finite_time():
    """With the default elasticity 0.98 a dropped ball bounces a few hundred times at the
    closed-form times, joins the floor near 28 s, lies at exactly r and sleeps, silent after."""
    world = islands_world(gravity=(0.0, -G), bounds=(-1.0, -1.0, 3.0, 3.0))
    floor = world.add_box(-1.0, -0.25, 6.0, 0.25, fixed=True, name="floor")
    ball = world.add_circle((0.5, 0.5), 0.0625, mass=1.0, name="ball")
    assert ball.elasticity == 0.98 and floor.elasticity == 0.98
    h0 = 0.5 - 0.0625
    n = island_bounces(h0, 0.98, 1e-4, 0.0625)
    assert 200 <= n <= 400
    t_n = settle_time(h0, 0.98, n)
    assert 20.0 < t_n < 32.0
    times = collision_times(world)
    world.run_until(t_n + 1.0)
    assert len(times) == n
    assert abs(times[-1] - t_n) <= CLOSE * t_n
    assert ball.asleep and ball.resting_on is floor and ball.velocity == (0.0, 0.0)
    assert abs(ball.position[1] - 0.0625) <= EXACT and ball.position[0] == 0.5
    assert_silent(world, t_n + 200.0)
    assert ball.resting_on is floor and abs(ball.position[1] - 0.0625) <= EXACT


# ------------------------------------------------------------------ stacks


@pytest.mark.parametrize(
    "elasticity, widths, gap",
    [
        (elasticity, widths, gap)
        for widths, gap in [((0.1, 0.1, 0.1), 0.01), ((0.25, 0.1875, 0.125), 0.015625), ((0.125, 0.125, 0.125), 0.003)]
        for elasticity in (0.5, 0.98, 0.0)
    ],
)
def test_stack_of_three_boxes_settles_and_stays_stacked(elasticity, widths, gap):
    """Three boxes dropped with small gaps land, stand level at the exact heights on one another
    and centred, without sideways drift or tilt (to 1e-9, as the stacks of docs/contact.md: a
    landing that closes a gap within a step leaves rounding of ~1e-11), sleep within 4 s (or,
    nearly elastic, within a second of the time a box dropped by the gap onto a floor takes to
    stop bouncing, ``sqrt(2 gap / g) (1 + e) / (1 - e)``: 5.6 s at e = 0.98 and the widest
    gap) and stay silent for 10 s."""
    world, floor = islands_floor_world(elasticity=elasticity)
    boxes = []
    y = gap
    for k, w in enumerate(widths):
        boxes.append(world.add_box(0.5 - w / 2, y, w, 0.1, mass=1.0 + k, name=f"b{k}"))
        y += 0.1 + gap
    bouncing = math.sqrt(2.0 * gap / 9.81) * (1.0 + elasticity) / (1.0 - elasticity)
    limit = max(4.0, 1.0 + bouncing)
    t = 0.0
    while not all(b.asleep for b in boxes):
        t += 0.05
        assert t < limit, "the stack never fell asleep"
        world.run_until(t)
    assert world.stats["joins"] >= 1
    assert [b.resting_on for b in boxes] == [floor, boxes[0], boxes[1]]
    settled = [b.position for b in boxes]
    assert_silent(world, t + 10.0)
    assert [b.position for b in boxes] == settled
    assert all(b.velocity == (0.0, 0.0) and b.asleep for b in boxes)
    assert abs(boxes[0].bounding_box[1]) <= CLOSE
    for lower, upper in itertools.pairwise(boxes):
        assert abs(upper.bounding_box[1] - lower.bounding_box[3]) <= CLOSE
    for body in boxes:
        assert abs(body.position[0] - 0.5) <= CLOSE  # no sideways drift
        assert abs(body.angle) <= CLOSE
    assert world.overlaps(CLOSE) == []


def test_box_dropped_on_a_box_sliding_on_ice_is_dragged_along_keeping_momentum():
    """A box (m 1, friction 0.5) dropped with no horizontal speed onto a box (m 1) sliding at 2 m/s
    on a frictionless floor rides on it: only friction between the two acts horizontally, so their
    momentum stays 2 kg m/s (1e-9) and their energy never rises, sampled every 0.01 s until the top
    box (which tips off the back here) reaches the floor. Energy may rise only by a step's
    integration error while the top box turns (docs/contact.md, "Energy": at most 2e-7 of the
    scene's energy over a step); it is held to 1e-12 of it, since it only fell (measured)."""
    world, floor = islands_floor_world(elasticity=0.0, bounds=(-1.0, -1.0, 5.0, 3.0))
    low = world.add_box(0.0, 1e-4, 0.4, 0.1, mass=1.0, elasticity=0.0, friction=0.0, name="low")
    world.run_until(0.05)
    low.velocity = (2.0, 0.0)
    top = world.add_box(0.1, 0.1 + 1e-3, 0.1, 0.1, mass=1.0, elasticity=0.0, friction=0.5, name="top")
    on_floor = collision_times(world, floor)
    before = energy(world)
    scale = max(1.0, abs(before))
    rode = samples = 0
    for k in range(1, 31):
        world.run_until(0.05 + 0.01 * k)
        if on_floor:
            break  # the floor's friction acts from here on
        samples += 1
        rode += top.resting_on is low
        assert low.velocity[0] + top.velocity[0] == pytest.approx(2.0, abs=CLOSE)
        now = energy(world)
        assert now <= before + EXACT * scale
        before = now
    assert rode >= 10 and samples >= 15
    assert abs(top.velocity[0] - low.velocity[0]) < 2.0  # friction dragged it along


# ------------------------------------------------------------------ slopes


@pytest.mark.parametrize(
    "shape, fraction, angle",
    [(shape, fraction, angle) for shape, fraction in [("box", 0.0), ("box", 0.5), ("box", 0.95), ("circle", 0.0)]
     for angle in (10.0, 30.0, 50.0) if not (shape == "box" and fraction * math.tan(math.radians(angle)) > 1.0)],
)
@pytest.mark.parametrize("on_ramp", [False, True])
def test_body_on_a_slope_slides_with_acceleration_g_sin_minus_mu_cos(shape, angle, fraction, on_ramp):
    """tan(a) > mu: a body at rest on the slope slides down s = g (sin a - mu cos a) t^2 / 2 and
    stays on the surface, exactly (constant contact forces). A square box with mu > 1 topples
    instead (test_square_box_on_a_steep_rough_slope_topples)."""
    a = math.radians(angle)
    mu = fraction * math.tan(a)
    world, body, ramp, tangent = islands_slope_scene(angle, shape, mu, on_ramp=on_ramp)
    start = body.position
    normal = (-tangent[1], tangent[0])
    t = 0.5
    world.run_until(t)
    assert body.resting_on is ramp and not body.asleep
    expected = 0.5 * G * (math.sin(a) - mu * math.cos(a)) * t * t
    assert abs(-along(start, body.position, tangent) - expected) <= CLOSE
    assert abs(along(start, body.position, normal)) <= EXACT
    speed = G * (math.sin(a) - mu * math.cos(a)) * t
    assert abs(-along((0.0, 0.0), body.velocity, tangent) - speed) <= CLOSE
    assert abs(along((0.0, 0.0), body.velocity, normal)) <= EXACT
    if shape == "box":
        assert abs(body.angle) <= EXACT
    assert world.overlaps(1e-11) == []


@pytest.mark.parametrize("angle", [10.0, 30.0])
@pytest.mark.parametrize("fraction", [1.05, 2.0])
def test_body_on_a_slope_stays_put_when_mu_exceeds_tan(angle, fraction):
    """tan(a) < mu (and the square's tipping angle 45 degrees not reached): a box at rest on the
    slope stays exactly where it is, falls asleep on the ramp within 1 s, and then makes no event
    or step for 10 s."""
    mu = fraction * math.tan(math.radians(angle))
    world, body, ramp, _ = islands_slope_scene(angle, "box", mu)
    start = body.position
    world.run_until(1.0)
    assert body.asleep and body.resting_on is ramp
    assert world.stats["events"] <= 2
    assert_silent(world, 10.0)
    assert body.resting_on is ramp and body.velocity == (0.0, 0.0)
    assert abs(body.position[0] - start[0]) <= EXACT and abs(body.position[1] - start[1]) <= EXACT
    assert abs(body.angle) <= EXACT


@pytest.mark.parametrize("fraction", [1.05, 2.0])
def test_square_box_on_a_steep_rough_slope_topples(fraction):
    """At 50 degrees a square box whose friction exceeds tan(a) cannot slide, but its weight acts
    outside its base (tan 50 > 1 = width / height): it tips over its lower edge and tumbles down,
    turning more than a quarter turn within 1 s."""
    mu = fraction * math.tan(math.radians(50.0))
    world, body, ramp, tangent = islands_slope_scene(50.0, "box", mu)
    start = body.position
    world.run_until(1.0)
    assert abs(body.angle) > 0.5 * math.pi
    assert -along(start, body.position, tangent) > 0.05


@pytest.mark.parametrize("angle, mu", [(30.0, 0.3), (20.0, 0.1), (30.0, 0.8)])
def test_box_pushed_up_a_slope_stops_then_slides_back_or_stays(angle, mu):
    """Pushed up at v, a box decelerates at g (sin + mu cos) exactly, stops at v^2 / (2 a_up), then
    slides back at g (sin - mu cos) (tan > mu) or stays and sleeps. The stop falls within a step,
    whose one constant force cannot turn friction round at the instant: the slide back starts at
    the step's end, late by at most h, so its speed is off by at most a_down h and its position by
    at most a_down h t; a box that stays stops at the step's end, at most a_up h^2 / 8 beyond
    v^2 / (2 a_up) (as on the flat: test_sliding_body_stops_at_v_squared_over_2_mu_g)."""
    a = math.radians(angle)
    v = 1.0
    world, body, ramp, tangent = islands_slope_scene(angle, "box", mu, velocity=v)
    start = body.position
    up = G * (math.sin(a) + mu * math.cos(a))
    down = max(0.0, G * (math.sin(a) - mu * math.cos(a)))
    t_stop = v / up
    world.run_until(0.5 * t_stop)
    assert abs(along(start, body.position, tangent) - (v * 0.5 * t_stop - 0.125 * up * t_stop**2)) <= CLOSE
    assert abs(along((0.0, 0.0), body.velocity, tangent) - 0.5 * v) <= CLOSE
    world.run_until(t_stop + 0.3)
    assert body.resting_on is ramp
    if down > 0.0:
        expected = v * v / (2.0 * up) - 0.5 * down * 0.3**2
        assert abs(along(start, body.position, tangent) - expected) <= down * H * 0.3 + CLOSE
        assert abs(along((0.0, 0.0), body.velocity, tangent) + down * 0.3) <= down * H + CLOSE
        assert along((0.0, 0.0), body.velocity, tangent) < 0.0  # sliding back down
    else:
        assert abs(along(start, body.position, tangent) - v * v / (2.0 * up)) <= up * H * H / 8.0 + CLOSE
        assert math.hypot(*body.velocity) <= EXACT
        world.run_until(t_stop + 1.0)
        assert body.asleep and body.resting_on is ramp and body.velocity == (0.0, 0.0)
        assert_silent(world, 5.0)


# ------------------------------------------------------------------ sliding on the flat


@pytest.mark.parametrize("v, mu", [(1.0, 0.5), (2.0, 0.25), (0.75, 1.0)])
def test_sliding_body_stops_at_v_squared_over_2_mu_g(v, mu):
    """A box sliding on the floor with friction mu decelerates at mu g exactly and stops at
    v^2 / (2 mu g), then sleeps and stays silent. The stop falls within a step, over which the
    step's one constant force brings the box to rest at the step's end: with speed u < mu g h at
    the step's start it travels u h / 2 instead of u^2 / (2 mu g), at most mu g h^2 / 8 more."""
    world, floor = islands_floor_world()
    body = world.add_box(0.0, 0.0, 0.125, 0.125, mass=2.0, velocity=(v, 0.0), friction=mu)
    x0, y0 = body.position
    t_stop = v / (mu * G)
    world.run_until(0.5 * t_stop)
    assert body.resting_on is floor
    assert abs(body.velocity[0] - 0.5 * v) <= CLOSE and abs(body.velocity[1]) <= EXACT
    assert abs(body.position[0] - x0 - (0.5 * v * t_stop - 0.125 * mu * G * t_stop**2)) <= CLOSE
    world.run_until(1.5 * t_stop)
    overshoot = body.position[0] - x0 - v * v / (2.0 * mu * G)
    assert -EXACT <= overshoot <= mu * G * H * H / 8.0 + EXACT
    assert abs(body.position[1] - y0) <= EXACT
    assert math.hypot(*body.velocity) <= EXACT
    world.run_until(1.5 * t_stop + 1.0)
    assert body.asleep and body.resting_on is floor
    assert body.velocity == (0.0, 0.0)
    stopped = body.position
    assert abs(stopped[0] - x0 - v * v / (2.0 * mu * G) - overshoot) <= EXACT
    assert_silent(world, 100.0)
    assert body.position == stopped and body.resting_on is floor


# ------------------------------------------------------------------ leaving an edge


@pytest.mark.parametrize("x0, v, end", [(0.125, 1.0, 0.5), (0.13, 0.9, 0.53), (0.2, 1.3, 0.61)])
def test_frictionless_ball_leaves_the_shelf_end_and_falls(x0, v, end):
    """A ball sliding along a shelf leaves it at the first step after its centre passes the end
    (a body leaves its island at a step: at most h late) and then falls freely: its height, its
    horizontal position and its landing on the floor all agree with one departure time in
    (t_leave, t_leave + h], to 1e-9."""
    world, floor = islands_floor_world(floor_friction=0.5)
    r, top = 0.0625, 0.625
    shelf = world.add_box(0.0, top - 0.125, end, 0.125, fixed=True, name="shelf")
    ball = world.add_circle((x0, top + r), r, mass=1.0, velocity=(v, 0.0), name="ball")
    assert v * v > G * r  # fast enough to clear the corner
    t_leave = (end - x0) / v
    landings = collision_times(world, floor)
    world.run_until(0.5 * t_leave)
    assert ball.resting_on is shelf
    assert abs(ball.position[1] - (top + r)) <= EXACT
    dt = 0.1
    world.run_until(t_leave + dt)
    assert ball.resting_on is None
    assert abs(ball.position[0] - (end + v * dt)) <= CLOSE  # frictionless: the speed never changed
    height = ball.position[1]
    world.run_until(t_leave + 1.0)
    assert landings, "the ball never reached the floor"
    departure = landings[0] - math.sqrt(2.0 * top / G)
    assert t_leave - CLOSE < departure <= t_leave + H + CLOSE
    fall = t_leave + dt - departure
    assert abs(height - (top + r - 0.5 * G * fall * fall)) <= CLOSE


def test_ball_slid_off_a_shelf_ends_below_it_rolling_on_the_floor():
    """A ball that slid off a frictionless shelf lands below it and, on the floor (friction 0.5),
    rolls at once (the landing's friction matches spin and speed, exactly: omega r = -v to 1e-9)
    at a constant speed, without events."""
    world, floor = islands_floor_world(floor_friction=0.5)
    r, top = 0.0625, 0.625
    shelf = world.add_box(0.0, top - 0.125, 0.5, 0.125, fixed=True, name="shelf")
    ball = world.add_circle((0.125, top + r), r, mass=1.0, velocity=(1.0, 0.0), name="ball")
    world.run_until(0.1)
    assert ball.resting_on is shelf
    world.run_until(1.5)
    assert ball.resting_on is floor
    assert abs(ball.position[1] - r) <= EXACT
    assert ball.position[0] > 0.5 + r
    vx, vy = ball.velocity
    assert vx > 0.0 and abs(vy) <= EXACT
    assert abs(vx + ball.angular_velocity * r) <= CLOSE  # rolling
    events = world.stats["events"]
    world.run_until(2.5)
    assert world.stats["events"] == events
    assert abs(ball.velocity[0] - vx) <= EXACT and abs(ball.velocity[1]) <= EXACT


def test_box_slides_off_the_shelf_end_tips_falls_and_lies_flat_on_the_floor():
    """A frictionless box sliding off a shelf rides flat while its centre is over the shelf, tips
    over the edge once its centre has passed it (before its whole base has), falls, and ends
    asleep lying flat on the floor (a whole number of quarter turns, its bottom at y = 0 to 1e-9)."""
    world, floor = islands_floor_world(floor_friction=0.5)
    top, side, v = 0.625, 0.125, 1.0
    shelf = world.add_box(0.0, top - 0.125, 0.5, 0.125, fixed=True, name="shelf")
    box = world.add_box(0.125, top, side, side, mass=1.0, velocity=(v, 0.0), name="box")
    t_centre = (0.5 - 0.125 - side / 2) / v
    t_leave = (0.5 - 0.125) / v
    world.run_until(0.9 * t_centre)
    assert box.resting_on is shelf
    assert abs(box.angle) <= EXACT and abs(box.position[1] - (top + side / 2)) <= EXACT
    assert abs(box.position[0] - (0.125 + side / 2 + v * 0.9 * t_centre)) <= CLOSE
    world.run_until(t_leave)
    assert box.angle < -0.05  # tipping over the edge (clockwise)
    world.run_until(t_leave + 0.1)
    assert box.resting_on is None
    world.run_until(10.0)
    assert box.asleep and box.resting_on is floor and box.velocity == (0.0, 0.0)
    quarter = box.angle / (0.5 * math.pi)
    assert abs(quarter - round(quarter)) <= 1e-9
    assert abs(box.bounding_box[1]) <= CLOSE


# ------------------------------------------------------------------ releases


def _side_hit_scene():
    """A big resting ball (r 0.125, 2 kg) about to be hit low on its side by a small ball (r 0.0625, 1 kg) sliding at 2."""
    world, floor = islands_floor_world(elasticity=0.5)
    big = world.add_circle((1.0, 0.125), 0.125, mass=2.0, name="big")
    small = world.add_circle((0.25, 0.0625), 0.0625, mass=1.0, velocity=(2.0, 0.0), name="small")
    dy, d = 0.0625, 0.1875
    dx = math.sqrt(d * d - dy * dy)
    return world, floor, big, small, (dx / d, dy / d), (1.0 - dx - 0.25) / 2.0


def test_resting_ball_hit_low_from_the_side_is_lifted_off_and_flies():
    """A ball hit below its centre leaves the floor with the impulse of a hit whose striker stays
    pressed into the floor (the small ball keeps only the horizontal part), rises exactly to
    v_y^2 / 2g, lands, and lies again at exactly r."""
    world, floor, big, small, (nx, ny), t_hit = _side_hit_scene()
    world.run_until(0.5 * t_hit)
    assert big.resting_on is floor and small.resting_on is floor
    hits = []
    world.on_collision(
        lambda event: hits.append((event.time, big.resting_on, big.velocity, small.resting_on, small.velocity)), big
    )
    world.run_until(t_hit + 1e-9)
    assert len(hits) == 1
    time, big_support, big_v, small_support, small_v = hits[0]
    assert abs(time - t_hit) <= CLOSE
    j = (1.0 + 0.5) * 2.0 * nx / (1.0 / 2.0 + (1.0 - ny * ny))
    assert big_support is None
    assert abs(big_v[0] - j * nx / 2.0) <= EXACT and abs(big_v[1] - j * ny / 2.0) <= EXACT
    assert small_support is floor
    assert abs(small_v[0] - (2.0 - j * nx)) <= EXACT and abs(small_v[1]) <= EXACT
    vy = j * ny / 2.0
    world.run_until(t_hit + vy / G)
    assert big.resting_on is None
    assert abs(big.position[1] - (0.125 + vy * vy / (2.0 * G))) <= CLOSE
    assert abs(big.position[0] - (1.0 + j * nx / 2.0 * vy / G)) <= CLOSE
    world.run_until(t_hit + 1.0)  # landed and sliding, still well before the floor's end at x = 5
    assert big.resting_on is floor and abs(big.position[1] - 0.125) <= EXACT
    assert world.stats["joins"] >= 2


def test_horizontal_hit_keeps_both_balls_resting():
    """Equal balls on the floor hit head-on (e = 1) swap velocities exactly and both stay on the
    floor at exactly r."""
    world, floor = islands_floor_world(elasticity=1.0)
    a = world.add_circle((1.0, 0.0625), 0.0625, mass=1.0, name="a")
    b = world.add_circle((0.25, 0.0625), 0.0625, mass=1.0, velocity=(2.0, 0.0), name="b")
    seen = []
    world.on_collision(lambda event: seen.append((event.time, a.resting_on, b.resting_on, a.velocity, b.velocity)), a)
    world.run_until(0.5)
    assert len(seen) == 1
    time, a_support, b_support, a_v, b_v = seen[0]
    assert abs(time - 0.3125) <= CLOSE
    assert (a_support, b_support, a_v, b_v) == (floor, floor, (2.0, 0.0), (0.0, 0.0))
    assert a.resting_on is floor and b.resting_on is floor
    assert abs(a.position[0] - (1.0 + 2.0 * (0.5 - 0.3125))) <= EXACT and abs(a.position[1] - 0.0625) <= EXACT
    assert abs(b.position[0] - 0.875) <= EXACT and abs(b.position[1] - 0.0625) <= EXACT


def test_set_velocity_upwards_lifts_a_sleeping_ball_and_it_flies():
    """An upward velocity wakes a ball asleep on the floor; it rises v^2 / 2g, is back 2 v / g
    later (exactly: free flight), and lies asleep on the floor again."""
    world, floor = islands_floor_world(elasticity=0.5)
    ball = world.add_circle((0.5, 0.0625), 0.0625, mass=1.0, name="ball")
    world.run_until(1.0)
    assert ball.resting_on is floor and ball.asleep
    v = 2.0
    world.set_velocity(ball, (0.0, v))
    assert not ball.asleep
    landings = collision_times(world, ball)
    world.run_until(1.0 + v / G)
    assert ball.resting_on is None
    assert abs(ball.position[1] - (0.0625 + v * v / (2.0 * G))) <= CLOSE
    world.run_until(5.0)
    assert abs(landings[0] - (1.0 + 2.0 * v / G)) <= CLOSE
    assert ball.asleep and ball.resting_on is floor and ball.velocity == (0.0, 0.0)
    assert abs(ball.position[1] - 0.0625) <= EXACT and ball.position[0] == 0.5


def test_zero_gravity_leaves_nothing_resting():
    """After set_gravity((0, 0)), by the next step no body rests on anything, and a stack that
    stood still stays exactly where it is, at rest (no push without pressure)."""
    world, floor = islands_floor_world(elasticity=0.5)
    slider = world.add_box(0.0, 0.0, 0.125, 0.125, mass=1.0, velocity=(1.0, 0.0), friction=0.5, name="slider")
    lower = world.add_box(1.5, 0.0, 0.125, 0.125, mass=1.0, name="lower")
    upper = world.add_box(1.5, 0.125, 0.125, 0.125, mass=1.0, name="upper")
    bodies = (slider, lower, upper)
    world.run_until(0.1)
    assert [b.resting_on for b in bodies] == [floor, floor, lower]
    assert abs(slider.velocity[0] - (1.0 - 0.5 * G * 0.1)) <= CLOSE
    world.set_gravity((0.0, 0.0))
    world.run_until(0.1 + 2.0 * H)
    assert [b.resting_on for b in bodies] == [None, None, None]
    world.run_until(2.0)
    assert [b.resting_on for b in bodies] == [None, None, None]
    for body, (x, y) in ((lower, (1.5625, 0.0625)), (upper, (1.5625, 0.1875))):
        assert abs(body.position[0] - x) <= EXACT and abs(body.position[1] - y) <= EXACT
        assert math.hypot(*body.velocity) <= EXACT


@pytest.mark.parametrize("support_fixed", [False, True])
def test_rider_falls_onto_the_floor_when_its_support_is_removed(support_fixed):
    """Removing the body a sleeping ball rests on leaves the ball resting on nothing: it falls
    freely (exactly), lands at the free-fall time and sleeps on the floor at exactly r."""
    world, floor = islands_floor_world(elasticity=0.5)
    if support_fixed:
        height = 0.5
        support = world.add_box(0.5, height - 0.125, 0.25, 0.125, fixed=True, name="shelf")
    else:
        height = 0.25
        support = world.add_box(0.5, 0.0, 0.25, height, mass=1.0, name="block")
    ball = world.add_circle((0.625, height + 0.0625), 0.0625, mass=1.0, name="ball")
    world.run_until(1.0)
    assert ball.resting_on is support and ball.asleep
    world.remove(support)
    assert ball.resting_on is None and not ball.asleep
    landings = collision_times(world, ball)
    world.run_until(1.0 + 0.5 * math.sqrt(2.0 * height / G))
    assert ball.resting_on is None
    assert abs(ball.position[1] - (height + 0.0625 - 0.5 * G * 0.25 * 2.0 * height / G)) <= CLOSE
    world.run_until(5.0)
    assert abs(landings[0] - (1.0 + math.sqrt(2.0 * height / G))) <= CLOSE
    assert ball.asleep and ball.resting_on is floor and ball.velocity == (0.0, 0.0)
    assert abs(ball.position[1] - 0.0625) <= EXACT and ball.position[0] == 0.625


def test_top_of_a_stack_falls_onto_the_bottom_when_the_middle_is_removed():
    """Removing the middle box of a sleeping stack lets the top one fall freely onto the bottom
    one (landing at the free-fall time) and sleep on it, face on face."""
    world, floor = islands_floor_world(elasticity=0.5)
    boxes = [world.add_box(0.5, 0.125 * k, 0.125, 0.125, mass=1.0, name=f"b{k}") for k in range(3)]
    world.run_until(1.0)
    assert [b.resting_on for b in boxes] == [floor, boxes[0], boxes[1]]
    assert all(b.asleep for b in boxes)
    world.remove(boxes[1])
    assert boxes[2].resting_on is None and boxes[0].resting_on is floor
    landings = collision_times(world, boxes[2])
    world.run_until(5.0)
    assert abs(landings[0] - (1.0 + math.sqrt(2.0 * 0.125 / G))) <= CLOSE
    assert boxes[2].asleep and boxes[2].resting_on is boxes[0]
    assert abs(boxes[2].bounding_box[1] - boxes[0].bounding_box[3]) <= EXACT
    assert world.overlaps(EXACT) == []


# ------------------------------------------------------------------ energy


def _scene_drop(e):
    world, _ = islands_floor_world(elasticity=e)
    world.add_circle((0.5, 0.5), 0.0625, mass=1.0)
    return world


def _scene_slope():
    return islands_slope_scene(30.0, "box", 0.3)[0]


def _scene_slide():
    world, _ = islands_floor_world()
    world.add_box(0.0, 0.25, 0.125, 0.125, mass=2.0, velocity=(1.5, 0.5), friction=0.4)
    return world


def _scene_side_hit():
    return _side_hit_scene()[0]


@pytest.mark.parametrize(
    "make, duration",
    [
        (lambda: _scene_drop(0.5), 3.0),
        (lambda: _scene_drop(0.98), 32.0),
        (_scene_slope, 0.8),
        (_scene_slide, 3.0),
        (_scene_side_hit, 3.0),
    ],
    ids=["drop-0.5", "drop-0.98", "slope", "slide", "side-hit"],
)
def test_energy_never_increases_across_a_settle(make, duration):
    """Kinetic plus potential energy never rises, sampled after every collision and 200 times,
    and ends no higher than at the start, with the bodies in contact. Impacts and steps never add
    energy; between samples it may rise only by a step's integration error where a body turns
    in contact (a box landing with friction), which docs/contact.md ("Energy") bounds by 2e-7 of
    the scene's energy (measured: 4e-11 here)."""
    world = make()
    start = energy(world)
    scale = max(1.0, abs(start))
    samples = []
    world.on_collision(lambda event: samples.append(energy(world)))
    steps = 200
    for k in range(1, steps + 1):
        world.run_until(duration * k / steps)
        samples.append(energy(world))
    end = energy(world)
    assert end <= start
    previous = start
    for value in samples + [end]:
        assert value <= previous + 2e-7 * scale
        previous = value
    assert any(b.resting_on is not None for b in world.bodies if not b.is_fixed)


# ------------------------------------------------------------------ wedged between two sliding faces


def test_circle_wedged_between_two_sliding_faces_makes_no_storm():
    """A circle that drops, spinning, into the V between two polygons sliding apart (which made
    the former resting-contact rules swap supports at one instant until the event-storm error) joins
    one island with them: bounded work (under 1000 events in 1 s) and overlap at most the step's
    first-order error, 1e-5 of the pair's radii (docs/contact.md, "Overlap inside islands")."""
    world = islands_world(gravity=(0.0, -G))
    world.add_box(-0.5, -0.1, 2.0, 0.1, fixed=True, elasticity=0.5)
    left = world.add_polygon(V_LEFT, mass=1.86, elasticity=0.88, velocity=(0.0757, 0.0))
    right = world.add_polygon(V_RIGHT, mass=1.79, elasticity=0.83, velocity=(0.0806, 0.0))
    ball = world.add_circle((0.6574, 0.0629), 0.0623, mass=0.94, elasticity=0.26, velocity=(0.0783, -0.0119),
                            angular_velocity=11.7)
    for k in range(1, 101):
        world.run_until(0.01 * k)
        for body, other, depth in world.overlaps():
            assert depth <= 1e-5 * (body.bounding_radius + other.bounding_radius), (body, other, depth)
    assert world.stats["events"] < 1000
    assert world.stats["joins"] >= 1
    assert ball.position[1] > 0.0 and left.resting_on is not None and right.resting_on is not None
