"""pge play: the player's state machine, headless walks, the window loop, a drawn frame's pixels, errors."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
from recording_helpers import falling_scene, raw_batch_file, record_small

from pge.cli import main
from pge.playback.control import MAX_SPEED, MIN_SPEED, PlayerState, press, start, tick
from pge.playback.history import EventHistory, event_lines
from pge.playback.player import default_size, play
from pge.playback.screen import PANEL, STRIP, fit, status_line
from pge.recording import Recorder, open_recording
from pge.render.protocol import NullDisplay

TIMES = np.arange(0, 31) * 0.1  # 31 frames, 0 .. 3 s, last index 30


@pytest.fixture(scope="module")
def bouncing(tmp_path_factory):
    """A recording with collisions: the bouncing scene, 0.5 s at 20 fps (11 frames)."""
    path = tmp_path_factory.mktemp("play") / "bouncing.pgerec"
    record_small(path, until=0.5, frame_rate=20)
    return path


@pytest.fixture(scope="module")
def falling(tmp_path_factory):
    """A recording without events: five discs and a triangle in flight, 0.3 s at 10 fps (4 frames)."""
    path = tmp_path_factory.mktemp("play") / "falling.pgerec"
    world, _ = falling_scene()
    for body, colour in zip(
        world.bodies, [(250, 20, 20), (20, 250, 20), (20, 20, 250), (250, 250, 20), (20, 250, 250)]
    ):
        body.data = {"colour": colour}
    with Recorder(world, path, frame_rate=10):
        world.run_until(0.3)
    return path


# ------------------------------------------------------------ state machine


def test_start_at_a_time_picks_the_frame_shown_then():
    """start() begins at the last frame at or before the start time, clamped to the recording."""
    assert start(TIMES).index == 0 and not start(TIMES).paused
    assert start(TIMES, 1.25).index == 12 and start(TIMES, 1.25).time == TIMES[12]
    assert start(TIMES, -5.0).index == 0
    assert start(TIMES, 99.0).index == 30


def test_start_refuses_empty_recordings_and_speeds_out_of_range():
    """No frames, or a speed outside MIN_SPEED..MAX_SPEED, is a ValueError naming the problem."""
    with pytest.raises(ValueError, match="no frames"):
        start(np.zeros(0))
    with pytest.raises(ValueError, match="speed must be between"):
        start(TIMES, speed=MAX_SPEED * 2)
    with pytest.raises(ValueError, match="speed must be between"):
        start(TIMES, speed=MIN_SPEED / 2)


def test_space_pauses_and_resumes_and_restarts_at_the_end():
    """Space toggles pause; at the last frame it plays again from frame 0."""
    playing = start(TIMES, 0.55)
    paused = press(playing, "space", TIMES)
    assert paused.paused and paused.index == playing.index
    resumed = press(paused, "space", TIMES)
    assert not resumed.paused and resumed.index == 5 and resumed.time == TIMES[5]
    at_end = press(playing, "end", TIMES)
    assert at_end.paused and at_end.index == 30
    again = press(at_end, "space", TIMES)
    assert not again.paused and again.index == 0 and again.time == 0.0


def test_steps_move_one_frame_pause_and_stop_at_the_ends():
    """Right/left step one frame (pausing playback) and stay put at the first and last frame."""
    state = press(start(TIMES, 1.0), "right", TIMES)
    assert state.paused and state.index == 11 and state.time == TIMES[11]
    state = press(press(state, "left", TIMES), "left", TIMES)
    assert state.index == 9 and state.paused
    first = press(start(TIMES), "left", TIMES)
    assert first.index == 0 and first.time == 0.0
    last = press(press(start(TIMES), "end", TIMES), "right", TIMES)
    assert last.index == 30 and last.time == TIMES[30]


def test_seeks_move_by_10_and_100_frames_clamped():
    """Up/down seek 10 frames, page keys 100, home/end to the ends; never outside the recording."""
    state = start(TIMES, 1.0)
    assert press(state, "up", TIMES).index == 20
    assert press(state, "down", TIMES).index == 0
    assert press(press(state, "up", TIMES), "up", TIMES).index == 30  # 30 is the last frame
    assert press(press(state, "up", TIMES), "down", TIMES).index == 10
    assert press(state, "page up", TIMES).index == 30 and press(state, "page down", TIMES).index == 0
    assert press(state, "home", TIMES).index == 0
    assert not press(state, "up", TIMES).paused  # seeking keeps playing
    seeked = press(press(state, "space", TIMES), "up", TIMES)
    assert seeked.paused and seeked.time == TIMES[20]


def test_speed_doubles_and_halves_within_limits():
    """+ doubles and - halves the speed, stopping at MAX_SPEED and MIN_SPEED; other keys change nothing."""
    state = start(TIMES)
    assert press(state, "+", TIMES).speed == 2.0 and press(state, "[+]", TIMES).speed == 2.0
    assert press(state, "-", TIMES).speed == 0.5 and press(state, "[-]", TIMES).speed == 0.5
    fast = state
    for _ in range(20):
        fast = press(fast, "=", TIMES)
    assert fast.speed == MAX_SPEED
    slow = state
    for _ in range(20):
        slow = press(slow, "-", TIMES)
    assert slow.speed == MIN_SPEED
    assert press(state, "x", TIMES) == state and press(state, "escape", TIMES).quit and press(state, "q", TIMES).quit


def test_tick_advances_the_clock_by_wall_time_times_speed_and_pauses_at_the_end():
    """Playing, 0.25 wall seconds at speed 2 move the clock 0.5 s; paused, nothing moves; the end pauses."""
    state = tick(start(TIMES, 1.0, speed=2.0), 0.25, TIMES)
    assert abs(state.time - 1.5) < 1e-12 and state.index == 15
    assert tick(replace(state, paused=True), 10.0, TIMES) == replace(state, paused=True)
    slow = tick(start(TIMES, 1.0, speed=0.5), 0.15, TIMES)
    assert slow.index == 10 and abs(slow.time - 1.075) < 1e-12  # between frames: the earlier one shows
    done = tick(state, 100.0, TIMES)
    assert done.paused and done.index == 30 and done.time == TIMES[30]


# ------------------------------------------------------------ screen and events


def test_fit_centres_the_bounds_at_one_scale():
    """A 2:1 world in a square window fills its width and is centred vertically."""
    view = fit((0.0, 0.0, 2.0, 1.0), (400, 400))
    assert view.k == 0.5 and view.ox == 0.0 and view.oy == 0.25 and view.pixel == 1 / 400
    wide = fit((0.0, 0.0, 1.0, 1.0), (600, 300))
    assert wide.width == 2.0 and wide.k == 1.0 and wide.ox == 0.5


def test_fit_keeps_the_event_panel_and_status_strip_off_the_scene():
    """With a panel and a strip the scene fits in what is left: left of the panel, above the strip."""
    view = fit((0.0, 0.0, 1.0, 1.0), default_size((0.0, 0.0, 1.0, 1.0)), PANEL, STRIP)
    scene_right = view.ox + view.k
    assert abs(view.panel_x - scene_right) < 1e-12 and abs(view.oy - STRIP * view.pixel) < 1e-12
    assert abs(view.k / view.pixel - 800) < 1e-9  # the scene keeps its 800 pixels
    small = fit((0.0, 0.0, 1.0, 1.0), (300, 300), PANEL, STRIP)
    assert small.panel_x == small.width  # too narrow for a panel: the scene keeps the room


def test_event_list_shows_the_latest_collisions_with_time_and_ids(bouncing):
    """The event list at a frame holds the last collisions up to that frame, newest last, with times and ids."""
    recording = open_recording(bouncing)
    every = [line for frame in recording.frames() for line in event_lines(frame)]
    assert len(every) == recording.event_counts["collisions"] > 3
    history = EventHistory(recording)
    last = len(recording) - 1
    assert history.recent(last, 3) == every[-3:]
    frame = next(f for f in recording.frames() if len(f.collisions.times))
    a, b, t = int(frame.collisions.a[0]), int(frame.collisions.b[0]), float(frame.collisions.times[0])
    assert history.recent(frame.index, 100)[-len(event_lines(frame)) :] == list(event_lines(frame))
    assert f"{t:.4f} s  collision {a}-{b}" in event_lines(frame)


def test_status_line_names_frame_time_and_speed(bouncing):
    """The status line shows frame/last, the frame's time, the speed and whether playback is paused."""
    recording = open_recording(bouncing)
    line = status_line(recording, PlayerState(index=4, time=0.2, paused=True, speed=0.25))
    assert line.startswith("frame 4/10  t 0.2000 s / 0.5 s  speed 1/4x  paused")
    assert status_line(recording, PlayerState(index=10, time=0.5, paused=True)).endswith("end (space: again)")


# ------------------------------------------------------------ playing


class CountingDisplay(NullDisplay):
    """A null display that counts frames and keeps the text of the last one."""

    def __init__(self):
        self.frames = 0
        self.texts = []

    def begin_frame(self, background):
        self.frames += 1
        self.texts = []

    def text(self, x, y, s, colour, size):
        self.texts.append(s)


def test_headless_play_walks_every_frame_through_the_drawing_code(bouncing):
    """Headless play draws each frame once, from --start to the end, and counts its events."""
    recording = open_recording(bouncing)
    display = CountingDisplay()
    summary = play(recording, headless=True, display=display)
    assert display.frames == summary.frames == len(recording) == 11
    assert summary.collisions == sum(len(f.collisions.times) for f in recording.frames()) > 0
    assert display.texts[-1].startswith("frame 10/10")
    later = play(recording, headless=True, display=CountingDisplay(), start_time=0.3)
    assert later.frames == 5 and later.first == 6


def test_pge_play_headless_prints_a_summary(bouncing, monkeypatch, capsys):
    """pge play with PGE_HEADLESS=1 opens no window, waits for nothing and prints one summary line."""
    monkeypatch.setenv("PGE_HEADLESS", "1")
    assert main(["play", str(bouncing), "--speed", "0.125"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("pge play: 11 frames shown (0 s to 0.5 s)") and "headless" in out
    monkeypatch.delenv("PGE_HEADLESS")
    assert main(["play", "--headless", "--start", "0.25", str(bouncing)]) == 0
    assert capsys.readouterr().out.startswith("pge play: 6 frames shown (0.25 s to 0.5 s)")


def test_headless_play_reads_an_original_output_raw(tmp_path, capsys):
    """A hand-written output.raw plays headless: its 4 frames are walked."""
    path = tmp_path / "output.raw"
    path.write_bytes(raw_batch_file(3))
    assert main(["play", "--headless", str(path)]) == 0
    assert capsys.readouterr().out.startswith("pge play: 4 frames shown")


class ScriptedDisplay(CountingDisplay):
    """Feeds one batch of key names per look at the input; draws nothing."""

    def __init__(self, batches, clock=None):
        super().__init__()
        self.batches = list(batches)
        self.clock = clock
        self.shown = []
        self.when = []

    def events(self):
        return self.batches.pop(0) if self.batches else []

    def key_name(self, event):
        return None if event == "QUIT" else event

    def is_quit(self, event):
        return event == "QUIT"

    def end_frame(self):
        self.shown.append(self.texts[-1].split()[1])  # "frame 3/10 ..." -> "3/10"
        self.when.append(self.clock() if self.clock else None)


def _fake_time():
    now = [0.0]

    def sleep(seconds):
        assert 0.0 <= seconds <= 0.01 + 1e-12  # never waits longer than the poll interval
        now[0] += max(seconds, 0.001)

    return (lambda: now[0]), sleep


def test_window_loop_plays_in_real_time_then_pauses_at_the_end(bouncing):
    """On a fake clock the loop shows each frame of a 20 fps recording within 10 ms of its time, pauses
    at the end, and quits on q."""
    recording = open_recording(bouncing)
    clock, sleep = _fake_time()
    display = ScriptedDisplay([[]] * 200 + [["q"]], clock)
    summary = play(recording, display=display, clock=clock, sleep=sleep)
    assert display.shown == [f"{k}/10" for k in range(len(recording))]
    for k in range(len(recording)):
        assert recording.times[k] <= display.when[k] < recording.times[k] + 0.011
    assert display.texts[-1].endswith("end (space: again)")
    assert summary.last == 10 and summary.frames == 11 and not summary.headless


def test_window_loop_applies_keys(bouncing):
    """Keys reach the state machine: pause, two steps forward, one back, home, then the window is closed."""
    recording = open_recording(bouncing)
    clock, sleep = _fake_time()
    display = ScriptedDisplay([["space"], ["right"], ["right"], ["left"], ["end"], ["home", "+"], ["QUIT"]])
    play(recording, display=display, clock=clock, sleep=sleep)
    assert display.shown == ["0/10", "1/10", "2/10", "1/10", "10/10", "0/10"]
    assert "speed 2x  paused" in display.texts[-1]
    assert clock() < 0.1  # closing the window ended the loop at once


def test_window_loop_reads_real_pygame_keys(bouncing, monkeypatch):
    """In a dummy-driver window, a posted right-arrow key steps to frame 1 and a q ends playback."""
    monkeypatch.setenv("SDL_VIDEODRIVER", "dummy")
    import pygame

    from pge.render.pygame_display import PygameDisplay

    display = PygameDisplay((200, 200))
    try:
        pygame.event.post(pygame.event.Event(pygame.KEYDOWN, key=pygame.K_RIGHT))
        quit_key = pygame.event.Event(pygame.KEYDOWN, key=pygame.K_q)
        summary = play(open_recording(bouncing), display=display, sleep=lambda s: pygame.event.post(quit_key))
    finally:
        display.close()
    assert (summary.frames, summary.first, summary.last) == (1, 0, 1)


# ------------------------------------------------------------ pixels


def test_drawn_frame_has_each_disc_colour_at_its_position(falling, monkeypatch):
    """Under SDL's dummy driver the last frame drawn shows each disc's colour at its centre's pixel."""
    monkeypatch.setenv("SDL_VIDEODRIVER", "dummy")
    from pge.render.pygame_display import PygameDisplay

    recording = open_recording(falling)
    display = PygameDisplay((300, 300))
    try:
        play(recording, headless=True, display=display)
        frame = recording.frame(len(recording) - 1)
        view = fit(recording.bounds, (300, 300), PANEL, STRIP)
        assert len(frame.circles.ids) == 5
        for (x, y), colour in zip(frame.circles.centres.tolist(), frame.circles.colours.tolist()):
            px, py = display.to_pixels(view.ox + (x - view.x0) * view.k, view.oy + (y - view.y0) * view.k)
            assert display.pixel(round(px), round(py)) == recording.colour(colour)
        assert display.pixel(150, 20) == recording.colour(recording.background)
    finally:
        display.close()


# ------------------------------------------------------------ errors


def _one_line_error(capsys, code, expected_code, *fragments):
    err = capsys.readouterr().err
    lines = err.strip().splitlines()
    assert code == expected_code
    assert len(lines) == 1 and lines[0].startswith("pge: error: "), err
    for fragment in fragments:
        assert fragment in lines[0]
    assert "Traceback" not in err


def test_play_errors_are_one_line(bouncing, tmp_path, capsys):
    """Missing file, not a recording, a corrupt recording and bad speeds give one line and a non-zero exit."""
    _one_line_error(capsys, main(["play", "--headless", str(tmp_path / "nope.pgerec")]), 1, "nope.pgerec: no such file")
    text = tmp_path / "notes.txt"
    text.write_text("hello\n")
    _one_line_error(capsys, main(["play", "--headless", str(text)]), 1, "not a recording")
    data = bytearray(bouncing.read_bytes())
    data[len(data) // 2] ^= 0xFF
    corrupt = tmp_path / "corrupt.pgerec"
    corrupt.write_bytes(bytes(data))
    _one_line_error(capsys, main(["play", "--headless", str(corrupt)]), 1, "corrupt", "frame")
    _one_line_error(capsys, main(["play", "--headless", "--speed", "0", str(bouncing)]), 2, "--speed")
    _one_line_error(capsys, main(["play", "--headless", "--speed", "1000", str(bouncing)]), 1, "speed must be between")
    _one_line_error(capsys, main(["play", "--headless", "--size", "0x5", str(bouncing)]), 2, "--size")


def test_play_without_a_video_driver_says_to_use_headless(bouncing, monkeypatch, capsys):
    """With no usable video driver, pge play fails in one line that points at --headless."""
    monkeypatch.setenv("SDL_VIDEODRIVER", "no-such-driver")
    monkeypatch.delenv("PGE_HEADLESS", raising=False)
    _one_line_error(capsys, main(["play", str(bouncing)]), 1, "cannot open a window", "--headless")
