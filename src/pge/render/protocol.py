"""The drawing protocol: what a frame is drawn through, and the null backend.

Coordinates are world coordinates (the unit square, y up); colours are
``(r, g, b, a)`` tuples of 0..255 integers. A backend maps the world to its
pixels. ``pge.render.pygame_display.PygameDisplay`` draws into a window; the
``NullDisplay`` accepts everything and draws nothing (headless runs).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Protocol

__all__ = ["Display", "NullDisplay", "RGBA"]

RGBA = tuple[int, int, int, int]


class Display(Protocol):
    """A place frames are drawn to."""

    #: False for a backend that ignores drawing (callers may then skip composing frames).
    draws: bool

    def begin_frame(self, background: RGBA) -> None:
        """Start a frame: clear to ``background``."""

    def circles(self, xs, ys, radii, colours, index=None) -> None:
        """Filled circles with centres ``(xs[k], ys[k])`` and radii ``radii[k]`` (arrays).

        ``colours`` is one RGBA tuple for all of them, or a sequence of one per
        circle, or, with ``index`` (an integer array), a palette: circle ``k``
        has colour ``colours[index[k]]``.
        """

    def circle(self, x: float, y: float, r: float, colour: RGBA) -> None:
        """One filled circle."""

    def polygon(self, points: Sequence[tuple[float, float]], colour: RGBA) -> None:
        """One filled polygon through ``points``."""

    def text(self, x: float, y: float, s: str, colour: RGBA, size: int) -> None:
        """Text ``size`` pixels high with its top-left corner at ``(x, y)``."""

    def end_frame(self) -> None:
        """Finish the frame and show it."""

    def events(self) -> list:
        """Input events since the last call (keyboard, mouse, window)."""

    def is_quit(self, event) -> bool:
        """True for a request to close the window."""

    def key_name(self, event) -> str | None:
        """The name of the key pressed, as ``pygame.key.name`` spells it (``"space"``,
        ``"left"``, ``"page up"``, ``"q"``), for a key-press event; None for any other event."""

    def close(self) -> None:
        """Release the backend (close the window)."""


class NullDisplay:
    """A display that draws nothing and never has input: used by headless runs."""

    draws = False

    def begin_frame(self, background) -> None:
        pass

    def circles(self, xs, ys, radii, colours, index=None) -> None:
        pass

    def circle(self, x, y, r, colour) -> None:
        pass

    def polygon(self, points, colour) -> None:
        pass

    def text(self, x, y, s, colour, size) -> None:
        pass

    def end_frame(self) -> None:
        pass

    def events(self) -> list:
        return []

    def is_quit(self, event) -> bool:
        return False

    def key_name(self, event) -> str | None:
        return None

    def close(self) -> None:
        pass
