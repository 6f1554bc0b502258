"""Reading the original PGE's output.raw (hand-written files following the reference spec)."""

from fractions import Fraction

import pytest
from recording_helpers import cmd, disc, fract, raw_batch_file, short, sleep

from pge.recording import CorruptRecording, TruncatedRecording, open_recording
from pge.render.export import export


def test_batch_file_gives_one_frame_per_drawn_flip_with_exact_fractions(tmp_path):
    """Frame 1 (colours only) plus four drawn frames; the doubled fb adds none; fractions decode exactly."""
    path = tmp_path / "output.raw"
    path.write_bytes(raw_batch_file(4))
    recording = open_recording(path)
    assert recording.format == "PGE output.raw" and recording.complete
    assert len(recording) == 5
    assert recording.times.tolist() == [0.0, 0.02, 0.04, 0.06, 0.08]
    assert recording.frame(0).shape_count == 0
    frame = recording.frame(3)
    assert frame.circles.centres.tolist() == [[3 / 10, 0.5]] and frame.circles.radii.tolist() == [0.1]
    assert frame.polygons.outline(0).tolist() == [[0.6, 0.1], [0.9, 0.1], [0.75, 0.3]]
    assert recording.colours[frame.circles.colours[0]] == (128, 64, 255)
    assert recording.colours[frame.polygons.colours[0]] == (255, 0, 0)
    assert recording.body_count == 2
    assert any("dp" in note for note in recording.notes)


def test_fraction_with_whole_part_and_predefined_colour(tmp_path):
    """Tag 3 fractions (w + n/d) decode exactly; an unregistered predefined colour falls back to its RGB."""
    path = tmp_path / "output.raw"
    path.write_bytes(cmd("fn") + short(0) + short(1) + disc(Fraction(5, 4), Fraction(1, 3), Fraction(1, 20), 5) + cmd("fb"))
    frame = open_recording(path).frame(0)
    assert frame.circles.centres.tolist() == [[1.25, 1 / 3]]
    assert open_recording(path).colours[frame.circles.colours[0]] == (0, 0, 255)
    assert fract(Fraction(5, 4))[0] == 3


def test_truncated_raw_names_the_frame_and_keeps_earlier_frames(tmp_path):
    """A raw file cut inside frame 3's disc is truncated 'in frame 3'; frames 0-2 are readable."""
    data = raw_batch_file(4)
    cut = data.index(cmd("dC"), data.index(cmd("fn") + b"\0\0\0\4")) + 10
    path = tmp_path / "output.raw"
    path.write_bytes(data[:cut])
    with pytest.raises(TruncatedRecording, match="in frame 3 ") as caught:
        open_recording(path)
    assert len(caught.value.partial) == 3
    assert caught.value.partial.frame(2).circles.centres[0, 0] == 0.2


def test_unknown_command_is_corruption(tmp_path):
    """An unknown 3-byte command is reported as corrupt with its bytes and frame."""
    path = tmp_path / "output.raw"
    path.write_bytes(raw_batch_file(2) + b"zz\0" + sleep(0.1))
    with pytest.raises(CorruptRecording, match=r"unknown command b'zz\\x00' in frame 3"):
        open_recording(path)


def test_hand_written_raw_exports_to_gif(tmp_path):
    """An output.raw exports like a pge recording: the disc's pixel is its registered colour."""
    from PIL import Image

    path = tmp_path / "output.raw"
    path.write_bytes(raw_batch_file(4))
    out = tmp_path / "raw.gif"
    assert export(open_recording(path), out, size=(100, 100), progress=False) == 5
    with Image.open(out) as gif:
        assert gif.n_frames == 5 and gif.size == (100, 100)
        gif.seek(1)
        assert gif.convert("RGB").getpixel((10, 50)) == (128, 64, 255)
        assert gif.convert("RGB").getpixel((75, 85)) == (255, 0, 0)
