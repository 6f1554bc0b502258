"""Running a PGE script as a program: ``python -m pge.classic [--headless] SCRIPT [ARGS...]``.

``run_script`` executes the script as ``__main__`` (as ``python SCRIPT`` would),
with ``sys.argv`` set to ``[SCRIPT, *ARGS]`` and its directory first on
``sys.path``; ``--headless`` sets PGE_HEADLESS=1 first, so the game runs with
no window, no pacing and no input. ``add_run_command`` adds the same thing as
the ``run`` subcommand of an argparse parser (for the ``pge`` command).
"""

from __future__ import annotations

import argparse
import os
import runpy
import sys
import traceback
from pathlib import Path

__all__ = ["run_script", "add_run_command", "main"]


def run_script(path, args=(), headless: bool = False) -> int:
    """Run the PGE script at ``path`` with arguments ``args``; returns its exit status."""
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(2, "No such file", str(path))
    if headless:
        os.environ["PGE_HEADLESS"] = "1"
    saved_argv, saved_path = sys.argv, list(sys.path)
    sys.argv = [str(path), *args]
    sys.path.insert(0, str(path.resolve().parent))
    try:
        runpy.run_path(str(path), run_name="__main__")
    except SystemExit as done:
        if done.code is None or isinstance(done.code, int):
            return done.code or 0
        print(done.code, file=sys.stderr)
        return 1
    finally:
        sys.argv, sys.path[:] = saved_argv, saved_path
    return 0


def _handle(args) -> int:
    """Run the script; an error in it prints its traceback (the script's bug, not pge's) and gives 1."""
    if not Path(args.script).is_file():
        raise FileNotFoundError(2, "No such file", args.script)
    try:
        return run_script(args.script, args.args, args.headless)
    except Exception:  # noqa: BLE001 (whatever the script raises: show its traceback)
        traceback.print_exc()
        return 1


def add_run_command(commands) -> argparse.ArgumentParser:
    """Add ``run [--headless] SCRIPT [ARGS...]`` to an argparse subparsers object."""
    command = commands.add_parser(
        "run",
        help="run a PGE game script (in a window, or headless)",
        description="Run a script written against the PGE API. With --headless (or PGE_HEADLESS=1) "
        "there is no window, no wall-clock pacing and no input: the game runs as fast as it can.",
    )
    command.add_argument("--headless", action="store_true", help="no window (sets PGE_HEADLESS=1)")
    command.add_argument("script", metavar="SCRIPT", help="the Python script to run")
    command.add_argument("args", nargs=argparse.REMAINDER, metavar="ARGS", help="arguments for the script")
    command.set_defaults(handler=_handle)
    return command


def main(argv=None) -> int:
    """``python -m pge.classic``: run a PGE script."""
    parser = argparse.ArgumentParser(prog="python -m pge.classic", description="Run a PGE game script.")
    commands = parser.add_subparsers(dest="command")
    add_run_command(commands)
    argv = list(sys.argv[1:] if argv is None else argv)
    if not argv or argv[0] != "run":
        argv.insert(0, "run")
    args = parser.parse_args(argv)
    try:
        return args.handler(args)
    except FileNotFoundError as error:
        print(f"{parser.prog}: error: {error.filename}: no such file", file=sys.stderr)
        return 2
