#!/bin/bash
# Which compiled functions call NRT_incref / NRT_decref in pge's event loop, and how often.
#   benchmarks/refcount_callers.sh [N] [START] [DURATION] [SAMPLES]     (defaults 10000 1 0.5 20000)
# Runs benchmarks/profile_events.py --perf-map --pause, attaches gdb with
# benchmarks/refcount_callers.gdb.py once the run has reached START, samples the first SAMPLES
# refcount calls of the timed part, then lets it finish. Python: $PYTHON (default .venv/bin/python).
set -euo pipefail
N=${1:-10000}; START=${2:-1}; DURATION=${3:-0.5}; export PGE_SAMPLE_LIMIT=${4:-20000}
HERE=$(cd "$(dirname "$0")" && pwd)
PYTHON=${PYTHON:-$HERE/../.venv/bin/python}
WORK=$(mktemp -d)
export PGE_CALLERS_OUT=$WORK/callers.txt
mkfifo "$WORK/go"
"$PYTHON" "$HERE/profile_events.py" --n "$N" --start "$START" --duration "$DURATION" --perf-map --pause \
    < "$WORK/go" > "$WORK/run.txt" 2>&1 &
exec 3>"$WORK/go"
until grep -q READY "$WORK/run.txt"; do sleep 0.5; done
PID=$(awk '/READY/{print $2}' "$WORK/run.txt")
(sleep 5; echo go >&3) &   # gdb needs a moment to attach and set its breakpoints
gdb -p "$PID" -batch -x "$HERE/refcount_callers.gdb.py" > "$WORK/gdb.txt" 2>&1 || true
wait
grep -v READY "$WORK/run.txt"
cat "$PGE_CALLERS_OUT"
