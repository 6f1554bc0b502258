"""``press_rate`` (the gap's second derivative at a contact) against finite differences of the
exact gap, for every way the contact normal turns: a point on b's face, b's point on a's face,
a circle's centre on b's face, round b's corner, and two circles.

Each case builds the exact gap ``g(t)`` of the touching feature pair from closed-form motion
(b's centroid at the origin, a's at ``o + v t + acc t^2 / 2``, spins ``omega_a`` and
``omega_b``), so the test does not depend on the engine's kernels. The sign of the curvature
decides whether the pivot rule and the rotating kernel treat a contact as pressed: a wrong one
made a circle resting on the floor and a polygon pivoting on its side collide 400,000 times in
3 ms (tools/repro/repro_resting_circle_zeno.py).
"""

import math

from hypothesis import given, settings
from hypothesis import strategies as st

from pge.toi.rotating import press_noise, press_rate


def _turn(angle, x, y):
    c, s = math.cos(angle), math.sin(angle)
    return c * x - s * y, s * x + c * y


def _second_derivative(gap, h=1e-4):
    """Central difference of ``gap`` at 0, with the step's truncation error estimated from h / 2."""
    coarse = (gap(h) - 2.0 * gap(0.0) + gap(-h)) / (h * h)
    fine = (gap(h / 2) - 2.0 * gap(0.0) + gap(-h / 2)) / (h * h / 4)
    return (4.0 * fine - coarse) / 3.0  # Richardson: error O(h^4)


def _motion(o, v, acc):
    def centre(t):
        return o[0] + v[0] * t + 0.5 * acc[0] * t * t, o[1] + v[1] * t + 0.5 * acc[1] * t * t

    return centre


component = st.floats(-3.0, 3.0)
spin = st.floats(-20.0, 20.0)
angle = st.floats(0.0, 2.0 * math.pi)
lever = st.floats(0.01, 0.08)


def _check(expected, got, scale):
    assert abs(got - expected) <= 1e-7 * scale + 1e-6, (got, expected)


@settings(max_examples=200, deadline=None)
@given(normal_angle=angle, along=st.floats(-0.05, 0.05), depth=lever, lean=st.floats(-1.2, 1.2),
       vx=component, vy=component, ax=component, ay=component, omega_a=spin, omega_b=spin, a_owns=st.booleans())
def test_point_on_a_face(normal_angle, along, depth, lean, vx, vy, ax, ay, omega_a, omega_b, a_owns):
    """A vertex touching a face, the face on b (the normal turns with b) or on a."""
    nx, ny = math.cos(normal_angle), math.sin(normal_angle)  # b towards a
    # The contact point relative to b's centroid: on the face, which is ``depth`` out from b's centroid.
    px, py = depth * nx - along * ny, depth * ny + along * nx
    # a's centroid beyond the face, leaning sideways.
    ox, oy = px + depth * (nx * math.cos(lean) - ny * math.sin(lean)), py + depth * (ny * math.cos(lean) + nx * math.sin(lean))
    centre = _motion((ox, oy), (vx, vy), (ax, ay))

    def gap(t):
        cx, cy = centre(t)
        if not a_owns:  # a's vertex against b's face
            qx, qy = _turn(omega_a * t, px - ox, py - oy)
            fx, fy = _turn(omega_b * t, px, py)
            mx, my = _turn(omega_b * t, nx, ny)
            return (cx + qx - fx) * mx + (cy + qy - fy) * my
        # b's vertex against a's face, whose outward normal is -n
        qx, qy = _turn(omega_b * t, px, py)
        fx, fy = _turn(omega_a * t, px - ox, py - oy)
        mx, my = _turn(omega_a * t, -nx, -ny)
        return (qx - cx - fx) * mx + (qy - cy - fy) * my

    assert abs(gap(0.0)) < 1e-15
    omega_face = omega_a if a_owns else omega_b
    got = press_rate(px, py, nx, ny, ox, oy, vx, vy, ax, ay, omega_a, omega_b, omega_face, 0.0)
    speed = math.hypot(vx, vy) + (abs(omega_a) + abs(omega_b)) * 0.2
    _check(_second_derivative(gap), got, math.hypot(ax, ay) + speed * speed / 0.01)


@settings(max_examples=200, deadline=None)
@given(normal_angle=angle, along=st.floats(-0.05, 0.05), depth=lever, radius=lever,
       vx=component, vy=component, ax=component, ay=component, omega_b=spin)
def test_circle_on_a_face(normal_angle, along, depth, radius, vx, vy, ax, ay, omega_b):
    """A circle's centre at ``radius`` from b's face: the normal turns with b, and the rim point
    is not what moves with the gap (that was the bug: it added omega_b^2 r)."""
    nx, ny = math.cos(normal_angle), math.sin(normal_angle)
    px, py = depth * nx - along * ny, depth * ny + along * nx  # on the face
    ox, oy = px + radius * nx, py + radius * ny
    centre = _motion((ox, oy), (vx, vy), (ax, ay))

    def gap(t):
        cx, cy = centre(t)
        fx, fy = _turn(omega_b * t, px, py)
        mx, my = _turn(omega_b * t, nx, ny)
        return (cx - fx) * mx + (cy - fy) * my - radius

    got = press_rate(ox, oy, nx, ny, ox, oy, vx, vy, ax, ay, 0.0, omega_b, omega_b, 0.0)
    speed = math.hypot(vx, vy) + abs(omega_b) * 0.2
    _check(_second_derivative(gap), got, math.hypot(ax, ay) + speed * speed / 0.01)


@settings(max_examples=200, deadline=None)
@given(normal_angle=angle, corner_angle=angle, corner=lever, radius=lever,
       vx=component, vy=component, ax=component, ay=component, omega_b=spin)
def test_circle_round_a_corner(normal_angle, corner_angle, corner, radius, vx, vy, ax, ay, omega_b):
    """A circle's centre at ``radius`` from b's corner: the normal turns with the centre's slip."""
    nx, ny = math.cos(normal_angle), math.sin(normal_angle)
    px, py = corner * math.cos(corner_angle), corner * math.sin(corner_angle)
    ox, oy = px + radius * nx, py + radius * ny
    centre = _motion((ox, oy), (vx, vy), (ax, ay))

    def gap(t):
        cx, cy = centre(t)
        qx, qy = _turn(omega_b * t, px, py)
        return math.hypot(cx - qx, cy - qy) - radius

    got = press_rate(px, py, nx, ny, ox, oy, vx, vy, ax, ay, 0.0, omega_b, 0.0, 1.0 / radius)
    speed = math.hypot(vx, vy) + abs(omega_b) * 0.2
    _check(_second_derivative(gap), got, math.hypot(ax, ay) + speed * speed / 0.01)


@settings(max_examples=100, deadline=None)
@given(normal_angle=angle, ra=lever, rb=lever, vx=component, vy=component, ax=component, ay=component)
def test_two_circles(normal_angle, ra, rb, vx, vy, ax, ay):
    nx, ny = math.cos(normal_angle), math.sin(normal_angle)
    ox, oy = (ra + rb) * nx, (ra + rb) * ny
    centre = _motion((ox, oy), (vx, vy), (ax, ay))

    def gap(t):
        return math.hypot(*centre(t)) - ra - rb

    got = press_rate(0.0, 0.0, nx, ny, ox, oy, vx, vy, ax, ay, 0.0, 0.0, 0.0, 1.0 / (ra + rb))
    speed = math.hypot(vx, vy)
    _check(_second_derivative(gap), got, math.hypot(ax, ay) + speed * speed / 0.01)


def test_the_traced_zeno_contact_is_pressed():
    """The contact of tools/repro/repro_resting_circle_zeno.py, measured at t = 0.6627 + 2.6 us:
    circle 7 (r = 0.0430, at rest) against the left face of polygon 5 spinning at -10.87 rad/s.
    Finite differences of the gap gave -1.091; the rim-point curvature said +3.99 (opening),
    so the pivot rule never fired."""
    omega_b = -10.866398
    radius = 0.04300817450989561
    nx, ny = -0.9824388650019017, -0.1865847703693293
    # polygon 5's centroid as origin; the contact (rim) point and the circle's centre
    px, py = 0.7716588284690395 - 0.8225678168434049, 0.05103284487482853 - 0.06880666764272719
    ox, oy = px + radius * nx, py + radius * ny
    vx, vy = -0.1890094228607405, 0.5314723057926561  # the circle at rest, the polygon moving
    ax, ay = 0.0, 9.81
    got = press_rate(ox, oy, nx, ny, ox, oy, vx, vy, ax, ay, 0.0, omega_b, omega_b, 0.0)
    rim = press_rate(px, py, nx, ny, ox, oy, vx, vy, ax, ay, 0.0, omega_b, omega_b, 0.0)
    assert got < -1.0
    assert abs(rim - got - omega_b * omega_b * radius) < 1e-9
    noise = press_noise(math.hypot(ax, ay), math.hypot(vx, vy), 0.0, abs(omega_b), 0.0, 0.07, 1e-13, 0.0)
    assert noise < 1e-6
