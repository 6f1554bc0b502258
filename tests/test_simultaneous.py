"""Bodies touching at one instant: a body squeezed between two others, without gravity.

Two bodies strike a third from both sides at the same instant. The engine resolves the two
contacts one after the other; with elasticity 0 each impulse sends the middle body into the
other neighbour, and the approach speeds shrink geometrically. They must shrink to nothing
in a few dozen collisions: once an approach is rounding, the kernels and the collision
response must agree that it is no approach (``pge.core.predict.still_speed``), or the same
pair is reported again at the same instant for ever (the event-storm error).

Checked for circles and boxes, with spins, friction and slightly offset centres: the run
ends, with few collisions, and conserves linear momentum, never gains energy and leaves no
overlap.
"""

from __future__ import annotations

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from pge import World

RADIUS = 0.1
MOMENTUM = 1e-12  # absolute, total momentum starts at 0 with unit masses and speeds
ENERGY = 1e-12  # relative
OVERLAP = 1e-9  # relative to the bodies' size
#: a squeeze ends in a few collisions (a pair that collides again within a step and parts
#: slowly joins an island); as a run of exact impulses, every speed halved at each collision
#: until the speeds underflowed, about 1400 collisions for three boxes. An event storm is 1e6.
MAX_COLLISIONS = 3000


def _add(world, kind, x, y, **properties):
    if kind == "circle":
        return world.add_circle((x, y), RADIUS, **properties)
    return world.add_box(x - RADIUS, y - RADIUS, 2 * RADIUS, 2 * RADIUS, **properties)


def squeeze(kinds, spins, friction, offset, elasticity=0.0, masses=(1.0, 1.0, 1.0)):
    """Left and right bodies reach the middle one at t = 0.1, from both sides at unit speed."""
    world = World(gravity=(0.0, 0.0), elasticity=elasticity, bounds=(-1.0, -1.0, 2.0, 2.0))
    left = _add(world, kinds[0], 0.2, 0.5 + offset, mass=masses[0], velocity=(1.0, 0.0),
                angular_velocity=spins[0], friction=friction)
    middle = _add(world, kinds[1], 0.5, 0.5, mass=masses[1], angular_velocity=spins[1], friction=friction)
    right = _add(world, kinds[2], 0.8, 0.5 - offset, mass=masses[2], velocity=(-1.0, 0.0),
                 angular_velocity=spins[2], friction=friction)
    return world, (left, middle, right)


def energy(bodies):
    return sum(0.5 * b.mass * (b.velocity[0] ** 2 + b.velocity[1] ** 2) + 0.5 * b.inertia * b.angular_velocity ** 2
               for b in bodies)


def momentum(bodies):
    return (sum(b.mass * b.velocity[0] for b in bodies), sum(b.mass * b.velocity[1] for b in bodies))


def check_squeeze(world, bodies):
    """Run to t = 0.5, checking every collision; return the number of collisions."""
    start_energy = energy(bodies)
    start_px, start_py = momentum(bodies)
    before = start_energy
    collisions = 0
    for event in world.events(0.5):
        if type(event).__name__ != "Collision":
            continue
        collisions += 1
        assert collisions <= MAX_COLLISIONS, f"no end to the squeeze at t={event.time!r}"
        now = energy(bodies)
        assert now <= before * (1.0 + ENERGY), f"energy rose from {before!r} to {now!r} at {event!r}"
        before = now
        px, py = momentum(bodies)
        assert math.hypot(px - start_px, py - start_py) <= MOMENTUM
    for i, a in enumerate(bodies):
        for b in bodies[:i]:
            assert world.overlap_depth(a, b) <= OVERLAP * 2 * RADIUS
    return collisions


SPINS = [(0.0, 0.0, 0.0), (1.07, -1.68, -1.79), (13.1, -7.7, 3.3), (100.0, -50.0, 70.0)]


@pytest.mark.parametrize("spins", SPINS)
@pytest.mark.parametrize("friction", [0.0, 0.5])
@pytest.mark.parametrize("offset", [0.0, 0.013, 0.031])
def test_circle_squeezed_between_two_circles_ends_in_few_collisions(spins, friction, offset):
    """Most of these stormed before the shared 'still' rule (1M collisions at t = 0.1)."""
    world, bodies = squeeze(("circle", "circle", "circle"), spins, friction, offset)
    collisions = check_squeeze(world, bodies)
    assert 2 <= collisions <= 100  # both contacts were met, and the squeeze converged
    assert world.stats["grazes"] <= collisions


def test_plastic_squeeze_of_equal_circles_ends_with_all_three_at_rest():
    """Head on, without spin or friction, momentum 0 and e = 0: all three stop (to rounding)."""
    world, bodies = squeeze(("circle", "circle", "circle"), (0.0, 0.0, 0.0), 0.0, 0.0)
    check_squeeze(world, bodies)
    for body in bodies:
        assert math.hypot(*body.velocity) <= 1e-12


@pytest.mark.parametrize("kinds", [("box", "circle", "box"), ("circle", "box", "circle"), ("box", "box", "box")])
@pytest.mark.parametrize("friction", [0.0, 0.7])
def test_squeeze_with_boxes_ends(kinds, friction):
    """Boxes squeezed head-on (they once stormed: a pressed contact within rounding) end too."""
    world, bodies = squeeze(kinds, (0.0, 0.0, 0.0), friction, 0.0)
    assert check_squeeze(world, bodies) >= 2


@settings(max_examples=40, deadline=None)
@given(
    spins=st.tuples(*[st.floats(-60.0, 60.0)] * 3),
    friction=st.floats(0.0, 1.0),
    offset=st.floats(-0.05, 0.05),
    elasticity=st.sampled_from([0.0, 0.1, 0.5]),
    masses=st.tuples(*[st.floats(0.2, 5.0)] * 3),
)
def test_random_circle_squeezes_end_and_never_gain_energy(spins, friction, offset, elasticity, masses):
    world, bodies = squeeze(("circle", "circle", "circle"), spins, friction, offset, elasticity, masses)
    check_squeeze(world, bodies)


def test_spinning_circles_with_friction_do_not_graze_for_ever():
    """tools/repro/repro_livelock.py: after a sticking plastic collision the kernel saw an
    approach of -4.5e-17 that the collision response (with the spin terms) computed as 0."""
    world = World(gravity=(0.0, -9.81), elasticity=0.0, bounds=(0, 0, 1, 1))
    world.add_circle((0.2979906630636345, 0.9082176500196211), 0.03989288880633947, mass=1.760694019126658,
                     velocity=(0.5846948518416122, -1.2866932182626927), angular_velocity=-19.711546627023733,
                     friction=1.0)
    world.add_circle((0.3340481455015375, 0.733809171856975), 0.05819627758333601, mass=0.9323053557169774,
                     velocity=(0.21483027485665504, 0.5981897800255815), angular_velocity=-1.945104252898517,
                     friction=1.0)
    world.run_until(0.05)
    assert world.stats["collisions"] == 1
    assert world.stats["grazes"] == 0
