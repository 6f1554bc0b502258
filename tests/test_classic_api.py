"""The classic PGE API table (pge-api.md section 2): every name, its parameters and defaults."""

from __future__ import annotations

import inspect
import subprocess
import sys

import pytest
from classic_support import session  # noqa: F401 (the fixture every test uses)

import pge

pytestmark = pytest.mark.usefixtures("session")

# section 2.1 to 2.7: module functions, exactly as the original's signatures
FUNCTIONS = {
    "batch": "()",
    "interactive": "()",
    "display_set_mode": "(r)",
    "display_fullscreen": "(b)",
    "fps": "(f)",
    "slow_down": "(t)",
    "gravity": "(value=-9.81)",
    "record": "()",
    "finish_record": "()",
    "rgb": "(r, g, b)",
    "white": "()",
    "box": "(x, y, w, h, c, level=0)",
    "poly3": "(x0, y0, x1, y1, x2, y2, c, level=0)",
    "poly4": "(x0, y0, x1, y1, x2, y2, x3, y3, c, level=0)",
    "circle": "(x, y, r, c, level=0)",
    "text": "(x, y, s, c, size, level)",
    "spring": "(ob1, ob2, k, d, l=None)",
    "run": "(t=-1)",
    "runpy": "(t=-1)",
    "runbatch": "(t)",
    "at_time": "(t, p)",
    "at_cancel": "(i)",
    "register_handler": "(function, pyeventlist)",
    "deregister_handler": "(pyeventlist)",
    "get_frame_no": "()",
    "local_fps": "()",
    "update_fps": "(e, o)",
    "delay": "(t)",
    "draw_collision": "(actual, predict)",
    "collision_colour": "(c)",
    "dump_world": "()",
    "play": "(name)",
    "message": "(text)",
    "get_font": "(size)",
    "flip": "(y)",
    "pyg_to_unit_coord": "(v)",
    "normalise": "(v)",
    "magnitude": "(v)",
    "sub_coord": "(a, b)",
    "toFloat": "(f)",
}

# section 2.4: methods of pge.object
OBJECT_METHODS = {
    "velocity": "(self, vx, vy)",
    "accel": "(self, ax, ay)",
    "fix": "(self)",
    "unfix": "(self)",
    "is_fixed": "(self)",
    "mass": "(self, m)",
    "get_mass": "(self)",
    "apply_impulse": "(self, unit_vec, magnitude)",
    "moving_towards": "(self, x, y)",
    "get_xpos": "(self)",
    "get_ypos": "(self)",
    "get_unit_coord": "(self)",
    "get_xvel": "(self)",
    "get_yvel": "(self)",
    "get_xaccel": "(self)",
    "get_yaccel": "(self)",
    "put_xvel": "(self, f)",
    "put_yvel": "(self, f)",
    "put_xaccel": "(self, f)",
    "put_yaccel": "(self, f)",
    "on_collision": "(self, p)",
    "on_collision_with": "(self, another, p)",
    "rm": "(self)",
    "get_param": "(self)",
    "set_param": "(self, value)",
    "set_width": "(self, value)",
    "get_width": "(self)",
    "get_colour": "(self)",
    "set_colour": "(self, c)",
    "set_alpha": "(self, value)",
    "set_visible": "(self, value)",
    "draw": "(self, c, w)",
    "end": "(self, c)",
    "mid": "(self, c)",
    "when": "(self, l, p)",
}

# section 2.5: methods of pge.event
EVENT_METHODS = {
    "collision_between": "(self)",
    "cancel": "(self)",
    "was_cancelled": "(self)",
    "get_timer_id": "(self)",
}

# issue 3, item 3: the extensions
EXTENSION_FUNCTIONS = {
    "poly5": "(x0, y0, x1, y1, x2, y2, x3, y3, x4, y4, c, level=0)",
    "poly6": "(x0, y0, x1, y1, x2, y2, x3, y3, x4, y4, x5, y5, c, level=0)",
    "polygon": "(points, colour, level=0)",
    "elasticity": "(e)",
    "get_time": "()",
    "velocity_damping": "(factor=0.98)",
}
EXTENSION_OBJECT_METHODS = {
    "elasticity": "(self, e)",
    "rotate": "(self, angle)",
    "rvel": "(self, omega)",
    "get_angle": "(self)",
    "get_rvel": "(self)",
    "set_gravity": "(self, g)",
    "get_gravity": "(self)",
}
EXTENSION_EVENT_METHODS = {"get_time": "(self)", "get_point": "(self)"}

# section 2.7: module constants and their values
CONSTANTS = {
    "colour_t": 0,
    "box_t": 1,
    "circle_t": 2,
    "spring_t": 3,
    "fb_box_t": 4,
    "fb_circle_t": 5,
    "fb_text_t": 6,
    "batch_d": 0,
    "pyg_d": 1,
    "no_event": 0,
    "frame_event": 1,
    "collision_event": 2,
    "function_event": 3,
    "spring_event": 4,
    "final_event": 5,
    "program_name": "pge",
    "version_number": "4.0",
    "framesPerSecond": 100.0,
    "Black": (0, 0, 0),
}


def parameters(function) -> str:
    """The signature's parameter list with defaults, e.g. ``(x, y, r, c, level=0)``."""
    signature = inspect.signature(function)
    return str(signature.replace(return_annotation=inspect.Signature.empty))


@pytest.mark.parametrize("name", sorted({**FUNCTIONS, **EXTENSION_FUNCTIONS}))
def test_function_has_the_documented_signature(name):
    """Each module function exists in pge with the original's parameter names and defaults."""
    expected = {**FUNCTIONS, **EXTENSION_FUNCTIONS}[name]
    function = getattr(pge, name)
    assert callable(function)
    assert parameters(function) == expected


@pytest.mark.parametrize("name", sorted({**OBJECT_METHODS, **EXTENSION_OBJECT_METHODS}))
def test_object_method_has_the_documented_signature(name):
    """Each method of pge.object exists with the original's parameters."""
    expected = {**OBJECT_METHODS, **EXTENSION_OBJECT_METHODS}[name]
    assert parameters(getattr(pge.object, name)) == expected


@pytest.mark.parametrize("name", sorted({**EVENT_METHODS, **EXTENSION_EVENT_METHODS}))
def test_event_method_has_the_documented_signature(name):
    """Each method of pge.event exists with the original's parameters."""
    expected = {**EVENT_METHODS, **EXTENSION_EVENT_METHODS}[name]
    assert parameters(getattr(pge.event, name)) == expected


@pytest.mark.parametrize("name", sorted(CONSTANTS))
def test_constant_has_the_original_value(name):
    """Each module constant has the original's value."""
    assert getattr(pge, name) == CONSTANTS[name]


def test_every_public_name_is_listed_and_exported():
    """pge.classic.PGE_NAMES covers the whole table; pge exports them and keeps the World API."""
    table = set(FUNCTIONS) | set(EXTENSION_FUNCTIONS) | set(CONSTANTS) | {"object", "event"}
    assert table == set(pge.classic.PGE_NAMES)
    star = set(pge.__all__)
    assert table - {"object", "event"} <= star
    for name in ("World", "Body", "Circle", "Polygon", "Collision", "Timer", "Frame", "Stop", "__version__"):
        assert name in star and hasattr(pge, name)
    assert "object" not in star and "event" not in star  # a star import must not shadow builtins


def test_frames_per_second_follows_fps():
    """pge.framesPerSecond is the current frame rate, as the original's module variable."""
    pge.fps(40)
    assert pge.framesPerSecond == 40.0


def test_import_pge_needs_no_display_and_no_pygame():
    """import pge (and making a scene) works without a display and does not import pygame."""
    code = "import sys, pge; pge.batch(); pge.circle(0.5, 0.5, 0.1, pge.white()).fix(); print('pygame' in sys.modules)"
    env = {"PATH": "/usr/bin:/bin", "PGE_HEADLESS": "1"}
    done = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=120, check=False
    )
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "False"


def test_only_the_display_module_imports_pygame():
    """No module of pge except pge.render.pygame_display imports pygame."""
    import pathlib

    root = pathlib.Path(pge.__file__).parent
    importers = sorted(
        str(path.relative_to(root))
        for path in root.rglob("*.py")
        if any(line.lstrip().startswith(("import pygame", "from pygame")) for line in path.read_text().splitlines())
    )
    assert importers == ["render/pygame_display.py"]
