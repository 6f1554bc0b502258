"""``Recorder``: record a running ``pge.World`` into a pge recording.

The recorder listens to the world's FRAME events (``World.on_frame``) and
collisions (``World.on_collision``). At each frame it reads every body
through the public ``Body`` API (``position``, ``vertices``), so the
recorded numbers are exactly the engine's closed-form positions at the
frame's time, bit for bit. Colours come from ``body.data["colour"]`` when
given (an RGB tuple, 0-255), else from ``pge.render.image.PALETTE`` (fixed
bodies grey), as in ``pge.render.image``.

The World API has no hook for timers registered by others, so timers are
recorded when set through ``Recorder.at_time`` (or passed to
``Recorder.timer`` from your own callback).
"""

from __future__ import annotations

import numpy as np

from pge.recording.writer import RecordingWriter
from pge.render.image import BACKGROUND, FIXED_COLOUR, PALETTE

__all__ = ["Recorder"]

#: colour table every recording starts with: background, fixed bodies, then PALETTE.
BASE_COLOURS = (BACKGROUND, FIXED_COLOUR, *PALETTE)
_FIRST_PALETTE = 2


class Recorder:
    """Record ``world`` into the file ``path``, a frame at every FRAME event.

    ``frame_rate`` (frames per second) is set on the world if given, or if the
    world has none (then 60). Frame 0 is the state when the recorder is made;
    then one frame per FRAME event. ``collisions=False`` skips collision
    events (the engine then need not stop for each one). Call ``close()`` when
    done, or use it as a context manager::

        with Recorder(world, "run.pgerec"):
            world.run_until(5.0)

    ``close`` writes the events after the last frame and the end record, and
    takes the recorder's callbacks off the world (``World.record(path)``
    makes the same recorder).
    """

    def __init__(self, world, path, frame_rate=None, collisions: bool = True) -> None:
        if frame_rate is not None or world.frame_rate is None:
            world.frame_rate = 60.0 if frame_rate is None else frame_rate
        self.world = world
        self._writer = RecordingWriter(
            path, world.bounds, BASE_COLOURS, background=0, frame_rate=world.frame_rate, start_time=world.time
        )
        self._colour_index = {rgb: k for k, rgb in enumerate(BASE_COLOURS)}
        self._known: dict[int, tuple] = {}  # body id -> (kind, radius)
        self._collisions: list[tuple] = []
        self._timers: list[tuple] = []
        self.closed = False
        world.on_frame(self._on_frame)
        if collisions:
            world.on_collision(self._on_collision)
        self._snapshot(world.time)

    @property
    def path(self):
        """The file being written."""
        return self._writer.path

    @property
    def frames(self) -> int:
        """Frames written so far."""
        return self._writer.frames

    # ------------------------------------------------------------------ hooks

    def _on_frame(self, frame) -> None:
        if not self.closed:
            self._snapshot(frame.time)

    def _on_collision(self, event) -> None:
        if not self.closed:
            self._collisions.append(
                (
                    event.time,
                    -1 if event.a is None else event.a.id,
                    -1 if event.b is None else event.b.id,
                    event.point,
                    event.normal,
                    event.impulse,
                )
            )

    def timer(self, event) -> None:
        """Record a fired ``pge.Timer`` event (call it from your timer callback)."""
        if not self.closed:
            self._timers.append((event.time, event.timer_id))

    def at_time(self, time, callback, data=None) -> int:
        """``World.at_time`` that also records the timer when it fires."""

        def fire(event):
            self.timer(event)
            callback(event)

        return self.world.at_time(time, fire, data)

    # --------------------------------------------------------------- sampling

    def _snapshot(self, time: float) -> None:
        circles_ids, centres, radii, circle_colours = [], [], [], []
        polygon_ids, counts, vertices, polygon_colours = [], [], [], []
        new_bodies = []
        for body in self.world.bodies:
            known = self._known.get(body.id)
            if known is None:
                kind = body.kind
                known = (kind, body.shape.radius if kind == "circle" else None)
                self._known[body.id] = known
                new_bodies.append((body.id, kind, body.name, body.is_fixed))
            colour = self._colour_of(body)
            if known[0] == "circle":
                circles_ids.append(body.id)
                centres.append(body.position)
                radii.append(known[1])
                circle_colours.append(colour)
            else:
                corners = body.vertices
                polygon_ids.append(body.id)
                counts.append(len(corners))
                vertices.extend(corners)
                polygon_colours.append(colour)
        self._writer.add_bodies(new_bodies)
        self._writer.write_frame(
            time,
            (circles_ids, np.reshape(centres, (-1, 2)), radii, circle_colours),
            (polygon_ids, counts, np.reshape(vertices, (-1, 2)), polygon_colours),
            *self._take_events(),
        )

    def _take_events(self):
        collisions = timers = None
        if self._collisions:
            t, a, b, p, n, j = zip(*self._collisions)
            collisions = (t, a, b, np.reshape(p, (-1, 2)), np.reshape(n, (-1, 2)), j)
            self._collisions = []
        if self._timers:
            t, ids = zip(*self._timers)
            timers = (t, ids)
            self._timers = []
        return collisions, timers

    def _colour_of(self, body) -> int:
        rgb = body.data.get("colour") if isinstance(body.data, dict) else None
        if rgb is None:
            return 1 if body.is_fixed else _FIRST_PALETTE + body.id % len(PALETTE)
        rgb = tuple(int(c) for c in rgb)
        index = self._colour_index.get(rgb)
        if index is None:
            index = self._writer.add_colours([rgb])
            self._colour_index[rgb] = index
        return index

    # ---------------------------------------------------------------- closing

    def close(self) -> None:
        """Write the remaining events and the end record at the world's current time."""
        if self.closed:
            return
        self.closed = True
        # unhook first: the world may run on without a recording, and should not stop for our sake
        self.world.off_frame(self._on_frame)
        self.world.off_collision(self._on_collision)
        self._writer.close(self.world.time, *self._take_events())

    def __enter__(self):
        return self

    def __exit__(self, *exc) -> None:
        self.close()
