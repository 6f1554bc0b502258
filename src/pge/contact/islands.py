"""Which bodies form which island, when islands step, and when they sleep (Python side).

An island is a set of moving bodies in persistent contact with each other or with fixed
bodies. It is made when a collision is persistent (``pge.core.engine.joins``: the bodies'
acceleration would bring them back before they parted by the rest height), and grows when
another body joins it the same way. While awake, it steps every ``h`` seconds on one of the
World's internal timers (``pge.contact.island.step_island``); a body that touches nothing at a
step leaves it, and an island whose contacts fall into separate groups splits. An island whose
bodies all stay nearly still for ``SLEEP_TIME`` falls asleep: its bodies stop (no velocity, no
acceleration), make no events and are not stepped, until a collision, a World change to one of
its bodies or to a fixed body near it, or a new member wakes it.
"""

from __future__ import annotations

import math

import numpy as np

from pge.contact.island import contact_bodies, step_island
from pge.core import engine, grid
from pge.core import layout as L
from pge.core.tuning import SLEEP_OVERLAP, SLEEP_SPEED, SLEEP_TIME
from pge.toi import CIRCLE

_NO_KEYS = np.zeros(0, dtype=np.int64)
_NO_IMPULSES = np.zeros((0, 3))


def _grown(rows: np.ndarray, n: int) -> np.ndarray:
    """``rows`` with zero rows added up to ``n`` in all."""
    grown = np.zeros((n,) + rows.shape[1:])
    grown[: rows.shape[0]] = rows
    return grown


class Island:
    """One island: its bodies, its warm-start contacts, its timer and its sleep (``held``:
    the contacts and impulses it last fell asleep with)."""

    __slots__ = ("members", "keys", "impulses", "held", "timer", "asleep", "still_since")

    def __init__(self, members: list[int]) -> None:
        self.members = members
        self.keys = _NO_KEYS
        self.impulses = _NO_IMPULSES
        self.held = (_NO_KEYS, _NO_IMPULSES)
        self.timer: int | None = None
        self.asleep = False
        self.still_since: float | None = None


class Islands:
    """The islands of one World."""

    def __init__(self, world, step: float) -> None:
        self.world = world
        self.step = step
        self.islands: dict[int, Island] = {}
        self._next = 0
        self._local = np.full(64, -1, dtype=np.int64)
        # per body: its last step's push-out lift, and that step's start and end
        self._lift = np.zeros((64, 3))
        self._lift_span = np.zeros((64, 2))
        self.sweeps = 0  # solver sweeps over all steps (for benchmarks)

    # ------------------------------------------------------------------ queries

    def of(self, i: int) -> Island | None:
        """The island body ``i`` belongs to, or None."""
        k = int(self.world._state.I[i, L.ISLAND])
        return self.islands.get(k) if k >= 0 else None

    def asleep(self, i: int) -> bool:
        """Whether body ``i`` is in a sleeping island."""
        island = self.of(i)
        return island is not None and island.asleep

    def support(self, i: int) -> int:
        """The body that ``i`` presses on hardest: of its contacts at its island's last step
        (the ones it fell asleep with, while asleep), the other body of the pair whose points
        took the largest normal impulse; -1 if it is in no island or pressed on nothing."""
        island = self.of(i)
        if island is None:
            return -1
        # Until its first step after waking, an island's contacts are the ones it slept on.
        keys, impulses = (island.keys, island.impulses) if island.keys.shape[0] else island.held
        firsts, seconds = contact_bodies(keys)
        load: dict[int, float] = {}
        for a, b, impulse in zip(firsts.tolist(), seconds.tolist(), impulses[:, 0].tolist()):
            if i in (a, b) and impulse > 0.0:
                other = b if a == i else a
                load[other] = load.get(other, 0.0) + impulse
        return max(load, key=lambda other: (load[other], -other)) if load else -1

    # ------------------------------------------------------------------ changes

    def collided(self, a: int, b: int, how: float, t: float) -> float:
        """A collision of ``a`` and ``b`` at ``t`` touched an island or is persistent; ``how``
        is the engine's ``OUT_JOIN`` code. Wake the islands involved; ``JOIN``: make them one;
        ``ABSORB``: make them one and step it at once, its impact stage solving the impact
        (no impulse was applied) together with its contacts, and return the normal impulse
        the pair took (0 otherwise); ``WAKE``: each island involved steps now. Its last step
        planned its contact forces and margins for the velocities before the impact, and its
        bodies' contacts with fixed bodies and with each other are not predicted: a body
        knocked towards a wall is stopped there only by a step."""
        I = self.world._state.I
        bodies = [x for x in (a, b) if not I[x, L.FIXED]]
        for x in bodies:
            island = self.of(x)
            if island is not None and island.asleep:
                self._wake(int(I[x, L.ISLAND]), t)
        if how == L.ABSORB:
            k = self._merge(bodies, t)
            island = self.islands[k]
            self._cancel(island)
            self._step(k, t)
            return self._struck(island, a, b)
        if how == L.JOIN:
            self._merge(bodies, t)
            return 0.0
        for k in sorted({int(I[x, L.ISLAND]) for x in bodies if I[x, L.ISLAND] >= 0}):
            self._schedule(k, t)
        return 0.0

    @staticmethod
    def _struck(island: Island, a: int, b: int) -> float:
        """The normal impulse that the pair ``a``, ``b`` took in ``island``'s last impact stage."""
        firsts, seconds = contact_bodies(island.keys)
        pair = ((firsts == a) & (seconds == b)) | ((firsts == b) & (seconds == a))
        return float(island.impulses[pair, 2].sum())

    def _merge(self, bodies: list[int], t: float) -> int:
        I = self.world._state.I
        found = sorted({int(I[x, L.ISLAND]) for x in bodies if I[x, L.ISLAND] >= 0})
        if found:
            target = found[0]
            keep = self.islands[target]
        else:
            target = self._next
            self._next += 1
            keep = self.islands[target] = Island([])
        changed = []
        for k in found[1:]:
            other = self.islands.pop(k)
            self._cancel(other)
            keep.members.extend(other.members)
            changed.extend(other.members)
        for x in bodies:
            if I[x, L.ISLAND] < 0:
                keep.members.append(x)
                changed.append(x)
        for x in changed:
            I[x, L.ISLAND] = target
        keep.still_since = None
        if changed:
            # Pairs inside the island are no longer predicted: drop what was queued for them.
            self.world._touch(changed)
        self._schedule(target, t)
        return target

    def leave(self, i: int) -> None:
        """Take body ``i`` out of its island (removed or fixed)."""
        k = int(self.world._state.I[i, L.ISLAND])
        if k < 0:
            return
        island = self.islands[k]
        if island.asleep:
            self._wake(k, self.world.time)
        island.members.remove(i)
        state = self.world._state
        state.I[i, L.ISLAND] = -1
        self._unlift(i, self.world.time)
        engine.advance(state.F, i, self.world.time)  # free of its contact forces from now on
        state.F[i, L.AX] = state.F[i, L.FREE_AX]
        state.F[i, L.AY] = state.F[i, L.FREE_AY]
        state.F[i, L.ALPHA] = 0.0
        if not island.members:
            self._cancel(island)
            del self.islands[k]

    def wake_near(self, i: int) -> None:
        """Body ``i`` is about to change through the API: wake its island, or, for a fixed
        body, the sleeping islands near it. An awake island steps now: the contact forces its
        last step planned were for the motion before the change."""
        state = self.world._state
        now = self.world.time
        k = int(state.I[i, L.ISLAND])
        if k >= 0:
            if self.islands[k].asleep:
                self._wake(k, now)
            else:
                self._schedule(k, now)
            return
        if state.I[i, L.FIXED] and any(island.asleep for island in self.islands.values()):
            count = grid.gather(state.S, i, self.world._extent(i))
            for j in state.scratch[:count].tolist():
                k = int(state.I[j, L.ISLAND])
                if k >= 0 and self.islands[k].asleep:
                    self._wake(k, now)

    # ------------------------------------------------------------------ steps

    def _schedule(self, k: int, t: float) -> None:
        island = self.islands[k]
        self._cancel(island)
        island.timer = self.world._at_time_internal(t, lambda when, k=k: self._step(k, when))

    def _unlift(self, i: int, t: float) -> None:
        """Take back from body ``i`` at ``t`` what its last step's push-out lift left in its
        velocity: all of it once the step has run its length, which is the step's own
        doing; the rest when the step is cut short (a collision, a World change, leaving
        the island), so that the push-out moves a body and never leaves it a speed."""
        start, until = self._lift_span[i]
        lift = self._lift[i]
        if t < until and (lift[0] != 0.0 or lift[1] != 0.0 or lift[2] != 0.0):
            F = self.world._state.F
            engine.advance(F, i, t)
            share = (until - t) / (until - start)
            F[i, L.VX] -= share * lift[0]
            F[i, L.VY] -= share * lift[1]
            F[i, L.OMEGA] -= share * lift[2]
        lift[:] = 0.0

    def _cancel(self, island: Island) -> None:
        if island.timer is not None:
            self.world._timers.pop(island.timer, None)
            island.timer = None

    def _step(self, k: int, t: float) -> None:
        island = self.islands.get(k)
        if island is None:
            return
        island.timer = None
        state = self.world._state
        if self._local.shape[0] < state.n:
            self._local = np.full(2 * state.n, -1, dtype=np.int64)
            self._lift = _grown(self._lift, 2 * state.n)
            self._lift_span = _grown(self._lift_span, 2 * state.n)
        members = np.asarray(island.members, dtype=np.int64)
        # A lift is all taken back once its step has run its length: only the bodies whose
        # step was cut short have some left.
        for i in members[self._lift_span[members, 1] > t].tolist():
            self._unlift(i, t)
        state.ensure_events(2 * members.shape[0] + 16)
        island.keys, island.impulses, labels, fastest, deepest, sweeps, length, lift = step_island(
            state.S, members, self._local, self.step, t, island.keys, island.impulses
        )
        self._lift[members] = lift
        self._lift_span[members, 0] = t
        self._lift_span[members, 1] = t + length
        self.sweeps += sweeps
        if labels[0] >= 0 and (labels == labels[0]).all():
            self._after_step(k, island, t, length, fastest, deepest)  # still one island
            return
        parts: dict[int, list[int]] = {}
        for i, label in zip(members.tolist(), labels.tolist()):
            if label >= 0:
                parts.setdefault(label, []).append(i)
        if not parts:
            del self.islands[k]
            return
        groups = sorted(parts.values(), key=lambda g: (-len(g), g[0]))
        island.members = groups[0]
        for group in groups[1:]:
            new = self._next
            self._next += 1
            self.islands[new] = Island(group)
            for i in group:
                state.I[i, L.ISLAND] = new
            self._schedule(new, t + length)
        self._after_step(k, island, t, length, fastest, deepest)

    def _after_step(self, k: int, island: Island, t: float, length: float, fastest: float, deepest: float) -> None:
        """Island ``k`` stepped at ``t``: it falls asleep if it has been still long enough,
        else its next step is due after ``length``."""
        if fastest < SLEEP_SPEED and deepest <= SLEEP_OVERLAP:
            if island.still_since is None:
                island.still_since = t
            elif t - island.still_since >= SLEEP_TIME:
                self._sleep(k)
                return
        else:
            island.still_since = None
        self._schedule(k, t + length)

    # ------------------------------------------------------------------ sleep

    def _sleep(self, k: int) -> None:
        island = self.islands[k]
        F = self.world._state.F
        now = self.world.time
        I = self.world._state.I
        for i in island.members:
            engine.advance(F, i, now)
            self._lift[i] = 0.0
            F[i, L.VX] = F[i, L.VY] = 0.0
            pull = math.hypot(F[i, L.FREE_AX], F[i, L.FREE_AY]) * F[i, L.REACH]
            if I[i, L.KIND] != CIRCLE or abs(F[i, L.OMEGA]) * F[i, L.REACH] < SLEEP_SPEED * math.sqrt(pull):
                # A circle spinning faster than a still body may touches nothing with friction
                # (the step did not count its spin): it spins on, which no contact feels.
                F[i, L.OMEGA] = 0.0
            F[i, L.AX] = F[i, L.AY] = F[i, L.ALPHA] = 0.0
        island.asleep = True
        island.held = (island.keys, island.impulses)
        island.keys = _NO_KEYS
        island.impulses = _NO_IMPULSES
        self._cancel(island)
        self.world._state.stats[L.S_SLEEPS] += 1
        self.world._touch(island.members)

    def _wake(self, k: int, t: float) -> None:
        island = self.islands[k]
        F = self.world._state.F
        for i in island.members:
            engine.advance(F, i, t)
            F[i, L.AX] = F[i, L.FREE_AX]
            F[i, L.AY] = F[i, L.FREE_AY]
            F[i, L.ALPHA] = 0.0
        island.asleep = False
        island.still_since = None
        self.world._state.stats[L.S_WAKES] += 1
        self.world._touch(island.members)
        self._schedule(k, t)

