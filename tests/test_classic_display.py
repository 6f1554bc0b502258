"""The pygame window (SDL dummy driver): frames saved to PNG show the right shapes at the right pixels."""

from __future__ import annotations

import time

import pytest
from PIL import Image

import pge
from pge.classic import reset


@pytest.fixture
def window(monkeypatch):
    """A fresh session that opens a real pygame window on SDL's dummy video driver."""
    monkeypatch.setenv("SDL_VIDEODRIVER", "dummy")
    monkeypatch.delenv("PGE_HEADLESS", raising=False)
    reset()
    pge.interactive()
    yield pge
    reset()


RED, BLUE, GREEN, YELLOW, WHITE, MAGENTA = (
    (255, 0, 0),
    (0, 0, 255),
    (0, 255, 0),
    (255, 255, 0),
    (255, 255, 255),
    (255, 0, 255),
)


def colour(c):
    return pge.rgb(*(v / 255 for v in c))


def pixels(path):
    return Image.open(path).convert("RGB").load()


def test_frame_shows_levels_in_order_at_the_right_pixels(window, tmp_path):
    """Shapes land on the pixels the unit square maps to, levels stack in order, motion is sampled at the frame."""
    pge.display_set_mode([300, 200])
    pge.circle(0.25, 0.5, 0.1, colour(RED)).fix()  # centre (50, 100), radius 20 px
    pge.box(0.6, 0.1, 0.2, 0.2, colour(BLUE)).fix()  # x 120..160, rows 140..180
    pge.circle(1.25, 0.5, 0.2, colour(GREEN), -1)  # background, beyond x = 1: centre (250, 100)
    pge.circle(1.25, 0.5, 0.05, colour(WHITE)).fix()  # physics on top of the background
    pge.box(0.2, 0.45, 0.1, 0.1, colour(YELLOW), 1)  # foreground over the red circle's centre
    pge.circle(0.2, 0.2, 0.03, colour(MAGENTA)).mass(1).velocity(0.4, 0.0)  # at (0.4, 0.2) when t = 0.5
    pge.text(0.05, 0.97, "pge", colour(WHITE), 30, 2)
    pge.run(0.5)
    path = tmp_path / "frame.png"
    pge.classic.save_frame(path)
    image = Image.open(path)
    assert image.size == (300, 200)
    p = pixels(path)
    assert p[50, 100] == YELLOW  # foreground above physics
    assert p[50, 85] == RED and p[50, 116] == RED and p[34, 100] == RED
    assert p[50, 78] == (0, 0, 0) and p[72, 100] == (0, 0, 0)  # just outside the red circle
    assert p[140, 160] == BLUE and p[121, 141] == BLUE and p[159, 179] == BLUE
    assert p[118, 160] == (0, 0, 0) and p[140, 138] == (0, 0, 0)
    assert p[250, 100] == WHITE  # physics above background
    assert p[250, 75] == GREEN and p[285, 100] == GREEN
    assert p[80, 160] == MAGENTA and p[40, 160] == (0, 0, 0)  # sampled at t = 0.5, not at t = 0
    text_area = [p[x, y] for x in range(10, 60) for y in range(6, 30)]
    assert any(c[0] > 200 and c[1] > 200 and c[2] > 200 for c in text_area)


def test_alpha_and_visibility(window, tmp_path):
    """set_alpha(0.5) blends with the background; set_visible(False) hides an object."""
    pge.display_set_mode([200, 200])
    pge.circle(0.25, 0.5, 0.1, colour(RED)).fix().set_alpha(0.5)
    pge.box(0.6, 0.4, 0.2, 0.2, colour(BLUE)).fix().set_visible(False)
    pge.run(0.02)
    pge.classic.save_frame(tmp_path / "alpha.png")
    p = pixels(tmp_path / "alpha.png")
    r, g, b = p[50, 100]
    assert 120 <= r <= 135 and g == 0 and b == 0
    assert p[140, 100] == (0, 0, 0)


def test_collision_frame_draws_the_pair_in_the_collision_colour(window, tmp_path):
    """With draw_collision(True, False) the frame at the collision shows both objects in collision_colour."""
    pge.display_set_mode([200, 200])
    pge.box(0.0, 0.0, 1.0, 0.1, colour(BLUE)).fix()
    saved = []

    def hit(ball, event):
        if not saved:
            pge.classic.save_frame(tmp_path / "hit.png")
            saved.append(event.get_time())

    pge.circle(0.5, 0.3, 0.05, colour(RED)).mass(1).velocity(0.0, -1.0).on_collision(hit)
    pge.draw_collision(True, False)
    pge.collision_colour(colour(GREEN))
    pge.run(0.2)
    assert saved and abs(saved[0] - 0.15) < 1e-12
    p = pixels(tmp_path / "hit.png")
    assert p[100, 170] == GREEN and p[100, 162] == GREEN  # the ball (centre y 0.15) at the collision time
    assert p[20, 190] == GREEN  # the floor


def test_frames_are_paced_by_slow_down(window):
    """In a window, 0.2 simulated seconds at slow_down(2) take at least 0.4 s of wall-clock time."""
    pge.display_set_mode([100, 100])
    pge.slow_down(2.0)
    start = time.perf_counter()
    pge.run(0.2)
    assert time.perf_counter() - start >= 0.38
    assert pge.get_frame_no() == 20


def test_keyboard_handler_fires_between_events_and_quit_ends(window):
    """A posted KEYDOWN reaches its handler during the run; an unhandled QUIT ends the program."""
    import pygame

    pge.display_set_mode([100, 100])
    keys = []
    pge.register_handler(lambda e: keys.append((e.key, pge.get_time())), [pygame.KEYDOWN])
    pge.run(0.01)
    pygame.event.post(pygame.event.Event(pygame.KEYDOWN, key=pygame.K_SPACE))
    pge.run(0.05)
    assert [k for k, _ in keys] == [pygame.K_SPACE] and 0.01 < keys[0][1] <= 0.06
    pygame.event.post(pygame.event.Event(pygame.QUIT))
    with pytest.raises(SystemExit):
        pge.run(0.05)


def test_fullscreen_window(window):
    """display_fullscreen(True) opens the window with pygame's FULLSCREEN flag."""
    import pygame

    pge.display_set_mode([320, 240])
    pge.display_fullscreen(True)
    pge.run(0.01)
    assert pygame.display.get_surface().get_flags() & pygame.FULLSCREEN


def test_no_window_available_names_the_way_out(monkeypatch):
    """Without a usable video driver, run() says so and points at PGE_HEADLESS (no crash deep in pygame)."""
    monkeypatch.setenv("SDL_VIDEODRIVER", "no-such-driver")
    monkeypatch.delenv("PGE_HEADLESS", raising=False)
    reset()
    try:
        pge.circle(0.5, 0.5, 0.1, pge.white()).fix()
        with pytest.raises(RuntimeError, match="cannot open a window .*PGE_HEADLESS=1"):
            pge.run(0.1)
    finally:
        reset()


def test_delay_pauses_the_window(window):
    """delay(t) holds the next frame back t wall-clock seconds."""
    pge.display_set_mode([100, 100])
    pge.run(0.01)
    pge.delay(0.3)
    start = time.perf_counter()
    pge.run(0.02)
    assert time.perf_counter() - start >= 0.3


def test_fonts_and_sounds(window, tmp_path, monkeypatch):
    """get_font caches pygame fonts; play() plays a WAV and raises OSError for a missing file."""
    import math as m
    import struct
    import wave

    monkeypatch.setenv("SDL_AUDIODRIVER", "dummy")
    font = pge.get_font(24)
    assert font is pge.get_font(24) and font.get_height() > 10
    pge.display_set_mode([100, 100])
    pge.run(0.01)
    sound = tmp_path / "beep.wav"
    with wave.open(str(sound), "wb") as out:
        out.setnchannels(1)
        out.setsampwidth(2)
        out.setframerate(22050)
        out.writeframes(b"".join(struct.pack("<h", int(8000 * m.sin(k / 10))) for k in range(2205)))
    pge.play(str(sound))
    with pytest.raises(OSError, match="cannot load sound file"):
        pge.play(str(tmp_path / "missing.wav"))
