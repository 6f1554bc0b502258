"""Minimal event-driven molecular dynamics (EDMD) reference for hard discs.

This is the baseline the ``pge`` engine is measured against: the classic
design, written for speed in plain Python (standard library only).

* One binary heap (``heapq``) of predicted events; stale events are dropped
  lazily by per-disc collision counters (Sedgewick & Wayne): an event records
  its discs' counters when predicted and is void if either has changed.
* A uniform cell grid, cells at least one diameter wide, with cell-crossing
  events, so a disc only ever predicts collisions with discs in the 3x3 cells
  around it. A crossing does not change the velocity, so it bumps no counter
  and only predicts against the discs in the row/column of cells that just
  became adjacent.
* Hard box walls, hit times solved analytically; equal-mass elastic (e = 1)
  disc-disc collisions.
* Delayed states: each disc stores its position at its own time stamp and is
  advanced only when its velocity changes.

Run as a script for the standard case (N = 1000 discs, 10 simulated seconds):
``python benchmarks/edmd_reference.py`` with ``pge`` installed (or with
``PYTHONPATH=src`` from the repository root).
"""

from __future__ import annotations

import math
import time
from heapq import heappop, heappush

from pge.scenes import DiscGas, disc_gas

# Event kinds (the third field of an event); kinds >= 0 are the partner disc.
WALL_X, WALL_Y, CROSS_X, CROSS_Y = -1, -2, -3, -4

#: Smallest cell side, in disc diameters. Timed at area fraction 0.1 for
#: N = 1000 and N = 5000 over 1 to 4 diameters: 2 was fastest for both (~20%
#: faster than 1, where 85% of events are crossings; wider cells trade the
#: crossings for more pair predictions per collision and more stale events).
DEFAULT_CELL_FACTOR = 2.0


def run_reference(gas: DiscGas, duration: float, cell_factor: float = DEFAULT_CELL_FACTOR) -> dict:
    """Simulate ``gas`` for ``duration`` seconds and return event counts.

    Returns a dict with ``events`` (all valid events processed: pair
    collisions + wall collisions + cell crossings), ``pair_collisions``,
    ``wall_collisions``, ``cell_crossings``, ``stale`` (void events popped from
    the heap), ``wall_time_s`` (seconds of wall-clock time for the simulation,
    scene conversion excluded), ``kinetic_energy_start`` / ``_end`` (unit
    masses), and the final ``positions`` and ``velocities`` (lists of
    ``(x, y)`` tuples at time ``duration``).
    """
    if not (duration >= 0.0 and math.isfinite(duration)):
        raise ValueError(f"duration must be finite and >= 0, got {duration!r}")
    if not cell_factor >= 1.0:
        raise ValueError(f"cell_factor must be >= 1 (cells at least one diameter), got {cell_factor!r}")
    n = gas.n
    x = [p[0] for p in gas.positions]
    y = [p[1] for p in gas.positions]
    vx = [v[0] for v in gas.velocities]
    vy = [v[1] for v in gas.velocities]
    stamp = [0.0] * n  # time at which x, y are valid
    counter = [0] * n  # bumped whenever the disc's velocity changes
    radius = gas.radius
    sigma2 = (2.0 * radius) ** 2
    x_min, y_min, x_max, y_max = gas.box
    x_lo, x_hi, y_lo, y_hi = x_min + radius, x_max - radius, y_min + radius, y_max - radius
    nx = max(1, int((x_max - x_min) / (cell_factor * 2.0 * radius)))
    ny = max(1, int((y_max - y_min) / (cell_factor * 2.0 * radius)))
    cell_w, cell_h = (x_max - x_min) / nx, (y_max - y_min) / ny
    cells = [[] for _ in range(nx * ny)]
    # For each cell: the cell lists of its 3x3 neighbourhood, and of the strip
    # of three cells that becomes adjacent after a step to the right/left/up/down.
    def cell_lists(cxs, cys):
        """The lists of the cells at columns ``cxs`` x rows ``cys`` inside the grid."""
        return tuple(cells[cy * nx + cx] for cy in cys if 0 <= cy < ny for cx in cxs if 0 <= cx < nx)
    around = [cell_lists(range(cx - 1, cx + 2), range(cy - 1, cy + 2)) for cy in range(ny) for cx in range(nx)]
    strip = {
        (dx, dy): [cell_lists([cx + 2 * dx] if dx else range(cx - 1, cx + 2),
                              [cy + 2 * dy] if dy else range(cy - 1, cy + 2))
                   for cy in range(ny) for cx in range(nx)]
        for dx, dy in ((1, 0), (-1, 0), (0, 1), (0, -1))
    }
    cell_x = [min(nx - 1, int((xi - x_min) / cell_w)) for xi in x]
    cell_y = [min(ny - 1, int((yi - y_min) / cell_h)) for yi in y]
    for i in range(n):
        cells[cell_y[i] * nx + cell_x[i]].append(i)
    heap = []
    sqrt = math.sqrt
    end = float(duration)

    def predict_pairs(i, now, neighbour_cells):
        """Push collisions of disc ``i`` with every disc in ``neighbour_cells``."""
        dt = now - stamp[i]
        xi, yi, vxi, vyi, ci = x[i] + vx[i] * dt, y[i] + vy[i] * dt, vx[i], vy[i], counter[i]
        for members in neighbour_cells:
            for j in members:
                dvx, dvy = vx[j] - vxi, vy[j] - vyi
                dt = now - stamp[j]
                dx, dy = x[j] + vx[j] * dt - xi, y[j] + vy[j] * dt - yi
                b = dx * dvx + dy * dvy
                if b >= 0.0:  # separating or at rest relative to each other (also j == i)
                    continue
                c = dx * dx + dy * dy - sigma2
                if c <= 0.0:  # already touching/overlapping and approaching: collide now
                    heappush(heap, (now, i, j, ci, counter[j]))
                    continue
                disc = b * b - (dvx * dvx + dvy * dvy) * c
                if disc > 0.0:
                    hit = now + c / (sqrt(disc) - b)  # stable root: no cancellation as b < 0
                    if hit < end:
                        heappush(heap, (hit, i, j, ci, counter[j]))

    def predict_boundaries(i):
        """Push the next wall hit and cell crossing of disc ``i`` (just advanced)."""
        t0, xi, yi, vxi, vyi, ci = stamp[i], x[i], y[i], vx[i], vy[i], counter[i]
        tx = t0 + ((x_hi if vxi > 0.0 else x_lo) - xi) / vxi if vxi else math.inf
        ty = t0 + ((y_hi if vyi > 0.0 else y_lo) - yi) / vyi if vyi else math.inf
        wall_time, kind = (tx, WALL_X) if tx <= ty else (ty, WALL_Y)
        if wall_time < end:
            if wall_time < t0:  # already on (or a rounding error past) the wall
                wall_time = t0
            heappush(heap, (wall_time, i, kind, ci, 0))
        predict_crossing(i, t0)

    def predict_crossing(i, now):
        """Push the next cell crossing of disc ``i`` (none out of the outer cells)."""
        t0, vxi, vyi = stamp[i], vx[i], vy[i]
        cx, cy = cell_x[i], cell_y[i]
        tx = ty = math.inf
        if vxi > 0.0 and cx < nx - 1:
            tx = t0 + (x_min + (cx + 1) * cell_w - x[i]) / vxi
        elif vxi < 0.0 and cx > 0:
            tx = t0 + (x_min + cx * cell_w - x[i]) / vxi
        if vyi > 0.0 and cy < ny - 1:
            ty = t0 + (y_min + (cy + 1) * cell_h - y[i]) / vyi
        elif vyi < 0.0 and cy > 0:
            ty = t0 + (y_min + cy * cell_h - y[i]) / vyi
        cross_time, kind = (tx, CROSS_X) if tx <= ty else (ty, CROSS_Y)
        if cross_time < end:
            if cross_time < now:  # rounding, just after the previous crossing
                cross_time = now
            heappush(heap, (cross_time, i, kind, counter[i], 0))

    def advance(i, now):
        """Move disc ``i`` along its straight line to time ``now``."""
        dt = now - stamp[i]
        x[i] += vx[i] * dt
        y[i] += vy[i] * dt
        stamp[i] = now

    energy_start = 0.5 * math.fsum(a * a + b * b for a, b in zip(vx, vy))
    clock_start = time.perf_counter()
    for i in range(n):
        predict_pairs(i, 0.0, around[cell_y[i] * nx + cell_x[i]])
        predict_boundaries(i)
    pairs = walls = crossings = stale = 0
    while heap:
        now, i, kind, ci, cj = heappop(heap)
        if counter[i] != ci or (kind >= 0 and counter[kind] != cj):
            stale += 1
            continue
        if kind >= 0:
            j = kind
            advance(i, now)
            advance(j, now)
            dx, dy = x[j] - x[i], y[j] - y[i]
            impulse = (dx * (vx[j] - vx[i]) + dy * (vy[j] - vy[i])) / (dx * dx + dy * dy)
            vx[i] += impulse * dx
            vy[i] += impulse * dy
            vx[j] -= impulse * dx
            vy[j] -= impulse * dy
            counter[i] += 1
            counter[j] += 1
            predict_pairs(i, now, around[cell_y[i] * nx + cell_x[i]])
            predict_pairs(j, now, around[cell_y[j] * nx + cell_x[j]])
            predict_boundaries(i)
            predict_boundaries(j)
            pairs += 1
        elif kind <= CROSS_X:
            old = cell_y[i] * nx + cell_x[i]
            if kind == CROSS_X:
                step = (1, 0) if vx[i] > 0.0 else (-1, 0)
                cell_x[i] += step[0]
            else:
                step = (0, 1) if vy[i] > 0.0 else (0, -1)
                cell_y[i] += step[1]
            cells[old].remove(i)
            cells[cell_y[i] * nx + cell_x[i]].append(i)
            predict_pairs(i, now, strip[step][old])
            predict_crossing(i, now)
            crossings += 1
        else:
            advance(i, now)
            # Snap onto the wall so rounding can never leave the disc outside.
            if kind == WALL_X:
                x[i] = x_hi if vx[i] > 0.0 else x_lo
                vx[i] = -vx[i]
            else:
                y[i] = y_hi if vy[i] > 0.0 else y_lo
                vy[i] = -vy[i]
            counter[i] += 1
            predict_pairs(i, now, around[cell_y[i] * nx + cell_x[i]])
            predict_boundaries(i)
            walls += 1
    for i in range(n):
        advance(i, end)
    wall_time = time.perf_counter() - clock_start
    return {
        "events": pairs + walls + crossings,
        "pair_collisions": pairs,
        "wall_collisions": walls,
        "cell_crossings": crossings,
        "stale": stale,
        "wall_time_s": wall_time,
        "kinetic_energy_start": energy_start,
        "kinetic_energy_end": 0.5 * math.fsum(a * a + b * b for a, b in zip(vx, vy)),
        "positions": list(zip(x, y)),
        "velocities": list(zip(vx, vy)),
    }


if __name__ == "__main__":
    result = run_reference(disc_gas(1000), 10.0)
    for key, value in result.items():
        if key not in ("positions", "velocities"):
            print(f"{key:>22}: {value}")
    print(f"{'events_per_s':>22}: {result['events'] / result['wall_time_s']:.0f}")
