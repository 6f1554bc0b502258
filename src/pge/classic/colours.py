"""Colours of the classic ``pge`` module: ``rgb(r, g, b)`` and ``white()``.

A colour is a PGE object (``obj.type == colour_t``) whose ``get_colour()``
returns itself. Each call makes a new colour object, even for equal values;
colours compare and hash by identity, so scripts can use them as dict keys.
"""

from __future__ import annotations

from pge.classic.constants import colour_t
from pge.classic.objects import Object
from pge.classic.session import finite

__all__ = ["Colour", "rgb", "white", "is_colour"]


class Colour(Object):
    """A colour: red, green and blue intensities between 0.0 and 1.0."""

    def __init__(self, r: float, g: float, b: float) -> None:
        super().__init__(colour_t, 0)
        self.red, self.green, self.blue = r, g, b
        self._colour = self

    def rgb255(self) -> tuple[int, int, int]:
        """The colour as 0..255 integers."""
        return (_byte(self.red), _byte(self.green), _byte(self.blue))

    def __repr__(self) -> str:
        return f"<pge colour rgb({self.red:g}, {self.green:g}, {self.blue:g})>"


def _byte(value: float) -> int:
    return int(round(value * 255.0))


def _fraction(owner: str, what: str, value) -> float:
    value = finite(owner, what, value)
    if not 0.0 <= value <= 1.0:
        raise ValueError(f"{owner}: {what} must be between 0.0 and 1.0, got {value!r}")
    return value


def rgb(r, g, b) -> Colour:
    """A new colour with red ``r``, green ``g`` and blue ``b``, each from 0.0 to 1.0.

    Works before ``batch()``/``interactive()`` (the original exits then).
    Raises TypeError for a value that is not a number, ValueError outside 0..1.
    """
    return Colour(_fraction("rgb", "r", r), _fraction("rgb", "g", g), _fraction("rgb", "b", b))


def white() -> Colour:
    """A new white colour object, ``rgb(1.0, 1.0, 1.0)``."""
    return Colour(1.0, 1.0, 1.0)


def is_colour(value) -> bool:
    """True for a colour object."""
    return isinstance(value, Colour)
