"""Springs of the classic ``pge`` module: ``spring(ob1, ob2, k, d, l)`` and its object.

A spring object is a ``pge.object`` of type ``spring_t`` wrapping a
``pge.springs.Spring`` of the session's World (no physics here). Its methods:

* ``draw(c, w)``: draw it in a window as a filled band of width ``w`` between
  the two centres, in colour ``c``, on top of the level-0 objects (an
  undrawn spring is invisible, as in PGE). Recordings hold bodies only, so
  springs are not recorded.
* ``end(c)``, ``mid(c)``: the original's debug colours for the extra frames
  it drew when a spring reached an extreme or its rest length. Checked and
  kept, but no debug frames are drawn.
* ``when(l, p)``: call ``p(event, spring)`` once, at the first time the
  length is ``l``. The event is a function event whose ``get_timer_id()`` is
  an id from the same counter as ``at_time`` (so ``at_cancel`` cancels it).
* ``rm()``: remove the spring. Removing either end removes it too.
"""

from __future__ import annotations

import math

from pge.classic.constants import function_event, spring_t
from pge.classic.events import event
from pge.classic.objects import Object, Shape, _is_colour
from pge.classic.session import STATE, finite, positive
from pge.events import Timer

__all__ = ["SpringObject", "spring", "check_drawing", "band"]


class SpringObject(Object):
    """A spring between two level-0 objects (``type == spring_t``); made by ``pge.spring``."""

    def __init__(self, spring, ends) -> None:
        super().__init__(spring_t, 0, None)
        self._spring = spring  # pge.springs.Spring
        self._ends = ends  # the two pge objects
        self._band = None  # width of the drawn band, None while not drawn
        self._end_colour = None
        self._mid_colour = None
        STATE.springs[self] = None
        STATE.changed()

    @property
    def spring(self):
        """The ``pge.springs.Spring`` of this object in the World (not a PGE name)."""
        return self._spring

    def _set_drawing(self, c, w) -> None:
        self._colour = c
        self._band = w
        STATE.changed()

    def _watch_length(self, length: float, p) -> int:
        def reached(record) -> None:
            callback = STATE.timers.pop(record.watch_id, None)
            if callback is None:
                return  # cancelled with at_cancel
            if STATE.recorder is not None:
                STATE.recorder.timer(Timer(record.time, record.watch_id))
            STATE.call(callback, event(function_event, record.time, timer_id=record.watch_id), self)

        watch_id = self._spring.when(length, reached)
        STATE.timers[watch_id] = p
        STATE.last_timer = max(STATE.last_timer, watch_id)
        return watch_id

    def _remove(self) -> None:
        STATE.springs.pop(self, None)
        if self._spring.alive:
            STATE.world.remove_spring(self._spring)

    def __repr__(self) -> str:
        state = " deleted" if self.deleted else ""
        return f"<pge spring object{state}>"


def _end(owner: str, which: str, obj) -> Shape:
    if not isinstance(obj, Object):
        raise TypeError(f"{owner}: {which} must be a pge box or circle object, got {type(obj).__name__} {obj!r}")
    shape = obj._shape(owner, "attach a spring to", "a spring attachment")
    if not shape._fixed and shape._mass is None:
        raise ValueError(
            f"{owner}: {shape._description} must be fixed or have a mass before a spring is attached to it"
        )
    return shape


def spring(ob1, ob2, k, d, l=None):
    """A spring between the centres of ``ob1`` and ``ob2``: stiffness ``k`` (force per unit
    length), damping ``d`` (force per unit speed), rest length ``l`` (default: their distance
    now). Returns a ``spring_t`` object.

    Tension-only, as in PGE: it pulls while longer than ``l`` and does nothing
    while shorter. Both ends must be boxes or circles in level 0, fixed or
    with a mass (as the original required); they join the simulation now.
    Bad values raise TypeError or ValueError and nothing changes.
    """
    first = _end("spring", "ob1", ob1)
    second = _end("spring", "ob2", ob2)
    if first is second:
        raise ValueError("spring: ob1 and ob2 must be two different objects")
    k = finite("spring", "k", k)
    d = finite("spring", "d", d)
    l = None if l is None else finite("spring", "l", l)
    for name, value in (("k", k), ("d", d), ("l", l)):
        if value is not None and value < 0.0:
            raise ValueError(f"spring: {name} must not be negative, got {value!r}")
    a = first._live()
    b = second._live()
    made = STATE.world.add_spring(a, b, k, d, l)
    return SpringObject(made, (first, second))


def check_drawing(owner: str, c, w=None):
    """Checks of ``draw``/``end``/``mid`` arguments: ``c`` a colour, ``w`` positive."""
    if not _is_colour(c):
        raise TypeError(f"first parameter to {owner} is expected to be a colour")
    return None if w is None else positive(owner, "w", w)


def band(obj: SpringObject):
    """Corners of the drawn band of a spring now, or None if its ends coincide."""
    (xa, ya), (xb, yb) = obj._spring.a.position, obj._spring.b.position
    dx, dy = xb - xa, yb - ya
    length = math.hypot(dx, dy)
    if length == 0.0:
        return None
    half = 0.5 * obj._band / length
    nx, ny = -dy * half, dx * half
    return [(xa + nx, ya + ny), (xb + nx, yb + ny), (xb - nx, yb - ny), (xa - nx, ya - ny)]
