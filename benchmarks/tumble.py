"""Rotation benchmark: a gas of spinning polygons and discs, against the same gas not spinning.

The scene is the disc-gas layout of ``pge.scenes.disc_gas(n)`` with every
other disc replaced by a regular polygon (3 to 6 sides) of the same bounding
radius, inside four fixed walls, elasticity 1, no gravity. In the *spinning*
run every polygon starts with an angular velocity of up to ``--spin`` rad/s
(random sign and size, seeded), so its pairs go through the rotating kernels
(certified advancement); in the *still* baseline the same scene starts with no
spin. Collisions with polygons off their centre line make them turn even in
the baseline, so the baseline is "rotation only where impacts cause it".

Usage (from the repository root, with pge installed in .venv):

    .venv/bin/python benchmarks/tumble.py                      # N = 200, 500; 5 s
    .venv/bin/python benchmarks/tumble.py --sizes 200 1000 --duration 10

It prints a table (events, wall and CPU seconds, microseconds per event, the
spinning/still ratio per event, predictions) and writes one CSV row per run
(default ``benchmarks/results/tumble-<hostname>.csv``).
"""

from __future__ import annotations

import argparse
import csv
import datetime
import math
import os
import random
import socket
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent


def build(n: int, spin: float, seed: int):
    """The scene: returns a World ready to run."""
    from pge import World
    from pge.scenes import disc_gas

    gas = disc_gas(n, seed=seed)
    rng = random.Random(seed + 1)
    x0, y0, x1, y1 = gas.box
    world = World(elasticity=1.0, bounds=(x0 - 0.1, y0 - 0.1, x1 + 0.1, y1 + 0.1))
    t = 0.05
    world.add_box(x0 - t, y0 - t, x1 - x0 + 2 * t, t, fixed=True)
    world.add_box(x0 - t, y1, x1 - x0 + 2 * t, t, fixed=True)
    world.add_box(x0 - t, y0, t, y1 - y0, fixed=True)
    world.add_box(x1, y0, t, y1 - y0, fixed=True)
    r = gas.radius
    for k, ((x, y), velocity) in enumerate(zip(gas.positions, gas.velocities)):
        if k % 2 == 0:
            world.add_circle((x, y), r, mass=1.0, velocity=tuple(velocity))
            continue
        sides = 3 + (k // 2) % 4
        phase = rng.uniform(0.0, 2.0 * math.pi)
        corners = [
            (x + r * math.cos(phase + 2.0 * math.pi * j / sides), y + r * math.sin(phase + 2.0 * math.pi * j / sides))
            for j in range(sides)
        ]
        omega = spin * rng.uniform(-1.0, 1.0)
        world.add_polygon(corners, mass=1.0, velocity=tuple(velocity), angular_velocity=omega)
    return world


def measure(n: int, spin: float, duration: float, seed: int) -> dict:
    """Run one scene for ``duration`` simulated seconds; return its numbers."""
    world = build(n, spin, seed)
    world.run_until(1e-9)  # prime the grid and compile outside the timed part
    energy0 = world.kinetic_energy()
    wall = time.perf_counter()
    cpu = time.process_time()
    world.run_until(duration)
    wall = time.perf_counter() - wall
    cpu = time.process_time() - cpu
    stats = world.stats
    events = stats["events"]
    return {
        "n": n,
        "spin": spin,
        "duration": duration,
        "events": events,
        "collisions": stats["collisions"],
        "predictions": stats["predictions"],
        "wall_s": wall,
        "cpu_s": cpu,
        "us_per_event": 1e6 * cpu / max(events, 1),
        "energy_drift": (world.kinetic_energy() - energy0) / energy0,
        "worst_overlap": max((depth for _, _, depth in world.overlaps()), default=0.0),
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[200, 500])
    parser.add_argument("--duration", type=float, default=5.0)
    parser.add_argument("--spin", type=float, default=20.0, help="largest starting angular velocity (rad/s)")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--out", type=Path, default=HERE / "results" / f"tumble-{socket.gethostname()}.csv")
    args = parser.parse_args()
    build(20, args.spin, args.seed).run_until(0.5)  # compile once
    rows = []
    header = f"{'N':>5}  {'run':>8}  {'events':>8}  {'wall s':>7}  {'cpu s':>7}  {'us/event':>8}  {'ratio':>5}  {'predictions':>11}  {'KE drift':>9}  {'overlap':>8}"
    print(header)
    print("-" * len(header))
    for n in args.sizes:
        still = measure(n, 0.0, args.duration, args.seed)
        spinning = measure(n, args.spin, args.duration, args.seed)
        for name, row in (("still", still), ("spinning", spinning)):
            ratio = row["us_per_event"] / still["us_per_event"]
            row["run"] = name
            row["ratio_to_still"] = ratio
            row["date"] = datetime.date.today().isoformat()
            row["load"] = os.getloadavg()[0]
            rows.append(row)
            print(
                f"{n:>5}  {name:>8}  {row['events']:>8}  {row['wall_s']:>7.2f}  {row['cpu_s']:>7.2f}  "
                f"{row['us_per_event']:>8.1f}  {ratio:>5.2f}  {row['predictions']:>11}  "
                f"{row['energy_drift']:>9.1e}  {row['worst_overlap']:>8.1e}"
            )
    args.out.parent.mkdir(parents=True, exist_ok=True)
    with args.out.open("w", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    print(f"CSV: {args.out}")


if __name__ == "__main__":
    main()
