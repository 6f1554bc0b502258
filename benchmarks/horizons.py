"""How the broad phase's two lengths set the number of events of the disc gas (issue 20).

Every moving body holds a swept box for the next ``skin`` of travel; when it has travelled
that far without a collision, a HORIZON event renews the box and predicts again. In the gas
most events are such horizons (`gas.py`: 4.7 events per pair collision at N = 10,000). A
longer skin means fewer horizons but larger boxes, so more candidate pairs per prediction;
the grid's ``cell_size`` sets how many candidates a box meets. This script runs `gas.py`'s
gas (same scene, same walls) over a grid of both, as multiples of the disc radius, and
prints a table and writes a CSV: events, horizons and pair collisions per simulated
second, events per pair collision, candidates and exact predictions per event, wall and
CPU time, and the microseconds per event and per pair collision. The row ``default`` is the
World's own choice (``World._prime``). It only measures: it never fails on a timing.

    .venv/bin/python benchmarks/horizons.py                       # N = 10,000, 10 s
    .venv/bin/python benchmarks/horizons.py --n 1000 --skins 1 2 4 8 --cells 4 8 16
"""

from __future__ import annotations

import argparse
import csv
import functools
import os
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from gas import build_world  # noqa: E402  (the same scene as gas.py)

FIELDS = [
    "n", "duration_s", "cell_r", "skin_r", "cell", "skin", "wall_s", "cpu_s", "events", "horizons", "stale",
    "pair_collisions", "events_per_pair_collision", "horizon_share", "candidates_per_event",
    "predictions_per_event", "us_per_event", "us_per_pair_collision",
]


def run(n: int, duration: float, seed: int, cell_r: float | None, skin_r: float | None) -> dict:
    """One timed run of the gas with cell side ``cell_r`` and skin ``skin_r`` radii (None: the
    World's default)."""
    from pge import World
    from pge.scenes import disc_gas

    gas = disc_gas(n, seed=seed)
    options = {}
    if cell_r is not None:
        options["cell_size"] = cell_r * gas.radius
    if skin_r is not None:
        options["skin"] = skin_r * gas.radius
    world = build_world(functools.partial(World, **options), gas)
    world.run_until(1e-9)  # lay the grid and predict once, outside the timing
    before = dict(world.stats)
    start, cpu = time.perf_counter(), time.process_time()
    world.run_until(duration)
    wall, cpu = time.perf_counter() - start, time.process_time() - cpu
    s = {k: world.stats[k] - before.get(k, 0) for k in world.stats}
    events = max(s["events"], 1)
    pairs = max(s["pair_collisions"], 1)
    return {
        "n": n, "duration_s": duration,
        "cell_r": "default" if cell_r is None else cell_r, "skin_r": "default" if skin_r is None else skin_r,
        "cell": options.get("cell_size", ""),
        "skin": world._travel, "wall_s": wall, "cpu_s": cpu, "events": s["events"], "horizons": s["horizons"],
        "stale": s["stale"], "pair_collisions": s["pair_collisions"],
        "events_per_pair_collision": s["events"] / pairs, "horizon_share": s["horizons"] / events,
        "candidates_per_event": s["candidates"] / events, "predictions_per_event": s["predictions"] / events,
        "us_per_event": 1e6 * cpu / events, "us_per_pair_collision": 1e6 * cpu / pairs,
    }


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--n", type=int, default=10_000, help="discs (default 10,000)")
    parser.add_argument("--duration", type=float, default=10.0, help="simulated seconds (default 10)")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--skins", type=float, nargs="+", default=[1.0, 2.0, 4.0, 8.0],
                        help="skins to try, in disc radii")
    parser.add_argument("--cells", type=float, nargs="+", default=[4.0, 8.0, 16.0],
                        help="cell sides to try, in disc radii")
    parser.add_argument("--out", type=Path, default=HERE / "results" / f"horizons-{os.uname().nodename}.csv")
    args = parser.parse_args(argv)

    run(256, 0.1, args.seed, None, None)  # compile or load the kernels outside any timing
    combos = [(None, None)] + [(c, s) for c in args.cells for s in args.skins]
    rows = []
    print(f"gas, N = {args.n}, {args.duration:g} simulated s; lengths in disc radii; times are CPU")
    print(f"{'cell':>7} {'skin':>7} {'events/pair':>11} {'horizons':>9} {'cand/ev':>8} {'pred/ev':>8} "
          f"{'us/event':>9} {'us/pair':>8} {'cpu s':>7}")
    for cell_r, skin_r in combos:
        row = run(args.n, args.duration, args.seed, cell_r, skin_r)
        rows.append(row)
        print(f"{str(row['cell_r']):>7} {str(row['skin_r']):>7} {row['events_per_pair_collision']:11.2f} "
              f"{row['horizon_share']:9.0%} {row['candidates_per_event']:8.1f} {row['predictions_per_event']:8.2f} "
              f"{row['us_per_event']:9.2f} {row['us_per_pair_collision']:8.2f} {row['cpu_s']:7.2f}", flush=True)
    args.out.parent.mkdir(parents=True, exist_ok=True)
    with open(args.out, "w", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=FIELDS)
        writer.writeheader()
        writer.writerows(rows)
    print(f"CSV: {args.out}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
