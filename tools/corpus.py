"""A seeded corpus of random game-like scenes, and a benchmark that runs it.

    .venv/bin/python tools/corpus.py show 7                  # describe scene 7
    .venv/bin/python tools/corpus.py run --seeds 0:200 --until 20 --out benchmarks/results/corpus.csv
    .venv/bin/python tools/corpus.py summary benchmarks/results/corpus.csv [--seeds 0:100]

A scene is a closed box (four fixed walls around the unit square, 0.01-0.05 thick), a few fixed
pegs (circles) and ramps (thin tilted fixed rectangles), and 4-22 moving circles and convex
polygons (boxes, triangles, pentagons) of bounding radius 0.01-0.06 with random masses,
elasticities (0.3-1), friction (0-0.6, in some scenes and on some bodies), spin and velocity (up
to 3 units/s); gravity (0, -9.81) in most scenes, none in the others. No two bodies overlap at the
start: each is placed by rejection sampling with a gap, and a seed whose draw cannot be placed is
drawn again from ``(seed, attempt)``, so ``scene(seed)`` is deterministic.

As a module: ``scene_spec(seed)`` (plain data), ``build(spec)`` / ``scene(seed)`` (a ``pge.World``),
``run_scene(seed, until)`` (one measured run, in-process), ``escaped(world)``.

``run`` runs each scene in a worker process (two at most) with a wall-time limit: a scene over
the limit is recorded as ``timeout`` and its worker is killed and replaced, so the tool never
hangs. It writes one CSV row per seed, prints a summary and, if matplotlib is installed, saves a
histogram of wall times next to the CSV.
"""

from __future__ import annotations

import argparse
import csv
import math
import multiprocessing as mp
import os
import random
import statistics
import sys
import time

_HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(_HERE, "..", "tests"))

from strategies import closed_box, regular_polygon  # noqa: E402  (the test-suite's plain geometry)

TAU = 2.0 * math.pi
GRAVITY = (0.0, -9.81)
BOX = (0.0, 0.0, 1.0, 1.0)  # the inner faces of the walls
GAP = 0.004  # smallest clearance between bodies' bounding shapes at the start
SAMPLE = 0.1  # simulated seconds between two measurements of the deepest overlap during a run
MAX_ATTEMPTS = 50

FIELDS = [
    "seed",
    "bodies",
    "moving",
    "gravity",
    "outcome",
    "wall_s",
    "events",
    "collisions",
    "events_per_body_per_s",
    "max_overlap",
    "overlap_pairs",
    "max_overlap_sampled",
    "escaped",
    "final_time",
    "island_steps",
]


# ---------------------------------------------------------------- scene generation


class _Placer:
    """Rejection sampling against what is already placed: circles (x, y, r) and capsules."""

    def __init__(self, rng: random.Random, gap: float):
        self.rng = rng
        self.gap = gap
        self.circles: list[tuple[float, float, float]] = []
        self.capsules: list[tuple[float, float, float, float, float]] = []

    def free(self, x: float, y: float, r: float) -> bool:
        g = self.gap
        for px, py, pr in self.circles:
            if math.hypot(x - px, y - py) <= r + pr + g:
                return False
        for ax, ay, bx, by, h in self.capsules:
            if _segment_distance(x, y, ax, ay, bx, by) <= r + h + g:
                return False
        return True

    def spot(self, r: float, area=BOX, tries: int = 400):
        """A centre for a body of bounding radius ``r`` inside ``area`` and clear of the rest, or None."""
        x0, y0, x1, y1 = area
        m = r + self.gap
        if x1 - x0 <= 2 * m or y1 - y0 <= 2 * m:
            return None
        for _ in range(tries):
            x = self.rng.uniform(x0 + m, x1 - m)
            y = self.rng.uniform(y0 + m, y1 - m)
            if self.free(x, y, r):
                return x, y
        return None


def _segment_distance(x, y, ax, ay, bx, by) -> float:
    dx, dy = bx - ax, by - ay
    t = ((x - ax) * dx + (y - ay) * dy) / (dx * dx + dy * dy)
    t = min(1.0, max(0.0, t))
    return math.hypot(x - (ax + t * dx), y - (ay + t * dy))


def _rectangle(cx, cy, width, height, angle):
    """Vertices (anticlockwise) of a ``width`` x ``height`` rectangle centred at (cx, cy), turned by ``angle``."""
    c, s = math.cos(angle), math.sin(angle)
    out = []
    for u, v in ((-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)):
        px, py = u * width, v * height
        out.append((cx + c * px - s * py, cy + s * px + c * py))
    return out


def _draw(rng: random.Random) -> dict | None:
    """One draw of a scene, or None when its bodies cannot all be placed."""
    gravity = GRAVITY if rng.random() < 0.8 else (0.0, 0.0)
    wall = rng.uniform(0.01, 0.05)
    wall_elasticity = rng.uniform(0.7, 1.0)
    frictional = rng.random() < 0.6  # a scene with friction at all
    wall_friction = rng.uniform(0.0, 0.6) if frictional and rng.random() < 0.5 else 0.0
    placer = _Placer(rng, GAP)
    fixed = []

    for k in range(rng.randint(0, 3)):  # ramps: thin tilted rectangles
        length = rng.uniform(0.15, 0.35)
        thick = rng.uniform(0.008, 0.02)
        tilt = rng.choice((-1.0, 1.0)) * math.radians(rng.uniform(8.0, 35.0))
        half = 0.5 * length
        where = placer.spot(half + thick, (0.0, 0.1, 1.0, 0.9))
        if where is None:
            return None
        cx, cy = where
        ax, ay = cx - half * math.cos(tilt), cy - half * math.sin(tilt)
        bx, by = cx + half * math.cos(tilt), cy + half * math.sin(tilt)
        # The rectangle lies inside the capsule of its centre line with radius thick / 2.
        placer.capsules.append((ax, ay, bx, by, 0.5 * thick))
        fixed.append(
            {
                "kind": "polygon",
                "name": f"ramp {k}",
                "vertices": _rectangle(cx, cy, length, thick, tilt),
                "elasticity": wall_elasticity,
                "friction": wall_friction,
            }
        )

    for k in range(rng.randint(0, 6)):  # pegs
        r = rng.uniform(0.008, 0.03)
        where = placer.spot(r, (0.0, 0.1, 1.0, 0.95))
        if where is None:
            return None
        placer.circles.append((*where, r))
        fixed.append(
            {
                "kind": "circle",
                "name": f"peg {k}",
                "position": where,
                "radius": r,
                "elasticity": wall_elasticity,
                "friction": wall_friction,
            }
        )

    moving = []
    spin_share = rng.choice((0.0, 0.3, 0.7, 1.0))
    for k in range(rng.randint(4, 22)):
        shape = rng.choice(("circle", "circle", "box", "triangle", "pentagon"))
        size = rng.uniform(0.01, 0.06)  # bounding radius
        where = placer.spot(size)
        if where is None:
            return None
        x, y = where
        placer.circles.append((x, y, size))
        speed = rng.uniform(0.0, 3.0) if rng.random() < 0.8 else 0.0
        heading = rng.uniform(0.0, TAU)
        spec = {
            "name": f"{shape} {k}",
            "mass": rng.uniform(0.1, 3.0),
            "elasticity": rng.uniform(0.3, 1.0),
            "friction": rng.uniform(0.0, 0.6) if frictional and rng.random() < 0.7 else 0.0,
            "velocity": (speed * math.cos(heading), speed * math.sin(heading)),
            "angular_velocity": rng.uniform(-12.0, 12.0) if rng.random() < spin_share else 0.0,
        }
        turn = rng.uniform(0.0, TAU)
        if shape == "circle":
            spec.update(kind="circle", position=(x, y), radius=size)
        elif shape == "box":
            aspect = rng.uniform(0.4, 1.0)  # height / width; the diagonal is 2 * size
            width = 2.0 * size / math.sqrt(1.0 + aspect * aspect)
            spec.update(kind="polygon", vertices=_rectangle(x, y, width, aspect * width, turn))
        else:
            sides = 3 if shape == "triangle" else 5
            spec.update(kind="polygon", vertices=regular_polygon(sides, size, (x, y), turn))
        moving.append(spec)

    return {"gravity": gravity, "wall": wall, "wall_elasticity": wall_elasticity,
            "wall_friction": wall_friction, "fixed": fixed, "moving": moving}


def scene_spec(seed: int) -> dict:
    """The plain description of scene ``seed`` (deterministic): walls, fixed and moving bodies."""
    for attempt in range(MAX_ATTEMPTS):
        spec = _draw(random.Random(f"pge-corpus:{seed}:{attempt}"))
        if spec is not None:
            spec["seed"] = seed
            spec["attempt"] = attempt
            return spec
    raise RuntimeError(f"corpus: scene {seed} could not be placed in {MAX_ATTEMPTS} draws")


def build(spec: dict):
    """A fresh ``pge.World`` holding the scene ``spec`` describes."""
    from pge import World

    world = World(gravity=spec["gravity"])
    closed_box(world, *BOX, thickness=spec["wall"], elasticity=spec["wall_elasticity"],
               friction=spec["wall_friction"])
    for body in spec["fixed"] + spec["moving"]:
        options = {k: body[k] for k in ("name", "mass", "elasticity", "friction", "velocity", "angular_velocity")
                   if k in body}
        if "mass" not in body:
            options["fixed"] = True
        if body["kind"] == "circle":
            world.add_circle(body["position"], body["radius"], **options)
        else:
            world.add_polygon(body["vertices"], **options)
    return world


def scene(seed: int):
    """The ``pge.World`` of scene ``seed``: the same scene for the same seed, always."""
    return build(scene_spec(seed))


# ---------------------------------------------------------------- checks and one run


def escaped(world, box=BOX) -> list:
    """Moving bodies whose centre is outside the walls' inner faces (or not a number)."""
    x0, y0, x1, y1 = box
    out = []
    for body in world.bodies:
        if body.is_fixed:
            continue
        x, y = body.position
        if not (x0 <= x <= x1 and y0 <= y <= y1):  # also catches NaN
            out.append(body)
    return out


def run_scene(seed: int, until: float) -> dict:
    """Build scene ``seed``, run it to ``until`` in this process and measure it (one CSV row)."""
    spec = scene_spec(seed)
    world = build(spec)
    moving = len(spec["moving"])
    row = {"seed": seed, "bodies": len(world), "moving": moving, "gravity": spec["gravity"][1] != 0.0}
    start = time.perf_counter()
    sampling = 0.0  # wall time spent measuring overlaps, left out of wall_s
    deepest = 0.0
    try:
        for k in range(1, int(math.ceil(until / SAMPLE - 1e-9)) + 1):
            world.run_until(min(k * SAMPLE, until))
            begin = time.perf_counter()
            deepest = max([deepest] + [d for _, _, d in world.overlaps()])
            sampling += time.perf_counter() - begin
        row["outcome"] = "ok"
    except Exception as error:  # the benchmark records every failure, whatever it is
        message = " ".join(str(error).split())
        row["outcome"] = f"{type(error).__name__}: {message[:300]}"
    row["wall_s"] = time.perf_counter() - start - sampling
    row["max_overlap_sampled"] = deepest
    stats = world.stats
    t = world.time
    row["events"] = stats["events"]
    row["collisions"] = stats["collisions"]
    row["events_per_body_per_s"] = stats["events"] / (moving * t) if t > 0 else float("nan")
    try:
        found = world.overlaps()
        row["max_overlap"] = max((d for _, _, d in found), default=0.0)
        row["overlap_pairs"] = len(found)
    except Exception as error:  # noqa: BLE001
        row["max_overlap"] = float("nan")
        row["overlap_pairs"] = f"{type(error).__name__}"
    row["escaped"] = len(escaped(world))
    row["final_time"] = t
    row["island_steps"] = stats["island_steps"]
    return row


# ---------------------------------------------------------------- the corpus run


def _warm_up():
    """Load (or compile) the kernels a corpus scene uses, once per worker and outside any
    timing: flight and collisions (scene 0's start), and an island's step (a box and a ball
    landing on a floor; Numba compiles a kernel at its first call, and a scene's first
    island would otherwise pay for it); and the same for a scene whose polygons are all
    fixed, for which the loop has a version of its own (a ball alone on the floor)."""
    from pge import World

    build(scene_spec(0)).run_until(0.01)
    for movable_box in (True, False):
        world = World(gravity=(0.0, -9.81), bounds=(-2.0, -1.0, 2.0, 2.0))
        world.add_box(-2.0, -1.0, 4.0, 1.0, fixed=True)
        if movable_box:
            world.add_box(-0.5, 0.05, 0.2, 0.2, mass=1.0, friction=0.5, elasticity=0.3)
        world.add_circle((0.5, 0.2), 0.1, mass=1.0, friction=0.5, elasticity=0.3)
        world.run_until(1.0)


def _worker(inbox, outbox):
    _warm_up()

    outbox.send(("ready", None))
    while True:
        job = inbox.recv()
        if job is None:
            return
        seed, until = job
        outbox.send(("done", run_scene(seed, until)))


class _Slot:
    def __init__(self, ctx):
        self.ctx = ctx
        self.start_process()

    def start_process(self):
        parent_in, child_out = self.ctx.Pipe(duplex=False)
        child_in, parent_out = self.ctx.Pipe(duplex=False)
        self.proc = self.ctx.Process(target=_worker, args=(child_in, child_out), daemon=True)
        self.proc.start()
        self.results, self.jobs = parent_in, parent_out
        self.ready = False
        self.seed = None
        self.started = None

    def kill(self):
        self.proc.kill()
        self.proc.join()


def run_corpus(seeds, until: float, limit: float, processes: int = 2, progress=print, on_row=None) -> list[dict]:
    """Run every seed in worker processes; returns the rows in seed order.

    ``on_row(rows)`` is called with the rows so far (seed order) after each scene; an interrupt
    (Ctrl-C) kills the workers and returns the rows finished."""
    ctx = mp.get_context("spawn")
    pending = list(seeds)
    slots = [_Slot(ctx) for _ in range(max(1, min(processes, len(pending))))]
    rows = {}
    total = len(pending)

    def record(row):
        rows[row["seed"]] = row
        if on_row is not None:
            on_row([rows[s] for s in sorted(rows)])
        t = row["final_time"]
        progress(f"[{len(rows)}/{total}] seed {row['seed']}: {row['outcome'][:70]}, "
                 f"{row['wall_s']:.2f} s, {row['events'] or '?'} events, t = {t if t == '' else f'{t:.4g}'}",
                 flush=True)

    try:
        _schedule(slots, pending, rows, until, limit, record)
    except KeyboardInterrupt:
        progress(f"interrupted: keeping the {len(rows)} scenes finished")
        for slot in slots:
            slot.kill()
        return [rows[s] for s in sorted(rows)]
    for slot in slots:
        try:
            slot.jobs.send(None)
        except (BrokenPipeError, OSError):
            pass
        slot.proc.join(5)
        if slot.proc.is_alive():
            slot.kill()
    return [rows[s] for s in sorted(rows)]


def _schedule(slots, pending, rows, until, limit, record):
    while pending or any(s.seed is not None for s in slots):
        for slot in slots:
            if slot.seed is None and pending and slot.ready:
                slot.seed = pending.pop(0)
                slot.started = time.perf_counter()
                slot.jobs.send((slot.seed, until))
        for slot in slots:
            if slot.results.poll():
                try:
                    kind, row = slot.results.recv()
                except EOFError:
                    kind, row = "dead", None
                if kind == "ready":
                    slot.ready = True
                elif kind == "done":
                    record(row)
                    slot.seed = None
                    continue
            if not slot.proc.is_alive() and (slot.seed is not None or not slot.ready):
                if slot.seed is not None:
                    record(_failed_row(slot.seed, f"crash: worker exit code {slot.proc.exitcode}",
                                       time.perf_counter() - slot.started))
                slot.start_process()
            elif slot.seed is not None and time.perf_counter() - slot.started > limit:
                record(_failed_row(slot.seed, "timeout", time.perf_counter() - slot.started))
                slot.kill()
                slot.start_process()
        time.sleep(0.01)


def _failed_row(seed, outcome, wall):
    spec = scene_spec(seed)
    n = len(spec["fixed"]) + len(spec["moving"]) + 4
    return {"seed": seed, "bodies": n, "moving": len(spec["moving"]), "gravity": spec["gravity"][1] != 0.0,
            "outcome": outcome, "wall_s": wall, "events": "", "collisions": "", "events_per_body_per_s": "",
            "max_overlap": "", "overlap_pairs": "", "max_overlap_sampled": "", "escaped": "", "final_time": ""}


def _percentile(values, q):
    values = sorted(values)
    if not values:
        return float("nan")
    k = (len(values) - 1) * q
    lo, hi = math.floor(k), math.ceil(k)
    return values[lo] + (values[hi] - values[lo]) * (k - lo)


def summary(rows, until: float) -> str:
    """The summary table (markdown) of a corpus run."""
    lines = []
    outcomes: dict[str, int] = {}
    for row in rows:
        key = row["outcome"] if row["outcome"] in ("ok", "timeout") else row["outcome"].split(":")[0]
        outcomes[key] = outcomes.get(key, 0) + 1
    walls = [float(r["wall_s"]) for r in rows]
    finished = [r for r in rows if r["events"] != ""]
    rates = [float(r["events_per_body_per_s"]) for r in finished
             if r["events_per_body_per_s"] == r["events_per_body_per_s"]]
    median = statistics.median(walls) if walls else float("nan")
    lines.append(f"| scenes | {len(rows)} (simulated {until:g} s each) |")
    lines.append("|---|---|")
    lines.append("| outcomes | " + ", ".join(f"{k}: {v}" for k, v in sorted(outcomes.items())) + " |")
    lines.append(f"| wall time median / p90 / max | {median:.2f} s / {_percentile(walls, 0.9):.2f} s / "
                 f"{max(walls, default=float('nan')):.2f} s |")
    lines.append(f"| wall time total | {sum(walls):.0f} s |")
    lines.append(f"| slowest / median | {max(walls, default=float('nan')) / median:.0f} |" if median > 0
                 else "| slowest / median | n/a |")
    if rates:
        lines.append(f"| events per body per simulated s, median / max | {statistics.median(rates):.0f} / "
                     f"{max(rates):.0f} |")
    overlapping = [r for r in finished if r["max_overlap"] != "" and float(r["max_overlap"]) > 1e-9]
    lines.append(f"| scenes overlapping > 1e-9 at the end | {len(overlapping)} "
                 + (f"({', '.join(str(r['seed']) for r in overlapping)})" if overlapping else "") + " |")
    sampled = [float(r["max_overlap_sampled"]) for r in finished if r.get("max_overlap_sampled", "") not in ("", None)]
    if sampled:
        deep = sorted(sampled)
        lines.append(f"| deepest overlap during a run (every {SAMPLE:g} s): scenes > 1e-9, median / p90 / max | "
                     f"{sum(d > 1e-9 for d in deep)} / {statistics.median(deep):.2g} / {_percentile(deep, 0.9):.2g} / "
                     f"{deep[-1]:.2g} |")
    gone = [r for r in finished if r["escaped"] not in ("", 0, "0")]
    lines.append(f"| scenes with a body out of the box | {len(gone)} "
                 + (f"({', '.join(str(r['seed']) for r in gone)})" if gone else "") + " |")
    lines.append("")
    lines.append("Slowest seeds:")
    lines.append("")
    lines.append("| seed | moving bodies | wall s | events | simulated t | outcome |")
    lines.append("|---|---|---|---|---|---|")
    for r in sorted(rows, key=lambda r: -float(r["wall_s"]))[:8]:
        t = f"{float(r['final_time']):.4g}" if r["final_time"] != "" else "-"
        lines.append(f"| {r['seed']} | {r['moving']} | {float(r['wall_s']):.2f} | {r['events'] or '-'} | {t} | "
                     f"{r['outcome'][:80]} |")
    failing = [r for r in rows if r["outcome"] != "ok"]
    if failing:
        lines.append("")
        lines.append("Failing seeds:")
        lines.append("")
        for r in failing:
            lines.append(f"* seed {r['seed']}: {r['outcome']}")
    return "\n".join(lines)


def _plot(rows, path) -> None:
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib is not installed: no histogram of wall times")
        return
    walls = [float(r["wall_s"]) for r in rows]
    fig, ax = plt.subplots(figsize=(7, 4))
    lo = max(min(walls), 1e-3)
    hi = max(max(walls), lo * 1.01)
    bins = [lo * (hi / lo) ** (k / 30) for k in range(31)]
    ax.hist(walls, bins=bins)
    ax.set_xscale("log")
    ax.set_xlabel("wall time per scene (s)")
    ax.set_ylabel("scenes")
    ax.set_title(f"Random game-like corpus: {len(rows)} scenes")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    print(f"histogram: {path}")


def _seed_range(text: str):
    if "," in text:
        return [int(part) for part in text.split(",")]
    if ":" in text:
        a, b = text.split(":")
        return range(int(a), int(b))
    return range(int(text), int(text) + 1)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="command", required=True)
    run = sub.add_parser("run", help="run scenes in worker processes and write a CSV")
    run.add_argument("--seeds", type=_seed_range, default=range(0, 200), help="A:B, or a list A,B,C (default 0:200)")
    run.add_argument("--until", type=float, default=20.0, help="simulated seconds (20)")
    run.add_argument("--timeout", type=float, default=120.0, help="wall-time limit per scene, s (120)")
    run.add_argument("--processes", type=int, default=2, help="worker processes (at most 2)")
    run.add_argument("--out", default=os.path.join("benchmarks", "results", "corpus.csv"))
    run.add_argument("--plot", default=None, help="histogram path (default: <out dir>/corpus_wall.png)")
    summ = sub.add_parser("summary", help="print the summary of a CSV written by run")
    summ.add_argument("csv")
    summ.add_argument("--seeds", type=_seed_range, default=None, help="only these seeds, A:B")
    summ.add_argument("--until", type=float, default=20.0, help="simulated seconds of that run (20)")
    show = sub.add_parser("show", help="describe one scene")
    show.add_argument("seed", type=int)
    args = parser.parse_args(argv)

    if args.command == "summary":
        with open(args.csv, newline="") as handle:
            rows = [r for r in csv.DictReader(handle) if args.seeds is None or int(r["seed"]) in args.seeds]
        print(summary(rows, args.until))
        return 0

    if args.command == "show":
        spec = scene_spec(args.seed)
        print(f"scene {args.seed} (draw {spec['attempt']}): gravity {spec['gravity']}, walls {spec['wall']:.3f} thick, "
              f"e {spec['wall_elasticity']:.2f}, friction {spec['wall_friction']:.2f}")
        for body in spec["fixed"] + spec["moving"]:
            where = body.get("position") or tuple(round(v, 3) for v in _centre(body["vertices"]))
            extra = "" if "mass" not in body else (
                f" m={body['mass']:.2f} e={body['elasticity']:.2f} mu={body['friction']:.2f} "
                f"v=({body['velocity'][0]:.2f}, {body['velocity'][1]:.2f}) w={body['angular_velocity']:.2f}")
            print(f"  {body['name']:12s} at ({where[0]:.3f}, {where[1]:.3f}){extra}")
        return 0

    processes = max(1, min(2, args.processes))
    begin = time.perf_counter()
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    rows = run_corpus(args.seeds, args.until, args.timeout, processes, on_row=lambda rows: _write(rows, args.out))
    elapsed = time.perf_counter() - begin
    _write(rows, args.out)
    print()
    print(f"{len(rows)} scenes in {elapsed:.0f} s of wall time with {processes} worker(s); CSV: {args.out}")
    print()
    print(summary(rows, args.until))
    print()
    _plot(rows, args.plot or os.path.join(os.path.dirname(os.path.abspath(args.out)), "corpus_wall.png"))
    return 0


def _write(rows, path) -> None:
    """Write the CSV (rewritten after every scene, so a stopped run keeps what it measured)."""
    with open(path, "w", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=FIELDS, extrasaction="ignore")
        writer.writeheader()
        for row in rows:
            writer.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in row.items()})


def _centre(vertices):
    n = len(vertices)
    return (sum(v[0] for v in vertices) / n, sum(v[1] for v in vertices) / n)


if __name__ == "__main__":
    sys.exit(main())
