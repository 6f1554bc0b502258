"""Resting and sliding contact (issue 5, item 4): how bouncing ends, and what a resting body does.

Scenes are hand-built with closed-form answers. Flat scenes use dyadic sizes (0.0625, 0.125, ...)
so that "touching" is exact in binary floating point; the floor's top face is y = 0.

A body that starts touching a tilted surface cannot be placed exactly on it (its corners are
rounded), and a gap of 1e-16 is honoured by the engine as a free fall of a few nanoseconds (which
shifts a friction slide by ~1e-8). Such bodies are therefore pressed into the surface by 1e-12
(far inside the 1e-9 start-up overlap tolerance): touching and pressed together, they rest from
the very first event, as the brief demands.

Bounce count under ``rest_height`` (h): a ball dropped from gap h0 with restitution e reaches
height e^(2k) h0 after its k-th bounce; the bounce that would rise less than h times the body's
bounding radius R ends in rest, so there are n = ceil(ln(h0 / (h R)) / (2 ln(1/e))) collisions,
the last of which is the settle, at t_n = t0 + (2 v0 / g) (e + e^2 + ... + e^(n-1)).
"""

from __future__ import annotations

import itertools
import math

import pytest

from pge import World

G = 9.81
EXACT = 1e-12
CLOSE = 1e-9


# ------------------------------------------------------------------ helpers


def floor_world(elasticity=0.5, floor_friction=0.0, **options) -> tuple[World, object]:
    """A World under gravity (0, -G) with a wide fixed floor whose top face is y = 0."""
    options.setdefault("bounds", (-1.0, -1.0, 3.0, 3.0))
    world = World(gravity=(0.0, -G), elasticity=elasticity, **options)
    floor = world.add_box(-1.0, -0.25, 6.0, 0.25, fixed=True, friction=floor_friction, name="floor")
    return world, floor


def energy(world: World) -> float:
    """Kinetic (translation plus rotation) plus gravitational potential energy (g = G downwards, zero at
    y = 0) of the moving bodies."""
    total = 0.0
    for body in world.bodies:
        if not body.is_fixed:
            vx, vy = body.velocity
            w = body.angular_velocity
            total += body.mass * (0.5 * (vx * vx + vy * vy) + G * body.position[1]) + 0.5 * body.inertia * w * w
    return total


def expected_bounces(h0: float, e: float, rest_height: float, reach: float) -> int:
    """Collisions until rest: the first k with e^(2k) h0 <= rest_height * reach."""
    ratio = math.log(h0 / (rest_height * reach)) / (2.0 * math.log(1.0 / e))
    assert abs(ratio - round(ratio)) > 0.01, "scene too close to the rest threshold to count exactly"
    return math.ceil(ratio)


def settle_time(h0: float, e: float, n: int) -> float:
    """Time of the n-th collision of a body dropped from rest with a gap h0 (restitution e)."""
    v0 = math.sqrt(2.0 * G * h0)
    return math.sqrt(2.0 * h0 / G) + 2.0 * v0 / G * sum(e**k for k in range(1, n))


def collision_times(world: World, body=None) -> list[float]:
    """A list that fills with the times of the collisions (of ``body``, or all)."""
    seen: list[float] = []
    world.on_collision(lambda event: seen.append(event.time), body)
    return seen


def slope_scene(angle_deg: float, shape: str, mu: float, velocity: float = 0.0, on_ramp: bool = False, contact="rules"):
    """A fixed ramp rising to the right at ``angle_deg`` and a body touching it (pressed in by
    1e-12) at rest, or moving up the slope at ``velocity``; friction ``mu`` on the body, or on
    the ramp (``on_ramp``); contact model ``contact``. Returns (world, body, ramp, unit tangent
    up the slope)."""
    a = math.radians(angle_deg)
    world = World(gravity=(0.0, -G), elasticity=0.5, bounds=(-1.0, -1.0, 5.0, 5.0), contact=contact)
    length = 4.0
    ramp = world.add_polygon(
        [(0.0, 0.0), (length * math.cos(a), 0.0), (length * math.cos(a), length * math.sin(a))],
        fixed=True,
        friction=mu if on_ramp else 0.0,
        name="ramp",
    )
    tx, ty = math.cos(a), math.sin(a)
    nx, ny = -ty, tx
    s0 = 0.5 * length  # where the body sits along the slope
    press = 1e-12
    options = {"mass": 1.0, "friction": 0.0 if on_ramp else mu, "velocity": (velocity * tx, velocity * ty), "name": "body"}
    if shape == "circle":
        r = 0.0625
        body = world.add_circle((s0 * tx + (r - press) * nx, s0 * ty + (r - press) * ny), r, **options)
    else:
        side = 0.125
        x0, y0 = s0 * tx - press * nx, s0 * ty - press * ny
        corners = [(0.0, 0.0), (side, 0.0), (side, side), (0.0, side)]
        body = world.add_polygon([(x0 + u * tx + w * nx, y0 + u * ty + w * ny) for u, w in corners], **options)
    return world, body, ramp, (tx, ty)


def along(p, q, direction) -> float:
    return (q[0] - p[0]) * direction[0] + (q[1] - p[1]) * direction[1]


# ------------------------------------------------------------------ a dropped body settles


@pytest.mark.parametrize("shape", ["circle", "box"])
@pytest.mark.parametrize("rest_height", [1e-4, 1e-2, 1e-7])
def test_half_elastic_drop_settles_after_the_bounces_rest_height_allows(shape, rest_height):
    """A body (e = 0.5 on a 0.5 floor) bounces exactly n(rest_height) < 60 times, settles at t_n, then is silent."""
    world, floor = floor_world(elasticity=0.5, rest_height=rest_height)
    if shape == "circle":
        body = world.add_circle((0.5, 0.5), 0.0625, mass=1.0, name="ball")
        half = 0.0625
    else:
        body = world.add_box(0.4375, 0.4375, 0.125, 0.125, mass=1.0, name="box")
        half = 0.0625
    h0 = 0.5 - half
    n = expected_bounces(h0, 0.5, rest_height, body.bounding_radius)
    assert n < 60
    times = collision_times(world, body)
    world.run_until(2.0)
    assert len(times) == n
    assert world.stats["rests"] == 1
    assert abs(times[-1] - settle_time(h0, 0.5, n)) <= CLOSE
    assert body.resting_on is floor
    assert body.velocity == (0.0, 0.0)
    x, y = body.position
    assert abs(y - half) <= EXACT and x == 0.5
    events = world.stats["events"]
    world.run_until(200.0)
    assert world.stats["events"] == events
    assert body.position == (x, y) and body.velocity == (0.0, 0.0) and body.resting_on is floor


def test_default_elasticity_drop_settles_after_a_few_hundred_bounces_in_finite_time():
    """With the default elasticity 0.98 a dropped ball bounces n (a few hundred) times, settles near 28 s and stays silent."""
    world = World(gravity=(0.0, -G), bounds=(-1.0, -1.0, 3.0, 3.0))
    floor = world.add_box(-1.0, -0.25, 6.0, 0.25, fixed=True, name="floor")
    ball = world.add_circle((0.5, 0.5), 0.0625, mass=1.0, name="ball")
    assert ball.elasticity == 0.98 and floor.elasticity == 0.98
    h0 = 0.5 - 0.0625
    n = expected_bounces(h0, 0.98, 1e-4, 0.0625)
    assert 200 <= n <= 400
    t_n = settle_time(h0, 0.98, n)
    times = collision_times(world)
    world.run_until(t_n + 1.0)
    assert len(times) == n
    assert abs(times[-1] - t_n) <= CLOSE * t_n
    assert ball.resting_on is floor and ball.velocity == (0.0, 0.0)
    assert abs(ball.position[1] - 0.0625) <= EXACT
    events = world.stats["events"]
    world.run_until(t_n + 200.0)
    assert world.stats["events"] == events
    assert ball.resting_on is floor and abs(ball.position[1] - 0.0625) <= EXACT


# ------------------------------------------------------------------ stacks


def _settled(bodies) -> bool:
    return all(b.resting_on is not None and b.velocity == (0.0, 0.0) for b in bodies)


@pytest.mark.parametrize("elasticity", [0.5, 0.98, 0.0])
@pytest.mark.parametrize(
    "widths, gap",
    [((0.1, 0.1, 0.1), 0.01), ((0.25, 0.1875, 0.125), 0.015625), ((0.125, 0.125, 0.125), 0.003)],
)
def test_stack_of_three_boxes_settles_and_stays_stacked(elasticity, widths, gap):
    """Three boxes dropped with small gaps settle into an exact stack that stays put for 10 s (at most 5 more events)."""
    world, floor = floor_world(elasticity=elasticity)
    boxes = []
    y = gap
    for k, w in enumerate(widths):
        boxes.append(world.add_box(0.5 - w / 2, y, w, 0.1, mass=1.0 + k, name=f"b{k}"))
        y += 0.1 + gap
    t = 0.0
    while not _settled(boxes):
        t += 0.05
        assert t < 10.0, "the stack never settled"
        world.run_until(t)
    assert [b.resting_on for b in boxes] == [floor, boxes[0], boxes[1]]
    settled_positions = [b.position for b in boxes]
    events = world.stats["events"]
    world.run_until(t + 10.0)
    assert world.stats["events"] - events <= 5
    assert [b.resting_on for b in boxes] == [floor, boxes[0], boxes[1]]
    assert all(b.velocity == (0.0, 0.0) for b in boxes)
    for before, body in zip(settled_positions, boxes):
        assert abs(body.position[0] - before[0]) <= EXACT and abs(body.position[1] - before[1]) <= EXACT
    assert abs(boxes[0].bounding_box[1] - 0.0) <= EXACT
    for lower, upper in itertools.pairwise(boxes):
        assert abs(upper.bounding_box[1] - lower.bounding_box[3]) <= EXACT
    for body in boxes:
        assert abs(body.position[0] - 0.5) <= EXACT  # no sideways drift
    assert world.overlaps(EXACT) == []


def test_box_dropped_on_a_box_sliding_on_ice_is_dragged_along_keeping_momentum():
    """A box (m 1, friction 0.5) dropped with no horizontal speed onto a box (m 1) sliding at 2 m/s
    on a frictionless floor: only friction between the two acts horizontally, so their horizontal
    momentum stays 2 kg m/s and their energy never rises, sampled every 0.01 s while the top box
    rides, until it slides off the back or both move together."""
    world, floor = floor_world(elasticity=0.0, bounds=(-1.0, -1.0, 5.0, 3.0))
    low = world.add_box(0.0, 1e-4, 0.4, 0.1, mass=1.0, elasticity=0.0, friction=0.0, name="low")
    world.run_until(0.05)
    low.velocity = (2.0, 0.0)
    top = world.add_box(0.1, 0.1 + 1e-3, 0.1, 0.1, mass=1.0, elasticity=0.0, friction=0.5, name="top")
    before = energy(world)
    rode = False
    for k in range(1, 31):
        world.run_until(0.05 + 0.01 * k)
        rode = rode or top.resting_on is low
        assert low.velocity[0] + top.velocity[0] == pytest.approx(2.0, abs=1e-9)
        now = energy(world)
        assert now <= before + EXACT
        before = now
    assert rode


# ------------------------------------------------------------------ slopes


@pytest.mark.parametrize("shape, fraction", [("box", 0.0), ("box", 0.5), ("box", 0.95), ("circle", 0.0)])
@pytest.mark.parametrize("angle", [10.0, 30.0, 50.0])
@pytest.mark.parametrize("on_ramp", [False, True])
def test_body_on_a_slope_slides_with_acceleration_g_sin_minus_mu_cos(shape, angle, fraction, on_ramp):
    """tan(a) > mu: a body at rest on the slope slides down s = g (sin a - mu cos a) t^2 / 2, staying on the surface
    (a circle with friction rolls instead: tests/test_rolling.py)."""
    a = math.radians(angle)
    mu = fraction * math.tan(a)
    world, body, ramp, tangent = slope_scene(angle, shape, mu, on_ramp=on_ramp)
    start = body.position
    normal = (-tangent[1], tangent[0])
    t = 0.5
    world.run_until(t)
    assert body.resting_on is ramp
    assert world.stats["rests"] == 1
    expected = 0.5 * G * (math.sin(a) - mu * math.cos(a)) * t * t
    assert abs(-along(start, body.position, tangent) - expected) <= CLOSE
    assert abs(along(start, body.position, normal)) <= EXACT
    speed = G * (math.sin(a) - mu * math.cos(a)) * t
    assert abs(-along((0.0, 0.0), body.velocity, tangent) - speed) <= CLOSE
    assert abs(along((0.0, 0.0), body.velocity, normal)) <= EXACT
    assert world.overlaps(1e-11) == []


@pytest.mark.parametrize("shape", ["box"])
@pytest.mark.parametrize("angle", [10.0, 30.0, 50.0])
@pytest.mark.parametrize("fraction", [1.05, 2.0])
def test_body_on_a_slope_stays_put_when_mu_exceeds_tan(shape, angle, fraction):
    """tan(a) < mu: a box at rest on the slope stays exactly where it is, silently, for 10 s (a circle
    rolls down: tests/test_rolling.py)."""
    mu = fraction * math.tan(math.radians(angle))
    world, body, ramp, _ = slope_scene(angle, shape, mu)
    start = body.position
    world.run_until(0.5)
    events = world.stats["events"]
    assert events <= 2
    world.run_until(10.0)
    assert world.stats["events"] == events
    assert body.resting_on is ramp
    assert body.velocity == (0.0, 0.0)
    assert abs(body.position[0] - start[0]) <= EXACT and abs(body.position[1] - start[1]) <= EXACT


@pytest.mark.parametrize("angle, mu", [(30.0, 0.3), (20.0, 0.1), (30.0, 0.8)])
def test_box_pushed_up_a_slope_stops_then_slides_back_or_stays(angle, mu):
    """Pushed up at v, a box decelerates at g (sin + mu cos), stops at v^2 / (2 a_up), then slides back (tan > mu) or stays."""
    a = math.radians(angle)
    v = 1.0
    world, body, ramp, tangent = slope_scene(angle, "box", mu, velocity=v)
    start = body.position
    up = G * (math.sin(a) + mu * math.cos(a))
    down = max(0.0, G * (math.sin(a) - mu * math.cos(a)))
    t_stop = v / up
    world.run_until(0.5 * t_stop)
    assert abs(along(start, body.position, tangent) - (v * 0.5 * t_stop - 0.125 * up * t_stop**2)) <= CLOSE
    world.run_until(t_stop + 0.3)
    assert world.stats["contact_changes"] >= 1  # the STOP_SLIDING
    assert body.resting_on is ramp
    expected = v * v / (2.0 * up) - 0.5 * down * 0.3**2
    assert abs(along(start, body.position, tangent) - expected) <= CLOSE
    assert abs(along((0.0, 0.0), body.velocity, tangent) + down * 0.3) <= CLOSE
    if down == 0.0:
        assert body.velocity == (0.0, 0.0)


# ------------------------------------------------------------------ sliding on the flat


@pytest.mark.parametrize("v, mu", [(1.0, 0.5), (2.0, 0.25), (0.75, 1.0)])
@pytest.mark.parametrize("shape", ["box"])
def test_sliding_body_stops_at_v_squared_over_2_mu_g(v, mu, shape):
    """A box sliding on the floor with friction mu decelerates at mu g and stops at v^2 / (2 mu g) (a STOP_SLIDING),
    then stays (a circle rolls on: tests/test_rolling.py)."""
    world, floor = floor_world()
    if shape == "box":
        body = world.add_box(0.0, 0.0, 0.125, 0.125, mass=2.0, velocity=(v, 0.0), friction=mu)
    else:
        body = world.add_circle((0.0625, 0.0625), 0.0625, mass=2.0, velocity=(v, 0.0), friction=mu)
    x0, y0 = body.position
    t_stop = v / (mu * G)
    world.run_until(0.5 * t_stop)
    assert body.resting_on is floor
    assert abs(body.velocity[0] - 0.5 * v) <= CLOSE and body.velocity[1] == 0.0
    assert abs(body.position[0] - x0 - (0.5 * v * t_stop - 0.125 * mu * G * t_stop**2)) <= CLOSE
    assert world.stats["contact_changes"] == 0
    world.run_until(1.5 * t_stop)
    assert world.stats["contact_changes"] == 1
    assert abs(body.position[0] - x0 - v * v / (2.0 * mu * G)) <= CLOSE
    assert body.position[1] == y0
    assert body.velocity == (0.0, 0.0)
    events = world.stats["events"]
    stopped = body.position
    world.run_until(100.0)
    assert world.stats["events"] == events
    assert body.position == stopped and body.resting_on is floor


# ------------------------------------------------------------------ leaving an edge


@pytest.mark.parametrize("x0, v, end", [(0.125, 1.0, 0.5), (0.13, 0.9, 0.53), (0.2, 1.3, 0.61)])
def test_frictionless_ball_leaves_the_shelf_end_and_falls_at_once(x0, v, end):
    """A ball sliding along a shelf is free from the moment its centre passes the end: it falls and lands at the free-fall time."""
    world, floor = floor_world(floor_friction=0.5)
    r, top = 0.0625, 0.625
    shelf = world.add_box(0.0, top - 0.125, end, 0.125, fixed=True, name="shelf")
    ball = world.add_circle((x0, top + r), r, mass=1.0, velocity=(v, 0.0), name="ball")
    assert v * v > G * r  # fast enough to clear the corner
    t_leave = (end - x0) / v
    landings = []
    world.on_collision(lambda event: landings.append(event.time), floor)
    world.run_until(0.5 * t_leave)
    assert ball.resting_on is shelf
    dt = 0.1
    world.run_until(t_leave + dt)
    assert ball.resting_on is None
    assert abs(ball.position[1] - (top + r - 0.5 * G * dt * dt)) <= CLOSE
    assert abs(ball.position[0] - (end + v * dt)) <= CLOSE
    world.run_until(t_leave + 1.0)
    assert landings, "the ball never reached the floor"
    assert abs(landings[0] - (t_leave + math.sqrt(2.0 * top / G))) <= CLOSE


def test_ball_slid_off_a_shelf_ends_below_it_rolling_on_the_floor():
    """A ball that slid off a frictionless shelf lands below it, skids on the floor (friction 0.5) until
    its spin matches its speed (at once, if the landing's friction can), and then rolls on without events."""
    world, floor = floor_world(floor_friction=0.5)
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
    assert vx > 0.0 and vy == 0.0
    assert abs(vx + ball.angular_velocity * r) <= CLOSE  # rolling
    assert world.stats["contact_changes"] >= 1  # left the shelf's edge (the landing's friction may stop the slip at once)
    events = world.stats["events"]
    world.run_until(2.5)
    assert world.stats["events"] == events
    assert ball.velocity == (vx, 0.0)


def test_box_slides_off_the_shelf_end_and_falls():
    """A box sliding off a shelf falls once its whole base has passed the end and lands at the free-fall time."""
    world, floor = floor_world(floor_friction=0.5)
    top, side, v = 0.625, 0.125, 1.0
    shelf = world.add_box(0.0, top - 0.125, 0.5, 0.125, fixed=True, name="shelf")
    box = world.add_box(0.125, top, side, side, mass=1.0, velocity=(v, 0.0), name="box")
    t_leave = (0.5 - 0.125) / v
    landings = collision_times(world, floor)
    world.run_until(t_leave - 1e-6)
    assert box.resting_on is shelf
    world.run_until(t_leave + 0.1)
    assert box.resting_on is None
    assert abs(box.position[1] - (top + side / 2 - 0.5 * G * 0.01)) <= CLOSE
    world.run_until(10.0)
    assert abs(landings[0] - (t_leave + math.sqrt(2.0 * top / G))) <= CLOSE
    assert box.resting_on is floor and box.velocity == (0.0, 0.0)
    assert abs(box.bounding_box[1]) <= EXACT


# ------------------------------------------------------------------ releases


def _side_hit_scene():
    """A big resting ball (r 0.125, 2 kg) about to be hit low on its side by a small ball (r 0.0625, 1 kg) sliding at 2."""
    world, floor = floor_world(elasticity=0.5)
    big = world.add_circle((1.0, 0.125), 0.125, mass=2.0, name="big")
    small = world.add_circle((0.25, 0.0625), 0.0625, mass=1.0, velocity=(2.0, 0.0), name="small")
    dy, d = 0.0625, 0.1875
    dx = math.sqrt(d * d - dy * dy)
    return world, floor, big, small, (dx / d, dy / d), (1.0 - dx - 0.25) / 2.0


def test_resting_ball_hit_low_from_the_side_is_released_and_flies():
    """A ball hit below its centre is lifted off the floor with the impulse the rest-aware equations give, flies and lands."""
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
    # the big ball takes the impulse with its whole mass; the small one stays pressed into the
    # floor, so only its tangential (horizontal) part of the impulse moves it
    j = (1.0 + 0.5) * 2.0 * nx / (1.0 / 2.0 + (1.0 - ny * ny))
    assert big_support is None
    assert abs(big_v[0] - j * nx / 2.0) <= EXACT and abs(big_v[1] - j * ny / 2.0) <= EXACT
    assert small_support is floor
    assert abs(small_v[0] - (2.0 - j * nx)) <= EXACT and small_v[1] == 0.0
    vy = j * ny / 2.0
    world.run_until(t_hit + vy / G)
    assert big.resting_on is None
    assert abs(big.position[1] - (0.125 + vy * vy / (2.0 * G))) <= CLOSE
    world.run_until(t_hit + 1.0)  # landed and sliding, still well before the floor's end at x = 5
    assert big.resting_on is floor and abs(big.position[1] - 0.125) <= EXACT


def test_a_collision_that_lifts_a_body_off_its_support_counts_as_a_release():
    """stats['releases'] counts bodies lifted off a support, also when a collision knocks them off."""
    world, _, big, _, _, t_hit = _side_hit_scene()
    world.run_until(0.5 * t_hit)
    assert world.stats["releases"] == 0
    world.run_until(t_hit + 1e-9)
    assert big.resting_on is None
    assert world.stats["releases"] == 1


def test_horizontal_hit_keeps_both_balls_resting():
    """Equal balls on the floor hit head-on (e = 1) swap velocities and both keep resting at exactly r."""
    world, floor = floor_world(elasticity=1.0)
    a = world.add_circle((1.0, 0.0625), 0.0625, mass=1.0, name="a")
    b = world.add_circle((0.25, 0.0625), 0.0625, mass=1.0, velocity=(2.0, 0.0), name="b")
    seen = []
    world.on_collision(lambda event: seen.append((a.resting_on, b.resting_on, a.velocity, b.velocity)), a)
    world.run_until(0.5)
    assert len(seen) == 1
    assert seen[0] == (floor, floor, (2.0, 0.0), (0.0, 0.0))
    assert a.resting_on is floor and b.resting_on is floor
    assert a.position == (1.0 + 2.0 * (0.5 - 0.3125), 0.0625)
    assert world.stats["releases"] == 0


def test_set_velocity_upwards_releases_a_resting_ball_and_it_flies():
    """An upward velocity lifts a resting ball off (resting_on None): it rises v^2 / 2g and is back 2 v / g later."""
    world, floor = floor_world(elasticity=0.5)
    ball = world.add_circle((0.5, 0.0625), 0.0625, mass=1.0, name="ball")
    world.run_until(1.0)
    assert ball.resting_on is floor
    releases = world.stats["releases"]
    v = 2.0
    world.set_velocity(ball, (0.0, v))
    assert ball.resting_on is None
    assert world.stats["releases"] == releases + 1
    landings = collision_times(world, ball)
    world.run_until(1.0 + v / G)
    assert ball.resting_on is None
    assert abs(ball.position[1] - (0.0625 + v * v / (2.0 * G))) <= CLOSE
    world.run_until(5.0)
    assert abs(landings[0] - (1.0 + 2.0 * v / G)) <= CLOSE
    assert ball.resting_on is floor and ball.velocity == (0.0, 0.0)
    assert abs(ball.position[1] - 0.0625) <= EXACT


def test_zero_gravity_leaves_nothing_resting():
    """After set_gravity((0, 0)) no body rests, none comes to rest again, and a slider keeps its velocity (no friction without pressure)."""
    world, floor = floor_world(elasticity=0.5)
    slider = world.add_box(0.0, 0.0, 0.125, 0.125, mass=1.0, velocity=(1.0, 0.0), friction=0.5, name="slider")
    lower = world.add_box(1.5, 0.0, 0.125, 0.125, mass=1.0, name="lower")
    upper = world.add_box(1.5, 0.125, 0.125, 0.125, mass=1.0, name="upper")
    bodies = (slider, lower, upper)
    world.run_until(0.1)
    assert [b.resting_on for b in bodies] == [floor, floor, lower]
    speed = slider.velocity[0]
    assert abs(speed - (1.0 - 0.5 * G * 0.1)) <= CLOSE
    releases = world.stats["releases"]
    world.set_gravity((0.0, 0.0))
    assert [b.resting_on for b in bodies] == [None, None, None]
    assert world.stats["releases"] == releases + 3
    x = slider.position[0]
    world.run_until(0.2)
    assert [b.resting_on for b in bodies] == [None, None, None]
    assert slider.velocity == (speed, 0.0)
    assert abs(slider.position[0] - (x + 0.1 * speed)) <= EXACT
    assert lower.position == (1.5625, 0.0625) and upper.position == (1.5625, 0.1875)
    assert lower.velocity == (0.0, 0.0) and upper.velocity == (0.0, 0.0)


@pytest.mark.parametrize("support_fixed", [False, True])
def test_rider_falls_onto_the_floor_when_its_support_is_removed(support_fixed):
    """Removing the body a ball rests on releases the ball: it falls freely and comes to rest on the floor."""
    world, floor = floor_world(elasticity=0.5)
    if support_fixed:
        height = 0.5
        support = world.add_box(0.5, height - 0.125, 0.25, 0.125, fixed=True, name="shelf")
    else:
        height = 0.25
        support = world.add_box(0.5, 0.0, 0.25, height, mass=1.0, name="block")
    ball = world.add_circle((0.625, height + 0.0625), 0.0625, mass=1.0, name="ball")
    world.run_until(1.0)
    assert ball.resting_on is support
    world.remove(support)
    assert ball.resting_on is None
    landings = collision_times(world, ball)
    world.run_until(1.0 + 0.5 * math.sqrt(2.0 * height / G))
    assert ball.resting_on is None
    assert abs(ball.position[1] - (height + 0.0625 - 0.5 * G * 0.25 * 2.0 * height / G)) <= CLOSE
    world.run_until(5.0)
    assert abs(landings[0] - (1.0 + math.sqrt(2.0 * height / G))) <= CLOSE
    assert ball.resting_on is floor and ball.velocity == (0.0, 0.0)
    assert abs(ball.position[1] - 0.0625) <= EXACT and ball.position[0] == 0.625


def test_top_of_a_stack_falls_onto_the_bottom_when_the_middle_is_removed():
    """Removing the middle box of a stack lets the top one fall onto the bottom one and rest there."""
    world, floor = floor_world(elasticity=0.5)
    boxes = [world.add_box(0.5, 0.125 * k, 0.125, 0.125, mass=1.0, name=f"b{k}") for k in range(3)]
    world.run_until(1.0)
    assert [b.resting_on for b in boxes] == [floor, boxes[0], boxes[1]]
    world.remove(boxes[1])
    assert boxes[2].resting_on is None and boxes[0].resting_on is floor
    landings = collision_times(world, boxes[2])
    world.run_until(5.0)
    assert abs(landings[0] - (1.0 + math.sqrt(2.0 * 0.125 / G))) <= CLOSE
    assert boxes[2].resting_on is boxes[0]
    assert abs(boxes[2].bounding_box[1] - boxes[0].bounding_box[3]) <= EXACT
    assert world.overlaps(EXACT) == []


# ------------------------------------------------------------------ energy


def _scene_drop(e):
    world, _ = floor_world(elasticity=e)
    world.add_circle((0.5, 0.5), 0.0625, mass=1.0)
    return world


def _scene_stack():
    world, _ = floor_world(elasticity=0.98)
    for k in range(3):
        world.add_box(0.45, 0.01 + 0.11 * k, 0.1, 0.1, mass=1.0 + k)
    return world


def _scene_slope():
    world, _, _, _ = slope_scene(30.0, "box", 0.3)
    return world


def _scene_slide():
    world, _ = floor_world()
    world.add_box(0.0, 0.25, 0.125, 0.125, mass=2.0, velocity=(1.5, 0.5), friction=0.4)
    return world


def _scene_side_hit():
    return _side_hit_scene()[0]


@pytest.mark.parametrize(
    "make, duration",
    [
        (lambda: _scene_drop(0.5), 3.0),
        (lambda: _scene_drop(0.98), 32.0),
        (_scene_stack, 5.0),
        (_scene_slope, 0.8),
        (_scene_slide, 3.0),
        (_scene_side_hit, 3.0),
    ],
    ids=["drop-0.5", "drop-0.98", "stack", "slope", "slide", "side-hit"],
)
def test_energy_never_increases_across_a_settle(make, duration):
    """Kinetic plus potential energy never rises (sampled after every collision and 200 times), and ends no higher than at the start."""
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
        assert value <= previous + 1e-12 * scale
        previous = value
    assert any(b.resting_on is not None for b in world.bodies if not b.is_fixed)


# ------------------------------------------------------------------ wedged between two sliding faces

#: two polygons sliding apart on a frictionless floor (seed 3 of the random rotating scenes, inelastic,
#: under gravity, at t = 2.0967) and a spinning circle dropping into the V between their tilted faces.
V_LEFT = [(0.559764773, 0.085430261), (0.525891043, 0.065559464), (0.54310438, 0.0), (0.58344796, 0.0),
          (0.603155705, 0.030400699), (0.590825229, 0.060750892)]
V_RIGHT = [(0.804262837, 0.018326242), (0.80510206, 0.065118083), (0.761276702, 0.07856254),
           (0.722125242, 0.065230135), (0.714674307, 0.034034038), (0.736623803, 0.0), (0.775273696, 0.0)]


def test_circle_wedged_between_two_sliding_faces_does_not_swap_supports_for_ever():
    """Resting on either face presses the circle into the other, and a side hit releases a rider of a
    face that moves along its normal: it swapped supports at one instant until the event-storm error
    (a million collisions at t = 0.0098). A rider wedged against a body that cannot give way (or on
    such a loose support, against any body) does not rest; it bounces under the pivot rule."""
    world = World(gravity=(0.0, -G))
    world.add_box(-0.5, -0.1, 2.0, 0.1, fixed=True, elasticity=0.5)
    left = world.add_polygon(V_LEFT, mass=1.86, elasticity=0.88, velocity=(0.0757, 0.0))
    right = world.add_polygon(V_RIGHT, mass=1.79, elasticity=0.83, velocity=(0.0806, 0.0))
    ball = world.add_circle((0.6574, 0.0629), 0.0623, mass=0.94, elasticity=0.26, velocity=(0.0783, -0.0119),
                            angular_velocity=11.7)
    for k in range(1, 101):
        world.run_until(0.01 * k)
        for body, other, depth in world.overlaps():
            assert depth <= CLOSE * (body.bounding_radius + other.bounding_radius), (body, other, depth)
    assert world.stats["events"] < 1000
    assert ball.position[1] > 0.0 and left.resting_on is not None and right.resting_on is not None
