"""The player's state machine: where playback is, and what time and keys do to it.

Pure functions of immutable values, no window and no clock, so every rule is
unit tested: ``start`` makes the first state, ``tick(state, wall, times)``
lets ``wall`` seconds of wall-clock time pass, ``press(state, key, times)``
applies one key. ``times`` is the recording's non-decreasing array of frame
times (``Recording.times``); ``state.index`` is always a valid frame index.

Keys are pygame's key names (``pygame.key.name``): ``space`` pauses and
resumes (at the last frame it starts again from the first); ``right`` /
``left`` pause and step one frame; ``up`` / ``down`` seek 10 frames forwards
/ backwards, ``page up`` / ``page down`` 100; ``home`` / ``end`` go to the
first / last frame; ``+`` (also ``=`` and keypad ``[+]``) doubles the speed,
``-`` (keypad ``[-]``) halves it, within ``MIN_SPEED`` .. ``MAX_SPEED``;
``escape`` or ``q`` quits. Seeks and steps stop at the first and last frame.
"""

from __future__ import annotations

import bisect
import math
from dataclasses import dataclass, replace

__all__ = ["PlayerState", "start", "tick", "press", "MIN_SPEED", "MAX_SPEED", "SEEK", "PAGE"]

#: slowest and fastest playback, in simulated seconds per wall-clock second.
MIN_SPEED = 1.0 / 64.0
MAX_SPEED = 64.0
#: frames moved by up/down and by page up/page down.
SEEK = 10
PAGE = 100

_FASTER = frozenset({"+", "=", "[+]"})
_SLOWER = frozenset({"-", "[-]"})
_QUIT = frozenset({"escape", "q"})
_SEEKS = {"up": SEEK, "down": -SEEK, "page up": PAGE, "page down": -PAGE}


@dataclass(frozen=True)
class PlayerState:
    """Where playback is.

    ``index``: the frame shown; ``time``: the playback clock in simulated
    seconds (at or after ``times[index]``, before the next frame's time while
    playing); ``paused``; ``speed`` (simulated seconds per wall second);
    ``quit``: the user asked to leave.
    """

    index: int
    time: float
    paused: bool = False
    speed: float = 1.0
    quit: bool = False


def _check_speed(speed: float) -> float:
    speed = float(speed)
    if not (math.isfinite(speed) and MIN_SPEED <= speed <= MAX_SPEED):
        raise ValueError(f"speed must be between 1/{1 / MIN_SPEED:g} and {MAX_SPEED:g}, got {speed:g}")
    return speed


def _index_at(times, time: float) -> int:
    return max(0, bisect.bisect_right(times, time) - 1)


def start(times, start_time=None, speed: float = 1.0, paused: bool = False) -> PlayerState:
    """The state before the first tick: at the last frame at or before ``start_time``
    (default: the first frame; a time past the end gives the last frame).

    ValueError if there are no frames or ``speed`` is outside ``MIN_SPEED`` .. ``MAX_SPEED``.
    """
    if len(times) == 0:
        raise ValueError("the recording has no frames")
    speed = _check_speed(speed)
    if start_time is None:
        index = 0
    else:
        if not math.isfinite(start_time):
            raise ValueError(f"start time must be finite, got {start_time!r}")
        index = _index_at(times, start_time)
    return PlayerState(index=index, time=float(times[index]), paused=paused, speed=speed)


def _at(state: PlayerState, index: int, times, **changes) -> PlayerState:
    """``state`` moved to frame ``index`` (clamped), its clock on that frame's time."""
    index = min(max(index, 0), len(times) - 1)
    return replace(state, index=index, time=float(times[index]), **changes)


def tick(state: PlayerState, wall: float, times) -> PlayerState:
    """``wall`` seconds of wall-clock time later: while playing, the clock moves on by
    ``wall * speed``; at the last frame's time playback pauses there."""
    if state.paused or state.quit or wall <= 0.0:
        return state
    time = state.time + wall * state.speed
    last = len(times) - 1
    if time >= times[last]:
        return _at(state, last, times, paused=True)
    return replace(state, time=time, index=_index_at(times, time))


def press(state: PlayerState, key: str, times) -> PlayerState:
    """The state after the key named ``key``; unknown keys change nothing."""
    last = len(times) - 1
    if key in _QUIT:
        return replace(state, quit=True)
    if key == "space":
        if not state.paused:
            return replace(state, paused=True)
        if state.index >= last > 0:
            return _at(state, 0, times, paused=False)  # at the end: play again from the start
        return _at(state, state.index, times, paused=False)
    if key == "right":
        return _at(state, state.index + 1, times, paused=True)
    if key == "left":
        return _at(state, state.index - 1, times, paused=True)
    if key in _SEEKS:
        return _at(state, state.index + _SEEKS[key], times)
    if key == "home":
        return _at(state, 0, times)
    if key == "end":
        return _at(state, last, times, paused=True)
    if key in _FASTER:
        return replace(state, speed=min(MAX_SPEED, state.speed * 2.0))
    if key in _SLOWER:
        return replace(state, speed=max(MIN_SPEED, state.speed / 2.0))
    return state
