"""``pge play``: show a recording in a window, or walk it headless.

``play`` connects the pieces: the state machine (``control``), the screen
(``screen``), the event list (``history``) and a display of the drawing
protocol. In a window it polls input and the wall clock about every 10 ms,
feeds keys and elapsed time to the state machine and redraws when the frame,
pause or speed changed; it never waits longer than the time to the next
recorded frame divided by the speed. Headless it draws every frame from the
start frame to the last one through the same screen code, with no window and
no waiting, and reports what it walked. The clock and the sleep are
parameters, so tests can drive the window loop without real time passing.
"""

from __future__ import annotations

import time
from dataclasses import replace
from typing import NamedTuple

from pge.playback.control import press, start, tick
from pge.playback.history import EventHistory
from pge.playback.screen import PANEL, STRIP, TEXT_SIZE, draw_screen, fit
from pge.render.protocol import NullDisplay

__all__ = ["play", "PlaySummary", "NoWindow", "default_size", "POLL"]

#: longest wait between two looks at input and clock in the window (seconds).
POLL = 0.01
#: the longer side of the window when no size is given (pixels).
DEFAULT_SIDE = 800


class NoWindow(OSError):
    """No window could be opened (no display, no video driver)."""


class PlaySummary(NamedTuple):
    """What ``play`` showed: ``frames`` drawn, from frame ``first`` to ``last``, and the
    collisions and timers of the frames drawn."""

    frames: int
    first: int
    last: int
    collisions: int
    timers: int
    headless: bool

    def line(self, recording) -> str:
        """One line for the terminal."""
        mode = "headless, no window" if self.headless else "window"
        return (
            f"pge play: {self.frames} frames shown ({recording.times[self.first]:g} s to "
            f"{recording.times[self.last]:g} s), {self.collisions} collisions, {self.timers} timers ({mode})"
        )


def default_size(bounds) -> tuple[int, int]:
    """A window whose scene is ``DEFAULT_SIDE`` pixels on its longer side with the aspect of
    ``bounds``, widened by the event panel and heightened by the status strip."""
    x0, y0, x1, y1 = bounds
    w, h = x1 - x0, y1 - y0
    side = max(w, h)
    return (
        max(200, round(DEFAULT_SIDE * w / side)) + PANEL,
        max(200, round(DEFAULT_SIDE * h / side)) + STRIP,
    )


def _open_window(size, fullscreen: bool, caption: str):
    from pge.render.pygame_display import PygameDisplay, WindowError

    try:
        return PygameDisplay(size, fullscreen, caption)
    except WindowError as error:
        raise NoWindow(
            f"cannot open a window ({error}); use --headless (or PGE_HEADLESS=1) to play without one"
        ) from None


def play(
    recording,
    *,
    speed: float = 1.0,
    start_time=None,
    size=None,
    fullscreen: bool = False,
    headless: bool = False,
    display=None,
    clock=time.perf_counter,
    sleep=time.sleep,
) -> PlaySummary:
    """Play ``recording`` (a ``pge.recording.Recording``) from the frame at ``start_time``.

    ``speed``: simulated seconds per wall-clock second (``MIN_SPEED`` .. ``MAX_SPEED``);
    ``size``: window ``(width, height)`` in pixels (default: ``default_size``);
    ``headless``: walk every frame without waiting (on ``display``, default a
    ``NullDisplay``); otherwise play in ``display`` (default: a new pygame
    window, closed at the end) until the user quits. Raises ValueError for an
    empty recording or a bad speed, ``NoWindow`` if no window can be opened.
    """
    state = start(recording.times, start_time, speed)
    size = tuple(size) if size is not None else default_size(recording.bounds)
    own = display is None
    if own:
        display = (
            NullDisplay()
            if headless
            else _open_window(None if fullscreen else size, fullscreen, f"pge play {recording.path}")
        )
    try:
        pixels = (getattr(display, "width", size[0]), getattr(display, "height", size[1]))
        view = fit(recording.bounds, pixels, PANEL, STRIP)
        history = EventHistory(recording)
        if headless:
            return _walk(recording, display, view, state, history)
        return _loop(recording, display, view, state, history, clock, sleep)
    finally:
        if own:
            display.close()


def _show(recording, display, view, state, history):
    frame = recording.frame(state.index)
    history.note(frame)
    lines = max(1, int((view.height - STRIP * view.pixel) / ((TEXT_SIZE + 2) * view.pixel)) - 1)  # fill the panel
    draw_screen(display, recording, frame, view, state, history.recent(state.index, lines))
    return frame


def _walk(recording, display, view, state, history) -> PlaySummary:
    """Every frame from ``state.index`` to the last, drawn once each, no waiting."""
    first = state.index
    collisions = timers = 0
    for index in range(first, len(recording)):
        state = replace(state, index=index, time=float(recording.times[index]))
        frame = _show(recording, display, view, state, history)
        collisions += len(frame.collisions.times)
        timers += len(frame.timers.times)
    return PlaySummary(len(recording) - first, first, len(recording) - 1, collisions, timers, True)


def _loop(recording, display, view, state, history, clock, sleep) -> PlaySummary:
    """The window: input, clock, redraw on change, until quit."""
    times = recording.times
    first = state.index
    shown = None
    frames = collisions = timers = 0
    last_index = first
    before = clock()
    while True:
        for event in display.events():
            if display.is_quit(event):
                state = replace(state, quit=True)
                continue
            key = display.key_name(event)
            if key is not None:
                state = press(state, key, times)
        now = clock()
        state = tick(state, now - before, times)
        before = now
        if state.quit:
            break
        look = (state.index, state.paused, state.speed)
        if look != shown:
            frame = _show(recording, display, view, state, history)
            shown = look
            frames += 1
            last_index = state.index
            collisions += len(frame.collisions.times)
            timers += len(frame.timers.times)
        wait = POLL
        if not state.paused and state.index + 1 < len(times):
            wait = min(POLL, (times[state.index + 1] - state.time) / state.speed)
        sleep(max(0.0, wait))
    return PlaySummary(frames, first, last_index, collisions, timers, False)
