"""pge: a predictive 2D physics and game engine.

Two front doors to one engine:

* ``pge.World``: the modern API. Bodies are circles and convex polygons
  moving under constant accelerations, and every collision is found at its
  exact time.
* The classic PGE API (``pge.circle``, ``pge.run``, ...), compatible with
  Gaius Mulley's PGE and implemented in ``pge.classic`` over ``pge.World``.
  ``pge.framesPerSecond`` follows ``pge.fps()``, as the original's module
  variable did.

``pge.sweep(scene, params, seeds=..., until=...)`` runs a scene for every
combination of parameters and seeds on Dask and returns a pandas DataFrame
(the optional ``sweep`` extra; see ``pge.sweeps``).
"""

import os as _os

# before anything imports pygame (pge's window, or a game's pygame.locals): no banner on stdout
_os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")

from pge import _jit_cache  # noqa: E402,F401  (must come first: it configures the kernel cache)
from pge import classic as _classic
from pge.bodies import Body
from pge.classic import (  # the classic PGE names: pge.classic.PGE_NAMES
    Black,
    at_cancel,
    at_time,
    batch,
    batch_d,
    box,
    box_t,
    circle,
    circle_t,
    collision_colour,
    collision_event,
    colour_t,
    delay,
    deregister_handler,
    display_fullscreen,
    display_set_mode,
    draw_collision,
    dump_world,
    elasticity,
    fb_box_t,
    fb_circle_t,
    fb_text_t,
    final_event,
    finish_record,
    flip,
    fps,
    frame_event,
    function_event,
    get_font,
    get_frame_no,
    get_time,
    gravity,
    interactive,
    local_fps,
    magnitude,
    message,
    no_event,
    normalise,
    play,
    poly3,
    poly4,
    poly5,
    poly6,
    polygon,
    program_name,
    pyg_d,
    pyg_to_unit_coord,
    record,
    register_handler,
    rgb,
    run,
    runbatch,
    runpy,
    slow_down,
    spring,
    spring_event,
    spring_t,
    sub_coord,
    text,
    toFloat,
    update_fps,
    velocity_damping,
    version_number,
    white,
)
from pge.classic import event as event  # class pge.event: not in __all__ (see pge.classic.__all__)
from pge.classic import object as object  # class pge.object: not in __all__ (see pge.classic.__all__)
from pge.events import Collision, Frame, Stop, Timer
from pge.shapes import Circle, Polygon
from pge.world import World

__version__ = "0.1.0"

__all__ = [
    "World",
    "Body",
    "Circle",
    "Polygon",
    "Collision",
    "Timer",
    "Frame",
    "Stop",
    "__version__",
    "sweep",
    *_classic.__all__,  # the classic PGE API (without the classes object and event)
]


def sweep(scene, params=None, **options):
    """Run ``scene(seed, **params) -> World`` for every combination of ``params`` and seeds on Dask.

    Returns a pandas DataFrame with one row per run. A thin front for
    ``pge.sweeps.sweep`` (see there for every option: ``seeds``, ``until``,
    ``out``, ``events``, ``scheduler``, ``client``, ``workers``, ...), kept
    here so that ``import pge`` does not import dask, pyarrow or pandas.
    """
    from pge.sweeps import sweep as run_sweep

    return run_sweep(scene, params, **options)


def __getattr__(name):
    if name == "framesPerSecond":
        return _classic._STATE.fps
    raise AttributeError(f"module 'pge' has no attribute {name!r}")
