"""Behaviour of each World method, checked on small hand-built scenes with analytic answers.

The walls of ``walled()`` have their inner faces on the unit square, so a circle of radius
r at x moving right at speed v touches the right wall at t = (1 - r - x) / v.
"""

from __future__ import annotations

import math

import pytest
from strategies import build_scene, closed_box, random_scene

from pge import Collision, Frame, Stop, Timer, World

EXACT = 1e-12


def walled(**options) -> World:
    """A World (elasticity 1 unless given) inside four fixed walls whose inner faces are the unit square."""
    options.setdefault("elasticity", 1.0)
    world = World(**options)
    closed_box(world, thickness=0.1)
    return world


def collisions_of(world: World) -> list[Collision]:
    """A list that fills with every Collision record of ``world`` (via a world-wide callback)."""
    seen: list[Collision] = []
    world.on_collision(seen.append)
    return seen


def involves(event: Collision, body) -> bool:
    return event.a is body or event.b is body


def near(a, b, tol=EXACT) -> bool:
    return all(abs(x - y) <= tol for x, y in zip(a, b))


# --------------------------------------------------------------------- add / remove


def test_remove_in_collision_callback_drops_body_and_its_pending_events():
    """A body removed in a collision callback takes part in no later collision; its predicted wall hit never happens."""
    world = walled()
    striker = world.add_circle((0.2, 0.5), 0.05, mass=1.0, velocity=(1.0, 0.0), name="striker")
    target = world.add_circle((0.5, 0.5), 0.05, mass=1.0, name="target")
    seen = collisions_of(world)

    def remove_target(event):
        if target.alive:
            world.remove(target)

    world.on_collision(remove_target, body=target)
    world.run_until(3.0)
    # the first and only collision: striker meets target at t = 0.2 and stops dead (equal masses, e = 1)
    assert len(seen) == 1
    assert abs(seen[0].time - 0.2) <= EXACT and involves(seen[0], target)
    assert not target.alive
    assert target not in world.bodies and len(world) == 5
    assert striker.velocity == (0.0, 0.0)
    assert near(striker.position, (0.4, 0.5))
    assert world.stats["collisions"] == 1


def test_remove_from_timer_drops_the_removed_bodys_predicted_collisions():
    """Bodies removed by a timer never collide: a wall hit and a hit by another body, both predicted, are dropped."""
    world = walled()
    runner = world.add_circle((0.5, 0.3), 0.05, mass=1.0, velocity=(1.0, 0.0), name="runner")  # wall at t = 0.45
    sitter = world.add_circle((0.7, 0.5), 0.05, mass=1.0, name="sitter")
    crosser = world.add_circle((0.7, 0.15), 0.05, mass=1.0, velocity=(0.0, 1.0), name="crosser")  # sitter at 0.25
    seen = collisions_of(world)

    def clear(event):
        world.remove(runner)
        world.remove(sitter)

    world.run_until(0.05)  # both predictions are now queued
    world.at_time(0.1, clear)
    world.run_until(0.75)
    assert seen == []
    assert near(crosser.position, (0.7, 0.9)) and crosser.velocity == (0.0, 1.0)
    world.run_until(1.0)
    # crosser flies on to the ceiling (centre 0.95) at t = 0.8
    assert len(seen) == 1 and involves(seen[0], crosser)
    assert abs(seen[0].time - 0.8) <= EXACT
    assert len(world) == 5


def test_add_in_collision_callback_takes_part_at_once():
    """A body added in a collision callback is predicted at once: the rebounding ball hits it at the analytic time."""
    world = walled()
    ball = world.add_circle((0.5, 0.5), 0.05, mass=1.0, velocity=(1.0, 0.0), name="ball")
    seen = collisions_of(world)
    added = []

    def add_post(event):
        if not added:
            added.append(world.add_circle((0.3, 0.5), 0.05, fixed=True, name="post"))

    world.on_collision(add_post, body=ball)
    world.run_until(1.2)
    # right wall at t = 0.45 (centre 0.95), back left at speed 1, meets the post (centre 0.4) at t = 1.0
    assert len(seen) == 2
    assert abs(seen[0].time - 0.45) <= EXACT
    assert abs(seen[1].time - 1.0) <= EXACT and involves(seen[1], added[0])
    assert ball.velocity == (1.0, 0.0)
    assert len(world) == 6 and world.bodies[-1] is added[0]


# --------------------------------------------------------------- changing motion mid-run


def _first_hit_after(world, body, start):
    seen = []
    world.on_collision(lambda event: seen.append(event), body=body)
    world.run_until(start + 5.0)
    assert seen, "the body never hit anything"
    return seen[0]


def test_set_velocity_mid_run_takes_effect_at_once_and_is_predicted():
    """set_velocity in a timer changes the velocity at that instant (position unchanged) and the wall hit is exact."""
    world = walled()
    ball = world.add_circle((0.5, 0.5), 0.05, mass=1.0, name="ball")
    state = {}

    def push(event):
        world.set_velocity(ball, (2.0, 0.0))
        state["velocity"], state["position"] = ball.velocity, ball.position

    world.at_time(0.1, push)
    hit = _first_hit_after(world, ball, 0.0)
    assert state == {"velocity": (2.0, 0.0), "position": (0.5, 0.5)}
    assert abs(hit.time - (0.1 + 0.45 / 2.0)) <= EXACT
    assert hit.a.name == "right wall" or hit.b.name == "right wall"


def test_apply_impulse_mid_run_changes_velocity_by_j_over_m():
    """apply_impulse adds J / m to the velocity at once; the redirected ball reaches the floor at the analytic time."""
    world = walled()
    ball = world.add_circle((0.5, 0.5), 0.05, mass=2.0, velocity=(0.5, 0.0), name="ball")
    state = {}

    def kick(event):
        world.apply_impulse(ball, (0.0, -2.0))
        state["velocity"] = ball.velocity

    world.at_time(0.2, kick)
    hit = _first_hit_after(world, ball, 0.0)
    assert state["velocity"] == (0.5, -1.0)
    # at t = 0.2 the ball is at y = 0.5; it falls 0.45 at speed 1
    assert abs(hit.time - 0.65) <= EXACT
    assert {hit.a.name, hit.b.name} == {"ball", "floor"}
    assert near(hit.point, (0.6 + 0.5 * 0.45, 0.0))


def test_set_acceleration_mid_run_is_predicted_with_the_parabola():
    """set_acceleration from rest: the floor is reached sqrt(2 d / a) after the change."""
    world = walled()
    ball = world.add_circle((0.5, 0.5), 0.05, mass=1.0, name="ball")
    state = {}

    def accelerate(event):
        world.set_acceleration(ball, (0.0, -2.0))
        state["own"], state["total"] = ball.acceleration, ball.total_acceleration

    world.at_time(0.1, accelerate)
    hit = _first_hit_after(world, ball, 0.0)
    assert state == {"own": (0.0, -2.0), "total": (0.0, -2.0)}
    assert abs(hit.time - (0.1 + math.sqrt(0.45))) <= EXACT


def test_set_position_mid_run_keeps_velocity_and_is_predicted():
    """set_position in a timer teleports the body (velocity kept); the next wall hit is timed from the new place."""
    world = walled()
    ball = world.add_circle((0.5, 0.5), 0.05, mass=1.0, velocity=(1.0, 0.0), name="ball")
    state = {}

    def teleport(event):
        world.set_position(ball, (0.2, 0.3))
        state["position"], state["velocity"] = ball.position, ball.velocity

    world.at_time(0.1, teleport)
    hit = _first_hit_after(world, ball, 0.0)
    assert state == {"position": (0.2, 0.3), "velocity": (1.0, 0.0)}
    assert abs(hit.time - (0.1 + 0.75)) <= EXACT
    assert near(hit.point, (1.0, 0.3))


def test_body_property_assignment_calls_the_world_setter():
    """Assigning body.velocity / position / acceleration mid-run behaves like the World.set_* calls."""
    world = walled()
    ball = world.add_circle((0.5, 0.5), 0.05, mass=1.0, name="ball")

    def change(event):
        ball.position = (0.3, 0.5)
        ball.velocity = (-1.0, 0.0)

    world.at_time(0.1, change)
    hit = _first_hit_after(world, ball, 0.0)
    assert abs(hit.time - (0.1 + 0.25)) <= EXACT
    assert {hit.a.name, hit.b.name} == {"ball", "left wall"}


def test_redirect_inside_collision_callback_overrides_the_bounce():
    """set_velocity inside a collision callback replaces the bounce velocity; the next hit follows the new one."""
    world = walled()
    ball = world.add_circle((0.5, 0.5), 0.05, mass=1.0, velocity=(1.0, 0.0), name="ball")
    seen = collisions_of(world)

    def redirect(event):
        if len(seen) == 1:
            world.set_velocity(ball, (0.0, 1.0))

    world.on_collision(redirect)
    world.run_until(1.0)
    # right wall at 0.45; then straight up from y = 0.5: ceiling at 0.45 + 0.45 = 0.9
    assert len(seen) == 2
    assert abs(seen[1].time - 0.9) <= EXACT
    assert {seen[1].a.name, seen[1].b.name} == {"ball", "ceiling"}


# ------------------------------------------------------------------------- fixed bodies


def test_set_fixed_freezes_the_body_and_unfix_restores_its_velocity():
    """set_fixed(True) stops a moving body where it is (velocity reads 0); set_fixed(False) resumes the old velocity."""
    world = walled()
    ball = world.add_circle((0.3, 0.5), 0.05, mass=1.0, velocity=(1.0, 0.0), name="ball")
    seen = collisions_of(world)
    world.run_until(0.1)
    world.set_fixed(ball, True)
    assert ball.is_fixed and ball.velocity == (0.0, 0.0) and ball.total_acceleration == (0.0, 0.0)
    frozen = ball.position
    assert near(frozen, (0.4, 0.5))
    world.run_until(0.3)
    assert ball.position == frozen
    world.set_fixed(ball, False)
    assert not ball.is_fixed and ball.velocity == (1.0, 0.0)
    world.run_until(1.0)
    # from x = 0.4 at t = 0.3: right wall (centre 0.95) at t = 0.85
    assert len(seen) == 1 and abs(seen[0].time - 0.85) <= EXACT


def test_velocity_set_while_fixed_is_kept_for_release():
    """set_velocity on a fixed body does not move it; releasing it moves it with that velocity."""
    world = walled()
    ball = world.add_circle((0.5, 0.5), 0.05, mass=1.0, fixed=True, name="ball")
    world.add_circle((0.2, 0.2), 0.05, mass=1.0, velocity=(0.0, 0.1), name="other")
    world.run_until(0.1)
    world.set_velocity(ball, (0.0, -1.0))
    assert ball.velocity == (0.0, 0.0)
    world.run_until(0.2)
    assert ball.position == (0.5, 0.5)
    world.set_fixed(ball, False)
    assert ball.velocity == (0.0, -1.0)
    hit = _first_hit_after(world, ball, 0.2)
    assert abs(hit.time - 0.65) <= EXACT


def test_fixed_body_is_an_immovable_obstacle():
    """A body fixed mid-run acts as an infinitely heavy obstacle: a ball bounces straight back and it stays put."""
    world = walled()
    post = world.add_circle((0.6, 0.5), 0.05, mass=1.0, velocity=(0.0, 0.3), name="post")
    ball = world.add_circle((0.2, 0.5), 0.05, mass=1.0, velocity=(1.0, 0.0), name="ball")
    seen = collisions_of(world)
    world.set_fixed(post, True)
    world.run_until(0.4)
    assert len(seen) == 1 and abs(seen[0].time - 0.3) <= EXACT
    assert ball.velocity == (-1.0, 0.0)
    assert post.position == (0.6, 0.5)
    world.set_fixed(post, False)
    assert post.velocity == (0.0, 0.3)


# ------------------------------------------------------------------------------ gravity


def test_gravity_change_mid_run_applies_at_once_to_moving_bodies_only():
    """Setting world.gravity in a timer accelerates every moving body from that instant; fixed bodies stay put."""
    world = walled()
    ball = world.add_circle((0.5, 0.5), 0.05, mass=1.0, name="ball")
    post = world.add_circle((0.2, 0.2), 0.05, fixed=True, name="post")
    state = {}

    def switch(event):
        world.gravity = (0.0, -9.81)
        state["total"], state["own"], state["post"] = ball.total_acceleration, ball.acceleration, post.total_acceleration

    world.at_time(0.2, switch)
    hit = _first_hit_after(world, ball, 0.0)
    assert state == {"total": (0.0, -9.81), "own": (0.0, 0.0), "post": (0.0, 0.0)}
    assert world.gravity == (0.0, -9.81)
    assert abs(hit.time - (0.2 + math.sqrt(2 * 0.45 / 9.81))) <= EXACT
    assert post.position == (0.2, 0.2)


def test_gravity_switched_off_mid_flight_keeps_the_current_velocity():
    """set_gravity((0, 0)) mid-flight: the body continues in a straight line with the velocity it had."""
    world = walled(gravity=(0.0, -1.0))
    ball = world.add_circle((0.5, 0.9), 0.05, mass=1.0, name="ball")
    world.at_time(0.5, lambda event: world.set_gravity((0.0, 0.0)))
    world.run_until(0.5)
    assert near(ball.velocity, (0.0, -0.5))
    world.run_until(1.0)
    assert near(ball.velocity, (0.0, -0.5))
    assert near(ball.position, (0.5, 0.9 - 0.125 - 0.25))


def test_own_acceleration_adds_to_gravity():
    """total_acceleration is gravity plus the body's own acceleration, and the motion follows it."""
    world = walled(gravity=(0.0, -2.0))
    ball = world.add_circle((0.5, 0.5), 0.05, mass=1.0, acceleration=(1.0, 0.5), name="ball")
    assert ball.total_acceleration == (1.0, -1.5)
    world.run_until(0.2)
    assert near(ball.position, (0.5 + 0.5 * 1.0 * 0.04, 0.5 - 0.5 * 1.5 * 0.04))
    assert near(ball.velocity, (0.2, -0.3))


# ------------------------------------------------------------------------------ timers


def test_timers_fire_in_time_order_and_equal_times_in_registration_order():
    """at_time callbacks run in time order (ties by registration), with world.time equal to the timer's time."""
    world = walled()
    world.add_circle((0.5, 0.5), 0.05, mass=1.0, velocity=(0.3, 0.7), name="ball")
    fired = []

    def log(event):
        fired.append((event.time, event.data, world.time, event.timer_id))

    ids = {}
    for t, tag in ((0.3, "c"), (0.1, "a"), (0.2, "b1"), (0.2, "b2"), (0.0, "now")):
        ids[tag] = world.at_time(t, log, data=tag)
    world.run_until(1.0)
    assert [(t, tag) for t, tag, _, _ in fired] == [(0.0, "now"), (0.1, "a"), (0.2, "b1"), (0.2, "b2"), (0.3, "c")]
    assert all(now == t for t, _, now, _ in fired)
    assert [timer_id for *_, timer_id in fired] == [ids[tag] for _, tag, _, _ in fired]
    assert len(set(ids.values())) == 5


def test_cancel_timer():
    """cancel_timer stops a pending timer (True once, then False); fired or unknown ids give False."""
    world = walled()
    world.add_circle((0.5, 0.5), 0.05, mass=1.0, velocity=(0.3, 0.7), name="ball")
    fired = []
    keep = world.at_time(0.2, fired.append, data="keep")
    drop = world.at_time(0.4, fired.append, data="drop")
    assert world.cancel_timer(drop) is True
    assert world.cancel_timer(drop) is False
    world.run_until(1.0)
    assert [event.data for event in fired] == ["keep"]
    assert isinstance(fired[0], Timer) and fired[0].timer_id == keep
    assert world.cancel_timer(keep) is False
    assert world.cancel_timer(12345) is False


def test_timer_cancelled_from_an_earlier_timer_never_fires():
    """A timer cancelled from inside another timer's callback does not fire."""
    world = World()
    fired = []
    later = world.at_time(0.5, lambda event: fired.append("later"))
    world.at_time(0.25, lambda event: fired.append(("cancel", world.cancel_timer(later))))
    world.run_until(1.0)
    assert fired == [("cancel", True)]


def test_timer_registered_in_a_callback_for_now_fires_in_the_same_run():
    """at_time(world.time) from a callback fires in the same run, after the current event."""
    world = World()
    fired = []

    def first(event):
        fired.append("first")
        world.at_time(world.time, lambda e: fired.append(("second", e.time)))

    world.at_time(0.5, first)
    world.run_until(0.5)
    assert fired == ["first", ("second", 0.5)]


def _wall_hit_time() -> float:
    """The time a ball of radius 1/8 at x = 1/2, speed 1, first touches the right wall (0.375 ideally)."""
    world = walled()
    world.add_circle((0.5, 0.5), 0.125, mass=1.0, velocity=(1.0, 0.0))
    seen = collisions_of(world)
    world.run_until(1.0)
    return seen[0].time


def test_collision_timer_and_frame_at_equal_times_come_in_that_order():
    """At one instant the collision is processed first, then the timer, then the frame (documented order)."""
    hit = _wall_hit_time()
    assert abs(hit - 0.375) <= EXACT
    rate = 1.0 / hit
    assert 1.0 / rate == hit, "test set-up: a frame must fall exactly on the collision time"
    world = walled()
    ball = world.add_circle((0.5, 0.5), 0.125, mass=1.0, velocity=(1.0, 0.0))
    velocity_seen = {}
    world.at_time(hit, lambda event: velocity_seen.setdefault("timer", ball.velocity))
    world.on_frame(lambda event: velocity_seen.setdefault("frame", ball.velocity))
    world.frame_rate = rate
    order = [(type(e).__name__, e.time) for e in world.events(hit + 0.1)]
    assert order == [("Collision", hit), ("Timer", hit), ("Frame", hit), ("Stop", hit + 0.1)]
    # the timer and the frame see the world after the bounce
    assert velocity_seen == {"timer": (-1.0, 0.0), "frame": (-1.0, 0.0)}


def test_timer_and_frame_at_equal_times_come_timer_first():
    """A timer and a frame due at the same time fire timer first, whatever the registration order."""
    world = World(frame_rate=4.0)
    order = []

    def frame(event):
        order.append(("frame", event.time))
        if event.index == 1:  # the frame at 0.5 is already queued: register the timer after it
            world.at_time(0.5, lambda timer: order.append(("timer", timer.time)))

    world.on_frame(frame)
    world.run_until(0.5)
    assert order == [("frame", 0.25), ("timer", 0.5), ("frame", 0.5)]


# -------------------------------------------------------------------------- callbacks


def test_on_collision_body_filter_sees_only_that_bodys_collisions():
    """on_collision(cb, body=x) is called exactly for collisions involving x; world-wide callbacks run first."""
    world = walled()
    left = world.add_circle((0.3, 0.5), 0.05, mass=1.0, velocity=(-1.0, 0.0), name="left")
    right = world.add_circle((0.7, 0.5), 0.05, mass=1.0, velocity=(0.5, 0.0), name="right")
    log = []
    world.on_collision(lambda event: log.append(("all", event.time)))
    world.on_collision(lambda event: log.append(("left", event.time)), body=left)
    world.run_until(0.7)
    # left hits the left wall at t = 0.25, right hits the right wall at t = 0.5; they meet only later
    times = sorted(t for tag, t in log if tag == "all")
    assert len(times) == 2 and abs(times[0] - 0.25) <= EXACT and abs(times[1] - 0.5) <= EXACT
    assert [tag for tag, t in log] == ["all", "left", "all"]
    assert right.velocity == (-0.5, 0.0) and left.velocity == (1.0, 0.0)


def test_on_collision_body_filter_works_without_world_wide_callbacks_and_for_b_side():
    """A filtered callback alone still hears every collision of its body, whether it is event.a or event.b."""
    world = walled()
    one = world.add_circle((0.3, 0.5), 0.05, mass=1.0, velocity=(1.0, 0.0), name="one")
    two = world.add_circle((0.7, 0.5), 0.05, mass=1.0, velocity=(-1.0, 0.0), name="two")
    heard = {"one": [], "two": []}
    world.on_collision(lambda event: heard["one"].append(event), body=one)
    world.on_collision(lambda event: heard["two"].append(event), body=two)
    world.run_until(0.6)
    # they meet head on at t = 0.15 (gap 0.3 closing at 2), swap velocities and reach the walls at t = 0.55
    assert len(heard["one"]) == 2 and len(heard["two"]) == 2
    pair = heard["one"][0]
    assert heard["two"][0] is pair
    assert abs(pair.time - 0.15) <= EXACT and {pair.a.name, pair.b.name} == {"one", "two"}
    assert {heard["one"][1].a.name, heard["one"][1].b.name} == {"one", "left wall"}
    assert {heard["two"][1].a.name, heard["two"][1].b.name} == {"two", "right wall"}
    assert abs(heard["one"][1].time - 0.55) <= EXACT and abs(heard["two"][1].time - 0.55) <= EXACT


def test_on_frame_times_are_k_over_frame_rate():
    """With frame_rate 60, frames fire at exactly k/60 (index k = 1, 2, ...) and world.time equals the frame time."""
    world = walled(frame_rate=60)
    world.add_circle((0.5, 0.5), 0.05, mass=1.0, velocity=(3.0, 2.0))
    frames = []
    world.on_frame(lambda event: frames.append((event.index, event.time, world.time)))
    world.run_until(1.0)
    assert [index for index, _, _ in frames] == list(range(1, 61))
    assert all(t == k / 60 and now == t for k, t, now in frames)
    assert world.stats["frames"] == 60


def test_frame_rate_change_restarts_the_frame_clock():
    """Changing frame_rate mid-run drops the old frames; new ones fall at change_time + k / new_rate."""
    world = World(frame_rate=100)
    frames = []
    world.on_frame(lambda event: frames.append(event))
    world.run_until(0.5)
    assert len(frames) == 50
    world.frame_rate = 10
    world.run_until(1.0)
    later = frames[50:]
    assert [f.index for f in later] == [1, 2, 3, 4, 5]
    assert all(f.time == 0.5 + f.index / 10 for f in later)
    world.frame_rate = None
    world.run_until(2.0)
    assert len(frames) == 55


def test_callback_exception_propagates_and_world_stays_usable():
    """An exception raised in a callback comes out of run_until; the world can run on afterwards."""
    world = walled()
    ball = world.add_circle((0.5, 0.5), 0.05, mass=1.0, velocity=(1.0, 0.0))

    def boom(event):
        raise RuntimeError("boom")

    world.at_time(0.1, boom)
    with pytest.raises(RuntimeError, match="boom"):
        world.run_until(1.0)
    assert world.time == 0.1
    world.run_until(1.0)
    assert world.time == 1.0
    assert near(ball.position, (0.4, 0.5))  # right wall at t = 0.45, then 0.55 back


# ----------------------------------------------------------------------- running loops


def test_events_yields_stop_last_and_run_until_sets_time():
    """events(until) yields records then Stop(until) last; run_until(t) leaves world.time == t even with no events."""
    world = walled()
    world.add_circle((0.5, 0.5), 0.05, mass=1.0, velocity=(1.0, 0.0))
    records = list(world.events(1.0))
    assert records[-1] == Stop(1.0)
    assert all(not isinstance(r, Stop) for r in records[:-1])
    assert [type(r) for r in records[:-1]] == [Collision]  # right wall at 0.45; the left one only at 1.35
    assert abs(records[0].time - 0.45) <= EXACT
    assert world.time == 1.0
    quiet = World()
    quiet.run_until(2.5)
    assert quiet.time == 2.5
    quiet.run(0.5)
    assert quiet.time == 3.0
    assert list(quiet.events(4.0)) == [Stop(4.0)]
    assert quiet.time == 4.0


def test_events_without_until_ends_when_the_queue_runs_dry():
    """events() with no until ends without a Stop when nothing can ever happen (no moving bodies, no frames)."""
    world = World()
    world.add_circle((0.5, 0.5), 0.05, fixed=True)
    world.at_time(1.5, lambda event: None, data="only")
    records = list(world.events())
    assert [type(r) for r in records] == [Timer]
    assert records[0].time == 1.5 and records[0].data == "only"


def test_abandoning_events_midway_leaves_a_consistent_world():
    """Breaking out of events() after a collision leaves time at that collision; a later run continues identically."""

    def make():
        world = walled()
        world.add_circle((0.3, 0.4), 0.05, mass=1.0, velocity=(0.9, 0.4))
        world.add_polygon([(0.6, 0.6), (0.7, 0.6), (0.65, 0.7)], mass=2.0, velocity=(-0.5, 0.3))
        return world

    reference = make()
    expected = [(e.time, e.a.id, e.b.id) for e in reference.events(3.0) if isinstance(e, Collision)]
    world = make()
    first = None
    for event in world.events(3.0):
        if isinstance(event, Collision):
            first = event
            break
    assert first is not None and world.time == first.time
    rest = collisions_of(world)
    world.run_until(3.0)
    assert [(first.time, first.a.id, first.b.id)] + [(e.time, e.a.id, e.b.id) for e in rest] == expected
    assert [b.position for b in world.bodies] == [b.position for b in reference.bodies]


def test_same_scene_gives_bit_identical_traces():
    """Two identical worlds give bit-identical event traces and final states."""

    def trace():
        world = walled(gravity=(0.0, -9.81), frame_rate=50)
        build_scene(world, random_scene(7, n_circles=6, n_polygons=3))
        out = [(type(e).__name__, e.time, getattr(e, "point", None)) for e in world.events(1.0)]
        return out, [(b.position, b.velocity) for b in world.bodies]

    assert trace() == trace()


def test_stop_from_a_callback_returns_after_the_current_event():
    """world.stop() in a callback ends run_until right after that event; the next run continues the same trace."""

    def make():
        world = walled()
        build_scene(world, random_scene(3, n_circles=5, n_polygons=2))
        return world

    reference = make()
    expected = [(e.time, e.a.id, e.b.id) for e in reference.events(2.0) if isinstance(e, Collision)]
    assert len(expected) >= 3
    world = make()
    seen = []

    def stop_on_second(event):
        seen.append((event.time, event.a.id, event.b.id))
        if len(seen) == 2:
            world.stop()

    world.on_collision(stop_on_second)
    world.run_until(2.0)
    assert len(seen) == 2 and world.time == seen[1][0] < 2.0
    world.run_until(2.0)
    assert seen == expected and world.time == 2.0


def test_stop_ends_events_without_a_stop_record():
    """world.stop() from a frame callback ends an events() iteration after that frame, with no Stop record."""
    world = World(frame_rate=10)
    world.on_frame(lambda event: world.stop() if event.index == 3 else None)
    records = list(world.events(5.0))
    assert [(type(r), r.index) for r in records] == [(Frame, 1), (Frame, 2), (Frame, 3)]
    assert [r.time for r in records] == [1 / 10, 2 / 10, 3 / 10]
    assert world.time == records[-1].time
    # the next run is not stopped by the old request
    assert list(world.events(0.5))[-1] == Stop(0.5)


# -------------------------------------------------------------------------- inspecting


def test_stats_counters_are_consistent():
    """stats: collisions/pair_collisions/frames/timers match the records; predictions + avoided <= candidates."""
    world = walled(frame_rate=25)
    bodies = build_scene(world, random_scene(11, n_circles=8, n_polygons=4))
    for t in (0.1, 0.2, 0.3):
        world.at_time(t, lambda event: None)
    world.cancel_timer(world.at_time(0.4, lambda event: None))
    records = list(world.events(2.0))
    stats = world.stats
    collisions = [r for r in records if isinstance(r, Collision)]
    assert stats["collisions"] == len(collisions) > 0
    assert stats["pair_collisions"] == sum(1 for r in collisions if not r.a.is_fixed and not r.b.is_fixed)
    assert stats["frames"] == sum(1 for r in records if isinstance(r, Frame)) == 50
    assert stats["timers"] == sum(1 for r in records if isinstance(r, Timer)) == 3
    assert stats["events"] >= stats["collisions"] + stats["grazes"] + stats["frames"] + stats["timers"] + stats["horizons"]
    assert world.predictions_avoided == stats["box_rejects"] + stats["bound_rejects"]
    assert stats["predictions"] + world.predictions_avoided <= stats["candidates"]
    assert stats["hits"] <= stats["predictions"]
    assert all(value >= 0 for value in stats.values())
    assert len(bodies) == 12


def test_stats_events_count_every_processed_event_exactly():
    """For a lone ball with timers and frames, stats['events'] = collisions + horizons + timers + frames (+ grazes)."""
    world = walled(frame_rate=10)
    world.add_circle((0.5, 0.5), 0.05, mass=1.0, velocity=(1.0, 0.3))
    world.at_time(0.35, lambda event: None)
    world.run_until(1.0)
    s = world.stats
    assert s["frames"] == 10 and s["timers"] == 1 and s["collisions"] >= 1
    assert s["events"] == s["collisions"] + s["grazes"] + s["horizons"] + s["timers"] + s["frames"]


def test_kinetic_energy_and_momentum_of_a_hand_built_scene():
    """kinetic_energy() and momentum() sum the moving bodies with a mass; fixed and massless bodies are left out."""
    world = World()
    world.add_circle((0.2, 0.2), 0.05, mass=2.0, velocity=(1.0, 2.0))
    world.add_polygon([(0.5, 0.5), (0.6, 0.5), (0.55, 0.6)], mass=3.0, velocity=(-3.0, 0.5))
    world.add_circle((0.8, 0.8), 0.05, mass=5.0, velocity=(7.0, 7.0), fixed=True)
    ghost = world.add_circle((0.8, 0.2), 0.05, velocity=(9.0, 9.0))
    assert world.kinetic_energy() == pytest.approx(0.5 * 2 * 5 + 0.5 * 3 * 9.25, rel=1e-15)
    assert world.momentum() == pytest.approx((2 - 9, 4 + 1.5), rel=1e-15)
    world.set_mass(ghost, 1.0)
    assert world.momentum() == pytest.approx((2 - 9 + 9, 4 + 1.5 + 9), rel=1e-15)
    assert world.kinetic_energy() == pytest.approx(18.875 + 81.0, rel=1e-15)


def test_momentum_under_gravity_changes_by_total_mass_times_g_t():
    """With gravity and no contacts, total momentum changes by (sum of masses) * g * t."""
    world = World(gravity=(0.0, -2.0))
    world.add_circle((0.2, 0.8), 0.05, mass=2.0, velocity=(0.1, 0.0))
    world.add_circle((0.6, 0.8), 0.05, mass=3.0, velocity=(0.0, 0.5))
    world.run_until(0.1)
    px, py = world.momentum()
    assert px == pytest.approx(0.2, abs=1e-15)
    assert py == pytest.approx(1.5 - 5.0 * 2.0 * 0.1, abs=1e-14)


def test_overlap_queries_on_a_hand_built_scene():
    """overlap_depth is minus the gap for separated circles and the depth for overlapping ones; overlaps() lists them."""
    world = World()
    a = world.add_circle((0.2, 0.5), 0.1, mass=1.0, name="a")
    b = world.add_circle((0.5, 0.5), 0.1, mass=1.0, name="b")
    c = world.add_circle((0.65, 0.5), 0.1, mass=1.0, name="c")
    assert world.overlap_depth(a, b) == pytest.approx(-0.1, abs=1e-15)
    assert world.overlap_depth(b, c) == pytest.approx(0.05, abs=1e-15)
    found = world.overlaps()
    assert len(found) == 1 and {found[0][0].name, found[0][1].name} == {"b", "c"}
    assert found[0][2] == pytest.approx(0.05, abs=1e-15)
    assert world.overlaps(tolerance=0.06) == []


# ----------------------------------------------------------------------------- bodies


def _signed_area(corners) -> float:
    n = len(corners)
    return 0.5 * sum(corners[k][0] * corners[(k + 1) % n][1] - corners[(k + 1) % n][0] * corners[k][1] for k in range(n))


def test_box_vertices_are_its_world_corners_anticlockwise_and_move_with_it():
    """add_box's vertices are its four world corners, anticlockwise; they follow the body as it moves."""
    world = World()
    box = world.add_box(0.1, 0.2, 0.3, 0.4, mass=1.0, velocity=(0.5, -0.25), name="crate")
    corners = {(0.1, 0.2), (0.4, 0.2), (0.4, 0.6), (0.1, 0.6)}
    assert len(box.vertices) == 4
    assert all(any(near(v, c, 1e-15) for c in corners) for v in box.vertices)
    assert _signed_area(box.vertices) == pytest.approx(0.12, rel=1e-12)
    assert near(box.position, (0.25, 0.4), 1e-15)
    world.run_until(0.2)
    moved = {(x + 0.1, y - 0.05) for x, y in corners}
    assert all(any(near(v, c, 1e-15) for c in moved) for v in box.vertices)


def test_polygon_position_is_its_area_centroid_either_winding():
    """A triangle's position is its centroid; clockwise input gives the same body as anticlockwise."""
    world = World()
    ccw = world.add_polygon([(0.0, 0.0), (0.3, 0.0), (0.0, 0.3)], mass=1.0)
    cw = world.add_polygon([(0.6, 0.6), (0.6, 0.9), (0.9, 0.6)], mass=1.0)
    assert near(ccw.position, (0.1, 0.1), 1e-15)
    assert near(cw.position, (0.7, 0.7), 1e-15)
    assert _signed_area(cw.vertices) > 0.0 and _signed_area(ccw.vertices) > 0.0
    assert ccw.shape.area == pytest.approx(0.045, rel=1e-12)


def test_polygon_angle_turns_its_vertices_about_the_centroid():
    """A box added with angle pi/2 has its corners turned a quarter turn about its centroid."""
    world = World()
    box = world.add_box(0.4, 0.45, 0.2, 0.1, mass=1.0, angle=math.pi / 2)
    assert box.angle == math.pi / 2
    xs = [x for x, _ in box.vertices]
    ys = [y for _, y in box.vertices]
    assert max(xs) - min(xs) == pytest.approx(0.1, abs=1e-12)
    assert max(ys) - min(ys) == pytest.approx(0.2, abs=1e-12)
    assert near(box.position, (0.5, 0.5), 1e-15)


def test_body_properties():
    """Body handles report kind, label, name, data, mass (None until set), shape and liveness."""
    world = World(gravity=(0.0, -1.0))
    ball = world.add_circle((0.5, 0.5), 0.05, name="ball", data={"colour": "red"})
    tri = world.add_polygon([(0.1, 0.1), (0.2, 0.1), (0.15, 0.2)], mass=2.0)
    assert ball.kind == "circle" and tri.kind == "polygon"
    assert ball.mass is None
    ball.mass = 3.0
    assert ball.mass == 3.0 and tri.mass == 2.0
    assert ball.label() == f"circle {ball.id} 'ball'"
    assert tri.label() == f"polygon {tri.id}"
    assert ball.name == "ball" and ball.data == {"colour": "red"} and tri.name is None
    assert ball.shape.radius == 0.05 and ball.vertices == ()
    assert ball.acceleration == (0.0, 0.0) and ball.total_acceleration == (0.0, -1.0)
    assert ball.elasticity == 0.98 and not ball.is_fixed
    ball.elasticity = 0.5
    assert ball.elasticity == 0.5
    tri.angular_velocity = 2.0
    assert tri.angular_velocity == 2.0
    assert world.bodies == (ball, tri) and len(world) == 2
    assert ball.alive
    world.remove(ball)
    assert not ball.alive and world.bodies == (tri,)
    assert "removed" in repr(ball)


# ------------------------------------------------------------- more mid-run changes


def test_moving_a_fixed_post_out_of_the_way_drops_the_predicted_hit():
    """set_position of a fixed body mid-run: the old predicted contact is dropped, a new one is made at its new place."""
    world = walled()
    world.add_circle((0.2, 0.5), 0.05, mass=1.0, velocity=(1.0, 0.0), name="ball")
    post = world.add_circle((0.6, 0.5), 0.05, fixed=True, name="post")  # would be hit at t = 0.3
    seen = collisions_of(world)
    world.run_until(0.1)
    world.set_position(post, (0.6, 0.8))
    world.run_until(0.7)
    # the ball flies on to the right wall (centre 0.95) at t = 0.75
    assert seen == []
    world.set_position(post, (0.3, 0.5))  # back in the ball's way after the bounce
    world.run_until(1.5)
    assert len(seen) == 2
    assert abs(seen[0].time - 0.75) <= EXACT and involves(seen[1], post)
    # from x = 0.95 at t = 0.75 going left, the post (centre 0.3) is touched when the ball's centre is at 0.4
    assert abs(seen[1].time - 1.3) <= EXACT


def test_removing_a_wall_mid_run_lets_the_ball_through():
    """Removing a fixed wall mid-run drops the predicted hit: the ball leaves through the gap."""
    world = walled()
    ball = world.add_circle((0.5, 0.5), 0.05, mass=1.0, velocity=(1.0, 0.0), name="ball")
    right = next(b for b in world.bodies if b.name == "right wall")
    seen = collisions_of(world)
    world.run_until(0.3)
    world.remove(right)
    world.run_until(1.0)
    assert seen == []
    assert near(ball.position, (1.5, 0.5))


def test_adding_a_wall_mid_run_in_a_balls_path_is_hit():
    """A fixed body added mid-run (from a timer) in a moving body's path is hit at the analytic time."""
    world = walled()
    world.add_circle((0.2, 0.5), 0.05, mass=1.0, velocity=(1.0, 0.0), name="ball")
    seen = collisions_of(world)
    added = []
    world.at_time(0.1, lambda event: added.append(world.add_box(0.6, 0.3, 0.05, 0.4, fixed=True, name="gate")))
    world.run_until(0.6)
    # the ball's right side (x + 0.05) reaches the gate's face x = 0.6 at t = 0.35
    assert len(seen) == 1 and involves(seen[0], added[0])
    assert abs(seen[0].time - 0.35) <= EXACT
    assert near(seen[0].point, (0.6, 0.5))


def test_set_mass_mid_run_changes_the_next_collision_response():
    """set_mass between collisions is used by the next bounce: a 1 kg ball hitting a resting 3 kg one (e = 1)."""
    world = walled()
    a = world.add_circle((0.2, 0.5), 0.05, mass=1.0, velocity=(1.0, 0.0), name="a")
    b = world.add_circle((0.6, 0.5), 0.05, mass=1.0, name="b")
    world.run_until(0.1)
    world.set_mass(b, 3.0)
    seen = collisions_of(world)
    world.run_until(0.31)
    assert len(seen) == 1 and abs(seen[0].time - 0.3) <= EXACT
    # elastic 1-D collision: v_a = (m_a - m_b) / (m_a + m_b) = -0.5, v_b = 2 m_a / (m_a + m_b) = 0.5
    assert near(a.velocity, (-0.5, 0.0)) and near(b.velocity, (0.5, 0.0))
    assert seen[0].impulse == pytest.approx(1.5, rel=1e-12)


@pytest.mark.parametrize(
    "rule, expected",
    [("min", 0.5), ("max", 1.0), ("mean", 0.75), ("geometric", math.sqrt(0.5))],
)
def test_restitution_rules_combine_elasticities(rule, expected):
    """A ball of elasticity 0.5 bouncing off a wall of elasticity 1 rebounds at the rule's combined coefficient."""
    world = World(restitution=rule)
    assert world.restitution == rule
    world.add_box(0.9, 0.0, 0.1, 1.0, fixed=True, elasticity=1.0)
    ball = world.add_circle((0.5, 0.5), 0.05, mass=1.0, velocity=(2.0, 0.0), elasticity=0.5)
    seen = collisions_of(world)
    world.run_until(0.5)
    assert len(seen) == 1
    assert ball.velocity[0] == pytest.approx(-2.0 * expected, rel=1e-12)
    assert seen[0].approach_speed == pytest.approx(2.0, rel=1e-12)
    assert seen[0].impulse == pytest.approx(2.0 * (1.0 + expected), rel=1e-12)


def test_set_elasticity_mid_run_changes_the_next_bounce():
    """set_elasticity mid-run is used by the next bounce."""
    world = walled()
    ball = world.add_circle((0.5, 0.5), 0.05, mass=1.0, velocity=(1.0, 0.0), name="ball")
    world.run_until(0.2)
    ball.elasticity = 0.25
    world.run_until(0.5)
    assert ball.velocity == pytest.approx((-0.25, 0.0), abs=1e-15)


def test_set_angle_mid_run_is_predicted_with_the_new_orientation():
    """Turning a falling square by 45 degrees mid-run: its lowest corner reaches the floor at the analytic time."""
    world = walled()
    square = world.add_box(0.4, 0.4, 0.2, 0.2, mass=1.0, velocity=(0.0, -1.0), name="square")
    seen = collisions_of(world)
    world.at_time(0.1, lambda event: world.set_angle(square, math.pi / 4))
    world.run_until(0.5)
    # at t = 0.1 the centre is at y = 0.4; the corner hangs 0.1 * sqrt(2) below it
    assert len(seen) == 1
    assert abs(seen[0].time - (0.1 + 0.4 - 0.1 * math.sqrt(2.0))) <= EXACT
    assert near(seen[0].point, (0.5, 0.0), 1e-12)


def test_run_in_pieces_gives_the_same_frames_as_one_run():
    """run(d) repeatedly: frames continue at k / rate with consecutive indices, as in a single run."""
    world = World(frame_rate=10)
    frames = []
    world.on_frame(frames.append)
    for _ in range(4):
        world.run(0.25)
    assert world.time == 1.0
    assert [f.index for f in frames] == list(range(1, 11))
    assert all(f.time == f.index / 10 for f in frames)


def test_run_until_exactly_a_collision_time_processes_that_collision():
    """run_until(t) processes a collision due at exactly t (events up to and including t)."""
    hit = _wall_hit_time()
    world = walled()
    ball = world.add_circle((0.5, 0.5), 0.125, mass=1.0, velocity=(1.0, 0.0))
    world.run_until(hit)
    assert world.stats["collisions"] == 1 and ball.velocity == (-1.0, 0.0)


def test_registration_methods_return_the_callback_for_decorator_use():
    """on_collision and on_frame return their callback, so they can be used as decorators."""
    world = World()

    @world.on_collision
    def hit(event):
        pass

    @world.on_frame
    def frame(event):
        pass

    assert callable(hit) and hit.__name__ == "hit" and callable(frame) and frame.__name__ == "frame"


def test_positions_in_bulk_equal_each_bodys_closed_form_position():
    """World.positions() returns, bit for bit, every body's Body.position at the current time."""
    world = World(gravity=(0.0, -1.0))
    a = world.add_circle((0.2, 0.5), 0.05, mass=1.0, velocity=(0.1, 0.3))
    b = world.add_box(0.5, 0.5, 0.1, 0.1, mass=2.0, velocity=(-0.2, 0.0))
    world.run_until(0.37)
    xy = world.positions()
    assert [tuple(row) for row in xy] == [a.position, b.position]
    assert [tuple(row) for row in world.positions([b])] == [b.position]


def test_off_collision_unregisters_a_callback():
    """A collision callback removed with off_collision is no longer called; removing twice says False."""
    world = World()
    world.add_box(0.0, 0.0, 1.0, 0.1, fixed=True)
    ball = world.add_circle((0.5, 0.5), 0.05, mass=1.0, velocity=(0.0, -1.0))
    seen = []
    callback = world.on_collision(lambda event: seen.append(event.time), ball)
    assert world.off_collision(callback, ball) is True
    assert world.off_collision(callback, ball) is False
    world.run_until(1.0)
    assert seen == []


def test_default_elasticity_applies_to_new_bodies_only():
    """Assigning World.elasticity changes the default of bodies added later, not existing ones."""
    world = World()
    first = world.add_circle((0.2, 0.5), 0.05, mass=1.0)
    world.elasticity = 0.5
    second = world.add_circle((0.6, 0.5), 0.05, mass=1.0)
    assert first.elasticity == 0.98 and second.elasticity == 0.5
    with pytest.raises(ValueError, match="elasticity"):
        world.elasticity = 1.5
