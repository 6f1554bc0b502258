"""One screen of the player: a recorded frame, the event list and the status line.

Everything is drawn through the protocol of ``pge.render.protocol``, so the
same code draws into the pygame window and into the null display of headless
runs. A display shows the unit square scaled to ``min(width, height)`` pixels
with y up (``pge.render.pygame_display``); ``View`` maps the recording's
bounds into the window, centred, at one scale for x and y. The player keeps
a panel at the right for the event list and a strip at the bottom for the
status line, so neither is ever drawn over the scene.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

__all__ = ["View", "fit", "draw_screen", "status_line", "TEXT_SIZE", "PANEL", "STRIP"]

#: height of the overlay text in pixels.
TEXT_SIZE = 20
#: event lines shown at most.
EVENT_LINES = 8
#: width in pixels of the event panel beside the scene (the longest line, "12.3456 s  collision 123-456", fits).
PANEL = 270
#: height in pixels of the status strip under the scene.
STRIP = TEXT_SIZE + 10


class View(NamedTuple):
    """Display coordinates of a world point: ``(ox + k (x - x0), oy + k (y - y0))``.

    ``width`` and ``height`` are the window's extent in display units and
    ``pixel`` the size of a pixel in display units.
    """

    x0: float
    y0: float
    k: float
    ox: float
    oy: float
    width: float
    height: float
    pixel: float
    #: display x where the event panel starts (the scene's right edge; ``width`` if there is no panel)
    panel_x: float | None = None


def fit(bounds, size, panel: int = 0, strip: int = 0) -> View:
    """The view that shows ``bounds`` ``(x0, y0, x1, y1)`` as large as it fits in a
    display of ``size = (width, height)`` pixels, centred, leaving ``panel`` pixels free
    at the right and ``strip`` pixels at the bottom (for text beside the scene)."""
    x0, y0, x1, y1 = bounds
    width_px, height_px = size
    scale = float(min(width_px, height_px))
    width, height = width_px / scale, height_px / scale
    # a window too small for the panel or strip gives them up rather than the scene
    right = panel / scale if width_px >= 2 * panel else 0.0
    bottom = strip / scale if height_px >= 4 * strip else 0.0
    room_w, room_h = width - right, height - bottom
    k = min(room_w / (x1 - x0), room_h / (y1 - y0))
    ox = (room_w - (x1 - x0) * k) / 2.0
    oy = bottom + (room_h - (y1 - y0) * k) / 2.0
    return View(x0, y0, k, ox, oy, width, height, 1.0 / scale, room_w)


def _text_colour(background) -> tuple[int, int, int, int]:
    r, g, b = background
    return (20, 20, 20, 255) if 0.299 * r + 0.587 * g + 0.114 * b > 140 else (235, 235, 235, 255)


def status_line(recording, state) -> str:
    """``frame 12/120  t 0.1100 s / 1.2 s  speed 1x  playing`` for ``state``."""
    speed = f"{state.speed:g}x" if state.speed >= 1 else f"1/{1 / state.speed:g}x"
    last = len(recording) - 1
    mode = "paused" if state.paused else "playing"
    if state.paused and state.index == last:
        mode = "end (space: again)"
    return (
        f"frame {state.index}/{last}  t {recording.times[state.index]:.4f} s / {recording.end_time:g} s"
        f"  speed {speed}  {mode}"
    )


def draw_screen(display, recording, frame, view: View, state, events=()) -> None:
    """Draw ``frame`` of ``recording`` with the ``events`` lines (newest last) at the
    top of the panel beside the scene (top left if the view has none) and the status
    line of ``state`` at the bottom."""
    palette = [(*rgb, 255) for rgb in recording.colours]
    background = recording.colours[recording.background]
    display.begin_frame((*background, 255))
    k, x0, y0, ox, oy = view.k, view.x0, view.y0, view.ox, view.oy
    circles = frame.circles
    if len(circles.ids):
        xs = ox + (circles.centres[:, 0] - x0) * k
        ys = oy + (circles.centres[:, 1] - y0) * k
        display.circles(xs, ys, circles.radii * k, palette, circles.colours.astype(np.int64))
    polygons = frame.polygons
    if len(polygons.ids):
        points = np.column_stack((ox + (polygons.vertices[:, 0] - x0) * k, oy + (polygons.vertices[:, 1] - y0) * k))
        starts = polygons.starts.tolist()
        for n, colour in enumerate(polygons.colours.tolist()):
            display.polygon([tuple(p) for p in points[starts[n] : starts[n + 1]].tolist()], palette[colour])
    ink = _text_colour(background)
    line = (TEXT_SIZE + 2) * view.pixel
    margin = 6 * view.pixel
    left = margin if view.panel_x is None or view.panel_x >= view.width else view.panel_x + margin
    for n, text in enumerate(events):
        display.text(left, view.height - margin - n * line, text, ink, TEXT_SIZE)
    display.text(margin, margin + line, status_line(recording, state), ink, TEXT_SIZE)
    display.end_frame()
