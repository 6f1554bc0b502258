"""Springs: Hooke's law plus damping along the line joining two bodies' centres.

A spring between bodies ``a`` and ``b`` with stiffness ``k``, damping ``d``
and rest length ``l0`` pulls on ``a`` with

    F_a = -(k (L - l0) + d dL/dt) u,    s = x_a - x_b,  L = |s|,  u = s / L,

and on ``b`` with ``-F_a``; a fixed end takes nothing. By default a spring is
*tension-only*, as in PGE: an elastic rope that exerts nothing at all (no
Hooke term, no damping) while ``L <= l0``. A ``two_sided`` spring also pushes.

A spring's force depends on where the bodies are, so motion under springs is
not a polynomial in time and its contacts cannot be predicted exactly. The
engine's motion stays piecewise polynomial instead: every spring acceleration
is held constant over one *refresh interval* ``h`` (default the frame period,
or 0.01 s without frames), and at every refresh each body whose acceleration
changed is advanced and predicted again, so its predicted collisions are
exact for the motion it actually follows.

Which constant? The acceleration for ``[t, t + h]`` is the spring force at
the *predicted midpoint* positions ``y = x + v h / 2`` (pure drift). With
constant acceleration ``a(y)`` over the interval,
``x(t + h) = x + v h + a h^2 / 2`` and ``v(t + h) = v + a h``, which is
exactly drift ``h/2``, kick ``h a(y)``, drift ``h/2``: the position-Verlet
(leapfrog) method at the refresh times. It is symplectic and time-reversible,
so an undamped oscillator keeps its energy (no drift, only an ``O(h^2)``
ripple) and its period is off by ``-(w h)^2 / 24`` relative, while sampling
the force at the start of the interval (PGE's choice) gains energy every step
(amplitude x ``exp(pi w h / 2)`` per period). The damping term uses the
relative speed along the spring at the middle of the interval, estimated
implicitly from every other force on the two ends (the trapezoidal rule for
the damper), which is stable for any ``d`` and keeps a resting system exactly
at rest. Numbers measured: docs/springs.md.

``Spring.when(length, callback)`` calls back once, at the first time the
length reaches ``length`` from either side. Between refreshes both ends move
with constant accelerations, so ``|s(t)|^2 - length^2`` is a quartic in time;
its first root before the next refresh (``pge.numerics.roots.first_descent``,
never later than the exact root) is scheduled as an engine-internal timer.
Every refresh, and every collision of either end, computes it again.
"""

from __future__ import annotations

import math
from typing import Any, Callable, NamedTuple

import numpy as np

from pge.bodies import Body
from pge.core import layout as L
from pge.geometry import check_number
from pge.numerics.roots import first_descent

__all__ = ["Spring", "SpringSystem", "LengthReached", "DEFAULT_INTERVAL", "check_spring_parameters"]

#: seconds over which spring forces are held constant when the world has no frame rate.
DEFAULT_INTERVAL = 0.01

_INF = math.inf

#: relative tolerance on ``length^2`` within which a spring counts as at a ``when`` length now.
AT_LENGTH = 1e-12


class LengthReached(NamedTuple):
    """A spring's length reached the ``length`` asked for with ``Spring.when``, at ``time``.

    ``watch_id`` is the id ``when`` returned; ``spring`` the ``Spring``.
    """

    time: float
    spring: Any
    length: float
    watch_id: int

    kind = "spring"


def check_spring_parameters(owner: str, stiffness, damping, rest_length, two_sided) -> tuple:
    """``(stiffness, damping, rest_length, two_sided)`` checked: stiffness and damping finite and
    not negative, rest length None or finite and not negative, two_sided True or False.

    Raises TypeError or ValueError naming ``owner`` and the bad parameter.
    """
    stiffness = check_number(owner, "stiffness", stiffness)
    if stiffness < 0.0:
        raise ValueError(f"{owner}: stiffness must not be negative, got {stiffness!r}")
    damping = check_number(owner, "damping", damping)
    if damping < 0.0:
        raise ValueError(f"{owner}: damping must not be negative, got {damping!r}")
    if rest_length is not None:
        rest_length = check_number(owner, "rest_length", rest_length)
        if rest_length < 0.0:
            raise ValueError(f"{owner}: rest_length must not be negative, got {rest_length!r}")
    if not isinstance(two_sided, (bool, np.bool_)):
        raise TypeError(f"{owner}: two_sided must be True or False, got {type(two_sided).__name__} {two_sided!r}")
    return stiffness, damping, rest_length, bool(two_sided)


class _Watch:
    """One pending ``when``: the length, the callback, which side of it the spring is on, and
    the internal timer scheduled for the crossing (if one is due before the next refresh)."""

    __slots__ = ("watch_id", "length", "callback", "side", "timer", "due")

    def __init__(self, watch_id: int, length: float, callback: Callable) -> None:
        self.watch_id = watch_id
        self.length = length
        self.callback = callback
        self.side = 0  # +1 longer than `length`, -1 shorter; 0 until first looked at
        self.timer = None
        self.due = _INF


class Spring:
    """A spring between the centres of two bodies; make one with ``World.add_spring``.

    Read-only views: ``a``, ``b`` (the bodies), ``stiffness`` (force per
    unit length), ``damping`` (force per unit speed), ``rest_length``,
    ``two_sided`` (False: a tension-only rope), ``length`` (distance between
    the centres now), ``alive``. ``name`` is any label of yours. Once the
    spring is removed (``World.remove_spring``, or either body removed) every
    view but ``alive`` raises ValueError.
    """

    __slots__ = (
        "_system", "_a", "_b", "_stiffness", "_damping", "_rest_length", "_two_sided", "_watches", "number", "name"
    )  # fmt: skip

    def __init__(self, system, number, a: Body, b: Body, stiffness, damping, rest_length, two_sided, name) -> None:
        self._system = system
        self.number = number
        self._a = a
        self._b = b
        self._stiffness = stiffness
        self._damping = damping
        self._rest_length = rest_length
        self._two_sided = two_sided
        self._watches: list[_Watch] = []
        self.name = name

    def label(self) -> str:
        """A short name for messages, e.g. ``spring 2 'rope'``."""
        return f"spring {self.number}" + (f" {self.name!r}" if self.name is not None else "")

    def _live(self):
        if self._system is None:
            raise ValueError(f"{self.label()} has been removed from its world")
        return self._system

    @property
    def alive(self) -> bool:
        """False once the spring has been removed."""
        return self._system is not None

    @property
    def a(self) -> Body:
        """The first body."""
        self._live()
        return self._a

    @property
    def b(self) -> Body:
        """The second body."""
        self._live()
        return self._b

    @property
    def stiffness(self) -> float:
        """Hooke constant ``k``: force per unit of stretch."""
        self._live()
        return self._stiffness

    @property
    def damping(self) -> float:
        """Damping coefficient ``d``: force per unit of the rate of change of the length."""
        self._live()
        return self._damping

    @property
    def rest_length(self) -> float:
        """Length at which the spring exerts no Hooke force."""
        self._live()
        return self._rest_length

    @property
    def two_sided(self) -> bool:
        """True if the spring also pushes when shorter than its rest length; False (PGE's
        behaviour) for a rope that only pulls."""
        self._live()
        return self._two_sided

    @property
    def length(self) -> float:
        """Distance between the two bodies' centres now."""
        self._live()
        (xa, ya), (xb, yb) = self._a.position, self._b.position
        return math.hypot(xa - xb, ya - yb)

    def when(self, length, callback: Callable) -> int:
        """Call ``callback(event)`` once, at the first time from now that the length is ``length``.

        Either direction counts (stretching or shortening through it). A length
        equal to ``length`` right now does not count: the spring must come back
        to it. ``event`` is a ``LengthReached(time, spring, length, watch_id)``;
        the world's time is then the crossing time, exact to a few units in the
        last place for the motion between two refreshes. Returns the watch id
        (drawn from the world's timer ids), which ``cancel_when`` takes.
        Raises ValueError for a length that is not positive and finite,
        TypeError for a callback that is not callable.
        """
        system = self._live()
        owner = f"{self.label()}: when"
        length = check_number(owner, "length", length)
        if length <= 0.0:
            raise ValueError(f"{owner}: length must be positive, got {length!r}")
        if not callable(callback):
            raise TypeError(f"{owner}: callback must be callable as callback(event), got {callback!r}")
        watch = _Watch(system._new_id(), length, callback)
        self._watches.append(watch)
        system._predict(self, watch, registering=True)
        return watch.watch_id

    def cancel_when(self, watch_id) -> bool:
        """Forget the pending ``when`` with this id; True if it was still pending."""
        self._live()
        for watch in self._watches:
            if watch.watch_id == watch_id:
                self._system._drop(self, watch)
                return True
        return False

    @property
    def pending(self) -> tuple:
        """Ids of the ``when`` calls still waiting, oldest first."""
        self._live()
        return tuple(w.watch_id for w in self._watches)

    def __repr__(self) -> str:
        if self._system is None:
            return f"<{self.label()} removed>"
        kind = "two-sided" if self._two_sided else "tension-only"
        return (
            f"<{self.label()} {kind} {self._a.label()} - {self._b.label()} k={self._stiffness!r} "
            f"d={self._damping!r} rest={self._rest_length!r}>"
        )


class _Table:
    """The live springs as arrays, for refreshing them all at once."""

    def __init__(self, springs) -> None:
        a = np.array([s._a.id for s in springs], dtype=np.int64)
        b = np.array([s._b.id for s in springs], dtype=np.int64)
        self.bodies, index = np.unique(np.concatenate([a, b]), return_inverse=True)
        self.ia = index[: len(springs)]
        self.ib = index[len(springs) :]
        self.k = np.array([s._stiffness for s in springs])
        self.d = np.array([s._damping for s in springs])
        self.rest = np.array([s._rest_length for s in springs])
        self.two = np.array([s._two_sided for s in springs], dtype=bool)
        self.slot = {int(i): n for n, i in enumerate(self.bodies)}


class SpringSystem:
    """All springs of one World and their refresh schedule; the World makes it on first use.

    The World's ``add_spring``, ``remove_spring``, ``springs`` and
    ``spring_interval`` are this object's ``add``, ``remove``, ``springs``
    and ``interval``.
    """

    def __init__(self, world) -> None:
        self.world = world
        self._springs: list[Spring] = []
        self._ends: dict[int, list[Spring]] = {}  # body id -> its springs
        self._interval: float | None = None  # None: follow the world's frame rate
        self._timer: int | None = None  # the pending refresh
        self._next: float | None = None  # its time
        self._table: _Table | None = None
        self._count = 0
        world._collision_hooks.append(self._collided)
        world._removal_hooks.append(self._body_removed)

    # ------------------------------------------------------------ settings

    @property
    def springs(self) -> tuple[Spring, ...]:
        """The live springs, oldest first."""
        return tuple(self._springs)

    @property
    def interval(self) -> float:
        """Seconds over which spring forces are held constant: the value set, or else the
        world's frame period (0.01 s without a frame rate). Setting it (positive, finite)
        refreshes every spring now if the world is running."""
        if self._interval is not None:
            return self._interval
        rate = self.world._frame_rate
        return 1.0 / rate if rate else DEFAULT_INTERVAL

    @interval.setter
    def interval(self, value) -> None:
        value = check_number("spring_interval", "interval", value)
        if value <= 0.0:
            raise ValueError(f"spring_interval: interval must be positive, got {value!r}")
        self._interval = value
        if self._timer is not None and self.world._primed and self._next > self.world.time:
            self.world.cancel_timer(self._timer)
            self._tick(self.world.time)

    # ----------------------------------------------------- adding, removing

    def add(self, a, b, stiffness, damping=0.0, rest_length=None, two_sided=False, name=None) -> Spring:
        """Join bodies ``a`` and ``b`` with a spring (see ``World.add_spring``); returns it.

        Raises TypeError or ValueError, with the world unchanged, for a body
        that is not a live Body of this world, the same body twice, or a bad
        parameter.
        """
        owner = "add_spring" if name is None else f"add_spring {name!r}"
        for what, body in (("a", a), ("b", b)):
            if not isinstance(body, Body):
                raise TypeError(f"{owner}: {what} must be a Body, got {type(body).__name__} {body!r}")
            if body.world is not self.world:
                where = "has been removed from its world" if body.world is None else "belongs to another world"
                raise ValueError(f"{owner}: {what} ({body.label()}) {where}")
        if a is b:
            raise ValueError(f"{owner}: a spring needs two different bodies, got {a.label()} twice")
        stiffness, damping, rest_length, two_sided = check_spring_parameters(
            owner, stiffness, damping, rest_length, two_sided
        )
        if rest_length is None:
            (xa, ya), (xb, yb) = a.position, b.position
            rest_length = math.hypot(xa - xb, ya - yb)
        self._count += 1
        spring = Spring(self, self._count, a, b, stiffness, damping, rest_length, two_sided, name)
        self._springs.append(spring)
        self._table = None
        for body in (a, b):
            self._ends.setdefault(body.id, []).append(spring)
            self.world._watch(body.id, True)
        if self._timer is None:
            # First spring (again): the first refresh is now, or when the world first runs; the
            # accelerations are in place already, so the bodies are predicted with them.
            self._next = self.world.time
            self._timer = self.world._at_time_internal(self._next, self._tick)
        self._apply([a.id, b.id])
        return spring

    def remove(self, spring) -> None:
        """Take ``spring`` out of the world now; its ends lose its force at once."""
        if not isinstance(spring, Spring):
            raise TypeError(f"remove_spring: expected a Spring, got {type(spring).__name__} {spring!r}")
        if spring._system is not self:
            where = "has been removed from its world" if spring._system is None else "belongs to another world"
            raise ValueError(f"remove_spring: {spring.label()} {where}")
        ends = [spring._a.id, spring._b.id]
        self._detach(spring)
        self._apply(ends)

    def _detach(self, spring: Spring) -> None:
        for watch in tuple(spring._watches):
            self._drop(spring, watch)
        self._springs.remove(spring)
        self._table = None
        for body in (spring._a, spring._b):
            attached = self._ends[body.id]
            attached.remove(spring)
            if not attached:
                del self._ends[body.id]
            self.world._watch(body.id, False)
        spring._system = None
        if not self._springs and self._timer is not None:
            self.world.cancel_timer(self._timer)
            self._timer = self._next = None

    def _body_removed(self, i: int) -> None:
        """World removal hook: a removed body takes its springs with it."""
        attached = self._ends.get(i)
        if not attached:
            return
        others = set()
        for spring in tuple(attached):
            others.update((spring._a.id, spring._b.id))
            self._detach(spring)
        others.discard(i)
        self._apply(sorted(others))

    # ------------------------------------------------------------ refreshing

    def _tick(self, time: float) -> None:
        """The refresh timer: hold new accelerations over the next interval, predict every
        ``when`` again."""
        self._timer = self._next = None
        if not self._springs:
            return
        self._next = time + self.interval
        self._timer = self.world._at_time_internal(self._next, self._tick)
        table = self._tables()
        self._apply(table.bodies)
        for spring in tuple(self._springs):
            for watch in tuple(spring._watches):
                self._predict(spring, watch)

    def _collided(self, record) -> None:
        """World collision hook: a sprung body changed velocity mid-interval. Its springs'
        forces are sampled again for the rest of the interval, and their ``when`` crossings
        predicted again."""
        hit = [body.id for body in (record.a, record.b) if body is not None and body.id in self._ends]
        if not hit:
            return
        affected = set(hit)
        for i in hit:
            for spring in self._ends[i]:
                affected.update((spring._a.id, spring._b.id))
        self._apply(sorted(affected))
        seen = set()
        for i in affected:
            for spring in tuple(self._ends.get(i, ())):
                if spring not in seen:
                    seen.add(spring)
                    for watch in tuple(spring._watches):
                        self._predict(spring, watch)

    def _tables(self) -> _Table:
        if self._table is None:
            self._table = _Table(self._springs)
        return self._table

    def _step(self) -> float:
        """Length of the interval the accelerations set now are held for."""
        now = self.world.time
        if self._next is not None and self._next > now:
            return self._next - now
        return self.interval  # the refresh is due now and will use the full interval

    def _apply(self, ids) -> None:
        """Set the spring accelerations of bodies ``ids`` (0 for one without springs) for the
        rest of the current interval."""
        ids = [int(i) for i in ids if int(i) in self.world._handles]
        if not ids:
            return
        if self._springs:
            table = self._tables()
            ax, ay = accelerations(self.world, table, self._step())
            slots = [table.slot.get(i, -1) for i in ids]
            out_x = [float(ax[n]) if n >= 0 else 0.0 for n in slots]
            out_y = [float(ay[n]) if n >= 0 else 0.0 for n in slots]
        else:
            out_x = out_y = [0.0] * len(ids)
        self.world._set_spring_accelerations(ids, out_x, out_y)

    # --------------------------------------------------------------- when()

    def _new_id(self) -> int:
        """A fresh id from the world's timer-id counter (so ``when`` ids never equal timer ids)."""
        world = self.world
        watch_id = world._next_timer
        world._next_timer += 1
        return watch_id

    def _drop(self, spring: Spring, watch: _Watch) -> None:
        spring._watches.remove(watch)
        if watch.timer is not None:
            self.world.cancel_timer(watch.timer)
            watch.timer = None

    def _predict(self, spring: Spring, watch: _Watch, registering: bool = False) -> None:
        """Schedule the first crossing of ``watch.length`` before the next refresh, if any.

        A crossing already scheduled for now is left to fire. If the spring is on
        the other side of the length than when last looked at (its motion was
        changed by a call the springs do not hear of, or rounding put the
        crossing a hair past the refresh), the crossing has happened: fire now.
        """
        world = self.world
        now = world.time
        if watch.timer is not None:
            if watch.due <= now:
                return
            world.cancel_timer(watch.timer)
            watch.timer = None
            watch.due = _INF
        coefficients = _length_quartic(world, spring._a.id, spring._b.id, watch.length)
        if abs(coefficients[0]) <= _at_length(coefficients[1], watch.length, now):
            # At the length now (a when() made in the callback of another at the same length, or
            # a refresh right at a crossing): which side it is on is the way it is heading.
            coefficients = (0.0,) + coefficients[1:]
        side = _side(coefficients)
        if registering or watch.side == 0:
            watch.side = side or 1
        elif side != 0 and side != watch.side:
            self._schedule(spring, watch, now)
            return
        horizon = (self._next - now) if self._next is not None else 0.0
        if horizon <= 0.0:
            return  # the refresh due now predicts it
        sign = float(watch.side)
        c0, c1, c2, c3, c4 = (sign * c for c in coefficients)
        t = first_descent(c0, c1, c2, c3, c4, horizon, False)
        if t < _INF:
            self._schedule(spring, watch, now + t)

    def _schedule(self, spring: Spring, watch: _Watch, time: float) -> None:
        watch.due = time
        watch.timer = self.world._at_time_internal(time, lambda t: self._fire(spring, watch, t))

    def _fire(self, spring: Spring, watch: _Watch, time: float) -> None:
        if watch not in spring._watches:
            return
        watch.timer = None
        spring._watches.remove(watch)
        watch.callback(LengthReached(time, spring, watch.length, watch.watch_id))


def _length_quartic(world, i: int, j: int, length: float) -> tuple:
    """Coefficients in ``tau`` (seconds from now) of ``|x_i - x_j|^2 - length^2`` while both
    bodies keep their present constant accelerations."""
    F = world._state.F
    now = world.time
    rel = []
    for column_x, column_v in ((L.X, L.VX), (L.Y, L.VY)):
        column_a = L.AX if column_x == L.X else L.AY
        dt_i = now - F[i, L.T0]
        dt_j = now - F[j, L.T0]
        p = (F[i, column_x] + (F[i, column_v] + 0.5 * F[i, column_a] * dt_i) * dt_i) - (
            F[j, column_x] + (F[j, column_v] + 0.5 * F[j, column_a] * dt_j) * dt_j
        )
        v = (F[i, column_v] + F[i, column_a] * dt_i) - (F[j, column_v] + F[j, column_a] * dt_j)
        a = F[i, column_a] - F[j, column_a]
        rel.append((float(p), float(v), float(a)))
    (px, vx, ax), (py, vy, ay) = rel
    return (
        (px * px + py * py) - length * length,
        2.0 * (px * vx + py * vy),
        (vx * vx + vy * vy) + (px * ax + py * ay),
        vx * ax + vy * ay,
        0.25 * (ax * ax + ay * ay),
    )


def _at_length(rate: float, length: float, now: float) -> float:
    """How far ``|s|^2 - length^2`` may be from 0 and still count as "at the length": the
    rounding of the squares (1e-12 relative) plus what a few ulps of the clock move it."""
    return AT_LENGTH * length * length + 16.0 * math.ulp(now) * abs(rate)


def _side(coefficients) -> int:
    """+1 if the spring is (or, when exactly at the length, is about to be) longer than the
    length, -1 if shorter, 0 if it stays exactly at it."""
    for c in coefficients:
        if c > 0.0:
            return 1
        if c < 0.0:
            return -1
    return 0


def accelerations(world, table: _Table, step: float) -> tuple[np.ndarray, np.ndarray]:
    """Spring accelerations of ``table.bodies`` to hold over the next ``step`` seconds.

    Forces are taken at the bodies' predicted midpoint positions
    ``x + v step / 2``; the damper sees the relative speed along the spring
    at the midpoint, estimated implicitly (trapezoidal rule) from every
    other acceleration of the two ends. Fixed bodies (and bodies without a
    mass) get 0.
    """
    state = world._state
    F, I = state.F, state.I
    ids = table.bodies
    now = world.time
    dt = now - F[ids, L.T0]
    vx = F[ids, L.VX] + F[ids, L.AX] * dt
    vy = F[ids, L.VY] + F[ids, L.AY] * dt
    half = 0.5 * step
    x = F[ids, L.X] + (F[ids, L.VX] + 0.5 * F[ids, L.AX] * dt) * dt + vx * half
    y = F[ids, L.Y] + (F[ids, L.VY] + 0.5 * F[ids, L.AY] * dt) * dt + vy * half
    inverse = F[ids, L.INV_MASS]
    moving = I[ids, L.FIXED] == 0
    gx, gy = world._gravity
    other_x = np.where(moving, F[ids, L.OWN_AX] + gx, 0.0)
    other_y = np.where(moving, F[ids, L.OWN_AY] + gy, 0.0)

    ia, ib = table.ia, table.ib
    sx = x[ia] - x[ib]
    sy = y[ia] - y[ib]
    length = np.hypot(sx, sy)
    apart = length > 0.0
    safe = np.where(apart, length, 1.0)
    ux = np.where(apart, sx / safe, 0.0)
    uy = np.where(apart, sy / safe, 0.0)
    stretch = length - table.rest
    active = table.two | (stretch > 0.0)  # a slack rope exerts nothing, damping included
    hooke = np.where(active, table.k * stretch, 0.0)

    n = ids.shape[0]
    elastic_x = _gather(ia, ib, -hooke * ux, n) * inverse
    elastic_y = _gather(ia, ib, -hooke * uy, n) * inverse
    ox = other_x + elastic_x
    oy = other_y + elastic_y
    closing = (vx[ia] - vx[ib]) * ux + (vy[ia] - vy[ib]) * uy
    pulled = (ox[ia] - ox[ib]) * ux + (oy[ia] - oy[ib]) * uy
    rate = (closing + half * pulled) / (1.0 + half * table.d * (inverse[ia] + inverse[ib]))
    force = hooke + np.where(active, table.d * rate, 0.0)
    ax = _gather(ia, ib, -force * ux, n) * inverse
    ay = _gather(ia, ib, -force * uy, n) * inverse
    return ax, ay


def _gather(ia, ib, on_a, n: int) -> np.ndarray:
    """Per-body sums of a per-spring quantity acting on end ``a`` (``b`` gets its opposite)."""
    return np.bincount(ia, weights=on_a, minlength=n) - np.bincount(ib, weights=on_a, minlength=n)
