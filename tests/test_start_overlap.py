"""Bodies that overlap when a run starts: refused by the World by default; with
``allow_overlap`` (and always in the classic module, as in PGE) the pair passes through each
other until it has separated, with one warning naming it."""

from __future__ import annotations

import warnings

import pytest

from pge import World
from pge.errors import OverlapWarning


def _two_at_one_point(allow):
    world = World(gravity=(0.0, 0.0), elasticity=1.0, allow_overlap=allow)
    world.add_box(0.0, 0.0, 0.01, 1.0, fixed=True, name="left")
    world.add_box(0.99, 0.0, 0.01, 1.0, fixed=True, name="right")
    a = world.add_circle((0.5, 0.5), 0.05, mass=1.0, velocity=(1.0, 0.0), name="a")
    b = world.add_circle((0.5, 0.5), 0.05, mass=1.0, velocity=(-1.0, 0.0), name="b")
    return world, a, b


def test_the_world_refuses_overlapping_bodies_by_default():
    world, a, b = _two_at_one_point(False)
    with pytest.raises(ValueError, match="circle 2 'a' overlaps circle 3 'b'"):
        world.run_until(1.0)
    assert world.time == 0.0


def test_allow_overlap_must_be_a_bool():
    with pytest.raises(TypeError, match="allow_overlap must be True or False"):
        World(allow_overlap="yes")


def test_an_overlapping_pair_passes_until_it_separates_then_collides():
    """Two balls at one point fly apart through each other (no collision while they overlap),
    bounce off the side walls at t = 0.44 and meet again head on at t = 0.83 (elasticity 1)."""
    world, a, b = _two_at_one_point(True)
    hits = []
    world.on_collision(lambda c: hits.append((round(c.time, 9), {c.a.name, c.b.name})))
    with pytest.warns(OverlapWarning, match="circle 2 'a' overlaps circle 3 'b' by 0.1") as caught:
        world.run_until(1.0)
    assert len(caught) == 1
    assert hits[:3] == [(0.44, {"b", "left"}), (0.44, {"a", "right"}), (0.83, {"a", "b"})]
    assert world.overlaps(1e-9) == []


def test_one_warning_per_pair_and_none_for_a_separate_body():
    world, a, b = _two_at_one_point(True)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        world.run_until(0.1)
        world.add_circle((0.2, 0.8), 0.05, mass=1.0)
        world.run_until(0.2)
    assert [str(w.message).split(" by ")[0] for w in caught] == ["circle 2 'a' overlaps circle 3 'b'"]


def test_a_body_added_into_another_later_is_excused_too():
    world = World(gravity=(0.0, 0.0), allow_overlap=True)
    still = world.add_circle((0.5, 0.5), 0.05, mass=1.0, name="still")
    world.run_until(0.5)
    with pytest.warns(OverlapWarning, match="'still'.*'new'|'new'.*'still'"):
        new = world.add_circle((0.52, 0.5), 0.05, mass=1.0, velocity=(1.0, 0.0), name="new")
        world.run_until(1.0)
    assert still.velocity == (0.0, 0.0)  # it was never hit
    assert new.position[0] == pytest.approx(1.02)


def test_classic_module_runs_balls_placed_at_one_point(monkeypatch):
    """PGE's springs/boxes places two balls at one point; the original runs it."""
    import pge
    from pge.classic import reset

    monkeypatch.setenv("PGE_HEADLESS", "1")
    reset()
    try:
        pge.batch()
        colour = pge.rgb(0.2, 0.4, 0.8)
        pge.box(0.0, 0.0, 1.0, 0.02, colour).fix()
        first = pge.circle(0.5, 0.5, 0.03, colour).mass(1.0)
        second = pge.circle(0.5, 0.5, 0.03, colour).mass(1.0)
        pge.gravity()
        with pytest.warns(OverlapWarning, match="overlaps"):
            pge.run(2.0)
        assert pge.get_time() == pytest.approx(2.0)
        assert first.get_ypos() > 0.02 and second.get_ypos() > 0.02
    finally:
        reset()
