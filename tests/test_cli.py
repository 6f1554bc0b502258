"""The pge command line: info, export, --version, and one-line errors for every user mistake."""

import subprocess
import sys

import pytest
from recording_helpers import raw_batch_file, record_small

from pge import __version__
from pge.cli import main


@pytest.fixture(scope="module")
def small(tmp_path_factory):
    """A small complete recording with collisions (7 frames, 0.3 s)."""
    path = tmp_path_factory.mktemp("cli") / "small.pgerec"
    record_small(path, until=0.3, frame_rate=20)
    return path


def _one_line_error(capsys, code, expected_code, *fragments):
    captured = capsys.readouterr()
    lines = captured.err.strip().splitlines()
    assert code == expected_code
    assert len(lines) == 1 and lines[0].startswith("pge: error: "), captured.err
    for fragment in fragments:
        assert fragment in lines[0]
    assert "Traceback" not in captured.err


def test_info_reports_duration_frames_bodies_and_events(small, capsys):
    """pge info prints the duration, frame count, bodies and event counts of a recording."""
    assert main(["info", str(small)]) == 0
    out = capsys.readouterr().out
    assert "duration   0.3 s" in out
    assert "frames     7 at 20 fps" in out
    assert "bodies     7 (2 circles, 5 polygons)" in out
    assert "complete   yes" in out
    assert "collisions " in out and "timers     0" in out


def test_info_reads_an_original_output_raw(tmp_path, capsys):
    """pge info recognises a hand-written output.raw and counts its frames."""
    path = tmp_path / "output.raw"
    path.write_bytes(raw_batch_file(3))
    assert main(["info", str(path)]) == 0
    out = capsys.readouterr().out
    assert "PGE output.raw" in out and "frames     4" in out


def test_export_writes_a_gif_and_says_where(small, tmp_path, capsys):
    """pge export FILE OUT.gif writes the GIF and reports the frame count."""
    out = tmp_path / "small.gif"
    assert main(["export", str(small), str(out), "--size", "64x48"]) == 0
    assert out.stat().st_size > 100
    assert "7 frames written to" in capsys.readouterr().out


def test_missing_file_is_one_line_error(tmp_path, capsys):
    """A missing file gives 'no such file' and exit 1."""
    code = main(["info", str(tmp_path / "nope.pgerec")])
    _one_line_error(capsys, code, 1, "nope.pgerec: no such file")


def test_wrong_format_is_one_line_error(tmp_path, capsys):
    """A text file is 'not a recording'; a directory is refused too."""
    path = tmp_path / "notes.txt"
    path.write_text("not a recording\n")
    _one_line_error(capsys, main(["export", str(path), str(tmp_path / "x.gif")]), 1, "not a recording")
    _one_line_error(capsys, main(["info", str(tmp_path)]), 1, "is a directory")


def test_truncated_file_is_one_line_error_unless_partial(small, tmp_path, capsys):
    """A cut recording is reported with its frame; --partial reads the intact frames instead."""
    data = small.read_bytes()
    path = tmp_path / "cut.pgerec"
    path.write_bytes(data[: len(data) - 40])
    _one_line_error(capsys, main(["info", str(path)]), 1, "truncated", "frame 7", "7 frames before it are intact")
    assert main(["info", "--partial", str(path)]) == 0
    assert "frames     7" in capsys.readouterr().out


def test_bad_options_are_one_line_usage_errors(small, tmp_path, capsys):
    """Bad sizes, rates, suffixes and unknown commands exit 2 (usage) or 1 with one line."""
    gif = str(tmp_path / "x.gif")
    _one_line_error(capsys, main(["export", str(small), gif, "--size", "big"]), 2, "size must be")
    _one_line_error(capsys, main(["export", str(small), gif, "--fps", "-3"]), 2, "--fps")
    _one_line_error(capsys, main(["export", str(small), gif, "--start", "nan"]), 2, "--start")
    _one_line_error(capsys, main(["export", str(small), str(tmp_path / "x.avi")]), 1, ".gif, .mp4 or .html")
    _one_line_error(capsys, main(["export", str(small), gif, "--start", "9"]), 1, "misses the recording")
    _one_line_error(capsys, main(["frobnicate"]), 2, "invalid choice")
    _one_line_error(capsys, main(["info"]), 2, "FILE")


def test_version_and_help(capsys):
    """--version prints the version; every command has a --help that exits 0."""
    assert main(["--version"]) == 0
    assert capsys.readouterr().out.strip() == f"pge {__version__}"
    for command in ("showcase", "info", "export"):
        assert main([command, "--help"]) == 0
        assert "usage: pge " + command in capsys.readouterr().out


def test_console_command_prints_no_traceback_for_a_corrupt_file(small, tmp_path):
    """Run as a process, a corrupt recording ends with one stderr line and exit status 1."""
    data = bytearray(small.read_bytes())
    data[len(data) // 2] ^= 0x55
    path = tmp_path / "corrupt.pgerec"
    path.write_bytes(bytes(data))
    done = subprocess.run([sys.executable, "-m", "pge.cli", "info", str(path)], capture_output=True, text=True)
    assert done.returncode == 1
    assert done.stderr.count("\n") == 1 and done.stderr.startswith("pge: error: ")
    assert "corrupt: checksum mismatch in frame" in done.stderr
