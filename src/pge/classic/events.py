"""Events handed to PGE callbacks, collision dispatch, and timers (``at_time``, ``at_cancel``).

Callback argument orders are the original's:

* ``obj.on_collision(p)`` / ``obj.on_collision_with(lst, p)``: ``p(obj, event)``, object first;
* ``pge.at_time(t, p)``: ``p(event, None)``, event first;
* ``spring.when(l, p)``: ``p(event, spring)``, event first (a function event; its timer id
  comes from the ``at_time`` counter, see ``pge.classic.springs``).

At a collision the callbacks of both objects run after the bounce, in
``event.collision_between()`` order (for a circle and a polygon, the polygon
first), with the same event object. A callback that removes the other object
does not stop that object's callback from running for this event.
"""

from __future__ import annotations

from pge.classic.constants import circle_t, collision_event, function_event
from pge.classic.session import STATE, finite

__all__ = ["event", "dispatch_collision", "at_time", "at_cancel"]


class event:  # the original's lower-case class name
    """What happened: a collision, or a timer firing. ``type`` is ``collision_event`` or
    ``function_event``."""

    __slots__ = ("_cancelled", "_pair", "_point", "_time", "_timer_id", "type")

    def __init__(self, kind: int, time: float, pair=None, point=None, timer_id=None) -> None:
        self.type = kind
        self._time = time
        self._pair = pair
        self._point = point
        self._timer_id = timer_id
        self._cancelled = False

    def collision_between(self) -> list:
        """``[ob1, ob2]``, the two objects that collided (a polygon before a circle).

        Raises TypeError for an event that is not a collision.
        """
        if self.type != collision_event:
            raise TypeError("collision_between: this event is a timer, not a collision")
        return list(self._pair)

    def cancel(self) -> None:
        """Mark the event as cancelled (a flag only: the bounce has already happened)."""
        self._cancelled = True

    def was_cancelled(self) -> bool:
        """True once ``cancel()`` was called."""
        return self._cancelled

    def get_timer_id(self):
        """The id ``at_time`` returned, for a timer event; None for a collision."""
        return self._timer_id

    def get_time(self) -> float:
        """Simulation time of the event in seconds."""
        return self._time

    def get_point(self):
        """The contact point ``[x, y]`` of a collision; None for a timer event."""
        return None if self._point is None else list(self._point)

    def __repr__(self) -> str:
        if self.type == collision_event:
            return f"<pge collision event at {self._time!r}>"
        return f"<pge timer event {self._timer_id} at {self._time!r}>"


_last_record = None


def _ordered(a, b) -> tuple:
    if a.type == circle_t and b.type != circle_t:
        return (b, a)
    return (a, b)


def dispatch_collision(record) -> None:
    """World callback for bodies whose objects have PGE collision callbacks.

    The World calls it once for each such body of a collision; the first call
    runs the PGE callbacks of both objects, later calls for the same record
    return at once.
    """
    global _last_record
    if record is _last_record or record.a is None or record.b is None:
        return
    _last_record = record
    pair = _ordered(record.a.data["object"], record.b.data["object"])
    happened = event(collision_event, record.time, pair, record.point)
    for obj in pair:
        callback = obj._callback
        if callback is None:
            continue
        others = obj._with
        if len(others) == 0 or pair[0] in others or pair[1] in others:
            STATE.call(callback, obj, happened)


def at_time(t, p) -> int:
    """Call ``p(event, None)`` once, ``t`` wall-clock seconds from now; returns the timer id.

    The simulation runs ``slow_down`` times slower than the wall clock, so the
    timer fires ``t / slow_down`` simulated seconds from now (in a window and
    headless alike, so both runs see the same events). Re-arm it in the
    callback for a periodic timer. Raises ValueError for a negative ``t``.
    """
    t = finite("at_time", "t", t)
    if t < 0.0:
        raise ValueError(f"at_time: t must not be negative, got {t!r}")
    if not callable(p):
        raise TypeError(f"at_time: p must be callable as p(event, None), got {p!r}")
    world = STATE.world
    timer_id = world.at_time(world.time + t / STATE.slow, _fire)
    STATE.timers[timer_id] = p
    STATE.last_timer = max(STATE.last_timer, timer_id)
    return timer_id


def _fire(record) -> None:
    callback = STATE.timers.pop(record.timer_id, None)
    if callback is None:
        return
    if STATE.recorder is not None:
        STATE.recorder.timer(record)
    STATE.call(callback, event(function_event, record.time, timer_id=record.timer_id), None)


def at_cancel(i) -> None:
    """Cancel the timer ``i`` returned by ``at_time``, or a spring's ``when`` with that id
    (nothing if it has already fired).

    Raises ValueError for an id ``at_time`` never returned.
    """
    if i in STATE.timers:
        del STATE.timers[i]
        if not STATE.world.cancel_timer(i):
            for obj in STATE.springs:  # a spring's when() shares the ids
                if obj._spring.alive and obj._spring.cancel_when(i):
                    break
        return
    if not (isinstance(i, int) and not isinstance(i, bool) and 1 <= i <= STATE.last_timer):
        raise ValueError(f"at_cancel: no timer has id {i!r}")
