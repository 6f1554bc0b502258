"""The ``pge`` command line."""

from __future__ import annotations

import argparse
import sys

from pge import __version__


def _showcase(args) -> int:
    from pge.showcase import run_showcase

    run_showcase(args.out, args.duration, args.seed)
    return 0


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of the ``pge`` command."""
    parser = argparse.ArgumentParser(prog="pge", description="pge: a predictive 2D physics and game engine")
    parser.add_argument("--version", action="version", version=f"pge {__version__}")
    commands = parser.add_subparsers(dest="command", metavar="COMMAND")
    showcase = commands.add_parser("showcase", help="run the headless showcase scene and write a picture")
    showcase.add_argument("--out", default="out", help="directory for the picture (default: out)")
    showcase.add_argument("--duration", type=float, default=5.0, help="simulated seconds (default: 5)")
    showcase.add_argument("--seed", type=int, default=1, help="random seed of the scene (default: 1)")
    showcase.set_defaults(handler=_showcase)
    return parser


def main(argv=None) -> int:
    """Entry point of the ``pge`` console script."""
    parser = build_parser()
    args = parser.parse_args(argv)
    if not getattr(args, "handler", None):
        parser.print_help()
        return 2
    try:
        return args.handler(args)
    except (ValueError, OSError) as error:
        print(f"pge: error: {error}", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
