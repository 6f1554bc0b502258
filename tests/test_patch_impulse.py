"""A face meeting a face: both ends of the patch take the impact together
(``pge.core.impulse.patch_impulse``, used by ``pge.core.engine.collide`` where the manifold
has two points that touch within ``SIMULTANEOUS`` of an island step).

Choosing one end of a face patch (the first to touch, or the faster-approaching one) sets a
body turning on a difference of rounding: a box landing with a tilt of 1e-10 rad, or a spin
of 1e-12 rad/s, took a corner impulse and left spinning at O(1). Three elastic boxes (e 0.98)
stacked with gaps exploded out of the world from a tilt of 1e-10 of the top one."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from pge import Collision, World
from pge.core.impulse import contact_impulse, patch_impulse

G = 9.81


def _geometry(rng, fixed_b):
    """Two bodies (b possibly fixed) touching along a face with normal (0, 1): the ends p1, p2,
    each body's inverse mass and inertia and centroid; returns the contact-space inverse mass
    over (n at p1, n at p2, t at the midpoint)."""
    n = np.array([0.0, 1.0])
    t = np.array([-1.0, 0.0])
    half = rng.uniform(0.01, 0.5)
    centre = rng.uniform(-0.3, 0.3)
    p1 = np.array([centre - half, 0.0])
    p2 = np.array([centre + half, 0.0])
    pm = 0.5 * (p1 + p2)
    bodies = []
    for k in range(2):
        if k == 1 and fixed_b:
            bodies.append((0.0, 0.0, np.zeros(2)))
            continue
        m = 1.0 / rng.uniform(0.2, 5.0)
        inertia = 1.0 / rng.uniform(0.001, 0.5)
        c = np.array([rng.uniform(-0.5, 0.5), rng.uniform(0.05, 0.5) * (1 if k == 0 else -1)])
        bodies.append((m, inertia, c))

    def cross(r, d):
        return r[0] * d[1] - r[1] * d[0]

    K = np.zeros((3, 3))
    for m, inertia, c in bodies:
        arms = [(p1 - c, n), (p2 - c, n), (pm - c, t)]
        for i in range(3):
            for j in range(3):
                ri, di = arms[i]
                rj, dj = arms[j]
                K[i, j] += m * float(di @ dj) + inertia * cross(ri, di) * cross(rj, dj)
    return K


def _solve(u, K, e, mu):
    return np.array(patch_impulse(u[0], u[1], u[2], K[0, 0], K[0, 1], K[1, 1], K[0, 2], K[1, 2], K[2, 2], e, mu))


@settings(max_examples=400, deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    e=st.floats(0.0, 1.0),
    mu=st.sampled_from([0.0, 0.1, 0.5, 1.0, 3.0]),
    fixed_b=st.booleans(),
)
def test_patch_impulse_obeys_restitution_friction_and_never_gains_energy(seed, e, mu, fixed_b):
    """For random bodies and velocities: normal impulses never pull; no end is left
    approaching; friction stays in its cone; kinetic energy never rises; and where the energy
    guard did not act, an end that takes an impulse leaves at exactly ``-e u`` (or at 0 if it
    was separating) and the friction either sticks or slides at the cone's edge."""
    rng = np.random.default_rng(seed)
    K = _geometry(rng, fixed_b)
    u = rng.uniform(-2.0, 2.0, 3)
    if u[0] >= 0.0 and u[1] >= 0.0:
        u[rng.integers(0, 2)] *= -1.0
    J = _solve(u, K, e, mu)
    scale = np.abs(u).sum() + 1e-300
    after = u + K @ J
    assert J[0] >= 0.0 and J[1] >= 0.0
    assert after[0] >= -1e-9 * scale and after[1] >= -1e-9 * scale
    assert abs(J[2]) <= mu * (J[0] + J[1]) * (1.0 + 1e-9) + 1e-15
    gain = J @ u + 0.5 * J @ K @ J
    assert gain <= 1e-12 * (abs(J @ u) + 1e-300)
    if gain < -1e-9 * abs(J @ u):
        for k in range(2):
            target = -e * u[k] if u[k] < 0.0 else 0.0
            if J[k] > 1e-9 * (J[0] + J[1]):
                assert after[k] == pytest.approx(target, abs=1e-9 * scale)
            else:
                assert after[k] >= target - 1e-9 * scale
        if mu > 0.0 and abs(J[2]) < mu * (J[0] + J[1]) * (1.0 - 1e-9):
            assert abs(after[2]) <= 1e-9 * scale


def test_a_face_landing_flat_takes_equal_impulses_and_no_spin():
    """Both ends approaching equally on a symmetric patch: equal impulses, no friction, both
    ends leave at -e u."""
    K = np.array([[2.0, 0.5, 0.0], [0.5, 2.0, 0.0], [0.0, 0.0, 1.5]])
    l1, l2, jt = patch_impulse(-1.0, -1.0, 0.0, K[0, 0], K[0, 1], K[1, 1], K[0, 2], K[1, 2], K[2, 2], 0.5, 0.3)
    assert l1 == pytest.approx(l2, rel=1e-15)
    assert jt == 0.0
    assert (K[0, 0] * l1 + K[0, 1] * l2) == pytest.approx(1.5, rel=1e-14)


@pytest.mark.parametrize("mu", [0.0, 0.4])
def test_one_end_separating_fast_gives_the_single_point_impulse(mu):
    """Where the other end separates fast enough that one end's impulse leaves it separating,
    the patch's answer is the single-point impulse at the approaching end (friction at the
    midpoint aside: without tangential coupling both agree)."""
    K = np.array([[2.0, 0.5, 0.0], [0.5, 2.0, 0.0], [0.0, 0.0, 1.5]])
    u1, u2, ut = -1.0, 3.0, 0.2
    l1, l2, jt = patch_impulse(u1, u2, ut, K[0, 0], K[0, 1], K[1, 1], K[0, 2], K[1, 2], K[2, 2], 0.7, mu)
    jn, jt1 = contact_impulse(u1, ut, K[0, 0], 0.0, K[2, 2], 0.7, mu)
    assert l2 == 0.0
    assert l1 == pytest.approx(jn, rel=1e-14)
    assert jt == pytest.approx(jt1, rel=1e-14, abs=1e-15)


def _drop_box(tilt, spin, e=0.9, mu=0.5):
    world = World(gravity=(0.0, -G), elasticity=e, bounds=(-1.0, -1.0, 3.0, 3.0))
    world.add_box(-1.0, -0.5, 3.0, 0.5, fixed=True, friction=mu, name="floor")
    box = world.add_box(0.4, 0.2, 0.2, 0.1, mass=1.0, angle=tilt, angular_velocity=spin, friction=mu)
    first = next(e for e in world.events(2.0) if isinstance(e, Collision))
    return first, box


@pytest.mark.parametrize("tilt, spin", [(0.0, 0.0), (1e-10, 0.0), (-3e-9, 0.0), (0.0, 1e-12), (2e-9, -1e-9)])
def test_a_box_landing_flat_to_rounding_bounces_without_turning(tilt, spin):
    """A box dropped from 0.2 with a tilt or spin of rounding's size lands as a face: it
    bounces straight up at e times its landing speed and turns no faster than it did (a corner
    impulse at 1.98 m/s would give it about 10 rad/s)."""
    first, box = _drop_box(tilt, spin)
    landing = math.sqrt(2.0 * G * 0.2)
    assert first.approach_speed == pytest.approx(landing, rel=1e-6)
    assert abs(box.angular_velocity) <= 1e-6
    assert box.velocity[1] == pytest.approx(0.9 * landing, rel=1e-6)
    assert abs(box.velocity[0]) <= 1e-6


def test_a_box_landing_on_a_corner_still_turns():
    """A clear tilt (0.05 rad: the far corner 1e-2 above the floor, far outside the window)
    is a corner impact, as before: the box turns."""
    first, box = _drop_box(0.05, 0.0)
    assert abs(box.angular_velocity) > 1.0


def test_three_elastic_boxes_stacked_with_a_tilt_of_rounding_settle_level():
    """Three boxes (e 0.98, widths 0.25, 0.1875, 0.125) dropped with 1.5 cm gaps, the top one
    tilted by 1e-10 rad: they settle level and centred, and sleep, as without the tilt (they
    were flung out of the world when one end of a face patch took the impact), within a
    second of the time a box dropped by the gap onto a floor takes to stop bouncing at this
    elasticity, ``sqrt(2 gap / g) (1 + e) / (1 - e)`` = 5.6 s."""
    world = World(gravity=(0.0, -G), elasticity=0.98, bounds=(-1.0, -1.0, 3.0, 3.0))
    world.add_box(-1.0, -1.0, 3.0, 1.0, fixed=True, friction=0.0, name="floor")
    boxes = []
    y = 0.015625
    for k, w in enumerate((0.25, 0.1875, 0.125)):
        boxes.append(world.add_box(0.5 - w / 2, y, w, 0.1, mass=1.0 + k, angle=1e-10 if k == 2 else 0.0))
        y += 0.1 + 0.015625
    limit = 1.0 + math.sqrt(2.0 * 0.015625 / G) * (1.0 + 0.98) / (1.0 - 0.98)
    t = 0.0
    while not all(b.asleep for b in boxes):
        t += 0.05
        assert t < limit, "the stack never fell asleep"
        world.run_until(t)
    for k, body in enumerate(boxes):
        assert abs(body.position[0] - 0.5) <= 1e-6
        assert abs(body.position[1] - (0.05 + 0.1 * k)) <= 1e-6
        assert abs(math.remainder(body.angle, math.pi / 2)) <= 1e-6
