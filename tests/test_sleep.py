"""Sleeping islands (pge.core.sleep): a pile that contact forces can hold stops and makes no
events; one they cannot hold keeps moving; anything that touches or changes it wakes it.

The main scene is a plank leaning on a wall (a ladder). With friction only on the floor it
stands when the floor's coefficient is at least

    mu* = (L cos(theta) - W sin(theta)) / (2 L sin(theta))

(moments about the foot: the wall's push times the height of the top corner balances the
weight times the centroid's reach; the floor's friction must carry the wall's push), for a
plank of length L and thickness W at angle theta: 0.4667 at 45 degrees.
"""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from pge import World
from pge.core.sleep import nnls

G = 9.81
LENGTH, THICKNESS = 0.3, 0.02


def ladder(theta_deg, mu_floor, mu_wall=0.0, drop=1e-3, elasticity=0.5):
    """A plank leaning on a wall from ``drop`` above the floor, nudged into a slow turn so
    that it does not rest on its corner at once. Friction combines by ``max`` (the World's
    default), so the plank's own coefficient is 0 and each surface's is its own."""
    world = World(gravity=(0.0, -G), elasticity=elasticity)
    theta = math.radians(theta_deg)
    ux, uy = math.cos(theta), math.sin(theta)
    vx, vy = -math.sin(theta), math.cos(theta)
    x0 = 0.2
    foot = (x0, drop)
    top = (x0 + LENGTH * ux, drop + LENGTH * uy)
    corners = [foot, top, (top[0] + THICKNESS * vx, top[1] + THICKNESS * vy), (x0 + THICKNESS * vx, drop + THICKNESS * vy)]
    floor = world.add_box(-0.5, -0.1, 2.0, 0.1, fixed=True, name="floor")
    floor.friction = mu_floor
    wall = world.add_box(top[0] + 1e-4, 0.0, 0.1, 1.0, fixed=True, name="wall")
    wall.friction = mu_wall
    plank = world.add_polygon(corners, mass=1.0, angular_velocity=0.01, name="plank")
    plank.friction = 0.0
    return world, plank, floor, wall


def threshold(theta_deg):
    theta = math.radians(theta_deg)
    return (LENGTH * math.cos(theta) - THICKNESS * math.sin(theta)) / (2.0 * LENGTH * math.sin(theta))


def energy(world, bodies):
    total = 0.0
    for body in bodies:
        vx, vy = body.velocity
        total += 0.5 * body.mass * (vx * vx + vy * vy) + 0.5 * body.inertia * body.angular_velocity**2
        total += body.mass * G * body.position[1]
    return total


def test_threshold_formula():
    assert threshold(45) == pytest.approx(0.14 / 0.3)


@pytest.mark.parametrize("margin", [0.02, 0.05, 0.2])
def test_a_ladder_that_friction_holds_falls_asleep_and_makes_no_more_events(margin):
    world, plank, _, _ = ladder(45, threshold(45) + margin)
    start = plank.position
    before = energy(world, [plank])
    world.run_until(0.5)
    assert plank.asleep
    assert world.stats["sleeps"] >= 1
    events = world.stats["events"] - world.stats["frames"]
    world.run_until(5.0)
    assert world.stats["events"] - world.stats["frames"] == events  # nothing happens while asleep
    assert plank.asleep and plank.velocity == (0.0, 0.0) and plank.angular_velocity == 0.0
    # It stands where it was put (it only fell the 1 mm drop and turned a little).
    assert math.dist(plank.position, start) < 2e-3
    assert energy(world, [plank]) <= before
    assert world.overlaps(1e-9) == []


@pytest.mark.parametrize("margin", [-0.02, -0.05, -0.2])
def test_a_ladder_that_friction_cannot_hold_slides_down(margin):
    world, plank, _, _ = ladder(45, threshold(45) + margin)
    before = energy(world, [plank])
    world.run_until(0.05)
    assert not plank.asleep
    world.run_until(3.0)
    # It has slid down and lies flat on the floor (it may sleep there).
    assert abs(abs(plank.angle) - math.pi / 4) < 1e-3
    assert plank.position[1] < THICKNESS
    assert energy(world, [plank]) < before
    assert world.overlaps(1e-9) == []


def test_a_ball_landing_on_a_sleeping_ladder_wakes_it():
    world, plank, _, _ = ladder(45, 0.8)
    world.run_until(0.5)
    assert plank.asleep
    ball = world.add_circle((0.3, 0.4), 0.02, mass=0.5, name="ball")
    wakes = world.stats["wakes"]
    hit = []
    for event in world.events(0.8):
        if getattr(event, "a", None) is not None and plank in (event.a, event.b):
            hit.append(event)
            break
    assert hit, "the ball never reached the plank"
    assert world.stats["wakes"] == wakes + 1
    assert not plank.asleep
    world.run_until(3.0)
    assert world.overlaps(1e-9) == []


@pytest.mark.parametrize("change", ["velocity", "position", "remove wall", "unfix wall", "gravity"])
def test_changing_a_sleeping_pile_or_what_holds_it_wakes_it(change):
    world, plank, floor, wall = ladder(45, 0.8)
    world.run_until(0.5)
    assert plank.asleep
    if change == "velocity":
        plank.velocity = (0.0, 0.1)
    elif change == "position":
        x, y = plank.position
        world.set_position(plank, (x - 0.01, y + 0.01))
    elif change == "remove wall":
        world.remove(wall)
    elif change == "unfix wall":
        wall.mass = 5.0
        world.set_fixed(wall, False)
    else:
        world.gravity = (0.0, -5.0)
    assert not plank.asleep
    if change == "remove wall":
        world.run_until(3.0)
        assert plank.position[1] < THICKNESS  # with nothing to lean on it fell flat


def test_a_box_sliding_into_a_sleeping_ladder_wakes_it():
    world, plank, floor, _ = ladder(45, 0.8)
    world.run_until(0.5)
    assert plank.asleep
    # A box sliding on the floor (friction 0.8) into the plank's foot: the hit wakes the plank.
    box = world.add_box(-0.1, 0.0, 0.05, 0.05, mass=1.0, velocity=(3.0, 0.0), name="box")
    box.friction = 0.0
    woke_or_awake = []
    for event in world.events(2.0):
        if getattr(event, "a", None) is not None and {event.a, event.b} == {box, plank}:
            woke_or_awake.append(not plank.asleep)
            break
    assert woke_or_awake == [True]
    assert world.overlaps(1e-9) == []


@settings(max_examples=60, deadline=None)
@given(
    rows=st.integers(1, 8),
    cols=st.integers(1, 10),
    seed=st.integers(0, 2**32 - 1),
)
def test_nnls_meets_its_optimality_conditions(rows, cols, seed):
    """x >= 0 and, with g = A^T (A x - b): g = 0 where x > 0, g >= 0 where x = 0 (KKT)."""
    rng = np.random.default_rng(seed)
    A = rng.normal(size=(rows, cols))
    b = rng.normal(size=rows)
    x = nnls(A, b)
    assert (x >= 0.0).all()
    g = A.T @ (A @ x - b)
    scale = 1e-8 * (1.0 + np.abs(A).sum() * (np.abs(b).sum() + 1.0))
    assert (g >= -scale).all()
    assert (np.abs(g[x > 0.0]) <= scale).all()


def test_nnls_solves_a_consistent_system_exactly():
    A = np.array([[1.0, 0.0, 1.0], [0.0, 1.0, 1.0]])
    b = np.array([2.0, 3.0])
    x = nnls(A, b)
    assert np.allclose(A @ x, b, atol=1e-12) and (x >= 0.0).all()
    # b outside the cone: the best fit has a residual
    x = nnls(A, np.array([-1.0, 0.0]))
    assert np.allclose(x, 0.0)
