"""Where an event's time goes: the engine's counters on the issue-20 gas, and hooks for perf and gdb.

The scene is ``vs_pymunk.py``'s gas (radius 5, area fraction 0.1, speed 100, e = 1, closed box).
The script warms the kernels up, builds the gas, optionally runs it untimed to ``--start`` (to
measure a steady state), then times ``run_until(--start + --duration)`` and prints:

* the engine's counters for the timed span (``world.stats`` differences) and what they give per
  event: horizon events (swept boxes renewed without a collision), stale queue entries popped,
  pushes, predict calls, candidates, box and bound rejects, exact solves;
* the heap size (queue entries) at the end;
* with ``NUMBA_NRT_STATS=1`` in the environment, Numba's runtime counters (allocations and frees
  of Numba-owned memory: arrays, not reference counts) over the timed span.

Options for external profilers:

* ``--perf-map``: write ``/tmp/perf-<pid>.map`` naming every compiled function of the engine
  (from the object code Numba loads from its cache), so that ``perf report`` attributes samples
  in JIT code to functions such as ``predict``, ``gather``, ``NRT_incref``:

      perf record -F 1999 -g -k CLOCK_MONOTONIC -o /tmp/gas.perf -- \
          .venv/bin/python benchmarks/profile_events.py --start 1 --duration 4 --perf-map
      perf report -i /tmp/gas.perf --no-children --sort sym --time A,B   # A,B: the printed window

* ``--pause``: after the untimed part, print ``READY <pid>`` and wait for a line on stdin before the
  timed part, so that a debugger can attach (``refcount_callers.sh`` uses it).
* ``--non-atomic``: Numba's reference counts done with plain increments instead of atomic ones
  (measures what the atomicity costs; safe here, the engine runs on one thread).

Micro-benchmarks (after the run):

* ``--calls``: a compiled call that takes the state tuple ``S`` (19 arrays) against the same call
  taking the three arrays it uses, and against the work inlined, in a compiled loop;
* ``--heap``: the engine's own ``push`` / ``pop_earliest`` on a copy of the run's queue.
"""

from __future__ import annotations

import argparse
import math
import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

#: object code of every Numba library loaded in this process, by library name
OBJECTS: dict[str, bytes] = {}


def keep_object_code() -> None:
    """Have Numba hand us a copy of each library's object code as it loads or compiles it.

    Must run before the first compiled function is used: the hooks are registered when Numba's
    code generator is made.
    """
    from numba.core import codegen

    library_class = codegen.JITCodeLibrary
    loaded = library_class._object_getbuffer_hook.__func__
    compiled = library_class._object_compiled_hook.__func__

    def on_load(cls, ll_module):
        library = getattr(ll_module, "_CPUCodeLibrary__library", None)
        if library is not None and library._object_caching_enabled and library._compiled_object:
            OBJECTS[library.name] = bytes(library._compiled_object)
        return loaded(cls, ll_module)

    def on_compile(cls, ll_module, buffer):
        library = getattr(ll_module, "_CPUCodeLibrary__library", None)
        if library is not None:
            OBJECTS[library.name] = bytes(buffer)
        return compiled(cls, ll_module, buffer)

    library_class._object_getbuffer_hook = classmethod(on_load)
    library_class._object_compiled_hook = classmethod(on_compile)


def short_name(symbol: str) -> str:
    """``_ZN3pge4core7predict7predictB3v63...`` -> ``pge.core.predict.predict``."""
    if not symbol.startswith("_ZN"):
        return symbol
    i, parts = 3, []
    while i < len(symbol) and symbol[i].isdigit():
        digits = re.match(r"\d+", symbol[i:]).group()
        i += len(digits)
        parts.append(symbol[i : i + int(digits)])
        i += int(digits)
    return ".".join(parts) or symbol


def write_perf_map(dump: Path | None = None) -> Path:
    """Write /tmp/perf-<pid>.map: start, size and name of every function in the loaded objects.

    With ``dump``, also write each object there (``<library>.o``) and ``bases.txt`` (library name
    and the address its code section was loaded at), to read the machine code of a sampled address
    (``objdump -d <library>.o``, at ``address - base``).
    """
    from numba.core.registry import cpu_target

    engine = cpu_target.target_context.codegen()._engine
    lines = []
    bases = []
    with tempfile.TemporaryDirectory() as scratch:
        for name, code in OBJECTS.items():
            path = Path(scratch) / f"{len(bases)}.o"
            path.write_bytes(code)
            listing = subprocess.run(["nm", "-S", str(path)], capture_output=True, text=True, check=True).stdout
            functions = []
            for row in listing.splitlines():
                fields = row.split()
                if len(fields) == 4 and fields[2] in "TtWw":
                    functions.append((int(fields[0], 16), int(fields[1], 16), fields[2], fields[3]))
            # Every function sits in one code section: its load address follows from any
            # strong global symbol the execution engine knows.
            base = None
            for offset, _, kind, symbol in functions:
                if kind == "T":
                    address = engine.get_function_address(symbol)
                    if address:
                        base = address - offset
                        break
            if base is None:
                continue
            bases.append(f"{name} {base:x}")
            if dump is not None:
                dump.mkdir(parents=True, exist_ok=True)
                (dump / f"{name}.o").write_bytes(code)
            for offset, size, _, symbol in functions:
                lines.append(f"{base + offset:x} {size:x} {short_name(symbol)} [{name}]")
    out = Path(f"/tmp/perf-{os.getpid()}.map")
    out.write_text("\n".join(lines) + "\n")
    if dump is not None:
        (dump / "bases.txt").write_text("\n".join(bases) + "\n")
    return out


# ----------------------------------------------------------------- the call cost


def time_calls(repeats: int = 5, n: int = 2_000_000) -> None:
    """ns per compiled call of a small function taking S, and the same function taking three arrays.

    LLVM inlines a small callee whatever Numba is told, so the callees are compiled with
    ``debug=True`` (which marks them ``noinline``) but without the bounds checks and extended
    variable lifetimes that debug mode would otherwise add: the code is the optimised code.
    """
    import numpy as np
    from numba import njit

    from pge.core.state import EngineState

    apart = {"debug": True, "boundscheck": False, "_dbg_extend_lifetimes": False}

    @njit(**apart)
    def work_tuple(S, i):
        F = S.F
        I = S.I
        Q = S.Q
        j = i & 63
        Q[1] += I[j, 0] + np.int64(F[j, 0])
        return Q[1]

    @njit(**apart)
    def work_arrays(F, I, Q, i):
        j = i & 63
        Q[1] += I[j, 0] + np.int64(F[j, 0])
        return Q[1]

    @njit
    def loop_tuple(S, n):
        for i in range(n):
            work_tuple(S, i)
        return S.Q[1]

    @njit
    def loop_arrays(S, n):
        F = S.F
        I = S.I
        Q = S.Q
        for i in range(n):
            work_arrays(F, I, Q, i)
        return Q[1]

    @njit
    def loop_inline(S, n):
        F = S.F
        I = S.I
        Q = S.Q
        for i in range(n):
            j = i & 63
            Q[1] += I[j, 0] + np.int64(F[j, 0])
        return Q[1]

    S = EngineState().S
    print(f"compiled call cost, {n:,} calls in a compiled loop, best of {repeats}:")
    for label, loop, callee in (
        (f"callee takes S ({len(S)} arrays)", loop_tuple, work_tuple),
        ("callee takes F, I, Q", loop_arrays, work_arrays),
        ("no call (work inlined)", loop_inline, None),
    ):
        loop(S, 10)
        best = min(_timed(loop, S, n) for _ in range(repeats))
        detail = ""
        if callee is not None:
            caller = next(iter(loop.inspect_asm().values())).split(".Lfunc_end0")[0]
            body = next(iter(callee.inspect_asm().values())).split(".Lfunc_end0")[0]
            detail = (f"   (per call: {caller.count('pushq') * 8} bytes of arguments pushed, "
                      f"{len(re.findall(r'callq', body))} calls to NRT_incref/NRT_decref in the callee)")
        print(f"  {label:28s} {1e9 * best / n:6.2f} ns per iteration{detail}")


def time_heap(world, pushes_per_pop: float, rounds: int = 400_000, repeats: int = 5) -> None:
    """ns per pop and per push of the engine's own queue code on a copy of the world's queue.

    The copy keeps the queue's size and the spread of its event times; each round pops the
    earliest entry and pushes one or two new ones (``pushes_per_pop`` on average, as in the run),
    each at the popped time plus a lead time drawn from the copy's own entries.
    """
    import numpy as np
    from numba import njit

    from pge.core import layout as L
    from pge.core.queue import pop_earliest, push

    state = world._state
    n = int(state.Q[L.HEAP_N])
    now = float(state.P[L.TIME])
    leads = np.sort(state.heap_time[:n] - now)
    leads = leads[np.isfinite(leads) & (leads >= 0.0)]
    rng = np.random.default_rng(1)
    draws = rng.choice(leads, size=1 << 16)
    twice = rng.random(1 << 16) < (pushes_per_pop - 1.0)

    @njit
    def churn(S, rounds, draws, twice):
        for k in range(rounds):
            slot, t, key = pop_earliest(S)
            m = k & 65535
            push(S, t + draws[m], key, 0, 0, 0, 0, 0)
            if twice[m]:
                push(S, t + draws[(m * 7919) & 65535], key, 0, 0, 0, 0, 0)
                pop_earliest(S)  # keep the size steady
        return S.Q[L.HEAP_N]

    @njit
    def pops_only(S, rounds):
        for k in range(rounds):
            pop_earliest(S)
        return S.Q[L.HEAP_N]

    def copy_of_state():
        return type(state.S)(*(a.copy() for a in state.S))

    churn(copy_of_state(), 10, draws, twice)
    pops_only(copy_of_state(), 10)
    best = math.inf
    for _ in range(repeats):
        S = copy_of_state()
        start = time.perf_counter()
        churn(S, rounds, draws, twice)
        best = min(best, time.perf_counter() - start)
    operations = rounds * (1 + 1) + 2 * int(twice.mean() * rounds)  # pops + pushes
    pop_best = math.inf
    for _ in range(repeats):
        S = copy_of_state()
        count = min(rounds, n - 1)
        start = time.perf_counter()
        pops_only(S, count)
        pop_best = min(pop_best, (time.perf_counter() - start) / count)
    print(f"queue ({n:,} entries, the engine's push and pop_earliest on a copy): "
          f"{1e9 * best / operations:.1f} ns per push or pop on average; {1e9 * pop_best:.1f} ns per pop "
          f"(draining it)")


def _timed(loop, S, n) -> float:
    start = time.perf_counter()
    loop(S, n)
    return time.perf_counter() - start


# -------------------------------------------------------------------------- main


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--n", type=int, default=10000, help="number of discs (default 10000)")
    parser.add_argument("--start", type=float, default=0.0, help="simulated seconds run untimed first (default 0)")
    parser.add_argument("--duration", type=float, default=10.0, help="simulated seconds timed (default 10)")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--perf-map", action="store_true", help="write /tmp/perf-<pid>.map for perf report")
    parser.add_argument("--dump-objects", type=Path, default=None,
                        help="with --perf-map: also write the objects and their load addresses here")
    parser.add_argument("--pause", action="store_true", help="wait for a line on stdin before the timed part")
    parser.add_argument(
        "--non-atomic", action="store_true",
        help="make Numba's NRT_incref/NRT_decref plain (non-atomic) increments: the kernels call the "
        "runtime's copy, built when the process starts, so no recompilation is needed (one thread only)",
    )
    parser.add_argument("--calls", action="store_true", help="also time a compiled call taking S")
    parser.add_argument("--heap", action="store_true", help="also time the queue's push and pop on a copy")
    args = parser.parse_args(argv)

    if args.perf_map or args.non_atomic:
        keep_object_code()
    if args.non_atomic:
        from numba.core.runtime import nrtdynmod

        nrtdynmod._disable_atomicity = 1  # read when the runtime's NRT functions are built
    from vs_pymunk import make_gas, pge_warm_up, pge_world

    from pge.core import layout as L

    print(f"warm-up: {pge_warm_up(args.seed):.2f} s", flush=True)
    world = pge_world(make_gas(args.n, args.seed))
    world.run_until(args.start)  # primes the world (initial predictions) even at 0
    if args.perf_map:
        print(f"perf map: {write_perf_map(args.dump_objects)}", flush=True)
    if "nrt" in OBJECTS:
        with tempfile.TemporaryDirectory() as scratch:
            path = Path(scratch) / "nrt.o"
            path.write_bytes(OBJECTS["nrt"])
            listing = subprocess.run(["objdump", "-d", str(path)], capture_output=True, text=True).stdout
        locks = {}
        for block in listing.split("\n\n"):
            name = re.search(r"<(NRT_incref|NRT_decref)>:", block)
            if name:
                locks[name.group(1)] = block.count("lock ")
        print("Numba runtime: lock-prefixed instructions in "
              + ", ".join(f"{name} {count}" for name, count in sorted(locks.items()))
              + (" (atomic reference counts)" if any(locks.values()) else " (plain increments: --non-atomic)"),
              flush=True)
    nrt = None
    if os.environ.get("NUMBA_NRT_STATS") == "1":
        from numba.core.runtime import rtsys

        nrt = rtsys.get_allocation_stats()
    before = world.stats
    state = world._state
    heap_before = int(state.Q[L.HEAP_N])
    if args.pause:
        print(f"READY {os.getpid()}", flush=True)
        sys.stdin.readline()
    cpu = time.process_time()
    window = time.clock_gettime(time.CLOCK_MONOTONIC)
    start = time.perf_counter()
    world.run_until(args.start + args.duration)
    wall = time.perf_counter() - start
    window = (window, time.clock_gettime(time.CLOCK_MONOTONIC))
    cpu = time.process_time() - cpu
    after = world.stats
    d = {key: after[key] - before[key] for key in after}
    heap_after = int(state.Q[L.HEAP_N])
    events = d["events"]
    pops = events + d["stale"]
    pushes = pops + heap_after - heap_before
    walls = d["collisions"] - d["pair_collisions"]
    # Bodies predicted again: both discs of a pair collision, the disc of a wall collision
    # (a fixed wall is not re-predicted) and the disc of a horizon.
    predicts = 2 * d["pair_collisions"] + walls + d["horizons"]
    print(f"N = {args.n}, simulated {args.start:g} -> {args.start + args.duration:g} s: wall {wall:.3f} s, "
          f"cpu {cpu:.3f} s, load average {os.getloadavg()[0]:.2f}")
    print(f"  timed window, CLOCK_MONOTONIC (for perf record -k CLOCK_MONOTONIC; perf report --time): "
          f"{window[0]:.6f},{window[1]:.6f}")
    print(f"  events {events:,} ({1e6 * wall / events:.3f} us/event wall, {1e6 * cpu / events:.3f} cpu)")
    rows = [
        ("pair collisions", d["pair_collisions"], events),
        ("wall collisions", walls, events),
        ("horizons (swept box renewed, no collision)", d["horizons"], events),
        ("grazes", d["grazes"], events),
        ("stale pops (per valid event)", d["stale"], events),
        ("queue pops (valid + stale)", pops, events),
        ("queue pushes", pushes, events),
        ("bodies predicted (predict calls)", predicts, events),
        ("candidates from the grid", d["candidates"], events),
        ("  rejected by the swept boxes", d["box_rejects"], events),
        ("  rejected by the short-circuit bound", d["bound_rejects"], events),
        ("  exact time-of-impact solves", d["predictions"], events),
        ("  hits (a contact found)", d["hits"], events),
    ]
    for label, count, per in rows:
        print(f"  {label:44s} {count:>11,}  {count / per:7.3f} per event")
    print(f"  stale share of pops: {d['stale'] / pops:.1%}; horizon share of events: {d['horizons'] / events:.1%}")
    print(f"  queue entries: {heap_before:,} before, {heap_after:,} after ({heap_after / args.n:.2f} per body)")
    if nrt is not None:
        from numba.core.runtime import rtsys

        now = rtsys.get_allocation_stats()
        print("  Numba runtime (NUMBA_NRT_STATS=1) during the timed part: "
              + ", ".join(f"{field} {getattr(now, field) - getattr(nrt, field)}" for field in now._fields))
    if args.calls:
        time_calls()
    if args.heap:
        time_heap(world, pushes / pops)
    return 0


if __name__ == "__main__":
    sys.exit(main())
