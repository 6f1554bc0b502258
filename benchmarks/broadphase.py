"""What the broad phase saves: every stage switched off in turn, on the same scenes.

Answers the question the bounding-circle lecture ends with ("does it make a
noticeable difference?") by measurement. For each scene the engine runs with
every combination of ``World.broadphase`` below, and the script reports the
wall time of ``run_until``, the exact predictions made (``stats["predictions"]``)
and the predictions each stage avoided: ``box_rejects`` (swept-box check),
``bound_rejects`` (short-circuit test) and, for the grid, the candidate pairs
it never produced (candidates without the grid minus candidates with it).

Combinations:

* ``sound``: everything on (the engine's default);
* ``no-short-circuit``, ``no-boxes``, ``no-grid``: one stage off;
* ``short-circuit-only``: all pairs, no boxes, only the short-circuit test (the
  lecture's setting: PGE has no grid, and the tutorial adds the test to it);
* ``nothing``: all three off (every pair solved exactly: the naive engine);
* ``lecture``: the lecture's (unsound) short-circuit test instead of the sound one.

Each combination runs ``--repeat`` times (default 3; once if it takes more than a
quarter of the budget) and keeps the least CPU and wall time; the counts are the same in every repeat (checked: ``deterministic``).

The sound switches must not change any event: every run is checked against
the ``sound`` run (events, collisions, hits, and the final positions and
velocities bit for bit; column ``same``). The lecture run is expected to
differ: an audit run (with a collision log, untimed) compares its collision
trace with the sound run's, reports where and how they first diverge, counts
the contacts it reported with the bodies already overlapping (found late), and
the pairs still overlapping at the end.

Scenes:

* ``gas-N``: N discs of radius 5 at area fraction 0.1, speed 100, elasticity 1,
  no gravity, in a closed square box (four fixed walls); N = 100, 1000, 10000;
* ``manygrav``: 400 balls of mixed sizes bouncing under gravity in a closed box
  (elasticity 1), after PGE's many-balls-under-gravity demo;
* ``spinning``: 1000 bodies, half of them regular polygons spinning at up to
  20 rad/s, in a closed box (the scene of benchmarks/tumble.py), so polygon
  pairs go through the bounding-circle test and the rotating kernels;
* ``showcase``: ``pge.showcase.build_showcase()`` (circles, polygons, fixed
  pegs, gravity).

Every run happens in a forked child process (the compiled kernels are warmed
up once, before forking) and is given a wall-time budget (``--budget``): the
child stops a run whose projected time exceeds it, and the parent kills one
that overruns; both are reported as "skipped: >budget".

Usage (from the repository root, with ``pip install -e '.[bench]'``):

    .venv/bin/python benchmarks/broadphase.py                       # every scene, about 6 minutes
    .venv/bin/python benchmarks/broadphase.py --scenes gas-100 gas-1000 --budget 20

Writes ``benchmarks/results/broadphase-<hostname>.csv`` and a bar chart
``broadphase-<hostname>.png`` beside it; prints a table. Timings are only
reported, never asserted.
"""

from __future__ import annotations

import argparse
import csv
import datetime
import gc
import hashlib
import math
import multiprocessing
import os
import platform
import random
import socket
import subprocess
import sys
import time
import traceback
from pathlib import Path

HERE = Path(__file__).resolve().parent

COMBINATIONS = {
    "sound": {},
    "no-short-circuit": {"short_circuit": False},
    "no-boxes": {"boxes": False},
    "no-grid": {"grid": False},
    "short-circuit-only": {"boxes": False, "grid": False},
    "nothing": {"short_circuit": False, "boxes": False, "grid": False},
    "lecture": {"short_circuit": "lecture"},
}

#: a collision reported with the bodies overlapping deeper than this fraction of the
#: smaller body's bounding radius was found late (a sound run reports ~1e-15).
LATE_DEPTH = 1e-6
#: how many pieces a timed run is cut into; between them the child checks its budget.
CHUNKS = 40


# ------------------------------------------------------------------------- scenes


def gas(n: int):
    """N discs of radius 5, area fraction 0.1, speed 100, e = 1, in a closed square box."""
    from pge import World
    from pge.scenes import disc_gas

    radius = 5.0
    side = radius * math.sqrt(math.pi * n / 0.1)  # N pi r^2 / side^2 = 0.1
    scene = disc_gas(n, area_fraction=0.1, speed=100.0, seed=0, box=(0.0, 0.0, side, side))
    world = World(elasticity=1.0, bounds=scene.box)
    _walls(world, side, side)
    for position, velocity in zip(scene.positions, scene.velocities):
        world.add_circle(position, scene.radius, mass=1.0, velocity=velocity)
    return world


def manygrav(n: int = 400, seed: int = 0):
    """Balls of radius 0.006 to 0.014 thrown about under gravity in a closed unit box, e = 1."""
    from pge import World

    rng = random.Random(seed)
    world = World(gravity=(0.0, -9.81), elasticity=1.0)
    _walls(world, 1.0, 1.0)
    placed: list[tuple[float, float, float]] = []
    while len(placed) < n:
        r = rng.uniform(0.006, 0.014)
        x, y = rng.uniform(r + 0.001, 1.0 - r - 0.001), rng.uniform(r + 0.001, 1.0 - r - 0.001)
        if all(math.hypot(x - px, y - py) > r + pr + 0.001 for px, py, pr in placed):
            placed.append((x, y, r))
            world.add_circle((x, y), r, mass=r * r, velocity=(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)))
    return world


def spinning(n: int = 1000):
    """benchmarks/tumble.py's gas: every other disc a regular polygon spinning at up to 20 rad/s."""
    sys.path.insert(0, str(HERE))
    from tumble import build

    return build(n, 20.0, 0)


def showcase():
    """The headless showcase scene."""
    from pge.showcase import build_showcase

    return build_showcase()


def _walls(world, width: float, height: float) -> None:
    t = 0.05 * max(width, height)
    world.add_box(-t, -t, width + 2 * t, t, fixed=True)
    world.add_box(-t, height, width + 2 * t, t, fixed=True)
    world.add_box(-t, 0.0, t, height, fixed=True)
    world.add_box(width, 0.0, t, height, fixed=True)


#: name -> (builder, simulated seconds of the timed run, simulated seconds of the lecture audit)
SCENES = {
    "gas-100": (lambda: gas(100), 50.0, 50.0),
    "gas-1000": (lambda: gas(1000), 10.0, 10.0),
    "gas-10000": (lambda: gas(10000), 2.0, 1.0),
    "manygrav": (manygrav, 5.0, 5.0),
    "spinning": (spinning, 5.0, 2.0),
    "showcase": (showcase, 5.0, 5.0),
}


# ------------------------------------------------------------------------- one run


def timed_run(scene: str, combination: str, budget: float) -> dict:
    """Build ``scene``, switch the stages of ``combination`` off, run it, return its numbers.

    Stops early (``skipped``) when the time spent so far projects past ``budget``.
    """
    build, duration, _ = SCENES[scene]
    world = build()
    world.broadphase = COMBINATIONS[combination]
    gc.collect()
    wall = 0.0
    cpu = time.process_time()
    for k in range(1, CHUNKS + 1):
        start = time.perf_counter()
        world.run_until(duration * k / CHUNKS)
        wall += time.perf_counter() - start
        if wall * CHUNKS / k > budget and k < CHUNKS:
            return {"skipped": f">{budget:g} s (projected {wall * CHUNKS / k:.0f} s)"}
    cpu = time.process_time() - cpu
    stats = world.stats
    row = {"wall_s": wall, "cpu_s": cpu, "n_bodies": len(world), "duration_s": duration}
    for key in ("events", "collisions", "horizons", "candidates", "box_rejects", "bound_rejects", "predictions", "hits"):
        row[key] = stats[key]
    state = world._state
    # Positions, velocities and their reference times, bit for bit, to check the sound switches.
    row["fingerprint"] = hashlib.sha256(state.F[: state.n, :5].tobytes()).hexdigest()
    row["overlapping_end"] = len(world.overlaps(_late_tolerance(world)))
    return row


def lecture_audit(scene: str) -> dict:
    """Sound and lecture runs with collision logs: where the lecture's run departs, and how."""
    from pge.traces import CollisionLog, compare_traces

    build, _, duration = SCENES[scene]
    logs = {}
    for name in ("sound", "lecture"):
        world = build()
        world.broadphase = COMBINATIONS[name]
        log = CollisionLog(world, depths=True)
        world.run_until(duration)
        logs[name] = (world, log)
    sound_world, sound = logs["sound"]
    lecture_world, lecture = logs["lecture"]
    tolerance = _late_tolerance(sound_world)
    divergence = compare_traces(sound.entries, lecture.entries)
    return {
        "audit_s": duration,
        "sound_collisions": len(sound.entries),
        "lecture_collisions": len(lecture.entries),
        "sound_late": sound.late(tolerance),
        "lecture_late": lecture.late(tolerance),
        "first_divergence_time": divergence.reference[0] if divergence.reference else math.nan,
        "first_divergence_index": divergence.index,
        "first_divergence": divergence.fate,
        "first_divergence_delay": divergence.delay,
        "lecture_overlapping_end": len(lecture_world.overlaps(tolerance)),
    }


def _late_tolerance(world) -> float:
    from pge.core import layout as L

    state = world._state
    reach = [state.F[i, L.REACH] for i in range(state.n) if not state.I[i, L.FIXED]]
    return LATE_DEPTH * min(reach)


def _child(connection, job, argument, budget) -> None:
    try:
        result = job(*argument, budget) if job is timed_run else job(*argument)
    except Exception as error:  # reported in the table, not raised: one bad run must not stop the rest
        result = {"error": f"{type(error).__name__}: {error}", "trace": traceback.format_exc()}
    connection.send(result)
    connection.close()


def in_child(job, argument, budget: float) -> dict:
    """Run ``job(*argument)`` in a forked child; kill it past ``budget`` (plus slack)."""
    context = multiprocessing.get_context("fork")
    receive, send = context.Pipe(duplex=False)
    process = context.Process(target=_child, args=(send, job, argument, budget))
    process.start()
    send.close()
    deadline = 1.5 * budget + 10.0  # the child stops itself first; this catches a run stuck inside a chunk
    result = {"skipped": f">{budget:g} s (killed after {deadline:.0f} s)"}
    if receive.poll(deadline):
        try:
            result = receive.recv()
        except EOFError:
            result = {"error": f"child died (exit code {process.exitcode})"}
    process.kill()
    process.join()
    return result


# ------------------------------------------------------------------------- report


def warm_up() -> float:
    """Load (or compile) every kernel the runs use, before timing and forking."""
    from pge import World

    start = time.perf_counter()
    world = World(gravity=(0.0, -9.81), elasticity=1.0)
    _walls(world, 1.0, 1.0)
    for k in range(8):
        world.add_circle((0.1 + 0.1 * k, 0.3), 0.03, mass=1.0, velocity=(1.0, 0.5 * k - 2.0))
        world.add_polygon(
            [(0.1 + 0.1 * k + dx, 0.7 + dy) for dx, dy in ((-0.03, -0.02), (0.03, -0.02), (0.0, 0.03))],
            mass=1.0,
            velocity=(0.3 * k - 1.0, 1.0),
            angular_velocity=5.0 - k,
        )
    for combination in COMBINATIONS.values():
        world.broadphase = combination
        world.run(0.2)
    from pge.traces import CollisionLog

    CollisionLog(world, depths=True)
    world.run(0.2)
    return time.perf_counter() - start


COLUMNS = [
    ("scene", "scene", "s"),
    ("bodies", "n_bodies", "d"),
    ("sim s", "duration_s", "g"),
    ("combination", "combination", "s"),
    ("wall s", "wall_s", ".3f"),
    ("cpu s", "cpu_s", ".3f"),
    ("x sound", "slowdown", ".2f"),
    ("events", "events", "d"),
    ("candidates", "candidates", "d"),
    ("grid avoided", "grid_avoided", "d"),
    ("box rejects", "box_rejects", "d"),
    ("bound rejects", "bound_rejects", "d"),
    ("predictions", "predictions", "d"),
    ("hits", "hits", "d"),
    ("same", "same", "s"),
]


def cell(row: dict, key: str, spec: str) -> str:
    value = row.get(key)
    if value is None or value == "" or (isinstance(value, float) and math.isnan(value)):
        return "-"
    return format(value, spec)


def table(rows: list[dict]) -> str:
    header = [title for title, _, _ in COLUMNS]
    body = []
    for row in rows:
        if "skipped" in row or "error" in row:
            first = [cell(row, key, spec) for _, key, spec in COLUMNS[:4]]
            note = f"skipped: {row['skipped']}" if "skipped" in row else f"error: {row['error'][:72]}..."
            body.append(first + [note] + [""] * (len(COLUMNS) - 5))
        else:
            body.append([cell(row, key, spec) for _, key, spec in COLUMNS])
    widths = [max(len(text) for text in column) for column in zip(header, *[b for b in body if len(b[4]) < 12])]
    lines = []
    for line in [header] + body:
        if line[4].startswith(("skipped", "error")):
            lines.append("  ".join(text.rjust(width) for text, width in zip(line[:4], widths)) + "  " + line[4])
        else:
            lines.append("  ".join(text.rjust(width) for text, width in zip(line, widths)))
    lines.insert(1, "  ".join("-" * width for width in widths))
    return "\n".join(lines)


def chart(rows: list[dict], path: Path) -> None:
    """Grouped bars: wall time of each combination per scene, relative to the sound run (log scale)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.ticker

    scenes = list(dict.fromkeys(row["scene"] for row in rows))
    names = list(COMBINATIONS)
    figure, axes = plt.subplots(2, 1, figsize=(11, 8), sharex=True)
    width = 0.8 / len(names)
    for k, name in enumerate(names):
        xs, times, preds, labels = [], [], [], []
        for s, scene in enumerate(scenes):
            row = next((r for r in rows if r["scene"] == scene and r["combination"] == name), None)
            if row is None:
                continue
            x = s + (k - (len(names) - 1) / 2) * width
            if "wall_s" in row:
                xs.append(x)
                times.append(row["slowdown"])
                preds.append(row["predictions"])
            else:
                labels.append(x)
        bars = axes[0].bar(xs, times, width, label=name)
        axes[1].bar(xs, preds, width, color=bars.patches[0].get_facecolor() if bars.patches else None)
        for x in labels:
            axes[0].text(x, 1.0, "skipped", rotation=90, ha="center", va="bottom", fontsize=7)
    axes[0].set_yscale("log")
    axes[0].yaxis.set_major_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
    axes[0].yaxis.set_minor_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
    axes[0].axhline(1.0, color="black", linewidth=0.6)
    axes[0].set_ylabel("CPU time / sound run's")
    axes[0].set_title("pge broad phase: each stage switched off (benchmarks/broadphase.py)")
    axes[0].legend(ncol=3, fontsize=8)
    axes[1].set_yscale("log")
    axes[1].set_ylabel("exact predictions")
    axes[1].set_xlim(-0.5, len(scenes) - 0.5)  # room for the "skipped" marks beside the last bars
    axes[1].set_xticks(range(len(scenes)))
    axes[1].set_xticklabels(scenes)
    figure.tight_layout()
    figure.savefig(path, dpi=110)
    plt.close(figure)


def _numbers(row: dict) -> dict:
    """A CSV row with its empty cells dropped and its numeric cells as numbers."""
    out = {}
    for key, value in row.items():
        if value == "":
            continue
        try:
            out[key] = int(value)
        except ValueError:
            try:
                out[key] = float(value)
            except ValueError:
                out[key] = value
    return out


def git_commit(where: Path) -> str:
    """The commit of the checkout holding ``where`` (``+dirty`` if changed): gas.py's."""
    sys.path.insert(0, str(HERE))
    from gas import git_commit as commit_of

    return commit_of(where)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scenes", nargs="+", default=list(SCENES), choices=list(SCENES))
    parser.add_argument("--combinations", nargs="+", default=list(COMBINATIONS), choices=list(COMBINATIONS))
    parser.add_argument("--budget", type=float, default=30.0, help="wall seconds allowed per timed run (default 30)")
    parser.add_argument("--repeat", type=int, default=3, help="runs per combination; the best is kept (default 3)")
    parser.add_argument("--no-audit", action="store_true", help="skip the lecture audit runs")
    parser.add_argument("--out", type=Path, default=HERE / "results" / f"broadphase-{socket.gethostname()}.csv")
    parser.add_argument("--replot", type=Path, default=None, help="only redraw the chart from this CSV")
    args = parser.parse_args(argv)
    if args.replot is not None:
        with open(args.replot, newline="", encoding="utf-8") as handle:
            rows = [_numbers(row) for row in csv.DictReader(handle)]
        chart(rows, args.replot.with_suffix(".png"))
        print(f"chart: {args.replot.with_suffix('.png')}")
        return 0
    if not args.budget > 0:
        parser.error("--budget must be positive")
    if args.repeat < 1:
        parser.error("--repeat must be at least 1")
    if "sound" not in args.combinations:
        args.combinations.insert(0, "sound")  # every other run is compared with it

    import numba
    import numpy
    import pge

    common = {
        "hostname": socket.gethostname(),
        "python": platform.python_version(),
        "numpy": numpy.__version__,
        "numba": numba.__version__,
        "pge_commit": git_commit(Path(pge.__file__).resolve().parent),
        "timestamp_utc": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ"),
        "budget_s": args.budget,
        "repeat": args.repeat,
    }
    warm = warm_up()
    print(f"warm-up (kernels loaded or compiled) {warm:.1f} s; budget {args.budget:g} s per run; "
          f"pge {common['pge_commit']}, numba {common['numba']}, load {os.getloadavg()[0]:.2f}", flush=True)
    rows, audits = [], {}
    for scene in args.scenes:
        sound = None
        for combination in args.combinations:
            print(f"{scene:>10} {combination:<17}", end="", flush=True)
            result = in_child(timed_run, (scene, combination), args.budget)
            if "wall_s" in result:
                result["deterministic"] = True
            # Best of --repeat: the machine is shared, and the least disturbed run is the
            # best estimate of the cost; every repeat must give the same events.
            for _ in range(args.repeat - 1):
                if "wall_s" not in result or result["wall_s"] > 0.25 * args.budget:
                    break  # a long run is less disturbed, relatively, and repeating it costs most
                again = in_child(timed_run, (scene, combination), args.budget)
                if "wall_s" not in again:
                    break
                if again["fingerprint"] != result["fingerprint"]:
                    result["deterministic"] = False
                result["cpu_s"] = min(result["cpu_s"], again["cpu_s"])
                result["wall_s"] = min(result["wall_s"], again["wall_s"])
            row = dict(common, scene=scene, combination=combination, loadavg_1min=os.getloadavg()[0], **result)
            if combination == "sound":
                sound = row if "wall_s" in row else None
            if "wall_s" in row and sound is not None:
                # CPU time: on a shared machine it is steadier than wall time.
                row["slowdown"] = row["cpu_s"] / sound["cpu_s"]
                row["grid_avoided"] = None
                if combination != "lecture":
                    same = all(row[k] == sound[k] for k in ("events", "collisions", "hits", "fingerprint"))
                    row["same"] = "yes" if same else "NO"
                else:
                    row["same"] = "yes" if row["fingerprint"] == sound["fingerprint"] else "no (unsound)"
            rows.append(row)
            print(f" {row.get('wall_s', math.nan):8.3f} s  {row.get('skipped', row.get('error', ''))}", flush=True)
        # Pairs the grid kept from the broad-phase tests: the same events, so the
        # difference of the candidate counts is exact.
        by = {r["combination"]: r for r in rows if r["scene"] == scene and "wall_s" in r}
        if "sound" in by and "no-grid" in by:
            by["sound"]["grid_avoided"] = by["no-grid"]["candidates"] - by["sound"]["candidates"]
        if "lecture" in args.combinations and not args.no_audit:
            print(f"{scene:>10} lecture audit    ", end="", flush=True)
            audits[scene] = in_child(lecture_audit, (scene,), 2 * args.budget)
            print(" done", flush=True)
        if sound is not None:
            for row in rows:
                if row["scene"] == scene and scene in audits:
                    row.update({f"audit_{k}": v for k, v in audits[scene].items() if k != "trace"})
    for row in rows:
        row.pop("trace", None)
        row["n_bodies"] = row.get("n_bodies") or next(
            (r.get("n_bodies") for r in rows if r["scene"] == row["scene"] and r.get("n_bodies")), None
        )
        row["duration_s"] = SCENES[row["scene"]][1]

    print()
    print(table(rows))
    print()
    print("'x sound': CPU time over the sound run's; 'grid avoided' (on the sound row): candidate pairs the grid never produced (no-grid run's candidates "
          "minus the sound run's); 'same': events, collisions, hits and final positions/velocities bit-identical "
          "to the sound run")
    if audits:
        print()
        print("Lecture's short-circuit test, audited against the sound run (collision logs, untimed):")
        for scene, audit in audits.items():
            if "error" in audit or "skipped" in audit:
                print(f"  {scene}: {audit.get('error') or 'skipped: ' + audit['skipped']}")
                continue
            print(
                f"  {scene}: {audit['audit_s']:g} s simulated; sound {audit['sound_collisions']} collisions "
                f"({audit['sound_late']} found late), lecture {audit['lecture_collisions']} "
                f"({audit['lecture_late']} found late, bodies overlapping > {LATE_DEPTH:g} R); first divergence: "
                f"{audit['first_divergence']} at collision #{audit['first_divergence_index']} "
                f"(t = {audit['first_divergence_time']:.6g} s, delay {audit['first_divergence_delay']:.3g} s); "
                f"{audit['lecture_overlapping_end']} pairs overlapping at the end"
            )
    args.out.parent.mkdir(parents=True, exist_ok=True)
    keys = list(dict.fromkeys(key for row in rows for key in row if key != "fingerprint"))
    with open(args.out, "w", newline="", encoding="utf-8") as handle:
        writer = csv.DictWriter(handle, fieldnames=keys, extrasaction="ignore")
        writer.writeheader()
        for row in rows:
            writer.writerow({key: row.get(key, "") for key in keys})
    png = args.out.with_suffix(".png")
    chart([row for row in rows if "slowdown" in row or "wall_s" not in row], png)
    print(f"CSV: {args.out}\nchart: {png}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
