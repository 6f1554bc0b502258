"""record()/finish_record() of the classic API write a pge recording, and only when asked."""

from __future__ import annotations

import pytest
from classic_support import session  # noqa: F401 (the fixture every test uses)

import pge

pytestmark = pytest.mark.usefixtures("session")


def test_record_writes_output_pgerec_with_every_frame(tmp_path, monkeypatch):
    """record() then run(0.5) writes output.pgerec: 51 frames at 100 fps, the ball where it was, in its colour."""
    monkeypatch.chdir(tmp_path)
    from pge.recording import open_recording

    pge.box(0.0, 0.0, 1.0, 0.05, pge.rgb(0.2, 0.3, 0.4)).fix()
    ball = pge.circle(0.5, 0.5, 0.05, pge.rgb(1, 0, 0)).mass(1)
    pge.gravity()
    pge.record()
    pge.at_time(0.1, lambda e, o: None)
    pge.run(0.5)
    pge.finish_record()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["output.pgerec"]
    recording = open_recording(tmp_path / "output.pgerec")
    assert len(recording) == 51 and recording.frame_rate == 100.0 and recording.complete
    assert recording.event_counts == {"collisions": 1, "timers": 1}
    frame = recording.frame(20)
    assert abs(frame.time - 0.2) < 1e-12
    assert tuple(frame.circles.centres[0]) == (0.5, 0.5 - 0.5 * 9.81 * frame.time**2)
    assert recording.colour(int(frame.circles.colours[0])) == (255, 0, 0)
    last = recording.frame(len(recording) - 1)
    assert tuple(last.circles.centres[0]) == (ball.get_xpos(), ball.get_ypos())  # after its bounce


def test_no_file_without_record(tmp_path, monkeypatch):
    """Runs (headless or batch) write nothing unless record() was called."""
    monkeypatch.chdir(tmp_path)
    pge.batch()
    pge.circle(0.5, 0.5, 0.05, pge.white()).mass(1).velocity(0.1, 0.0)
    pge.run(0.3)
    assert list(tmp_path.iterdir()) == []
