"""Body handles: what users hold for a circle or polygon in a World.

The motion state lives in the world's arrays (``pge.core.layout``) and is
*delayed*: each body stores its position and velocity at its own reference
time ``t0`` plus a constant acceleration, and is advanced only when it takes
part in an event. Reading a position evaluates the closed form
``x(t) = x0 + v (t - t0) + a (t - t0)^2 / 2`` at the world's current time.

A handle whose body was removed raises a ValueError naming it; body ids are
never reused, so a stale handle can never alias a newer body.
"""

from __future__ import annotations

import math

from pge.core import layout as L
from pge.shapes import Circle

__all__ = ["Body"]


class Body:
    """A circle or convex polygon in a ``World``; create bodies with ``World.add_*``.

    Views of the state at the world's current time: ``position`` (centre or
    area centroid), ``velocity``, ``acceleration`` (the body's own, on top of
    gravity), ``total_acceleration``, ``mass`` (None until given),
    ``is_fixed``, ``elasticity``, ``angle``, ``angular_velocity``, ``shape``,
    ``vertices`` (world coordinates of a polygon's corners). Assigning
    ``position``, ``velocity``, ``acceleration``, ``mass``, ``elasticity``,
    ``angle`` or ``angular_velocity`` calls the matching ``World.set_*``.
    """

    __slots__ = ("id", "name", "data", "shape", "world")

    def __init__(self, world, body_id: int, shape, name=None, data=None) -> None:
        self.world = world
        self.id = body_id
        self.shape = shape
        self.name = name
        self.data = data

    @property
    def kind(self) -> str:
        """``"circle"`` or ``"polygon"``."""
        return "circle" if isinstance(self.shape, Circle) else "polygon"

    def label(self) -> str:
        """A short name for messages, e.g. ``circle 3 'ball'``."""
        return f"{self.kind} {self.id}" + (f" {self.name!r}" if self.name is not None else "")

    def _row(self):
        world = self.world
        if world is None:
            raise ValueError(f"{self.label()} has been removed from its world")
        return world._state.F[self.id], world

    @property
    def alive(self) -> bool:
        """False once the body has been removed from its world."""
        return self.world is not None

    @property
    def position(self) -> tuple[float, float]:
        """Centre (circle) or area centroid (polygon) at the world's current time."""
        row, world = self._row()
        dt = world.time - row[L.T0]
        return (
            float(row[L.X] + (row[L.VX] + 0.5 * row[L.AX] * dt) * dt),
            float(row[L.Y] + (row[L.VY] + 0.5 * row[L.AY] * dt) * dt),
        )

    @position.setter
    def position(self, value) -> None:
        self._row()[1].set_position(self, value)

    @property
    def velocity(self) -> tuple[float, float]:
        """Velocity at the world's current time (zero while fixed)."""
        row, world = self._row()
        dt = world.time - row[L.T0]
        return (float(row[L.VX] + row[L.AX] * dt), float(row[L.VY] + row[L.AY] * dt))

    @velocity.setter
    def velocity(self, value) -> None:
        self._row()[1].set_velocity(self, value)

    @property
    def acceleration(self) -> tuple[float, float]:
        """The body's own constant acceleration, applied on top of the world's gravity."""
        row, _ = self._row()
        return (float(row[L.OWN_AX]), float(row[L.OWN_AY]))

    @acceleration.setter
    def acceleration(self, value) -> None:
        self._row()[1].set_acceleration(self, value)

    @property
    def total_acceleration(self) -> tuple[float, float]:
        """The acceleration the body moves with: own plus gravity, zero while fixed."""
        row, _ = self._row()
        return (float(row[L.AX]), float(row[L.AY]))

    @property
    def mass(self) -> float | None:
        """Mass (None until given). A fixed body behaves as if infinitely heavy."""
        row, _ = self._row()
        value = float(row[L.MASS])
        return None if math.isnan(value) else value

    @mass.setter
    def mass(self, value) -> None:
        self._row()[1].set_mass(self, value)

    @property
    def is_fixed(self) -> bool:
        """True for an immovable body."""
        _, world = self._row()
        return bool(world._state.I[self.id, L.FIXED])

    @property
    def elasticity(self) -> float:
        """Elasticity in [0, 1], combined with the other body's by the world's restitution rule."""
        row, _ = self._row()
        return float(row[L.ELASTICITY])

    @elasticity.setter
    def elasticity(self, value) -> None:
        self._row()[1].set_elasticity(self, value)

    @property
    def angle(self) -> float:
        """Orientation in radians, anticlockwise, at the world's current time."""
        row, world = self._row()
        dt = world.time - row[L.T0]
        return float(row[L.ANGLE] + (row[L.OMEGA] + 0.5 * row[L.ALPHA] * dt) * dt)

    @angle.setter
    def angle(self, value) -> None:
        self._row()[1].set_angle(self, value)

    @property
    def angular_velocity(self) -> float:
        """Angular velocity in radians per second, anticlockwise, at the world's current time (zero
        while fixed; it changes while a circle rolls or skids on a face)."""
        row, world = self._row()
        return float(row[L.OMEGA] + row[L.ALPHA] * (world.time - row[L.T0]))

    @angular_velocity.setter
    def angular_velocity(self, value) -> None:
        self._row()[1].set_angular_velocity(self, value)

    @property
    def friction(self) -> float:
        """Coulomb friction coefficient (0 unless given), combined by the world's friction rule."""
        row, _ = self._row()
        return float(row[L.FRICTION])

    @friction.setter
    def friction(self, value) -> None:
        self._row()[1].set_friction(self, value)

    @property
    def resting_on(self) -> "Body | None":
        """The body this one rests, slides or rolls on, or None while free: the one it pressed
        on hardest at its island's last step (the one it fell asleep on, while asleep)."""
        _, world = self._row()
        support = world._islands.support(self.id)
        return world._handles.get(support) if support >= 0 else None

    @property
    def asleep(self) -> bool:
        """True while the body sleeps in an island that contact forces hold still: it makes no
        events until something touches it or it is changed."""
        _, world = self._row()
        return world._islands.asleep(self.id)

    @property
    def inertia(self) -> float | None:
        """Moment of inertia about the centroid (mass x shape's inertia per mass); None
        without a mass."""
        mass = self.mass
        return None if mass is None else mass * self.shape.inertia_per_mass

    @property
    def bounding_box(self) -> tuple[float, float, float, float]:
        """Axis-aligned box ``(xmin, ymin, xmax, ymax)`` around the shape now."""
        if isinstance(self.shape, Circle):
            x, y = self.position
            r = self.shape.radius
            return (float(x - r), float(y - r), float(x + r), float(y + r))
        corners = self.vertices
        xs = [p[0] for p in corners]
        ys = [p[1] for p in corners]
        return (min(xs), min(ys), max(xs), max(ys))

    @property
    def bounding_radius(self) -> float:
        """Largest distance of the shape from its reference point (any orientation)."""
        return self.shape.bounding_radius

    @property
    def vertices(self) -> tuple[tuple[float, float], ...]:
        """World coordinates of a polygon's corners (anticlockwise) now; () for a circle."""
        _, world = self._row()
        x, y = self.position
        state = world._state
        start = state.I[self.id, L.OUTLINE_START]
        count = state.I[self.id, L.OUTLINE_N]
        rows = state.OB[start : start + count]
        angle = self.angle
        c = math.cos(angle)
        s = math.sin(angle)
        return tuple((float(x + c * vx - s * vy), float(y + s * vx + c * vy)) for vx, vy in rows[:, :2])

    def __repr__(self) -> str:
        if self.world is None:
            state = "removed"
        else:
            state = "fixed" if self.is_fixed else "moving"
        return f"<Body {self.label()} {state}>"
