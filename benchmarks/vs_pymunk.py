"""Hard-disc gas: pge against pymunk (Chipmunk, stepped) and the pure-Python event-driven reference.

The gas of issue 20: N discs of radius 5 at area fraction 0.1 in a closed square box of side
L = sqrt(N pi 25 / 0.1) (four fixed walls), every disc at speed 100 in a random direction (seeded),
elasticity 1, no friction, no gravity, 10 simulated seconds, for N = 1000, 10000, 100000. The
scene is ``pge.scenes.disc_gas(n, 0.1, 100, seed, box=(0, 0, L, L))``, so the three start from
bit-identical positions and velocities.

* pge: the World API. ``World(bounds=(0, 0, L, L))``: the grid covers the box; cell size and
  travel per horizon come from the disc radius (4 r and 2 r here, recorded in the CSV), so the
  scene behaves as ``gas.py``'s unit-box gas scaled up. Four fixed wall boxes 0.05 L thick lie
  outside the box (they are clamped into the border cells). Timed: ``run_until(duration)``.
* pymunk (its runs alternate with pge's): ``pymunk.Space()`` with its defaults (10 iterations, collision slop 0.1, its bias and
  persistence), ``step(dt)`` with dt = 0.01, discs of mass 1 (moment of a solid disc), static
  box polygons for walls, elasticity 1 and friction 0 on every shape. Timed: the steps alone
  (wall and CPU time around each ``space.step``). After every step, untimed, the
  cached arbiters are read with ``pymunk.batch`` to get the deepest overlap seen (contact
  distance) and the number of new disc-disc contacts (= pymunk's ``begin`` callbacks): that is
  the fairness note, pymunk lets discs overlap and pge does not.
* reference: ``benchmarks/edmd_reference.py`` (plain Python), timed by its own clock. It is run
  at an N only if its time projected from the previous N stays under ``--reference-limit``
  seconds; otherwise the table says "skipped" with the projection.

Memory per body (``--memory-sizes``, default 100000 and 1000000, ``--memory-duration`` 0.05 s):
each engine builds the gas and runs it briefly in a fresh child process; ``rss_B_per_body`` is
(peak RSS of the child - RSS before building) / N, which counts everything the engine holds
(Python objects, C structures, arrays, transient peaks). For pge also ``state_B_per_body``: the
``nbytes`` of the engine's numpy arrays (``EngineState``: bodies, grid, event queue) / N.

    .venv/bin/pip install -e '.[bench]'                    # matplotlib, pymunk
    .venv/bin/python benchmarks/vs_pymunk.py                # N = 1e3 1e4 1e5, 10 s, best of 1
    .venv/bin/python benchmarks/vs_pymunk.py --sizes 1000 --duration 1 --memory-sizes  # quick look
    .venv/bin/python benchmarks/vs_pymunk.py --repeat 3 --memory-sizes 100000 1000000
    .venv/bin/python benchmarks/vs_pymunk.py --repeat 3 --memory-from results/vs-pymunk-old.csv  # timings only

Every engine's CPU time is recorded next to its wall time: on a shared machine compare those.
Prints a table, writes ``benchmarks/results/vs-pymunk-<hostname>.csv`` (rewritten after every N)
and the log-log plot ``benchmarks/results/vs-pymunk-<hostname>.png``. It only measures: it never
fails on a timing.
"""

from __future__ import annotations

import argparse
import csv
import datetime
import gc
import json
import math
import os
import platform
import socket
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from gas import cpu_model, git_commit, loadavg, table, write_csv  # noqa: E402

RADIUS = 5.0
AREA_FRACTION = 0.1
SPEED = 100.0
#: wall thickness as a fraction of the box side (as gas.py and broadphase.py)
WALL_FRACTION = 0.05
#: growth of the reference's wall time with N used for its projection (its us/event grows with N)
REFERENCE_EXPONENT = 1.3


def parse_args(argv=None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[1000, 10000, 100000], help="numbers of discs N")
    parser.add_argument("--duration", type=float, default=10.0, help="simulated seconds (default 10)")
    parser.add_argument("--seed", type=int, default=0, help="scene seed (default 0)")
    parser.add_argument("--repeat", type=int, default=1, help="runs of pge and pymunk per N; the best wall time is kept")
    parser.add_argument("--reference-repeat", type=int, default=1, help="runs of the reference per N (default 1)")
    parser.add_argument("--dt", type=float, default=0.01, help="pymunk's time step (default 0.01)")
    parser.add_argument(
        "--reference-limit", type=float, default=180.0,
        help="skip the reference at an N where its projected wall time exceeds this (s, default 180)",
    )
    parser.add_argument("--no-reference", action="store_true", help="never run the reference")
    parser.add_argument(
        "--memory-sizes", type=int, nargs="*", default=[100000, 1000000],
        help="N at which to measure memory per body (fresh child processes); none: skip",
    )
    parser.add_argument("--memory-duration", type=float, default=0.05, help="simulated seconds of the memory runs")
    parser.add_argument(
        "--memory-from", type=Path, default=None,
        help="earlier vs-pymunk CSV: copy its memory columns instead of measuring memory (memory does not "
        "depend on the machine's load; the runs at 1e6 take minutes)",
    )
    parser.add_argument("--out", type=Path, default=None, help="CSV (default benchmarks/results/vs-pymunk-<host>.csv)")
    parser.add_argument("--plot", type=Path, default=None, help="PNG (default: the CSV's path with .png)")
    parser.add_argument("--memory-child", nargs=3, metavar=("ENGINE", "N", "SEED"), help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.repeat < 1 or args.reference_repeat < 1:
        parser.error("--repeat and --reference-repeat must be at least 1")
    if not (args.duration > 0.0 and math.isfinite(args.duration)):
        parser.error("--duration must be positive and finite")
    if not args.dt > 0.0:
        parser.error("--dt must be positive")
    if any(n < 1 for n in args.sizes + args.memory_sizes):
        parser.error("sizes must be positive")
    return args


# ------------------------------------------------------------------------ scene


def box_side(n: int) -> float:
    """Side of the square box holding ``n`` discs of radius 5 at area fraction 0.1."""
    return math.sqrt(n * math.pi * RADIUS * RADIUS / AREA_FRACTION)


def make_gas(n: int, seed: int):
    from pge.scenes import disc_gas

    side = box_side(n)
    return disc_gas(n, area_fraction=AREA_FRACTION, speed=SPEED, seed=seed, box=(0.0, 0.0, side, side))


def wall_rectangles(gas):
    """(x0, y0, x1, y1) of the four walls: 0.05 L thick, just outside the box."""
    x0, y0, x1, y1 = gas.box
    t = WALL_FRACTION * max(x1 - x0, y1 - y0)
    return [
        (x0 - t, y0 - t, x1 + t, y0),  # floor
        (x0 - t, y1, x1 + t, y1 + t),  # ceiling
        (x0 - t, y0, x0, y1),  # left
        (x1, y0, x1 + t, y1),  # right
    ]


# ------------------------------------------------------------------------- pge


def pge_world(gas):
    from pge import World

    world = World(gravity=(0.0, 0.0), elasticity=1.0, bounds=gas.box)
    for x0, y0, x1, y1 in wall_rectangles(gas):
        world.add_box(x0, y0, x1 - x0, y1 - y0, fixed=True, elasticity=1.0, friction=0.0)
    add = world.add_circle
    radius = gas.radius
    for position, velocity in zip(gas.positions, gas.velocities):
        add(position, radius, mass=1.0, velocity=velocity, elasticity=1.0, friction=0.0)
    return world


def pge_warm_up(seed: int) -> float:
    """Load (or compile) the kernels on a small gas of the same kind; return the seconds."""
    start = time.perf_counter()
    world = pge_world(make_gas(64, seed + 12345))
    world.run_until(2.0)
    world.overlaps()
    world.kinetic_energy()
    return time.perf_counter() - start


def pge_once(gas, duration: float) -> dict:
    from pge.core import layout as L

    gc.collect()
    start = time.perf_counter()
    world = pge_world(gas)
    setup = time.perf_counter() - start
    energy = world.kinetic_energy()
    gc.collect()
    cpu = time.process_time()
    start = time.perf_counter()
    world.run_until(duration)
    wall = time.perf_counter() - start
    cpu = time.process_time() - cpu
    overlaps = world.overlaps()
    P, Q = world._state.P, world._state.Q
    return {
        "setup_s": setup,
        "wall_s": wall,
        "cpu_s": cpu,
        "stats": world.stats,
        "ke_drift": (world.kinetic_energy() - energy) / energy,
        "max_overlap": max((depth for _, _, depth in overlaps), default=0.0),
        "cell_size": float(P[L.CELL_SIZE]),
        "travel": float(P[L.TRAVEL]),
        "grid_cells": int(Q[L.GRID_NX] * Q[L.GRID_NY]),
    }


def run_pge(gas, duration: float, repeat: int, runs: list | None = None) -> dict:
    runs = runs if runs is not None else [pge_once(gas, duration) for _ in range(repeat)]
    best = min(runs, key=lambda run: run["wall_s"])
    s = best["stats"]
    wall = best["wall_s"]
    return {
        "pge_setup_s": min(run["setup_s"] for run in runs),
        "pge_wall_s": wall,
        "pge_wall_s_all": ";".join(f"{run['wall_s']:.3f}" for run in runs),
        "pge_cpu_s": best["cpu_s"],
        "pge_events": s["events"],
        "pge_us_per_event": 1e6 * wall / s["events"] if s["events"] else math.nan,
        "pge_pair_collisions": s["pair_collisions"],
        "pge_wall_collisions": s["collisions"] - s["pair_collisions"],
        "pge_pair_collisions_per_s": s["pair_collisions"] / wall,
        "pge_horizons": s["horizons"],
        "pge_stale": s["stale"],
        "pge_predictions": s["predictions"],
        "pge_candidates": s["candidates"],
        "pge_ke_drift": best["ke_drift"],
        "pge_max_overlap_rel_radius": best["max_overlap"] / gas.radius,
        "pge_cell_size": best["cell_size"],
        "pge_travel": best["travel"],
        "pge_grid_cells": best["grid_cells"],
        "pge_deterministic": all(run["stats"] == s for run in runs),
    }


def pge_state_bytes(world) -> int:
    """nbytes of every numpy array the engine state holds (each array counted once)."""
    import numpy as np

    seen, total = set(), 0
    state = world._state
    for value in list(vars(state).values()) + list(state.S):
        if isinstance(value, np.ndarray) and id(value) not in seen:
            seen.add(id(value))
            total += value.nbytes
    return total


# ----------------------------------------------------------------------- pymunk


def pymunk_space(gas):
    import pymunk

    space = pymunk.Space()  # defaults: iterations 10, collision_slop 0.1, no gravity, no damping
    for x0, y0, x1, y1 in wall_rectangles(gas):
        wall = pymunk.Poly(space.static_body, [(x0, y0), (x1, y0), (x1, y1), (x0, y1)])
        wall.elasticity = 1.0
        wall.friction = 0.0
        space.add(wall)
    moment = pymunk.moment_for_circle(1.0, 0.0, gas.radius)
    for position, velocity in zip(gas.positions, gas.velocities):
        body = pymunk.Body(1.0, moment)
        body.position = position
        body.velocity = velocity
        disc = pymunk.Circle(body, gas.radius)
        disc.elasticity = 1.0
        disc.friction = 0.0
        space.add(body, disc)
    return space


def pymunk_energy(space) -> float:
    return 0.5 * math.fsum(b.mass * b.velocity.length_squared for b in space.bodies)


def pymunk_once(gas, duration: float, dt: float) -> dict:
    import numpy as np
    import pymunk.batch as batch

    gc.collect()
    start = time.perf_counter()
    space = pymunk_space(gas)
    setup = time.perf_counter() - start
    energy = pymunk_energy(space)
    steps = max(1, round(duration / dt))
    fields = (
        batch.ArbiterFields.BODY_A_ID | batch.ArbiterFields.BODY_B_ID
        | batch.ArbiterFields.IS_FIRST_CONTACT | batch.ArbiterFields.DISTANCE_1
    )
    buffer = batch.Buffer()
    static_id = space.static_body.id
    deepest_pair = deepest_wall = last_pair = 0.0
    new_pairs = 0
    step = space.step
    clock = time.perf_counter
    cpu_clock = time.process_time
    gc.collect()
    wall = cpu = 0.0
    for _ in range(steps):
        start = clock()
        start_cpu = cpu_clock()
        step(dt)
        cpu += cpu_clock() - start_cpu
        wall += clock() - start
        # Untimed: the arbiters cached after this step (touching now or within the
        # persistence window), their contact distances (< 0: overlap) and first contacts.
        buffer.clear()
        batch.get_space_arbiters(space, fields, buffer)
        depth = -np.frombuffer(buffer.float_buf(), dtype=np.float64)
        if depth.shape[0]:
            ints = np.frombuffer(buffer.int_buf(), dtype=np.uintp).reshape(-1, 3)
            on_wall = (ints[:, 0] == static_id) | (ints[:, 1] == static_id)
            pair = ~on_wall
            new_pairs += int(ints[pair, 2].sum())
            last_pair = float(depth[pair].max()) if pair.any() else 0.0
            deepest_pair = max(deepest_pair, last_pair)
            if on_wall.any():
                deepest_wall = max(deepest_wall, float(depth[on_wall].max()))
        else:
            last_pair = 0.0
    return {
        "setup_s": setup,
        "wall_s": wall,
        "cpu_s": cpu,
        "steps": steps,
        "new_pairs": new_pairs,
        "deepest_pair": deepest_pair,
        "deepest_wall": deepest_wall,
        "last_pair": last_pair,
        "ke_drift": (pymunk_energy(space) - energy) / energy,
    }


def run_pymunk(gas, duration: float, dt: float, repeat: int, runs: list | None = None) -> dict:
    runs = runs if runs is not None else [pymunk_once(gas, duration, dt) for _ in range(repeat)]
    best = min(runs, key=lambda run: run["wall_s"])
    wall = best["wall_s"]
    r = gas.radius
    return {
        "pymunk_setup_s": min(run["setup_s"] for run in runs),
        "pymunk_wall_s": wall,
        "pymunk_wall_s_all": ";".join(f"{run['wall_s']:.3f}" for run in runs),
        "pymunk_cpu_s": best["cpu_s"],
        "pymunk_steps": best["steps"],
        "pymunk_ms_per_step": 1e3 * wall / best["steps"],
        "pymunk_pair_contacts": best["new_pairs"],
        "pymunk_max_overlap_rel_radius": best["deepest_pair"] / r,
        "pymunk_max_wall_overlap_rel_radius": best["deepest_wall"] / r,
        "pymunk_end_overlap_rel_radius": best["last_pair"] / r,
        "pymunk_ke_drift": best["ke_drift"],
    }


# -------------------------------------------------------------------- reference


def run_ref(gas, duration: float, repeat: int) -> dict:
    from edmd_reference import run_reference

    runs = []
    for _ in range(repeat):
        gc.collect()
        cpu = time.process_time()
        runs.append(run_reference(gas, duration))
        runs[-1]["cpu_s"] = time.process_time() - cpu  # includes converting the scene: negligible
    best = min(runs, key=lambda run: run["wall_time_s"])
    wall = best["wall_time_s"]
    return {
        "ref_wall_s": wall,
        "ref_cpu_s": best["cpu_s"],
        "ref_wall_s_all": ";".join(f"{run['wall_time_s']:.3f}" for run in runs),
        "ref_events": best["events"],
        "ref_us_per_event": 1e6 * wall / best["events"] if best["events"] else math.nan,
        "ref_pair_collisions": best["pair_collisions"],
        "ref_pair_collisions_per_s": best["pair_collisions"] / wall,
        "ref_ke_drift": (best["kinetic_energy_end"] - best["kinetic_energy_start"]) / best["kinetic_energy_start"],
    }


# ----------------------------------------------------------------------- memory


def _status_bytes(field: str) -> int:
    """A memory line of /proc/self/status (VmRSS: resident now, VmHWM: peak resident), in bytes."""
    with open("/proc/self/status", encoding="ascii") as handle:
        for line in handle:
            if line.startswith(field + ":"):
                return int(line.split()[1]) * 1024
    raise RuntimeError(f"no {field} in /proc/self/status")


def _reset_peak_rss() -> None:
    """Set the peak (VmHWM) back to the current RSS (Linux: write 5 to clear_refs)."""
    with open("/proc/self/clear_refs", "w", encoding="ascii") as handle:
        handle.write("5")


def memory_child(engine: str, n: int, seed: int, duration: float) -> dict:
    """In a fresh process: build the gas in ``engine`` and run it briefly; bytes per body."""
    gas = make_gas(n, seed)
    if engine == "pge":
        pge_warm_up(seed)
    elif engine == "pymunk":
        import pymunk  # noqa: F401
    else:
        from edmd_reference import run_reference
    gc.collect()
    before = _status_bytes("VmRSS")
    _reset_peak_rss()  # so that peaks while importing or warming up do not count
    start = time.perf_counter()
    result = {"engine": engine, "n": n}
    if engine == "pge":
        world = pge_world(gas)
        world.run_until(duration)
        result["state_bytes"] = pge_state_bytes(world)
    elif engine == "pymunk":
        space = pymunk_space(gas)
        for _ in range(max(1, round(duration / 0.01))):
            space.step(0.01)
    else:
        run_reference(gas, duration)
    result["seconds"] = time.perf_counter() - start
    result["rss_growth"] = _status_bytes("VmHWM") - before
    return result


def measure_memory(engine: str, n: int, seed: int, duration: float) -> dict:
    command = [sys.executable, str(Path(__file__).resolve()), "--memory-child", engine, str(n), str(seed),
               "--duration", repr(duration)]
    done = subprocess.run(command, capture_output=True, text=True, check=False)
    if done.returncode != 0:
        return {"error": (done.stderr.strip().splitlines() or ["failed"])[-1]}
    return json.loads(done.stdout.strip().splitlines()[-1])


# ----------------------------------------------------------------------- output

CSV_COLUMNS = [
    "n", "box_side", "radius", "duration_s", "seed", "repeat", "loadavg_1min",
    "pge_setup_s", "pge_wall_s", "pge_wall_s_all", "pge_cpu_s", "pge_events", "pge_us_per_event",
    "pge_pair_collisions", "pge_wall_collisions", "pge_pair_collisions_per_s", "pge_horizons", "pge_stale",
    "pge_predictions", "pge_candidates", "pge_ke_drift", "pge_max_overlap_rel_radius", "pge_deterministic",
    "pge_cell_size", "pge_travel", "pge_grid_cells",
    "pymunk_dt", "pymunk_setup_s", "pymunk_wall_s", "pymunk_wall_s_all", "pymunk_cpu_s", "pymunk_steps",
    "pymunk_ms_per_step", "pymunk_pair_contacts", "pymunk_max_overlap_rel_radius",
    "pymunk_max_wall_overlap_rel_radius", "pymunk_end_overlap_rel_radius", "pymunk_ke_drift",
    "ref_status", "ref_wall_s", "ref_wall_s_all", "ref_cpu_s", "ref_events", "ref_us_per_event", "ref_pair_collisions",
    "ref_pair_collisions_per_s", "ref_ke_drift",
    "pymunk_over_pge", "ref_over_pge", "pymunk_over_pge_cpu", "ref_over_pge_cpu",
    "memory_duration_s", "pge_state_B_per_body", "pge_rss_B_per_body", "pymunk_rss_B_per_body",
    "ref_rss_B_per_body", "memory_loadavg_1min", "memory_source",
    "hostname", "cpu_model", "cpu_count", "python", "numpy", "numba", "pymunk", "chipmunk",
    "pge_path", "pge_commit", "timestamp_utc",
]  # fmt: skip

MEMORY_COLUMNS = [
    "memory_duration_s", "pge_state_B_per_body", "pge_rss_B_per_body", "pymunk_rss_B_per_body",
    "ref_rss_B_per_body", "memory_loadavg_1min",
]  # fmt: skip

TABLE = [
    ("N", "n", "d"),
    ("load", "loadavg_1min", ".2f"),
    ("pge s", "pge_wall_s", ".2f"),
    ("cpu s", "pge_cpu_s", ".2f"),
    ("events", "pge_events", ",d"),
    ("us/event", "pge_us_per_event", ".2f"),
    ("pair coll", "pge_pair_collisions", ",d"),
    ("pair coll/s", "pge_pair_collisions_per_s", ",.0f"),
    ("pymunk s", "pymunk_wall_s", ".2f"),
    ("cpu s", "pymunk_cpu_s", ".2f"),
    ("ms/step", "pymunk_ms_per_step", ".3f"),
    ("pymunk contacts", "pymunk_pair_contacts", ",d"),
    ("pymunk overlap/r", "pymunk_max_overlap_rel_radius", ".2f"),
    ("ref s", "ref_wall_s", ".2f"),
    ("ref pair coll/s", "ref_pair_collisions_per_s", ",.0f"),
    ("pymunk/pge", "pymunk_over_pge", ".2f"),
    ("ref/pge", "ref_over_pge", ".2f"),
    ("pymunk/pge cpu", "pymunk_over_pge_cpu", ".2f"),
]

MEMORY_TABLE = [
    ("N", "n", "d"),
    ("load", "memory_loadavg_1min", ".2f"),
    ("pge state B/body", "pge_state_B_per_body", ",.0f"),
    ("pge RSS B/body", "pge_rss_B_per_body", ",.0f"),
    ("pymunk RSS B/body", "pymunk_rss_B_per_body", ",.0f"),
    ("ref RSS B/body", "ref_rss_B_per_body", ",.0f"),
]


def plot(rows: list[dict], path: Path, title: str) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.ticker

    figure, axes = plt.subplots(figsize=(7.5, 5.2))
    # (label, column, marker style, colour, where the value labels go in points)
    series = [
        ("pge (event-driven, Numba)", "pge_wall_s", "o-", "tab:blue", (-8, 6), "right"),
        ("pymunk 7 (Chipmunk, dt = 0.01, defaults)", "pymunk_wall_s", "s-", "tab:orange", (8, -12), "left"),
        ("reference EDMD (pure Python)", "ref_wall_s", "^-", "tab:green", (-8, 6), "right"),
    ]
    timed = [row for row in rows if row.get("pge_wall_s") or row.get("pymunk_wall_s")]
    for label, key, style, colour, offset, align in series:
        points = [(row["n"], row[key]) for row in timed if row.get(key)]
        if points:
            xs, ys = zip(*points)
            axes.plot(xs, ys, style, color=colour, label=label)
            for x, y in points:
                axes.annotate(f"{y:.3g} s", (x, y), textcoords="offset points", xytext=offset, fontsize=8,
                              color=colour, ha=align)
    for row in timed:
        if row.get("ref_status", "").startswith("skipped") and row.get("ref_projected_s"):
            axes.plot([row["n"]], [row["ref_projected_s"]], "^", color="tab:green", fillstyle="none")
            axes.annotate(f"reference skipped\n(projected {row['ref_projected_s'] / 60:.0f} min)",
                          (row["n"], row["ref_projected_s"]), textcoords="offset points", xytext=(-10, 0),
                          fontsize=8, color="tab:green", ha="right", va="center")
    if timed:
        duration = timed[0]["duration_s"]
        axes.axhline(duration, color="grey", linestyle="--", linewidth=0.8)
        axes.annotate(f"real time ({duration:g} s)", (max(r["n"] for r in timed), duration),
                      textcoords="offset points", xytext=(0, 4), fontsize=8, color="grey", ha="right")
    axes.set_xscale("log")
    axes.set_yscale("log")
    sizes = sorted(row["n"] for row in timed)
    axes.set_xticks(sizes)
    axes.set_xticklabels([f"{n:,}" for n in sizes])
    axes.xaxis.set_minor_locator(matplotlib.ticker.NullLocator())
    axes.set_xlim(sizes[0] / 1.6, sizes[-1] * 1.6)
    axes.set_xlabel("number of discs N")
    axes.set_ylabel("wall time for the run (s)")
    axes.set_title(title, fontsize=10)
    axes.grid(True, which="major", linewidth=0.3)
    axes.legend(fontsize=9, loc="lower right")
    figure.tight_layout()
    figure.savefig(path, dpi=110)
    plt.close(figure)


# ------------------------------------------------------------------------- main


def main(argv=None) -> int:
    args = parse_args(argv)
    if args.memory_child:
        engine, n, seed = args.memory_child
        print(json.dumps(memory_child(engine, int(n), int(seed), args.duration)), flush=True)
        os._exit(0)  # skip the teardown: freeing a million pymunk bodies one by one takes many minutes

    import numba
    import numpy
    import pymunk

    import pge

    hostname = socket.gethostname()
    out = args.out or HERE / "results" / f"vs-pymunk-{hostname}.csv"
    png = args.plot or out.with_suffix(".png")
    pge_path = Path(pge.__file__).resolve().parent
    common = {
        "duration_s": args.duration,
        "seed": args.seed,
        "repeat": args.repeat,
        "pymunk_dt": args.dt,
        "hostname": hostname,
        "cpu_model": cpu_model(),
        "cpu_count": os.cpu_count(),
        "python": platform.python_version(),
        "numpy": numpy.__version__,
        "numba": numba.__version__,
        "pymunk": pymunk.version,
        "chipmunk": pymunk.chipmunk_version.split("-")[0],
        "pge_path": str(pge_path),
        "pge_commit": git_commit(pge_path),
        "timestamp_utc": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ"),
    }
    print(
        f"hard-disc gas: r = 5, area fraction 0.1, speed 100, e = 1, {args.duration:g} simulated s, seed {args.seed}; "
        f"pge and pymunk best of {args.repeat}, reference best of {args.reference_repeat}"
    )
    print(
        f"{common['cpu_model']} x{common['cpu_count']}, Python {common['python']}, numpy {common['numpy']}, "
        f"numba {common['numba']}, pymunk {common['pymunk']} (Chipmunk {common['chipmunk']}), "
        f"pge {common['pge_commit'] or '?'} ({pge_path})"
    )
    print(f"pge warm-up (kernels loaded or compiled, not timed): {pge_warm_up(args.seed):.2f} s", flush=True)

    rows: dict[int, dict] = {}
    stored_memory = {}  # read now: --memory-from may be the CSV this run rewrites
    if args.memory_from is not None:
        with open(args.memory_from, newline="", encoding="utf-8") as handle:
            for earlier in csv.DictReader(handle):
                if earlier.get("memory_duration_s"):
                    copied = {key: float(earlier[key]) for key in MEMORY_COLUMNS if earlier.get(key)}
                    copied["memory_source"] = (
                        earlier.get("memory_source") if earlier.get("memory_source") not in (None, "", "measured")
                        else f"{args.memory_from.name} {earlier['timestamp_utc']}"
                    )
                    stored_memory[int(earlier["n"])] = copied

    def save() -> None:
        write_csv(out, [rows[n] for n in sorted(rows)], CSV_COLUMNS)

    measured_ref: list[tuple[int, float]] = []
    for n in args.sizes:
        gas = make_gas(n, args.seed)
        row = dict(common, n=n, box_side=gas.box[2], radius=gas.radius, loadavg_1min=loadavg())
        rows[n] = row
        print(f"N = {n} (L = {gas.box[2]:.1f}, load {row['loadavg_1min']:.2f}): pge and pymunk, alternating, "
              f"x{args.repeat} ...", end="", flush=True)
        # Alternate the two so that a change in the machine's speed during the row hits both.
        pge_runs, pymunk_runs = [], []
        for _ in range(args.repeat):
            pge_runs.append(pge_once(gas, args.duration))
            pymunk_runs.append(pymunk_once(gas, args.duration, args.dt))
        row.update(run_pge(gas, args.duration, args.repeat, pge_runs))
        row.update(run_pymunk(gas, args.duration, args.dt, args.repeat, pymunk_runs))
        print(f" pge {row['pge_wall_s']:.2f} s, pymunk", end="", flush=True)
        row["pymunk_over_pge"] = row["pymunk_wall_s"] / row["pge_wall_s"]
        row["pymunk_over_pge_cpu"] = row["pymunk_cpu_s"] / row["pge_cpu_s"]
        print(f" {row['pymunk_wall_s']:.2f} s", end="", flush=True)
        if args.no_reference:
            row["ref_status"] = "not run (--no-reference)"
        else:
            projected = None
            if measured_ref:
                n0, wall0 = measured_ref[-1]
                projected = wall0 * (n / n0) ** REFERENCE_EXPONENT
            if projected is not None and projected > args.reference_limit:
                shown = f"{projected / 60:.0f} min" if projected >= 120 else f"{projected:.0f} s"
                row["ref_status"] = f"skipped (projected {shown})"
                row["ref_projected_s"] = projected
                print(f"; reference {row['ref_status']}", end="", flush=True)
            else:
                print(f"; reference x{args.reference_repeat} ...", end="", flush=True)
                row.update(run_ref(gas, args.duration, args.reference_repeat))
                row["ref_status"] = "measured"
                row["ref_over_pge"] = row["ref_wall_s"] / row["pge_wall_s"]
                row["ref_over_pge_cpu"] = row["ref_cpu_s"] / row["pge_cpu_s"]
                measured_ref.append((n, row["ref_wall_s"]))
                print(f" {row['ref_wall_s']:.2f} s", end="", flush=True)
        print(flush=True)
        save()

    for n, copied in stored_memory.items():
        rows.setdefault(n, dict(common, n=n, box_side=box_side(n), radius=RADIUS)).update(copied)
    if stored_memory:
        save()
    for n in [] if args.memory_from is not None else args.memory_sizes:
        row = rows.setdefault(n, dict(common, n=n, box_side=box_side(n), radius=RADIUS))
        row["memory_duration_s"] = args.memory_duration
        row["memory_loadavg_1min"] = loadavg()
        row["memory_source"] = "measured"
        for engine in ("pge", "pymunk", "ref"):
            print(f"memory N = {n}: {engine} ...", end="", flush=True)
            found = measure_memory(engine, n, args.seed, args.memory_duration)
            if "error" in found:
                print(f" failed: {found['error']}", flush=True)
                continue
            row[f"{engine}_rss_B_per_body"] = found["rss_growth"] / n
            if "state_bytes" in found:
                row["pge_state_B_per_body"] = found["state_bytes"] / n
            print(f" {found['rss_growth'] / n:,.0f} B/body ({found['seconds']:.1f} s)", flush=True)
        save()

    ordered = [rows[n] for n in sorted(rows)]
    timed = [row for row in ordered if row.get("pge_wall_s")]
    print()
    print(f"Wall time for {args.duration:g} simulated s (pymunk: steps only, dt = {args.dt:g}; "
          "overlap/r: deepest disc-disc overlap seen by pymunk over the radius; pge never overlaps)")
    print(table(timed, TABLE, notes={"ref_wall_s": "ref_status"}))
    with_memory = [row for row in ordered if row.get("memory_duration_s")]
    if with_memory:
        print()
        print("Memory per body: pge state = nbytes of the engine's numpy arrays; RSS = peak RSS growth of a fresh "
              f"process building the gas and running it {with_memory[0]['memory_duration_s']:g} s"
              + ("" if with_memory[0].get("memory_source") == "measured"
                 else f" (copied from {with_memory[0].get('memory_source')})"))
        print(table(with_memory, MEMORY_TABLE))
    for row in timed:
        if row["loadavg_1min"] > 1.0:
            print(f"note: N = {row['n']}: load average {row['loadavg_1min']:.2f} at the start: times may be inflated")
        for engine in ("pge", "pymunk"):
            if row[f"{engine}_wall_s"] > 1.2 * row[f"{engine}_cpu_s"]:
                print(f"note: N = {row['n']}: {engine}'s wall time is {row[f'{engine}_wall_s'] / row[f'{engine}_cpu_s']:.2f}x "
                      "its CPU time: it waited for a CPU; compare the CPU times")
        if row.get("pge_max_overlap_rel_radius"):
            print(f"warning: N = {row['n']}: pge ends with overlaps ({row['pge_max_overlap_rel_radius']:.2g} r)")
    if timed:
        plot(timed, png, f"Hard-disc gas, r = 5, area fraction 0.1, {args.duration:g} simulated s "
                         f"({common['cpu_model']}, pge {common['pge_commit']})")
        print(f"plot: {png}")
    print(f"CSV: {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
