"""Run the original PGE's example programs against pge, headless, and report how each ends.

The examples are not part of this project: point the script at a checkout of the original
(for instance ``git archive`` of gaiusm/pge unpacked somewhere) and it runs each listed program
unchanged, with ``PGE_HEADLESS=1``, in an empty temporary directory, under a wall-time limit.

    python tools/pge_examples.py /path/to/pge-checkout             # the 24 that end there
    python tools/pge_examples.py /path/to/pge-checkout springs/boxes.py --timeout 120

A program passes when it exits with status 0, prints no Traceback and finishes within the
limit. The table gives the wall time and the last lines of its output for the failures.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

#: the original's examples that run to their end there (triangle.py ends in a deliberate error)
ENDING = [
    "breakout/breakout.py",
    "snooker/snooker.py",
    "test/test.py",
    "rotation/rotation.py",
    "matchsticks/matchsticks.py",
    "bagatelle/bagatelle.py",
    "trapped/trapped.py",
    "boxes.py",
    "triangle.py",
    "springs/bounce.py",
    "springs/boxes-break.py",
    "springs/boxes.py",
    "springs/bridge.py",
    "springs/catapult.py",
    "springs/double.py",
    "springs/gravity.py",
    "springs/madness.py",
    "springs/ramps.py",
    "springs/swing.py",
    "springs/tiny.py",
    "springs/tinyfall.py",
    "springs/tinyfall2.py",
    "springs/treble.py",
    "springs/unequal.py",
]


def run_one(path: Path, timeout: float) -> tuple[str, float, str]:
    """Run one program headless; ``(verdict, wall seconds, output tail)``."""
    env = dict(os.environ, PGE_HEADLESS="1", PYGAME_HIDE_SUPPORT_PROMPT="1")
    start = time.perf_counter()
    with tempfile.TemporaryDirectory() as where:
        try:
            done = subprocess.run(
                [sys.executable, str(path)], cwd=where, env=env, capture_output=True, text=True, timeout=timeout
            )
        except subprocess.TimeoutExpired as expired:
            out = expired.stdout or b""
            out = out.decode(errors="replace") if isinstance(out, bytes) else out
            return f"HANG (> {timeout:g} s)", time.perf_counter() - start, out[-400:]
    wall = time.perf_counter() - start
    text = done.stdout + done.stderr
    if path.name == "triangle.py" and text.rstrip().endswith("has no attribute 'finish'"):
        return "OK (finish)", wall, ""  # its last line calls a function neither PGE nor pge has
    if "Traceback" in text:
        return "TRACEBACK", wall, text[-800:]
    if done.returncode != 0:
        return f"EXIT {done.returncode}", wall, text[-800:]
    return "OK", wall, ""


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("checkout", type=Path, help="a checkout of the original PGE (holding examples/)")
    parser.add_argument("programs", nargs="*", help="paths under examples/ (default: the 24 that end there)")
    parser.add_argument("--timeout", type=float, default=120.0, help="wall seconds per program (default 120)")
    args = parser.parse_args(argv)
    root = args.checkout / "examples"
    if not root.is_dir():
        parser.error(f"{args.checkout} has no examples/ folder")
    failures = 0
    for name in args.programs or ENDING:
        path = root / name
        if not path.is_file():
            print(f"{name:<28} MISSING")
            failures += 1
            continue
        verdict, wall, tail = run_one(path, args.timeout)
        print(f"{name:<28} {verdict:<16} {wall:7.1f} s", flush=True)
        if not verdict.startswith("OK"):
            failures += 1
            for line in tail.strip().splitlines()[-6:]:
                print("    " + line)
    print(f"{len(args.programs or ENDING) - failures} passed, {failures} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
