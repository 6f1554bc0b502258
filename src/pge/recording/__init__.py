"""Recordings: the pge file format, writing from a World, reading, and the original's output.raw.

``Recorder(world, path)`` records a running world; ``open_recording(path)``
reads a pge recording or an original PGE ``output.raw`` into a
``Recording`` with random access to its frames. The format is specified in
``docs/recording-format.md``.
"""

from pge.recording.errors import (
    CorruptRecording,
    NotARecording,
    RecordingError,
    TruncatedRecording,
    UnsupportedVersion,
)
from pge.recording.model import BodyInfo, RecordedFrame, Recording
from pge.recording.reader import open_recording
from pge.recording.recorder import Recorder
from pge.recording.writer import RecordingWriter

__all__ = [
    "Recorder",
    "RecordingWriter",
    "Recording",
    "RecordedFrame",
    "BodyInfo",
    "open_recording",
    "RecordingError",
    "NotARecording",
    "UnsupportedVersion",
    "TruncatedRecording",
    "CorruptRecording",
]
