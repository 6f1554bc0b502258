"""Object constructors of the classic ``pge`` module: box, poly3..poly6, polygon, circle, text, spring.

Level 0 (the default) puts the object in the physics: it starts unfixed, at
rest, without a mass. Any other level makes eye-candy that is only drawn:
negative levels behind the physics, positive ones in front, lower levels
first. Coordinates are world (unit-square) coordinates with y up; polygons
take their vertices in order, either winding, and must be convex in level 0.
"""

from __future__ import annotations

from pge.classic.constants import box_t, circle_t, fb_box_t, fb_circle_t
from pge.classic.objects import Decoration, Object, Shape, Text
from pge.classic.session import finite, positive
from pge.classic.springs import spring
from pge.shapes import Circle, Polygon

__all__ = ["box", "poly3", "poly4", "poly5", "poly6", "polygon", "circle", "text", "spring"]


def _colour(value, message: str):
    from pge.classic.colours import is_colour

    if not is_colour(value):
        raise TypeError(message)
    return value


def _level(owner: str, level) -> int:
    if isinstance(level, bool) or not isinstance(level, int):
        raise TypeError(f"{owner}: level must be an integer, got {level!r}")
    return level


def _fmt(*values) -> str:
    return ", ".join(f"{v:g}" for v in values)


def _make_polygon(owner: str, points, colour, level: int, description: str) -> Object:
    if level == 0:
        shape, centroid = Polygon.from_points(points, owner)
        return Shape(box_t, colour, shape, centroid, list(points), description)
    return Decoration(fb_box_t, level, colour, points=list(points))


def _vertices(owner: str, coordinates) -> list[tuple[float, float]]:
    names = []
    for k in range(len(coordinates) // 2):
        names += [f"x{k}", f"y{k}"]
    values = [finite(owner, name, value) for name, value in zip(names, coordinates)]
    return list(zip(values[0::2], values[1::2]))


def box(x, y, w, h, c, level=0):
    """An axis-aligned rectangle with lower-left corner ``(x, y)``, width ``w``, height ``h``.

    Also stores ``w`` with ``set_width``. Raises TypeError if ``c`` is not a colour.
    """
    _colour(c, "fifth parameter to box is expected to be a colour")
    level = _level("box", level)
    x, y = finite("box", "x", x), finite("box", "y", y)
    w, h = positive("box", "w", w), positive("box", "h", h)
    corners = [(x, y), (x + w, y), (x + w, y + h), (x, y + h)]
    obj = _make_polygon("box", corners, c, level, f"box ({_fmt(x, y, w, h)})")
    obj.set_width(w)
    return obj


def _poly(owner: str, coordinates, c, level, ordinal: str) -> Object:
    _colour(c, f"{ordinal} parameter to {owner} is expected to be a colour")
    level = _level(owner, level)
    points = _vertices(owner, coordinates)
    description = f"{owner} (" + ", ".join(f"({_fmt(*p)})" for p in points) + ")"
    return _make_polygon(owner, points, c, level, description)


def poly3(x0, y0, x1, y1, x2, y2, c, level=0):
    """A triangle through three vertices."""
    return _poly("poly3", (x0, y0, x1, y1, x2, y2), c, level, "seventh")


def poly4(x0, y0, x1, y1, x2, y2, x3, y3, c, level=0):
    """A convex quadrilateral through four vertices in order."""
    return _poly("poly4", (x0, y0, x1, y1, x2, y2, x3, y3), c, level, "ninth")


def poly5(x0, y0, x1, y1, x2, y2, x3, y3, x4, y4, c, level=0):
    """A convex pentagon through five vertices in order."""
    return _poly("poly5", (x0, y0, x1, y1, x2, y2, x3, y3, x4, y4), c, level, "eleventh")


def poly6(x0, y0, x1, y1, x2, y2, x3, y3, x4, y4, x5, y5, c, level=0):
    """A convex hexagon through six vertices in order."""
    return _poly("poly6", (x0, y0, x1, y1, x2, y2, x3, y3, x4, y4, x5, y5), c, level, "thirteenth")


def polygon(points, colour, level=0):
    """A convex polygon through ``points``, a sequence of ``(x, y)`` pairs in order (3 or more)."""
    _colour(colour, "second parameter to polygon is expected to be a colour")
    level = _level("polygon", level)
    try:
        pairs = [tuple(p) for p in points]
    except TypeError:
        raise TypeError(f"polygon: points must be a sequence of (x, y) pairs, got {points!r}") from None
    if any(len(p) != 2 for p in pairs):
        raise ValueError(f"polygon: every point must be an (x, y) pair, got {points!r}")
    flat = [value for pair in pairs for value in pair]
    return _poly("polygon", flat, colour, level, "second")


def circle(x, y, r, c, level=0):
    """A circle centred at ``(x, y)`` with radius ``r``."""
    _colour(c, "fourth parameter to circle is expected to be a colour")
    level = _level("circle", level)
    x, y = finite("circle", "x", x), finite("circle", "y", y)
    r = positive("circle", "r", r)
    if level == 0:
        return Shape(circle_t, c, Circle(r, "circle"), (x, y), None, f"circle ({_fmt(x, y, r)})")
    return Decoration(fb_circle_t, level, c, circle=(x, y, r))


def text(x, y, s, c, size, level):
    """Text ``s`` in colour ``c``, ``size`` pixels high, top-left corner at ``(x, y)``.

    Text is eye-candy: ``level`` must not be 0. Shown only in a window.
    """
    _colour(c, "fourth parameter to text is expected to be a colour")
    level = _level("text", level)
    if level == 0:
        raise ValueError("not allowed to place in level 0")
    x, y = finite("text", "x", x), finite("text", "y", y)
    size = positive("text", "size", size)
    return Text(x, y, str(s), c, max(1, int(round(size))), level)
