"""Analytic answers through the World API: drop times, bounce series, elastic exchanges,
corner reflections, polygon landings and the restitution rules.

Collision records are read from ``world.events()``: when a Collision is yielded
the world's time is the collision time and bodies show their velocities (and
spins) just after the bounce. Before the bounce the motion is known in closed
form from the initial conditions (nothing else has happened yet in these scenes).
"""

from __future__ import annotations

import math
from itertools import pairwise

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from strategies import masses, regular_polygon, vectors

from pge import Collision, World

REL = 1e-12


class After(dict):
    """Velocities by body id just after a collision; ``spin`` holds the angular velocities by id."""

    def __init__(self, bodies):
        super().__init__((body.id, body.velocity) for body in bodies)
        self.spin = {body.id: body.angular_velocity for body in bodies}


def collisions(world, count, until=10.0):
    """The first ``count`` Collision records (each with the velocities and spins of the bodies just after it)."""
    found = []
    for event in world.events(until):
        if isinstance(event, Collision):
            found.append((event, After(world.bodies)))
            if len(found) == count:
                break
    assert len(found) == count, f"expected {count} collisions, saw {len(found)}"
    return found


def first_collision(world, until=10.0):
    return collisions(world, 1, until)[0]


def close(a, b, tol):
    return all(abs(x - y) <= tol for x, y in zip(a, b))


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1]


def cross(a, b):
    return a[0] * b[1] - a[1] * b[0]


def point_velocity(v, w, r):
    """Velocity of the material point at lever arm ``r`` of a body moving at ``v`` and turning at ``w``."""
    return (v[0] - w * r[1], v[1] + w * r[0])


# ------------------------------------------------------------------ dropped ball


@pytest.mark.parametrize(
    "h,g",
    [(1e-3, 9.81), (0.1, 9.81), (0.45, 9.81), (0.3, 1.0), (0.3, 100.0), (2.5, 9.81), (0.05, 1000.0)],
)
def test_ball_released_at_rest_first_touches_the_floor_at_sqrt_2h_over_g(h, g):
    """A ball whose lowest point is h above a fixed floor touches it at sqrt(2h/g) (relative 1e-12)."""
    r = 0.05
    world = World(gravity=(0.0, -g), bounds=(-1.0, -1.0, 2.0, 4.0))
    floor = world.add_box(-1.0, -0.2, 3.0, 0.2, fixed=True)  # top face at y = 0
    ball = world.add_circle((0.5, h + r), r, mass=2.0, elasticity=0.9)
    event, after = first_collision(world)
    expected = math.sqrt(2.0 * h / g)
    assert abs(event.time - expected) <= REL * expected
    assert {event.a, event.b} == {ball, floor}
    # the record: contact at the bottom of the ball, normal along y, approach speed sqrt(2 g h)
    sign = 1.0 if event.a is ball else -1.0
    assert close(event.normal, (0.0, sign), 1e-15)
    assert close(event.point, (0.5, 0.0), 1e-12)
    speed = math.sqrt(2.0 * g * h)
    assert abs(event.approach_speed - speed) <= REL * speed
    assert abs(event.impulse - 2.0 * 1.9 * speed) <= REL * 2.0 * 1.9 * speed
    assert after[ball.id][0] == 0.0 and abs(after[ball.id][1] - 0.9 * speed) <= REL * speed


@pytest.mark.parametrize("e", [0.5, 0.8, 0.9, 0.98])
def test_bounce_intervals_shrink_by_exactly_e(e):
    """With ball and floor of elasticity e, each interval between bounces is e times the previous (1e-9)."""
    world = World(gravity=(0.0, -9.81), elasticity=e)
    world.add_box(-1.0, -0.2, 3.0, 0.2, fixed=True)
    world.add_circle((0.5, 0.35), 0.05, mass=1.0)
    times = [event.time for event, _ in collisions(world, 6)]
    intervals = [b - a for a, b in pairwise(times)]
    assert len(intervals) == 5
    for before, after in pairwise(intervals):
        assert abs(after / before - e) <= 1e-9
    # and the first interval is the flight time of a ball leaving at e sqrt(2 g h)
    first = 2.0 * e * math.sqrt(2.0 * 9.81 * 0.3) / 9.81
    assert abs(intervals[0] - first) <= 1e-9 * first


# ------------------------------------------------------------------ circles


@pytest.mark.parametrize("u1,u2", [(1.0, 0.0), (0.7, -0.3), (2.0, 1.0), (0.25, -1.5)])
def test_equal_masses_head_on_elastic_swap_velocities(u1, u2):
    """Equal masses meeting head-on with e = 1 exchange their velocities (1e-12)."""
    world = World(elasticity=1.0)
    left = world.add_circle((0.3, 0.5), 0.05, mass=1.5, velocity=(u1, 0.0))
    right = world.add_circle((0.7, 0.5), 0.05, mass=1.5, velocity=(u2, 0.0))
    event, after = first_collision(world)
    assert abs(event.time - 0.3 / (u1 - u2)) <= REL * event.time
    assert close(after[left.id], (u2, 0.0), REL)
    assert close(after[right.id], (u1, 0.0), REL)


@st.composite
def oblique_pairs(draw):
    """Two circles set on a collision course with a random impact parameter and random masses."""
    ra = draw(st.floats(0.02, 0.1))
    rb = draw(st.floats(0.02, 0.1))
    reach = ra + rb
    ma, mb = draw(masses()), draw(masses())
    w = draw(st.floats(0.1, 3.0))  # closing speed
    heading = draw(st.floats(0.0, 2.0 * math.pi))
    u = (math.cos(heading), math.sin(heading))
    impact = draw(st.floats(-0.95, 0.95)) * reach
    back = reach + draw(st.floats(1e-3, 0.3))
    b_pos = (0.5, 0.5)
    a_pos = (b_pos[0] - back * u[0] - impact * u[1], b_pos[1] - back * u[1] + impact * u[0])
    vb = draw(vectors(2.0))
    va = (vb[0] + w * u[0], vb[1] + w * u[1])
    return {"ra": ra, "rb": rb, "ma": ma, "mb": mb, "a_pos": a_pos, "b_pos": b_pos, "va": va, "vb": vb}


@settings(deadline=None, max_examples=60)
@given(oblique_pairs())
def test_oblique_elastic_collisions_conserve_momentum_and_energy(pair):
    """Random elastic circle collisions conserve momentum and kinetic energy to 1e-12 relative."""
    world = World(elasticity=1.0, bounds=(-5.0, -5.0, 5.0, 5.0))
    a = world.add_circle(pair["a_pos"], pair["ra"], mass=pair["ma"], velocity=pair["va"])
    b = world.add_circle(pair["b_pos"], pair["rb"], mass=pair["mb"], velocity=pair["vb"])
    ma, mb, va, vb = pair["ma"], pair["mb"], pair["va"], pair["vb"]
    p_before = (ma * va[0] + mb * vb[0], ma * va[1] + mb * vb[1])
    e_before = 0.5 * ma * dot(va, va) + 0.5 * mb * dot(vb, vb)
    event, after = first_collision(world)
    va2, vb2 = after[a.id], after[b.id]
    p_after = (ma * va2[0] + mb * vb2[0], ma * va2[1] + mb * vb2[1])
    e_after = 0.5 * ma * dot(va2, va2) + 0.5 * mb * dot(vb2, vb2)
    scale = ma * math.hypot(*va) + mb * math.hypot(*vb)
    assert close(p_after, p_before, REL * scale)
    assert abs(e_after - e_before) <= REL * e_before
    # the impulse acts along the line of centres at contact
    pa, pb = a.position, b.position
    n = (event.normal[0], event.normal[1])
    line = ((pa[0] - pb[0]) / math.dist(pa, pb), (pa[1] - pb[1]) / math.dist(pa, pb))
    if event.a is b:
        line = (-line[0], -line[1])
    assert close(n, line, 1e-12)
    dva = (va2[0] - va[0], va2[1] - va[1])
    assert abs(dva[0] * n[1] - dva[1] * n[0]) <= REL * (math.hypot(*va) + math.hypot(*vb))


# ------------------------------------------------------------------ corner reflection


CORNER_CASES = [
    # label, offset (fraction of r, perpendicular to the approach), speed, gravity
    ("square corner, straight at it", 0.0, 1.0, 0.0),
    ("square corner, offset 0.3 r", 0.3, 1.0, 0.0),
    ("square corner, offset -0.6 r", -0.6, 2.0, 0.0),
    ("square corner, offset 0.2 r, under gravity", 0.2, 3.0, -9.81),
    ("square corner, offset -0.4 r, under gravity", -0.4, 4.0, -9.81),
]


@pytest.mark.parametrize("label,offset,speed,g", CORNER_CASES, ids=[c[0] for c in CORNER_CASES])
def test_ball_hitting_a_fixed_corner_leaves_along_the_corner_normal(label, offset, speed, g):
    """A ball striking a fixed polygon's corner is reflected about the line from the corner to its centre."""
    r = 0.05
    world = World(gravity=(0.0, g), elasticity=1.0)
    box = world.add_box(0.5, 0.5, 0.2, 0.2, fixed=True)  # corner of interest at (0.5, 0.5)
    corner = (0.5, 0.5)
    s = 1.0 / math.sqrt(2.0)
    start = (0.5 - 0.3 * s + offset * r * s, 0.5 - 0.3 * s - offset * r * s)
    # aimed along the diagonal; under gravity lifted so that the parabola still meets the corner
    flight = 0.25 / speed
    v0 = (speed * s, speed * s - 0.5 * g * flight)
    ball = world.add_circle(start, r, mass=1.0, velocity=v0)
    event, after = first_collision(world)
    t = event.time
    assert {event.a, event.b} == {ball, box}
    centre = ball.position
    # geometry: the centre is r from the corner, in the corner's normal cone (not an edge hit)
    to_centre = (centre[0] - corner[0], centre[1] - corner[1])
    distance = math.hypot(*to_centre)
    assert abs(distance - r) <= 1e-9
    n = (to_centre[0] / distance, to_centre[1] / distance)
    assert n[0] < 0.0 and n[1] < 0.0
    # the record agrees with the geometry
    sign = 1.0 if event.a is ball else -1.0
    assert close((sign * event.normal[0], sign * event.normal[1]), n, 1e-9)
    assert close(event.point, corner, 1e-12)
    # outgoing velocity: the incoming one reflected about the corner-to-centre line
    v_in = (v0[0], v0[1] + g * t)
    vn = dot(v_in, n)
    assert vn < 0.0
    expected = (v_in[0] - 2.0 * vn * n[0], v_in[1] - 2.0 * vn * n[1])
    assert close(after[ball.id], expected, 1e-9)
    assert abs(math.hypot(*after[ball.id]) - math.hypot(*v_in)) <= 1e-12


# ------------------------------------------------------------------ polygons


@pytest.mark.parametrize("h,e", [(0.2, 0.9), (0.05, 1.0), (0.4, 0.5)])
def test_box_falling_flat_onto_a_fixed_box_lands_at_the_analytic_time_and_bounces_straight_up(h, e):
    """A box dropped flat from h onto a fixed box touches at sqrt(2h/g) and leaves straight up at e times its speed."""
    g = 9.81
    world = World(gravity=(0.0, -g), elasticity=e)
    floor = world.add_box(0.0, 0.0, 1.0, 0.1, fixed=True)
    box = world.add_box(0.4, 0.1 + h, 0.2, 0.1, mass=3.0)
    event, after = first_collision(world)
    expected = math.sqrt(2.0 * h / g)
    assert abs(event.time - expected) <= REL * expected
    assert {event.a, event.b} == {box, floor}
    sign = 1.0 if event.a is box else -1.0
    assert close((sign * event.normal[0], sign * event.normal[1]), (0.0, 1.0), 1e-15)
    assert abs(event.point[1] - 0.1) <= 1e-12 and 0.4 - 1e-12 <= event.point[0] <= 0.6 + 1e-12
    vx, vy = after[box.id]
    assert vx == 0.0
    assert abs(vy - e * g * event.time) <= REL * g * event.time
    assert abs(box.position[1] - 0.15) <= 1e-12  # its bottom on the floor's top at the contact


@pytest.mark.parametrize("m1,m2,u1,u2", [(1.0, 1.0, 1.0, 0.0), (1.0, 3.0, 1.5, -0.5), (4.0, 0.5, 0.2, -1.0)])
def test_circle_hitting_a_moving_box_face_follows_the_1d_elastic_formulas(m1, m2, u1, u2):
    """A circle striking a moving box's flat face head-on exchanges momentum as two 1-D elastic bodies."""
    world = World(elasticity=1.0)
    ball = world.add_circle((0.2, 0.5), 0.05, mass=m1, velocity=(u1, 0.0))
    box = world.add_box(0.6, 0.4, 0.2, 0.2, mass=m2, velocity=(u2, 0.0))
    event, after = first_collision(world)
    assert abs(event.time - 0.35 / (u1 - u2)) <= REL * event.time
    v1 = ((m1 - m2) * u1 + 2.0 * m2 * u2) / (m1 + m2)
    v2 = ((m2 - m1) * u2 + 2.0 * m1 * u1) / (m1 + m2)
    scale = abs(u1) + abs(u2)
    assert close(after[ball.id], (v1, 0.0), REL * scale)
    assert close(after[box.id], (v2, 0.0), REL * scale)


def _exchange_checks(event, a, b, ma, mb, va, vb, after, e, wa=0.0, wb=0.0):
    """A frictionless rigid-body bounce of a and b (velocities va, vb and spins wa, wb just before).

    Linear momentum and angular momentum about a fixed point are conserved;
    each body's linear momentum changes along the normal only, and its spin by
    ``I dw = r x J`` with ``J = m dv`` and ``r`` from its centroid to the
    contact point; the normal relative speed of the two contact points is
    reversed times e; with e = 1 the kinetic energy (with rotation) is conserved.
    Returns the normal from b towards a.
    """
    va2, vb2 = after[a.id], after[b.id]
    wa2, wb2 = after.spin[a.id], after.spin[b.id]
    ia, ib = a.inertia, b.inertia
    ca, cb = a.position, b.position  # positions do not jump at the bounce
    p = event.point
    ra = (p[0] - ca[0], p[1] - ca[1])
    rb = (p[0] - cb[0], p[1] - cb[1])
    scale = ma * math.hypot(*va) + mb * math.hypot(*vb)
    p_before = (ma * va[0] + mb * vb[0], ma * va[1] + mb * vb[1])
    p_after = (ma * va2[0] + mb * vb2[0], ma * va2[1] + mb * vb2[1])
    assert close(p_after, p_before, REL * scale)
    # angular momentum about the origin: sum of m (c x v) + I w
    l_before = ma * cross(ca, va) + ia * wa + mb * cross(cb, vb) + ib * wb
    l_after = ma * cross(ca, va2) + ia * wa2 + mb * cross(cb, vb2) + ib * wb2
    arm = max(math.hypot(*ca), math.hypot(*cb), math.hypot(*ra), math.hypot(*rb))
    l_scale = scale * arm + abs(ia * wa) + abs(ib * wb) + abs(ia * wa2) + abs(ib * wb2)
    assert abs(l_after - l_before) <= REL * l_scale
    n = event.normal if event.a is a else (-event.normal[0], -event.normal[1])  # from b towards a
    assert abs(math.hypot(*n) - 1.0) <= 1e-15
    for m, inertia, r, v, v2, w, w2 in ((ma, ia, ra, va, va2, wa, wa2), (mb, ib, rb, vb, vb2, wb, wb2)):
        j = (m * (v2[0] - v[0]), m * (v2[1] - v[1]))  # the impulse this body received
        assert abs(cross(j, n)) <= REL * scale  # no tangential change (no friction)
        assert abs(inertia * (w2 - w) - cross(r, j)) <= REL * scale * math.hypot(*r)  # I dw = r x J
    ua = point_velocity(va, wa, ra)
    ub = point_velocity(vb, wb, rb)
    ua2 = point_velocity(va2, wa2, ra)
    ub2 = point_velocity(vb2, wb2, rb)
    closing = dot((ua[0] - ub[0], ua[1] - ub[1]), n)
    opening = dot((ua2[0] - ub2[0], ua2[1] - ub2[1]), n)
    assert closing < 0.0
    assert abs(opening + e * closing) <= REL * abs(closing)
    assert abs(event.approach_speed + closing) <= REL * abs(closing)
    if e == 1.0:
        ke = lambda v1, w1, v2, w2: (
            0.5 * ma * dot(v1, v1) + 0.5 * ia * w1 * w1 + 0.5 * mb * dot(v2, v2) + 0.5 * ib * w2 * w2
        )
        before = ke(va, wa, vb, wb)
        assert abs(ke(va2, wa2, vb2, wb2) - before) <= REL * before
    return n


@settings(deadline=None, max_examples=40)
@given(
    st.integers(3, 8),
    st.floats(0.0, 2.0 * math.pi),
    masses(),
    masses(),
    vectors(1.0),
    st.floats(-0.8, 0.8),
    st.sampled_from([1.0, 0.7]),
)
def test_circle_hitting_a_moving_polygon_exchanges_momentum(sides, angle, m1, m2, vp, aim, e):
    """A circle thrown at a moving polygon: linear and angular momentum conserved, impulse along the normal,
    contact-point normal speed ratio e."""
    world = World(elasticity=e, bounds=(-5.0, -5.0, 5.0, 5.0))
    polygon = world.add_polygon(regular_polygon(sides, 0.1, (0.6, 0.5), angle), mass=m2, velocity=vp)
    # aim at the polygon (in its frame) with a random offset
    rel = (1.5, aim * 0.1)
    vc = (vp[0] + rel[0], vp[1] + rel[1])
    ball = world.add_circle((0.3, 0.5), 0.04, mass=m1, velocity=vc)
    event, after = first_collision(world)
    assert {event.a, event.b} == {ball, polygon}
    n = _exchange_checks(event, ball, polygon, m1, m2, vc, vp, after, e)  # with energy for e = 1
    # the normal is the circle's centre-to-contact direction (reversed): the contact point is r away
    centre = ball.position
    assert abs(math.dist(centre, event.point) - 0.04) <= 1e-9
    assert close(((centre[0] - event.point[0]) / 0.04, (centre[1] - event.point[1]) / 0.04), n, 1e-9)


@pytest.mark.parametrize("e", [1.0, 0.6])
def test_two_moving_boxes_face_to_face_exchange_momentum(e):
    """Two moving boxes meeting flat faces first: 1-D impulse formulas along x, y velocities untouched."""
    world = World(elasticity=e)
    m1, m2 = 2.0, 0.5
    u1, u2 = (1.0, 0.3), (-0.5, 0.3)
    left = world.add_box(0.1, 0.4, 0.2, 0.2, mass=m1, velocity=u1)
    right = world.add_box(0.6, 0.45, 0.2, 0.1, mass=m2, velocity=u2)
    event, after = first_collision(world)
    assert abs(event.time - 0.3 / 1.5) <= REL * event.time
    n = _exchange_checks(event, left, right, m1, m2, u1, u2, after, e)
    assert close(n, (-1.0, 0.0), 1e-15)
    j = (1.0 + e) * (u1[0] - u2[0]) / (1.0 / m1 + 1.0 / m2)
    assert close(after[left.id], (u1[0] - j / m1, 0.3), REL * 2)
    assert close(after[right.id], (u2[0] + j / m2, 0.3), REL * 2)
    assert abs(event.impulse - j) <= REL * j


def test_moving_triangle_corner_strikes_a_moving_box_face():
    """A triangle's corner hitting a moving box's face: normal is the face normal, linear and angular momentum
    and kinetic energy (with rotation) are conserved."""
    world = World(elasticity=1.0)
    m1, m2 = 1.0, 2.5
    v1, v2 = (1.2, 0.4), (-0.2, 0.1)
    tri = world.add_polygon([(0.1, 0.45), (0.25, 0.5), (0.1, 0.55)], mass=m1, velocity=v1)  # tip at (0.25, 0.5)
    box = world.add_box(0.5, 0.3, 0.2, 0.4, mass=m2, velocity=v2)
    event, after = first_collision(world)
    n = _exchange_checks(event, tri, box, m1, m2, v1, v2, after, 1.0)
    assert close(n, (-1.0, 0.0), 1e-15)
    t = event.time
    assert abs(t - 0.25 / 1.4) <= REL * t
    assert close(event.point, (0.25 + v1[0] * t, 0.5 + v1[1] * t), 1e-12)
    # the tip strikes off the box's centre line (they drift apart in y at 0.3), so the box turns
    assert abs(after.spin[box.id]) > 1e-3


# ------------------------------------------------------------------ restitution rules


def _normal_speed_ratio(world, ea=None, eb=None):
    options_a = {} if ea is None else {"elasticity": ea}
    options_b = {} if eb is None else {"elasticity": eb}
    va, vb = (0.9, 0.0), (-0.4, 0.0)
    a = world.add_circle((0.3, 0.52), 0.06, mass=1.3, velocity=va, **options_a)
    b = world.add_circle((0.7, 0.5), 0.05, mass=0.7, velocity=vb, **options_b)
    event, after = first_collision(world)
    n = event.normal if event.a is a else (-event.normal[0], -event.normal[1])
    closing = dot((va[0] - vb[0], va[1] - vb[1]), n)
    va2, vb2 = after[a.id], after[b.id]
    opening = dot((va2[0] - vb2[0], va2[1] - vb2[1]), n)
    return -opening / closing


def test_two_default_bodies_bounce_with_exactly_0_98():
    """Two bodies with the default elasticity 0.98 separate at exactly 0.98 times their normal approach speed."""
    ratio = _normal_speed_ratio(World())
    assert abs(ratio - 0.98) <= REL


@pytest.mark.parametrize(
    "rule,expected",
    [("min", 0.6), ("max", 0.9), ("mean", 0.75), ("geometric", math.sqrt(0.6 * 0.9))],
)
def test_restitution_rules_combine_as_documented(rule, expected):
    """'min', 'max', 'mean' and 'geometric' give min, max, mean and sqrt(product) of 0.6 and 0.9."""
    ratio = _normal_speed_ratio(World(restitution=rule), 0.6, 0.9)
    assert abs(ratio - expected) <= REL
    # and the order of the two bodies does not matter
    assert abs(_normal_speed_ratio(World(restitution=rule), 0.9, 0.6) - expected) <= REL


@pytest.mark.parametrize("rule", ["min", "max", "mean", "geometric"])
def test_every_rule_gives_e_for_equal_elasticities(rule):
    """For equal elasticities e every rule gives exactly e."""
    for e in (0.3, 0.98, 1.0):
        assert abs(_normal_speed_ratio(World(restitution=rule), e, e) - e) <= REL


def test_unknown_restitution_rule_is_refused():
    """An unknown rule name raises ValueError naming the choices."""
    with pytest.raises(ValueError, match="restitution"):
        World(restitution="median")
