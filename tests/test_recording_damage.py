"""Damaged recordings: every cut and every flipped byte is reported with the frame where reading stopped."""

import msgpack
import pytest
from recording_helpers import record_small

from pge.recording import (
    CorruptRecording,
    NotARecording,
    RecordingError,
    TruncatedRecording,
    UnsupportedVersion,
    open_recording,
)
from pge.recording import format as F


@pytest.fixture(scope="module")
def small(tmp_path_factory):
    """A small complete recording: its bytes, its frames' circle data, and where each record ends."""
    path = tmp_path_factory.mktemp("small") / "small.pgerec"
    record_small(path, until=0.3, frame_rate=20)
    data = path.read_bytes()
    recording = open_recording(path)
    frames = [frame.circles.centres.tobytes() + frame.polygons.vertices.tobytes() for frame in recording.frames()]
    records = []  # (start, end, frames before this record, kind)
    offset, count = F.PRELUDE.size, 0
    while offset < len(data):
        length, _ = F.RECORD_HEAD.unpack_from(data, offset)
        end = offset + F.RECORD_HEAD.size + length
        kind = msgpack.unpackb(data[offset + F.RECORD_HEAD.size : end])["k"]
        records.append((offset, end, count, kind))
        count += kind == F.FRAME
        offset = end
    kinds = [r[3] for r in records]
    assert len(frames) == 7 and kinds.count(F.FRAME) == 7 and kinds[-1] == F.END
    return data, frames, records


def _check_partial(recording, frames, count):
    assert len(recording) == count
    for k in range(count):
        frame = recording.frame(k)
        assert frame.circles.centres.tobytes() + frame.polygons.vertices.tobytes() == frames[k]


def _intact_frames(records, offset):
    """Number of frame records lying wholly before byte ``offset``."""
    return sum(1 for _, end, _, kind in records if end <= offset and kind == F.FRAME)


def test_cut_at_every_byte_is_reported_with_the_frame_and_earlier_frames_stay_readable(small, tmp_path):
    """Cutting the file at any byte gives intact frames before the cut and names the frame that was cut."""
    data, frames, records = small
    path = tmp_path / "cut.pgerec"
    ends = {r[1] for r in records}
    for cut in range(1, len(data)):
        path.write_bytes(data[:cut])
        intact = _intact_frames(records, cut)
        if cut in ends:  # a cut between records: readable, just not closed
            recording = open_recording(path)
            assert not recording.complete and recording.damage is None
            _check_partial(recording, frames, intact)
            continue
        with pytest.raises(TruncatedRecording) as caught:
            open_recording(path)
        error = caught.value
        assert error.frame == intact, cut
        if cut > records[0][1]:
            assert f"in frame {intact} " in str(error)
            _check_partial(error.partial, frames, intact)
        lenient = open_recording(path, strict=False) if error.partial is not None else None
        if lenient is not None:
            assert isinstance(lenient.damage, TruncatedRecording) and len(lenient) == intact


def test_flipped_byte_anywhere_is_reported_with_the_frame_and_earlier_frames_stay_readable(small, tmp_path):
    """Inverting any one byte is detected; the error names the frame whose record holds it."""
    data, frames, records = small
    path = tmp_path / "flipped.pgerec"
    for at in range(len(data)):
        damaged = bytearray(data)
        damaged[at] ^= 0xFF
        path.write_bytes(bytes(damaged))
        with pytest.raises(RecordingError) as caught:
            open_recording(path)
        error = caught.value
        if at < 8:
            assert isinstance(error, NotARecording)
            continue
        if at < F.PRELUDE.size:
            assert isinstance(error, (UnsupportedVersion, CorruptRecording))
            continue
        assert isinstance(error, (CorruptRecording, TruncatedRecording)), at
        holder = next(count for start, end, count, _ in records if start <= at < end)
        assert error.frame == holder, at
        if error.partial is not None:
            _check_partial(error.partial, frames, holder)
        else:
            assert holder == 0


def test_garbage_and_empty_files_are_not_recordings(tmp_path):
    """Text, random bytes and an empty file are refused as 'not a recording'."""
    for name, content in (("text.txt", b"hello world\n"), ("empty", b""), ("noise", bytes(range(256)))):
        path = tmp_path / name
        path.write_bytes(content)
        with pytest.raises(NotARecording, match="not a recording"):
            open_recording(path)


def test_bytes_after_the_end_record_are_corruption(small, tmp_path):
    """Anything appended after the end record is reported, with every frame still readable."""
    data, frames, _ = small
    path = tmp_path / "tail.pgerec"
    path.write_bytes(data + b"\0\0\0")
    with pytest.raises(CorruptRecording, match="after the end record") as caught:
        open_recording(path)
    _check_partial(caught.value.partial, frames, len(frames))
