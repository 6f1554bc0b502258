"""Scenes and measures shared by the contact tests (test_contact.py, test_resting.py).

Flat scenes use dyadic sizes (0.0625, 0.125, ...) so that "touching" is exact in binary floating
point; a floor's top face is y = 0 and gravity is (0, -G).
"""

from __future__ import annotations

import math

from pge import World

G = 9.81
EXACT = 1e-12
CLOSE = 1e-9

#: a circle rolling on a floor (test_resting)
RADIUS = 0.0625
#: a plank leaning on a wall (test_resting's ladder)
LENGTH, THICKNESS = 0.3, 0.02

#: two polygons sliding apart on a frictionless floor (seed 3 of the random rotating scenes, inelastic,
#: under gravity, at t = 2.0967) and a spinning circle dropping into the V between their tilted faces.
V_LEFT = [(0.559764773, 0.085430261), (0.525891043, 0.065559464), (0.54310438, 0.0), (0.58344796, 0.0),
          (0.603155705, 0.030400699), (0.590825229, 0.060750892)]
V_RIGHT = [(0.804262837, 0.018326242), (0.80510206, 0.065118083), (0.761276702, 0.07856254),
           (0.722125242, 0.065230135), (0.714674307, 0.034034038), (0.736623803, 0.0), (0.775273696, 0.0)]


def floor_world(elasticity=0.5, floor_friction=0.0, **options) -> tuple[World, object]:
    """A World under gravity (0, -G) with a wide fixed floor whose top face is y = 0."""
    options.setdefault("bounds", (-1.0, -1.0, 3.0, 3.0))
    world = World(gravity=(0.0, -G), elasticity=elasticity, **options)
    floor = world.add_box(-1.0, -0.25, 6.0, 0.25, fixed=True, friction=floor_friction, name="floor")
    return world, floor


def ice_world(**options) -> tuple[World, object]:
    """A World under gravity (0, -G), elasticity 0, with a wide frictionless fixed floor (top y = 0)."""
    options.setdefault("bounds", (-2.0, -1.0, 4.0, 3.0))
    world = World(gravity=(0.0, -G), elasticity=0.0, **options)
    floor = world.add_box(-2.0, -0.25, 6.0, 0.25, fixed=True, friction=0.0, name="floor")
    return world, floor


def energy(world: World) -> float:
    """Kinetic (translation plus rotation) plus gravitational potential energy (g = G downwards, zero at
    y = 0) of the moving bodies."""
    return bodies_energy([body for body in world.bodies if not body.is_fixed])


def bodies_energy(bodies) -> float:
    """Kinetic (translation plus rotation) plus gravitational potential energy of ``bodies``."""
    total = 0.0
    for body in bodies:
        vx, vy = body.velocity
        w = body.angular_velocity
        total += body.mass * (0.5 * (vx * vx + vy * vy) + G * body.position[1]) + 0.5 * body.inertia * w * w
    return total


def horizontal_momentum(bodies) -> float:
    return sum(b.mass * b.velocity[0] for b in bodies)


def settle_time(h0: float, e: float, n: int) -> float:
    """Time of the n-th collision of a body dropped from rest with a gap h0 (restitution e)."""
    v0 = math.sqrt(2.0 * G * h0)
    return math.sqrt(2.0 * h0 / G) + 2.0 * v0 / G * sum(e**k for k in range(1, n))


def collision_times(world: World, body=None) -> list[float]:
    """A list that fills with the times of the collisions (of ``body``, or all)."""
    seen: list[float] = []
    world.on_collision(lambda event: seen.append(event.time), body)
    return seen


def slope_scene(angle_deg: float, shape: str, mu: float, velocity: float = 0.0, on_ramp: bool = False):
    """A fixed ramp rising to the right at ``angle_deg`` and a body touching it (pressed in by
    1e-12, far inside the start-up overlap tolerance: a body cannot be placed exactly on a tilted
    face) at rest, or moving up the slope at ``velocity``; friction ``mu`` on the body, or on
    the ramp (``on_ramp``). Returns (world, body, ramp, unit tangent up the slope)."""
    a = math.radians(angle_deg)
    world = World(gravity=(0.0, -G), elasticity=0.5, bounds=(-1.0, -1.0, 5.0, 5.0))
    length = 4.0
    ramp = world.add_polygon(
        [(0.0, 0.0), (length * math.cos(a), 0.0), (length * math.cos(a), length * math.sin(a))],
        fixed=True,
        friction=mu if on_ramp else 0.0,
        name="ramp",
    )
    tx, ty = math.cos(a), math.sin(a)
    nx, ny = -ty, tx
    s0 = 0.5 * length  # where the body sits along the slope
    press = 1e-12
    options = {"mass": 1.0, "friction": 0.0 if on_ramp else mu, "velocity": (velocity * tx, velocity * ty), "name": "body"}
    if shape == "circle":
        r = 0.0625
        body = world.add_circle((s0 * tx + (r - press) * nx, s0 * ty + (r - press) * ny), r, **options)
    else:
        side = 0.125
        x0, y0 = s0 * tx - press * nx, s0 * ty - press * ny
        corners = [(0.0, 0.0), (side, 0.0), (side, side), (0.0, side)]
        body = world.add_polygon([(x0 + u * tx + w * nx, y0 + u * ty + w * ny) for u, w in corners], **options)
    return world, body, ramp, (tx, ty)


def along(p, q, direction) -> float:
    """How far ``q`` lies from ``p`` along ``direction``."""
    return (q[0] - p[0]) * direction[0] + (q[1] - p[1]) * direction[1]


def threshold(theta_deg):
    """The floor friction a ladder of ``LENGTH`` x ``THICKNESS`` leaning at ``theta_deg`` on a
    frictionless wall needs to stand."""
    theta = math.radians(theta_deg)
    return (LENGTH * math.cos(theta) - THICKNESS * math.sin(theta)) / (2.0 * LENGTH * math.sin(theta))
