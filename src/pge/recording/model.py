"""What a recording holds, whatever file it came from.

A ``Recording`` is a sequence of ``RecordedFrame``s (the shapes drawn at one
simulation time, with the events since the previous frame) plus what the
header says: world bounds, colour table, frame rate, the bodies seen. Frames
are decoded on demand through an index built when the file is opened, so a
long recording opens in about the time it takes to read the file once.
"""

from __future__ import annotations

import bisect
from typing import Callable, NamedTuple

import numpy as np

__all__ = ["Recording", "RecordedFrame", "Circles", "Polygons", "Collisions", "Timers", "BodyInfo"]


class Circles(NamedTuple):
    """Filled circles of one frame, in drawing order (n rows)."""

    ids: np.ndarray  # (n,) int64 body ids
    centres: np.ndarray  # (n, 2) float64, world coordinates
    radii: np.ndarray  # (n,) float64
    colours: np.ndarray  # (n,) indices into Recording.colours


class Polygons(NamedTuple):
    """Filled convex polygons of one frame: polygon k has ``vertices[starts[k]:starts[k + 1]]``."""

    ids: np.ndarray  # (n,) int64 body ids
    starts: np.ndarray  # (n + 1,) int64 offsets into vertices
    vertices: np.ndarray  # (total, 2) float64, world coordinates
    colours: np.ndarray  # (n,)

    def outline(self, k: int) -> np.ndarray:
        """The (m, 2) corners of polygon ``k``."""
        return self.vertices[self.starts[k] : self.starts[k + 1]]


class Collisions(NamedTuple):
    """Collisions since the previous frame (n rows); a body id of -1 means unknown."""

    times: np.ndarray
    a: np.ndarray
    b: np.ndarray
    points: np.ndarray  # (n, 2) contact points
    normals: np.ndarray  # (n, 2) unit normals from b towards a
    impulses: np.ndarray


class Timers(NamedTuple):
    """Timers fired since the previous frame (n rows)."""

    times: np.ndarray
    ids: np.ndarray


class RecordedFrame(NamedTuple):
    """Frame ``index`` of a recording: what was drawn at simulation ``time``.

    ``collisions`` and ``timers`` are the events after the previous frame's
    time and up to and including this one's.
    """

    index: int
    time: float
    circles: Circles
    polygons: Polygons
    collisions: Collisions
    timers: Timers

    @property
    def shape_count(self) -> int:
        """Circles plus polygons drawn."""
        return len(self.circles.ids) + len(self.polygons.ids)


class BodyInfo(NamedTuple):
    """A body that appears in a recording."""

    id: int
    kind: str  # "circle" or "polygon"
    name: str | None
    fixed: bool


def empty_circles() -> Circles:
    return Circles(np.zeros(0, np.int64), np.zeros((0, 2)), np.zeros(0), np.zeros(0, np.uint16))


def empty_polygons() -> Polygons:
    return Polygons(np.zeros(0, np.int64), np.zeros(1, np.int64), np.zeros((0, 2)), np.zeros(0, np.uint16))


def empty_collisions() -> Collisions:
    z = np.zeros(0)
    return Collisions(z, np.zeros(0, np.int64), np.zeros(0, np.int64), np.zeros((0, 2)), np.zeros((0, 2)), z)


def empty_timers() -> Timers:
    return Timers(np.zeros(0), np.zeros(0, np.int64))


class Recording:
    """A recording opened for reading: random access to its frames.

    Attributes: ``path``; ``format`` (e.g. ``"pge 1.0"`` or ``"PGE output.raw"``);
    ``writer`` (the program that wrote it, if known); ``bounds``
    ``(x0, y0, x1, y1)`` of the world shown; ``colours`` (list of RGB tuples,
    0-255, which shapes' colour indices refer to); ``background`` (an index
    into ``colours``); ``frame_rate`` (frames per second, or None);
    ``bodies`` (dict id -> BodyInfo); ``times`` (float64 array, one time per
    frame, non-decreasing); ``complete`` (False if the file was not closed by
    its writer: still being written, or cut at a record boundary);
    ``damage`` (the RecordingError that stopped reading, or None);
    ``event_counts`` (dict: collisions, timers) and ``end_time``.

    Build one with ``pge.recording.open_recording(path)``.
    """

    def __init__(
        self,
        *,
        path,
        format: str,
        writer: str | None,
        bounds,
        colours,
        background: int,
        frame_rate,
        bodies: dict,
        times,
        load: Callable[[int], RecordedFrame],
        event_counts: dict,
        end_time: float | None,
        complete: bool,
        damage=None,
        notes=(),
    ) -> None:
        self.path = path
        self.format = format
        self.writer = writer
        self.bounds = tuple(float(v) for v in bounds)
        self.colours = [tuple(int(c) for c in rgb) for rgb in colours]
        self.background = background
        self.frame_rate = frame_rate
        self.bodies = dict(bodies)
        self.times = np.asarray(times, dtype=np.float64)
        self._load = load
        self.event_counts = dict(event_counts)
        self.complete = complete
        self.damage = damage
        self.notes = list(notes)
        if end_time is None:
            end_time = float(self.times[-1]) if len(self.times) else 0.0
        self.end_time = float(end_time)

    def __len__(self) -> int:
        return len(self.times)

    @property
    def frame_count(self) -> int:
        """Number of frames."""
        return len(self.times)

    @property
    def start_time(self) -> float:
        """Time of the first frame (0.0 if there is none)."""
        return float(self.times[0]) if len(self.times) else 0.0

    @property
    def duration(self) -> float:
        """Seconds from the first frame to the end of the recording."""
        return max(0.0, self.end_time - self.start_time)

    @property
    def body_count(self) -> int:
        """Bodies seen (for files without body ids: most shapes in one frame)."""
        return len(self.bodies)

    def frame(self, index: int) -> RecordedFrame:
        """Frame ``index`` (negative counts from the end); IndexError if out of range."""
        count = len(self.times)
        if index < 0:
            index += count
        if not 0 <= index < count:
            raise IndexError(f"frame {index} out of range: the recording has {count} frames")
        return self._load(index)

    def index_at(self, time: float) -> int:
        """Index of the last frame at or before ``time`` (0 if ``time`` precedes every frame)."""
        return max(0, bisect.bisect_right(self.times, time) - 1)

    def frame_at(self, time: float) -> RecordedFrame:
        """The frame showing the world at ``time`` (the last one at or before it)."""
        return self.frame(self.index_at(time))

    def frames(self, start: int = 0, stop: int | None = None, step: int = 1):
        """Iterate over frames ``start``, ``start + step``, ... before ``stop``."""
        for index in range(*slice(start, stop, step).indices(len(self.times))):
            yield self._load(index)

    def colour(self, index: int) -> tuple[int, int, int]:
        """The RGB colour (0-255) of colour index ``index``."""
        return self.colours[index]

    def __repr__(self) -> str:
        return f"<Recording {self.path} ({self.format}): {len(self)} frames, {self.duration:g} s>"

    def _repr_html_(self) -> str:
        """Jupyter plays a recording inline in the browser viewer (``pge.viewer.Animation``)."""
        from pge.viewer import Animation

        return Animation.from_recording(self)._repr_html_()
