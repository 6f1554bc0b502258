"""Engine-independent scene definitions.

Every function here returns plain, immutable data (floats and tuples) built
only from the standard library, so the same scene can be fed to the engine,
to the reference implementations in ``benchmarks/`` and to tests, and all of
them are guaranteed to start from bit-identical initial conditions.

Units are arbitrary but consistent: lengths in box units, times in seconds,
speeds in length units per second, masses in mass units.
"""

from __future__ import annotations

import math
import random
from dataclasses import dataclass

__all__ = ["DiscGas", "disc_gas", "PLACEMENT_GAP_FACTOR"]

#: Minimum clearance between the surfaces of any two discs, and between any
#: disc and a box edge, at placement time, as a fraction of the disc radius.
#: 1e-3 is far above floating-point rounding of positions (~1e-16 of the box
#: size) and above any plausible contact tolerance, so no consumer ever sees
#: an initial contact or overlap, yet it is negligible next to the free space
#: each disc has in its lattice cell (several radii at the usual densities),
#: so the jittered placement stays close to uniform.
PLACEMENT_GAP_FACTOR = 1e-3


@dataclass(frozen=True)
class DiscGas:
    """A gas of ``n`` equal hard discs in a rectangular box.

    Attributes:
        radius: radius shared by all discs (length units).
        positions: centre ``(x, y)`` of each disc at time 0 (length units).
        velocities: velocity ``(vx, vy)`` of each disc at time 0 (length
            units per second); every one has magnitude ``speed`` up to
            rounding.
        box: ``(x_min, y_min, x_max, y_max)`` of the walls (length units).
        speed: the common initial speed of the discs.
        seed: seed of the ``random.Random`` that generated the scene.
    """

    radius: float
    positions: tuple[tuple[float, float], ...]
    velocities: tuple[tuple[float, float], ...]
    box: tuple[float, float, float, float]
    speed: float
    seed: int

    @property
    def n(self) -> int:
        """Number of discs."""
        return len(self.positions)

    def kinetic_energy(self, mass: float = 1.0) -> float:
        """Total kinetic energy ``sum(m |v|^2 / 2)`` with every disc of ``mass``.

        Returns energy in mass * length^2 / s^2; equals
        ``n * mass * speed**2 / 2`` up to rounding.
        """
        return 0.5 * mass * math.fsum(vx * vx + vy * vy for vx, vy in self.velocities)


def disc_gas(
    n: int,
    area_fraction: float = 0.10,
    speed: float = 0.1129,
    seed: int = 0,
    box: tuple[float, float, float, float] = (0.0, 0.0, 1.0, 1.0),
) -> DiscGas:
    """Build a deterministic gas of ``n`` equal, non-overlapping discs.

    The disc radius is chosen so the discs cover ``area_fraction`` of the box:
    ``radius = sqrt(area_fraction * W * H / (pi * n))``.

    Placement: the box (shrunk by half a gap on every side) is split into a
    lattice of ``cols x rows`` equal cells, with ``cols * rows >= n`` chosen to
    make the smaller cell side as large as possible; for a square box this is
    ``ceil(sqrt(n))`` cells per side. ``n`` distinct cells are drawn at random
    and each disc is put uniformly at random inside its cell, far enough from
    the cell edges that any two disc surfaces, and any disc surface and wall,
    are at least ``PLACEMENT_GAP_FACTOR * radius`` apart.

    Velocities: every disc gets magnitude ``speed`` in a direction uniform on
    ``[0, 2 pi)``.

    Everything is drawn from one ``random.Random(seed)``, so equal arguments
    always give an identical scene (on any platform with IEEE doubles).

    Args:
        n: number of discs, at least 1.
        area_fraction: total disc area over box area, in ``(0, 0.5]``.
        speed: speed of every disc (length units per second), finite, >= 0.
        seed: seed of the random generator.
        box: ``(x_min, y_min, x_max, y_max)`` with ``x_max > x_min`` and
            ``y_max > y_min``, all finite.

    Returns:
        A frozen :class:`DiscGas`, discs ordered row by row through the
        lattice (bottom row first, left to right).

    Raises:
        ValueError: on any invalid argument, or if ``n`` discs at this area
            fraction do not fit on the lattice (only happens for a handful of
            discs at area fractions near 0.5, or for extremely thin boxes).
    """
    if isinstance(n, bool) or not isinstance(n, int):
        raise ValueError(f"n must be an integer, got {n!r}")
    if n < 1:
        raise ValueError(f"n must be at least 1, got {n}")
    area_fraction = float(area_fraction)
    if not (0.0 < area_fraction <= 0.5):
        raise ValueError(f"area_fraction must be in (0, 0.5], got {area_fraction!r}")
    speed = float(speed)
    if not math.isfinite(speed) or speed < 0.0:
        raise ValueError(f"speed must be finite and >= 0, got {speed!r}")
    if len(box) != 4:
        raise ValueError(f"box must be (x_min, y_min, x_max, y_max), got {box!r}")
    x_min, y_min, x_max, y_max = (float(v) for v in box)
    if not all(math.isfinite(v) for v in (x_min, y_min, x_max, y_max)):
        raise ValueError(f"box coordinates must be finite, got {box!r}")
    width, height = x_max - x_min, y_max - y_min
    if not (width > 0.0 and height > 0.0):
        raise ValueError(f"box is empty: width {width!r}, height {height!r}")

    radius = math.sqrt(area_fraction * width * height / (math.pi * n))
    gap = PLACEMENT_GAP_FACTOR * radius
    cols, rows = _lattice_shape(n, width - gap, height - gap)
    cell_w = (width - gap) / cols
    cell_h = (height - gap) / rows
    # Centre offsets inside a cell keep radius + gap/2 from its edges; the outer
    # cells additionally sit gap/2 inside the walls, so walls also get a full gap.
    clearance = radius + 0.5 * gap
    slack_x = cell_w - 2.0 * clearance
    slack_y = cell_h - 2.0 * clearance
    if slack_x < 0.0 or slack_y < 0.0:
        raise ValueError(
            f"{n} discs at area_fraction {area_fraction} do not fit on a "
            f"{cols}x{rows} placement lattice in this box; lower area_fraction"
        )

    rng = random.Random(seed)
    cells = sorted(rng.sample(range(cols * rows), n))
    origin_x = x_min + 0.5 * gap + clearance
    origin_y = y_min + 0.5 * gap + clearance
    positions = []
    for cell in cells:
        row, col = divmod(cell, cols)
        x = origin_x + col * cell_w + rng.random() * slack_x
        y = origin_y + row * cell_h + rng.random() * slack_y
        positions.append((x, y))
    velocities = []
    for _ in range(n):
        angle = rng.uniform(0.0, 2.0 * math.pi)
        velocities.append((speed * math.cos(angle), speed * math.sin(angle)))

    return DiscGas(
        radius=radius,
        positions=tuple(positions),
        velocities=tuple(velocities),
        box=(x_min, y_min, x_max, y_max),
        speed=speed,
        seed=seed,
    )


def _lattice_shape(n: int, width: float, height: float) -> tuple[int, int]:
    """Columns and rows (``cols * rows >= n``) maximising the smaller cell side."""
    best_cols, best_rows, best_side = 1, n, -1.0
    for cols in range(1, n + 1):
        rows = -(-n // cols)
        side = min(width / cols, height / rows)
        if side > best_side:
            best_cols, best_rows, best_side = cols, rows, side
    return best_cols, best_rows
