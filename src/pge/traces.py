"""Collision traces: record a run's collisions and tell where another run first departs from it.

Used to check ``World.broadphase`` switches: a sound stage switched off must
leave the trace bit-identical, and the lecture's unsound short-circuit test
shows up as a contact it misses (never reported, or reported late, once the
bodies already overlap). Plain Python; nothing here is on the engine's path.
"""

from __future__ import annotations

import math
from typing import NamedTuple

__all__ = ["CollisionLog", "Divergence", "compare_traces"]


class CollisionLog:
    """Records every collision of ``world`` as ``(time, a, b, px, py, nx, ny, impulse)``.

    ``a`` and ``b`` are body ids. With ``depths=True`` it also keeps, per collision,
    how deeply the two bodies overlap at the reported time (``World.overlap_depth``):
    a sound run reports contacts at first touch, so its depths are rounding-small;
    a depth of a visible fraction of the bodies' size is a contact found late.
    Registering it makes the world return to Python at every collision, so time
    runs without it.
    """

    def __init__(self, world, depths: bool = False) -> None:
        self.entries: list[tuple] = []
        self.depths: list[float] = []
        self._world = world
        self._with_depths = bool(depths)
        world.on_collision(self._record)

    def _record(self, event) -> None:
        (px, py), (nx, ny) = event.point, event.normal
        self.entries.append((event.time, event.a.id, event.b.id, px, py, nx, ny, event.impulse))
        if self._with_depths:
            # Positions do not jump at a bounce, so the depth now is the depth at contact.
            self.depths.append(self._world.overlap_depth(event.a, event.b))

    def late(self, tolerance: float) -> int:
        """How many collisions were reported with the bodies overlapping by more than ``tolerance``."""
        if not self._with_depths:
            raise ValueError("CollisionLog.late: the log was made without depths=True")
        return sum(1 for depth in self.depths if depth > tolerance)


class Divergence(NamedTuple):
    """Where a trace first departs from a reference trace (see ``compare_traces``).

    ``index``: position of the first differing entry (None: identical traces);
    ``fate``: ``"identical"``, ``"missed"`` (the reference's collision there never
    happens in the other run), ``"late"`` (it happens later, by ``delay`` seconds),
    ``"extra"`` (the other run reports a collision the reference does not have at
    that time, or goes on after the reference's last), ``"different"`` (same pair
    and time, other numbers); ``reference``: the reference's entry there (None if
    it has none).
    """

    index: int | None
    fate: str
    reference: tuple | None
    delay: float


def compare_traces(reference, other) -> Divergence:
    """The first place where ``other`` departs from ``reference``, and what happened there.

    Both are lists of ``(time, a, b, px, py, nx, ny, impulse)`` (``CollisionLog.entries``).
    Entries are compared exactly (bit for bit), as a sound broad-phase switch must
    leave them. After the first divergence the two runs follow different
    trajectories, so only that first difference says something about the test
    that caused it.
    """
    for index, (mine, theirs) in enumerate(zip(reference, other)):
        if mine == theirs:
            continue
        pair = {mine[1], mine[2]}
        if theirs[0] < mine[0]:
            return Divergence(index, "extra", mine, math.nan)
        if theirs[0] == mine[0] and {theirs[1], theirs[2]} == pair:
            return Divergence(index, "different", mine, 0.0)
        for later in other[index:]:
            if {later[1], later[2]} == pair:
                if later[0] == mine[0]:
                    return Divergence(index, "different", mine, 0.0)
                return Divergence(index, "late", mine, later[0] - mine[0])
        return Divergence(index, "missed", mine, math.nan)
    if len(reference) == len(other):
        return Divergence(None, "identical", None, 0.0)
    index = len(other)
    if index < len(reference):
        # The other run ended with no more collisions: the reference's next one never happened.
        return Divergence(index, "missed", reference[index], math.nan)
    return Divergence(len(reference), "extra", None, math.nan)
