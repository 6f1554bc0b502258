"""Behaviour of pge.object methods: motion state, fixing, mass, impulses, bookkeeping, extensions."""

from __future__ import annotations

import math

import pytest
from classic_support import session, walls  # noqa: F401 (session: the fixture every test uses)

import pge

pytestmark = pytest.mark.usefixtures("session")


def test_constructors_make_the_documented_kinds():
    """box/poly3..poly6/polygon are box_t, circle circle_t, other levels eye-candy, rgb colour_t."""
    c = pge.rgb(0.1, 0.2, 0.3)
    assert c.type == pge.colour_t and c.get_colour() is c
    assert pge.white().type == pge.colour_t
    assert pge.box(0.1, 0.1, 0.1, 0.1, c).type == pge.box_t
    assert pge.poly3(0.3, 0.3, 0.4, 0.3, 0.35, 0.4, c).type == pge.box_t
    assert pge.poly4(0.5, 0.5, 0.6, 0.5, 0.6, 0.6, 0.5, 0.6, c).type == pge.box_t
    assert pge.circle(0.8, 0.8, 0.05, c).type == pge.circle_t
    assert pge.box(0.1, 0.1, 0.1, 0.1, c, 1).type == pge.fb_box_t
    assert pge.circle(0.1, 0.1, 0.1, c, -2).type == pge.fb_circle_t
    assert pge.text(0.1, 0.1, "hi", c, 20, 3).type == pge.fb_text_t
    assert isinstance(c, pge.object)


def test_chaining_returns_self_and_put_methods_return_none():
    """Configuring methods return the object; put_*, set_width and rm return None (as PGE)."""
    ball = pge.circle(0.5, 0.5, 0.05, pge.white())
    for result in (
        ball.mass(1),
        ball.velocity(0.1, 0.2),
        ball.accel(0.0, 0.1),
        ball.on_collision(lambda o, e: None),
        ball.on_collision_with([], lambda o, e: None),
        ball.set_param(3),
        ball.set_colour(pge.white()),
        ball.set_visible(True),
        ball.set_alpha(0.5),
        ball.elasticity(0.5),
        ball.rotate(0.1),
        ball.rvel(0.2),
        ball.set_gravity(0.0),
        ball.apply_impulse([1, 0], 0.1),
        ball.fix(),
        ball.unfix(),
    ):
        assert result is ball
    for result in (ball.put_xvel(1), ball.put_yvel(1), ball.put_xaccel(0), ball.put_yaccel(0), ball.set_width(2)):
        assert result is None
    assert ball.rm() is None


def test_velocity_reads_back_without_damping_when_switched_off():
    """With velocity_damping(1.0), reading or setting a velocity never damps it (by default it
    loses 2 % per read, as in the original: tests/test_classic_games.py)."""
    pge.velocity_damping(1.0)
    ball = pge.circle(0.5, 0.5, 0.05, pge.white()).mass(1).velocity(0.3, -0.2)
    pge.run(0.1)
    for _ in range(5):
        assert (ball.get_xvel(), ball.get_yvel()) == (0.3, -0.2)
    ball.put_xvel(0.7)
    assert (ball.get_xvel(), ball.get_yvel()) == (0.7, -0.2)
    ball.put_yvel(0.1)
    assert (ball.get_xvel(), ball.get_yvel()) == (0.7, 0.1)


def test_motion_is_closed_form_with_gravity_and_own_acceleration():
    """Position after t follows x0 + v t + a t^2 / 2 with a = own acceleration + gravity."""
    ball = pge.circle(0.5, 0.5, 0.02, pge.white()).mass(1).velocity(0.1, 0.2).accel(0.3, 0.4)
    pge.gravity(-1.0)
    pge.run(0.25)
    t = 0.25
    assert abs(ball.get_xpos() - (0.5 + 0.1 * t + 0.5 * 0.3 * t * t)) < 1e-12
    assert abs(ball.get_ypos() - (0.5 + 0.2 * t + 0.5 * (0.4 - 1.0) * t * t)) < 1e-12
    assert (ball.get_xaccel(), ball.get_yaccel()) == (0.3, 0.4)
    ball.put_xaccel(-0.5)
    ball.put_yaccel(0.25)
    assert (ball.get_xaccel(), ball.get_yaccel()) == (-0.5, 0.25)


def test_fix_holds_the_object_and_unfix_resumes_its_velocity():
    """A fixed object stays put under gravity; unfix() moves it again with its stored velocity."""
    pge.velocity_damping(1.0)  # exact reads
    pge.gravity()
    ball = pge.circle(0.5, 0.5, 0.05, pge.white()).mass(1).velocity(0.2, 0.0)
    pge.run(0.1)
    ball.fix()
    assert ball.is_fixed()
    where = (ball.get_xpos(), ball.get_ypos())
    pge.run(0.2)
    assert (ball.get_xpos(), ball.get_ypos()) == where
    ball.unfix()
    assert not ball.is_fixed()
    vy_at_fix = -9.81 * 0.1
    assert abs(ball.get_xvel() - 0.2) < 1e-15 and abs(ball.get_yvel() - vy_at_fix) < 1e-12
    pge.run(0.05)
    assert abs(ball.get_xpos() - (where[0] + 0.2 * 0.05)) < 1e-12


def test_mass_is_remembered():
    """get_mass() is None until mass() is called, then the value given."""
    box = pge.box(0.2, 0.2, 0.1, 0.1, pge.white())
    assert box.get_mass() is None
    assert box.mass(2.5).get_mass() == 2.5


def test_apply_impulse_changes_velocity_by_magnitude_over_mass():
    """apply_impulse(v, m) adds m / mass along v normalised, for circles and polygons; fixed: nothing."""
    pge.velocity_damping(1.0)  # exact reads
    ball = pge.circle(0.3, 0.5, 0.05, pge.white()).mass(2.0).velocity(0.1, 0.0)
    crate = pge.box(0.6, 0.4, 0.1, 0.1, pge.white()).mass(0.5)
    post = pge.circle(0.8, 0.8, 0.05, pge.white()).fix()
    pge.run(0.01)
    ball.apply_impulse([3.0, 4.0], 1.0)
    assert abs(ball.get_xvel() - (0.1 + 0.3)) < 1e-15 and abs(ball.get_yvel() - 0.4) < 1e-15
    crate.apply_impulse([0.0, -2.0], 0.25)
    assert crate.get_xvel() == 0.0 and abs(crate.get_yvel() + 0.5) < 1e-15
    post.apply_impulse([1.0, 0.0], 5.0)
    assert not post.moving_towards(1.0, 0.8) and post.is_fixed()


def test_moving_towards():
    """moving_towards is True when the velocity points at the point, False when fixed."""
    ball = pge.circle(0.5, 0.5, 0.05, pge.white()).mass(1).velocity(0.5, 0.0)
    assert ball.moving_towards(0.9, 0.5)
    assert not ball.moving_towards(0.1, 0.5)
    ball.fix()
    assert not ball.moving_towards(0.9, 0.5)


def test_positions_are_centres_and_centroids():
    """get_xpos/get_ypos of a polygon is its area centroid; get_unit_coord is [x, y]."""
    tri = pge.poly3(0.0, 0.0, 0.3, 0.0, 0.0, 0.3, pge.white()).fix()
    assert abs(tri.get_xpos() - 0.1) < 1e-15 and abs(tri.get_ypos() - 0.1) < 1e-15
    ball = pge.circle(0.6, 0.7, 0.05, pge.white()).fix()
    assert ball.get_unit_coord() == [0.6, 0.7]


def test_params_widths_colours():
    """set_param/get_param keep any value, box() stores its width, set_colour changes the colour."""
    red, blue = pge.rgb(1, 0, 0), pge.rgb(0, 0, 1)
    crate = pge.box(0.1, 0.1, 0.2, 0.1, red)
    assert crate.get_param() is None
    assert crate.set_param({"hits": 3}).get_param() == {"hits": 3}
    assert crate.get_width() == 0.2
    crate.set_width(0.7)
    assert crate.get_width() == 0.7
    assert crate.get_colour() is red
    assert crate.set_colour(blue).get_colour() is blue


def test_colours_are_new_objects_hashable_by_identity():
    """Each rgb() call is a new colour; colours work as dict keys."""
    a, b = pge.rgb(0.5, 0.5, 0.5), pge.rgb(0.5, 0.5, 0.5)
    assert a is not b and len({a: 1, b: 2}) == 2


def test_eye_candy_takes_no_part_in_physics():
    """A ball falls straight through a foreground box and a background circle."""
    pge.gravity()
    pge.box(0.0, 0.3, 1.0, 0.05, pge.white(), 1)
    pge.circle(0.5, 0.6, 0.1, pge.white(), -1)
    hits = []
    ball = pge.circle(0.5, 0.9, 0.02, pge.white()).mass(1).on_collision(lambda o, e: hits.append(e))
    pge.run(0.4)
    assert hits == []
    assert abs(ball.get_ypos() - (0.9 - 0.5 * 9.81 * 0.16)) < 1e-12


def test_polygons_of_any_vertex_count():
    """poly5, poly6 and polygon(points) make convex polygons with that many corners."""
    c = pge.white()
    pentagon = pge.poly5(0.1, 0.1, 0.2, 0.1, 0.23, 0.18, 0.15, 0.23, 0.07, 0.18, c).fix()
    hexagon = pge.poly6(0.5, 0.1, 0.6, 0.1, 0.65, 0.18, 0.6, 0.26, 0.5, 0.26, 0.45, 0.18, c).fix()
    octagon = pge.polygon(
        [(0.8 + 0.05 * math.cos(k * math.pi / 4), 0.8 + 0.05 * math.sin(k * math.pi / 4)) for k in range(8)], c
    ).fix()
    pge.run(0.01)
    assert [len(o.body.vertices) for o in (pentagon, hexagon, octagon)] == [5, 6, 8]
    with pytest.raises(ValueError, match="convex"):
        pge.polygon([(0.1, 0.1), (0.3, 0.1), (0.2, 0.15), (0.3, 0.3), (0.1, 0.3)], c)


def test_object_elasticity_sets_the_bounce():
    """A ball of elasticity 0.5 leaves the floor at half its impact speed; pge.elasticity sets the default."""
    pge.velocity_damping(1.0)  # exact reads
    floor = walls()[0]
    ball = pge.circle(0.5, 0.2, 0.05, pge.white()).mass(1).velocity(0.0, -1.0).elasticity(0.5)
    speeds = []
    ball.on_collision(lambda o, e: speeds.append(o.get_yvel()))
    pge.run(0.2)
    assert abs(speeds[0] - 0.5) < 1e-12
    pge.elasticity(0.25)  # objects without their own elasticity follow the default
    assert floor.body.elasticity == 0.25 and ball.body.elasticity == 0.5


def test_rotation_state_is_stored_and_reported():
    """rotate/rvel set the angle and angular velocity; a free body then turns at angle0 + w t, get_angle
    reports it and its corners turn with it; a fixed rotated body keeps its angle."""
    crate = pge.box(0.4, 0.4, 0.2, 0.2, pge.white()).mass(1).rotate(math.pi / 4).rvel(2.0)
    ramp = pge.box(0.0, 0.0, 0.3, 0.02, pge.white()).fix().rotate(-0.35)
    assert crate.get_angle() == math.pi / 4 and crate.get_rvel() == 2.0
    pge.run(0.0)  # the bodies enter the World
    assert crate.get_angle() == math.pi / 4 and crate.get_rvel() == 2.0
    lowest = min(y for _, y in crate.body.vertices)
    assert abs(lowest - (0.5 - 0.1 * math.sqrt(2))) < 1e-12
    pge.run(0.01)
    angle = math.pi / 4 + 2.0 * 0.01
    assert abs(crate.get_angle() - angle) < 1e-12 and crate.get_rvel() == 2.0
    assert abs(crate.get_xpos() - 0.5) < 1e-12 and abs(crate.get_ypos() - 0.5) < 1e-12  # it turns about its centre
    # a square of half-side 0.1 at angle a reaches 0.1 (|cos a| + |sin a|) below its centre
    lowest = min(y for _, y in crate.body.vertices)
    assert abs(lowest - (0.5 - 0.1 * (abs(math.cos(angle)) + abs(math.sin(angle))))) < 1e-12
    assert ramp.get_angle() == -0.35 and ramp.get_rvel() == 0.0


def test_per_object_gravity_adds_to_the_worlds():
    """set_gravity(g) adds g to the world's gravity for that object only."""
    pge.gravity()
    floating = pge.circle(0.3, 0.5, 0.02, pge.white()).mass(1).set_gravity(9.81)
    heavy = pge.circle(0.7, 0.5, 0.02, pge.white()).mass(1).set_gravity(-9.81)
    pge.run(0.2)
    assert floating.get_ypos() == 0.5 and floating.get_gravity() == 9.81
    assert abs(heavy.get_ypos() - (0.5 - 0.5 * 2 * 9.81 * 0.04)) < 1e-12
    assert heavy.get_yaccel() == 0.0  # own acceleration excludes gravity


def test_gravity_change_takes_effect_mid_run():
    """pge.gravity() called from a timer changes the motion from that moment on."""
    ball = pge.circle(0.5, 0.8, 0.02, pge.white()).mass(1)
    pge.at_time(0.1, lambda e, o: pge.gravity(-2.0))
    pge.run(0.3)
    assert abs(ball.get_ypos() - (0.8 - 0.5 * 2.0 * 0.2**2)) < 1e-12


def test_rm_removes_from_physics_and_drawing():
    """rm() takes a level-0 object out of the World and an eye-candy object out of its level."""
    ball = pge.circle(0.5, 0.5, 0.05, pge.white()).mass(1)
    label = pge.text(0.1, 0.1, "x", pge.white(), 10, 1)
    pge.run(0.01)
    world = pge.classic._STATE.world
    assert len(world) == 1
    ball.rm()
    ball.rm()  # a second rm is a no-op
    label.rm()
    assert ball.deleted and len(world) == 0
    assert label not in pge.classic._STATE.levels[1]


def test_spring_methods_need_a_spring():
    """draw, end, mid and when are spring methods: on a circle they raise TypeError (springs: test_springs.py)."""
    a = pge.circle(0.3, 0.5, 0.02, pge.white()).fix()
    b = pge.circle(0.6, 0.5, 0.02, pge.white()).mass(1)
    for call in (lambda: a.draw(pge.white(), 0.01), lambda: a.end(pge.white()), lambda: a.mid(pge.white())):
        with pytest.raises(TypeError, match="circle object"):
            call()
    with pytest.raises(TypeError, match="when: you cannot give a length callback to a circle object"):
        a.when(0.2, lambda e, s: None)
    assert pge.spring(a, b, 100.0, 1.0).type == pge.spring_t


def test_vector_utilities():
    """normalise, magnitude, sub_coord and toFloat compute what PGE's did."""
    assert pge.normalise([3.0, 4.0]) == [0.6, 0.8]
    assert pge.magnitude([3.0, 4.0]) == 5.0
    assert pge.sub_coord([1.0, 2.0], [0.5, 0.25]) == [0.5, 1.75]
    assert pge.toFloat((1, 1, 4)) == 1.25 and pge.toFloat((2, 0, 0)) == 2.0


def test_pixel_coordinates_follow_the_window():
    """pyg_to_unit_coord and flip map pixels of display_set_mode's window to the unit square, y up."""
    size = [800, 400]
    pge.display_set_mode(size)
    assert size == [800, 400]  # the caller's list is not changed (the original set r[1] = r[0])
    assert pge.pyg_to_unit_coord([200, 300]) == [0.5, 0.25]
    assert pge.flip(100) == 300


def test_dump_world_prints_every_object(capsys):
    """dump_world prints one line per level-0 object with its kind and state."""
    pge.box(0.0, 0.0, 1.0, 0.1, pge.white()).fix()
    pge.circle(0.5, 0.5, 0.05, pge.white()).mass(2)
    pge.dump_world()
    out = capsys.readouterr().out
    assert "fixed polygon" in out and "movable circle at (0.5, 0.5) radius 0.05 mass 2.0" in out
