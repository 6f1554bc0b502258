"""gdb script: who calls Numba's NRT_incref / NRT_decref, and how often, in pge's event loop.

Used by ``benchmarks/refcount_callers.sh`` (see benchmarks/README.md, "Where the time goes"):
gdb attaches to ``profile_events.py --perf-map --pause``, puts a breakpoint on every copy of
NRT_incref and NRT_decref named in /tmp/perf-<pid>.map, and for the first ``PGE_SAMPLE_LIMIT``
calls (default 20000) reads the return address off the stack; the calling function is the
perf-map entry holding it. The breakpoints are then disabled and the run finishes at full speed.
Output: ``PGE_CALLERS_OUT`` (default /tmp/refcount_callers.txt), one line per (callee, caller).
"""

import bisect
import collections
import os

import gdb

pid = gdb.selected_inferior().pid
entries = []
with open(f"/tmp/perf-{pid}.map") as handle:
    for line in handle:
        start, size, name, tag = line.split()
        entries.append((int(start, 16), int(size, 16), f"{name} {tag}"))
entries.sort()
starts = [start for start, _, _ in entries]
limit = int(os.environ.get("PGE_SAMPLE_LIMIT", "20000"))
out = os.environ.get("PGE_CALLERS_OUT", "/tmp/refcount_callers.txt")
counts = collections.Counter()
breakpoints = []
seen = [0]


def owner(address):
    k = bisect.bisect_right(starts, address) - 1
    if k >= 0 and address < entries[k][0] + entries[k][1]:
        return entries[k][2]
    return hex(address)


class Counter(gdb.Breakpoint):
    def __init__(self, address, callee):
        super().__init__(f"*{address:#x}", internal=True)
        self.callee = callee

    def stop(self):
        rsp = int(gdb.parse_and_eval("$rsp"))
        ret = int.from_bytes(gdb.selected_inferior().read_memory(rsp, 8).tobytes(), "little")
        counts[(self.callee, owner(ret))] += 1
        seen[0] += 1
        if seen[0] >= limit:
            for b in breakpoints:
                b.enabled = False
        return False


for start, size, name in entries:
    callee = name.split()[0]
    if callee in ("NRT_incref", "NRT_decref"):
        breakpoints.append(Counter(start, callee))


def report(event):
    with open(out, "w") as handle:
        total = sum(counts.values())
        handle.write(f"# {total} sampled calls\n")
        for (callee, caller), count in counts.most_common():
            handle.write(f"{count:8d} {count / total:7.1%}  {callee:11s} <- {caller}\n")


gdb.events.exited.connect(report)
gdb.execute("continue")
