"""Shape descriptions: circles and convex polygons, with their mass properties.

Shapes are immutable and know nothing about position or motion; a body places
a shape in the world. Polygon vertices are kept anticlockwise and relative to
the area centroid.
"""

from __future__ import annotations

import math
from typing import Sequence

from pge.geometry import Vec, check_number, polygon_properties

__all__ = ["Circle", "Polygon"]


class Circle:
    """A disc of the given radius (world units).

    Raises ValueError for a radius that is not positive and finite.
    """

    __slots__ = ("radius",)
    kind = "circle"

    def __init__(self, radius: float, owner: str = "circle"):
        radius = check_number(owner, "radius", radius)
        if radius <= 0.0:
            raise ValueError(f"{owner}: radius must be positive, got {radius!r}")
        self.radius = radius

    @property
    def area(self) -> float:
        """Area, pi r^2."""
        return math.pi * self.radius * self.radius

    @property
    def inertia_per_mass(self) -> float:
        """Moment of inertia about the centre divided by the mass, r^2 / 2."""
        return 0.5 * self.radius * self.radius

    @property
    def bounding_radius(self) -> float:
        """Radius of the smallest circle about the centre holding the shape: r."""
        return self.radius

    @property
    def bounding_box(self) -> tuple[float, float, float, float]:
        """Box around the shape relative to its centre: ``(-r, -r, r, r)``."""
        r = self.radius
        return (-r, -r, r, r)

    def __repr__(self) -> str:
        return f"Circle(radius={self.radius!r})"


class Polygon:
    """A convex polygon given by its vertices in order (either winding).

    ``Polygon.from_points`` returns the shape and its area centroid in the
    coordinates the points were given in. Raises ValueError for a non-convex
    or self-intersecting outline, fewer than 3 distinct vertices, or zero
    area; TypeError for values that are not numbers.
    """

    __slots__ = ("vertices", "area", "inertia_per_mass", "bounding_radius")
    kind = "polygon"

    def __init__(self, vertices: Sequence[Vec], owner: str = "polygon"):
        centroid, local, area, inertia, radius = polygon_properties(vertices, owner)
        self.vertices: tuple[Vec, ...] = local
        """Vertices relative to the area centroid, anticlockwise."""
        self.area: float = area
        self.inertia_per_mass: float = inertia
        self.bounding_radius: float = radius

    @classmethod
    def from_points(cls, points: Sequence[Vec], owner: str = "polygon") -> tuple["Polygon", Vec]:
        """The polygon through ``points`` and the centroid of those points' outline."""
        centroid = polygon_properties(points, owner)[0]
        return cls(points, owner), centroid

    @property
    def bounding_box(self) -> tuple[float, float, float, float]:
        """Box around the unrotated shape relative to its centroid ``(xmin, ymin, xmax, ymax)``."""
        xs = [x for x, _ in self.vertices]
        ys = [y for _, y in self.vertices]
        return (min(xs), min(ys), max(xs), max(ys))

    def __repr__(self) -> str:
        return f"Polygon(vertices={list(self.vertices)!r})"
