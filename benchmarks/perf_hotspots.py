"""Hot instructions inside one compiled function, from a perf recording of ``profile_events.py``.

perf cannot disassemble Numba's JIT code, but ``profile_events.py --perf-map --dump-objects DIR``
leaves the map of the functions' addresses and the object files they were loaded from. This
script takes the sampled addresses (``perf script -F ip -G``), keeps those inside FUNCTION,
buckets them by offset in the function and prints the hottest buckets with their machine code::

    perf record -F 1999 -k CLOCK_MONOTONIC -o /tmp/gas.perf -- .venv/bin/python \\
        benchmarks/profile_events.py --start 1 --duration 10 --perf-map --dump-objects /tmp/objs
    perf script -i /tmp/gas.perf --time A,B -F ip -G > /tmp/ips.txt     # A,B: the printed window
    .venv/bin/python benchmarks/perf_hotspots.py /tmp/perf-<pid>.map /tmp/ips.txt \\
        pge.core.grid.gather --objects /tmp/objs

Reading the instructions tells which array load the time waits on (for example
``mov 0x20(%r9,%rbx,8),%rbx``: column 4 of a row of ``I``, the cell list's NEXT).
"""

from __future__ import annotations

import argparse
import bisect
import collections
import re
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from profile_events import short_name  # noqa: E402  (the same symbol names as the perf map)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("map", type=Path, help="/tmp/perf-<pid>.map written by profile_events.py --perf-map")
    parser.add_argument("ips", type=Path, help="sampled addresses, one hex address first on each line")
    parser.add_argument("function", help="function name as in the map, e.g. pge.core.engine.run")
    parser.add_argument("--objects", type=Path, default=None, help="directory of profile_events.py --dump-objects")
    parser.add_argument("--bucket", type=int, default=32, help="bytes per bucket (default 32)")
    parser.add_argument("--top", type=int, default=8, help="how many buckets to show (default 8)")
    args = parser.parse_args(argv)

    entries = []
    for line in args.map.read_text().splitlines():
        start, size, name, tag = line.split()
        entries.append((int(start, 16), int(size, 16), name, tag.strip("[]")))
    entries.sort()
    starts = [entry[0] for entry in entries]
    total = 0
    inside = collections.Counter()
    library = None
    for line in args.ips.read_text().splitlines():
        fields = line.split()
        if not fields:
            continue
        try:
            ip = int(fields[0], 16)
        except ValueError:
            continue
        total += 1
        k = bisect.bisect_right(starts, ip) - 1
        if k >= 0 and ip < entries[k][0] + entries[k][1] and entries[k][2] == args.function:
            inside[(ip - entries[k][0]) // args.bucket * args.bucket] += 1
            library = entries[k][3]
    hits = sum(inside.values())
    if not hits:
        print(f"no samples in {args.function}")
        return 1
    print(f"{args.function} [{library}]: {hits} of {total} samples ({hits / total:.1%})")
    code = {}
    if args.objects is not None:
        code = disassemble(args.objects / f"{library}.o", args.function)
    for offset, count in inside.most_common(args.top):
        print(f"\n+{offset:#x}..+{offset + args.bucket:#x}: {count} samples, {count / hits:.1%} of the function, "
              f"{count / total:.1%} of all")
        for at in sorted(code):
            if offset - 16 <= at < offset + args.bucket:
                print(f"    +{at:#06x}  {code[at]}")
    return 0


def disassemble(obj: Path, function: str) -> dict[int, str]:
    """Offset within ``function`` -> instruction text, from the object file."""
    symbols = subprocess.run(["nm", "-S", str(obj)], capture_output=True, text=True, check=True).stdout
    start = None
    for row in symbols.splitlines():
        fields = row.split()
        if len(fields) == 4 and fields[2] in "TtWw" and short_name(fields[3]) == function:
            start = int(fields[0], 16)
            break
    if start is None:
        return {}
    listing = subprocess.run(["objdump", "-d", "--no-show-raw-insn", str(obj)], capture_output=True, text=True,
                             check=True).stdout
    code = {}
    for line in listing.splitlines():
        m = re.match(r"\s+([0-9a-f]+):\s+(.*)", line)
        if m:
            offset = int(m.group(1), 16) - start
            if offset >= 0:
                code[offset] = re.sub(r"<_ZN\S+>", "<...>", m.group(2))
    return code


if __name__ == "__main__":
    sys.exit(main())
