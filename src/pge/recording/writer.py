"""Writing a pge recording, record by record (see ``pge.recording.format``).

``RecordingWriter`` knows nothing about worlds: it is given plain numbers
(shapes per frame, events, colours, bodies) and appends one framed record per
call, flushed at once, so a reader can follow the file while it grows and a
crash loses at most the record being written. ``Recorder`` feeds it from a
``pge.World``.
"""

from __future__ import annotations

from pathlib import Path

import msgpack
import numpy as np

from pge.recording import format as F

__all__ = ["RecordingWriter"]


def _writer_name() -> str:
    from pge import __version__

    return f"pge {__version__}"


class RecordingWriter:
    """Append frames to a new recording file at ``path`` (overwritten if present).

    ``bounds`` is the world rectangle ``(x0, y0, x1, y1)``; ``colours`` the
    initial colour table (RGB tuples 0-255) and ``background`` an index into
    it; ``frame_rate`` frames per second (or None). Use as a context manager,
    or call ``close(end_time)``.
    """

    def __init__(self, path, bounds, colours, background: int = 0, frame_rate=None, start_time: float = 0.0) -> None:
        self.path = Path(path)
        self._file = open(self.path, "wb")
        self._colours = [tuple(int(c) for c in rgb) for rgb in colours]
        self.frames = 0
        self.collisions = 0
        self.timers = 0
        self.closed = False
        major, minor = F.FORMAT_VERSION
        self._file.write(F.PRELUDE.pack(F.MAGIC, major, minor))
        self._write(
            {
                "k": F.HEADER,
                "format": [major, minor],
                "writer": _writer_name(),
                "bounds": [float(v) for v in bounds],
                "colours": [list(rgb) for rgb in self._colours],
                "background": int(background),
                "frame_rate": None if frame_rate is None else float(frame_rate),
                "start": float(start_time),
            }
        )

    @property
    def colours(self) -> tuple:
        """The colour table written so far."""
        return tuple(self._colours)

    def _write(self, record: dict) -> None:
        if self.closed:
            raise ValueError(f"recording {self.path}: already closed")
        self._file.write(F.record_bytes(msgpack.packb(record, use_bin_type=True)))
        self._file.flush()

    def add_colours(self, colours) -> int:
        """Append RGB colours to the table; returns the index of the first one."""
        first = len(self._colours)
        new = [tuple(int(c) for c in rgb) for rgb in colours]
        self._colours.extend(new)
        self._write({"k": F.COLOURS, "first": first, "colours": [list(rgb) for rgb in new]})
        return first

    def add_bodies(self, bodies) -> None:
        """Declare bodies: an iterable of ``(id, kind, name, fixed)``."""
        rows = [[int(i), str(kind), None if name is None else str(name), bool(fixed)] for i, kind, name, fixed in bodies]
        if rows:
            self._write({"k": F.BODIES, "bodies": rows})

    def write_frame(self, time: float, circles=None, polygons=None, collisions=None, timers=None) -> int:
        """Append a frame at simulation ``time``; returns its index.

        ``circles``: ``(ids, centres (n, 2), radii, colours)``; ``polygons``:
        ``(ids, counts, vertices (total, 2), colours)``; ``collisions``:
        ``(times, a, b, points (n, 2), normals (n, 2), impulses)`` and
        ``timers``: ``(times, ids)``, the events since the previous frame.
        Any of them may be None for none.
        """
        record = {"k": F.FRAME, "i": self.frames, "t": float(time)}
        record.update(_circle_columns(circles))
        record.update(_polygon_columns(polygons))
        record.update(self._event_columns(collisions, timers))
        self._write(record)
        self.frames += 1
        return self.frames - 1

    def _event_columns(self, collisions, timers) -> dict:
        columns = {}
        if collisions is not None and len(collisions[0]):
            times, a, b, points, normals, impulses = collisions
            n = len(times)
            columns["nE"] = n
            columns["E"] = [
                F.pack_column(times, F.REAL),
                F.pack_column(a, F.ID),
                F.pack_column(b, F.ID),
                F.pack_column(points, F.REAL),
                F.pack_column(normals, F.REAL),
                F.pack_column(impulses, F.REAL),
            ]
            self.collisions += n
        if timers is not None and len(timers[0]):
            times, ids = timers
            columns["nT"] = len(times)
            columns["T"] = [F.pack_column(times, F.REAL), F.pack_column(ids, F.ID)]
            self.timers += len(times)
        return columns

    def close(self, end_time: float, collisions=None, timers=None) -> None:
        """Write the end record (with events after the last frame) and close the file."""
        if self.closed:
            return
        record = {
            "k": F.END,
            "t": float(end_time),
            "frames": self.frames,
        }
        record.update(self._event_columns(collisions, timers))
        record["collisions"] = self.collisions
        record["timers"] = self.timers
        self._write(record)
        self.closed = True
        self._file.close()

    def abandon(self) -> None:
        """Close the file without an end record (readers will call it incomplete)."""
        if not self.closed:
            self.closed = True
            self._file.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc) -> None:
        self.abandon()


def _circle_columns(circles) -> dict:
    if circles is None or len(circles[0]) == 0:
        return {}
    ids, centres, radii, colours = circles
    return {
        "nC": len(ids),
        "C": [
            F.pack_column(ids, F.ID),
            F.pack_column(centres, F.REAL),
            F.pack_column(radii, F.REAL),
            F.pack_column(colours, F.COLOUR),
        ],
    }


def _polygon_columns(polygons) -> dict:
    if polygons is None or len(polygons[0]) == 0:
        return {}
    ids, counts, vertices, colours = polygons
    counts = np.asarray(counts)
    return {
        "nP": len(ids),
        "nV": int(counts.sum()),
        "P": [
            F.pack_column(ids, F.ID),
            F.pack_column(counts, F.COUNT),
            F.pack_column(vertices, F.REAL),
            F.pack_column(colours, F.COLOUR),
        ],
    }
