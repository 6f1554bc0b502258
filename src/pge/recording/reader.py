"""Reading pge recordings, and ``open_recording`` for any supported file.

Opening scans the file once: it checks the prelude, then walks the records,
verifying each one's length and CRC-32 and noting where every frame starts.
Frames are decoded only when asked for (``Recording.frame``), re-reading
their record from the file. Reading stops at the first damaged record: in
strict mode (the default) that raises a ``RecordingError`` naming the frame
and byte offset, with ``error.partial`` holding the intact frames before it;
with ``strict=False`` the Recording is returned and ``damage`` says why it
ends early.
"""

from __future__ import annotations

import zlib
from pathlib import Path

import msgpack
import numpy as np

from pge.recording import format as F
from pge.recording.errors import (
    CorruptRecording,
    NotARecording,
    RecordingError,
    TruncatedRecording,
    UnsupportedVersion,
)
from pge.recording.model import (
    BodyInfo,
    Circles,
    Collisions,
    Polygons,
    RecordedFrame,
    Recording,
    Timers,
    empty_circles,
    empty_collisions,
    empty_polygons,
    empty_timers,
)

__all__ = ["open_recording", "read_pge"]


def open_recording(path, strict: bool = True) -> Recording:
    """Open a pge recording or an original PGE ``output.raw``, whichever ``path`` is.

    Raises FileNotFoundError / OSError if the file cannot be read,
    ``NotARecording`` if it is neither kind, and (``strict``) another
    ``RecordingError`` if it is damaged.
    """
    path = Path(path)
    with open(path, "rb") as file:
        start = file.read(len(F.MAGIC))
    if not start:
        raise NotARecording(f"{path}: empty file, not a recording", path, 0, 0)
    if F.MAGIC.startswith(start):  # a shorter start is a cut prelude
        return read_pge(path, strict)
    from pge.recording.raw import looks_like_raw, read_raw

    if looks_like_raw(start):
        return read_raw(path, strict)
    raise NotARecording(f"{path}: not a recording (neither a pge recording nor a PGE output.raw)", path, 0, 0)


def read_pge(path, strict: bool = True) -> Recording:
    """Open the pge recording at ``path`` (see ``open_recording``)."""
    path = Path(path)
    data = path.read_bytes()
    return _Scan(path, data).recording(strict)


class _Scan:
    """One pass over a pge file: header, colours, bodies, frame offsets."""

    def __init__(self, path: Path, data: bytes) -> None:
        self.path = path
        self.header = None
        self.colours = []
        self.bodies = {}
        self.offsets: list[int] = []
        self.times: list[float] = []
        self.counts = {"collisions": 0, "timers": 0}
        self.end = None
        self.damage = None
        self._walk(data)

    def _fail(self, kind, what: str, offset: int):
        frame = len(self.offsets)
        where = f"frame {frame}" if self.header is not None else "the header"
        label = "truncated" if kind is TruncatedRecording else "corrupt"
        raise kind(
            f"{self.path}: {label}: {what} in {where} (byte {offset}); {frame} frames before it are intact",
            self.path,
            frame,
            offset,
        )

    def _walk(self, data: bytes) -> None:
        view = memoryview(data)
        if len(data) < F.PRELUDE.size:
            if F.MAGIC.startswith(bytes(view[:8])):
                self.damage = TruncatedRecording(f"{self.path}: truncated in the prelude (byte {len(data)})", self.path, 0, 0)
                return
            raise NotARecording(f"{self.path}: not a pge recording (bad magic)", self.path, 0, 0)
        magic, major, minor = F.PRELUDE.unpack_from(view, 0)
        if magic != F.MAGIC:
            raise NotARecording(f"{self.path}: not a pge recording (bad magic)", self.path, 0, 0)
        if major != F.FORMAT_VERSION[0]:
            raise UnsupportedVersion(
                f"{self.path}: format version {major}.{minor} is not supported (this reader knows {F.FORMAT_VERSION[0]}.x)",
                self.path, 0, 0,
            )
        self.version = (major, minor)
        offset = F.PRELUDE.size
        try:
            while offset < len(data) and self.end is None:
                offset = self._record(view, offset)
            if self.end is not None and offset < len(data):
                self._fail(CorruptRecording, f"{len(data) - offset} bytes after the end record", offset)
            if self.header is None:
                self._fail(TruncatedRecording, "file ends before the header record", offset)
        except RecordingError as error:
            self.damage = error

    def _record(self, view: memoryview, offset: int) -> int:
        size = len(view)
        if offset + F.RECORD_HEAD.size > size:
            self._fail(TruncatedRecording, "file ends inside a record head", offset)
        length, crc = F.RECORD_HEAD.unpack_from(view, offset)
        if length > F.MAX_RECORD:
            self._fail(CorruptRecording, f"impossible record length {length}", offset)
        body = offset + F.RECORD_HEAD.size
        if body + length > size:
            self._fail(TruncatedRecording, f"record of {length} bytes cut after {size - body}", offset)
        payload = view[body : body + length]
        if zlib.crc32(payload, zlib.crc32(view[offset : offset + 4])) != crc:
            self._fail(CorruptRecording, "checksum mismatch", offset)
        try:
            record = msgpack.unpackb(payload, raw=False)
            self._take(record, offset)
        except RecordingError:
            raise
        except Exception as error:  # checksum right but contents wrong: a writer bug or a forgery
            self._fail(CorruptRecording, f"bad record contents ({error})", offset)
        return body + length

    def _take(self, record: dict, offset: int) -> None:
        kind = record["k"]
        if self.header is None:
            if kind != F.HEADER:
                raise ValueError(f"first record is {kind!r}, not the header")
            if list(record["format"]) != list(self.version):
                raise ValueError(f"header says format {record['format']}, prelude {list(self.version)}")
            self.header = record
            self.colours = [tuple(rgb) for rgb in record["colours"]]
            return
        if kind == F.FRAME:
            if record["i"] != len(self.offsets):
                raise ValueError(f"frame numbered {record['i']}")
            time = float(record["t"])
            if self.times and time < self.times[-1]:
                raise ValueError(f"frame time {time!r} before the previous frame's {self.times[-1]!r}")
            self.offsets.append(offset)
            self.times.append(time)
            self.counts["collisions"] += record.get("nE", 0)
            self.counts["timers"] += record.get("nT", 0)
        elif kind == F.BODIES:
            for i, body_kind, name, fixed in record["bodies"]:
                self.bodies[i] = BodyInfo(i, body_kind, name, fixed)
        elif kind == F.COLOURS:
            if record["first"] != len(self.colours):
                raise ValueError(f"colours start at {record['first']}, table has {len(self.colours)}")
            self.colours.extend(tuple(rgb) for rgb in record["colours"])
        elif kind == F.END:
            self.end = record
            self.counts["collisions"] += record.get("nE", 0)
            self.counts["timers"] += record.get("nT", 0)
        # unknown kinds are skipped: later minor versions may add some

    def recording(self, strict: bool) -> Recording:
        if self.header is None:
            raise self.damage
        header = self.header
        major, minor = header["format"]
        recording = Recording(
            path=self.path,
            format=f"pge {major}.{minor}",
            writer=header.get("writer"),
            bounds=header["bounds"],
            colours=self.colours,
            background=header.get("background", 0),
            frame_rate=header.get("frame_rate"),
            bodies=self.bodies,
            times=self.times,
            load=_FrameLoader(self.path, self.offsets),
            event_counts=self.counts,
            end_time=None if self.end is None else self.end["t"],
            complete=self.end is not None,
            damage=self.damage,
        )
        if self.damage is not None and strict:
            self.damage.partial = recording
            raise self.damage
        return recording


class _FrameLoader:
    """Decodes frame ``k`` from its record, re-read from the file."""

    def __init__(self, path: Path, offsets: list[int]) -> None:
        self.path = path
        self.offsets = offsets

    def __call__(self, index: int) -> RecordedFrame:
        offset = self.offsets[index]
        with open(self.path, "rb") as file:
            file.seek(offset)
            head = file.read(F.RECORD_HEAD.size)
            length, crc = F.RECORD_HEAD.unpack(head)
            payload = file.read(length)
        if len(payload) != length or zlib.crc32(payload, zlib.crc32(head[:4])) != crc:
            raise CorruptRecording(f"{self.path}: frame {index} changed since the file was opened", self.path, index, offset)
        return decode_frame(msgpack.unpackb(payload, raw=False))


def decode_frame(record: dict) -> RecordedFrame:
    """A RecordedFrame from a frame record's map."""
    circles = empty_circles()
    if record.get("nC"):
        n = record["nC"]
        ids, centres, radii, colours = record["C"]
        circles = Circles(
            F.unpack_column(ids, F.ID, n),
            F.unpack_column(centres, F.REAL, 2 * n).reshape(n, 2),
            F.unpack_column(radii, F.REAL, n),
            F.unpack_column(colours, F.COLOUR, n),
        )
    polygons = empty_polygons()
    if record.get("nP"):
        n, total = record["nP"], record["nV"]
        ids, counts, vertices, colours = record["P"]
        counts = F.unpack_column(counts, F.COUNT, n)
        starts = np.zeros(n + 1, np.int64)
        np.cumsum(counts, out=starts[1:])
        polygons = Polygons(
            F.unpack_column(ids, F.ID, n),
            starts,
            F.unpack_column(vertices, F.REAL, 2 * total).reshape(total, 2),
            F.unpack_column(colours, F.COLOUR, n),
        )
    return RecordedFrame(int(record["i"]), float(record["t"]), circles, polygons, *decode_events(record))


def decode_events(record: dict):
    """``(Collisions, Timers)`` from a frame or end record's map."""
    collisions = empty_collisions()
    if record.get("nE"):
        n = record["nE"]
        t, a, b, points, normals, impulses = record["E"]
        collisions = Collisions(
            F.unpack_column(t, F.REAL, n),
            F.unpack_column(a, F.ID, n),
            F.unpack_column(b, F.ID, n),
            F.unpack_column(points, F.REAL, 2 * n).reshape(n, 2),
            F.unpack_column(normals, F.REAL, 2 * n).reshape(n, 2),
            F.unpack_column(impulses, F.REAL, n),
        )
    timers = empty_timers()
    if record.get("nT"):
        n = record["nT"]
        t, ids = record["T"]
        timers = Timers(F.unpack_column(t, F.REAL, n), F.unpack_column(ids, F.ID, n))
    return collisions, timers
