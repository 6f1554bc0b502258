"""Run many random scenes of tests/test_rotation.py and list the failing ones.

    .venv/bin/python tools/repro/survey.py overlap --seeds 0 40 [--events 1500] [--only-gravity] [--only-inelastic]
    .venv/bin/python tools/repro/survey.py energy --seeds 0 40 [--gravity]
    .venv/bin/python tools/repro/survey.py full --seeds 0 4 --timeout 300

``full`` runs every scene to t = 10 s, checking overlaps every 0.01 s (not at every event, which
costs more than the engine), and reports how far each scene got, its event count, island steps
and joins, and its wall time.

Each scene runs in a worker process with a time limit; the output lists the seed, the settings
and what went wrong (overlap, energy gain, error or hang), then a count per kind of setting.
"""
from __future__ import annotations

import argparse
import multiprocessing as mp
import os
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "tests"))

import test_rotation as scenes  # noqa: E402


def _job(args):
    kind, seed, count, elastic, gravity, friction, events = args
    scenes.SCENE_EVENTS = events
    start = time.perf_counter()
    try:
        if kind == "full":
            result = _run_full(seed, count, elastic, gravity, friction)
            bad = result["first_bad"]
            stats = result["stats"]
            done = (
                f"t={result['end']:.3g}, {stats['events']} events, {stats['island_steps']} island steps, "
                f"{stats['joins']} joins, worst {result['worst']:.2g}"
            )
        elif kind == "overlap":
            result = scenes.run_overlap_scene(seed, count, elastic, gravity, friction)
            bad = result["first_bad"]
            done = f"{result['events']} events to t={result['end']:.3g}"
        else:
            result = scenes.run_energy_scene(seed, count, gravity)
            bad = result["first_bad"]
            done = f"{result['collisions']} collisions"
    except Exception as error:  # a survey reports every failure, whatever it is
        bad = f"{type(error).__name__}: {error}"
        done = ""
    return args, bad, done, time.perf_counter() - start


def _run_full(seed, count, elastic, gravity, friction, end=10.0, sample=0.01):
    """Run one scene to ``end``, checking the worst overlap every ``sample`` seconds, against the
    tests' bounds: ``OVERLAP`` for pairs no island holds, ``ISLAND_OVERLAP`` (an island step's
    integration error) for pairs one does."""
    world, _, bodies = scenes.build_spinning_scene(seed, count, elastic, gravity, friction)
    worst, first_bad, steps = -float("inf"), None, round(end / sample)
    for k in range(1, steps + 1):
        world.run_until(k * sample)
        for within, bound in ((False, scenes.OVERLAP), (True, scenes.ISLAND_OVERLAP)):
            depth, what = scenes.worst_overlap(world, bodies, within_islands=within)
            worst = max(worst, depth)
            if depth > bound and first_bad is None:
                where = " within an island" if within else ""
                first_bad = f"{depth:.3g}{where} ({what}) by t = {k * sample:.2f}"
    return {"worst": worst, "first_bad": first_bad, "end": world.time, "stats": world.stats}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("kind", choices=("overlap", "energy", "full"))
    parser.add_argument("--seeds", nargs=2, type=int, default=(0, 20))
    parser.add_argument("--events", type=int, default=1500)
    parser.add_argument("--count", type=int, default=10)
    parser.add_argument("--gravity", action="store_true", help="energy: under gravity")
    parser.add_argument("--only-gravity", action="store_true")
    parser.add_argument("--only-inelastic", action="store_true")
    parser.add_argument("--timeout", type=float, default=60.0)
    args = parser.parse_args(argv)
    jobs = []
    for seed in range(*args.seeds):
        if args.kind == "energy":
            jobs.append(("energy", seed, args.count, False, args.gravity, True, args.events))
            continue
        for elastic in (False,) if args.only_inelastic else (False, True):
            for gravity in (True,) if args.only_gravity else (False, True):
                for friction in (False, True):
                    jobs.append((args.kind, seed, args.count, elastic, gravity, friction, args.events))
    failures = {}
    times = []
    with mp.get_context("fork").Pool(2) as pool:
        pending = [(job, pool.apply_async(_job, (job,))) for job in jobs]
        for job, handle in pending:
            try:
                job, bad, done, seconds = handle.get(timeout=args.timeout)
            except mp.TimeoutError:
                bad, done, seconds = f"no result within {args.timeout:.0f} s", "", args.timeout
            tag = f"elastic={job[3]} gravity={job[4]} friction={job[5]}"
            times.append((seconds, job[1], tag, done))
            if bad:
                failures.setdefault(tag, []).append(job[1])
                print(f"FAIL seed {job[1]} {tag} ({seconds:.1f} s, {done}): {bad}", flush=True)
            elif args.kind == "full":
                print(f"ok   seed {job[1]} {tag} ({seconds:.1f} s, {done})", flush=True)
    print(f"\n{sum(map(len, failures.values()))} of {len(jobs)} scenes failed")
    print("slowest:", "; ".join(f"seed {seed} {tag} {seconds:.1f} s ({done})" for seconds, seed, tag, done in sorted(times)[-3:]))
    for tag, seeds in sorted(failures.items()):
        print(f"  {tag}: seeds {seeds}")


if __name__ == "__main__":
    main()
