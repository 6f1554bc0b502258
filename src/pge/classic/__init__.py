"""The classic PGE API: Gaius Mulley's ``pge`` module, as a thin facade over ``pge.World``.

Every public name of the original (functions, the ``object`` and ``event``
classes, constants) with the same parameters, defaults, return values and
callback argument orders, plus the extensions its users asked for (poly5,
poly6, polygon, elasticity, get_time, rotation state, per-object gravity).
No physics happens here: each call is a World call. The names are
re-exported by ``pge`` itself, so PGE scripts run unchanged::

    import pge
    pge.interactive()
    ball = pge.circle(0.5, 0.8, 0.05, pge.rgb(1, 0.8, 0)).mass(1)
    pge.gravity()
    pge.run(5)

``reset()`` forgets the whole session (tests call it between scenes).
Differences from the original are listed in docs/differences-from-pge.md.
"""

from pge.classic.colours import rgb, white
from pge.classic.constants import (
    Black,
    batch_d,
    box_t,
    circle_t,
    collision_event,
    colour_t,
    fb_box_t,
    fb_circle_t,
    fb_text_t,
    final_event,
    frame_event,
    function_event,
    no_event,
    program_name,
    pyg_d,
    spring_event,
    spring_t,
    version_number,
)
from pge.classic.constructors import box, circle, poly3, poly4, poly5, poly6, polygon, spring, text
from pge.classic.events import at_cancel, at_time
from pge.classic.events import event as event  # the original class name (not in __all__)
from pge.classic.objects import Object
from pge.classic.runloop import (
    batch,
    collision_colour,
    delay,
    deregister_handler,
    display_fullscreen,
    display_set_mode,
    draw_collision,
    elasticity,
    finish_record,
    fps,
    get_frame_no,
    get_time,
    gravity,
    interactive,
    local_fps,
    record,
    register_handler,
    run,
    runbatch,
    runpy,
    slow_down,
    update_fps,
    velocity_damping,
)
from pge.classic.runloop import save_frame as save_frame  # not a PGE name: pge.classic only
from pge.classic.session import STATE as _STATE
from pge.classic.session import reset as reset  # not a PGE name: pge.classic only
from pge.classic.utilities import (
    dump_world,
    flip,
    get_font,
    magnitude,
    message,
    normalise,
    play,
    pyg_to_unit_coord,
    sub_coord,
    toFloat,
)

#: the original's class names (``pge.object``, ``pge.event``).
object = Object  # shadows the builtin inside this module only, as the original did

#: the names ``from pge.classic import *`` (and ``from pge import *``) give: every public name of the
#: original PGE module and the extensions, except the classes ``object`` and ``event``, which would
#: shadow the builtin ``object`` (and a common variable name) in the importing script.
__all__ = [
    # setup
    "batch", "interactive", "display_set_mode", "display_fullscreen", "fps", "slow_down", "gravity",
    "record", "finish_record",
    # colours and objects
    "rgb", "white", "box", "poly3", "poly4", "circle", "text", "spring",
    # running, timers, input
    "run", "runpy", "runbatch", "at_time", "at_cancel", "register_handler", "deregister_handler",
    "get_frame_no", "local_fps", "update_fps", "delay",
    # output and utilities
    "draw_collision", "collision_colour", "dump_world", "play", "message", "get_font", "flip",
    "pyg_to_unit_coord", "normalise", "magnitude", "sub_coord", "toFloat",
    # constants
    "colour_t", "box_t", "circle_t", "spring_t", "fb_box_t", "fb_circle_t", "fb_text_t",
    "batch_d", "pyg_d", "no_event", "frame_event", "collision_event", "function_event", "spring_event",
    "final_event", "program_name", "version_number", "framesPerSecond", "Black",
    # extensions
    "poly5", "poly6", "polygon", "elasticity", "get_time", "velocity_damping",
]  # fmt: skip

#: every public name of the original PGE module, plus the extensions.
PGE_NAMES = [*__all__, "object", "event"]


def __getattr__(name):
    if name == "framesPerSecond":
        return _STATE.fps  # the original's module variable follows fps()
    raise AttributeError(f"module 'pge.classic' has no attribute {name!r}")
