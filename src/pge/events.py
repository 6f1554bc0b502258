"""Event records handed to callbacks and iterators.

The queue itself is compiled (``pge.core.queue``). Equal times are broken by kind in the
order collision, horizon, timer, frame (``pge.core.layout``), and a run's ``Stop`` comes
last, so a frame or a stop at time t shows the world after everything else that happens at
t. The constants below name the kinds of the records.
"""

from __future__ import annotations

from typing import Any, NamedTuple

__all__ = [
    "COLLISION",
    "HORIZON",
    "TIMER",
    "FRAME",
    "STOP",
    "Collision",
    "Timer",
    "Frame",
    "Stop",
]

COLLISION = 0
HORIZON = 1
TIMER = 2
FRAME = 3
STOP = 4


class Collision(NamedTuple):
    """Two bodies touched at ``time`` and bounced.

    ``point`` is the contact point and ``normal`` the unit contact normal,
    pointing from ``b`` towards ``a``, both in world coordinates at ``time``;
    ``impulse`` is the magnitude of the impulse exchanged along the normal
    (mass x velocity units) and ``approach_speed`` the normal speed at which
    the bodies closed (positive).

    ``in_island`` is True for an impact too slow for free flight on a body of an
    island (docs/contact.md, "The model in one paragraph"): it was solved together
    with that island's contacts at the same instant, so ``impulse`` is this
    pair's share of that solve, and the bodies' change of motion also holds the
    island's other contact impulses. False for an exact two-body impulse.

    ``patch`` is set where a face met a face and both ends of the touching stretch took the
    impact together (docs/rotation.md, "Response"): ``((x1, y1, j1), (x2, y2, j2), jt)``, the two
    ends with their normal impulses and the friction impulse at their midpoint (along
    ``(-normal[1], normal[0])``); ``impulse`` is then ``j1 + j2``, and ``point`` and
    ``approach_speed`` are the first touching point's. None for an impulse at one point.
    """

    time: float
    a: Any
    b: Any
    point: tuple[float, float]
    normal: tuple[float, float]
    impulse: float
    approach_speed: float
    in_island: bool = False
    patch: Any = None

    kind = "collision"


class Timer(NamedTuple):
    """A timer registered with ``World.at_time`` fired at ``time``."""

    time: float
    timer_id: int
    data: Any = None

    kind = "timer"


class Frame(NamedTuple):
    """Periodic sample number ``index`` at ``time = index / frame_rate``."""

    time: float
    index: int

    kind = "frame"


class Stop(NamedTuple):
    """The end of a run at ``time``."""

    time: float

    kind = "stop"
