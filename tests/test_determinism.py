"""Determinism: the same scene gives a bit-identical event trace and final state.

Scenes are random circles and polygons (``strategies.random_scene``) inside a
closed box of four fixed walls, under gravity, elasticity 1. Floats are compared
through ``float.hex`` so that bit-identical means bit-identical (0.0 and -0.0
differ, and so would two NaNs).
"""

from __future__ import annotations

import pytest
from strategies import build_scene, closed_box, random_scene

from pge import Collision, Frame, Stop, Timer, World

SEEDS = [0, 1, 2, 3]
DURATION = 1.5


def _hex(values):
    return tuple(float(v).hex() for v in values)


def record(event):
    """A hashable, bit-exact description of one event record."""
    if isinstance(event, Collision):
        return (
            "collision",
            float(event.time).hex(),
            event.a.id,
            event.b.id,
            _hex(event.point),
            _hex(event.normal),
            float(event.impulse).hex(),
            float(event.approach_speed).hex(),
        )
    if isinstance(event, Frame):
        return ("frame", float(event.time).hex(), event.index)
    if isinstance(event, Timer):
        return ("timer", float(event.time).hex(), event.timer_id)
    if isinstance(event, Stop):
        return ("stop", float(event.time).hex())
    raise AssertionError(f"unexpected event {event!r}")


def make_world(seed):
    """A fresh world holding the scene of ``seed``."""
    world = World(gravity=(0.0, -9.81), elasticity=1.0, frame_rate=20.0)
    closed_box(world, thickness=0.1)
    build_scene(world, random_scene(seed, n_circles=10, n_polygons=5, speed=1.0))
    world.at_time(0.7, lambda timer: None, data="marker")
    return world


def final_state(world):
    return tuple(
        (body.id, _hex(body.position), _hex(body.velocity)) for body in world.bodies
    )


def trace_by_events(seed, until=DURATION):
    world = make_world(seed)
    trace = [record(event) for event in world.events(until)]
    return trace, final_state(world), world


@pytest.mark.parametrize("seed", SEEDS)
def test_same_scene_twice_gives_a_bit_identical_trace(seed):
    """Two fresh worlds with the same scene yield identical events (times, ids, points, normals) and end states."""
    trace_1, state_1, world = trace_by_events(seed)
    trace_2, state_2, _ = trace_by_events(seed)
    collisions = [r for r in trace_1 if r[0] == "collision"]
    assert len(collisions) > 20, "the scene must be busy enough to mean something"
    assert any(r[2] >= 4 and r[3] >= 4 for r in collisions), "some collisions between two scene bodies"
    assert trace_1 == trace_2
    assert state_1 == state_2
    assert world.overlaps(1e-9) == []


@pytest.mark.parametrize("seed", SEEDS[:2])
def test_observing_the_run_does_not_change_it(seed):
    """run_until with a collision callback gives the same trace and end state as iterating events()."""
    trace, state, _ = trace_by_events(seed)
    world = make_world(seed)
    seen = []
    world.on_collision(lambda event: seen.append(record(event)))
    world.run_until(DURATION)
    assert seen == [r for r in trace if r[0] == "collision"]
    assert final_state(world) == state


@pytest.mark.parametrize("seed", SEEDS[:2])
def test_a_run_in_pieces_gives_the_same_trace_as_one_run(seed):
    """Stopping at arbitrary times and resuming changes nothing: same events, same end state."""
    trace, state, _ = trace_by_events(seed)
    world = make_world(seed)
    pieces = []
    for until in (0.123, 0.5, 0.5, 0.9871, DURATION):
        pieces.extend(record(event) for event in world.events(until) if not isinstance(event, Stop))
    assert pieces == [r for r in trace if r[0] != "stop"]
    assert final_state(world) == state


def test_different_seeds_give_different_traces():
    """The scenes really differ from seed to seed (a guard against comparing constant traces)."""
    first = trace_by_events(SEEDS[0], 0.5)[0]
    second = trace_by_events(SEEDS[1], 0.5)[0]
    assert first != second


def _disc_world(with_polygon):
    """Ten discs in a closed box of fixed walls, under gravity, elasticity 1; optionally a
    movable triangle outside the box, at rest without gravity's reach (it sits on a fixed
    shelf), which nothing inside can touch."""
    world = World(gravity=(0.0, -9.81), elasticity=1.0, bounds=(0.0, 0.0, 2.0, 1.0))
    closed_box(world, thickness=0.1)
    build_scene(world, random_scene(0, n_circles=10, n_polygons=0, speed=1.0))
    if with_polygon:
        world.add_box(1.5, 0.2, 0.4, 0.05, fixed=True)
        world.add_polygon([(1.6, 0.25), (1.8, 0.25), (1.7, 0.35)], mass=1.0, friction=0.5)
    return world


def test_the_loops_two_compiled_versions_give_the_same_discs():
    """A world whose polygons are all fixed runs the loop's version without the turning and
    polygon-polygon kernels (``engine.run`` with ``polygons`` None); a movable polygon
    anywhere makes it run the general one. The discs' collisions and end states are
    bit-identical either way."""
    plain = _disc_world(False)
    other = _disc_world(True)
    assert plain._polygons() is None and other._polygons() is True
    discs = [b.id for b in plain.bodies if b.kind == "circle"]
    assert len(discs) == 10
    traces = []
    for world in (plain, other):
        trace = [record(e) for e in world.events(2.0) if isinstance(e, Collision) and e.a.id in discs and e.b.id in discs]
        state = [(b.id, _hex(b.position), _hex(b.velocity)) for b in world.bodies if b.id in discs]
        traces.append((trace, state))
    assert len(traces[0][0]) > 10
    assert traces[0] == traces[1]


def test_the_world_picks_the_loops_version_as_polygons_are_fixed_released_and_removed():
    """``World._polygons`` (which compiled loop runs) is True exactly while some polygon can move."""
    world = World(gravity=(0.0, 0.0))
    closed_box(world, thickness=0.1)
    ball = world.add_circle((0.5, 0.5), 0.05, mass=1.0, velocity=(1.0, 0.0))
    assert world._polygons() is None
    triangle = world.add_polygon([(0.2, 0.2), (0.3, 0.2), (0.25, 0.3)], fixed=True)
    assert world._polygons() is None
    world.set_fixed(triangle, False)
    assert world._polygons() is True
    world.set_fixed(triangle, True)
    assert world._polygons() is None
    world.set_fixed(triangle, False)
    world.remove(triangle)
    assert world._polygons() is None
    square = world.add_polygon([(0.6, 0.2), (0.7, 0.2), (0.7, 0.3), (0.6, 0.3)], mass=1.0)
    assert world._polygons() is True
    world.set_fixed(ball, True)
    world.remove(square)
    assert world._polygons() is None
