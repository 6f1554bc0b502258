"""Utilities of the classic ``pge`` module: vectors, pixel coordinates, fonts, sound, dump_world.

Vectors are ``[x, y]`` lists as in PGE. Pixel coordinates follow the window
of ``display_set_mode`` (see ``pge.render.pygame_display``: a uniform scale of
``min(width, height)`` pixels per world unit, y up from the bottom edge).
"""

from __future__ import annotations

import math

from pge.classic.constants import circle_t
from pge.classic.session import STATE

__all__ = [
    "dump_world",
    "play",
    "message",
    "get_font",
    "flip",
    "pyg_to_unit_coord",
    "normalise",
    "magnitude",
    "sub_coord",
    "toFloat",
]


def _resolution(owner: str) -> tuple[int, int]:
    display = STATE.display
    if display is not None and getattr(display, "draws", False):
        return (display.width, display.height)
    if STATE.resolution is None:
        raise ValueError(
            f"you must assign the screen resolution with a call to 'display_set_mode' before calling '{owner}'"
        )
    return STATE.resolution


def pyg_to_unit_coord(v) -> list:
    """World coordinates ``[x, y]`` of the pixel position ``v = [px, py]`` (e.g. a mouse click)."""
    width, height = _resolution("pyg_to_unit_coord")
    try:
        px, py = v
        px, py = float(px), float(py)
    except (TypeError, ValueError):
        raise ValueError("'pyg_to_unit_coord' expects a list of two integers") from None
    scale = min(width, height)
    return [px / scale, (height - py) / scale]


def flip(y) -> int:
    """The pixel row ``y`` counted from the bottom of the window instead of the top."""
    return _resolution("flip")[1] - y


def normalise(v) -> list:
    """``v`` scaled to length 1; ValueError for the zero vector."""
    length = magnitude(v)
    if length == 0.0:
        raise ValueError("normalise: the zero vector has no direction")
    return [v[0] / length, v[1] / length]


def magnitude(v) -> float:
    """Length of the vector ``v = [x, y]``."""
    return math.hypot(v[0], v[1])


def sub_coord(a, b) -> list:
    """``a - b`` for vectors ``[x, y]``."""
    return [a[0] - b[0], a[1] - b[1]]


def toFloat(f) -> float:
    """The value of a fraction tuple ``(whole, numerator, denominator)``."""
    whole, numerator, denominator = f
    if numerator == 0 or denominator == 0:
        return float(whole)
    return whole + numerator / denominator


def get_font(size):
    """pygame's default font, ``size`` pixels high."""
    from pge.render.pygame_display import font

    return font(int(size))


def play(name) -> None:
    """Play the sound file ``name`` in a window (nothing headless, or without an audio device)."""
    display = STATE.display
    if display is not None and getattr(display, "draws", False):
        display.play(str(name))


def message(text) -> None:
    """A message for the recording (kept only if the recorder can store messages)."""
    recorder = STATE.recorder
    if recorder is not None and hasattr(recorder, "message"):
        recorder.message(str(text))


def dump_world() -> None:
    """Print every level-0 object (kind, state, position, size, mass, velocity, colour), then
    every spring (its ends, stiffness, damping, rest length and length now)."""
    print(f"pge world at time {STATE.now()!r}: {len(STATE.shapes)} objects")
    for number, obj in enumerate(STATE.shapes, start=1):
        state = "fixed" if obj._fixed else "movable"
        kind = "circle" if obj.type == circle_t else "polygon"
        x, y = obj._position()
        vx, vy = obj._velocity()
        colour = obj._colour
        line = f"object {number} is {state} {kind} at ({x!r}, {y!r})"
        if obj.type == circle_t:
            line += f" radius {obj._geometry.radius!r}"
        else:
            corners = obj._points if obj._body is None else list(obj._body.vertices)
            line += f" points {corners!r}"
        line += f" mass {obj._mass!r} velocity ({vx!r}, {vy!r})"
        line += f" colour rgb({colour.red:g}, {colour.green:g}, {colour.blue:g})"
        if obj._body is None:
            line += " (pending: joins the simulation at the next commit point)"
        print(line)
    numbers = {obj: number for number, obj in enumerate(STATE.shapes, start=1)}
    for obj in STATE.springs:
        spring = obj.spring
        first, second = (numbers.get(end, "?") for end in obj._ends)
        print(
            f"spring between object {first} and object {second}: k {spring.stiffness!r} "
            f"d {spring.damping!r} rest length {spring.rest_length!r} length {spring.length!r}"
        )
