"""Recording a World and reading it back: exact shapes, events, colours, bodies, random access."""

import numpy as np
import pytest
from recording_helpers import GRAVITY, bouncing_scene, falling_scene, record_small

from pge.recording import Recorder, RecordingWriter, UnsupportedVersion, open_recording
from pge.recording import format as F
from pge.render.image import PALETTE


def test_round_trip_matches_closed_form_positions_exactly(tmp_path):
    """Every recorded disc centre equals x0 + (v + a t / 2) t at its frame time, bit for bit."""
    world, starts = falling_scene()
    path = tmp_path / "fall.pgerec"
    with Recorder(world, path, frame_rate=100):
        world.run_until(1.0)
    recording = open_recording(path)
    assert len(recording) == 101
    assert recording.times.tolist() == [k / 100 for k in range(101)]
    for frame in recording.frames():
        t = frame.time
        expected = [
            (x + (vx + 0.5 * GRAVITY[0] * t) * t, y + (vy + 0.5 * GRAVITY[1] * t) * t) for (x, y), (vx, vy) in starts
        ]
        assert frame.circles.centres.tolist() == [list(p) for p in expected]
        assert frame.circles.radii.tolist() == [0.02 + 0.002 * k for k in range(5)]


def test_round_trip_equals_engine_positions_and_vertices_through_collisions(tmp_path):
    """With many collisions, each frame's shapes equal Body.position / Body.vertices read at that frame."""
    world = bouncing_scene()
    seen = []
    path = tmp_path / "bounce.pgerec"
    recorder = Recorder(world, path, frame_rate=50)

    def sample(frame):
        circles = [b.position for b in world.bodies if b.kind == "circle"]
        polygons = [v for b in world.bodies if b.kind == "polygon" for v in b.vertices]
        seen.append((frame.time, circles, polygons))

    world.on_frame(sample)
    world.run_until(1.0)
    recorder.close()
    recording = open_recording(path)
    assert recording.event_counts["collisions"] > 10
    assert len(recording) == len(seen) + 1
    for frame, (time, circles, polygons) in zip(recording.frames(1), seen):
        assert frame.time == time
        assert frame.circles.centres.tolist() == [list(p) for p in circles]
        assert frame.polygons.vertices.tolist() == [list(v) for v in polygons]


def test_collision_and_timer_events_are_recorded_with_time_bodies_and_point(tmp_path):
    """Each collision is stored once, in the first frame at or after its time, with ids and contact point."""
    world = bouncing_scene()
    events = []
    world.on_collision(events.append)
    path = tmp_path / "events.pgerec"
    with Recorder(world, path, frame_rate=20) as recorder:
        recorder.at_time(0.33, lambda event: None)
        world.run_until(0.61)
    recording = open_recording(path)
    stored = []
    previous = -1.0
    for frame in recording.frames():
        c = frame.collisions
        assert all(previous < t <= frame.time for t in c.times)
        stored += list(zip(c.times.tolist(), c.a.tolist(), c.b.tolist(), map(tuple, c.points.tolist())))
        previous = frame.time
    assert stored == [(e.time, e.a.id, e.b.id, e.point) for e in events if e.time <= 0.6]
    assert recording.event_counts == {"collisions": len(events), "timers": 1}
    timer_frame = recording.frame_at(0.35)
    assert timer_frame.timers.times.tolist() == [0.33]


def test_colours_bodies_and_header_are_recorded(tmp_path):
    """Data colours are added to the table, others follow the palette; bodies and bounds are listed."""
    path = tmp_path / "small.pgerec"
    record_small(path)
    recording = open_recording(path)
    first = recording.frame(0)
    assert recording.colours[first.circles.colours[0]] == (250, 20, 20)
    assert recording.colours[first.circles.colours[1]] == PALETTE[5 % len(PALETTE)]
    assert recording.bodies[4].name == "big" and recording.bodies[4].kind == "circle"
    assert recording.bodies[0].fixed and not recording.bodies[6].fixed
    assert recording.bounds == (0.0, 0.0, 1.0, 1.0)
    assert recording.frame_rate == 20.0
    assert recording.writer.startswith("pge ")
    assert recording.complete and recording.damage is None
    assert recording.end_time == 0.5 and recording.duration == 0.5


def test_random_access_by_index_and_time(tmp_path):
    """frame(k), frame(-1) and frame_at(t) pick the right frames; out of range raises IndexError."""
    path = tmp_path / "small.pgerec"
    record_small(path)
    recording = open_recording(path)
    assert recording.frame(7).index == 7 and recording.frame(7).time == 7 / 20
    assert recording.frame(-1).index == len(recording) - 1
    assert recording.frame_at(0.26).index == 5
    assert recording.frame_at(-1.0).index == 0
    with pytest.raises(IndexError):
        recording.frame(len(recording))


def test_file_is_readable_while_being_written(tmp_path):
    """A reader opening a file mid-run sees the frames written so far and calls it incomplete."""
    world = bouncing_scene()
    path = tmp_path / "growing.pgerec"
    recorder = Recorder(world, path, frame_rate=10)
    world.run_until(0.35)
    recording = open_recording(path)
    assert len(recording) == 4 and not recording.complete and recording.damage is None
    assert recording.frame(3).time == 0.3
    world.run_until(0.5)
    recorder.close()
    assert len(open_recording(path)) == 6


def test_newer_major_version_is_refused_with_its_number(tmp_path):
    """A file claiming format 2.0 is refused by name, not misread."""
    path = tmp_path / "future.pgerec"
    path.write_bytes(F.PRELUDE.pack(F.MAGIC, 2, 0) + F.record_bytes(b"\x80"))
    with pytest.raises(UnsupportedVersion, match="format version 2.0"):
        open_recording(path)


def test_writer_stores_doubles_at_full_precision(tmp_path):
    """Values with all 53 mantissa bits (and extremes) survive the column encoding unchanged."""
    values = np.array([[0.1, 1 / 3], [np.nextafter(1.0, 2.0), 5e-324], [-1e300, np.pi]])
    path = tmp_path / "precise.pgerec"
    with RecordingWriter(path, (0, 0, 1, 1), [(0, 0, 0)]) as writer:
        writer.write_frame(0.1, ([7, 8, 9], values, [1e-17, 2 / 3, 1e9], [0, 0, 0]))
        writer.close(0.1)
    frame = open_recording(path).frame(0)
    assert frame.circles.centres.tobytes() == values.tobytes()
    assert frame.circles.radii.tolist() == [1e-17, 2 / 3, 1e9]
    assert frame.circles.ids.tolist() == [7, 8, 9]
