"""The ``pge`` command line: showcase, info, play, view, export, run, sweep.

Every failure the user can cause (missing file, a file that is not a
recording, a damaged recording, bad options) ends with one line
``pge: error: ...`` on stderr and a non-zero exit status: 2 for bad usage,
1 otherwise. Set PGE_DEBUG=1 to see the traceback of an unexpected error.
"""

from __future__ import annotations

import argparse
import os
import sys

from pge import __version__

_EPILOG_EXPORT = """\
examples:
  pge export run.pgerec frames/                 every frame as frames/frame_00000.png, ...
  pge export run.pgerec run.gif --fps 25        an animated GIF at 25 frames per second
  pge export run.pgerec run.mp4 --size 1280x720 --start 2 --end 10
  pge export run.pgerec run.html                the browser viewer as one file anyone can open
"""

_EPILOG_VIEW = """\
the page:
  play/pause, step, a seek slider, the speed, the time, and the collisions and timers beside the scene;
  keys: space plays/pauses, left/right step, up/down jump 10 frames, home/end, +/- change the speed

examples:
  pge view run.pgerec                           serve on a free port and open the browser
  pge view output.raw --port 8000 --no-browser  serve on port 8000 only (open the printed URL yourself)
"""


_EPILOG_SWEEP = """\
the scene file defines (the name can be changed with SCENE.py:NAME):
  def scene(seed, **params) -> pge.World       called with the seed and one value of every --param

values:
  NAME=A:B:N        N evenly spaced values from A to B (ints if A, B and the step are whole)
  NAME=V1,V2,...    a list: ints stay ints, then floats, true/false, else text

examples:
  pge sweep gas.py --param density=0.05:0.4:8 --param elasticity=0.9,1.0 --seeds 20 --until 10 --out results/
  pge sweep gas.py -p density=0.1 --seeds 3,7 --until 5 --out results/ --scheduler tcp://10.0.0.5:8786
  python -c "import pandas; print(pandas.read_parquet('results/runs'))"

Runs already in DIR (same scene name, parameters, seed and --until) are not run again, so a sweep
that was stopped can be started again with the same command.
"""


class _Parser(argparse.ArgumentParser):
    """argparse, but a usage error is one line naming the command's --help."""

    def error(self, message):
        self.exit(2, f"pge: error: {message} (see '{self.prog} --help')\n")


def _showcase(args) -> int:
    from pge.showcase import run_showcase

    run_showcase(args.out, args.duration, args.seed)
    return 0


def _open(args):
    from pge.recording import open_recording

    return open_recording(args.file, strict=not args.partial)


def _info(args) -> int:
    recording = _open(args)
    kinds = [body.kind for body in recording.bodies.values()]
    writer = f" (written by {recording.writer})" if recording.writer else ""
    rate = f" at {recording.frame_rate:g} fps" if recording.frame_rate else ""
    if recording.damage is not None:
        state = f"no: {recording.damage}"
    elif recording.complete:
        state = "yes"
    else:
        state = "no end record (still being written, or cut at a record boundary)"
    lines = [
        ("file", str(recording.path)),
        ("format", recording.format + writer),
        ("duration", f"{recording.duration:g} s ({recording.start_time:g} s to {recording.end_time:g} s)"),
        ("frames", f"{len(recording)}{rate}"),
        ("bodies", f"{len(kinds)} ({kinds.count('circle')} circles, {kinds.count('polygon')} polygons)"),
        ("collisions", str(recording.event_counts.get("collisions", 0))),
        ("timers", str(recording.event_counts.get("timers", 0))),
        ("bounds", " ".join(f"{v:g}" for v in recording.bounds)),
        ("complete", state),
    ]
    lines += [("note", note) for note in recording.notes]
    for name, value in lines:
        print(f"{name:<11}{value}")
    return 0


def _size(text: str) -> tuple[int, int]:
    try:
        parts = [int(p) for p in text.lower().split("x")]
    except ValueError:
        parts = []
    if len(parts) == 1:
        parts *= 2
    if len(parts) != 2 or min(parts) < 1 or max(parts) > 16384:
        raise argparse.ArgumentTypeError(f"size must be WIDTHxHEIGHT or SIDE in pixels, got {text!r}")
    return parts[0], parts[1]


def _positive(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        value = float("nan")
    if not value > 0 or value == float("inf"):
        raise argparse.ArgumentTypeError(f"must be a positive number, got {text!r}")
    return value


def _time(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        value = float("nan")
    if value != value or abs(value) == float("inf"):
        raise argparse.ArgumentTypeError(f"must be a time in seconds, got {text!r}")
    return value


def _export(args) -> int:
    from pge.render.export import export

    recording = _open(args)
    count = export(
        recording,
        args.out,
        size=args.size,
        fps=args.fps,
        start=args.start,
        end=args.end,
        progress=not args.quiet,
    )
    if not args.quiet:
        print(f"pge export: {count} frames written to {args.out}")
    return 0


def _view(args) -> int:
    from pge.viewer.server import ViewerServer

    recording = _open(args)
    try:
        server = ViewerServer(recording, port=args.port, start=args.start, end=args.end)
    except OSError as error:
        raise OSError(f"cannot serve on 127.0.0.1 port {args.port}: {error.strerror or error}") from None
    print(f"pge view: serving {recording.path} at {server.url} (Ctrl-C stops)", flush=True)
    # no screen (a server, CI, PGE_HEADLESS=1): webbrowser could start a text browser in this
    # terminal, so only the printed URL is offered
    screen = os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY")
    screenless = sys.platform.startswith("linux") and not screen
    from pge.classic.session import is_headless

    if not args.no_browser and not screenless and not is_headless():
        import webbrowser

        # a headless machine has no browser: the printed URL is enough, so a failure is not an error
        try:
            webbrowser.open(server.url)
        except Exception:
            pass
    try:
        server.serve_forever()
    except KeyboardInterrupt:
        print("pge view: stopped", file=sys.stderr)
    return 0


def _port(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        value = -1
    if not 0 <= value <= 65535:
        raise argparse.ArgumentTypeError(f"must be a port number from 0 to 65535, got {text!r}")
    return value


_PLAY_KEYS = """\
keys:
  space              pause / resume (at the end: play again from the start)
  right, left        pause and step one frame forwards / backwards
  up, down           seek 10 frames forwards / backwards (page up, page down: 100)
  home, end          first / last frame
  +, -               double / halve the speed (1/64x to 64x)
  escape, q          quit

examples:
  pge play run.pgerec                       play at the recorded speed
  pge play run.pgerec --speed 0.25 --start 2
  pge play output.raw --size 1024x768
"""


def _play(args) -> int:
    from pge.classic.session import is_headless
    from pge.playback import play

    recording = _open(args)
    headless = args.headless or is_headless()
    summary = play(
        recording,
        speed=args.speed,
        start_time=args.start,
        size=args.size,
        fullscreen=args.fullscreen,
        headless=headless,
    )
    if headless:
        print(summary.line(recording))
    return 0


def _sweep_param(text: str):
    from pge.sweeps import SweepUsageError, parse_param

    try:
        return parse_param(text)
    except SweepUsageError as error:
        raise argparse.ArgumentTypeError(str(error)) from None


def _sweep_seeds(text: str):
    from pge.sweeps import SweepUsageError, parse_seeds

    try:
        return parse_seeds(text)
    except SweepUsageError as error:
        raise argparse.ArgumentTypeError(str(error)) from None


def _count(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        value = 0
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be a whole number >= 1, got {text!r}")
    return value


def _duration(text: str) -> float:
    value = _time(text)
    if value < 0:
        raise argparse.ArgumentTypeError(f"must be a time >= 0 in seconds, got {text!r}")
    return value


def _sweep(args) -> int:
    from pge import sweeps

    def usage(message: str) -> int:
        print(f"pge: error: {message} (see 'pge sweep --help')", file=sys.stderr)
        return 2

    try:
        sweeps._require_extras()
    except sweeps.MissingExtraError as error:
        print(f"pge: error: {error}", file=sys.stderr)
        return 1
    params = {}
    for name, values in args.param:
        if name in params:
            return usage(f"--param {name} is given twice")
        params[name] = values
    summary = sweeps.SweepSummary()
    try:
        sweeps.sweep(
            args.scene,
            params,
            seeds=args.seeds,
            until=args.until,
            out=args.out,
            events=args.events,
            scheduler=args.scheduler,
            workers=args.workers,
            progress=not args.quiet,
            retry_failed=args.retry_failed,
            summary=summary,
        )
    except sweeps.SweepUsageError as error:
        return usage(str(error))
    except sweeps.SweepLockedError as error:
        print(f"pge: error: {error}", file=sys.stderr)
        return 1
    if not args.quiet:
        out = os.path.join(args.out, "runs")
        print(
            f"pge sweep: {summary.total} runs ({summary.ran} run now, {summary.skipped} already written, "
            f"{summary.failed} failed) in {out}" + (f" and {os.path.join(args.out, 'events')}" if args.events else "")
        )
        if summary.first_failure:
            print(f"pge sweep: first failure: {summary.first_failure}")
    return 0


def _add_file(command) -> None:
    command.add_argument("file", metavar="FILE", help="a pge recording (.pgerec) or an original PGE output.raw")
    command.add_argument(
        "--partial",
        action="store_true",
        help="read a truncated or corrupt file up to the damage instead of refusing it",
    )


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of the ``pge`` command."""
    parser = _Parser(prog="pge", description="pge: a predictive 2D physics and game engine")
    parser.add_argument("--version", action="version", version=f"pge {__version__}")
    commands = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)

    showcase = commands.add_parser("showcase", help="run the headless showcase scene and write a picture")
    showcase.add_argument("--out", default="out", help="directory for the picture (default: out)")
    showcase.add_argument("--duration", type=float, default=5.0, help="simulated seconds (default: 5)")
    showcase.add_argument("--seed", type=int, default=1, help="random seed of the scene (default: 1)")
    showcase.set_defaults(handler=_showcase)

    info = commands.add_parser(
        "info",
        help="describe a recording: duration, frames, bodies, event counts",
        description="Describe a recording: format, duration, frames, bodies, collision and timer counts, "
        "and whether it is complete.",
    )
    _add_file(info)
    info.set_defaults(handler=_info)

    play = commands.add_parser(
        "play",
        help="play a recording in a window (pause, step, seek, speed, event list)",
        description="Play a recording in a window at its recorded speed, or faster or slower, with the "
        "latest collisions and timers listed on screen. With --headless (or PGE_HEADLESS=1) there is no "
        "window and no waiting: every frame is drawn once off screen and a summary line is printed.",
        epilog=_PLAY_KEYS,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    _add_file(play)
    play.add_argument(
        "--speed", type=_positive, default=1.0, help="simulated seconds per wall-clock second (default: 1, 1/64 to 64)"
    )
    play.add_argument(
        "--start", type=_time, default=None, metavar="T", help="start at the frame shown at time T seconds"
    )
    play.add_argument(
        "--size",
        type=_size,
        default=None,
        metavar="WxH",
        help="window size in pixels (default: 800 on the longer side)",
    )
    play.add_argument("--fullscreen", action="store_true", help="play full screen")
    play.add_argument("--headless", action="store_true", help="no window: walk every frame and print a summary")
    play.set_defaults(handler=_play)

    view = commands.add_parser(
        "view",
        help="watch a recording in a web browser (served on 127.0.0.1)",
        description="Serve a page that plays the recording on 127.0.0.1 (this machine only), print its URL "
        "and open it in the default browser. The page needs no internet. Ctrl-C stops the server.",
        epilog=_EPILOG_VIEW,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    _add_file(view)
    view.add_argument("--port", type=_port, default=0, help="port to serve on (default: a free one)")
    view.add_argument("--no-browser", action="store_true", help="do not open a browser, only print the URL (the default where there is no screen)")
    view.add_argument("--start", type=_time, default=None, metavar="T", help="first time in seconds (default: start)")
    view.add_argument("--end", type=_time, default=None, metavar="T", help="last time in seconds (default: end)")
    view.set_defaults(handler=_view)

    export = commands.add_parser(
        "export",
        help="export a recording as PNG frames, an animated GIF, an MP4 video or an HTML viewer",
        description="Export a recording. OUT ending in .gif writes an animated GIF, .mp4 an H.264 video, "
        ".html the browser viewer as one self-contained file (--size and --fps do not apply); "
        "any other name is a directory that receives one PNG per frame.",
        epilog=_EPILOG_EXPORT,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    _add_file(export)
    export.add_argument("out", metavar="OUT", help="DIRECTORY for PNG frames, or FILE.gif, FILE.mp4 or FILE.html")
    export.add_argument(
        "--size", type=_size, default=(512, 512), metavar="WxH", help="picture size in pixels (default: 512x512)"
    )
    export.add_argument(
        "--fps",
        type=_positive,
        default=None,
        help="output frames per second of simulated time (default: every frame for PNG; "
        "the recording's rate, at most 50 for GIF and 60 for MP4)",
    )
    export.add_argument("--start", type=_time, default=None, metavar="T", help="first time in seconds (default: start)")
    export.add_argument("--end", type=_time, default=None, metavar="T", help="last time in seconds (default: end)")
    export.add_argument("-q", "--quiet", action="store_true", help="no progress bar and no summary line")
    export.set_defaults(handler=_export)

    sweep = commands.add_parser(
        "sweep",
        help="run a scene for every combination of parameters and seeds on Dask; one Parquet row per run",
        description="Run SCENE.py's scene(seed, **params) for every combination of the --param values and "
        "every seed, on an embedded Dask LocalCluster (one worker process per core) or on the cluster of "
        "--scheduler, and write one row per run (parameters, seed, times, world.stats, kinetic energy, "
        "momentum, error) to the Parquet dataset DIR/runs; with --events every collision to DIR/events. "
        "Needs the sweep extra: pip install 'pge[sweep]'.",
        epilog=_EPILOG_SWEEP,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    sweep.add_argument("scene", metavar="SCENE.py", help="a Python file defining scene(seed, **params) -> pge.World")
    sweep.add_argument(
        "-p",
        "--param",
        action="append",
        default=[],
        type=_sweep_param,
        metavar="NAME=VALUES",
        help="a swept parameter: NAME=A:B:N or NAME=V1,V2,... (repeat for more; every combination is run)",
    )
    sweep.add_argument(
        "--seeds",
        type=_sweep_seeds,
        default=[0],
        metavar="N|S1,S2,...",
        help="N for seeds 0 to N-1, or a comma list of seeds (default: seed 0 only)",
    )
    sweep.add_argument(
        "--until", type=_duration, required=True, metavar="T", help="simulated seconds each run is run to"
    )
    sweep.add_argument("--out", required=True, metavar="DIR", help="output directory (DIR/runs, DIR/events)")
    sweep.add_argument("--events", action="store_true", help="also write every collision to DIR/events")
    sweep.add_argument(
        "--scheduler", metavar="ADDRESS", help="a running Dask scheduler, e.g. tcp://10.0.0.5:8786 (default: local)"
    )
    sweep.add_argument(
        "--workers", type=_count, default=None, help="worker processes of the local cluster (default: one per core)"
    )
    sweep.add_argument(
        "--retry-failed", action="store_true", help="run again the runs in DIR that recorded an error"
    )
    sweep.add_argument("-q", "--quiet", action="store_true", help="no progress bar and no summary line")
    sweep.set_defaults(handler=_sweep)

    from pge.classic.script import add_run_command

    add_run_command(commands)
    return parser


def _message(error: BaseException) -> str:
    if isinstance(error, FileNotFoundError):
        return f"{error.filename}: no such file"
    if isinstance(error, IsADirectoryError):
        return f"{error.filename}: is a directory, not a recording"
    if isinstance(error, PermissionError):
        return f"{error.filename}: permission denied"
    if isinstance(error, OSError) and error.filename is not None:
        return f"{error.filename}: {error.strerror or error}"
    return str(error)


def main(argv=None) -> int:
    """Entry point of the ``pge`` console script; returns the exit status."""
    parser = build_parser()
    try:
        args = parser.parse_args(argv)
    except SystemExit as done:
        return int(done.code or 0)
    if not getattr(args, "handler", None):
        parser.print_help()
        return 2
    try:
        return args.handler(args)
    except KeyboardInterrupt:
        print("pge: interrupted", file=sys.stderr)
        return 130
    except (ValueError, OSError) as error:
        print(f"pge: error: {_message(error)}", file=sys.stderr)
        return 1
    except Exception as error:  # never a traceback for users; PGE_DEBUG=1 shows it
        if os.environ.get("PGE_DEBUG"):
            raise
        print(f"pge: error: unexpected {type(error).__name__}: {error}", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
