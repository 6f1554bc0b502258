"""Rolling: a circle resting on a face with friction rolls or skids (pge.core.contact, pge.core.pile).

Friction acts at the contact point, whose slip along the tangent is ``v_t - omega R``; its force
``f`` pushes the centre and turns the circle (torque ``-R f``). While it skids, kinetic friction
``mu N`` acts against the slip; once the slip is zero the circle rolls, and static friction gives
whatever keeps it zero, if it can. For a uniform disc (``I = m R^2 / 2``) every answer below is
derived by hand from those two equations:

- thrown along the floor at ``v0`` with spin ``w0``, it skids for ``|v0 + w0 R| / (3 mu g)`` and
  then rolls for ever at ``(2 / 3) (v0 - w0 R / 2)`` (the angular momentum about the contact point
  is kept), having lost a third of the kinetic energy of the slip;
- on a slope at angle ``a`` it rolls down at ``(2 / 3) g sin a`` when ``tan a <= 3 mu``, and skids
  at ``g (sin a - mu cos a)`` with its spin growing at ``2 mu g cos a / R`` when steeper;
- on a box pushed along ice by ``M a0`` the box accelerates at ``A = M a0 / (M + m / 3)`` and the
  rolling ball at ``A / 3``.

Scenes use dyadic sizes so that touching is exact; the floor's top face is y = 0.
"""

from __future__ import annotations

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from pge import World
from pge.events import Collision
from test_piles import mechanical_energy  # kinetic (with rotation) plus potential energy

G = 9.81
CLOSE = 1e-9
RADIUS = 0.0625


def floor_world(floor_friction=0.0):
    """A World under gravity (0, -G), elasticity 0.5, with a wide fixed floor whose top face is y = 0."""
    world = World(gravity=(0.0, -G), elasticity=0.5, bounds=(-4.0, -1.0, 8.0, 3.0))
    floor = world.add_box(-4.0, -0.25, 12.0, 0.25, fixed=True, friction=floor_friction, name="floor")
    return world, floor


# ------------------------------------------------------------------ on the floor


@pytest.mark.parametrize("v0, mu", [(1.0, 0.5), (2.0, 0.25), (0.75, 1.0)])
def test_ball_thrown_along_the_floor_skids_then_rolls_on_at_two_thirds_of_its_speed(v0, mu):
    """Skidding, the ball slows at mu g while its spin grows at 2 mu g / R; at t1 = v0 / (3 mu g) it
    rolls, at 2 v0 / 3 and spin -2 v0 / (3 R), for ever and without another event."""
    world, floor = floor_world()
    ball = world.add_circle((0.0, RADIUS), RADIUS, mass=2.0, velocity=(v0, 0.0), friction=mu)
    t1 = v0 / (3.0 * mu * G)
    world.run_until(0.5 * t1)
    assert ball.resting_on is floor
    assert ball.velocity[0] == pytest.approx(v0 - mu * G * 0.5 * t1, abs=CLOSE)
    assert ball.angular_velocity == pytest.approx(-2.0 * mu * G / RADIUS * 0.5 * t1, abs=CLOSE)
    assert world.stats["contact_changes"] == 0
    world.run_until(t1 + 0.25)
    assert world.stats["contact_changes"] == 1  # the slip stopped
    assert ball.velocity == pytest.approx((2.0 * v0 / 3.0, 0.0), abs=CLOSE)
    assert ball.angular_velocity == pytest.approx(-2.0 * v0 / (3.0 * RADIUS), abs=CLOSE / RADIUS)
    skid = v0 * t1 - 0.5 * mu * G * t1 * t1
    assert ball.position[0] == pytest.approx(skid + 2.0 * v0 / 3.0 * 0.25, abs=CLOSE)
    assert ball.position[1] == RADIUS
    lost = 0.5 * 2.0 * v0 * v0 - mechanical_energy(world) + 2.0 * G * RADIUS
    assert lost == pytest.approx(2.0 * v0 * v0 / 6.0, rel=1e-9)
    events = world.stats["events"]
    world.run_until(world.time + 1.0)
    assert world.stats["events"] == events


@settings(max_examples=60, deadline=None)
@given(
    v0=st.floats(-2.0, 2.0),
    w0=st.floats(-40.0, 40.0),
    mu=st.floats(0.2, 1.5),
)
def test_any_throw_ends_rolling_with_the_angular_momentum_about_the_contact_point(v0, w0, mu):
    """Whatever the throw (backspin brings the ball back, topspin speeds it up), it rolls at last
    at (2/3)(v0 - w0 R / 2), never gaining energy on the way."""
    world, _ = floor_world()
    ball = world.add_circle((2.0, RADIUS), RADIUS, mass=1.0, velocity=(v0, 0.0), angular_velocity=w0, friction=mu)
    t1 = abs(v0 + w0 * RADIUS) / (3.0 * mu * G)
    before = mechanical_energy(world)
    for k in range(1, 11):
        world.run_until(1.2 * t1 * k / 10.0 + 1e-6)
        now = mechanical_energy(world)
        assert now <= before + 1e-12 * max(1.0, before)
        before = now
    final = 2.0 / 3.0 * (v0 - w0 * RADIUS / 2.0)
    assert ball.velocity[0] == pytest.approx(final, abs=1e-9 * (1.0 + abs(v0) + abs(w0) * RADIUS))
    assert ball.velocity[0] + ball.angular_velocity * RADIUS == pytest.approx(0.0, abs=1e-9 * (1.0 + abs(v0)))


def test_a_ball_at_rest_on_the_floor_with_friction_makes_no_events():
    """Still, rolling nowhere: no slip, no force, no event."""
    world, floor = floor_world()
    ball = world.add_circle((0.5, RADIUS), RADIUS, mass=1.0, friction=0.5)
    world.run_until(0.1)
    events = world.stats["events"]
    world.run_until(10.0)
    assert world.stats["events"] == events
    assert ball.velocity == (0.0, 0.0) and ball.angular_velocity == 0.0 and ball.resting_on is floor


def test_without_friction_the_spin_plays_no_part():
    """mu = 0: the ball slides on at its speed and keeps its spin, as in PGE."""
    world, _ = floor_world()
    ball = world.add_circle((0.0, RADIUS), RADIUS, mass=1.0, velocity=(1.0, 0.0), angular_velocity=5.0)
    world.run_until(1.0)
    assert ball.velocity == (1.0, 0.0)
    assert ball.angular_velocity == 5.0


# ------------------------------------------------------------------ on a slope


def ramp_with_ball(angle_deg, mu):
    """A fixed ramp rising to the right at ``angle_deg`` (friction 0) and a ball (friction ``mu``)
    at rest touching it halfway up, pressed in by 1e-12. Returns (world, ball, ramp, unit tangent up)."""
    a = math.radians(angle_deg)
    world = World(gravity=(0.0, -G), elasticity=0.5, bounds=(-1.0, -1.0, 5.0, 5.0))
    length = 4.0
    ramp = world.add_polygon(
        [(0.0, 0.0), (length * math.cos(a), 0.0), (length * math.cos(a), length * math.sin(a))],
        fixed=True, name="ramp",
    )
    tx, ty = math.cos(a), math.sin(a)
    nx, ny = -ty, tx
    s0 = 0.5 * length
    ball = world.add_circle((s0 * tx + (RADIUS - 1e-12) * nx, s0 * ty + (RADIUS - 1e-12) * ny), RADIUS,
                            mass=1.0, friction=mu, name="ball")
    return world, ball, ramp, (tx, ty)


@pytest.mark.parametrize("angle", [10.0, 30.0, 50.0])
@pytest.mark.parametrize("fraction", [0.34, 0.5, 1.0, 2.0])
def test_ball_on_a_slope_rolls_down_at_two_thirds_of_g_sin_whenever_tan_is_below_3_mu(angle, fraction):
    """mu = fraction tan(a) / 3 ... 2 tan(a) (a box would stay put above mu = tan a): the ball rolls,
    s = g sin(a) t^2 / 3, its spin matching its speed, its energy kept, with no event after it rests."""
    a = math.radians(angle)
    mu = fraction * math.tan(a)
    world, ball, ramp, (tx, ty) = ramp_with_ball(angle, mu)
    start = ball.position
    energy = mechanical_energy(world)
    t = 0.5
    world.run_until(t)
    assert ball.resting_on is ramp
    assert world.stats["events"] <= 2
    down = -((ball.position[0] - start[0]) * tx + (ball.position[1] - start[1]) * ty)
    assert down == pytest.approx(G * math.sin(a) * t * t / 3.0, abs=CLOSE)
    speed = -(ball.velocity[0] * tx + ball.velocity[1] * ty)
    assert speed == pytest.approx(2.0 / 3.0 * G * math.sin(a) * t, abs=CLOSE)
    assert ball.angular_velocity * RADIUS == pytest.approx(speed, abs=CLOSE)  # anticlockwise, rolling down-left
    assert mechanical_energy(world) == pytest.approx(energy, abs=1e-12)


@pytest.mark.parametrize("angle", [30.0, 50.0, 70.0])
@pytest.mark.parametrize("fraction", [0.1, 0.3])
def test_ball_on_a_steep_slope_skids_with_its_spin_growing_at_2_mu_g_cos_over_r(angle, fraction):
    """tan(a) > 3 mu: the ball skids down at g (sin a - mu cos a), friction turning it up at
    2 mu g cos(a) / R, and loses exactly the work of friction on the slip."""
    a = math.radians(angle)
    mu = fraction * math.tan(a)
    world, ball, ramp, (tx, ty) = ramp_with_ball(angle, mu)
    start = ball.position
    energy = mechanical_energy(world)
    t = 0.25
    world.run_until(t)
    assert ball.resting_on is ramp
    linear = G * (math.sin(a) - mu * math.cos(a))
    turning = 2.0 * mu * G * math.cos(a) / RADIUS
    down = -((ball.position[0] - start[0]) * tx + (ball.position[1] - start[1]) * ty)
    assert down == pytest.approx(0.5 * linear * t * t, abs=CLOSE)
    assert ball.angular_velocity == pytest.approx(turning * t, abs=CLOSE / RADIUS)
    slip_distance = 0.5 * (linear - turning * RADIUS) * t * t
    work = mu * G * math.cos(a) * slip_distance  # mass 1
    assert energy - mechanical_energy(world) == pytest.approx(work, rel=1e-9)


def test_ball_rolls_off_the_end_of_a_shelf_and_falls_spinning():
    """A ball rolling along a shelf with friction passes its end, falls with the spin it had (free),
    lands on the floor below and rolls on there."""
    world, floor = floor_world(floor_friction=0.5)
    shelf = world.add_box(-1.0, 0.25, 1.5, 0.25, fixed=True, friction=0.5, name="shelf")  # top y = 0.5, end x = 0.5
    v = 1.0
    ball = world.add_circle((0.0, 0.5 + RADIUS), RADIUS, mass=1.0, velocity=(v, 0.0), angular_velocity=-v / RADIUS,
                            friction=0.5)
    world.run_until(0.4)
    assert ball.resting_on is shelf
    assert ball.velocity == pytest.approx((v, 0.0), abs=CLOSE)
    assert ball.angular_velocity == pytest.approx(-v / RADIUS, abs=CLOSE)
    world.run_until(0.55)
    assert ball.resting_on is None and ball.position[0] > 0.5
    assert ball.angular_velocity == pytest.approx(-v / RADIUS, abs=1e-6)  # in the air the spin is kept
    world.run_until(3.0)
    assert ball.resting_on is floor
    assert ball.position[0] > 0.8 and ball.position[1] == pytest.approx(RADIUS, abs=1e-12)
    vx = ball.velocity[0]
    assert vx > 0.0 and vx + ball.angular_velocity * RADIUS == pytest.approx(0.0, abs=1e-9)


# ------------------------------------------------------------------ in a pile


def test_a_ball_on_a_box_pushed_along_ice_does_not_roll_but_is_carried():
    """On a support that can move a ball does not roll (``contact.rolls``; docs/rotation.md): held by
    static friction it is carried like a point, the box (M, own acceleration a0) and the ball (m)
    accelerating together at M a0 / (M + m), the ball's spin unchanged and its place on the box kept.
    (Rolling, the box would accelerate at M a0 / (M + m / 3) and the ball at a third of that.)"""
    world = World(gravity=(0.0, -G), elasticity=0.0, bounds=(-2.0, -1.0, 4.0, 3.0))
    floor = world.add_box(-2.0, -0.25, 6.0, 0.25, fixed=True, friction=0.0, name="floor")
    box_mass, ball_mass, push = 2.0, 1.0, 3.0
    box = world.add_box(0.0, 0.0, 1.0, 0.125, mass=box_mass, friction=0.0, name="box")
    ball = world.add_circle((0.75, 0.125 + RADIUS), RADIUS, mass=ball_mass, friction=0.8, name="ball")
    world.run_until(0.05)
    assert box.resting_on is floor and ball.resting_on is box
    box.acceleration = (push, 0.0)
    world.run_until(0.06)
    assert box.resting_on is floor and ball.resting_on is box
    t0 = world.time
    box_v, ball_v, spin = box.velocity[0], ball.velocity[0], ball.angular_velocity
    offset = ball.position[0] - box.position[0]
    world.run_until(t0 + 0.2)
    span = world.time - t0
    expected = box_mass * push / (box_mass + ball_mass)
    assert (box.velocity[0] - box_v) / span == pytest.approx(expected, rel=CLOSE)
    assert (ball.velocity[0] - ball_v) / span == pytest.approx(expected, rel=CLOSE)
    assert ball.angular_velocity == spin
    assert ball.position[0] - box.position[0] == pytest.approx(offset, abs=1e-12)
    assert ball.resting_on is box


def test_a_ball_dropped_on_a_box_sliding_on_ice_keeps_the_momentum():
    """Only friction between the ball and the box acts horizontally: the horizontal momentum never
    changes, the energy never rises, and the ball ends at rest on the box. (On a support that can
    move a ball does not roll yet: it slides to a stop keeping its spin; rolling it would end with
    no slip, v_ball - v_box + omega R = 0.)"""
    world = World(gravity=(0.0, -G), elasticity=0.3, bounds=(-2.0, -1.0, 8.0, 3.0))
    world.add_box(-2.0, -0.25, 10.0, 0.25, fixed=True, friction=0.0, name="floor")
    box = world.add_box(0.0, 0.0, 2.0, 0.125, mass=2.0, velocity=(1.5, 0.0), friction=0.0, name="box")
    ball = world.add_circle((1.8, 0.2), RADIUS, mass=1.0, angular_velocity=5.0, friction=0.05, name="ball")
    momentum = 2.0 * 1.5
    energy = mechanical_energy(world)
    for event in world.events(3.0):
        if isinstance(event, Collision):
            now = mechanical_energy(world)
            assert now <= energy + 1e-12
            energy = now
            assert 2.0 * box.velocity[0] + ball.velocity[0] == pytest.approx(momentum, abs=1e-12)
    assert ball.resting_on is box
    assert 2.0 * box.velocity[0] + ball.velocity[0] == pytest.approx(momentum, abs=1e-12)
    assert ball.velocity[0] - box.velocity[0] == pytest.approx(0.0, abs=1e-12)
    assert mechanical_energy(world) <= energy + 1e-12
