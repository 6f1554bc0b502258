"""Bad input: a clear ValueError/TypeError naming the object and the problem, and an unchanged world.

Every rejected call is checked three ways: the exception type, a message that names the
object (its kind and name, or the World / method) and the offending parameter, and a
snapshot of the world (bodies, count, time, positions, velocities, masses, gravity,
event counters) that must be identical before and after. Each case then runs the world on
to prove it still works.
"""

from __future__ import annotations

import math

import pytest

from pge import Body, World

NAN = math.nan
INF = math.inf

# ----------------------------------------------------------------------------- helpers


def make_world(primed: bool) -> tuple[World, dict[str, Body]]:
    """A unit box of four fixed walls with a named ball, a named triangle and a named fixed post.

    With ``primed`` the world has already run a little (so later additions are checked at
    once rather than at the next run).
    """
    world = World(elasticity=1.0)
    t = 0.01
    world.add_box(0.0, 0.0, 1.0, t, fixed=True, name="floor")
    world.add_box(0.0, 1.0 - t, 1.0, t, fixed=True, name="ceiling")
    world.add_box(0.0, 0.0, t, 1.0, fixed=True, name="left")
    world.add_box(1.0 - t, 0.0, t, 1.0, fixed=True, name="right")
    ball = world.add_circle((0.3, 0.3), 0.05, mass=1.0, velocity=(0.3, 0.2), name="ball")
    tri = world.add_polygon(
        [(0.6, 0.6), (0.75, 0.6), (0.7, 0.75)], mass=2.0, velocity=(-0.1, 0.25), name="tri"
    )
    post = world.add_circle((0.5, 0.8), 0.04, fixed=True, name="post")
    if primed:
        world.run_until(0.05)
    return world, {"ball": ball, "tri": tri, "post": post}


def snapshot(world: World):
    """Everything a failed call must leave untouched."""
    bodies = tuple(
        (
            b.id,
            b.kind,
            b.name,
            b.position,
            b.velocity,
            b.acceleration,
            b.mass,
            b.is_fixed,
            b.elasticity,
            b.angle,
            b.angular_velocity,
            b.vertices,
        )
        for b in world.bodies
    )
    # what happened (not the broad phase's work counters, which a re-prediction may bump)
    happened = {k: v for k, v in world.stats.items() if k in ("events", "collisions", "pair_collisions", "timers", "frames")}
    return (world.time, len(world), bodies, world.gravity, world.frame_rate, happened)


def assert_still_runs(world: World) -> None:
    """A later valid run works: time advances to the target and nothing overlaps."""
    start = world.time
    moving = [b for b in world.bodies if not b.is_fixed and b.velocity != (0.0, 0.0)]
    old = [b.position for b in moving]
    world.run_until(start + 0.5)
    assert world.time == start + 0.5
    assert world.overlaps(1e-9) == []
    assert all(b.position != p for b, p in zip(moving, old))


def check_rejected(world, call, error, *fragments):
    """``call()`` raises exactly ``error`` whose message holds every fragment; world unchanged."""
    before = snapshot(world)
    with pytest.raises(error) as info:
        call()
    assert type(info.value) is error, f"expected {error.__name__}, got {type(info.value).__name__}"
    message = str(info.value)
    for fragment in fragments:
        assert fragment.lower() in message.lower(), f"{fragment!r} not in {message!r}"
    assert snapshot(world) == before
    assert_still_runs(world)
    return message


@pytest.fixture(params=[False, True], ids=["fresh", "primed"])
def scene(request):
    return make_world(request.param)


# ------------------------------------------------------------------- polygon outlines

STAR = [
    (0.5 + 0.1 * math.cos(math.pi / 2 + k * 4 * math.pi / 5), 0.5 + 0.1 * math.sin(math.pi / 2 + k * 4 * math.pi / 5))
    for k in range(5)
]

BAD_OUTLINES = {
    "non-convex": ([(0.4, 0.4), (0.6, 0.4), (0.5, 0.45), (0.5, 0.6)], ["not convex"]),
    "non-convex-clockwise": ([(0.5, 0.6), (0.5, 0.45), (0.6, 0.4), (0.4, 0.4)], ["not convex"]),
    "star": (STAR, ["self-intersecting"]),
    "two-points": ([(0.4, 0.4), (0.6, 0.4)], ["3 distinct vertices"]),
    "three-points-two-distinct": ([(0.4, 0.4), (0.6, 0.4), (0.4, 0.4)], ["3 distinct vertices"]),
    "empty": ([], ["3 distinct vertices"]),
    "repeated-vertex": ([(0.4, 0.4), (0.6, 0.4), (0.6, 0.4), (0.5, 0.6)], ["repeats"]),
    "collinear": ([(0.4, 0.4), (0.5, 0.5), (0.6, 0.6)], ["zero area"]),
    "collinear-four": ([(0.4, 0.4), (0.5, 0.4), (0.6, 0.4), (0.7, 0.4)], ["zero area"]),
}


@pytest.mark.parametrize("case", sorted(BAD_OUTLINES))
def test_bad_polygon_outline_is_rejected_with_its_name(scene, case):
    """Non-convex, star, degenerate, repeated-vertex and collinear outlines raise ValueError naming the polygon."""
    world, _ = scene
    vertices, fragments = BAD_OUTLINES[case]
    check_rejected(world, lambda: world.add_polygon(vertices, mass=1.0, name="bad"), ValueError, "'bad'", *fragments)


@pytest.mark.parametrize(
    "vertices",
    [
        [(0.4, 0.4), (0.6, 0.6), (0.6, 0.4), (0.4, 0.6)],  # symmetric bow-tie (signed area 0)
        [(0.4, 0.4), (0.7, 0.7), (0.7, 0.4), (0.4, 0.5)],  # lopsided bow-tie
    ],
    ids=["symmetric", "lopsided"],
)
def test_bow_tie_polygon_is_reported_as_self_intersecting_or_non_convex(scene, vertices):
    """A bow-tie outline raises a ValueError that says it crosses itself / is not convex, not that it is collinear."""
    world, _ = scene
    check_rejected(world, lambda: world.add_polygon(vertices, mass=1.0, name="bow"), ValueError, "'bow'")
    with pytest.raises(ValueError) as info:
        world.add_polygon(vertices, mass=1.0, name="bow")
    message = str(info.value)
    assert "self-intersecting" in message or "not convex" in message, message


def test_bad_box_dimensions_are_rejected(scene):
    """add_box with zero or negative width/height raises ValueError naming the box."""
    world, _ = scene
    check_rejected(world, lambda: world.add_box(0.4, 0.4, 0.0, 0.1, mass=1.0, name="b"), ValueError, "'b'", "width")
    check_rejected(world, lambda: world.add_box(0.4, 0.4, 0.1, -0.1, mass=1.0, name="b"), ValueError, "'b'", "height")


# ----------------------------------------------------------------- numeric parameters


@pytest.mark.parametrize("radius", [0.0, -0.05, -INF], ids=["zero", "negative", "-inf"])
def test_non_positive_radius_is_rejected(scene, radius):
    """A circle radius <= 0 raises ValueError naming the circle and 'radius'."""
    world, _ = scene
    check_rejected(world, lambda: world.add_circle((0.5, 0.5), radius, mass=1.0, name="c"), ValueError, "'c'", "radius")


@pytest.mark.parametrize("mass", [0.0, -1.0, -0.0], ids=["zero", "negative", "minus-zero"])
def test_non_positive_mass_is_rejected_for_new_and_existing_bodies(scene, mass):
    """mass <= 0 raises ValueError naming the body and 'mass', at creation and in set_mass / body.mass =."""
    world, bodies = scene
    check_rejected(world, lambda: world.add_circle((0.5, 0.45), 0.02, mass=mass, name="c"), ValueError, "'c'", "mass")
    check_rejected(world, lambda: world.set_mass(bodies["ball"], mass), ValueError, "'ball'", "mass")

    def assign():
        bodies["tri"].mass = mass

    check_rejected(world, assign, ValueError, "'tri'", "mass")


@pytest.mark.parametrize("value", [-0.01, 1.01, -INF], ids=["below-0", "above-1", "-inf"])
def test_elasticity_outside_unit_interval_is_rejected(scene, value):
    """Elasticity outside [0, 1] raises ValueError naming the body (or World) and 'elasticity'."""
    world, bodies = scene
    check_rejected(
        world,
        lambda: world.add_circle((0.5, 0.45), 0.02, mass=1.0, elasticity=value, name="c"),
        ValueError,
        "'c'",
        "elasticity",
    )
    check_rejected(world, lambda: world.set_elasticity(bodies["ball"], value), ValueError, "'ball'", "elasticity")
    with pytest.raises(ValueError, match="World.*elasticity"):
        World(elasticity=value)


def test_elasticity_bounds_zero_and_one_are_accepted():
    """Elasticity exactly 0 and exactly 1 are valid (positive control for the range check)."""
    world = World(elasticity=0.0)
    body = world.add_circle((0.5, 0.5), 0.1, mass=1.0, elasticity=1.0)
    world.set_elasticity(body, 0.0)
    assert body.elasticity == 0.0


BAD_NUMBERS = [NAN, INF, -INF]
BAD_IDS = ["nan", "inf", "-inf"]


def _number_cases(world: World, bodies: dict[str, Body], bad: float):
    """(label, call, fragments) for every numeric parameter of every World entry point."""
    ball, tri = bodies["ball"], bodies["tri"]
    free = (0.5, 0.45)
    return [
        ("circle position x", lambda: world.add_circle((bad, 0.45), 0.02, mass=1.0, name="c"), ["'c'", "position"]),
        ("circle position y", lambda: world.add_circle((0.5, bad), 0.02, mass=1.0, name="c"), ["'c'", "position"]),
        ("circle radius", lambda: world.add_circle(free, bad, mass=1.0, name="c"), ["'c'", "radius"]),
        ("circle mass", lambda: world.add_circle(free, 0.02, mass=bad, name="c"), ["'c'", "mass"]),
        ("circle velocity", lambda: world.add_circle(free, 0.02, mass=1.0, velocity=(bad, 0), name="c"), ["'c'", "velocity"]),
        ("circle acceleration", lambda: world.add_circle(free, 0.02, mass=1.0, acceleration=(0, bad), name="c"), ["'c'", "acceleration"]),
        ("circle elasticity", lambda: world.add_circle(free, 0.02, mass=1.0, elasticity=bad, name="c"), ["'c'", "elasticity"]),
        ("circle angle", lambda: world.add_circle(free, 0.02, mass=1.0, angle=bad, name="c"), ["'c'", "angle"]),
        ("circle angular_velocity", lambda: world.add_circle(free, 0.02, mass=1.0, angular_velocity=bad, name="c"), ["'c'", "angular_velocity"]),
        ("polygon vertex", lambda: world.add_polygon([(0.45, 0.45), (bad, 0.45), (0.5, 0.5)], mass=1.0, name="p"), ["'p'", "vertex"]),
        ("polygon mass", lambda: world.add_polygon([(0.45, 0.45), (0.5, 0.45), (0.5, 0.5)], mass=bad, name="p"), ["'p'", "mass"]),
        ("box x", lambda: world.add_box(bad, 0.45, 0.02, 0.02, mass=1.0, name="b"), ["'b'", "x"]),
        ("box y", lambda: world.add_box(0.45, bad, 0.02, 0.02, mass=1.0, name="b"), ["'b'", "y"]),
        ("box width", lambda: world.add_box(0.45, 0.45, bad, 0.02, mass=1.0, name="b"), ["'b'", "width"]),
        ("box height", lambda: world.add_box(0.45, 0.45, 0.02, bad, mass=1.0, name="b"), ["'b'", "height"]),
        ("set_position", lambda: world.set_position(ball, (bad, 0.3)), ["'ball'", "position"]),
        ("set_velocity", lambda: world.set_velocity(ball, (0.1, bad)), ["'ball'", "velocity"]),
        ("set_acceleration", lambda: world.set_acceleration(tri, (bad, 0.0)), ["'tri'", "acceleration"]),
        ("apply_impulse", lambda: world.apply_impulse(ball, (bad, 0.0)), ["'ball'", "impulse"]),
        ("set_mass", lambda: world.set_mass(tri, bad), ["'tri'", "mass"]),
        ("set_elasticity", lambda: world.set_elasticity(ball, bad), ["'ball'", "elasticity"]),
        ("set_angle", lambda: world.set_angle(tri, bad), ["'tri'", "angle"]),
        ("set_angular_velocity", lambda: world.set_angular_velocity(tri, bad), ["'tri'", "angular_velocity"]),
        ("set_gravity", lambda: world.set_gravity((0.0, bad)), ["World", "gravity"]),
        ("gravity property", lambda: setattr(world, "gravity", (bad, 0.0)), ["World", "gravity"]),
        ("frame_rate", lambda: setattr(world, "frame_rate", bad), ["World", "frame_rate"]),
        ("run_until", lambda: world.run_until(bad), ["run_until", "time"]),
        ("run", lambda: world.run(bad), ["run", "duration"]),
        ("at_time", lambda: world.at_time(bad, lambda event: None), ["at_time", "time"]),
    ]


@pytest.mark.parametrize("bad", BAD_NUMBERS, ids=BAD_IDS)
def test_non_finite_numbers_are_rejected_everywhere(scene, bad):
    """NaN and +-inf in every numeric parameter raise ValueError naming the object and the parameter."""
    world, bodies = scene
    for label, call, fragments in _number_cases(world, bodies, bad):
        try:
            check_rejected(world, call, ValueError, *fragments)
        except AssertionError as failure:
            raise AssertionError(f"{label} with {bad!r}: {failure}") from None


def test_nan_until_in_events_is_rejected(scene):
    """events(until=nan) raises ValueError naming events() and leaves the world unchanged."""
    world, _ = scene
    check_rejected(world, lambda: world.events(NAN), ValueError, "events")


@pytest.mark.parametrize(
    "kwargs, fragment",
    [
        ({"gravity": (NAN, 0.0)}, "gravity"),
        ({"gravity": (0.0, INF)}, "gravity"),
        ({"elasticity": NAN}, "elasticity"),
        ({"frame_rate": NAN}, "frame_rate"),
        ({"frame_rate": INF}, "frame_rate"),
        ({"frame_rate": 0.0}, "frame_rate"),
        ({"frame_rate": -10.0}, "frame_rate"),
        ({"bounds": (0.0, 0.0, NAN, 1.0)}, "bounds"),
        ({"bounds": (0.0, 0.0, 0.0, 1.0)}, "bounds"),
        ({"cell_size": -1.0}, "cell_size"),
        ({"cell_size": INF}, "cell_size"),
        ({"skin": 0.0}, "skin"),
        ({"skin": NAN}, "skin"),
        ({"restitution": "average"}, "restitution"),
    ],
)
def test_world_constructor_rejects_bad_settings(kwargs, fragment):
    """World(...) with a non-finite, non-positive or unknown setting raises ValueError naming the setting."""
    with pytest.raises(ValueError) as info:
        World(**kwargs)
    assert fragment in str(info.value)


# ------------------------------------------------------------------------ wrong types


def _type_cases(world: World, bodies: dict[str, Body]):
    ball, tri = bodies["ball"], bodies["tri"]
    free = (0.5, 0.45)
    return [
        ("circle radius", lambda: world.add_circle(free, "0.02", mass=1.0, name="c"), ["'c'", "radius"]),
        ("circle position item", lambda: world.add_circle(("0.5", 0.45), 0.02, mass=1.0, name="c"), ["'c'", "position"]),
        ("circle position None", lambda: world.add_circle(None, 0.02, mass=1.0, name="c"), ["'c'", "position"]),
        ("circle mass", lambda: world.add_circle(free, 0.02, mass="1", name="c"), ["'c'", "mass"]),
        ("circle velocity", lambda: world.add_circle(free, 0.02, mass=1.0, velocity=("1", 0), name="c"), ["'c'", "velocity"]),
        ("circle elasticity", lambda: world.add_circle(free, 0.02, mass=1.0, elasticity="1", name="c"), ["'c'", "elasticity"]),
        ("circle radius bool", lambda: world.add_circle(free, True, mass=1.0, name="c"), ["'c'", "radius"]),
        ("polygon vertex", lambda: world.add_polygon([(0.45, 0.45), ("0.5", 0.45), (0.5, 0.5)], mass=1.0, name="p"), ["'p'", "vertex"]),
        ("polygon vertices scalar", lambda: world.add_polygon(3, mass=1.0, name="p"), ["'p'", "vertices"]),
        ("box width", lambda: world.add_box(0.45, 0.45, "0.02", 0.02, mass=1.0, name="b"), ["'b'", "width"]),
        ("set_velocity", lambda: world.set_velocity(ball, ("a", "b")), ["'ball'", "velocity"]),
        ("set_position", lambda: world.set_position(ball, (0.3, "0.3")), ["'ball'", "position"]),
        ("set_mass", lambda: world.set_mass(tri, "2"), ["'tri'", "mass"]),
        ("apply_impulse", lambda: world.apply_impulse(ball, (0.0, None)), ["'ball'", "impulse"]),
        ("set_gravity", lambda: world.set_gravity(("0", -9.8)), ["World", "gravity"]),
        ("frame_rate", lambda: setattr(world, "frame_rate", "60"), ["World", "frame_rate"]),
        ("run_until", lambda: world.run_until("1"), ["run_until", "time"]),
        ("run", lambda: world.run("1"), ["run", "duration"]),
        ("at_time", lambda: world.at_time("1", lambda event: None), ["at_time", "time"]),
        ("at_time callback", lambda: world.at_time(world.time + 1.0, "not callable"), ["at_time", "callback"]),
        ("on_collision callback", lambda: world.on_collision(42), ["on_collision", "callback"]),
        ("on_frame callback", lambda: world.on_frame(None), ["on_frame", "callback"]),
        ("remove non-body", lambda: world.remove("ball"), ["Body"]),
        ("set_velocity non-body", lambda: world.set_velocity(0, (1.0, 0.0)), ["Body"]),
    ]


def test_wrong_types_raise_type_error_naming_the_parameter(scene):
    """A string (or None, bool, non-callable) where a number/callable/Body is expected raises TypeError naming it."""
    world, bodies = scene
    for label, call, fragments in _type_cases(world, bodies):
        try:
            check_rejected(world, call, TypeError, *fragments)
        except AssertionError as failure:
            raise AssertionError(f"{label}: {failure}") from None


@pytest.mark.parametrize("until", ["1.0", "soon", None], ids=["numeric-string", "word", "None"])
def test_events_until_of_wrong_type_raises_type_error_naming_events(scene, until):
    """events(until=<str or None>) raises TypeError naming events() (as run_until does), not a bare float() error."""
    world, _ = scene
    check_rejected(world, lambda: world.events(until), TypeError, "events")


def test_string_as_whole_position_raises_type_error(scene):
    """add_circle('0.5', r): a string where an (x, y) pair of numbers is expected is a TypeError naming position."""
    world, _ = scene
    check_rejected(world, lambda: world.add_circle("0.5", 0.02, mass=1.0, name="c"), TypeError, "'c'", "position")


def test_non_boolean_fixed_option_is_rejected(scene):
    """fixed='no' (a truthy string) raises TypeError instead of silently fixing the body."""
    world, _ = scene
    check_rejected(world, lambda: world.add_circle((0.5, 0.45), 0.02, mass=1.0, fixed="no", name="c"), TypeError, "'c'", "fixed")


def test_wrong_length_vectors_raise_value_error(scene):
    """A position or velocity with other than 2 components raises ValueError naming it."""
    world, bodies = scene
    check_rejected(world, lambda: world.add_circle((0.5, 0.45, 0.0), 0.02, mass=1.0, name="c"), ValueError, "'c'", "position")
    check_rejected(world, lambda: world.set_velocity(bodies["ball"], (1.0,)), ValueError, "'ball'", "velocity")


@pytest.mark.parametrize("option", ["colour", "massive", "restitution", "inertia"])
def test_unknown_option_raises_type_error_naming_it(scene, option):
    """An unknown keyword to add_circle/add_polygon/add_box raises TypeError naming the body and the option."""
    world, _ = scene
    extra = {option: 1.0}
    check_rejected(world, lambda: world.add_circle((0.5, 0.45), 0.02, mass=1.0, name="c", **extra), TypeError, "'c'", option)
    check_rejected(
        world,
        lambda: world.add_polygon([(0.45, 0.45), (0.5, 0.45), (0.5, 0.5)], mass=1.0, name="p", **extra),
        TypeError,
        "'p'",
        option,
    )
    check_rejected(world, lambda: world.add_box(0.45, 0.45, 0.02, 0.02, mass=1.0, name="b", **extra), TypeError, "'b'", option)


@pytest.mark.parametrize(
    "kwargs, fragment",
    [({"elasticity": "1"}, "elasticity"), ({"gravity": ("0", 0)}, "gravity"), ({"frame_rate": "60"}, "frame_rate")],
)
def test_world_constructor_rejects_wrong_types(kwargs, fragment):
    """World(...) with a string where a number is expected raises TypeError naming World and the setting."""
    with pytest.raises(TypeError) as info:
        World(**kwargs)
    assert "World" in str(info.value) and fragment in str(info.value)


def test_unknown_world_option_raises_type_error():
    """World(unknown=...) raises TypeError naming the option."""
    with pytest.raises(TypeError, match="wind"):
        World(wind=(1.0, 0.0))


# ------------------------------------------------------------------ checks at run time


def _overlapping_world():
    world = World()
    world.add_box(0.0, 0.0, 1.0, 0.05, fixed=True, name="floor")
    world.add_box(0.0, 0.0, 0.05, 1.0, fixed=True, name="wall")  # overlaps the floor: allowed (both fixed)
    a = world.add_circle((0.4, 0.5), 0.1, mass=1.0, velocity=(1.0, 0.0), name="alpha")
    b = world.add_polygon([(0.45, 0.45), (0.65, 0.45), (0.55, 0.6)], mass=1.0, name="beta")
    world.at_time(0.0, lambda event: None)
    world.frame_rate = 100
    return world, a, b


@pytest.mark.parametrize("how", ["run_until", "run", "events"])
def test_overlap_at_run_start_names_both_bodies_and_processes_nothing(how):
    """Bodies overlapping when a run starts raise ValueError naming both; no event runs; time stays 0."""
    world, _, b = _overlapping_world()
    before = snapshot(world)
    seen = []
    world.on_collision(seen.append)
    world.on_frame(seen.append)
    with pytest.raises(ValueError) as info:
        if how == "run_until":
            world.run_until(1.0)
        elif how == "run":
            world.run(1.0)
        else:
            seen.extend(world.events(1.0))
    message = str(info.value)
    assert "'alpha'" in message and "'beta'" in message and "overlap" in message
    assert seen == []
    assert world.time == 0.0
    assert world.stats["events"] == 0
    assert snapshot(world) == before
    # fixing the overlap makes the same world runnable
    world.set_position(b, (0.7, 0.3))
    world.run_until(0.5)
    assert world.time == 0.5
    assert world.overlaps(1e-9) == []


def test_overlap_error_repeats_until_fixed():
    """A failed start does not half-prime the world: a second attempt raises the same overlap error."""
    world, alpha, b = _overlapping_world()
    with pytest.raises(ValueError, match="overlap"):
        world.run_until(1.0)
    with pytest.raises(ValueError, match="overlap"):
        world.run_until(1.0)
    assert world.time == 0.0 and world.stats["events"] == 0
    world.remove(b)
    world.run_until(1.0)
    assert world.time == 1.0
    assert alpha.position == pytest.approx((1.4, 0.5), abs=1e-12)
    assert world.stats["frames"] == 100


def test_adding_an_overlapping_body_after_the_first_run_raises_at_once(scene):
    """Once the world has run, add_* of a body overlapping another raises at once, naming both; nothing changes."""
    world, bodies = scene
    if world.time == 0.0:
        world.run_until(0.01)
    ball = bodies["ball"]
    x, y = ball.position
    message = check_rejected(world, lambda: world.add_circle((x + 0.01, y), 0.05, mass=1.0, name="intruder"), ValueError, "'intruder'", "overlap")
    assert "'ball'" in message


def test_set_position_into_overlap_after_the_first_run_raises_and_restores(scene):
    """Once running, set_position/set_angle into an overlap raise ValueError naming both; the body stays put."""
    world, bodies = scene
    if world.time == 0.0:
        world.run_until(0.01)
    ball, tri = bodies["ball"], bodies["tri"]
    message = check_rejected(world, lambda: world.set_position(tri, ball.position), ValueError, "'tri'", "overlap")
    assert "'ball'" in message
    # a rotation that turns a corner of the triangle into the post
    post = bodies["post"]
    px, py = post.position
    angles = [0.1 * k for k in range(63)]
    for gap in [0.05 + 0.002 * k for k in range(60)]:
        spot = (px + gap, py)
        if _turn_depth(tri, spot, post, tri.angle) < -1e-3:
            hits = [a for a in angles if _turn_depth(tri, spot, post, a) > 1e-3]
            if hits:
                break
    else:
        raise AssertionError("test set-up: no spot where a rotation reaches the post")
    world.set_position(tri, spot)
    check_rejected(world, lambda: world.set_angle(tri, hits[0]), ValueError, "'tri'", "overlap")


def _turn_depth(tri, spot, post, angle):
    """How deeply the triangle at ``spot`` turned to ``angle`` would overlap the post (computed here)."""
    from pge.geometry import circle_polygon_depth, rotate_points

    local = rotate_points(tri.shape.vertices, angle)
    cx, cy = post.position
    return circle_polygon_depth(cx, cy, post.shape.radius, spot[0], spot[1], local)


@pytest.mark.parametrize("change", ["set_position", "set_angle"])
def test_rejected_move_keeps_the_bodys_predicted_collisions(change):
    """After a rejected set_position/set_angle the body still bounces off the wall it was about to hit."""
    world = World(elasticity=1.0)
    world.add_box(0.9, 0.0, 0.1, 1.0, fixed=True, name="wall")
    world.add_circle((0.2, 0.2), 0.05, fixed=True, name="post")
    box = world.add_box(0.66, 0.45, 0.1, 0.1, mass=1.0, velocity=(1.0, 0.0), name="crate")
    world.run_until(0.12)  # primed; the crate's right face is at x = 0.88 and reaches the wall at t = 0.14
    with pytest.raises(ValueError, match="'crate'.*overlap"):
        if change == "set_position":
            world.set_position(box, (0.2, 0.2))
        else:
            world.set_angle(box, math.pi / 4)  # a corner would reach x = 0.83 + 0.0707 > 0.9
    assert world.overlaps(1e-9) == []
    world.run_until(0.5)
    assert world.stats["collisions"] == 1
    assert box.velocity == (-1.0, 0.0)
    assert box.position == pytest.approx((0.85 - 0.36, 0.5), abs=1e-12)  # bounced at t = 0.14
    assert world.overlaps(1e-9) == []


def test_moving_body_without_mass_fails_at_run_time():
    """A moving body with no mass raises ValueError naming it and 'mass' from the run; nothing is processed."""
    world = World()
    world.add_circle((0.2, 0.5), 0.05, mass=1.0, velocity=(1.0, 0.0), name="ok")
    ghost = world.add_circle((0.8, 0.5), 0.05, velocity=(-1.0, 0.0), name="ghost")
    assert ghost.mass is None
    before = snapshot(world)
    for run in (lambda: world.run_until(1.0), lambda: list(world.events(1.0))):
        with pytest.raises(ValueError) as info:
            run()
        assert "'ghost'" in str(info.value) and "mass" in str(info.value)
        assert snapshot(world) == before
    world.set_mass(ghost, 2.0)
    world.run_until(1.0)
    assert world.time == 1.0 and world.stats["pair_collisions"] == 1


def test_fixed_body_without_mass_is_fine_until_released():
    """A massless fixed body is valid; releasing it (set_fixed False) makes the next run raise naming it."""
    world = World()
    post = world.add_circle((0.5, 0.5), 0.05, fixed=True, name="post")
    world.add_circle((0.2, 0.5), 0.05, mass=1.0, velocity=(1.0, 0.0), name="ball")
    world.run_until(0.5)
    world.set_fixed(post, False)
    before = snapshot(world)
    with pytest.raises(ValueError) as info:
        world.run_until(1.0)
    assert "'post'" in str(info.value) and "mass" in str(info.value)
    assert snapshot(world) == before
    world.set_mass(post, 1.0)
    world.run_until(1.0)
    assert world.time == 1.0


def test_apply_impulse_to_fixed_or_massless_body_raises():
    """apply_impulse on a fixed body or one without a mass raises ValueError naming it; velocity unchanged."""
    world = World()
    post = world.add_circle((0.5, 0.5), 0.05, fixed=True, name="post")
    ghost = world.add_circle((0.2, 0.5), 0.05, name="ghost")
    with pytest.raises(ValueError, match="'post'.*fixed"):
        world.apply_impulse(post, (1.0, 0.0))
    with pytest.raises(ValueError, match="'ghost'.*mass"):
        world.apply_impulse(ghost, (1.0, 0.0))
    assert ghost.velocity == (0.0, 0.0) and post.velocity == (0.0, 0.0)


# -------------------------------------------------------------------- time travel


def test_run_until_into_the_past_is_rejected(scene):
    """run_until(t < now), run(-d) and events(t < now) raise ValueError; time and bodies unchanged."""
    world, _ = scene
    world.run_until(world.time + 0.2)
    past = world.time - 0.1
    check_rejected(world, lambda: world.run_until(past), ValueError, "run_until", "before")
    check_rejected(world, lambda: world.run(-0.1), ValueError, "run", "negative")
    check_rejected(world, lambda: world.events(past), ValueError, "events")


def test_run_until_now_is_a_valid_no_op(scene):
    """run_until(now) is allowed: time stays, bodies stay (positive control for the past check)."""
    world, _ = scene
    world.run_until(world.time + 0.1)
    before = snapshot(world)
    world.run_until(world.time)
    assert snapshot(world)[:3] == before[:3]


def test_at_time_in_the_past_is_rejected(scene):
    """at_time(t < now) raises ValueError naming at_time and 'past'; no timer is registered."""
    world, _ = scene
    world.run_until(world.time + 0.2)
    fired = []
    check_rejected(world, lambda: world.at_time(world.time - 1e-6, fired.append), ValueError, "at_time", "past")
    world.run_until(world.time + 1.0)
    assert fired == []
    assert world.stats["timers"] == 0


# ------------------------------------------------------------------ stale and foreign handles


def _handle_uses(world: World, body: Body, other: Body):
    return [
        ("remove", lambda: world.remove(body)),
        ("set_position", lambda: world.set_position(body, (0.5, 0.5))),
        ("set_velocity", lambda: world.set_velocity(body, (1.0, 0.0))),
        ("set_acceleration", lambda: world.set_acceleration(body, (1.0, 0.0))),
        ("apply_impulse", lambda: world.apply_impulse(body, (1.0, 0.0))),
        ("set_mass", lambda: world.set_mass(body, 2.0)),
        ("set_elasticity", lambda: world.set_elasticity(body, 0.5)),
        ("set_fixed", lambda: world.set_fixed(body, True)),
        ("set_angle", lambda: world.set_angle(body, 0.3)),
        ("set_angular_velocity", lambda: world.set_angular_velocity(body, 0.3)),
        ("on_collision", lambda: world.on_collision(lambda event: None, body=body)),
        ("overlap_depth", lambda: world.overlap_depth(body, other)),
        ("overlap_depth (second)", lambda: world.overlap_depth(other, body)),
    ]


def test_using_a_removed_body_raises_naming_it(scene):
    """Every World method and Body property given a removed body raises ValueError saying it was removed."""
    world, bodies = scene
    tri, ball = bodies["tri"], bodies["ball"]
    world.remove(tri)
    assert not tri.alive
    for label, call in _handle_uses(world, tri, ball):
        try:
            check_rejected(world, call, ValueError, "'tri'", "removed")
        except AssertionError as failure:
            raise AssertionError(f"{label}: {failure}") from None
    for attribute in ("position", "velocity", "acceleration", "mass", "is_fixed", "elasticity", "angle", "vertices"):
        with pytest.raises(ValueError, match="'tri'.*removed"):
            getattr(tri, attribute)
    for attribute, value in (("position", (0.5, 0.5)), ("velocity", (1.0, 0.0)), ("mass", 1.0)):
        with pytest.raises(ValueError, match="'tri'.*removed"):
            setattr(tri, attribute, value)


def test_using_a_body_of_another_world_raises_naming_it(scene):
    """Every World method given a body of another world raises ValueError saying so; neither world changes."""
    world, bodies = scene
    other_world = World()
    stranger = other_world.add_circle((0.5, 0.5), 0.05, mass=1.0, name="stranger")
    other_before = snapshot(other_world)
    for label, call in _handle_uses(world, stranger, bodies["ball"]):
        try:
            check_rejected(world, call, ValueError, "'stranger'", "another world")
        except AssertionError as failure:
            raise AssertionError(f"{label}: {failure}") from None
    assert snapshot(other_world) == other_before
    assert stranger.alive and len(other_world) == 1


def test_failed_additions_do_not_consume_visible_state(scene):
    """After many rejected additions the world's body tuple is identical and new bodies still get fresh ids."""
    world, _ = scene
    before = world.bodies
    for bad in (lambda: world.add_circle((0.5, 0.45), -1.0, mass=1.0), lambda: world.add_polygon([(0, 0), (1, 1), (2, 2)], mass=1.0)):
        with pytest.raises(ValueError):
            bad()
    assert world.bodies == before
    new = world.add_circle((0.5, 0.45), 0.01, mass=1.0, name="new")
    assert new.id not in {b.id for b in before}
    assert world.bodies == before + (new,)
