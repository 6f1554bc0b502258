"""Running a PGE script as a program: ``python -m pge.classic [OPTIONS] SCRIPT [ARGS...]``.

``run_script`` executes the script as ``__main__`` (as ``python SCRIPT`` would),
with ``sys.argv`` set to ``[SCRIPT, *ARGS]`` and its directory first on
``sys.path``; ``--headless`` sets PGE_HEADLESS=1 first, so the game runs with
no window, no pacing and no input. ``--record FILE`` records the run to FILE
(as if the script had called ``pge.record()``, but to that path) and
``--until T`` stops the simulation at simulated time T, both through
``pge.classic.runloop.run_options``. ``add_run_command`` adds the same thing
as the ``run`` subcommand of an argparse parser (for the ``pge`` command).
"""

from __future__ import annotations

import argparse
import os
import runpy
import sys
import traceback
from pathlib import Path

__all__ = ["run_script", "add_run_command", "main"]


def run_script(path, args=(), headless: bool = False, record=None, until=None) -> int:
    """Run the PGE script at ``path`` with arguments ``args``; returns its exit status.

    ``record``: a file the run is recorded to (closed when the script ends);
    ``until``: the simulated time in seconds at which the simulation stops
    (see ``pge.classic.runloop.run_options``). Both apply to this script only.
    """
    from pge.classic.runloop import finish_record, run_options
    from pge.classic.session import STATE

    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(2, "No such file", str(path))
    if headless:
        os.environ["PGE_HEADLESS"] = "1"
    run_options(record=record, until=until)
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
        if record is not None:
            finish_record()  # complete the file now, not at interpreter exit
            STATE.record_target = None
        STATE.until = float("inf")
    return 0


def _handle(args) -> int:
    """Run the script; an error in it prints its traceback (the script's bug, not pge's) and gives 1."""
    if not Path(args.script).is_file():
        raise FileNotFoundError(2, "No such file", args.script)
    if args.record is not None and not Path(args.record).resolve().parent.is_dir():
        raise ValueError(f"--record {args.record}: the directory {Path(args.record).parent} does not exist")
    try:
        code = run_script(args.script, args.args, args.headless, args.record, args.until)
    except Exception:  # noqa: BLE001 (whatever the script raises: show its traceback)
        traceback.print_exc()
        code = 1
    if args.record is not None:
        if Path(args.record).is_file():
            print(f"pge run: recording written to {args.record}", file=sys.stderr)
        else:
            print(f"pge run: nothing recorded to {args.record}: the script never ran the simulation", file=sys.stderr)
    return code


def _until(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        value = float("nan")
    if not 0.0 <= value < float("inf"):
        raise argparse.ArgumentTypeError(f"must be a simulated time in seconds (0 or more), got {text!r}")
    return value


def add_run_command(commands) -> argparse.ArgumentParser:
    """Add ``run [--headless] [--record FILE] [--until T] SCRIPT [ARGS...]`` to an argparse subparsers object."""
    command = commands.add_parser(
        "run",
        help="run a PGE game script (in a window, or headless)",
        description="Run a script written against the PGE API. With --headless (or PGE_HEADLESS=1) "
        "there is no window, no wall-clock pacing and no input: the game runs as fast as it can.",
    )
    command.add_argument("--headless", action="store_true", help="no window (sets PGE_HEADLESS=1)")
    command.add_argument(
        "--record",
        metavar="FILE",
        default=None,
        help="record the run to FILE (a pge recording, as if the script called pge.record(), to this path)",
    )
    command.add_argument(
        "--until",
        type=_until,
        metavar="T",
        default=None,
        help="cap the run at simulated time T seconds: a run() that would go past T stops there and returns "
        "(so the script can print its results), and a later run() ends the script; a game that ends "
        "sooner is not made to last until T",
    )
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
