"""Callbacks, events and timers of the classic API: argument orders, shared lists, rm mid-run, frames."""

from __future__ import annotations

import math

import pytest
from classic_support import session, walls  # noqa: F401 (session: the fixture every test uses)

import pge

pytestmark = pytest.mark.usefixtures("session")


def test_collision_callback_gets_object_then_event():
    """on_collision calls p(obj, event): the object first, then an event describing the collision."""
    floor = walls()[0]
    calls = []
    ball = pge.circle(0.5, 0.3, 0.05, pge.white()).mass(1).velocity(0.0, -1.0)
    ball.on_collision(lambda *args: calls.append(args))
    pge.run(0.3)
    obj, happened = calls[0]
    assert obj is ball and isinstance(happened, pge.event)
    assert happened.type == pge.collision_event
    assert happened.collision_between() == [floor, ball]  # a polygon before a circle
    assert happened.get_timer_id() is None
    assert abs(happened.get_time() - 0.24) < 1e-12
    x, y = happened.get_point()
    assert abs(x - 0.5) < 1e-12 and abs(y - 0.01) < 1e-12


def test_both_callbacks_run_in_collision_between_order_with_one_event():
    """At a collision the polygon's callback runs before the circle's, with the same event object."""
    order = []
    crate = pge.box(0.4, 0.1, 0.2, 0.1, pge.white()).fix()
    ball = pge.circle(0.5, 0.5, 0.05, pge.white()).mass(1).velocity(0.0, -1.0)
    ball.on_collision(lambda o, e: order.append(("ball", o, e)))  # registered first
    crate.on_collision(lambda o, e: order.append(("crate", o, e)))
    pge.run(0.3)
    assert [name for name, _, _ in order[:2]] == ["crate", "ball"]
    assert order[0][1] is crate and order[1][1] is ball
    assert order[0][2] is order[1][2]


def test_circle_pair_callbacks_name_both_circles():
    """Two moving circles colliding: each callback gets itself and the same two-circle pair."""
    a = pge.circle(0.3, 0.5, 0.05, pge.white()).mass(1).velocity(1.0, 0.0)
    b = pge.circle(0.7, 0.5, 0.05, pge.white()).mass(1).velocity(-1.0, 0.0)
    seen = []
    a.on_collision(lambda o, e: seen.append((o, set(e.collision_between()))))
    b.on_collision(lambda o, e: seen.append((o, set(e.collision_between()))))
    pge.run(0.2)
    assert [o for o, _ in seen] == [a, b]
    assert seen[0][1] == seen[1][1] == {a, b}


def test_on_collision_with_sees_objects_appended_to_the_shared_list():
    """on_collision_with keeps the list by reference: objects appended later count, others never do."""
    pge.elasticity(1.0)
    floor, ceiling, left, right = walls()
    targets = [left]
    hits = []
    ball = pge.circle(0.5, 0.5, 0.05, pge.white()).mass(1).velocity(1.0, 0.0)
    ball.on_collision_with(targets, lambda o, e: hits.append(next(x for x in e.collision_between() if x is not o)))
    other = pge.circle(0.5, 0.2, 0.05, pge.white()).mass(1).velocity(1.0, 0.0)
    other.on_collision_with(targets, lambda o, e: hits.append("other"))
    pge.run(0.5)  # the ball hits the right wall (0.44) only: not a target yet
    assert hits == []
    targets.append(right)
    pge.run(1.5)  # left wall at ~1.32, right wall at ~2.2
    assert hits[:2] == ["other", left] or hits[:2] == [left, "other"]
    pge.run(1.0)
    assert right in hits and floor not in hits and ceiling not in hits


def test_empty_list_means_every_collision():
    """on_collision_with([], p) fires on every collision of the object, like on_collision."""
    pge.elasticity(1.0)
    walls()
    count = []
    pge.circle(0.5, 0.5, 0.05, pge.white()).mass(1).velocity(1.0, 0.7).on_collision_with(
        [], lambda o, e: count.append(1)
    )
    pge.run(2.0)
    assert len(count) >= 4


def test_rm_in_a_callback_mid_run():
    """A brick that rm()s itself in its callback never collides again; the ball still gets that collision."""
    pge.elasticity(1.0)
    walls()
    brick_hits, ball_hits = [], []
    brick = pge.box(0.45, 0.8, 0.1, 0.05, pge.white()).fix()
    brick.on_collision(lambda o, e: (brick_hits.append(e.get_time()), o.rm()))
    ball = pge.circle(0.5, 0.3, 0.04, pge.white()).mass(1).velocity(0.0, 1.0)
    ball.on_collision(lambda o, e: ball_hits.append(e.collision_between()))
    pge.run(3.0)
    assert len(brick_hits) == 1 and brick.deleted
    assert ball_hits[0][0] is brick  # the ball's callback ran for the same collision
    assert all(brick not in pair for pair in ball_hits[1:])
    assert len(ball_hits) >= 3  # it went on bouncing between floor and ceiling
    with pytest.raises(ValueError, match="deleted"):
        brick.get_xpos()


def test_at_time_calls_event_then_none():
    """at_time(t, p) calls p(event, None) t / slow_down simulated seconds later, with its timer id."""
    pge.slow_down(4.0)
    calls = []
    timer_id = pge.at_time(2.0, lambda *args: calls.append((pge.get_time(), args)))
    assert isinstance(timer_id, int)
    pge.run(1.0)
    when, (happened, nothing) = calls[0]
    assert nothing is None and happened.type == pge.function_event
    assert happened.get_timer_id() == timer_id
    assert when == happened.get_time() == 0.5
    assert happened.get_point() is None
    with pytest.raises(TypeError, match="not a collision"):
        happened.collision_between()


def test_timer_ids_count_up_and_at_cancel_stops_a_timer():
    """Timer ids are 1, 2, 3...; a cancelled timer never fires; cancelling a fired one does nothing."""
    fired = []
    ids = [pge.at_time(0.1 * k, lambda e, o: fired.append(e.get_timer_id())) for k in (1, 2, 3)]
    assert ids == [1, 2, 3]
    pge.at_cancel(ids[1])
    pge.run(0.5)
    assert fired == [1, 3]
    pge.at_cancel(ids[0])  # already fired: nothing happens
    with pytest.raises(ValueError, match="no timer has id 99"):
        pge.at_cancel(99)


def test_event_cancel_is_a_flag():
    """cancel() sets was_cancelled(); nothing else changes."""
    flags = []

    def timer(e, o):
        flags.append(e.was_cancelled())
        e.cancel()
        flags.append(e.was_cancelled())

    pge.at_time(0.0, timer)
    pge.run(0.1)
    assert flags == [False, True]


def test_periodic_timer_rearms_itself():
    """A timer that re-arms in its callback fires once per period."""
    times = []

    def tick(e, o):
        times.append(e.get_time())
        pge.at_time(0.25, tick)

    pge.at_time(0.25, tick)
    pge.run(1.1)
    assert times == [0.25, 0.5, 0.75, 1.0]


def test_objects_made_in_a_callback_join_when_it_returns():
    """A ball created (and given its mass) inside a timer callback falls and hits the floor."""
    pge.gravity()
    walls()
    hits = []

    def drop(e, o):
        ball = pge.circle(0.5, 0.5, 0.05, pge.white())
        ball.mass(1).on_collision(lambda obj, ev: hits.append(pge.get_time()))

    pge.at_time(0.2, drop)
    pge.run(0.8)
    assert abs(hits[0] - (0.2 + math.sqrt(2 * 0.44 / 9.81))) < 1e-12


def test_get_time_in_callbacks_is_the_event_time():
    """Inside a collision callback pge.get_time() equals the event's time; outside, the run's end."""
    walls()
    times = []
    ball = pge.circle(0.5, 0.5, 0.05, pge.white()).mass(1).velocity(0.7, 0.0)
    ball.on_collision(lambda o, e: times.append((pge.get_time(), e.get_time())))
    pge.run(1.0)
    assert times and all(a == b for a, b in times)
    assert pge.get_time() == 1.0


def test_frames_count_at_the_frame_rate():
    """get_frame_no counts 100 frames per simulated second by default and follows fps()."""
    pge.run(1.0)
    assert pge.get_frame_no() == 100
    pge.fps(50)
    pge.run(1.0)
    assert pge.get_frame_no() == 150


def test_draw_collision_adds_a_frame_per_collision():
    """With draw_collision(True, False) every collision adds one frame."""
    pge.elasticity(1.0)
    walls()
    hits = []
    pge.circle(0.5, 0.5, 0.05, pge.white()).mass(1).velocity(0.9, 0.4).on_collision(lambda o, e: hits.append(1))
    pge.draw_collision(True, False)
    pge.collision_colour(pge.rgb(0, 1, 0))
    pge.run(1.0)
    assert hits and pge.get_frame_no() == 100 + len(hits)


def test_input_handlers_never_fire_headless(monkeypatch):
    """Headless, a queued key press never reaches its handler; deregister_handler works."""
    import pygame

    monkeypatch.setenv("SDL_VIDEODRIVER", "dummy")
    pygame.display.init()
    try:
        calls = []
        pge.register_handler(lambda e: calls.append(e), [pygame.KEYDOWN, pygame.QUIT])
        pygame.event.post(pygame.event.Event(pygame.KEYDOWN, key=pygame.K_a))
        pge.run(0.2)
        assert calls == []
        assert [e.key for e in pygame.event.get(pygame.KEYDOWN)] == [pygame.K_a]
    finally:
        pygame.display.quit()
    pge.deregister_handler([pygame.KEYDOWN])
    with pytest.raises(ValueError, match="no handler"):
        pge.deregister_handler([pygame.KEYDOWN])


def test_local_fps_shows_a_text_every_second():
    """local_fps() re-arms a one-second timer that replaces an 'fps N' text in level 1."""
    pge.local_fps()
    pge.run(2.5)
    texts = [o for o in pge.classic._STATE.levels[1] if o.type == pge.fb_text_t]
    assert len(texts) == 1 and texts[0]._text[2] == "fps 100"


def test_run_continues_where_it_stopped():
    """Two runs of 0.3 s give the same state as one of 0.6 s."""
    pge.gravity()
    walls()
    ball = pge.circle(0.3, 0.7, 0.05, pge.white()).mass(1).velocity(0.4, 0.0)
    pge.run(0.3)
    pge.run(0.3)
    twice = (ball.get_xpos(), ball.get_ypos(), ball.get_xvel(), ball.get_yvel())
    pge.classic.reset()
    pge.gravity()
    walls()
    ball = pge.circle(0.3, 0.7, 0.05, pge.white()).mass(1).velocity(0.4, 0.0)
    pge.run(0.6)
    assert twice == (ball.get_xpos(), ball.get_ypos(), ball.get_xvel(), ball.get_yvel())


def test_negative_run_time_headless_runs_thirty_seconds():
    """Headless, run() and runbatch(-1) run 30 simulated seconds (the original runbatch's default)."""
    pge.run()
    assert pge.get_time() == 30.0
    pge.runbatch(-1)
    assert pge.get_time() == 60.0


def test_headless_ignores_delay_sound_and_messages(tmp_path, monkeypatch):
    """Headless, delay() does not pause, play() and message() do nothing and write nothing."""
    import time

    monkeypatch.chdir(tmp_path)
    pge.delay(5.0)
    pge.play("no-such-sound.wav")
    pge.message("hello")
    start = time.perf_counter()
    pge.run(0.1)
    assert time.perf_counter() - start < 2.0
    assert list(tmp_path.iterdir()) == []
    with pytest.raises(ValueError, match="delay: t must not be negative"):
        pge.delay(-1.0)
