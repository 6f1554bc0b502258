"""The state of the classic ``pge`` module: one session per process, as in PGE.

PGE is a singleton API (``pge.circle(...)``, ``pge.run(10)``), so its state is
module-level: the ``World`` it drives, the objects in creation order, the
drawing levels, timers, input handlers, display settings. All of it lives in
one ``Session`` (``STATE``); ``reset()`` (exported as ``pge.classic.reset``)
closes any window and starts a fresh session, which is what tests need.

Objects join the World at *commit points* (``Session.commit``): the start of
``run()`` and the end of every callback or input handler. Until then an
object is *pending*: PGE scripts build an object in one statement
(``pge.circle(...).mass(1).velocity(1, 0)``), and committing after the
statement lets the World check the finished object (a mass for a moving
object, no overlap) without ever seeing a half-built one.
"""

from __future__ import annotations

import os

from pge.classic.constants import DEFAULT_ELASTICITY, DEFAULT_FPS, VELOCITY_DAMPING
from pge.geometry import check_number
from pge.world import World

__all__ = ["Session", "STATE", "reset", "world", "is_headless"]


class Session:
    """Everything the classic module remembers between calls."""

    def __init__(self) -> None:
        self._world: World | None = None
        self.device = None  # None until batch()/interactive()/run() choose: batch_d or pyg_d
        self.resolution = None  # (width, height) in pixels from display_set_mode
        self.fullscreen = False
        self.fps = DEFAULT_FPS
        self.slow = 1.0
        self.gravity = 0.0  # world gravity, y component
        self.elasticity = DEFAULT_ELASTICITY
        self.damping = VELOCITY_DAMPING  # velocity reads and writes multiply by this (1.0: off)
        self.shapes: dict = {}  # level-0 objects (pending or in the World), creation order
        self.springs: dict = {}  # spring objects (pge.classic.springs) in creation order
        self.levels: dict[int, dict] = {}  # level != 0 -> eye-candy objects in creation order
        self.pending: list = []  # objects waiting for the next commit point
        self.unfixed: set = set()  # objects released with unfix() since the last commit
        self.timers: dict[int, object] = {}  # pending timer id -> callback p(event, None)
        self.last_timer = 0  # largest timer id handed out
        self.handlers: dict[int, object] = {}  # pygame event type -> handler
        self.frame_no = 0
        self.draw_actual = False
        self.draw_predict = False
        self.collision_colour = None
        self.collision_hook = False  # world-wide collision callback registered
        self.record_requested = False
        self.recorder = None
        self.record_path = None
        self.record_target = None  # file record() writes (None: runloop.RECORDING_NAME); `pge run --record`
        self.until = float("inf")  # simulated time no run() goes past; `pge run --until`
        self.display = None  # a pge.render protocol object while a window is open
        self.pacer = None
        self.running = False
        self.windowed = False  # True while runpy runs: frames are paced, drawn, input read
        self.depth = 0  # > 0 while a user callback runs
        self.delay = 0.0
        self.fps_text = None
        self.fps_frames = 0
        self.generation = 0  # bumped whenever what is drawn changes (objects, colours)
        self.plan = None  # level-0 draw plan of pge.classic.frames, rebuilt when generation moves
        self.frame_handler = None  # set by pge.classic.runloop
        self.collision_handler = None

    # ---------------------------------------------------------------- the world

    @property
    def world(self) -> World:
        """The World this session drives, made on first use."""
        if self._world is None:
            self._world = World(gravity=(0.0, self.gravity), elasticity=self.elasticity, allow_overlap=True)
            self._world.on_frame(self._on_frame)
        return self._world

    @property
    def has_world(self) -> bool:
        """True once the World exists."""
        return self._world is not None

    def _on_frame(self, frame) -> None:
        if self.frame_handler is not None:
            self.frame_handler(frame)

    def now(self) -> float:
        """Simulation time (0 before the World exists)."""
        return 0.0 if self._world is None else self._world.time

    # ------------------------------------------------------------ commit points

    def commit(self) -> None:
        """Put pending objects into the World and check objects released since the last commit.

        Raises ValueError for a moving object without a mass (the object stays
        pending, so giving it a mass and running again works) or one the World
        refuses (overlap).
        """
        waiting, self.pending = self.pending, []
        for k, obj in enumerate(waiting):
            if not obj.deleted and obj._body is None:
                try:
                    obj._materialise()
                except Exception:
                    self.pending = waiting[k:] + self.pending
                    raise
        if self.unfixed:
            released, self.unfixed = self.unfixed, set()
            for obj in released:
                if not obj.deleted and not obj._fixed and obj._mass is None:
                    self.unfixed = released
                    raise ValueError(obj._no_mass_message())

    def call(self, function, *args):
        """Run a user callback, then commit what it created."""
        self.depth += 1
        try:
            result = function(*args)
        finally:
            self.depth -= 1
        self.commit()
        return result

    def changed(self) -> None:
        """Something drawn changed: frames rebuild their draw lists."""
        self.generation += 1


STATE = Session()


def world() -> World:
    """The current session's World."""
    return STATE.world


def is_headless() -> bool:
    """True if PGE_HEADLESS is set to a true value (1, true, yes, on)."""
    return os.environ.get("PGE_HEADLESS", "").strip().lower() in ("1", "true", "yes", "on")


def reset() -> None:
    """Forget everything: close the window and recording, start a new World on next use.

    Objects made before a reset belong to the old World and must not be used
    afterwards.
    """
    if STATE.recorder is not None:
        try:
            STATE.recorder.close()
        finally:
            STATE.recorder = None
    if STATE.display is not None:
        try:
            STATE.display.close()
        finally:
            STATE.display = None
    handlers = (STATE.frame_handler, STATE.collision_handler)
    STATE.__init__()
    STATE.frame_handler, STATE.collision_handler = handlers


def finite(owner: str, what: str, value) -> float:
    """``value`` as a finite float, or TypeError/ValueError naming ``owner`` and ``what``."""
    return check_number(owner, what, value)


def positive(owner: str, what: str, value) -> float:
    """``value`` as a positive finite float, or a TypeError/ValueError."""
    value = finite(owner, what, value)
    if value <= 0.0:
        raise ValueError(f"{owner}: {what} must be positive, got {value!r}")
    return value
