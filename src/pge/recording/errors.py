"""Errors raised when a recording cannot be read (or only partly).

Every error is a ``ValueError`` whose message is one line saying what is wrong
and where: the file, the frame at which reading stopped and the byte offset.
Damaged files still give what came before the damage: ``error.partial`` is a
``Recording`` of the frames read intact (None when not even the header was).
"""

from __future__ import annotations

__all__ = [
    "RecordingError",
    "NotARecording",
    "UnsupportedVersion",
    "TruncatedRecording",
    "CorruptRecording",
]


class RecordingError(ValueError):
    """A recording could not be read completely.

    ``frame`` is the index of the frame at which reading stopped (so frames
    ``0 .. frame - 1`` are intact), ``offset`` the byte offset of the damaged
    record, ``partial`` the Recording of the intact frames (or None).
    """

    def __init__(self, message: str, path=None, frame: int | None = None, offset: int | None = None) -> None:
        super().__init__(message)
        self.path = path
        self.frame = frame
        self.offset = offset
        self.partial = None


class NotARecording(RecordingError):
    """The file is neither a pge recording nor an original PGE output.raw."""


class UnsupportedVersion(RecordingError):
    """The file was written in a newer major format version than this reader knows."""


class TruncatedRecording(RecordingError):
    """The file ends inside a record: cut short, or still being written."""


class CorruptRecording(RecordingError):
    """A record's checksum or contents are wrong."""
