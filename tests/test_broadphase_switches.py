"""World.broadphase: switching a sound stage off changes no event; the lecture's test loses contacts.

Each sound switch (no short-circuit test, no swept-box check, no grid) only
skips work that cannot find a contact, so on the same scene the collision
trace (time, bodies, point, normal, impulse of every collision) and the final
state must be bit-identical, and so must every counter except the ones the
switch is meant to change (candidates, box_rejects, bound_rejects,
predictions). The lecture's test, swapped in for the sound one, must be
caught missing a contact that the sound run finds.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from strategies import build_scene, closed_box, random_scene

from pge import World
from pge.traces import CollisionLog, compare_traces
from pge.core import layout as L

#: counters a broad-phase switch is expected to change; every other one must match.
BROADPHASE_COUNTERS = {"candidates", "box_rejects", "bound_rejects", "predictions"}

SWITCHES = {
    "no-short-circuit": {"short_circuit": False},
    "no-boxes": {"boxes": False},
    "no-grid": {"grid": False},
    "nothing": {"short_circuit": False, "boxes": False, "grid": False},
}

#: scene kinds: (gravity, elasticity, spin of the polygons in rad/s, fixed pegs)
SCENES = {
    "free": ((0.0, 0.0), 1.0, 0.0, False),
    "gravity": ((0.0, -9.81), 0.9, 0.0, True),
    "spinning": ((0.0, 0.0), 1.0, 6.0, False),
    "spinning-gravity": ((0.0, -9.81), 1.0, 4.0, True),
}


def build(kind: str, seed: int, broadphase=None) -> World:
    """A seeded random scene of circles and polygons in a closed box."""
    gravity, elasticity, spin, pegs = SCENES[kind]
    world = World(gravity=gravity, elasticity=elasticity, broadphase=broadphase)
    closed_box(world, fixed=True, elasticity=elasticity)
    specs = random_scene(seed, n_circles=10, n_polygons=6, radius=(0.025, 0.06), speed=1.5, elasticity=elasticity)
    if pegs:
        # Two fixed pegs in the middle band, where random bodies rarely start: any
        # spec overlapping them is dropped (the scene stays reproducible).
        pegs_at = [(0.3, 0.5, 0.03), (0.7, 0.45, 0.03)]
        for x, y, r in pegs_at:
            world.add_circle((x, y), r, fixed=True, elasticity=elasticity)
        specs = [s for s in specs if all(_apart(s, x, y, r) for x, y, r in pegs_at)]
    bodies = build_scene(world, specs)
    if spin:
        for k, (spec, body) in enumerate(zip(specs, bodies)):
            if spec["kind"] == "polygon":
                world.set_angular_velocity(body, spin * (1 if k % 2 else -1))
    return world


def _apart(spec, x, y, r) -> bool:
    if spec["kind"] == "circle":
        cx, cy = spec["position"]
        size = spec["radius"]
    else:
        xs = [p[0] for p in spec["vertices"]]
        ys = [p[1] for p in spec["vertices"]]
        cx, cy = sum(xs) / len(xs), sum(ys) / len(ys)
        size = max(math.hypot(px - cx, py - cy) for px, py in spec["vertices"])
    return math.hypot(cx - x, cy - y) > size + r + 0.01


def run(kind: str, seed: int, broadphase=None, until: float = 2.0):
    world = build(kind, seed, broadphase)
    log = CollisionLog(world)
    world.run_until(until)
    return world, log.entries


def final_state(world: World) -> bytes:
    """Every float of every body row, and the int columns that are not scratch space."""
    state = world._state
    ints = np.delete(state.I[: state.n], [L.STAMP], axis=1)  # gather's de-duplication stamp
    return state.F[: state.n].tobytes() + ints.tobytes()


@pytest.mark.parametrize("seed", [0, 1, 2])
@pytest.mark.parametrize("kind", list(SCENES))
def test_every_sound_switch_leaves_the_event_trace_bit_identical(kind, seed):
    reference_world, reference = run(kind, seed)
    assert len(reference) > 20, "the scene must collide often enough to say something"
    reference_stats = reference_world.stats
    for name, switches in SWITCHES.items():
        world, trace = run(kind, seed, switches)
        divergence = compare_traces(reference, trace)
        assert divergence.fate == "identical", f"{kind} seed {seed}, {name}: {divergence}"
        assert final_state(world) == final_state(reference_world), f"{kind} seed {seed}, {name}"
        stats = world.stats
        for key, value in reference_stats.items():
            if key not in BROADPHASE_COUNTERS:
                assert stats[key] == value, f"{kind} seed {seed}, {name}: stats[{key!r}]"
        assert world.broadphase == {"short_circuit": True, "boxes": True, "grid": True, **switches}


@pytest.mark.parametrize("kind", ["free", "spinning-gravity"])
def test_each_switch_changes_the_counters_it_should(kind):
    """The switches really switch: the counters of the skipped stage move as expected."""
    base, _ = run(kind, 0)
    b = base.stats
    assert b["box_rejects"] > 0 and b["bound_rejects"] > 0

    no_sc, _ = run(kind, 0, {"short_circuit": False})
    s = no_sc.stats
    assert s["bound_rejects"] == 0
    assert s["predictions"] == b["predictions"] + b["bound_rejects"]  # every culled pair now solved exactly
    assert s["candidates"] == b["candidates"] and s["box_rejects"] == b["box_rejects"]

    no_boxes, _ = run(kind, 0, {"boxes": False})
    s = no_boxes.stats
    assert s["box_rejects"] == 0
    assert s["bound_rejects"] + s["predictions"] == b["bound_rejects"] + b["predictions"] + b["box_rejects"]

    no_grid, _ = run(kind, 0, {"grid": False})
    s = no_grid.stats
    assert s["candidates"] > b["candidates"]
    assert s["predictions"] == b["predictions"] and s["bound_rejects"] == b["bound_rejects"]

    nothing, _ = run(kind, 0, {"short_circuit": False, "boxes": False, "grid": False})
    s = nothing.stats
    g = no_grid.stats
    assert s["box_rejects"] == s["bound_rejects"] == 0
    assert s["candidates"] == g["candidates"]
    # Every all-pairs candidate that reached the box check is now solved exactly.
    assert s["predictions"] == g["predictions"] + g["box_rejects"] + g["bound_rejects"]


@settings(deadline=None, max_examples=6, suppress_health_check=[HealthCheck.too_slow])
@given(
    seed=st.integers(0, 10_000),
    circles=st.integers(0, 12),
    polygons=st.integers(1, 8),
    spin=st.sampled_from([0.0, 3.0, 15.0]),
    gravity=st.sampled_from([(0.0, 0.0), (0.0, -9.81), (2.0, -5.0)]),
    elasticity=st.sampled_from([1.0, 0.8]),
    switches=st.sampled_from(list(SWITCHES.values())),
)
def test_random_scenes_give_the_same_trace_with_a_stage_off(seed, circles, polygons, spin, gravity, elasticity, switches):
    def make(broadphase):
        world = World(gravity=gravity, elasticity=elasticity, broadphase=broadphase)
        closed_box(world, fixed=True, elasticity=elasticity)
        specs = random_scene(seed, n_circles=circles, n_polygons=polygons, radius=(0.03, 0.07), elasticity=elasticity)
        for k, body in enumerate(build_scene(world, specs)):
            if specs[k]["kind"] == "polygon" and spin:
                world.set_angular_velocity(body, spin if k % 2 else -spin)
        log = CollisionLog(world)
        world.run_until(1.5)
        return world, log.entries

    reference_world, reference = make(None)
    world, trace = make(switches)
    assert compare_traces(reference, trace).fate == "identical"
    assert final_state(world) == final_state(reference_world)


def test_switches_can_change_during_a_run_without_changing_events():
    reference_world, reference = run("spinning-gravity", 3, until=3.0)
    world = build("spinning-gravity", 3)
    log = CollisionLog(world)
    for k, switches in enumerate([{"grid": False}, {"boxes": False}, {}, {"short_circuit": False}, None, {}]):
        world.broadphase = switches
        world.run_until(0.5 * (k + 1))
    assert compare_traces(reference, log.entries).fate == "identical"
    assert final_state(world) == final_state(reference_world)


# ------------------------------------------------------------------ the lecture's test


def head_on(broadphase=None) -> World:
    """The lecture's first counterexample in a World: two discs of radius 0.02, 0.045
    apart, one closing at speed 1. Contact after 0.005 s. A skin of 0.01 makes the
    prediction window 0.01 s, within which the lecture's test compares the 0.01 of
    travel with W = 0.045^2 - 0.04^2 (not (0.045 - 0.04)^2) and culls the pair."""
    world = World(elasticity=1.0, skin=0.01, broadphase=broadphase)
    world.add_circle((0.4, 0.5), 0.02, mass=1.0, velocity=(1.0, 0.0))
    world.add_circle((0.445, 0.5), 0.02, mass=1.0)
    return world


def pushed_onto_a_peg(broadphase=None) -> World:
    """Accelerating towards each other along x: a disc moving at 0.2 and pushed by its own
    acceleration 9.81 towards a fixed peg 0.045 away (radii 0.02). The lecture's x term
    takes the velocity as j - i but the acceleration as i - j, so the two cancel over a
    window of 2 v / a ~ 0.041 s (a skin of 0.016 makes the window that long): S ~ 0 < W,
    the pair is culled, though the disc reaches the peg after ~0.0175 s."""
    world = World(elasticity=1.0, skin=0.016, broadphase=broadphase)
    world.add_circle((0.545, 0.5), 0.02, fixed=True)
    world.add_circle((0.5, 0.5), 0.02, mass=1.0, velocity=(0.2, 0.0), acceleration=(9.81, 0.0))
    return world


def rising_under_a_peg(broadphase=None) -> World:
    """The end of the window is not the whole window: a disc 0.0001 below a fixed peg
    (radii 0.02) thrown up at 0.04905 under gravity 9.81 rises 0.000123 and falls back
    to where it started 0.01 s later. With a skin of 0.000981 that is the window, the
    displacement at its end is zero, S = 0 < W, and the pair is culled, though the disc
    touches the peg after ~0.0029 s."""
    world = World(gravity=(0.0, -9.81), elasticity=1.0, skin=0.000981, broadphase=broadphase)
    world.add_circle((0.5, 0.5), 0.02, fixed=True)
    world.add_circle((0.5, 0.4599), 0.02, mass=1.0, velocity=(0.0, 0.04905))
    return world


@pytest.mark.parametrize("scene", [head_on, pushed_onto_a_peg, rising_under_a_peg])
def test_the_lecture_variant_is_caught_missing_a_contact(scene):
    sound_world = scene()
    sound = CollisionLog(sound_world, depths=True)
    sound_world.run_until(0.2)
    lecture_world = scene({"short_circuit": "lecture"})
    lecture = CollisionLog(lecture_world, depths=True)
    lecture_world.run_until(0.2)

    assert sound.entries, "the sound run must find the contact"
    assert sound.late(1e-9) == 0, "the sound run finds every contact at first touch"
    divergence = compare_traces(sound.entries, lecture.entries)
    assert divergence.index == 0 and divergence.fate in ("late", "missed"), divergence
    if divergence.fate == "late":
        # Found only at the next horizon, with the discs already overlapping.
        assert divergence.delay > 1e-3
        assert lecture.late(1e-6) > 0
    assert lecture_world.stats["bound_rejects"] > 0
    assert lecture_world.broadphase["short_circuit"] == "lecture"


# ------------------------------------------------------------------ validation


@pytest.mark.parametrize(
    "value, error, words",
    [
        ({"grids": False}, ValueError, "unknown key"),
        ({"short_circuit": "sound"}, ValueError, "'lecture'"),
        ({"short_circuit": 0}, TypeError, "short_circuit"),
        ({"boxes": "no"}, TypeError, "boxes"),
        ({"grid": None}, TypeError, "grid"),
        ([("grid", False)], TypeError, "dict"),
        ("lecture", TypeError, "dict"),
    ],
)
def test_bad_broadphase_options_are_refused_and_leave_the_world_unchanged(value, error, words):
    with pytest.raises(error, match=words):
        World(broadphase=value)
    world = World(broadphase={"grid": False})
    before = world.broadphase
    with pytest.raises(error, match=words):
        world.broadphase = value
    assert world.broadphase == before == {"short_circuit": True, "boxes": True, "grid": False}


def test_broadphase_defaults_and_round_trip():
    world = World()
    assert world.broadphase == {"short_circuit": True, "boxes": True, "grid": True}
    world.broadphase = {"short_circuit": "lecture", "boxes": False}
    assert world.broadphase == {"short_circuit": "lecture", "boxes": False, "grid": True}
    world.broadphase = world.broadphase  # what the getter returns is accepted back
    assert world.broadphase == {"short_circuit": "lecture", "boxes": False, "grid": True}
    world.broadphase = None
    assert world.broadphase == {"short_circuit": True, "boxes": True, "grid": True}


# ------------------------------------------------------------------ compare_traces


def test_compare_traces_names_what_happened_first():
    a = (0.1, 0, 1, 0.0, 0.0, 1.0, 0.0, 2.0)
    b = (0.2, 1, 2, 0.5, 0.0, 0.0, 1.0, 1.0)
    c = (0.3, 0, 2, 0.2, 0.2, 1.0, 0.0, 0.5)
    assert compare_traces([a, b], [a, b]).fate == "identical"
    late = compare_traces([a, b], [a, c, (0.25, 2, 1, 0.5, 0.0, 0.0, 1.0, 1.0)])
    assert (late.index, late.fate, late.reference) == (1, "late", b)
    assert late.delay == pytest.approx(0.05)
    assert compare_traces([a, b, c], [a, c]).fate == "missed"  # b's pair never collides again
    assert compare_traces([a, b], [a]).fate == "missed"  # the other run has no collision left
    assert compare_traces([a], [a, b]).fate == "extra"
    assert compare_traces([b], [a, b]).fate == "extra"  # a collision before the reference's first
    different = compare_traces([a], [(0.1, 1, 0, 0.0, 0.0, 1.0, 0.0, 2.5)])
    assert (different.fate, different.delay) == ("different", 0.0)
