"""Frames of the classic ``pge`` module: what is drawn, in which order, and when.

A frame draws the levels in ascending order: background eye-candy (levels
< 0), the physics objects (level 0, in creation order) with the springs given
``draw()`` on top of them, then foreground eye-candy and text (levels > 0). Positions are the World's closed-form
positions at the frame's time. Frames go to a display through the protocol of
``pge.render.protocol``; this module never imports pygame.

``Pacer`` holds frames back against the wall clock: simulated time ``t``
is shown at ``wall0 + (t - t0) * slow_down``.
"""

from __future__ import annotations

import time

import numpy as np

from pge.classic.constants import Black, circle_t, fb_circle_t, fb_text_t
from pge.classic.sampling import Sampler
from pge.classic.session import STATE

__all__ = ["compose", "Pacer", "rgba"]

_BACKGROUND = (*Black, 255)
#: a frame more than this late (wall seconds) is not caught up: the clock is re-anchored.
MAX_LAG = 0.25


def rgba(obj) -> tuple[int, int, int, int]:
    """The colour an object is drawn in, with its alpha."""
    return (*obj._colour.rgb255(), int(round(obj._alpha * 255.0)))


class _Plan:
    """Level 0 as runs of consecutive circles (drawn in one call) and single polygons."""

    def __init__(self, world, generation: int) -> None:
        self.generation = generation
        self.steps = []
        run = []
        for obj in STATE.shapes:
            if obj._body is None or not obj._visible or obj._alpha <= 0.0:
                continue
            if obj.type == circle_t:
                run.append(obj)
                continue
            if run:
                self.steps.append(self._circles(world, run))
                run = []
            self.steps.append(("polygon", obj._body, rgba(obj)))
        if run:
            self.steps.append(self._circles(world, run))

    @staticmethod
    def _circles(world, objects):
        radii = np.array([o._geometry.radius for o in objects])
        palette: dict = {}
        index = np.array([palette.setdefault(rgba(o), len(palette)) for o in objects], dtype=np.int64)
        return ("circles", Sampler(world, [o._body for o in objects]), radii, list(palette), index)


def compose(display, highlight=(), colour=None) -> None:
    """Draw the current state of the session to ``display`` as one frame.

    ``highlight`` objects are drawn again on top in ``colour`` (collision frames).
    """
    world = STATE.world
    if STATE.plan is None or STATE.plan.generation != STATE.generation:
        STATE.plan = _Plan(world, STATE.generation)
    display.begin_frame(_BACKGROUND)
    for level in sorted(set(STATE.levels) | {0}):
        if level == 0:
            _draw_level0(display, STATE.plan)
            _draw_springs(display)
        else:
            for obj in STATE.levels[level]:
                _draw_decoration(display, obj)
    for obj in highlight:
        if obj is not None and not obj.deleted and obj._body is not None:
            _draw_shape(display, obj, colour)
    display.end_frame()


def _draw_level0(display, plan: _Plan) -> None:
    for step in plan.steps:
        if step[0] == "circles":
            _, sampler, radii, palette, index = step
            xs, ys = sampler.positions()
            display.circles(xs, ys, radii, palette, index)
        else:
            display.polygon(step[1].vertices, step[2])


def _draw_springs(display) -> None:
    from pge.classic.springs import band

    for obj in STATE.springs:
        if obj._band is None or obj.deleted or not obj._spring.alive or obj._alpha <= 0.0:
            continue
        corners = band(obj)
        if corners is not None:
            display.polygon(corners, rgba(obj))


def _draw_shape(display, obj, colour) -> None:
    if obj.type == circle_t:
        x, y = obj._body.position
        display.circle(x, y, obj._geometry.radius, colour)
    else:
        display.polygon(obj._body.vertices, colour)


def _draw_decoration(display, obj) -> None:
    if not obj._visible or obj._alpha <= 0.0:
        return
    colour = rgba(obj)
    if obj.type == fb_text_t:
        x, y, s, size = obj._text
        display.text(x, y, s, colour, size)
    elif obj.type == fb_circle_t:
        x, y, r = obj._circle
        display.circle(x, y, r, colour)
    else:
        display.polygon(obj._points, colour)


class Pacer:
    """Holds frames back so that simulated time runs ``slow`` times slower than the wall clock."""

    def __init__(self, sim_time: float, slow: float) -> None:
        self.anchor(sim_time, slow)

    def anchor(self, sim_time: float, slow: float) -> None:
        """Simulated ``sim_time`` is now."""
        self.sim0 = sim_time
        self.wall0 = time.perf_counter()
        self.slow = slow

    def wait(self, sim_time: float) -> None:
        """Sleep until simulated ``sim_time`` is due on the wall clock."""
        due = self.wall0 + (sim_time - self.sim0) * self.slow
        now = time.perf_counter()
        if due > now:
            time.sleep(due - now)
        elif now - due > MAX_LAG:
            self.anchor(sim_time, self.slow)

    def pause(self, seconds: float) -> None:
        """Sleep ``seconds`` of wall-clock time without counting them as simulated time."""
        if seconds > 0.0:
            time.sleep(seconds)
            self.wall0 += seconds
