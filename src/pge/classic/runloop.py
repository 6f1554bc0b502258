"""Setting up and running a PGE game: devices, display settings, run, input, frames, recording.

``run(t)`` runs ``t`` simulated seconds more: in a window (frames paced
against the wall clock with ``slow_down``, input handlers called between
events) or headless (no window, no pacing, no input: as fast as the engine
goes). Headless means ``batch()`` was called, or PGE_HEADLESS=1 is set in the
environment, which turns ``interactive()`` into ``batch()`` so any PGE game
runs unchanged in CI. The simulation is the same either way: the same
objects, collisions, timers and frames at the same simulated times.
"""

from __future__ import annotations

import atexit
import warnings

from pge.classic import frames
from pge.classic.colours import is_colour, rgb, white
from pge.classic.constants import DEFAULT_GRAVITY, VELOCITY_DAMPING, batch_d, pyg_d, version_number
from pge.classic.constructors import text
from pge.classic.events import at_time
from pge.classic.session import STATE, finite, is_headless, positive
from pge.render.protocol import NullDisplay

__all__ = [
    "batch",
    "interactive",
    "display_set_mode",
    "display_fullscreen",
    "fps",
    "slow_down",
    "gravity",
    "elasticity",
    "get_time",
    "record",
    "finish_record",
    "run",
    "runbatch",
    "runpy",
    "register_handler",
    "deregister_handler",
    "get_frame_no",
    "local_fps",
    "update_fps",
    "delay",
    "draw_collision",
    "collision_colour",
    "headless",
    "save_frame",
    "RECORDING_NAME",
    "BATCH_SECONDS",
    "run_options",
]

#: the file ``record()`` writes, in the working directory.
RECORDING_NAME = "output.pgerec"
#: how long ``run()`` / ``runbatch()`` with a negative time runs headless (as the original's runbatch).
BATCH_SECONDS = 30.0


# ---------------------------------------------------------------- devices


def batch() -> None:
    """Run without a window: no display, no pacing, no input (headless)."""
    _choose(batch_d)


def interactive() -> None:
    """Run in a pygame window (headless instead if PGE_HEADLESS=1 is set)."""
    _choose(pyg_d)


def _choose(device: int) -> None:
    if STATE.device is not None and STATE.device != device:
        warnings.warn("cannot change device once pge has started", RuntimeWarning, stacklevel=3)
        return
    STATE.device = device


def headless() -> bool:
    """True if runs have no window: ``batch()`` was chosen or PGE_HEADLESS=1 is set."""
    return STATE.device == batch_d or is_headless()


def display_set_mode(r) -> None:
    """Use a window of ``r = [width, height]`` pixels (any aspect ratio; ``r`` is not changed)."""
    try:
        width, height = r
    except (TypeError, ValueError):
        raise TypeError(f"display_set_mode: r must be [width, height] in pixels, got {r!r}") from None
    width = positive("display_set_mode", "width", width)
    height = positive("display_set_mode", "height", height)
    STATE.resolution = (int(round(width)), int(round(height)))


def display_fullscreen(b) -> None:
    """Open the window full screen (True) or not (False); takes effect when it opens."""
    STATE.fullscreen = bool(b)


def fps(f) -> None:
    """Frames per second (default 100), from the next ``run()`` on."""
    STATE.fps = positive("fps", "f", f)


def slow_down(t) -> None:
    """Make the wall clock run ``t`` times slower than simulated time (default 1).

    Also scales ``at_time`` delays, which are wall-clock seconds.
    """
    STATE.slow = positive("slow_down", "t", t)
    if STATE.pacer is not None:
        STATE.pacer.anchor(STATE.now(), STATE.slow)


def gravity(value=DEFAULT_GRAVITY) -> None:
    """Pull every moving object along y with acceleration ``value`` (default -9.81: down).

    Takes effect at once, also in the middle of a run.
    """
    STATE.gravity = finite("gravity", "value", value)
    if STATE.has_world:
        STATE.world.set_gravity((0.0, STATE.gravity))


def elasticity(e) -> None:
    """Elasticity of every object that has none of its own (default 0.98), now and later."""
    e = finite("elasticity", "e", e)
    if not 0.0 <= e <= 1.0:
        raise ValueError(f"elasticity: e must be between 0.0 and 1.0, got {e!r}")
    STATE.elasticity = e
    for obj in STATE.shapes:
        if obj._own_elasticity is None and obj._body is not None:
            STATE.world.set_elasticity(obj._body, e)


def velocity_damping(factor=VELOCITY_DAMPING) -> None:
    """How ``get_xvel``, ``get_yvel``, ``put_xvel`` and ``put_yvel`` damp the object, now and later.

    The original PGE multiplied both velocity components by 0.98 (and set components below
    0.01 to zero) on every such read or write, and its games are tuned against that: a
    callback doing ``put_xvel(get_xvel() * 1.15)`` nets about 1.06 there. pge does the same
    by default. ``velocity_damping(1.0)`` makes reads and writes exact (a read then never
    changes anything); any factor in (0, 1] may be given. Not a name of the original module.
    """
    factor = finite("velocity_damping", "factor", factor)
    if not 0.0 < factor <= 1.0:
        raise ValueError(f"velocity_damping: factor must be in (0.0, 1.0], got {factor!r}")
    STATE.damping = factor


def get_time() -> float:
    """Simulation time in seconds; inside a callback, the time of its event."""
    return STATE.now()


# -------------------------------------------------------------- recording


def record() -> None:
    """Record the simulation into ``output.pgerec`` in the working directory (or the file given
    to ``run_options``), from the next ``run()`` on (nothing is written unless this is called)."""
    STATE.record_requested = True
    if STATE.depth > 0 and STATE.recorder is None:
        _start_recording()


def finish_record() -> None:
    """Close the recording (if one is being written)."""
    STATE.record_requested = False
    if STATE.recorder is not None:
        recorder, STATE.recorder = STATE.recorder, None
        recorder.close()


def _start_recording() -> None:
    from pge.recording import Recorder

    world = STATE.world
    if world.frame_rate != STATE.fps:
        world.frame_rate = STATE.fps
    STATE.record_path = STATE.record_target or RECORDING_NAME
    STATE.recorder = Recorder(world, STATE.record_path)


@atexit.register
def _close_recording() -> None:
    if STATE.recorder is not None:
        finish_record()


# ---------------------------------------------------------------- running


def run_options(record=None, until=None) -> None:
    """Settings a runner imposes on a script (``pge run --record FILE --until T``); not a PGE name.

    ``record``: record to this file, as if the script had called ``record()``
    (a ``record()`` of the script writes there too). ``until``: no ``run()``
    goes past simulated time ``until`` seconds, whatever the script asks for:
    the run that reaches it returns there and the script goes on (to print its
    results, say); a later ``run()`` ends the script with ``SystemExit(0)``, so a
    game that calls ``run()`` in a loop stops too. ``None`` leaves a setting as
    it is; ``reset()`` clears both.
    """
    if until is not None:
        until = finite("run_options", "until", until)
        if until < 0.0:
            raise ValueError(f"run_options: until must not be negative, got {until!r}")
        STATE.until = until
    if record is not None:
        STATE.record_target = str(record)
        STATE.record_requested = True  # what record() does outside a run


def run(t=-1) -> None:
    """Run ``t`` more seconds of simulated time (``-1``: until the window is closed; headless,
    30 seconds). May be called again to go on where it stopped.

    Raises ValueError if a moving object has no mass, RuntimeError when
    called from inside a callback.
    """
    if headless():
        runbatch(t)
    else:
        runpy(t)


def runbatch(t) -> None:
    """Run ``t`` more simulated seconds without a window, as fast as possible (``t < 0``: 30)."""
    t = finite("runbatch", "t", t)
    if t < 0.0:
        t = BATCH_SECONDS
    if STATE.display is None:
        STATE.display = NullDisplay()
    world = _start("runbatch")
    _go(world, world.time + t, windowed=False)


def runpy(t=-1) -> None:
    """Run ``t`` more simulated seconds in a pygame window paced by the wall clock (``t < 0``: until
    the window is closed). Headless (PGE_HEADLESS=1) this is ``runbatch(t)``."""
    if is_headless():
        runbatch(t)
        return
    t = finite("runpy", "t", t)
    world = _start("runpy")
    if STATE.display is None or not STATE.display.draws:
        STATE.display = _open_window()
    STATE.pacer = frames.Pacer(world.time, STATE.slow)
    frames.compose(STATE.display)
    _go(world, float("inf") if t < 0.0 else world.time + t, windowed=True)


def _open_window():
    from pge.render.pygame_display import PygameDisplay, WindowError

    try:
        return PygameDisplay(STATE.resolution, STATE.fullscreen, f"pge {version_number}")
    except WindowError as error:
        raise RuntimeError(f"runpy: cannot open a window ({error}); set PGE_HEADLESS=1 to run without one") from None


def _start(name: str):
    if STATE.depth > 0:
        raise RuntimeError(f"{name}: cannot run the simulation from inside a callback or handler")
    STATE.commit()
    world = STATE.world
    if world.frame_rate != STATE.fps:
        world.frame_rate = STATE.fps
    if STATE.record_requested and STATE.recorder is None:
        _start_recording()
    return world


def _go(world, end: float, windowed: bool) -> None:
    if end > world.time >= STATE.until:
        raise SystemExit(0)  # the runner's limit (run_options) was reached: the simulation is over
    end = min(end, STATE.until)
    STATE.running = True
    STATE.windowed = windowed
    try:
        while world.time < end:
            world.run_until(min(end, world.time + 1.0))
    finally:
        STATE.running = False
        STATE.windowed = False


def _frame(frame) -> None:
    """Every World frame: count it; in a window, wait for its time, handle input, draw it."""
    STATE.frame_no += 1
    display = STATE.display
    if not STATE.windowed:
        STATE.delay = 0.0
        return
    pacer = STATE.pacer
    if STATE.delay > 0.0:
        pacer.pause(STATE.delay)
        STATE.delay = 0.0
    pacer.wait(frame.time)
    for happened in display.events():
        handler = STATE.handlers.get(happened.type)
        if handler is not None:
            STATE.call(handler, happened)
        elif display.is_quit(happened):
            raise SystemExit(0)
    frames.compose(display)


def _collision_frame(record) -> None:
    """With ``draw_collision(True, ...)``: an extra frame at each collision, the two objects
    drawn in the collision colour."""
    if not STATE.draw_actual or record.a is None or record.b is None:
        return
    STATE.frame_no += 1
    display = STATE.display
    if not STATE.windowed:
        return
    STATE.pacer.wait(record.time)
    colour = STATE.collision_colour or rgb(0.0, 0.0, 1.0)
    pair = (record.a.data["object"], record.b.data["object"])
    frames.compose(display, pair, frames.rgba(colour))


STATE.frame_handler = _frame
STATE.collision_handler = _collision_frame


def save_frame(path) -> None:
    """Write the frame last shown in the window to ``path`` (PNG for a .png name).

    Not part of the original API. Raises RuntimeError when no window is open
    (headless, or before the first ``run()``).
    """
    display = STATE.display
    if display is None or not display.draws:
        raise RuntimeError("save_frame: no window is open (headless, or run() has not started)")
    display.save(path)


# ---------------------------------------------------------------- input


def register_handler(function, pyeventlist) -> None:
    """Call ``function(pygame_event)`` for each event whose type is in ``pyeventlist``
    (e.g. ``[KEYDOWN]``); the last registration for a type wins. Handlers run between
    events in a window, never headless."""
    if not callable(function):
        raise TypeError(f"register_handler: function must be callable, got {function!r}")
    for kind in _event_types("register_handler", pyeventlist):
        STATE.handlers[kind] = function


def deregister_handler(pyeventlist) -> None:
    """Stop handling the event types in ``pyeventlist``; ValueError for one not registered."""
    kinds = _event_types("deregister_handler", pyeventlist)
    missing = [kind for kind in kinds if kind not in STATE.handlers]
    if missing:
        raise ValueError(f"deregister_handler: no handler is registered for event type(s) {missing}")
    for kind in kinds:
        del STATE.handlers[kind]


def _event_types(owner: str, pyeventlist) -> list[int]:
    try:
        kinds = list(pyeventlist)
    except TypeError:
        raise TypeError(f"{owner}: pyeventlist must be a list of pygame event types, got {pyeventlist!r}") from None
    for kind in kinds:
        if isinstance(kind, bool) or not isinstance(kind, int):
            raise TypeError(f"{owner}: pygame event types are integers, got {kind!r}")
    return kinds


# ---------------------------------------------------------------- frames


def get_frame_no() -> int:
    """Frames so far (periodic frames plus collision frames of ``draw_collision``)."""
    return STATE.frame_no


def local_fps() -> None:
    """Show ``fps N`` (frames in the last wall-clock second) at (0.8, 0.1), updated every second."""
    STATE.fps_frames = STATE.frame_no
    at_time(1.0, update_fps)


def update_fps(e, o) -> None:
    """The timer callback of ``local_fps``: replace the fps text and re-arm."""
    count = STATE.frame_no - STATE.fps_frames
    STATE.fps_frames = STATE.frame_no
    if STATE.fps_text is not None:
        STATE.fps_text.rm()
    STATE.fps_text = text(0.8, 0.1, f"fps {count}", white(), 50, 1)
    at_time(1.0, update_fps)


def delay(t) -> None:
    """Pause the window for ``t`` wall-clock seconds before the next frame (ignored headless)."""
    t = finite("delay", "t", t)
    if t < 0.0:
        raise ValueError(f"delay: t must not be negative, got {t!r}")
    STATE.delay += t


def draw_collision(actual, predict) -> None:
    """``actual``: draw an extra frame at every collision with both objects in the collision
    colour. ``predict`` is accepted and ignored (the original's prediction debug frames)."""
    STATE.draw_actual = bool(actual)
    STATE.draw_predict = bool(predict)
    if STATE.draw_actual and not STATE.collision_hook:
        STATE.world.on_collision(lambda record: STATE.collision_handler(record))
        STATE.collision_hook = True


def collision_colour(c) -> None:
    """Colour of the colliding objects in collision frames (default blue)."""
    if not is_colour(c):
        raise TypeError("first parameter to collision_colour is expected to be a colour")
    STATE.collision_colour = c
