"""The headless showcase: a mixed scene of circles and polygons under gravity.

Elasticity 1 everywhere, so energy is conserved exactly (up to rounding) and
the scene never comes to rest; the summary reports the energy drift.
"""

from __future__ import annotations

import math
import random
import time
from pathlib import Path

from pge.render.image import save_png
from pge.world import World

WALL = 0.02


def build_showcase(seed: int = 1, balls: int = 120, polygons: int = 24) -> World:
    """A closed unit box with pegs, bouncing balls and falling polygons."""
    rng = random.Random(seed)
    world = World(gravity=(0.0, -9.81), elasticity=1.0)
    world.add_box(0.0, 0.0, 1.0, WALL, fixed=True, name="floor")
    world.add_box(0.0, 1.0 - WALL, 1.0, WALL, fixed=True, name="ceiling")
    world.add_box(0.0, WALL, WALL, 1.0 - 2 * WALL, fixed=True, name="left wall")
    world.add_box(1.0 - WALL, WALL, WALL, 1.0 - 2 * WALL, fixed=True, name="right wall")
    for row in range(3):
        for col in range(6):
            x = 0.12 + col * 0.15 + (0.075 if row % 2 else 0.0)
            y = 0.25 + row * 0.12
            world.add_polygon(_regular(x, y, 0.025, 6, 0.0), fixed=True)
    placed: list[tuple[float, float, float]] = []

    def free_spot(radius):
        for _ in range(1000):
            x = rng.uniform(WALL + radius + 0.01, 1.0 - WALL - radius - 0.01)
            y = rng.uniform(0.62, 1.0 - WALL - radius - 0.01)
            if all(math.hypot(x - px, y - py) > radius + pr + 0.004 for px, py, pr in placed):
                placed.append((x, y, radius))
                return x, y
        raise RuntimeError("showcase: could not place all bodies")

    for _ in range(polygons):
        radius = rng.uniform(0.018, 0.03)
        x, y = free_spot(radius)
        sides = rng.choice((3, 4, 5, 6))
        world.add_polygon(
            _regular(x, y, radius, sides, rng.uniform(0, math.pi)),
            mass=radius * radius * 1000,
            velocity=(rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5)),
        )
    for _ in range(balls):
        radius = rng.uniform(0.006, 0.012)
        x, y = free_spot(radius)
        world.add_circle(
            (x, y),
            radius,
            mass=radius * radius * 1000,
            velocity=(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)),
        )
    return world


def _regular(x, y, radius, sides, phase):
    return [
        (x + radius * math.cos(phase + 2 * math.pi * k / sides), y + radius * math.sin(phase + 2 * math.pi * k / sides))
        for k in range(sides)
    ]


def total_energy(world: World) -> float:
    """Kinetic plus potential energy (gravity along y)."""
    gy = world.gravity[1]
    energy = world.kinetic_energy()
    for body in world.bodies:
        if not body.is_fixed:
            energy -= body.mass * gy * body.position[1]
    return energy


def run_showcase(out_dir="out", duration: float = 5.0, seed: int = 1, gif: bool = True) -> dict:
    """Run the showcase headless and record it; print a summary and write
    ``showcase.png`` (final state), ``showcase.pgerec`` (the recording) and,
    unless ``gif`` is false, ``showcase.gif`` (exported from the recording)."""
    from pge.recording import Recorder, open_recording
    from pge.render.export import export

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    world = build_showcase(seed)
    energy_start = total_energy(world)
    recording_path = out / "showcase.pgerec"
    started = time.perf_counter()
    with Recorder(world, recording_path, frame_rate=25.0):
        world.run_until(duration)
    elapsed = time.perf_counter() - started
    energy_end = total_energy(world)
    stats = world.stats
    worst = max((depth for _, _, depth in world.overlaps()), default=0.0)
    picture = save_png(world, out / "showcase.png")
    animation = None
    if gif:
        animation = out / "showcase.gif"
        export(open_recording(recording_path), animation, size=(360, 360), progress=False)
    summary = {
        "bodies": len(world),
        "simulated_s": duration,
        "wall_s": elapsed,
        "collisions": stats["collisions"],
        "pair_collisions": stats["pair_collisions"],
        "events": stats["events"],
        "predictions": stats["predictions"],
        "predictions_avoided": world.predictions_avoided,
        "energy_drift": (energy_end - energy_start) / energy_start,
        "worst_overlap": worst,
        "picture": str(picture),
        "recording": str(recording_path),
        "animation": None if animation is None else str(animation),
    }
    print(f"pge showcase: {summary['bodies']} bodies, {duration:g} simulated seconds in {elapsed:.2f} s wall")
    print(f"  collisions        {summary['collisions']:>10}  ({summary['pair_collisions']} between moving bodies)")
    print(f"  events            {summary['events']:>10}")
    print(f"  exact predictions {summary['predictions']:>10}  (broad phase avoided {summary['predictions_avoided']})")
    print(f"  energy drift      {summary['energy_drift']:>10.2e}  (elasticity 1: should be ~0)")
    print(f"  worst overlap     {summary['worst_overlap']:>10.2e}")
    print(f"  picture           {summary['picture']}  (final state)")
    print(f"  recording         {summary['recording']}  (pge info / pge export)")
    if animation is not None:
        print(f"  animation         {summary['animation']}")
    return summary
