"""``pge.object``: the handle PGE scripts hold for colours, shapes, eye-candy and text.

As in the original, one class carries every method and each method checks the
kind of object it is called on (``obj.type``): physics methods need a box or
circle in level 0, ``set_colour`` something drawn, and so on. A wrong kind
raises TypeError with the message the original meant to give
(``"velocity: you cannot give a velocity to a colour object"``); a deleted
object raises ValueError (``"object has been deleted and now it is being
given a velocity"``).

Level-0 objects (``Shape``) are bodies of the session's ``pge.World``; every
physics method is one World call. A shape is *pending* until the next commit
point (see ``pge.classic.session``): until then its settings are kept here and
handed to ``World.add_circle``/``add_polygon`` in one go.
"""

from __future__ import annotations

import math

from pge.classic.constants import (
    KIND_NAMES,
    STILL_COMPONENT,
    box_t,
    circle_t,
    colour_t,
    fb_box_t,
    fb_circle_t,
    fb_text_t,
    spring_t,
)
from pge.classic.session import STATE, finite
from pge.geometry import check_vector

__all__ = ["Object", "Shape", "Decoration", "Text"]

_SHAPES = (box_t, circle_t)
_DRAWN = (box_t, circle_t, fb_box_t, fb_circle_t, fb_text_t)
_NAMES = {
    colour_t: "colour",
    box_t: "box",
    circle_t: "circle",
    spring_t: "spring",
    fb_box_t: "fb_box",
    fb_circle_t: "fb_circle",
    fb_text_t: "fb_text",
}

def _is_colour(value) -> bool:
    return isinstance(value, Object) and value.type == colour_t


class Object:
    """A PGE object: a colour, a box or circle in the physics (level 0), eye-candy or text.

    Public attributes, as in the original: ``type`` (``colour_t``, ``box_t``,
    ``circle_t``, ``fb_box_t``, ``fb_circle_t`` or ``fb_text_t``), ``level``
    and ``deleted``. Objects compare and hash by identity. Methods that
    configure an object return it, so calls chain:
    ``pge.circle(0.5, 0.5, 0.05, red).mass(1).velocity(0.2, 0)``.
    """

    def __init__(self, kind: int, level: int = 0, colour=None) -> None:
        self.type = kind
        self.level = level
        self.deleted = False
        self._colour = colour
        self._param = None
        self._width = None
        self._visible = True
        self._alpha = 1.0

    # ------------------------------------------------------------------ checks

    def _kind(self) -> str:
        return KIND_NAMES[self.type]

    def _need(self, kinds, method: str, verb: str) -> None:
        if self.type not in kinds:
            raise TypeError(f"{method}: you cannot {verb} a {self._kind()} object")

    def _shape(self, method: str, verb: str, given: str) -> Shape:
        """This object as a live level-0 shape, or the original's error for the wrong kind
        (TypeError) or a deleted object (ValueError)."""
        self._need(_SHAPES, method, verb)
        if self.deleted:
            raise ValueError(f"object has been deleted and now it is being given {given}")
        return self  # type: ignore[return-value]

    def _asked(self, method: str, what: str) -> Shape:
        self._need(_SHAPES, method, f"ask for the {what} of")
        if self.deleted:
            raise ValueError(f"object has been deleted and now it is being asked for its {what}")
        return self  # type: ignore[return-value]

    def _name(self) -> str:
        """The kind of object as a word (``"colour"``, ``"box"``, ``"circle"``, ...)."""
        return _NAMES[self.type]

    # ------------------------------------------------------------ motion state

    def velocity(self, vx, vy):
        """Set the velocity (world units per second); returns self.

        A fixed object keeps the velocity and moves with it once unfixed.
        """
        shape = self._shape("velocity", "give a velocity to", "a velocity")
        shape._set_velocity((finite("velocity", "vx", vx), finite("velocity", "vy", vy)))
        return self

    def accel(self, ax, ay):
        """Set the object's own constant acceleration (added to gravity); returns self."""
        shape = self._shape("accel", "give an acceleration to", "an acceleration")
        shape._user_accel = (finite("accel", "ax", ax), finite("accel", "ay", ay))
        shape._apply_accel()
        return self

    def fix(self):
        """Make the object immovable (infinitely heavy) where it is now; returns self.

        Its velocity is kept and used again by ``unfix()``.
        """
        shape = self._shape("fix", "fix", "a fixed position")
        if not shape._fixed:
            if shape._body is not None:
                shape._v = shape._body.velocity
                STATE.world.set_fixed(shape._body, True)
            shape._fixed = True
            STATE.unfixed.discard(shape)
        return self

    def unfix(self):
        """Let a fixed object move again with the velocity it had; returns self.

        It needs a mass before the simulation goes on (checked at the next
        commit point: the end of the current callback, or the next run).
        """
        shape = self._shape("unfix", "unfix", "an unfix")
        if shape._fixed:
            shape._fixed = False
            if shape._body is not None:
                STATE.world.set_fixed(shape._body, False)
            STATE.unfixed.add(shape)
        return self

    def is_fixed(self) -> bool:
        """True if the object is fixed."""
        shape = self._shape("is_fixed", "ask is_fixed of", "an is_fixed test")
        return shape._fixed

    def mass(self, m):
        """Set the mass (positive); returns self. Every moving object needs one."""
        shape = self._shape("mass", "give a mass to", "a mass")
        if m is None:
            raise ValueError("cannot give value None as the mass")
        m = finite("mass", "m", m)
        if m <= 0.0:
            raise ValueError(f"mass: m must be positive, got {m!r}")
        shape._mass = m
        if shape._body is not None:
            STATE.world.set_mass(shape._body, m)
        return self

    def get_mass(self):
        """The mass given with ``mass()``, or None."""
        self._need(_SHAPES, "get_mass", "ask for the mass of")
        return self._mass  # type: ignore[attr-defined]

    def apply_impulse(self, unit_vec, magnitude):
        """Apply an impulse of ``magnitude`` along the direction ``unit_vec``; returns self.

        The velocity changes by ``magnitude / mass`` along ``unit_vec``
        (normalised here, so any non-zero vector will do). Nothing happens to
        a fixed object; a moving one needs a mass.
        """
        shape = self._shape("apply_impulse", "give an impulse to", "an impulse")
        dx, dy = check_vector("apply_impulse", "unit_vec", unit_vec)
        magnitude = finite("apply_impulse", "magnitude", magnitude)
        length = math.hypot(dx, dy)
        if length == 0.0:
            raise ValueError("apply_impulse: unit_vec must not be the zero vector")
        if shape._fixed:
            return self
        body = shape._live()
        STATE.world.apply_impulse(body, (magnitude * dx / length, magnitude * dy / length))
        return self

    def moving_towards(self, x, y) -> bool:
        """True if the object is moving (not fixed) and its velocity points towards ``(x, y)``."""
        shape = self._asked("moving_towards", "motion")
        x, y = finite("moving_towards", "x", x), finite("moving_towards", "y", y)
        if shape._fixed:
            return False
        px, py = shape._position()
        vx, vy = shape._velocity()
        return (px - x) * vx + (py - y) * vy < 0.0

    def get_xpos(self) -> float:
        """x of the centre (circle) or area centroid (polygon) now."""
        return self._asked("get_xpos", "position")._position()[0]

    def get_ypos(self) -> float:
        """y of the centre (circle) or area centroid (polygon) now."""
        return self._asked("get_ypos", "position")._position()[1]

    def get_unit_coord(self) -> list:
        """``[x, y]``: the position now in world (unit) coordinates."""
        return list(self._asked("get_unit_coord", "position")._position())

    def get_xvel(self) -> float:
        """x velocity now, after the original's damping of both components (see
        ``pge.velocity_damping``; with ``velocity_damping(1.0)`` a read changes nothing)."""
        return self._asked("get_xvel", "velocity")._damp()[0]

    def get_yvel(self) -> float:
        """y velocity now, after the original's damping of both components (see ``get_xvel``)."""
        return self._asked("get_yvel", "velocity")._damp()[1]

    def get_xaccel(self) -> float:
        """The object's own x acceleration (without gravity)."""
        return self._asked("get_xaccel", "acceleration")._user_accel[0]

    def get_yaccel(self) -> float:
        """The object's own y acceleration (without world or object gravity)."""
        return self._asked("get_yaccel", "acceleration")._user_accel[1]

    def put_xvel(self, f):
        """Set the x velocity, keeping y, then damp both components as the original did (see
        ``get_xvel``); returns None (not chainable, as in PGE)."""
        shape = self._shape("put_xvel", "give a velocity to", "a velocity")
        shape._set_velocity((finite("put_xvel", "f", f), shape._velocity()[1]))
        shape._damp()

    def put_yvel(self, f):
        """Set the y velocity, keeping x, then damp both components (see ``put_xvel``); returns None."""
        shape = self._shape("put_yvel", "give a velocity to", "a velocity")
        shape._set_velocity((shape._velocity()[0], finite("put_yvel", "f", f)))
        shape._damp()

    def put_xaccel(self, f):
        """Set the object's own x acceleration; returns None."""
        shape = self._shape("put_xaccel", "give an acceleration to", "an acceleration")
        shape._user_accel = (finite("put_xaccel", "f", f), shape._user_accel[1])
        shape._apply_accel()

    def put_yaccel(self, f):
        """Set the object's own y acceleration; returns None."""
        shape = self._shape("put_yaccel", "give an acceleration to", "an acceleration")
        shape._user_accel = (shape._user_accel[0], finite("put_yaccel", "f", f))
        shape._apply_accel()

    # ------------------------------------------------------ extensions (motion)

    def elasticity(self, e):
        """Set this object's elasticity (0.0 to 1.0); returns self.

        Two touching objects bounce with the smaller of their elasticities.
        """
        shape = self._shape("elasticity", "give an elasticity to", "an elasticity")
        e = finite("elasticity", "e", e)
        if not 0.0 <= e <= 1.0:
            raise ValueError(f"elasticity: e must be between 0.0 and 1.0, got {e!r}")
        shape._own_elasticity = e
        if shape._body is not None:
            STATE.world.set_elasticity(shape._body, e)
        return self

    def rotate(self, angle):
        """Turn the object to ``angle`` radians (anticlockwise) about its centre; returns self."""
        shape = self._shape("rotate", "rotate", "a rotation")
        angle = finite("rotate", "angle", angle)
        if shape._body is not None:
            STATE.world.set_angle(shape._body, angle)
        shape._angle = angle
        return self

    def rvel(self, omega):
        """Set the angular velocity in radians per second (anticlockwise); returns self."""
        shape = self._shape("rvel", "give an angular velocity to", "an angular velocity")
        omega = finite("rvel", "omega", omega)
        if shape._body is not None:
            STATE.world.set_angular_velocity(shape._body, omega)
        shape._rvel = omega
        return self

    def friction(self, mu):
        """Set the Coulomb friction coefficient (0 or more; default 0, as in the original, which
        has no friction); returns self. Two objects' coefficients combine by the larger."""
        shape = self._shape("friction", "give a friction to", "a friction")
        mu = finite("friction", "mu", mu)
        if mu < 0.0:
            raise ValueError(f"friction: mu must not be negative, got {mu!r}")
        if shape._body is not None:
            STATE.world.set_friction(shape._body, mu)
        shape._friction = mu
        return self

    def get_friction(self) -> float:
        """The Coulomb friction coefficient."""
        shape = self._asked("get_friction", "friction")
        return shape._body.friction if shape._body is not None else shape._friction

    def get_angle(self) -> float:
        """Orientation in radians."""
        shape = self._asked("get_angle", "angle")
        return shape._body.angle if shape._body is not None else shape._angle

    def get_rvel(self) -> float:
        """Angular velocity in radians per second."""
        shape = self._asked("get_rvel", "angular velocity")
        return shape._body.angular_velocity if shape._body is not None else shape._rvel

    def set_gravity(self, g):
        """Give the object gravity ``g`` of its own, added to the world's (y, e.g. -9.81 pulls
        down); returns self."""
        shape = self._shape("set_gravity", "give a gravity to", "a gravity")
        shape._gravity = finite("set_gravity", "g", g)
        shape._apply_accel()
        return self

    def get_gravity(self) -> float:
        """The object's own gravity (0.0 unless ``set_gravity`` was called)."""
        return self._asked("get_gravity", "gravity")._gravity

    # --------------------------------------------------------------- callbacks

    def on_collision(self, p):
        """Call ``p(obj, event)`` after every collision of this object; returns self.

        Replaces any previous collision callback of the object.
        """
        return self.on_collision_with([], p)

    def on_collision_with(self, another, p):
        """Call ``p(obj, event)`` after this object hits one of the objects in ``another``.

        ``another`` is kept by reference: objects appended later count too. An
        empty list means every collision. Returns self.
        """
        shape = self._shape("on_collision_with", "give a collision callback to", "a collision callback")
        if not callable(p):
            raise TypeError(f"on_collision_with: p must be callable as p(obj, event), got {p!r}")
        if not (hasattr(another, "__len__") and hasattr(another, "__contains__")):
            raise TypeError(f"on_collision_with: another must be a list of objects, got {another!r}")
        shape._callback = p
        shape._with = another
        shape._listen()
        return self

    # ------------------------------------------------------------ bookkeeping

    def rm(self):
        """Remove the object (from the physics and from drawing) now; returns None.

        Safe inside callbacks; removing twice does nothing.
        """
        if self.deleted:
            return
        self.deleted = True
        self._remove()
        STATE.changed()
        return

    def _remove(self) -> None:
        pass

    def get_param(self):
        """The value given with ``set_param`` (None until then)."""
        return self._param

    def set_param(self, value):
        """Keep any value with the object; returns self."""
        self._param = value
        return self

    def set_width(self, value):
        """Keep a width with the object (``box`` stores its width); returns None."""
        self._width = value

    def get_width(self):
        """The width kept with ``set_width``."""
        self._need(_SHAPES, "get_width", "ask for the width of")
        return self._width

    def get_colour(self):
        """The object's colour (a colour returns itself)."""
        return self._colour

    def set_colour(self, c):
        """Draw the object in colour ``c`` from the next frame on; returns self."""
        self._need(_DRAWN, "set_colour", "set the colour of")
        if not _is_colour(c):
            raise TypeError("first parameter to set_colour is expected to be a colour")
        self._colour = c
        self._recoloured()
        STATE.changed()
        return self

    def _recoloured(self) -> None:
        pass

    def set_alpha(self, value):
        """Draw the object with opacity ``value``: 0.0 invisible to 1.0 opaque; returns self."""
        self._need(_DRAWN, "set_alpha", "set the transparency of")
        value = finite("set_alpha", "value", value)
        if not 0.0 <= value <= 1.0:
            raise ValueError(f"set_alpha: value must be between 0.0 and 1.0, got {value!r}")
        self._alpha = value
        STATE.changed()
        return self

    def set_visible(self, value):
        """Show (True) or hide (False) the object; physics is unaffected. Returns self."""
        self._need(_DRAWN, "set_visible", "set the visibility of")
        self._visible = bool(value)
        STATE.changed()
        return self

    # ----------------------------------------------------------------- springs

    def _spring_object(self, method: str, verb: str, given: str):
        """This object as a live spring, or TypeError (not a spring) / ValueError (deleted)."""
        self._need((spring_t,), method, verb)
        if self.deleted:
            raise ValueError(f"object has been deleted and now it is being given {given}")
        return self

    def draw(self, c, w):
        """Draw this spring in a window as a filled band ``w`` wide (world units) between the two
        centres, in colour ``c``; returns self. Springs not drawn are invisible."""
        from pge.classic.springs import check_drawing

        spring = self._spring_object("draw", "draw a spring on", "a spring drawing")
        spring._set_drawing(c, check_drawing("draw", c, w))
        return self

    def end(self, c):
        """Debug colour for the moments the spring is at an extreme (PGE drew extra frames then);
        kept, not drawn. Returns self."""
        from pge.classic.springs import check_drawing

        spring = self._spring_object("end", "give a spring end colour to", "a spring end colour")
        check_drawing("end", c)
        spring._end_colour = c
        return self

    def mid(self, c):
        """Debug colour for the moments the spring passes its rest length; kept, not drawn.
        Returns self."""
        from pge.classic.springs import check_drawing

        spring = self._spring_object("mid", "give a spring mid colour to", "a spring mid colour")
        check_drawing("mid", c)
        spring._mid_colour = c
        return self

    def when(self, l, p):
        """Call ``p(event, spring)`` once, at the first time from now that the spring's length is
        ``l`` (stretching or shortening); returns self.

        ``event`` is a function event; its ``get_timer_id()`` comes from the
        ``at_time`` counter and ``at_cancel`` cancels it.
        """
        spring = self._spring_object("when", "give a length callback to", "a length callback")
        l = finite("when", "l", l)
        if l <= 0.0:
            raise ValueError(f"when: l must be positive, got {l!r}")
        if not callable(p):
            raise TypeError(f"when: p must be callable as p(event, spring), got {p!r}")
        spring._watch_length(l, p)
        return self

    def __repr__(self) -> str:
        state = " deleted" if self.deleted else ""
        return f"<pge {self._kind()} object{state}>"


class Shape(Object):
    """A box, polygon or circle in level 0: a body of the session's World."""

    def __init__(self, kind: int, colour, shape, position, points, description: str) -> None:
        super().__init__(kind, 0, colour)
        self._geometry = shape  # pge.shapes.Circle or Polygon (validated)
        self._points = points  # polygon vertices as given (None for a circle)
        self._where = position  # centre or centroid while pending
        self._description = description
        self._body = None
        self._fixed = False
        self._mass = None
        self._v = (0.0, 0.0)  # velocity while pending or fixed
        self._user_accel = (0.0, 0.0)
        self._gravity = 0.0
        self._own_elasticity = None
        self._angle = 0.0
        self._rvel = 0.0
        self._friction = 0.0
        self._callback = None
        self._with = []
        self._listening = False
        STATE.shapes[self] = None
        STATE.pending.append(self)
        STATE.changed()

    @property
    def body(self):
        """The ``pge.Body`` of this object in the World (None while pending or once deleted)."""
        return self._body

    def _no_mass_message(self) -> str:
        return (
            f"{self._description} is not fixed and has no mass: all moving objects must have a mass "
            "(give it one with .mass(m), or .fix() it)"
        )

    def _elasticity_value(self) -> float:
        return STATE.elasticity if self._own_elasticity is None else self._own_elasticity

    def _materialise(self):
        """Add this object to the World with everything set so far."""
        if not self._fixed and self._mass is None:
            raise ValueError(self._no_mass_message())
        world = STATE.world
        options = {
            "mass": self._mass,
            "velocity": self._v,
            "acceleration": self._own_accel(),
            "fixed": self._fixed,
            "elasticity": self._elasticity_value(),
            "angle": self._angle,
            "angular_velocity": self._rvel,
            "friction": self._friction,
            "data": {"colour": self._colour.rgb255(), "object": self},
            "name": self._description,
        }
        if self.type == circle_t:
            body = world.add_circle(self._where, self._geometry.radius, **options)
        else:
            body = world.add_polygon(self._points, **options)
        self._body = body
        if self._callback is not None:
            self._listen()
        STATE.changed()
        return body

    def _live(self):
        """The World body, adding the object to the World now if it is still pending."""
        if self._body is None:
            self._materialise()
            if self in STATE.pending:
                STATE.pending.remove(self)
        return self._body

    def _listen(self) -> None:
        if self._body is not None and not self._listening:
            from pge.classic.events import dispatch_collision

            STATE.world.on_collision(dispatch_collision, self._body)
            self._listening = True

    def _position(self) -> tuple[float, float]:
        return self._where if self._body is None else self._body.position

    def _velocity(self) -> tuple[float, float]:
        if self._body is None or self._fixed:
            return self._v
        return self._body.velocity

    def _damp(self) -> tuple[float, float]:
        """The original's velocity damping on a read or write (its ``checkStationary``): both
        components times ``STATE.damping``, those then below ``STILL_COMPONENT`` set to 0.
        Returns the velocity after it."""
        v = self._velocity()
        factor = STATE.damping
        if factor == 1.0:
            return v
        damped = tuple(0.0 if abs(c * factor) < STILL_COMPONENT else c * factor for c in v)
        if damped != tuple(v):
            self._set_velocity(damped)
        return damped

    def _set_velocity(self, v) -> None:
        if self._body is None or self._fixed:
            self._v = v
        if self._body is not None:
            STATE.world.set_velocity(self._body, v)

    def _own_accel(self) -> tuple[float, float]:
        return (self._user_accel[0], self._user_accel[1] + self._gravity)

    def _apply_accel(self) -> None:
        if self._body is not None:
            STATE.world.set_acceleration(self._body, self._own_accel())

    def _remove(self) -> None:
        STATE.shapes.pop(self, None)
        STATE.unfixed.discard(self)
        if self._body is not None:
            STATE.world.remove(self._body)  # takes the springs attached to it
            for spring in [s for s in STATE.springs if not s._spring.alive]:
                spring.deleted = True
                del STATE.springs[spring]
        elif self in STATE.pending:
            STATE.pending.remove(self)

    def _recoloured(self) -> None:
        if self._body is not None:
            self._body.data["colour"] = self._colour.rgb255()

    def __repr__(self) -> str:
        if self.deleted:
            state = "deleted"
        else:
            state = ("fixed" if self._fixed else "moving") + (" pending" if self._body is None else "")
        return f"<pge {self._description} {state}>"


class Decoration(Object):
    """Eye-candy: a circle or polygon drawn in level ``level`` (not 0), outside the physics."""

    def __init__(self, kind: int, level: int, colour, circle=None, points=None) -> None:
        super().__init__(kind, level, colour)
        self._circle = circle  # (x, y, r) or None
        self._points = points  # [(x, y), ...] or None
        STATE.levels.setdefault(level, {})[self] = None
        STATE.changed()

    def _remove(self) -> None:
        STATE.levels.get(self.level, {}).pop(self, None)


class Text(Decoration):
    """Text drawn in level ``level`` (not 0) with its top-left corner at ``(x, y)``."""

    def __init__(self, x: float, y: float, s: str, colour, size: int, level: int) -> None:
        self._text = (x, y, s, size)
        super().__init__(fb_text_t, level, colour)
