"""Profile one hard-disc gas run under cProfile and print the top functions.

    .venv/bin/python benchmarks/profile_gas.py                    # engine, N = 5000, 10 s
    .venv/bin/python benchmarks/profile_gas.py --n 20000 --sort tottime --top 40
    .venv/bin/python benchmarks/profile_gas.py --target reference --n 1000
    .venv/bin/python benchmarks/profile_gas.py --out /tmp/gas.prof   # for snakeviz / pstats

The scene and the engine world are exactly those of ``benchmarks/gas.py``.
For the engine the Numba kernels are warmed up first (not profiled); the
profile covers building the world (with ``--with-setup``) and ``run_until``.
cProfile sees a compiled kernel as one opaque call, so inside the engine it
shows the Python-side cost (world building, priming, the event-loop driver,
callbacks, ``overlaps``) and how much time is spent in each compiled entry
point; for a line-level view of a kernel use ``NUMBA_DISABLE_JIT=1`` (very
slow: use a small ``--n``).
"""

from __future__ import annotations

import argparse
import cProfile
import pstats
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from edmd_reference import run_reference  # noqa: E402
from gas import build_world, warm_up  # noqa: E402

from pge import World  # noqa: E402
from pge.scenes import disc_gas  # noqa: E402


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description="cProfile one hard-disc gas run")
    parser.add_argument("--n", type=int, default=5000, help="number of discs (default 5000)")
    parser.add_argument("--duration", type=float, default=10.0, help="simulated seconds (default 10)")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--target", choices=("engine", "reference"), default="engine")
    parser.add_argument("--with-setup", action="store_true", help="engine: also profile building the world")
    parser.add_argument("--sort", default="cumulative", help="pstats sort key: cumulative, tottime, calls, ...")
    parser.add_argument("--top", type=int, default=25, help="how many functions to print")
    parser.add_argument("--out", type=Path, default=None, help="also dump the raw profile here")
    args = parser.parse_args(argv)

    gas = disc_gas(args.n, seed=args.seed)
    profiler = cProfile.Profile()
    if args.target == "engine":
        print(f"warm-up (Numba load/compile): {warm_up(World, disc_gas):.2f} s", flush=True)
        if args.with_setup:
            profiler.enable()
            world = build_world(World, gas)
        else:
            world = build_world(World, gas)
            profiler.enable()
        start = time.perf_counter()
        world.run_until(args.duration)
        elapsed = time.perf_counter() - start
        profiler.disable()
        events = world.stats["events"]
        print("engine stats:", world.stats)
    else:
        profiler.enable()
        start = time.perf_counter()
        result = run_reference(gas, args.duration)
        elapsed = time.perf_counter() - start
        profiler.disable()
        events = result["events"]
    print(
        f"{args.target}, N = {args.n}, {args.duration:g} s simulated: {events} events, "
        f"{elapsed:.3f} s wall under the profiler (profiling overhead included)"
    )
    if args.out:
        profiler.dump_stats(str(args.out))
        print(f"profile written to {args.out}")
    pstats.Stats(profiler).strip_dirs().sort_stats(args.sort).print_stats(args.top)
    return 0


if __name__ == "__main__":
    sys.exit(main())
