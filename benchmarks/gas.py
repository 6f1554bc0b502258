"""Hard-disc gas benchmark: the pge engine against the minimal EDMD reference.

N equal discs in the unit box, area fraction 0.10, every disc at speed
0.1129 in a random direction, elasticity 1, no gravity, for 10 simulated
seconds. The scene is ``pge.scenes.disc_gas(n, seed=seed)``, so the engine and
``benchmarks/edmd_reference.py`` start from bit-identical initial conditions.
In the engine the box is four fixed boxes (0.05 thick, elasticity 1) lying
just outside [0, 1]^2; the reference has analytic walls on the same lines.

Usage (from the repository root, with pge installed in .venv):

    .venv/bin/python benchmarks/gas.py                      # N = 1000 5000 20000
    .venv/bin/python benchmarks/gas.py --sizes 1000 --repeat 5
    .venv/bin/python benchmarks/gas.py --cold               # also time a full Numba compile

It prints two aligned tables and writes one CSV row per N (default
``benchmarks/results/gas-<hostname>.csv``). Timing is only reported, never
asserted: the script always exits 0 once it has run. See benchmarks/README.md
for what every column means.
"""

from __future__ import annotations

import argparse
import csv
import datetime
import gc
import math
import os
import platform
import socket
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent

#: Thickness of the four fixed wall boxes around the unit box.
WALL_THICKNESS = 0.05
#: Required by the project: us_per_event at the largest N over that at the smallest.
SCALING_LIMIT = 1.5
#: Pair-collision counts of engine and reference farther apart than this (percent) are flagged.
PAIR_DIFF_WARN_PCT = 3.0


def parse_args(argv=None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[1000, 5000, 20000], help="numbers of discs N")
    parser.add_argument("--duration", type=float, default=10.0, help="simulated seconds (default 10)")
    parser.add_argument("--seed", type=int, default=0, help="seed of pge.scenes.disc_gas (default 0)")
    parser.add_argument(
        "--out", type=Path, default=None, help="CSV path (default benchmarks/results/gas-<hostname>.csv)"
    )
    parser.add_argument("--repeat", type=int, default=1, help="runs per N; the best (smallest) wall time is kept")
    parser.add_argument(
        "--reference-repeat",
        type=int,
        default=None,
        help="runs of the reference per N (default: same as --repeat; it is slow at large N)",
    )
    parser.add_argument("--no-reference", action="store_true", help="skip the reference runs")
    parser.add_argument(
        "--reference-sizes",
        type=int,
        nargs="+",
        default=None,
        help="run the reference only at these N (default: every N of --sizes)",
    )
    parser.add_argument(
        "--reference-from",
        type=Path,
        default=None,
        help="earlier gas CSV: take the ref_* columns from its rows (same N, duration, seed) "
        "for the N where the reference is not run now (it is fixed code and slow at large N)",
    )
    parser.add_argument(
        "--cold",
        action="store_true",
        help="compile the Numba kernels from scratch (empty temporary NUMBA_CACHE_DIR): warmup_s = full JIT time",
    )
    args = parser.parse_args(argv)
    if args.repeat < 1:
        parser.error("--repeat must be at least 1")
    if args.reference_repeat is None:
        args.reference_repeat = args.repeat
    if args.reference_repeat < 1:
        parser.error("--reference-repeat must be at least 1")
    if not (args.duration > 0.0 and math.isfinite(args.duration)):
        parser.error("--duration must be positive and finite")
    if any(n < 1 for n in args.sizes):
        parser.error("--sizes must be positive")
    return args


# ------------------------------------------------------------------ environment


def cpu_model() -> str:
    try:
        with open("/proc/cpuinfo", encoding="utf-8", errors="replace") as handle:
            for line in handle:
                if line.lower().startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine() or "unknown"


def git_commit(where: Path) -> str:
    """Short commit of the repository holding ``where`` (+dirty if tracked files changed), or ''."""
    try:
        result = subprocess.run(
            ["git", "-C", str(where), "rev-parse", "--short", "HEAD"],
            check=False,
            capture_output=True,
            text=True,
            timeout=10,
        )
        commit = result.stdout.strip()
        dirty = subprocess.run(
            ["git", "-C", str(where), "status", "--porcelain", "--untracked-files=no"],
            check=False,
            capture_output=True,
            text=True,
            timeout=10,
        ).stdout.strip()
        return commit + ("+dirty" if commit and dirty else "")
    except (OSError, subprocess.SubprocessError):
        return ""


# ----------------------------------------------------------------------- engine


def build_world(World, gas):
    """The engine's version of ``gas``: four fixed wall boxes and N unit-mass discs, all e = 1."""
    world = World(gravity=(0.0, 0.0), elasticity=1.0, bounds=gas.box)
    x0, y0, x1, y1 = gas.box
    t = WALL_THICKNESS
    width, height = x1 - x0, y1 - y0
    world.add_box(x0 - t, y0 - t, width + 2 * t, t, fixed=True, elasticity=1.0, name="floor")
    world.add_box(x0 - t, y1, width + 2 * t, t, fixed=True, elasticity=1.0, name="ceiling")
    world.add_box(x0 - t, y0, t, height, fixed=True, elasticity=1.0, name="left wall")
    world.add_box(x1, y0, t, height, fixed=True, elasticity=1.0, name="right wall")
    radius = gas.radius
    add = world.add_circle
    for position, velocity in zip(gas.positions, gas.velocities):
        add(position, radius, mass=1.0, velocity=velocity, elasticity=1.0)
    return world


def warm_up(World, disc_gas) -> float:
    """Load (or compile) every Numba kernel the measured runs use; return the seconds it took."""
    start = time.perf_counter()
    world = build_world(World, disc_gas(64, seed=12345))
    world.run_until(2.0)
    world.overlaps()
    world.kinetic_energy()
    return time.perf_counter() - start


def run_engine_once(World, gas, duration: float) -> dict:
    gc.collect()
    start = time.perf_counter()
    world = build_world(World, gas)
    setup = time.perf_counter() - start
    energy_start = world.kinetic_energy()
    gc.collect()
    cpu_start = time.process_time()
    start = time.perf_counter()
    world.run_until(duration)
    wall = time.perf_counter() - start
    cpu = time.process_time() - cpu_start
    energy_end = world.kinetic_energy()
    overlaps = world.overlaps()
    stats = world.stats
    return {
        "setup_s": setup,
        "wall_s": wall,
        "cpu_s": cpu,
        "stats": stats,
        "avoided": world.predictions_avoided,
        "ke_start": energy_start,
        "ke_end": energy_end,
        "overlap_pairs": len(overlaps),
        "max_overlap": max((depth for _, _, depth in overlaps), default=0.0),
    }


def run_engine(World, gas, duration: float, repeat: int) -> dict:
    runs = [run_engine_once(World, gas, duration) for _ in range(repeat)]
    best = min(runs, key=lambda run: run["wall_s"])
    s = best["stats"]
    wall = best["wall_s"]
    events = s["events"]
    predictions = s["predictions"]
    avoided = best["avoided"]
    return {
        "setup_s": min(run["setup_s"] for run in runs),
        "engine_wall_s": wall,
        "engine_wall_s_all": ";".join(f"{run['wall_s']:.4f}" for run in runs),
        "engine_cpu_s": min(run["cpu_s"] for run in runs),
        "events": events,
        "events_per_s": events / wall,
        "us_per_event": 1e6 * wall / events if events else math.nan,
        "collisions": s["collisions"],
        "pair_collisions": s["pair_collisions"],
        "wall_collisions": s["collisions"] - s["pair_collisions"],
        "pair_collisions_per_s": s["pair_collisions"] / wall,
        "horizons": s["horizons"],
        "stale": s["stale"],
        "grazes": s["grazes"],
        "candidates": s["candidates"],
        "predictions": predictions,
        "predictions_avoided": avoided,
        "avoided_fraction": avoided / (avoided + predictions) if avoided + predictions else math.nan,
        "ke_start": best["ke_start"],
        "ke_drift": (best["ke_end"] - best["ke_start"]) / best["ke_start"],
        "overlap_pairs": best["overlap_pairs"],
        "max_overlap": best["max_overlap"],
        "max_overlap_rel_radius": best["max_overlap"] / gas.radius,
        "deterministic": all(run["stats"] == s for run in runs),
    }


# -------------------------------------------------------------------- reference


def run_ref(run_reference, gas, duration: float, repeat: int) -> dict:
    runs = []
    cpu_times = []
    for _ in range(repeat):
        gc.collect()
        cpu_start = time.process_time()
        runs.append(run_reference(gas, duration))
        cpu_times.append(time.process_time() - cpu_start)
    best = min(runs, key=lambda run: run["wall_time_s"])
    wall = best["wall_time_s"]
    return {
        "ref_source": "measured",
        "ref_wall_s": wall,
        "ref_wall_s_all": ";".join(f"{run['wall_time_s']:.4f}" for run in runs),
        "ref_cpu_s": min(cpu_times),
        "ref_events": best["events"],
        "ref_us_per_event": 1e6 * wall / best["events"] if best["events"] else math.nan,
        "ref_pair_collisions": best["pair_collisions"],
        "ref_wall_collisions": best["wall_collisions"],
        "ref_cell_crossings": best["cell_crossings"],
        "ref_stale": best["stale"],
        "ref_ke_drift": (best["kinetic_energy_end"] - best["kinetic_energy_start"]) / best["kinetic_energy_start"],
    }


# ----------------------------------------------------------------------- output

CSV_COLUMNS = [
    "n", "duration_s", "seed", "radius", "repeat", "reference_repeat",
    "import_s", "warmup_s", "cold_jit", "setup_s", "engine_wall_s", "engine_wall_s_all", "engine_cpu_s",
    "events", "events_per_s", "us_per_event", "us_per_event_vs_smallest_n",
    "collisions", "pair_collisions", "wall_collisions", "pair_collisions_per_s",
    "horizons", "stale", "grazes", "candidates", "predictions", "predictions_avoided", "avoided_fraction",
    "ke_start", "ke_drift", "overlap_pairs", "max_overlap", "max_overlap_rel_radius", "deterministic",
    "ref_source", "ref_wall_s", "ref_wall_s_all", "ref_cpu_s", "ref_events", "ref_us_per_event", "ref_pair_collisions",
    "ref_wall_collisions", "ref_cell_crossings", "ref_stale", "ref_ke_drift",
    "speedup_vs_reference", "speedup_cpu", "pair_collision_diff_pct", "loadavg_1min",
    "hostname", "cpu_model", "cpu_count", "python", "numpy", "numba", "pge_path", "pge_commit", "timestamp_utc",
]  # fmt: skip

ENGINE_TABLE = [
    ("N", "n", "d"),
    ("setup s", "setup_s", ".3f"),
    ("wall s", "engine_wall_s", ".3f"),
    ("cpu s", "engine_cpu_s", ".3f"),
    ("events", "events", "d"),
    ("events/s", "events_per_s", ",.0f"),
    ("us/event", "us_per_event", ".3f"),
    ("collisions", "collisions", "d"),
    ("pair coll/s", "pair_collisions_per_s", ",.0f"),
    ("predictions", "predictions", "d"),
    ("avoided", "predictions_avoided", "d"),
    ("avoided %", "avoided_fraction", ".1%"),
    ("KE drift", "ke_drift", ".1e"),
    ("max overlap", "max_overlap", ".1e"),
]

REFERENCE_TABLE = [
    ("N", "n", "d"),
    ("engine s", "engine_wall_s", ".3f"),
    ("ref s", "ref_wall_s", ".3f"),
    ("ref/engine", "speedup_vs_reference", ".2f"),
    ("ref/engine cpu", "speedup_cpu", ".2f"),
    ("engine pairs", "pair_collisions", "d"),
    ("ref pairs", "ref_pair_collisions", "d"),
    ("pairs diff %", "pair_collision_diff_pct", "+.2f"),
    ("engine walls", "wall_collisions", "d"),
    ("ref walls", "ref_wall_collisions", "d"),
    ("ref events", "ref_events", "d"),
    ("ref us/event", "ref_us_per_event", ".3f"),
    ("ref KE drift", "ref_ke_drift", ".1e"),
]


def cell(value, spec: str) -> str:
    if value is None or value == "" or (isinstance(value, float) and math.isnan(value)):
        return "-"
    return format(value, spec)


def table(rows: list[dict], columns, notes: dict | None = None) -> str:
    """Aligned text table; ``notes`` maps a key to another key whose text is shown in place
    of a missing value."""
    notes = notes or {}
    header = [title for title, _, _ in columns]
    body = []
    for row in rows:
        line = []
        for _, key, spec in columns:
            value = row.get(key)
            if (value is None or value == "") and row.get(notes.get(key, "")):
                line.append(str(row[notes[key]]))
            else:
                line.append(cell(value, spec))
        body.append(line)
    widths = [max(len(text) for text in column) for column in zip(header, *body)]
    lines = ["  ".join(text.rjust(width) for text, width in zip(line, widths)) for line in [header] + body]
    lines.insert(1, "  ".join("-" * width for width in widths))
    return "\n".join(lines)


def write_csv(path: Path, rows: list[dict], columns=None) -> None:
    """Write ``rows`` with ``columns`` (default: this script's), missing values empty."""
    columns = CSV_COLUMNS if columns is None else columns
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path, "w", newline="", encoding="utf-8") as handle:
        writer = csv.DictWriter(handle, fieldnames=columns, extrasaction="ignore")
        writer.writeheader()
        for row in rows:
            writer.writerow({key: ("" if row.get(key) is None else row.get(key)) for key in columns})


# ------------------------------------------------------------------------- main


def load_reference_rows(path: Path, duration: float, seed: int) -> dict[int, dict]:
    """ref_* columns of an earlier gas CSV, by N, for rows with the same duration and seed."""
    found = {}
    with open(path, newline="", encoding="utf-8") as handle:
        for row in csv.DictReader(handle):
            if not row.get("ref_wall_s"):
                continue
            if float(row["duration_s"]) != duration or int(row["seed"]) != seed:
                continue
            ref = {}
            for key, value in row.items():
                if key.startswith("ref_") and value != "":
                    ref[key] = value if key in ("ref_source", "ref_wall_s_all") else float(value)
            for key in ("ref_events", "ref_pair_collisions", "ref_wall_collisions", "ref_cell_crossings", "ref_stale"):
                if key in ref:
                    ref[key] = int(ref[key])
            if row.get("reference_repeat"):
                ref["reference_repeat"] = int(row["reference_repeat"])
            if row.get("ref_source", "measured") == "measured":  # else keep naming the run that measured it
                ref["ref_source"] = f"{path.name} {row.get('timestamp_utc', '')}".strip()
            found[int(row["n"])] = ref
    return found


def main(argv=None) -> int:
    args = parse_args(argv)
    if args.cold:
        if "numba" in sys.modules:
            print("warning: numba was already imported; --cold may not take effect", file=sys.stderr)
        # Read when numba is first imported, just below.
        os.environ["NUMBA_CACHE_DIR"] = tempfile.mkdtemp(prefix="pge-numba-cold-")

    start = time.perf_counter()
    import numba
    import numpy

    import pge
    from pge import World
    from pge.scenes import disc_gas

    import_s = time.perf_counter() - start
    sys.path.insert(0, str(HERE))
    from edmd_reference import run_reference

    hostname = socket.gethostname()
    out = args.out or HERE / "results" / f"gas-{hostname}.csv"
    pge_path = Path(pge.__file__).resolve().parent
    if args.no_reference:
        reference_sizes = set()
    elif args.reference_sizes is None:
        reference_sizes = set(args.sizes)
    else:
        reference_sizes = set(args.reference_sizes)
    stored = {}
    if args.reference_from is not None and not args.no_reference:
        stored = load_reference_rows(args.reference_from, args.duration, args.seed)
    common = {
        "duration_s": args.duration,
        "seed": args.seed,
        "repeat": args.repeat,
        "import_s": import_s,
        "cold_jit": args.cold,
        "hostname": hostname,
        "cpu_model": cpu_model(),
        "cpu_count": os.cpu_count(),
        "python": platform.python_version(),
        "numpy": numpy.__version__,
        "numba": numba.__version__,
        "pge_path": str(pge_path),
        "pge_commit": git_commit(pge_path),
        "timestamp_utc": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ"),
    }
    print(
        f"hard-disc gas: area fraction 0.10, speed 0.1129, e = 1, {args.duration:g} simulated s, seed {args.seed}; "
        f"engine best of {args.repeat}, reference best of {args.reference_repeat}"
    )
    print(
        f"{common['cpu_model']} x{common['cpu_count']}, Python {common['python']}, numpy {common['numpy']}, "
        f"numba {common['numba']}, pge {common['pge_commit'] or '?'} ({pge_path})"
    )
    warmup_s = warm_up(World, disc_gas)
    common["warmup_s"] = warmup_s
    print(
        f"import {import_s:.2f} s; warm-up {warmup_s:.2f} s "
        f"({'full Numba compile, empty cache' if args.cold else 'Numba kernels loaded from cache or compiled'}; "
        "not included below)",
        flush=True,
    )

    rows = []
    for n in args.sizes:
        gas = disc_gas(n, seed=args.seed)
        row = dict(common, n=n, radius=gas.radius, loadavg_1min=loadavg())
        print(f"N = {n}: engine x{args.repeat} ...", end="", flush=True)
        row.update(run_engine(World, gas, args.duration, args.repeat))
        print(f" {row['engine_wall_s']:.3f} s", end="", flush=True)
        if n in reference_sizes:
            print(f"; reference x{args.reference_repeat} ...", end="", flush=True)
            row.update(run_ref(run_reference, gas, args.duration, args.reference_repeat))
            row["reference_repeat"] = args.reference_repeat
            print(f" {row['ref_wall_s']:.3f} s", end="", flush=True)
        elif n in stored:
            row.update(stored[n])
            print(f"; reference from {row['ref_source']}: {row['ref_wall_s']:.3f} s", end="", flush=True)
        if row.get("ref_wall_s"):
            row["speedup_vs_reference"] = row["ref_wall_s"] / row["engine_wall_s"]
            if row.get("ref_cpu_s"):
                row["speedup_cpu"] = row["ref_cpu_s"] / row["engine_cpu_s"]
            row["pair_collision_diff_pct"] = (
                100.0 * (row["pair_collisions"] - row["ref_pair_collisions"]) / row["ref_pair_collisions"]
                if row["ref_pair_collisions"]
                else math.nan
            )
        print(f"  (load average {row['loadavg_1min']:.2f})", flush=True)
        rows.append(row)
        smallest = min(rows, key=lambda r: r["n"])
        for r in rows:
            r["us_per_event_vs_smallest_n"] = r["us_per_event"] / smallest["us_per_event"]
        write_csv(out, rows)  # after every N, so a long run that is stopped keeps what it measured

    print()
    print("Engine (pge), best wall time of run_until, warm kernels")
    print(table(rows, ENGINE_TABLE))
    with_reference = [row for row in rows if row.get("ref_wall_s")]
    if with_reference:
        print()
        print("Reference (benchmarks/edmd_reference.py), same scene; ref/engine > 1 means the engine is faster")
        print(table(with_reference, REFERENCE_TABLE))
        reused = sorted({row["ref_source"] for row in with_reference if row["ref_source"] != "measured"})
        if reused:
            print("reference rows not measured in this run come from: " + ", ".join(reused))
    print()

    by_n = {row["n"]: row for row in rows}
    low, high = min(by_n), max(by_n)
    if high > low:
        ratio = by_n[high]["us_per_event"] / by_n[low]["us_per_event"]
        verdict = "meets" if ratio <= SCALING_LIMIT else "DOES NOT meet"
        cpu_ratio = (by_n[high]["engine_cpu_s"] / by_n[high]["events"]) / (
            by_n[low]["engine_cpu_s"] / by_n[low]["events"]
        )
        print(
            f"scaling: us/event(N={high}) / us/event(N={low}) = {ratio:.3f}  "
            f"({verdict} the required <= {SCALING_LIMIT}; with CPU times {cpu_ratio:.3f})"
        )
    if by_n.get(1000, {}).get("speedup_vs_reference"):
        speedup = by_n[1000]["speedup_vs_reference"]
        verdict = "yes" if speedup >= 1.0 else "NO"
        print(f"engine at least as fast as the reference at N=1000 (required): {verdict} (ref/engine = {speedup:.2f})")
    for row in rows:
        diff = row.get("pair_collision_diff_pct")
        if diff is not None and not math.isnan(diff) and abs(diff) > PAIR_DIFF_WARN_PCT:
            print(f"warning: N={row['n']}: pair collisions differ from the reference by {diff:+.2f}%")
        if not row["deterministic"]:
            print(f"warning: N={row['n']}: engine event counts differed between repeats")
        if row["overlap_pairs"]:
            print(
                f"warning: N={row['n']}: {row['overlap_pairs']} overlapping pairs at the end "
                f"(max {row['max_overlap']:.3g})"
            )
    busy = [row["n"] for row in rows if row["loadavg_1min"] > 1.0]
    if busy:
        print(
            f"note: load average above 1 when N = {', '.join(map(str, busy))} started: other processes shared the "
            "CPU; wall times may be inflated (compare the CPU times)"
        )
    for row in rows:
        if row["engine_wall_s"] > 1.2 * row["engine_cpu_s"]:
            print(
                f"note: N={row['n']}: engine wall time {row['engine_wall_s']:.3f} s is "
                f"{row['engine_wall_s'] / row['engine_cpu_s']:.2f}x its CPU time: the process waited for a CPU"
            )
    print(f"CSV: {out}")
    return 0


def loadavg() -> float:
    """The 1-minute load average, or NaN where the system has none."""
    try:
        return os.getloadavg()[0]
    except OSError:
        return math.nan


if __name__ == "__main__":
    sys.exit(main())
