"""Reading the original PGE's ``output.raw`` into a ``Recording``.

The original's recording is a stream of glyph commands (see
``docs/recording-format.md`` and the PGE reference, sections 3.4-3.5): each
command is two ASCII letters and a NUL, then its fields; ``short`` and
``card`` are big-endian unsigned 16/32-bit integers, ``double`` is native
(little-endian on the machines PGE ran on; big-endian is tried when the
little-endian value is not a sane duration), and ``fract`` is an exact
fraction (a tag byte, then 0, 2 or 3 big-endian uint64).

How it maps onto a Recording:

* a frame ends at ``fb``; an ``fb`` with nothing drawn and no ``fn`` since
  the previous frame (the original writes two per frame) adds no frame;
* a frame's time is the sum of the ``sl`` sleeps before it: the original's
  playback clock (in batch recordings that runs about twice as fast as the
  simulation, since both the engine and Python write a sleep);
* shapes have no body ids in this format, so a shape's id is its position
  in its frame's drawing order;
* colours are the ``rc`` registrations, with the engine's predefined colours
  1-7 (white, black, red, green, blue, yellow, purple) as fallback;
* the world border ``dp``, outline circles ``dc``, lines ``dl``, sounds ``ps``
  and messages ``ms`` are read and counted in ``Recording.notes`` but not drawn.
"""

from __future__ import annotations

import math
import struct
from pathlib import Path

import numpy as np

from pge.recording.errors import CorruptRecording, RecordingError, TruncatedRecording
from pge.recording.model import (
    BodyInfo,
    Circles,
    Polygons,
    RecordedFrame,
    Recording,
    empty_collisions,
    empty_timers,
)

__all__ = ["read_raw", "looks_like_raw", "COMMANDS", "PREDEFINED_COLOURS"]

COMMANDS = (b"rc", b"dP", b"dp", b"dC", b"dc", b"dl", b"fb", b"sl", b"fn", b"ex", b"ps", b"ms", b"fr")
_HEADERS = {name + b"\0": name.decode() for name in COMMANDS}

#: the engine's colour ids 1-7, used when a file draws with one it never registered.
PREDEFINED_COLOURS = {
    1: (255, 255, 255),
    2: (0, 0, 0),
    3: (255, 0, 0),
    4: (0, 255, 0),
    5: (0, 0, 255),
    6: (255, 255, 0),
    7: (128, 0, 128),
}
_UNKNOWN_COLOUR = (128, 128, 128)
_BACKGROUND = (0, 0, 0)  # the original player's
_LONGEST_SLEEP = 1e6


def looks_like_raw(start: bytes) -> bool:
    """True if ``start`` (the file's first bytes) begins with an output.raw command."""
    return start[:3] in _HEADERS


class _Truncated(Exception):
    pass


class _Bad(Exception):
    pass


class _Stream:
    """Big-endian field reader over the file's bytes."""

    def __init__(self, data: bytes) -> None:
        self.data = data
        self.pos = 0

    def take(self, n: int) -> bytes:
        end = self.pos + n
        if end > len(self.data):
            raise _Truncated()
        chunk = self.data[self.pos : end]
        self.pos = end
        return chunk

    def short(self) -> int:
        return struct.unpack(">H", self.take(2))[0]

    def card(self) -> int:
        return struct.unpack(">I", self.take(4))[0]

    def fract(self) -> float:
        tag = self.take(1)[0]
        if tag == 0:
            return 0.0
        if tag == 1:
            return 1.0
        if tag == 2:
            numerator, denominator = struct.unpack(">QQ", self.take(16))
            whole = 0
        elif tag == 3:
            whole, numerator, denominator = struct.unpack(">QQQ", self.take(24))
        else:
            raise _Bad(f"bad fraction tag {tag}")
        if denominator == 0:
            raise _Bad("fraction with denominator 0")
        return (whole * denominator + numerator) / denominator  # exact ints, one correct rounding

    def point(self) -> tuple[float, float]:
        return (self.fract(), self.fract())

    def double(self) -> float:
        raw = self.take(8)
        value = struct.unpack("<d", raw)[0]
        if not (math.isfinite(value) and 0.0 <= value <= _LONGEST_SLEEP):
            value = struct.unpack(">d", raw)[0]
            if not (math.isfinite(value) and 0.0 <= value <= _LONGEST_SLEEP):
                raise _Bad("sleep is not a sane duration in either byte order")
        return value

    def text(self) -> str:
        end = self.data.find(b"\0", self.pos)
        if end < 0:
            raise _Truncated()
        text = self.data[self.pos : end].decode("latin-1")
        self.pos = end + 1
        return text


class _Parser:
    """Turns the command stream into frames."""

    def __init__(self, path: Path, data: bytes) -> None:
        self.path = path
        self.stream = _Stream(data)
        self.colours = [_BACKGROUND]
        self.colour_index: dict[int, int] = {}
        self.frames: list[RecordedFrame] = []
        self.clock = 0.0
        self._carry = 0.0  # Neumaier compensation: the clock stays the correctly rounded sum
        self.frame_rate = None
        self.notes: dict[str, int] = {}
        self.kinds: dict[int, str] = {}
        self._start_frame()

    def _start_frame(self) -> None:
        self.circles: list[tuple] = []
        self.polygons: list[tuple] = []
        self.started = False  # an fn or a drawing command since the last frame

    def _note(self, what: str) -> None:
        self.notes[what] = self.notes.get(what, 0) + 1

    def _colour(self, engine_id: int) -> int:
        index = self.colour_index.get(engine_id)
        if index is None:
            self.colours.append(PREDEFINED_COLOURS.get(engine_id, _UNKNOWN_COLOUR))
            if engine_id not in PREDEFINED_COLOURS:
                self._note(f"colour {engine_id} used but never registered")
            index = self.colour_index[engine_id] = len(self.colours) - 1
        return index

    def parse(self):
        """Read every command; returns the damage (a RecordingError) or None."""
        stream = self.stream
        while stream.pos < len(stream.data):
            at = stream.pos
            try:
                header = stream.take(3)
                command = _HEADERS.get(header)
                if command is None:
                    raise _Bad(f"unknown command {header!r}")
                if getattr(self, "_" + command)() is False:
                    break
            except _Truncated:
                return self._damage(TruncatedRecording, "file ends inside a command", at)
            except _Bad as error:
                return self._damage(CorruptRecording, str(error), at)
        if self.circles or self.polygons:
            return self._damage(TruncatedRecording, "file ends inside a frame (no fb)", stream.pos)
        return None

    def _damage(self, kind, what: str, offset: int) -> RecordingError:
        frame = len(self.frames)
        return kind(
            f"{self.path}: {'truncated' if kind is TruncatedRecording else 'corrupt'}: {what} in frame {frame} "
            f"(byte {offset}); {frame} frames before it are intact",
            self.path,
            frame,
            offset,
        )

    # one method per command; each reads its fields

    def _rc(self) -> None:
        engine_id = self.stream.short()
        rgb = tuple(int(round(min(1.0, self.stream.fract()) * 255)) for _ in range(3))
        self.colours.append(rgb)
        self.colour_index[engine_id] = len(self.colours) - 1

    def _dP(self) -> None:
        n = self.stream.short()
        corners = [self.stream.point() for _ in range(n)]
        colour = self._colour(self.stream.short())
        if n >= 3:
            self.polygons.append((len(self.circles) + len(self.polygons), corners, colour))
        else:
            self._note("degenerate filled polygon (fewer than 3 corners)")
        self.started = True

    def _dp(self) -> None:
        n = self.stream.short()
        for _ in range(n):
            self.stream.point()
        self.stream.fract()
        self._note("outline polygon (dp) not drawn")

    def _dC(self) -> None:
        centre = self.stream.point()
        radius = self.stream.fract()
        colour = self._colour(self.stream.short())
        self.circles.append((len(self.circles) + len(self.polygons), centre, radius, colour))
        self.started = True

    def _dc(self) -> None:
        self.stream.point()
        self.stream.fract()
        self.stream.fract()
        self._note("outline circle (dc) not drawn")

    def _dl(self) -> None:
        self.stream.point()
        self.stream.point()
        self.stream.fract()
        self.stream.short()
        self._note("line (dl) not drawn")

    def _fb(self) -> None:
        if self.started:
            self._finish_frame()

    def _sl(self) -> None:
        seconds = self.stream.double()
        total = self.clock + seconds
        if abs(self.clock) >= abs(seconds):
            self._carry += (self.clock - total) + seconds
        else:
            self._carry += (seconds - total) + self.clock
        self.clock = total

    @property
    def now(self) -> float:
        return self.clock + self._carry

    def _fn(self) -> None:
        self.stream.card()
        self.started = True

    def _ex(self) -> bool:
        self.stream.take(1)
        if self.stream.pos < len(self.stream.data):
            self._note("bytes after ex ignored")
        return False

    def _ps(self) -> None:
        self.stream.text()
        self._note("sound (ps) not played")

    def _ms(self) -> None:
        self.stream.text()
        self._note("message (ms) not shown")

    def _fr(self) -> None:
        fps = self.stream.card()
        self.frame_rate = float(fps) if fps else None

    def _finish_frame(self) -> None:
        index = len(self.frames)
        circles = Circles(
            np.array([c[0] for c in self.circles], np.int64),
            np.array([c[1] for c in self.circles], np.float64).reshape(-1, 2),
            np.array([c[2] for c in self.circles], np.float64),
            np.array([c[3] for c in self.circles], np.uint16),
        )
        counts = [len(p[1]) for p in self.polygons]
        starts = np.zeros(len(counts) + 1, np.int64)
        np.cumsum(counts, out=starts[1:])
        polygons = Polygons(
            np.array([p[0] for p in self.polygons], np.int64),
            starts,
            np.array([xy for p in self.polygons for xy in p[1]], np.float64).reshape(-1, 2),
            np.array([p[2] for p in self.polygons], np.uint16),
        )
        for shape_id in circles.ids:
            self.kinds.setdefault(int(shape_id), "circle")
        for shape_id in polygons.ids:
            self.kinds.setdefault(int(shape_id), "polygon")
        self.frames.append(RecordedFrame(index, self.now, circles, polygons, empty_collisions(), empty_timers()))
        self._start_frame()


def read_raw(path, strict: bool = True) -> Recording:
    """Open an original PGE ``output.raw`` (see ``pge.recording.open_recording``)."""
    path = Path(path)
    parser = _Parser(path, path.read_bytes())
    damage = parser.parse()
    frames = parser.frames
    recording = Recording(
        path=path,
        format="PGE output.raw",
        writer=None,
        bounds=(0.0, 0.0, 1.0, 1.0),
        colours=parser.colours,
        background=0,
        frame_rate=parser.frame_rate,
        bodies={i: BodyInfo(i, kind, None, False) for i, kind in sorted(parser.kinds.items())},
        times=[frame.time for frame in frames],
        load=frames.__getitem__,
        event_counts={"collisions": 0, "timers": 0},
        end_time=max(parser.now, frames[-1].time) if frames else parser.now,
        complete=damage is None,
        damage=damage,
        notes=[f"{what}: {count}" for what, count in parser.notes.items()],
    )
    if damage is not None and strict:
        damage.partial = recording
        raise damage
    return recording
