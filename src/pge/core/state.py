"""The engine's arrays, their growth, and the grid's static part (Python side).

``EngineState.S`` is the ``State`` handed to every compiled function, a named tuple of
the arrays (compiled code reads ``S.F``, ``S.heap_time``, ...); it is rebuilt whenever an
array is replaced by a larger one.
"""

from __future__ import annotations

import math
from collections import namedtuple

import numpy as np

from pge.core import layout as L
from pge.core.tuning import STORM_LIMIT, STORM_PER_BODY


#: The engine state as compiled code sees it: bodies (``F`` floats, ``I`` ints, one row
#: each, columns in ``pge.core.layout``), polygon outlines turned (``OL``) and unturned
#: (``OB``), world parameters (``P`` floats, ``Q`` ints), the grid (``head``,
#: ``static_start``, ``static_items``), the event queue (by heap position ``heap_time``, and
#: ``heap_entry``: key and slot; ``slot_data``, ``free``), the counters of ``World.stats``
#: (``stats``), the record of the event that returned to Python (``out``), work space
#: (``scratch``), the bodies waiting to be predicted (``pending``), the pairs that
#: overlapped at the start (``excused``) and the moving bodies' horizons (a heap:
#: ``horizon_time`` by position; ``horizon_index``, the body at a position in column 0 and a
#: body's position in column 1).
State = namedtuple("State", ["F", "I", "OL", "P", "Q", "head", "static_start", "static_items", "heap_time",
                             "heap_entry", "slot_data", "free", "stats", "out", "scratch", "pending", "OB", "excused",
                             "horizon_time", "horizon_index"])


def heap_times(capacity: int) -> np.ndarray:
    """Zeroed float64 array for the queue's times, placed so that each node's four children
    (positions ``4 i + 1`` to ``4 i + 4``, ``pge.core.queue``) share one 32-byte block and so
    one cache line."""
    buffer = np.zeros(capacity + 4)
    skip = (-(buffer.ctypes.data + 8) % 32) // 8
    return buffer[skip : skip + capacity]


def aligned_rows(capacity: int, columns: int, dtype=np.float64) -> np.ndarray:
    """Zeroed ``(capacity, columns)`` array whose rows start on 64-byte boundaries (cache lines,
    for rows of a whole number of lines: ``pge.core.layout``)."""
    size = np.dtype(dtype).itemsize
    buffer = np.zeros(capacity * columns + 64 // size, dtype=dtype)
    skip = (-buffer.ctypes.data % 64) // size
    return buffer[skip : skip + capacity * columns].reshape(capacity, columns)


def horizon_index(capacity: int) -> np.ndarray:
    """The horizons' heap index (``pge.core.queue``): column 0 the body at each position,
    column 1 each body's position (-1: none)."""
    index = np.zeros((capacity, 2), dtype=np.int64)
    index[:, 1] = -1
    return index


class EngineState:
    """Arrays for bodies, outlines, the grid and the event queue, with room to grow."""

    def __init__(self, capacity: int = 64, event_capacity: int = 1024) -> None:
        self.n = 0  # body rows in use (removed bodies keep their rows)
        self.F = aligned_rows(capacity, L.NF)
        self.I = aligned_rows(capacity, L.NI, np.int64)
        self.I[:, L.CELL] = -1
        self.I[:, L.ISLAND] = -1
        self.I[:, L.LAST_OTHER] = -1
        self.OL = np.zeros((64, 5))  # polygon outlines turned to each body's ORIENT angle
        self.OB = np.zeros((64, 5))  # the same outlines unturned (angle 0): the rotating kernels' input
        self.n_outline = 0
        self.P = np.zeros(L.NP)
        self.Q = np.zeros(L.NQ, dtype=np.int64)
        self.head = np.full(1, -1, dtype=np.int64)
        self.static_start = np.zeros(2, dtype=np.int64)
        self.static_items = np.zeros(0, dtype=np.int64)
        self.heap_time = heap_times(event_capacity)
        self.heap_entry = np.zeros((event_capacity, 2), dtype=np.int64)
        self.slot_data = np.zeros((event_capacity, 5), dtype=np.int64)
        self.free = np.arange(event_capacity, dtype=np.int64)[::-1].copy()
        self.Q[L.FREE_N] = event_capacity
        self.Q[L.GRID_NX] = self.Q[L.GRID_NY] = 1
        self.P[L.CELL_SIZE] = self.P[L.INV_CELL] = 1.0
        self.P[L.STORM_START] = -np.inf
        self.Q[L.FAST_BODY] = -1
        self.stats = np.zeros(L.NSTATS, dtype=np.int64)
        self.out = np.zeros(L.NOUT)
        self.scratch = np.zeros(capacity, dtype=np.int64)
        self.pending = np.zeros(4 * capacity + 16, dtype=np.int64)
        self.excused = np.zeros((4, 2), dtype=np.int64)  # pairs that may overlap until they separate
        self.horizon_time = heap_times(capacity)
        self.horizon_index = horizon_index(capacity)
        self._update_min_free()
        self.refresh()

    def refresh(self) -> None:
        """Rebuild the ``State`` passed to compiled code."""
        self.S = State(*(getattr(self, name) for name in State._fields))

    def excuse(self, i: int, j: int) -> None:
        """Let bodies ``i`` and ``j``, which overlap now, pass until they have separated."""
        n = int(self.Q[L.EXCUSED_N])
        if n == self.excused.shape[0]:
            grown = np.zeros((2 * n, 2), dtype=np.int64)
            grown[:n] = self.excused
            self.excused = grown
            self.refresh()
        self.excused[n] = (min(i, j), max(i, j))
        self.Q[L.EXCUSED_N] = n + 1

    def _update_min_free(self) -> None:
        # One event touches at most every body once (a push each, its horizon); one
        # prediction pushes at most one event per other body.
        self.Q[L.MIN_FREE] = 3 * self.n + 16
        # N bodies may legitimately meet at one instant (a row of balls landing together).
        self.Q[L.STORM_CAP] = STORM_LIMIT + STORM_PER_BODY * self.n

    # ------------------------------------------------------------- growth

    def new_body(self) -> int:
        """Row index for a new body (arrays grow by doubling)."""
        if self.n == self.F.shape[0]:
            capacity = 2 * self.F.shape[0]
            F = aligned_rows(capacity, L.NF)
            F[: self.n] = self.F[: self.n]
            I = aligned_rows(capacity, L.NI, np.int64)
            I[: self.n] = self.I[: self.n]
            I[self.n :, L.CELL] = -1
            I[self.n :, L.ISLAND] = -1
            I[self.n :, L.LAST_OTHER] = -1
            self.F, self.I = F, I
            horizon_time = heap_times(capacity)
            horizon_time[: self.n] = self.horizon_time
            index = horizon_index(capacity)
            index[: self.n] = self.horizon_index
            self.horizon_time, self.horizon_index = horizon_time, index
            self.scratch = np.zeros(capacity, dtype=np.int64)
            pending = np.zeros(4 * capacity + 16, dtype=np.int64)
            pending[: self.pending.shape[0]] = self.pending
            self.pending = pending
        index = self.n
        self.n += 1
        self._update_min_free()
        self.ensure_events(0)
        self.refresh()
        return index

    def add_outline(self, rows: np.ndarray) -> int:
        """Store a polygon's unturned outline rows (in OB and OL); returns the first row's index."""
        needed = self.n_outline + rows.shape[0]
        if needed > self.OL.shape[0]:
            capacity = max(needed, 2 * self.OL.shape[0])
            OL = np.zeros((capacity, 5))
            OL[: self.n_outline] = self.OL[: self.n_outline]
            OB = np.zeros((capacity, 5))
            OB[: self.n_outline] = self.OB[: self.n_outline]
            self.OL, self.OB = OL, OB
        start = self.n_outline
        self.OL[start:needed] = rows
        self.OB[start:needed] = rows
        self.n_outline = needed
        self.refresh()
        return start

    def ensure_events(self, extra: int) -> None:
        """Make sure at least ``MIN_FREE + extra`` event slots are free."""
        want = int(self.Q[L.MIN_FREE]) + extra
        free_now = int(self.Q[L.FREE_N])
        if free_now >= want:
            return
        old = self.heap_time.shape[0]
        capacity = max(2 * old, old + want - free_now)
        grown = capacity - old
        heap_time = heap_times(capacity)
        heap_time[:old] = self.heap_time
        heap_entry = np.zeros((capacity, 2), dtype=np.int64)
        heap_entry[:old] = self.heap_entry
        slot_data = np.zeros((capacity, 5), dtype=np.int64)
        slot_data[:old] = self.slot_data
        free = np.zeros(capacity, dtype=np.int64)
        free[:free_now] = self.free[:free_now]
        free[free_now : free_now + grown] = np.arange(capacity - 1, old - 1, -1)
        self.heap_time, self.heap_entry, self.slot_data, self.free = heap_time, heap_entry, slot_data, free
        self.Q[L.FREE_N] = free_now + grown
        self.refresh()

    # -------------------------------------------------------------- the grid

    def set_grid(self, x0: float, y0: float, x1: float, y1: float, cell: float) -> None:
        """Lay a fresh grid of square cells over the rectangle (bodies must be re-placed)."""
        nx = max(1, math.ceil((x1 - x0) / cell))
        ny = max(1, math.ceil((y1 - y0) / cell))
        self.P[L.GRID_X0] = x0
        self.P[L.GRID_Y0] = y0
        self.P[L.CELL_SIZE] = cell
        self.P[L.INV_CELL] = 1.0 / cell
        self.Q[L.GRID_NX] = nx
        self.Q[L.GRID_NY] = ny
        self.head = np.full(nx * ny, -1, dtype=np.int64)
        self.I[: self.n, L.CELL] = -1
        self.I[: self.n, L.NEXT] = -1
        self.I[: self.n, L.PREV] = -1
        self.static_start = np.zeros(nx * ny + 1, dtype=np.int64)
        self.static_items = np.zeros(0, dtype=np.int64)
        self.refresh()

    def _cell(self, value: float, origin: float, count: int) -> int:
        f = (value - origin) * self.P[L.INV_CELL]
        if not f > 0.0:
            return 0
        if f >= count - 1:
            return count - 1
        return int(f)

    def rebuild_static(self) -> None:
        """Register every live fixed body's box in all the cells it covers."""
        nx = int(self.Q[L.GRID_NX])
        ny = int(self.Q[L.GRID_NY])
        x0 = self.P[L.GRID_X0]
        y0 = self.P[L.GRID_Y0]
        cells: list[list[int]] = [[] for _ in range(nx * ny)]
        F, I = self.F, self.I
        for i in np.flatnonzero((I[: self.n, L.FIXED] != 0) & (I[: self.n, L.ALIVE] != 0)):
            ix0 = self._cell(F[i, L.BOX_X0], x0, nx)
            ix1 = self._cell(F[i, L.BOX_X1], x0, nx)
            iy0 = self._cell(F[i, L.BOX_Y0], y0, ny)
            iy1 = self._cell(F[i, L.BOX_Y1], y0, ny)
            for ix in range(ix0, ix1 + 1):
                for iy in range(iy0, iy1 + 1):
                    cells[ix * ny + iy].append(int(i))
        counts = np.array([len(c) for c in cells], dtype=np.int64)
        self.static_start = np.zeros(nx * ny + 1, dtype=np.int64)
        np.cumsum(counts, out=self.static_start[1:])
        self.static_items = np.array([i for c in cells for i in c], dtype=np.int64)
        self.refresh()
