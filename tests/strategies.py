"""Shared hypothesis strategies and scene helpers for the pge test-suite.

Everything here is plain geometry or plain ``hypothesis`` and independent of the
engine's own geometry code, so tests that use it check the engine against an
outside description of the shapes.

Shapes:

* ``regular_polygon(n, radius, centre, angle)``: the vertices of a regular n-gon
  (a plain function); ``regular_polygons(...)``: a strategy for them.
* ``convex_polygons(min_radius, max_radius, ...)``: random convex polygons whose
  vertices lie between the two distances from ``centre``; well-shaped (no
  sliver edges or near-straight corners), anticlockwise.
* ``area_centroid(vertices)``, ``centred(vertices)``: the area centroid and the
  anticlockwise vertices relative to it (what ``pge.toi.outline_rows`` wants).
* ``radii``, ``masses``, ``elasticities``, ``vectors``, ``motions``: numbers and
  vectors in modest, physically sensible ranges.

Scenes:

* ``closed_box(world, ...)``: four fixed walls around a rectangle.
* ``random_scene(seed, ...)``: a reproducible list of body specs (circles and
  polygons, no two overlapping, inside a rectangle), and ``build_scene(world,
  specs)`` to add them to a World.
"""

from __future__ import annotations

import math
import random

from hypothesis import strategies as st

__all__ = [
    "area_centroid",
    "bounding_radius",
    "build_scene",
    "centred",
    "closed_box",
    "convex_hull",
    "convex_polygons",
    "elasticities",
    "masses",
    "motions",
    "radii",
    "random_scene",
    "regular_polygon",
    "regular_polygons",
    "translate",
    "vectors",
]

TAU = 2.0 * math.pi


# ---------------------------------------------------------------- polygons


def regular_polygon(n: int, radius: float, centre=(0.0, 0.0), angle: float = 0.0) -> list[tuple[float, float]]:
    """Vertices (anticlockwise) of a regular ``n``-gon with circumradius ``radius``."""
    cx, cy = centre
    return [
        (cx + radius * math.cos(angle + TAU * k / n), cy + radius * math.sin(angle + TAU * k / n)) for k in range(n)
    ]


def regular_polygons(min_sides=3, max_sides=8, min_radius=0.05, max_radius=0.2, centre=(0.0, 0.0)):
    """Strategy: vertices of a regular polygon with a random side count, size and orientation."""
    return st.builds(
        lambda n, r, a: regular_polygon(n, r, centre, a),
        st.integers(min_sides, max_sides),
        st.floats(min_radius, max_radius),
        st.floats(0.0, TAU),
    )


def _cross(o, a, b) -> float:
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])


def convex_hull(points) -> list[tuple[float, float]]:
    """Strict convex hull (anticlockwise, collinear points dropped), Andrew's monotone chain."""
    pts = sorted({(float(x), float(y)) for x, y in points})
    if len(pts) < 3:
        return pts

    def half(seq):
        out: list = []
        for p in seq:
            while len(out) >= 2:
                o, a = out[-2], out[-1]
                scale = math.dist(o, a) * math.dist(a, p)
                if _cross(o, a, p) <= 1e-9 * scale:
                    out.pop()
                else:
                    break
            out.append(p)
        return out

    lower = half(pts)
    upper = half(reversed(pts))
    return lower[:-1] + upper[:-1]


def area_centroid(vertices) -> tuple[float, float]:
    """Area centroid of a simple polygon (either winding)."""
    n = len(vertices)
    ox, oy = vertices[0]
    twice_area = cx = cy = 0.0
    for k in range(n):
        x0, y0 = vertices[k][0] - ox, vertices[k][1] - oy
        x1, y1 = vertices[(k + 1) % n][0] - ox, vertices[(k + 1) % n][1] - oy
        cross = x0 * y1 - x1 * y0
        twice_area += cross
        cx += (x0 + x1) * cross
        cy += (y0 + y1) * cross
    return (ox + cx / (3.0 * twice_area), oy + cy / (3.0 * twice_area))


def signed_area(vertices) -> float:
    """Signed area: positive for an anticlockwise outline."""
    n = len(vertices)
    return 0.5 * sum(
        vertices[k][0] * vertices[(k + 1) % n][1] - vertices[(k + 1) % n][0] * vertices[k][1] for k in range(n)
    )


def centred(vertices) -> tuple[list[tuple[float, float]], tuple[float, float]]:
    """``(local, centroid)``: anticlockwise vertices relative to the area centroid, and the centroid."""
    vertices = [(float(x), float(y)) for x, y in vertices]
    if signed_area(vertices) < 0.0:
        vertices.reverse()
    cx, cy = area_centroid(vertices)
    return [(x - cx, y - cy) for x, y in vertices], (cx, cy)


def bounding_radius(local_vertices) -> float:
    """Largest distance of a vertex from the origin."""
    return max(math.hypot(x, y) for x, y in local_vertices)


def translate(vertices, offset) -> list[tuple[float, float]]:
    """Vertices shifted by ``offset``."""
    dx, dy = offset
    return [(x + dx, y + dy) for x, y in vertices]


@st.composite
def convex_polygons(draw, min_radius=0.05, max_radius=0.2, min_sides=3, max_sides=8, centre=(0.0, 0.0)):
    """Strategy: a random convex polygon (anticlockwise vertices, world coordinates).

    Vertices sit at distances in ``[min_radius, max_radius]`` from ``centre`` at
    angles whose gaps differ by at most a factor of 1.8 (no slivers, and every
    gap is below half a turn, so the hull always contains ``centre``); the
    strict convex hull is kept.
    """
    n = draw(st.integers(min_sides, max_sides))
    weights = draw(st.lists(st.floats(1.0, 1.8), min_size=n, max_size=n))
    start = draw(st.floats(0.0, TAU))
    rads = draw(st.lists(st.floats(min_radius, max_radius), min_size=n, max_size=n))
    total = sum(weights)
    angle = start
    points = []
    for w, r in zip(weights, rads):
        points.append((centre[0] + r * math.cos(angle), centre[1] + r * math.sin(angle)))
        angle += TAU * w / total
    hull = convex_hull(points)
    if len(hull) < 3:
        # Impossible with these gaps (each below pi), but keep the strategy total.
        hull = regular_polygon(3, max_radius, centre, start)
    return hull


# ---------------------------------------------------------------- numbers and motions


def radii(min_radius=0.02, max_radius=0.2):
    """Strategy: a circle radius."""
    return st.floats(min_radius, max_radius)


def masses(min_mass=0.1, max_mass=10.0):
    """Strategy: a body mass."""
    return st.floats(min_mass, max_mass)


def elasticities():
    """Strategy: an elasticity in [0, 1], with the ends and PGE's 0.98 likely."""
    return st.one_of(st.sampled_from([0.0, 0.5, 0.98, 1.0]), st.floats(0.0, 1.0))


def vectors(max_norm=1.0, min_norm=0.0):
    """Strategy: a 2D vector with ``min_norm <= |v| <= max_norm`` (polar, so directions are uniform)."""
    return st.builds(
        lambda r, a: (r * math.cos(a), r * math.sin(a)),
        st.floats(min_norm, max_norm),
        st.floats(0.0, TAU),
    )


def motions(max_speed=2.0, max_accel=10.0, accelerate=True):
    """Strategy: ``(velocity, acceleration)``; the acceleration is zero unless ``accelerate``."""
    accel = vectors(max_accel) if accelerate else st.just((0.0, 0.0))
    return st.tuples(vectors(max_speed), accel)


# ---------------------------------------------------------------- scenes


def closed_box(world, x0=0.0, y0=0.0, x1=1.0, y1=1.0, thickness=0.05, **options):
    """Add four fixed walls enclosing the rectangle ``[x0, x1] x [y0, y1]``; returns them.

    The walls lie outside the rectangle (the floor's top is at ``y0``, and so on)
    and overlap each other at the corners, which fixed bodies may.
    """
    t = thickness
    options = {"fixed": True, **options}
    return [
        world.add_box(x0 - t, y0 - t, x1 - x0 + 2 * t, t, name="floor", **options),
        world.add_box(x0 - t, y1, x1 - x0 + 2 * t, t, name="ceiling", **options),
        world.add_box(x0 - t, y0 - t, t, y1 - y0 + 2 * t, name="left wall", **options),
        world.add_box(x1, y0 - t, t, y1 - y0 + 2 * t, name="right wall", **options),
    ]


def random_scene(
    seed,
    n_circles=8,
    n_polygons=4,
    area=(0.0, 0.0, 1.0, 1.0),
    radius=(0.03, 0.07),
    speed=1.0,
    mass=(0.5, 2.0),
    elasticity=1.0,
    gap=1e-3,
):
    """A reproducible scene: a list of body specs, none overlapping another or the area's edge.

    Each spec is a dict with ``kind`` ("circle" or "polygon"), ``position``
    (centre) and ``radius`` for a circle or ``vertices`` (world coordinates)
    for a polygon, ``mass``, ``velocity`` and ``elasticity``. Bodies keep at
    least ``gap`` between their bounding circles. Raises RuntimeError if they
    cannot all be placed.
    """
    rng = random.Random(seed)
    x0, y0, x1, y1 = area
    placed: list[tuple[float, float, float]] = []
    specs = []
    kinds = ["circle"] * n_circles + ["polygon"] * n_polygons
    rng.shuffle(kinds)
    for kind in kinds:
        size = rng.uniform(*radius)
        for _ in range(10000):
            cx = rng.uniform(x0 + size + gap, x1 - size - gap)
            cy = rng.uniform(y0 + size + gap, y1 - size - gap)
            if all(math.hypot(cx - px, cy - py) > size + pr + gap for px, py, pr in placed):
                break
        else:
            raise RuntimeError(f"random_scene: cannot place body {len(specs)} (seed {seed!r})")
        placed.append((cx, cy, size))
        angle = rng.uniform(0.0, TAU)
        velocity = (speed * math.cos(angle), speed * math.sin(angle))
        spec = {
            "kind": kind,
            "mass": rng.uniform(*mass),
            "velocity": velocity,
            "elasticity": elasticity,
        }
        if kind == "circle":
            spec["position"] = (cx, cy)
            spec["radius"] = size
        else:
            sides = rng.randint(3, 7)
            spec["vertices"] = regular_polygon(sides, size, (cx, cy), rng.uniform(0.0, TAU))
        specs.append(spec)
    return specs


def build_scene(world, specs):
    """Add the bodies described by ``random_scene`` specs to ``world``; returns them in order."""
    bodies = []
    for spec in specs:
        options = {"mass": spec["mass"], "velocity": spec["velocity"], "elasticity": spec["elasticity"]}
        if spec["kind"] == "circle":
            bodies.append(world.add_circle(spec["position"], spec["radius"], **options))
        else:
            bodies.append(world.add_polygon(spec["vertices"], **options))
    return bodies
