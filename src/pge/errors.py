"""Errors a running simulation can raise (bad input raises ValueError or TypeError instead).

Both are RuntimeErrors, so code that caught the old ``RuntimeError('event storm ...')`` still
catches them; each carries the time and the bodies involved as attributes.
"""

from __future__ import annotations


class SimulationError(RuntimeError):
    """The engine cannot go on from this state without moving a body wrongly or spinning.

    ``time`` is the simulated time, ``bodies`` the handles of the bodies involved.
    """

    def __init__(self, message: str, time: float, bodies: tuple = ()):
        super().__init__(message)
        self.time = time
        self.bodies = tuple(bodies)


class EventStormError(SimulationError):
    """A run of events the clock cannot separate: a zero-time loop, a Zeno run converging on
    one instant, or a clock that creeps a few ulps per event. ``kinds`` counts the run's events
    by kind."""

    def __init__(self, message: str, time: float, bodies: tuple = (), kinds: dict | None = None):
        super().__init__(message, time, bodies)
        self.kinds = dict(kinds or {})


class TooFastError(SimulationError):
    """A body moves so fast that one tick of the clock carries it further than its travel
    step: its collisions cannot be resolved in time, so it is refused rather than let
    through a wall. ``speed`` is its speed (with spin), ``tick`` the clock's resolution."""

    def __init__(self, message: str, time: float, bodies: tuple = (), speed: float = 0.0, tick: float = 0.0):
        super().__init__(message, time, bodies)
        self.speed = speed
        self.tick = tick


class OverlapWarning(UserWarning):
    """Two bodies overlap when a run begins in a world that allows it (``World(allow_overlap=True)``,
    and always in the classic ``pge`` module, as in the original): they pass through each other
    until they have separated."""
