"""Bad calls to the classic API raise exceptions with the messages the original meant to give."""

from __future__ import annotations

import warnings

import pytest
from classic_support import session  # noqa: F401 (the fixture every test uses)

import pge

pytestmark = pytest.mark.usefixtures("session")


def test_wrong_kind_of_object():
    """Physics methods on a colour, eye-candy or text raise TypeError naming the action and the kind."""
    red = pge.rgb(1, 0, 0)
    with pytest.raises(TypeError, match="^velocity: you cannot give a velocity to a colour object$"):
        red.velocity(1, 2)
    with pytest.raises(TypeError, match="^mass: you cannot give a mass to a text object$"):
        pge.text(0.1, 0.1, "hi", red, 10, 1).mass(1)
    with pytest.raises(TypeError, match="fix: you cannot fix a foreground/background box object"):
        pge.box(0.1, 0.1, 0.1, 0.1, red, 2).fix()
    with pytest.raises(TypeError, match="get_xpos: you cannot ask for the position of a colour object"):
        red.get_xpos()
    with pytest.raises(TypeError, match="set_colour: you cannot set the colour of a colour object"):
        red.set_colour(red)


def test_wrong_type_of_value():
    """A value that is not a number raises TypeError naming the function and the parameter."""
    white = pge.white()
    with pytest.raises(TypeError, match="circle: x must be a number, got str 'a'"):
        pge.circle("a", 0.5, 0.1, white)
    with pytest.raises(TypeError, match="velocity: vy must be a number"):
        pge.circle(0.5, 0.5, 0.1, white).velocity(0.1, None)
    with pytest.raises(TypeError, match="box: level must be an integer"):
        pge.box(0.1, 0.1, 0.1, 0.1, white, 0.5)
    with pytest.raises(TypeError, match="at_time: p must be callable"):
        pge.at_time(1.0, "later")
    with pytest.raises(TypeError, match="on_collision_with: another must be a list"):
        pge.circle(0.2, 0.2, 0.1, white).on_collision_with(3, lambda o, e: None)
    with pytest.raises(ValueError, match="circle: r must be positive"):
        pge.circle(0.5, 0.5, -0.1, white)
    with pytest.raises(ValueError, match="rgb: g must be between 0.0 and 1.0"):
        pge.rgb(0.5, 1.5, 0.5)


def test_a_colour_is_expected():
    """Constructors and colour setters name the parameter that should have been a colour."""
    cases = [
        (lambda: pge.box(0.1, 0.1, 0.1, 0.1, "red"), "fifth parameter to box is expected to be a colour"),
        (lambda: pge.poly3(0, 0, 1, 0, 0, 1, None), "seventh parameter to poly3 is expected to be a colour"),
        (lambda: pge.poly4(0, 0, 1, 0, 1, 1, 0, 1, 7), "ninth parameter to poly4 is expected to be a colour"),
        (lambda: pge.circle(0.5, 0.5, 0.1, (1, 0, 0)), "fourth parameter to circle is expected to be a colour"),
        (lambda: pge.text(0.1, 0.1, "x", "white", 10, 1), "fourth parameter to text is expected to be a colour"),
        (lambda: pge.polygon([(0, 0), (1, 0), (0, 1)], 3), "second parameter to polygon is expected to be a colour"),
        (lambda: pge.collision_colour("blue"), "first parameter to collision_colour is expected to be a colour"),
        (
            lambda: pge.circle(0.5, 0.5, 0.1, pge.white()).set_colour(0.5),
            "first parameter to set_colour is expected to be a colour",
        ),
    ]
    for call, message in cases:
        with pytest.raises(TypeError) as caught:
            call()
        assert str(caught.value) == message


def test_missing_mass_on_a_moving_object_at_run_time():
    """run() refuses a moving object without a mass, naming it; giving it a mass lets the run go on."""
    ball = pge.circle(0.5, 0.5, 0.05, pge.white())
    with pytest.raises(ValueError) as caught:
        pge.run(1.0)
    assert str(caught.value) == (
        "circle (0.5, 0.5, 0.05) is not fixed and has no mass: all moving objects must have a mass "
        "(give it one with .mass(m), or .fix() it)"
    )
    assert pge.get_time() == 0.0
    ball.mass(1.0)
    pge.run(0.1)
    assert pge.get_time() == 0.1


def test_missing_mass_of_an_object_made_in_a_callback():
    """A massless moving object created in a timer stops the run when the callback returns."""
    pge.at_time(0.1, lambda e, o: pge.box(0.1, 0.1, 0.1, 0.1, pge.white()))
    with pytest.raises(ValueError, match=r"box \(0.1, 0.1, 0.1, 0.1\) is not fixed and has no mass"):
        pge.run(1.0)
    assert abs(pge.get_time() - 0.1) < 1e-12


def test_unfix_without_a_mass():
    """unfix() of a massless object is refused at the next commit point."""
    post = pge.circle(0.5, 0.5, 0.05, pge.white()).fix()
    pge.run(0.1)
    post.unfix()
    with pytest.raises(ValueError, match="is not fixed and has no mass"):
        pge.run(0.1)


def test_deleted_object():
    """Every use of a deleted level-0 object raises ValueError saying it was deleted."""
    ball = pge.circle(0.5, 0.5, 0.05, pge.white()).mass(1)
    pge.run(0.1)
    ball.rm()
    with pytest.raises(ValueError, match="^object has been deleted and now it is being given a velocity$"):
        ball.velocity(1, 0)
    with pytest.raises(ValueError, match="^object has been deleted and now it is being given a mass$"):
        ball.mass(2)
    with pytest.raises(ValueError, match="^object has been deleted and now it is being given an impulse$"):
        ball.apply_impulse([1, 0], 1)
    with pytest.raises(ValueError, match="^object has been deleted and now it is being asked for its velocity$"):
        ball.get_xvel()
    with pytest.raises(ValueError, match="being given a fixed position"):
        ball.fix()


def test_other_documented_errors():
    """mass(None), text in level 0, pixels before a resolution, run from a callback, zero vectors."""
    ball = pge.circle(0.5, 0.5, 0.05, pge.white())
    with pytest.raises(ValueError, match="^cannot give value None as the mass$"):
        ball.mass(None)
    ball.rm()
    with pytest.raises(ValueError, match="^not allowed to place in level 0$"):
        pge.text(0.1, 0.1, "x", pge.white(), 10, 0)
    with pytest.raises(ValueError, match="display_set_mode' before calling 'pyg_to_unit_coord'"):
        pge.pyg_to_unit_coord([10, 10])
    pge.display_set_mode([100, 100])
    with pytest.raises(ValueError, match="expects a list of two integers"):
        pge.pyg_to_unit_coord([1, 2, 3])
    with pytest.raises(ValueError, match="zero vector"):
        pge.normalise([0.0, 0.0])
    with pytest.raises(ValueError, match="zero vector"):
        pge.circle(0.8, 0.8, 0.05, pge.white()).mass(1).apply_impulse([0, 0], 1.0)
    with pytest.raises(ValueError, match="at_time: t must not be negative"):
        pge.at_time(-1.0, lambda e, o: None)
    pge.at_time(0.05, lambda e, o: pge.run(1.0))
    with pytest.raises(RuntimeError, match="inside a callback"):
        pge.run(0.1)


def test_colours_work_before_a_device_is_chosen_and_devices_do_not_switch():
    """rgb() before batch()/interactive() works (the original exited); switching device only warns."""
    colour = pge.rgb(0.2, 0.4, 0.6)
    assert colour.type == pge.colour_t
    pge.batch()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        pge.interactive()
    assert "cannot change device once pge has started" in str(caught[0].message)
    assert pge.classic._STATE.device == pge.batch_d


def test_overlapping_objects_run_with_one_warning_naming_both():
    """Two moving objects placed overlapping run, as in the original: one OverlapWarning names
    both (no silent push apart), and they pass through each other until they separate."""
    from pge.errors import OverlapWarning

    pge.circle(0.5, 0.5, 0.05, pge.white()).mass(1)
    pge.circle(0.52, 0.5, 0.05, pge.white()).mass(1)
    with pytest.warns(
        OverlapWarning,
        match=r"circle \(0.5, 0.5, 0.05\).* overlaps .*circle \(0.52, 0.5, 0.05\)|"
        r"circle \(0.52, 0.5, 0.05\).* overlaps .*circle \(0.5, 0.5, 0.05\)",
    ) as caught:
        pge.run(0.1)
    assert len(caught) == 1
    assert pge.get_time() == pytest.approx(0.1)
