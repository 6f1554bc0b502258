"""Where the time of a scene with islands goes: the event loop, the islands' Python side, and
each stage of the compiled island step.

    .venv/bin/python benchmarks/island_stages.py --seeds 82 186 165 --until 20
    .venv/bin/python benchmarks/island_stages.py --box 100 --until 1

For each corpus scene (``tools/corpus.py``), or games.py's box of ``N`` spinning polygons and
circles under gravity (``--box N``), it runs the scene twice: once as it is, and once
with the island step replaced by a Python replica of ``pge.contact.island.step_island`` that
calls the same compiled stages and times each one. The replica must give the same run to the
bit (final positions, velocities, statistics compared; the script stops if not), so its table
describes the real step. A stage's time includes one Python-to-compiled call (a few µs, the
"calls" column shows how many), which the compiled step does not pay; the "step total"
line of the plain run is the real cost.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
import time
from collections import defaultdict

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tools"))
sys.path.insert(0, HERE)

import corpus  # noqa: E402
import games  # noqa: E402

from pge.contact import island as K, rows as KR, solve as KS, arcs as KA, pushout as KP, energy as KE  # noqa: E402
from pge.contact import islands as islands_module  # noqa: E402
from pge.core import layout as L  # noqa: E402


def timed_step_island(clock):
    """A replica of ``step_island`` that adds each stage's wall time to ``clock[stage]``."""

    def timed(name, fn, *args):
        begin = time.perf_counter()
        value = fn(*args)
        clock[name][0] += time.perf_counter() - begin
        clock[name][1] += 1
        return value

    def step_island(S, members, local, h, t, warm_keys, warm_impulses):
        F = S.F
        now, margin = timed("start", K._start, S, members, local, h, t)
        rows, pairs, count = timed("collect (manifold)", K._collect, S, members, local, margin, t)
        pull = 0.0
        for k in range(members.shape[0]):
            pull = max(pull, math.hypot(F[members[k], L.FREE_AX], F[members[k], L.FREE_AY]))
        down_x = F[members[0], L.FREE_AX]
        down_y = F[members[0], L.FREE_AY]
        shortest = min(K.SHORTEST_STEP, (count + 1) / K.ROW_BUDGET) * h
        natural = timed("step length", K._turn_limit, S, members, now, h, shortest)
        h = min(timed("step length", K._until_contact, S, now, rows, pairs, count, h,
                      np.full(count, K.BOUNCE_WINDOW), shortest),
                natural)
        keys = timed("prepare", K._prepare, S, rows, pairs, count, h, warm_keys, warm_impulses)
        speed = K._speed_scale(F, members, now, h, pull)
        shorter = timed("after bounces", K._after_bounces, S, members, now, rows, pairs, count, h, speed, down_x,
                        down_y, min(shortest, h))
        if shorter < h:
            h = shorter
            keys = timed("prepare", K._prepare, S, rows, pairs, count, h, warm_keys, warm_impulses)
            speed = K._speed_scale(F, members, now, h, pull)
        sweeps, struck = timed("impacts", K._impacts, F, members, now, rows, pairs, count, speed, down_x, down_y)
        turned = timed("step length", K._turn_limit, S, members, now, h, min(shortest, h))
        if turned < h:
            natural = min(natural, turned)
        shorter = timed("step length", K._within_margins, F, members, now, margin, min(h, turned))
        if shorter < h:
            h = shorter
            speed = K._speed_scale(F, members, now, h, pull)
        timed("mid-step rows", KA._midstep_rows, S, now, rows, pairs, count, h)
        K._force_targets(rows, count, h)
        end = np.empty_like(now)
        for k in range(members.shape[0]):
            i = members[k]
            end[k, 0] = now[k, 0] + h * F[i, L.FREE_AX]
            end[k, 1] = now[k, 1] + h * F[i, L.FREE_AY]
            end[k, 2] = now[k, 2]
        K._end_targets(rows, now, pairs, count)
        sweeps += timed("forces (solve)", KS._solve, F, end, rows, pairs, count, speed, down_x, down_y,
                        K.ISLAND_ITERATIONS, K.LCP_LIMIT)
        timed("energy", KE._no_gain, F, members, now, end, rows, pairs, count, h)
        ends = np.empty((count, 5))
        timed("arcs (end and inside)", KA._solved_arcs, S, now, end, rows, pairs, count, h, ends)
        lift, pushes = timed("push-out", KP._push_out, F, now, end, rows, pairs, count, h, natural, down_x, down_y,
                             ends)
        sweeps += pushes
        if timed("lift paid", KE._lift_paid, F, members, now, end, lift, rows, pairs, count, h):
            timed("arcs (end and inside)", KA._solved_arcs, S, now, end, rows, pairs, count, h, ends)
            lift, pushes = timed("push-out", KP._push_out, F, now, end, rows, pairs, count, h, natural, down_x,
                                 down_y, ends)
            sweeps += pushes
        labels, fastest, deepest = timed("finish (touch)", K._finish, S, members, local, now, end, lift, rows,
                                         pairs, count, h, speed)
        S.stats[L.S_ISLAND_STEPS] += 1
        order = np.argsort(keys)
        impulses = np.empty((count, 3))
        for c in range(count):
            impulses[c, 0] = rows[order[c], KR.LAMBDA_N]
            impulses[c, 1] = rows[order[c], KR.LAMBDA_T]
            impulses[c, 2] = struck[order[c]]
        clock["rows"][0] += count
        clock["rows"][1] += 1
        return keys[order], impulses, labels, fastest, deepest, sweeps, h, lift

    return step_island


def build(scene: str):
    """A fresh World of ``scene``: ``corpus:SEED`` or ``box:N``."""
    kind, number = scene.split(":")
    if kind == "box":
        return games.spinning_box(int(number), 10.0, 0)[0]
    return corpus.build(corpus.scene_spec(int(number)))


def run(scene: str, until: float, replica: bool):
    """Run ``scene`` to ``until``; returns (final state, stats, clock, wall)."""
    clock = defaultdict(lambda: [0.0, 0])
    compiled = islands_module.step_island
    real_step = islands_module.Islands._step

    def python_side(self, k, t):
        begin = time.perf_counter()
        real_step(self, k, t)
        clock["island step, Python side included"][0] += time.perf_counter() - begin
        clock["island step, Python side included"][1] += 1

    def plain(*args):
        begin = time.perf_counter()
        value = compiled(*args)
        clock["step_island (compiled)"][0] += time.perf_counter() - begin
        clock["step_island (compiled)"][1] += 1
        return value

    islands_module.step_island = timed_step_island(clock) if replica else plain
    islands_module.Islands._step = python_side
    try:
        world = build(scene)
        begin = time.perf_counter()
        world.run_until(until)
        wall = time.perf_counter() - begin
    finally:
        islands_module.step_island = compiled
        islands_module.Islands._step = real_step
    n = world._state.n
    final = (world._state.F[:n].copy(), dict(world.stats))
    return final, clock, wall


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, nargs="*", default=[82, 186, 165])
    parser.add_argument("--box", type=int, nargs="*", default=[], help="games.py's spinning box of N bodies")
    parser.add_argument("--until", type=float, default=20.0)
    args = parser.parse_args(argv)
    run("corpus:0", 0.5, False)  # compile or load the kernels, for the step and for the replica's calls
    run("corpus:0", 0.5, True)
    scenes = [f"corpus:{seed}" for seed in args.seeds] + [f"box:{n}" for n in args.box]
    for seed in scenes:
        (plain_state, stats), plain_clock, wall = run(seed, args.until, False)
        (replica_state, replica_stats), clock, replica_wall = run(seed, args.until, True)
        if not (np.array_equal(plain_state, replica_state, equal_nan=True) and stats == replica_stats):
            print(f"scene {seed}: the replica's run differs from the compiled step's; update the replica")
            return 1
        steps = stats["island_steps"]
        step_total = plain_clock["step_island (compiled)"][0]
        python_total = plain_clock["island step, Python side included"][0]
        print(f"\nscene {seed}: {args.until:g} s simulated in {wall:.2f} s wall; {stats['events']} events, "
              f"{steps} island steps, {clock['rows'][0] / max(clock['rows'][1], 1):.1f} contact rows a step")
        print(f"  {'part':36s} {'s':>7s} {'share':>6s} {'us/step':>8s}")
        for name, seconds in (("step_island (compiled)", step_total),
                              ("islands' Python side", python_total - step_total),
                              ("event loop and the rest", wall - python_total)):
            print(f"  {name:36s} {seconds:7.3f} {seconds / wall:6.1%} {1e6 * seconds / max(steps, 1):8.1f}")
        staged = sum(v[0] for k, v in clock.items() if k not in ("rows", "island step, Python side included"))
        print(f"  stages of the replica ({staged:.3f} s in all, with one Python call each):")
        for name, (seconds, calls) in sorted(clock.items(), key=lambda item: -item[1][0]):
            if name in ("rows", "island step, Python side included"):
                continue
            print(f"    {name:34s} {seconds:7.3f} {seconds / staged:6.1%} {1e6 * seconds / max(steps, 1):8.1f}"
                  f"  ({calls} calls)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
