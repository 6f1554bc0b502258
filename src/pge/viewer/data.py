"""A recording as the plain JSON-ready dictionary the browser viewer plays.

The browser needs every frame's shapes and events at hand to seek freely,
so the whole recording (or a time range of it) is converted once. Numbers
are rounded to 7 significant digits: far below a pixel at any zoom the
viewer offers, and it keeps the JSON about half the size of full doubles.

Layout (``"version": 1``)::

    {"version": 1, "title": str, "format": str,
     "bounds": [x0, y0, x1, y1], "colours": [[r, g, b], ...], "background": int,
     "frame_rate": float | null, "end_time": float,
     "bodies": {"<id>": [kind, name | null, fixed], ...},
     "times": [t0, t1, ...],
     "frames": [{"c": [x, y, r, colour, x, y, r, colour, ...],
                 "p": [[colour, x, y, x, y, ...], ...],
                 "e": [[t, "c", a, b, px, py, impulse] | [t, "t", timer_id], ...]}, ...]}

``c`` lists circles as flat groups of four, ``p`` one polygon per entry,
``e`` the collisions ("c") and timers ("t") since the previous frame.
"""

from __future__ import annotations

import json
import math

__all__ = ["recording_data", "to_json", "DATA_VERSION"]

DATA_VERSION = 1
_DIGITS = 7


def _r(value: float):
    """``value`` rounded to ``_DIGITS`` significant digits; None for NaN or infinity (JSON has neither)."""
    value = float(value)
    if not math.isfinite(value):
        return None
    if value == 0.0:
        return 0.0
    return round(value, _DIGITS - 1 - int(math.floor(math.log10(abs(value)))))


def _frame_data(frame) -> dict:
    circles = frame.circles
    flat = []
    for (x, y), r, colour in zip(circles.centres.tolist(), circles.radii.tolist(), circles.colours.tolist()):
        flat += (_r(x), _r(y), _r(r), int(colour))
    polygons = []
    shapes = frame.polygons
    starts = shapes.starts.tolist()
    vertices = shapes.vertices.tolist()
    for k, colour in enumerate(shapes.colours.tolist()):
        outline = [int(colour)]
        for x, y in vertices[starts[k] : starts[k + 1]]:
            outline += (_r(x), _r(y))
        polygons.append(outline)
    events = []
    hits = frame.collisions
    for t, a, b, (px, py), j in zip(
        hits.times.tolist(), hits.a.tolist(), hits.b.tolist(), hits.points.tolist(), hits.impulses.tolist()
    ):
        events.append([_r(t), "c", int(a), int(b), _r(px), _r(py), _r(j)])
    for t, timer in zip(frame.timers.times.tolist(), frame.timers.ids.tolist()):
        events.append([_r(t), "t", int(timer)])
    events.sort(key=lambda e: -math.inf if e[0] is None else e[0])
    return {"c": flat, "p": polygons, "e": events}


def recording_data(recording, start=None, end=None, title=None) -> dict:
    """The viewer's dictionary for the frames of ``recording`` shown between ``start``
    and ``end`` seconds (default: all of them).

    Raises ValueError for a recording without frames or a range with none.
    """
    count = len(recording)
    if count == 0:
        raise ValueError(f"{recording.path}: the recording has no frames")
    first = 0 if start is None else recording.index_at(float(start))
    last = count - 1
    if end is not None:
        last = recording.index_at(float(end))
        if float(end) < recording.start_time:
            raise ValueError(f"no frame at or before {float(end):g} s (the recording starts at {recording.start_time:g} s)")
    if last < first:
        raise ValueError(f"empty time range: start {float(start):g} s is after end {float(end):g} s")
    frames = [_frame_data(recording.frame(k)) for k in range(first, last + 1)]
    bodies = {str(info.id): [info.kind, info.name, bool(info.fixed)] for info in recording.bodies.values()}
    end_time = recording.end_time if last == count - 1 else float(recording.times[last])
    if title is None:
        title = str(getattr(recording, "path", "") or "recording").replace("\\", "/").rsplit("/", 1)[-1]
    return {
        "version": DATA_VERSION,
        "title": title,
        "format": recording.format,
        "bounds": [_r(v) for v in recording.bounds],
        "colours": [list(rgb) for rgb in recording.colours],
        "background": int(recording.background),
        "frame_rate": None if recording.frame_rate is None else _r(recording.frame_rate),
        "end_time": _r(end_time),
        "bodies": bodies,
        "times": [_r(t) for t in recording.times[first : last + 1].tolist()],
        "frames": frames,
    }


def to_json(data: dict, for_script: bool = False) -> str:
    """Compact JSON of ``data``; with ``for_script`` safe inside an HTML ``<script>`` element
    (a ``</script>`` or ``<!--`` in a body's name cannot end or confuse the element)."""
    text = json.dumps(data, separators=(",", ":"), allow_nan=False)
    if for_script:
        text = text.replace("<", "\\u003c").replace(">", "\\u003e").replace("&", "\\u0026")
    return text
