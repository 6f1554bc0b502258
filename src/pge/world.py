"""The World: the public, Pythonic front door to the engine.

A World holds bodies (circles and convex polygons), callbacks and timers, and
drives the compiled event loop of ``pge.core.engine``. Everything the loop
needs lives in ``pge.core.state.EngineState`` arrays; this module validates
input at the boundary (errors name the object and the problem and leave the
world unchanged), turns compiled event records into ``pge.events`` records
and calls user callbacks.
"""

from __future__ import annotations

import math
import numbers
import warnings
from typing import Callable, Iterator

import numpy as np

from pge.bodies import Body
from pge.core import engine, grid, motion, overlap, queue
from pge.core import layout as L
from pge.core.state import EngineState
from pge.contact.islands import Islands
from pge.core.tuning import ISLAND_STEP, MIN_TICKS
from pge.errors import EventStormError, OverlapWarning, TooFastError
from pge.events import Collision, Frame, Stop, Timer
from pge.geometry import check_number, check_vector
from pge.response import RESTITUTION_RULES, restitution_rule
from pge.shapes import Circle, Polygon
from pge.toi import CIRCLE, POLYGON, outline_rows
from pge.watch import LeftWorldWarning, check_escapes

__all__ = ["World", "LeftWorldWarning"]

_INF = math.inf

#: overlap allowed between bodies when a run starts, relative to their bounding radii.
OVERLAP_TOLERANCE = 1e-9

_RULE_CODES = {name: code for code, name in enumerate(("min", "max", "mean", "geometric"))}
_OPTIONS = frozenset(
    ["mass", "velocity", "acceleration", "fixed", "elasticity", "friction", "angle", "angular_velocity", "name", "data"]
)



def _patch_record(out) -> tuple:
    """A face patch's ends and impulses from the loop's record (``Collision.patch``)."""
    return (
        (float(out[L.OUT_X1]), float(out[L.OUT_Y1]), float(out[L.OUT_L1])),
        (float(out[L.OUT_X2]), float(out[L.OUT_Y2]), float(out[L.OUT_L2])),
        float(out[L.OUT_JT]),
    )

class World:
    """A 2D world of circles and convex polygons moving under constant accelerations.

    Every contact between bodies in flight is predicted at its exact time. Bodies in
    persistent contact (resting, stacked, sliding, rolling, tipping) form islands whose
    contacts are solved together at short steps, while their contacts with everything
    else stay exact (docs/contact.md).

    Parameters:

    * ``gravity``: acceleration ``(gx, gy)`` of every moving body, in world
      units per second squared; default none. PGE's ``pge.gravity()`` is
      ``(0, -9.81)`` in a unit-square world with y up.
    * ``elasticity``: default elasticity of new bodies, 0.98 as in PGE.
    * ``restitution``: how two bodies' elasticities combine, one of
      ``"min"`` (default: the less elastic body decides), ``"max"``,
      ``"mean"``, ``"geometric"``. Each gives exactly ``e`` for two bodies of
      elasticity ``e``.
    * ``bounds``: ``(x0, y0, x1, y1)``, the region covered by the broad-phase
      grid; bodies may leave it (they are then found less efficiently).
      Default: the unit square.
    * ``frame_rate``: FRAME events per second, or None (default) for none.
    * ``cell_size``, ``skin``: broad-phase tuning (grid cell side; distance a
      body may travel before its swept box is renewed). Derived from the
      typical body size when the world first runs, unless given.
    * ``friction_rule``: how two bodies' friction coefficients combine, as
      ``restitution`` (default ``"max"``, so giving one body friction is
      enough).
    * ``rest_height``: a bounce that would rise less than this times the
      smaller bounding radius of the pair is persistent contact (default 1e-4):
      the two bodies join an island and rest, slide or roll on each other
      instead of bouncing for ever.
    * ``broadphase``: switches for measuring the broad phase, a dict with any of
      ``"short_circuit"`` (True: the sound bounding-circle test, the default;
      False: off; ``"lecture"``: the lecture's unsound test), ``"boxes"`` (the
      swept-box overlap check) and ``"grid"`` (False: every pair is a
      candidate); omitted keys are on. Switching a sound stage off only costs
      time: the events are bit-identical. See ``World.broadphase``.
    * ``allow_overlap``: False (default) refuses to run while two bodies
      overlap (ValueError naming them); True lets each overlapping pair pass
      through each other until it has separated, with one ``OverlapWarning``
      per pair, as PGE does (the classic ``pge`` module sets it).
    * ``contact_step``: the islands' step length in seconds (default 1/240): how
      often the contacts of bodies in persistent contact are solved; see
      docs/contact.md.

    A run raises ``pge.errors.TooFastError`` for a body too fast for the
    clock, and ``pge.errors.EventStormError`` for a run of events the clock
    cannot separate (docs/architecture.md, "Progress").

    Time starts at 0. ``run_until(t)`` processes every event up to ``t``;
    ``events(until)`` yields them one by one; ``time`` is the current time,
    at which positions and velocities are read.
    """

    def __init__(
        self,
        gravity=(0.0, 0.0),
        elasticity: float = 0.98,
        restitution: str = "min",
        bounds=(0.0, 0.0, 1.0, 1.0),
        frame_rate: float | None = None,
        cell_size: float | None = None,
        skin: float | None = None,
        friction_rule: str = "max",
        rest_height: float = 1e-4,
        allow_overlap: bool = False,
        broadphase=None,
        contact_step: float | None = None,
    ) -> None:
        self._gravity = check_vector("World", "gravity", gravity)
        self._default_elasticity = _check_elasticity("World", elasticity)
        restitution_rule(restitution)
        self._restitution = restitution
        try:
            x0, y0, x1, y1 = (check_number("World", "bounds", v) for v in bounds)
        except (TypeError, ValueError) as error:
            raise type(error)(f"World: bounds must be (x0, y0, x1, y1): {error}") from None
        if not (x1 > x0 and y1 > y0):
            raise ValueError(f"World: bounds must satisfy x0 < x1 and y0 < y1, got {bounds!r}")
        self._bounds = (x0, y0, x1, y1)
        self._cell_option = None if cell_size is None else _positive("World", "cell_size", cell_size)
        self._skin_option = None if skin is None else _positive("World", "skin", skin)
        self._state = EngineState()
        self._state.Q[L.RULE] = _RULE_CODES[restitution]
        if friction_rule not in _RULE_CODES:
            raise ValueError(f"World: friction_rule must be one of {sorted(_RULE_CODES)}, got {friction_rule!r}")
        self._friction_rule = friction_rule
        self._state.Q[L.FRICTION_RULE] = _RULE_CODES[friction_rule]
        self._state.P[L.REST_HEIGHT] = _positive("World", "rest_height", rest_height)
        self._state.P[L.OVERLAP_TOLERANCE] = OVERLAP_TOLERANCE
        if not isinstance(allow_overlap, bool):
            raise TypeError(f"World: allow_overlap must be True or False, got {allow_overlap!r}")
        self._allow_overlap = allow_overlap
        self._state.Q[L.BROADPHASE] = _broadphase_bits(broadphase)
        step = ISLAND_STEP if contact_step is None else _positive("World", "contact_step", contact_step)
        self._state.P[L.CONTACT_STEP] = step
        self._islands = Islands(self, step)
        self._handles: dict[int, Body] = {}
        self._primed = False
        self._movable_polygons = 0  # polygons neither fixed nor removed: which loop runs (_polygons)
        self._unchecked: set[int] = set()
        self._collision_callbacks: list[Callable] = []
        self._body_callbacks: dict[int, list[Callable]] = {}
        self._frame_callbacks: list[Callable] = []
        self._timers: dict[int, tuple] = {}
        self._watchers: dict[int, int] = {}  # body id -> how many internal collision watches
        self._collision_hooks: list[Callable] = []  # internal: called for watched bodies' collisions
        self._removal_hooks: list[Callable] = []  # internal: called with a body id before it goes
        self._springs = None  # pge.springs.SpringSystem, made by the first add_spring
        self._next_timer = 1
        self._frame_rate: float | None = None
        self._frame_epoch = 0
        self._frame_base = 0.0
        self._stop_requested = False
        if frame_rate is not None:
            self.frame_rate = frame_rate

    # ------------------------------------------------------------ world settings

    @property
    def time(self) -> float:
        """The current simulation time in seconds."""
        return float(self._state.P[L.TIME])

    @property
    def gravity(self) -> tuple[float, float]:
        """World gravity ``(gx, gy)``; assigning it calls ``set_gravity``."""
        return self._gravity

    @gravity.setter
    def gravity(self, value) -> None:
        self.set_gravity(value)

    def set_gravity(self, value) -> None:
        """Change the world's gravity now; every moving body is advanced and predicted again."""
        gravity = check_vector("World", "gravity", value)
        self._gravity = gravity
        moving = [i for i in self._handles if not self._state.I[i, L.FIXED]]
        for i in moving:
            self._islands.wake_near(i)
        for i in moving:
            engine.advance(self._state.F, i, self.time)
            self._update_acceleration(i)
        self._changed(moving)

    @property
    def frame_rate(self) -> float | None:
        """FRAME events per second, or None for none. Frames fall at ``start + k / rate``."""
        return self._frame_rate

    @frame_rate.setter
    def frame_rate(self, value) -> None:
        if value is not None:
            value = _positive("World", "frame_rate", value)
        self._frame_rate = value
        self._frame_epoch += 1  # frames queued at the old rate are dropped when they pop
        self._frame_base = self.time
        if value:
            self._push_frame(1)

    @property
    def elasticity(self) -> float:
        """Default elasticity given to new bodies; assignable (existing bodies keep theirs)."""
        return self._default_elasticity

    @elasticity.setter
    def elasticity(self, value) -> None:
        self._default_elasticity = _check_elasticity("World", value)

    @property
    def broadphase(self) -> dict:
        """Which broad-phase stages run: ``{"short_circuit": True | False | "lecture",
        "boxes": bool, "grid": bool}`` (all True by default).

        Assign a dict with any of these keys (omitted keys are on) to switch stages
        off and measure what each saves, on the same scene: ``"boxes": False``
        skips the swept-box overlap check (the prediction window stays
        ``[now, min(h_i, h_j)]``), ``"grid": False`` makes every other body a
        candidate (each pair is still predicted once per event),
        ``"short_circuit": False`` skips the bounding-circle test. None of these
        can change an event: they only skip work that cannot find a contact.
        ``"short_circuit": "lecture"`` replaces the sound test by the lecture's,
        which can cull real contacts (bodies then pass through each other); it
        exists to count what it misses. Takes effect from the next prediction.
        Raises TypeError or ValueError on anything else, leaving the world unchanged.
        """
        bits = int(self._state.Q[L.BROADPHASE])
        if bits & L.NO_SHORT_CIRCUIT:
            short_circuit = False
        elif bits & L.LECTURE_TEST:
            short_circuit = "lecture"
        else:
            short_circuit = True
        return {"short_circuit": short_circuit, "boxes": not bits & L.NO_BOXES, "grid": not bits & L.NO_GRID}

    @broadphase.setter
    def broadphase(self, value) -> None:
        self._state.Q[L.BROADPHASE] = _broadphase_bits(value)

    @property
    def bounds(self) -> tuple[float, float, float, float]:
        """The region ``(x0, y0, x1, y1)`` covered by the broad-phase grid (and drawn by default)."""
        return self._bounds

    @property
    def restitution(self) -> str:
        """Name of the rule combining two bodies' elasticities (see ``pge.response``)."""
        return self._restitution

    @property
    def bodies(self) -> tuple[Body, ...]:
        """The bodies in the world, in order of creation."""
        return tuple(self._handles.values())

    def __len__(self) -> int:
        return len(self._handles)

    @property
    def stats(self) -> dict[str, int]:
        """Counters since the world was made: events (valid events processed, of every
        kind), collisions, pair_collisions (both bodies moving), horizons (swept-box
        renewals), timers, frames, stale (invalidated queue entries skipped), grazes,
        candidates (pairs gathered from the grid), box_rejects, bound_rejects
        (short-circuit test), predictions (exact time-of-impact solves), hits, sleeps and
        wakes (of islands), joins (collisions that were persistent contact, or that an
        island took in), island_steps."""
        return {name: int(value) for name, value in zip(L.STAT_NAMES, self._state.stats)}

    @property
    def predictions_avoided(self) -> int:
        """Exact predictions the broad phase made unnecessary: candidate pairs rejected
        by the swept-box overlap or by the short-circuit bound."""
        stats = self._state.stats
        return int(stats[L.S_BOX_REJECTS] + stats[L.S_BOUND_REJECTS])

    # ------------------------------------------------------------------ bodies

    def add_circle(self, position, radius, **options) -> Body:
        """Add a circle centred at ``position`` with ``radius``; returns its Body.

        Options (keywords): ``mass`` (required before the world runs unless
        ``fixed``), ``velocity``, ``acceleration`` (own, on top of gravity),
        ``fixed`` (default False), ``elasticity`` (default the world's),
        ``angle``, ``angular_velocity``, ``name``, ``data`` (any user value).
        Bad values raise ValueError or TypeError naming the problem and leave
        the world unchanged.
        """
        owner = _owner("circle", options)
        shape = Circle(radius, owner)
        centre = check_vector(owner, "position", position)
        return self._add(shape, centre, owner, options)

    def add_polygon(self, vertices, **options) -> Body:
        """Add a convex polygon through ``vertices`` (world coordinates, either winding).

        The body's position is the polygon's area centroid. Options as for
        ``add_circle``. Non-convex, self-intersecting or degenerate outlines
        and non-finite values raise a ValueError naming the problem.
        """
        owner = _owner("polygon", options)
        shape, centroid = Polygon.from_points(vertices, owner)
        return self._add(shape, centroid, owner, options)

    def add_box(self, x, y, width, height, **options) -> Body:
        """Add an axis-aligned rectangle with lower-left corner ``(x, y)``."""
        owner = _owner("box", options)
        x = check_number(owner, "x", x)
        y = check_number(owner, "y", y)
        width = check_number(owner, "width", width)
        height = check_number(owner, "height", height)
        if width <= 0.0 or height <= 0.0:
            raise ValueError(f"{owner}: width and height must be positive, got {width!r} x {height!r}")
        corners = [(x, y), (x + width, y), (x + width, y + height), (x, y + height)]
        return self.add_polygon(corners, **options)

    def _add(self, shape, position, owner: str, options: dict) -> Body:
        unknown = set(options) - _OPTIONS
        if unknown:
            raise TypeError(f"{owner}: unknown option(s) {sorted(unknown)}")
        fixed = _check_flag(owner, "fixed", options.get("fixed", False))
        mass = options.get("mass")
        if mass is not None:
            mass = _positive(owner, "mass", mass)
        velocity = check_vector(owner, "velocity", options.get("velocity", (0.0, 0.0)))
        accel = check_vector(owner, "acceleration", options.get("acceleration", (0.0, 0.0)))
        elasticity = options.get("elasticity")
        elasticity = self._default_elasticity if elasticity is None else _check_elasticity(owner, elasticity)
        friction = _check_friction(owner, options.get("friction", 0.0))
        angle = check_number(owner, "angle", options.get("angle", 0.0))
        omega = check_number(owner, "angular_velocity", options.get("angular_velocity", 0.0))

        state = self._state
        i = state.new_body()
        F, I = state.F, state.I
        F[i] = 0.0
        I[i] = 0
        I[i, L.CELL] = I[i, L.NEXT] = I[i, L.PREV] = -1
        I[i, L.ISLAND] = I[i, L.LAST_OTHER] = -1
        F[i, L.FRICTION] = friction
        F[i, L.X], F[i, L.Y] = position
        F[i, L.T0] = self.time
        if fixed:
            F[i, L.HELD_VX], F[i, L.HELD_VY] = velocity
        else:
            F[i, L.VX], F[i, L.VY] = velocity
        F[i, L.OWN_AX], F[i, L.OWN_AY] = accel
        F[i, L.MASS] = math.nan if mass is None else mass
        F[i, L.ELASTICITY] = elasticity
        if fixed:
            F[i, L.HELD_OMEGA] = omega
        else:
            F[i, L.OMEGA] = omega
        F[i, L.REACH] = shape.bounding_radius
        I[i, L.FIXED] = int(fixed)
        I[i, L.ALIVE] = 1
        if isinstance(shape, Circle):
            I[i, L.KIND] = CIRCLE
            F[i, L.RADIUS] = shape.radius
        else:
            I[i, L.KIND] = POLYGON
            self._movable_polygons += 0 if fixed else 1
        self._set_inverse_mass(i, shape)
        if isinstance(shape, Polygon):
            rows = outline_rows(shape.vertices)
            I[i, L.OUTLINE_START] = state.add_outline(rows)
            I[i, L.OUTLINE_N] = rows.shape[0]
        self._orient(i, angle)
        self._update_acceleration(i)
        body = Body(self, i, shape, options.get("name"), options.get("data"))
        self._handles[i] = body
        if self._primed:
            try:
                self._fit_grid(i)
                self._touch([i], predict=False)
                self._check([i])
            except ValueError:
                self._forget(i)
                raise
            self._drain()
        else:
            self._unchecked.add(i)
        return body

    def _orient(self, i: int, angle: float) -> None:
        """Turn body ``i`` to ``angle`` now (its reference state must be at now)."""
        state = self._state
        F = state.F
        F[i, L.ANGLE] = angle
        if state.I[i, L.KIND] == CIRCLE:
            r = F[i, L.RADIUS]
            F[i, L.EXT_X0], F[i, L.EXT_Y0], F[i, L.EXT_X1], F[i, L.EXT_Y1] = -r, -r, r, r
            return
        motion.orient(F, state.I, state.OL, state.OB, i, F[i, L.T0])

    def remove(self, body: Body) -> None:
        """Take a body out of the world now; its handle becomes invalid.

        Safe inside callbacks; pending events that involve it are dropped.
        """
        body = self._own(body)
        i = body.id
        self._islands.wake_near(i)
        engine.advance(self._state.F, i, self.time)
        self._forget(i)

    def _forget(self, i: int) -> None:
        for hook in tuple(self._removal_hooks):
            hook(i)
        self._islands.leave(i)
        self._watchers.pop(i, None)
        state = self._state
        was_fixed = bool(state.I[i, L.FIXED])
        if state.I[i, L.KIND] != CIRCLE and not was_fixed:
            self._movable_polygons -= 1
        state.I[i, L.COUNT] += 1
        state.I[i, L.ALIVE] = 0
        grid.unlink(state.S, i)
        queue.drop_horizon(state.S, i)
        body = self._handles.pop(i)
        body.world = None
        self._body_callbacks.pop(i, None)
        self._unchecked.discard(i)
        state.I[i, L.NOTIFY] = 0
        if was_fixed and self._primed:
            state.rebuild_static()

    # ------------------------------------------------------------ state setters

    def _own(self, body) -> Body:
        if not isinstance(body, Body):
            raise TypeError(f"expected a Body, got {type(body).__name__} {body!r}")
        if body.world is not self:
            if body.world is None:
                raise ValueError(f"{body.label()} has been removed from its world")
            raise ValueError(f"{body.label()} belongs to another world")
        return body

    def _update_acceleration(self, i: int) -> None:
        """Free acceleration from own acceleration and gravity (the body must not be resting)."""
        F = self._state.F
        if self._state.I[i, L.FIXED]:
            F[i, L.FREE_AX] = F[i, L.FREE_AY] = 0.0
        else:
            F[i, L.FREE_AX] = F[i, L.OWN_AX] + F[i, L.SPRING_AX] + self._gravity[0]
            F[i, L.FREE_AY] = F[i, L.OWN_AY] + F[i, L.SPRING_AY] + self._gravity[1]
        F[i, L.AX] = F[i, L.FREE_AX]
        F[i, L.AY] = F[i, L.FREE_AY]
        F[i, L.ALPHA] = 0.0  # an island's contact forces are planned again at its next step

    def _set_inverse_mass(self, i: int, shape=None) -> None:
        """Inverse mass and inverse moment of inertia about the centroid (0 if fixed)."""
        F = self._state.F
        mass = F[i, L.MASS]
        fixed = self._state.I[i, L.FIXED]
        if fixed or math.isnan(mass):
            F[i, L.INV_MASS] = F[i, L.INV_INERTIA] = 0.0
            return
        F[i, L.INV_MASS] = 1.0 / mass
        shape = shape if shape is not None else self._handles[i].shape
        F[i, L.INV_INERTIA] = 1.0 / (mass * shape.inertia_per_mass)

    def _changed(self, ids) -> None:
        """Bodies whose motion changed now: invalidate, place and predict them again."""
        if self._primed and ids:
            self._touch(ids)

    def set_position(self, body: Body, position) -> None:
        """Move a body to ``position`` now, keeping its velocity.

        Raises ValueError (world unchanged) if it would overlap another body
        once the world has started running; before that, overlaps are reported
        by the first run.
        """
        body = self._own(body)
        x, y = check_vector(body.label(), "position", position)
        i = body.id
        F = self._state.F
        self._islands.wake_near(i)
        engine.advance(F, i, self.time)
        old = (F[i, L.X], F[i, L.Y])
        F[i, L.X], F[i, L.Y] = x, y
        self._after_geometry_change(i, lambda: _restore_xy(F, i, old))

    def set_angle(self, body: Body, angle) -> None:
        """Turn a body to ``angle`` radians about its centroid now (same rules as
        ``set_position``)."""
        body = self._own(body)
        angle = check_number(body.label(), "angle", angle)
        i = body.id
        self._islands.wake_near(i)
        engine.advance(self._state.F, i, self.time)
        old = float(self._state.F[i, L.ANGLE])
        self._orient(i, angle)
        self._after_geometry_change(i, lambda: self._orient(i, old))

    def _after_geometry_change(self, i: int, undo: Callable) -> None:
        if not self._primed:
            self._unchecked.add(i)
            return
        try:
            self._touch([i], predict=False)
            self._check([i])
        except ValueError:
            undo()
            self._touch([i])
            raise
        self._drain()

    def set_velocity(self, body: Body, velocity) -> None:
        """Give a body a new velocity now. A fixed body keeps it until it is released."""
        body = self._own(body)
        vx, vy = check_vector(body.label(), "velocity", velocity)
        i = body.id
        F = self._state.F
        if self._state.I[i, L.FIXED]:
            F[i, L.HELD_VX], F[i, L.HELD_VY] = vx, vy
            return
        self._islands.wake_near(i)
        engine.advance(F, i, self.time)
        F[i, L.VX], F[i, L.VY] = vx, vy
        self._changed([i])

    def apply_impulse(self, body: Body, impulse) -> None:
        """Change a moving body's velocity by ``impulse / mass`` now.

        Raises ValueError for a fixed body or one without a mass.
        """
        body = self._own(body)
        jx, jy = check_vector(body.label(), "impulse", impulse)
        i = body.id
        F = self._state.F
        if self._state.I[i, L.FIXED]:
            raise ValueError(f"{body.label()} is fixed and cannot take an impulse")
        if math.isnan(F[i, L.MASS]):
            raise ValueError(f"{body.label()} has no mass; give it one before applying an impulse")
        self._islands.wake_near(i)
        engine.advance(F, i, self.time)
        F[i, L.VX] += jx * F[i, L.INV_MASS]
        F[i, L.VY] += jy * F[i, L.INV_MASS]
        self._changed([i])

    def set_acceleration(self, body: Body, acceleration) -> None:
        """Set a body's own constant acceleration (added to gravity) from now on."""
        body = self._own(body)
        ax, ay = check_vector(body.label(), "acceleration", acceleration)
        i = body.id
        F = self._state.F
        self._islands.wake_near(i)
        engine.advance(F, i, self.time)
        F[i, L.OWN_AX], F[i, L.OWN_AY] = ax, ay
        self._update_acceleration(i)
        if not self._state.I[i, L.FIXED]:
            self._changed([i])

    def set_mass(self, body: Body, mass) -> None:
        """Set a body's mass (positive and finite)."""
        body = self._own(body)
        mass = _positive(body.label(), "mass", mass)
        self._islands.wake_near(body.id)
        self._state.F[body.id, L.MASS] = mass
        self._set_inverse_mass(body.id)

    def set_friction(self, body: Body, friction) -> None:
        """Set a body's Coulomb friction coefficient (0 or more; default 0, as in PGE)."""
        body = self._own(body)
        i = body.id
        self._state.F[i, L.FRICTION] = _check_friction(body.label(), friction)
        self._islands.wake_near(i)

    def set_elasticity(self, body: Body, elasticity) -> None:
        """Set a body's elasticity, between 0 and 1."""
        body = self._own(body)
        elasticity = _check_elasticity(body.label(), elasticity)
        self._islands.wake_near(body.id)
        self._state.F[body.id, L.ELASTICITY] = elasticity

    def set_angular_velocity(self, body: Body, omega) -> None:
        """Give a body an angular velocity in radians per second (anticlockwise) now. A fixed
        body keeps it until it is released."""
        body = self._own(body)
        omega = check_number(body.label(), "angular_velocity", omega)
        i = body.id
        F = self._state.F
        if self._state.I[i, L.FIXED]:
            F[i, L.HELD_OMEGA] = omega
            return
        self._islands.wake_near(i)
        engine.advance(F, i, self.time)
        F[i, L.OMEGA] = omega
        self._changed([i])

    def set_fixed(self, body: Body, fixed: bool = True) -> None:
        """Fix a body (immovable, infinitely heavy) or release it: it then moves on with the
        velocity it had when fixed (or was given since) and needs a mass before the next run."""
        body = self._own(body)
        i = body.id
        state = self._state
        F, I = state.F, state.I
        fixed = _check_flag(body.label(), "fixed", fixed)
        if fixed == bool(I[i, L.FIXED]):
            return
        self._islands.wake_near(i)
        engine.advance(F, i, self.time)
        if fixed:
            self._islands.leave(i)
            F[i, L.HELD_VX], F[i, L.HELD_VY] = F[i, L.VX], F[i, L.VY]
            F[i, L.HELD_OMEGA] = F[i, L.OMEGA]
            F[i, L.VX] = F[i, L.VY] = F[i, L.OMEGA] = 0.0
            grid.unlink(state.S, i)
        else:
            F[i, L.VX], F[i, L.VY] = F[i, L.HELD_VX], F[i, L.HELD_VY]
            F[i, L.OMEGA] = F[i, L.HELD_OMEGA]
            self._unchecked.add(i)
        if I[i, L.KIND] != CIRCLE:
            self._movable_polygons += -1 if fixed else 1
        I[i, L.FIXED] = int(fixed)
        self._set_inverse_mass(i)
        self._update_acceleration(i)
        if self._primed:
            if not fixed:
                state.rebuild_static()  # it leaves the static lists
                self._fit_grid(i)
            self._touch([i])

    # ------------------------------------------------------------------ springs

    def _spring_system(self):
        if self._springs is None:
            from pge.springs import SpringSystem

            self._springs = SpringSystem(self)
        return self._springs

    def add_spring(self, a: Body, b: Body, stiffness, damping=0.0, rest_length=None, two_sided: bool = False, name=None):
        """Join the centres of ``a`` and ``b`` with a spring; returns a ``pge.springs.Spring``.

        Hooke force ``stiffness * (length - rest_length)`` plus ``damping`` times
        the rate of change of the length, along the line of the centres.
        ``rest_length`` defaults to the current distance. Tension-only (a rope
        that never pushes, as in PGE) unless ``two_sided``. The force is held
        constant over each ``spring_interval`` and every sprung body is
        predicted again at each refresh.
        """
        return self._spring_system().add(a, b, stiffness, damping, rest_length, two_sided, name)

    def remove_spring(self, spring) -> None:
        """Take a spring out of the world now."""
        self._spring_system().remove(spring)

    @property
    def springs(self) -> tuple:
        """The springs in the world, oldest first."""
        return () if self._springs is None else self._springs.springs

    @property
    def spring_interval(self) -> float:
        """Seconds over which spring forces are held constant (default: the frame period, or
        0.01 s without frames)."""
        return self._spring_system().interval

    @spring_interval.setter
    def spring_interval(self, value) -> None:
        self._spring_system().interval = value

    # ---------------------------------------------- internal hooks (springs)

    def _update_notify(self, i: int) -> None:
        self._state.I[i, L.NOTIFY] = int(i in self._body_callbacks or i in self._watchers)

    def _watch(self, i: int, on: bool) -> None:
        """Count an internal interest in body ``i``'s collisions (``_collision_hooks`` hear
        of them); ``on=False`` takes one back."""
        count = self._watchers.get(i, 0) + (1 if on else -1)
        if count > 0:
            self._watchers[i] = count
        else:
            self._watchers.pop(i, None)
        self._update_notify(i)

    def _at_time_internal(self, time: float, callback: Callable) -> int:
        """Call ``callback(time)`` at simulation ``time``: an engine-internal timer, neither
        yielded by ``events`` nor counted as a timer event. Returns its id (cancel with
        ``cancel_timer``)."""
        timer_id = self._next_timer
        self._next_timer += 1
        self._timers[timer_id] = (callback, None, True)
        self._state.ensure_events(1)
        queue.push(self._state.S, time, (L.TIMER << L.KIND_SHIFT) | timer_id, timer_id, 0, 0, 0, 0)
        return timer_id

    def _set_spring_accelerations(self, ids, ax, ay) -> None:
        """Give moving bodies ``ids`` the spring accelerations ``ax[k], ay[k]`` from now on
        (added to their own acceleration and gravity); bodies whose acceleration changes
        wake their islands and are predicted again."""
        state = self._state
        F, I = state.F, state.I
        changed: list[int] = []
        for i, x, y in zip(ids, ax, ay):
            i = int(i)
            if I[i, L.ALIVE] == 0 or I[i, L.FIXED]:
                continue
            if F[i, L.SPRING_AX] == x and F[i, L.SPRING_AY] == y:
                continue
            self._islands.wake_near(i)
            engine.advance(F, i, self.time)
            F[i, L.SPRING_AX], F[i, L.SPRING_AY] = x, y
            self._update_acceleration(i)
            changed.append(i)
        self._changed(changed)

    # --------------------------------------------------------------- callbacks

    def on_collision(self, callback: Callable, body: Body | None = None) -> Callable:
        """Call ``callback(event)`` after every collision, or every one involving ``body``.

        ``event`` is a ``pge.events.Collision``. Callbacks run after the bounce
        in registration order (world-wide ones first); changes they make apply
        at once, at the event's time. Returns the callback, so it can decorate.
        """
        if not callable(callback):
            raise TypeError(f"on_collision: callback must be callable, got {callback!r}")
        if body is None:
            self._collision_callbacks.append(callback)
        else:
            i = self._own(body).id
            self._body_callbacks.setdefault(i, []).append(callback)
            self._update_notify(i)
        return callback

    def off_collision(self, callback: Callable, body: Body | None = None) -> bool:
        """Unregister a collision callback given to ``on_collision`` (with the same ``body``);
        True if it was registered."""
        if body is None:
            callbacks = self._collision_callbacks
        else:
            i = self._own(body).id
            callbacks = self._body_callbacks.get(i, [])
        if callback not in callbacks:
            return False
        callbacks.remove(callback)
        if body is not None and not callbacks:
            self._body_callbacks.pop(body.id, None)
            self._update_notify(body.id)
        return True

    def off_frame(self, callback: Callable) -> bool:
        """Unregister a frame callback; True if it was registered."""
        if callback not in self._frame_callbacks:
            return False
        self._frame_callbacks.remove(callback)
        return True

    def on_frame(self, callback: Callable) -> Callable:
        """Call ``callback(frame)`` at every FRAME event (see ``frame_rate``)."""
        if not callable(callback):
            raise TypeError(f"on_frame: callback must be callable, got {callback!r}")
        self._frame_callbacks.append(callback)
        return callback

    def at_time(self, time, callback: Callable, data=None) -> int:
        """Call ``callback(timer_event)`` at simulation time ``time``; returns a timer id.

        ``time`` may not be in the past. Cancel with ``cancel_timer``.
        """
        when = check_number("at_time", "time", time)
        if when < self.time:
            raise ValueError(f"at_time: time {when!r} is in the past (now {self.time!r})")
        if not callable(callback):
            raise TypeError(f"at_time: callback must be callable, got {callback!r}")
        timer_id = self._next_timer
        self._next_timer += 1
        self._timers[timer_id] = (callback, data, False)
        self._state.ensure_events(1)
        queue.push(self._state.S, when, (L.TIMER << L.KIND_SHIFT) | timer_id, timer_id, 0, 0, 0, 0)
        return timer_id

    def cancel_timer(self, timer_id: int) -> bool:
        """Cancel a pending timer; True if it was still pending."""
        return self._timers.pop(timer_id, None) is not None

    def stop(self) -> None:
        """Make the running ``run_until`` or ``events`` return after the current event."""
        self._stop_requested = True

    # ----------------------------------------------------------------- running

    def run_until(self, time) -> None:
        """Process every event up to and including ``time``, then set ``time``.

        Raises ValueError, before anything happens, if a moving body has no
        mass or two bodies overlap.
        """
        until = check_number("run_until", "time", time)
        if until < self.time:
            raise ValueError(f"run_until: time {until!r} is before the current time {self.time!r}")
        for _ in self._loop(until, False):
            pass

    def run(self, duration) -> None:
        """Run for ``duration`` more seconds of simulated time."""
        duration = check_number("run", "duration", duration)
        if duration < 0.0:
            raise ValueError(f"run: duration must not be negative, got {duration!r}")
        self.run_until(self.time + duration)

    def events(self, until=_INF) -> Iterator:
        """Process events up to ``until``, yielding each one as it happens.

        Yields ``Collision``, ``Timer`` and ``Frame`` records, then a ``Stop``
        at ``until`` (none if ``until`` is infinite and the queue runs dry).
        """
        if isinstance(until, bool) or not isinstance(until, numbers.Real):
            raise TypeError(f"events: until must be a number, got {type(until).__name__} {until!r}")
        until = float(until)
        if math.isnan(until) or until < self.time:
            raise ValueError(f"events: until must be a time not before now, got {until!r}")
        return self._loop(until, True)

    def _loop(self, until: float, emit: bool):
        self._prepare()
        state = self._state
        out = state.out
        self._stop_requested = False
        while True:
            notify_all = emit or bool(self._collision_callbacks)
            code = engine.run(state.S, until, notify_all, self._polygons())
            if code == L.DONE or code == L.EMPTY:
                if until != _INF:
                    state.P[L.TIME] = until
                check_escapes(self, 3 if emit else 4)  # at the end of a run: cheap, once per run
                if emit and until != _INF:
                    yield Stop(until)
                return
            if code == L.NEED_SPACE:
                state.ensure_events(0)
                continue
            if code == L.STORM:
                raise self._storm_error()
            if code == L.TOO_FAST:
                raise self._too_fast_error()
            record = None
            absorbed = False
            if code == L.JOINED:
                a = int(out[L.OUT_A])
                b = int(out[L.OUT_B])
                struck = self._islands.collided(a, b, float(out[L.OUT_JOIN]), float(out[L.OUT_TIME]))
                if out[L.OUT_JOIN] == L.ABSORB:
                    out[L.OUT_IMPULSE] = struck
                    absorbed = True
                I = state.I
                if out[L.OUT_IMPULSE] != 0.0 and (notify_all or I[a, L.NOTIFY] or I[b, L.NOTIFY]):
                    code = L.COLLIDED
            if code == L.COLLIDED:
                a = self._handles.get(int(out[L.OUT_A]))
                b = self._handles.get(int(out[L.OUT_B]))
                record = Collision(
                    float(out[L.OUT_TIME]),
                    a,
                    b,
                    (float(out[L.OUT_PX]), float(out[L.OUT_PY])),
                    (float(out[L.OUT_NX]), float(out[L.OUT_NY])),
                    float(out[L.OUT_IMPULSE]),
                    float(out[L.OUT_SPEED]),
                    absorbed,
                    _patch_record(out) if out[L.OUT_PATCH] == 1.0 and not absorbed else None,
                )
                self._notify(record)
            elif code == L.FIRED_TIMER:
                timer_id = int(out[L.OUT_ID])
                timer = self._timers.pop(timer_id, None)
                if timer is None:
                    continue  # cancelled
                if timer[2]:
                    timer[0](float(out[L.OUT_TIME]))
                    if self._stop_requested:
                        self._stop_requested = False
                        return
                    continue
                record = Timer(float(out[L.OUT_TIME]), timer_id, timer[1])
                state.stats[L.S_EVENTS] += 1
                state.stats[L.S_TIMERS] += 1
                timer[0](record)
            elif code == L.FIRED_FRAME:
                if int(out[L.OUT_EPOCH]) != self._frame_epoch:
                    continue  # queued before the frame rate changed
                index = int(out[L.OUT_ID])
                record = Frame(float(out[L.OUT_TIME]), index)
                state.stats[L.S_EVENTS] += 1
                state.stats[L.S_FRAMES] += 1
                self._push_frame(index + 1)
                for callback in tuple(self._frame_callbacks):
                    callback(record)
            if emit and record is not None:
                yield record
            if self._stop_requested:
                self._stop_requested = False
                return

    def _describe(self, i: int) -> str:
        """What body ``i`` is doing now, for an error message."""
        body = self._handles.get(i)
        if body is None:
            return "?"
        F, I = self._state.F, self._state.I
        (x, y), (vx, vy) = body.position, body.velocity
        text = f"{body.label()} at ({x:.6g}, {y:.6g}) moving at ({vx:.4g}, {vy:.4g})"
        if I[i, L.KIND] != 0 and F[i, L.OMEGA] != 0.0:
            text += f" spinning at {F[i, L.OMEGA]:.4g} rad/s"
        if I[i, L.FIXED]:
            text += " (fixed)"
        island = self._islands.of(i)
        if island is not None:
            text += f", in an island of {len(island.members)} bodies" + (" (asleep)" if island.asleep else "")
        return text

    def _storm_error(self) -> EventStormError:
        """The progress watch found a run of events the clock cannot separate."""
        state = self._state
        out, Q = state.out, state.Q
        when = float(out[L.OUT_TIME])
        ids = [int(out[k]) for k in (L.OUT_A, L.OUT_B) if int(out[k]) >= 0]
        names = ("collisions", "horizons", "timers", "frames")
        kinds = {name: int(Q[L.STORM_KINDS + k]) for k, name in enumerate(names) if Q[L.STORM_KINDS + k]}
        span = when - float(state.P[L.STORM_START])
        ticks = span / max(math.ulp(when), 5e-324)
        # The next run starts afresh, so that the caller may change the scene and go on.
        state.P[L.STORM_START] = -_INF
        state.Q[L.STORM_RUN] = 0
        made = ", ".join(f"{count} {name}" for name, count in kinds.items())
        where = "; ".join(self._describe(i) for i in ids) or "no body (timers or frames)"
        return EventStormError(
            f"event storm at time {when!r}: {sum(kinds.values())} events ({made}) within {span:.3g} s "
            f"({ticks:.3g} ticks of the clock), more than the clock can separate; the last involved {where}. "
            "Something is speeding a body up without bound or trapping it at one instant",
            when,
            tuple(self._handles[i] for i in ids if i in self._handles),
            kinds,
        )

    def _too_fast_error(self) -> TooFastError:
        """A body's travel step is shorter than the clock can resolve."""
        state = self._state
        i = int(state.Q[L.FAST_BODY])
        state.Q[L.FAST_BODY] = -1
        when = self.time
        F = state.F
        body = self._handles.get(i)
        vx, vy = body.velocity if body is not None else (0.0, 0.0)
        spin = abs(F[i, L.OMEGA]) * F[i, L.REACH] if state.I[i, L.KIND] != 0 else 0.0
        speed = math.hypot(vx, vy) + spin
        tick = math.ulp(when) if when > 0.0 else 5e-324
        return TooFastError(
            f"{self._describe(i)} at time {when!r} is faster than the world can represent: one tick of the "
            f"clock ({tick:.3g} s) carries it {speed * tick:.3g}, and its travel step {self._travel:.3g} takes "
            f"fewer than {MIN_TICKS:g} ticks, so its collisions cannot be resolved. Slow it down (something may "
            "be speeding it up without bound)",
            when,
            (body,) if body is not None else (),
            speed,
            tick,
        )

    def _notify(self, record: Collision) -> None:
        if self._collision_hooks and any(b is not None and b.id in self._watchers for b in (record.a, record.b)):
            for hook in tuple(self._collision_hooks):
                hook(record)
        for callback in tuple(self._collision_callbacks):
            callback(record)
        for body in (record.a, record.b):
            if body is not None:
                for callback in tuple(self._body_callbacks.get(body.id, ())):
                    callback(record)

    def _push_frame(self, index: int) -> None:
        when = self._frame_base + index / self._frame_rate
        self._state.ensure_events(1)
        queue.push(
            self._state.S, when, (L.FRAME << L.KIND_SHIFT) | index, index, self._frame_epoch, 0, 0, 0
        )

    # ------------------------------------------------------------ broad phase

    def _prepare(self) -> None:
        """Before a run: build the grid on the first, check new bodies on every run."""
        if not self._primed:
            self._prime()
        elif self._unchecked:
            self._check(sorted(self._unchecked))
            self._unchecked.clear()

    def _prime(self) -> None:
        state = self._state
        ids = sorted(self._handles)
        I, F = state.I, state.F
        moving = [i for i in ids if not I[i, L.FIXED]]
        reaches = sorted(F[i, L.REACH] for i in moving) or [0.05]
        typical = reaches[len(reaches) // 2]
        x0, y0, x1, y1 = self._bounds
        # Cells: a few typical bodies wide, but never more cells than about 4 per body.
        cell = self._cell_option or max(4.0 * typical, math.sqrt((x1 - x0) * (y1 - y0) / (4.0 * len(ids) + 4.0)))
        # Travel per horizon: four typical reaches, or as far as still fits the widest moving
        # body in one cell if that is further (the cells then grow to fit the travel). Longer
        # travel means fewer horizons and more candidates each; four reaches was the fastest
        # of 2, 3, 4 and 5 on the hard-disc gas at 1,000, 10,000 and 100,000 discs
        # (benchmarks/README.md, "Horizons against the skin").
        widest = max((self._extent(i) for i in moving), default=0.0)
        self._travel = self._skin_option or max(4.0 * typical, cell - widest)
        state.P[L.TRAVEL] = self._travel
        cell = max([cell] + [self._box_span(i) for i in moving])
        self._lay_grid(cell)
        for i in ids:
            engine.advance(F, i, self.time)
        self._touch(ids, predict=False)
        try:
            self._check(ids)
        except ValueError:
            state.set_grid(x0, y0, x1, y1, cell)  # drop what was filed
            state.Q[L.PENDING_N] = state.Q[L.PENDING_DONE] = 0
            raise
        self._primed = True
        self._unchecked.clear()
        self._drain()

    def _extent(self, i: int) -> float:
        """Widest the body's box can be at any angle (polygons may start to turn)."""
        return 2.0 * self._state.F[i, L.REACH]

    def _box_span(self, i: int) -> float:
        """Widest swept box body ``i`` can have: shape extent plus travel, with margin."""
        return (self._extent(i) + self._travel) * (1.0 + 1e-6) + 4.0 * self._state.P[L.MARGIN]

    def _lay_grid(self, cell: float) -> None:
        state = self._state
        state.P[L.MARGIN] = 1e-9 * cell
        state.set_grid(*self._bounds, cell)

    def _fit_grid(self, i: int) -> None:
        """Grow the grid's cells if a new moving body's box would not fit in one."""
        state = self._state
        if state.I[i, L.FIXED]:
            return
        span = self._box_span(i)
        if span <= state.P[L.CELL_SIZE]:
            return
        self._lay_grid(2.0 * span)
        self._touch([j for j in sorted(self._handles) if j != i])

    def _touch(self, ids, predict: bool = True) -> None:
        """Bodies whose motion or shape changed now: invalidate their events, give them new
        swept boxes and contact events, and (unless ``predict`` is false) predict them."""
        state = self._state
        array = np.asarray(sorted(set(ids)), dtype=np.int64)
        if array.shape[0] == 0:
            return
        state.ensure_events(2 * array.shape[0] + 16)
        engine.touch_group(state.S, array, array.shape[0])
        if state.I[array, L.FIXED].any():
            state.rebuild_static()
        if predict:
            self._drain()

    def _drain(self) -> None:
        """Run the queued predictions, growing the event arrays as needed."""
        state = self._state
        while not engine.drain_predictions(state.S, self._polygons()):
            state.ensure_events(0)

    def _polygons(self):
        """None while every polygon is fixed (no pair turns, no two polygons meet), else True:
        which compiled version of the event loop runs (``engine.run``). Counted where bodies
        are added, fixed, released and removed: the loop is entered at every island step."""
        return True if self._movable_polygons else None

    # ------------------------------------------------------------- validation

    def _check(self, ids) -> None:
        """Raise ValueError if a moving body of ``ids`` lacks a mass or overlaps a body (with
        ``allow_overlap``, excuse each overlapping pair instead, with a warning)."""
        state = self._state
        for i in ids:
            if not state.I[i, L.FIXED] and math.isnan(state.F[i, L.MASS]):
                raise ValueError(f"{self._handles[i].label()} is moving but has no mass; give it a mass or fix it")
        if self._allow_overlap:
            self._excuse_overlaps(ids)
            return
        i, j, depth = overlap.find_overlap(state.S, np.asarray(ids, dtype=np.int64), OVERLAP_TOLERANCE)
        if i >= 0:
            raise ValueError(
                f"{self._handles[i].label()} overlaps {self._handles[j].label()} by {depth:.3g} "
                f"at time {self.time!r}; bodies must not overlap when the world runs"
            )

    def _excuse_overlaps(self, ids) -> None:
        """Let every pair of ``ids`` (with any body) that overlaps now pass through each other
        until it has separated, warning once per pair."""
        state = self._state
        wanted = set(ids)
        known = {tuple(row) for row in state.excused[: int(state.Q[L.EXCUSED_N])]}
        F = state.F
        for a, b, depth in self.overlaps():
            pair = (min(a.id, b.id), max(a.id, b.id))
            if pair in known or not (a.id in wanted or b.id in wanted):
                continue
            if depth <= OVERLAP_TOLERANCE * (F[a.id, L.REACH] + F[b.id, L.REACH]):
                continue
            state.excuse(*pair)
            known.add(pair)
            warnings.warn(
                f"{a.label()} overlaps {b.label()} by {depth:.3g} at time {self.time!r}; they will not collide "
                "until they have separated",
                OverlapWarning,
                stacklevel=4,
            )

    def overlap_depth(self, a: Body, b: Body) -> float:
        """How deeply two bodies overlap now (positive) or how far apart they are (negative;
        for two polygons a lower bound on the distance)."""
        a, b = self._own(a), self._own(b)
        return float(overlap.overlap_depth(self._state.S, a.id, b.id))

    def overlaps(self, tolerance: float = 0.0) -> list[tuple[Body, Body, float]]:
        """Pairs of bodies (not both fixed) overlapping by more than ``tolerance`` now.

        A sweep over the bodies' current bounding boxes along x: O(N log N + pairs).
        """
        state = self._state
        F = state.F
        spans = []
        for i in self._handles:
            x, y = self._handles[i].position
            spans.append((x + F[i, L.EXT_X0], x + F[i, L.EXT_X1], y + F[i, L.EXT_Y0], y + F[i, L.EXT_Y1], i))
        spans.sort()
        found = []
        active: list = []
        for span in spans:
            active = [s for s in active if s[1] >= span[0]]
            for other in active:
                i, j = other[4], span[4]
                if state.I[i, L.FIXED] and state.I[j, L.FIXED]:
                    continue
                if other[2] > span[3] or other[3] < span[2]:
                    continue
                depth = float(overlap.overlap_depth(state.S, i, j))
                if depth > tolerance:
                    found.append((self._handles[i], self._handles[j], depth))
            active.append(span)
        return found

    def positions(self, bodies=None) -> np.ndarray:
        """Positions now of ``bodies`` (default: all, in creation order) as an (n, 2) array.

        Evaluated in closed form in bulk: the fast way to sample many bodies
        for drawing or recording.
        """
        if bodies is None:
            ids = np.fromiter(self._handles, dtype=np.int64, count=len(self._handles))
        else:
            ids = np.array([self._own(body).id for body in bodies], dtype=np.int64)
        return self._positions_of(ids)

    def _positions_of(self, ids: np.ndarray) -> np.ndarray:
        """``positions`` for body ids already known to be live (no checks: for samplers
        that hold a fixed list of bodies and re-check it when bodies change)."""
        F = self._state.F
        dt = self.time - F[ids, L.T0]
        out = np.empty((ids.shape[0], 2))
        out[:, 0] = F[ids, L.X] + (F[ids, L.VX] + 0.5 * F[ids, L.AX] * dt) * dt
        out[:, 1] = F[ids, L.Y] + (F[ids, L.VY] + 0.5 * F[ids, L.AY] * dt) * dt
        return out

    def kinetic_energy(self) -> float:
        """Total kinetic energy of the moving bodies now: translation plus rotation about
        the centroid (``I omega^2 / 2``)."""
        total = 0.0
        for body in self._handles.values():
            mass = body.mass
            if mass is not None and not body.is_fixed:
                vx, vy = body.velocity
                omega = body.angular_velocity
                total += 0.5 * mass * (vx * vx + vy * vy) + 0.5 * body.inertia * omega * omega
        return total

    def momentum(self) -> tuple[float, float]:
        """Total linear momentum of the moving bodies now."""
        px = py = 0.0
        for body in self._handles.values():
            mass = body.mass
            if mass is not None and not body.is_fixed:
                vx, vy = body.velocity
                px += mass * vx
                py += mass * vy
        return px, py

    # ------------------------------------------------------------ watching

    def picture(self, path=None, size=None, bounds=None):
        """A picture of the world now, as a ``PIL.Image``; written to ``path`` (PNG) if given.

        ``size`` is the longer side in pixels (default 800, the other side
        following the aspect of ``bounds``) or ``(width, height)``; ``bounds``
        ``(x0, y0, x1, y1)`` is the region shown (default: the world's bounds).
        A body's colour is ``body.data["colour"]`` (an RGB tuple) if given.
        """
        from pge.watch import picture

        return picture(self, path, size, bounds)

    def _repr_png_(self) -> bytes:
        """Jupyter shows a World as its picture now (400 pixels on the longer side)."""
        from pge.watch import png_bytes

        return png_bytes(self)

    def record(self, path, frame_rate=None, collisions: bool = True):
        """Start recording to ``path`` (a ``.pgerec`` file): returns a ``pge.recording.Recorder``.

        Use it as a context manager, ``with world.record("run.pgerec"):
        world.run_until(5)``, or call its ``close()``; watch the file with
        ``pge view``, ``pge play`` or ``pge export``.
        """
        from pge.recording import Recorder

        return Recorder(self, path, frame_rate=frame_rate, collisions=collisions)

    def animate(self, until, frame_rate=None):
        """Run to time ``until`` while recording, and return a ``pge.viewer.Animation``:
        in a notebook it plays inline; ``.save("run.html")`` writes it as a page.

        ``frame_rate`` defaults to the world's, else 30 frames per second.
        """
        from pge.watch import animate

        return animate(self, until, frame_rate)


def _restore_xy(F, i, old) -> None:
    F[i, L.X], F[i, L.Y] = old


def _owner(kind: str, options: dict) -> str:
    name = options.get("name")
    return kind if name is None else f"{kind} {name!r}"


_BROADPHASE_KEYS = ("short_circuit", "boxes", "grid")


def _broadphase_bits(value) -> int:
    """The Q[BROADPHASE] bits for a ``broadphase`` option (None: every stage on)."""
    if value is None:
        return 0
    if not isinstance(value, dict):
        raise TypeError(
            f"World: broadphase must be a dict with keys among {list(_BROADPHASE_KEYS)}, got {type(value).__name__}"
        )
    unknown = [key for key in value if key not in _BROADPHASE_KEYS]
    if unknown:
        raise ValueError(f"World: broadphase has unknown key(s) {unknown!r}; the keys are {list(_BROADPHASE_KEYS)}")
    bits = 0
    short_circuit = value.get("short_circuit", True)
    if isinstance(short_circuit, str):
        if short_circuit != "lecture":
            raise ValueError(
                f"World: broadphase['short_circuit'] must be True, False or 'lecture', got {short_circuit!r}"
            )
        bits |= L.LECTURE_TEST
    elif isinstance(short_circuit, (bool, np.bool_)):
        if not short_circuit:
            bits |= L.NO_SHORT_CIRCUIT
    else:
        raise TypeError(
            f"World: broadphase['short_circuit'] must be True, False or 'lecture', got {short_circuit!r}"
        )
    for key, bit in (("boxes", L.NO_BOXES), ("grid", L.NO_GRID)):
        on = value.get(key, True)
        if not isinstance(on, (bool, np.bool_)):
            raise TypeError(f"World: broadphase[{key!r}] must be True or False, got {on!r}")
        if not on:
            bits |= bit
    return bits


def _positive(owner: str, what: str, value) -> float:
    value = check_number(owner, what, value)
    if value <= 0.0:
        raise ValueError(f"{owner}: {what} must be positive, got {value!r}")
    return value


def _check_flag(owner: str, what: str, value) -> bool:
    if not isinstance(value, (bool, np.bool_)):
        raise TypeError(f"{owner}: {what} must be True or False, got {type(value).__name__} {value!r}")
    return bool(value)


def _check_friction(owner: str, value) -> float:
    value = check_number(owner, "friction", value)
    if value < 0.0:
        raise ValueError(f"{owner}: friction must not be negative, got {value!r}")
    return value


def _check_elasticity(owner: str, value) -> float:
    value = check_number(owner, "elasticity", value)
    if not 0.0 <= value <= 1.0:
        raise ValueError(f"{owner}: elasticity must be between 0 and 1, got {value!r}")
    return value


assert set(_RULE_CODES) == set(RESTITUTION_RULES)
