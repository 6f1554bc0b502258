"""Where a cold start's compile time goes: Numba compile time per kernel and signature.

Runs a command (a module with ``-m``, or a script) in this process with an empty
temporary Numba cache, listening to Numba's ``numba:compile`` and
``numba:llvm_lock`` events, and prints, per compiled kernel, its *self* time (its
own compile, without the kernels it called that were compiled on the way) and
the part of it spent in LLVM (optimising and emitting machine code); then per
signature. A kernel listed with several signatures was compiled several times.

Usage (from the repository root):

    .venv/bin/python benchmarks/jit_profile.py -m pge.cli showcase --out /tmp/out
    .venv/bin/python benchmarks/jit_profile.py benchmarks/gas.py --sizes 200 --duration 1 --no-reference

The report goes to stderr after the command ends (``--top K`` before the command:
how many rows, default 40). Timing is only reported, never asserted.
"""

from __future__ import annotations

import atexit
import collections
import os
import runpy
import sys
import tempfile
import time


def main(argv: list[str]) -> None:
    """Profile the command in ``argv`` (see the module docstring)."""
    top = 40
    if argv[:1] == ["--top"]:
        top = int(argv[1])
        argv = argv[2:]
    if not argv:
        sys.exit(__doc__)
    # Before Numba is imported: it reads the cache directory once.
    os.environ["NUMBA_CACHE_DIR"] = tempfile.mkdtemp(prefix="pge-jit-profile-")
    from numba.core import event

    stack = []  # [kernel, signature, start, time of nested compiles, LLVM time]
    own = collections.defaultdict(float)
    llvm = collections.defaultdict(float)
    started = time.perf_counter()

    class Compiles(event.Listener):
        def on_start(self, ev):
            function = getattr(ev.data.get("dispatcher"), "py_func", None)
            name = f"{function.__module__}.{function.__qualname__}" if function else "?"
            stack.append([name, str(ev.data.get("args")), time.perf_counter(), 0.0, 0.0])

        def on_end(self, ev):
            name, signature, start, nested, in_llvm = stack.pop()
            elapsed = time.perf_counter() - start
            own[name, signature] += elapsed - nested
            llvm[name, signature] += in_llvm
            if stack:
                stack[-1][3] += elapsed

    class Llvm(event.Listener):
        # LLVM work is charged to the innermost kernel being compiled.
        def on_start(self, ev):
            self.start = time.perf_counter()

        def on_end(self, ev):
            if stack:
                stack[-1][4] += time.perf_counter() - self.start

    event.register("numba:compile", Compiles())
    event.register("numba:llvm_lock", Llvm())

    def report():
        out = sys.stderr
        total = sum(own.values())
        print(
            f"\njit_profile: {time.perf_counter() - started:.1f} s in all, {total:.1f} s compiling "
            f"({sum(llvm.values()):.1f} s in LLVM), {len(own)} signatures",
            file=out,
        )
        kernels = collections.defaultdict(lambda: [0.0, 0.0, 0])
        for key, seconds in own.items():
            row = kernels[key[0]]
            row[0] += seconds
            row[1] += llvm[key]
            row[2] += 1
        print("\n  self s  LLVM s  signatures  kernel", file=out)
        for name, (seconds, in_llvm, count) in sorted(kernels.items(), key=lambda kv: -kv[1][0])[:top]:
            print(f"{seconds:8.2f} {in_llvm:7.2f} {count:11d}  {name}", file=out)
        print("\n  self s  LLVM s  kernel (signature)", file=out)
        for key, seconds in sorted(own.items(), key=lambda kv: -kv[1])[:top]:
            print(f"{seconds:8.2f} {llvm[key]:7.2f}  {key[0]} {key[1][:160]}", file=out)

    atexit.register(report)
    if argv[0] == "-m":
        sys.argv = argv[1:]
        runpy.run_module(argv[1], run_name="__main__", alter_sys=True)
    else:
        sys.argv = argv
        runpy.run_path(argv[0], run_name="__main__")


if __name__ == "__main__":
    main(sys.argv[1:])
