"""Size and load time of a pge recording: 1000 discs, 60 s at 100 frames per second.

Run: python benchmarks/recording_size.py [--bodies N] [--seconds S] [--fps F] [--out FILE]
Prints one CSV line (and a header) that can be appended to benchmarks/results/<machine>.csv.
"""

from __future__ import annotations

import argparse
import os
import platform
import tempfile
import time

from pge import World
from pge.recording import Recorder, open_recording
from pge.scenes import disc_gas

WALL = 0.05


def gas_world(n: int) -> World:
    """``n`` equal discs in the unit box, elasticity 1, walls outside the box."""
    gas = disc_gas(n)
    x0, y0, x1, y1 = gas.box
    world = World(elasticity=1.0, bounds=gas.box)
    world.add_box(x0 - WALL, y0 - WALL, x1 - x0 + 2 * WALL, WALL, fixed=True)
    world.add_box(x0 - WALL, y1, x1 - x0 + 2 * WALL, WALL, fixed=True)
    world.add_box(x0 - WALL, y0, WALL, y1 - y0, fixed=True)
    world.add_box(x1, y0, WALL, y1 - y0, fixed=True)
    for position, velocity in zip(gas.positions, gas.velocities):
        world.add_circle(position, gas.radius, mass=1.0, velocity=velocity)
    return world


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--bodies", type=int, default=1000)
    parser.add_argument("--seconds", type=float, default=60.0)
    parser.add_argument("--fps", type=float, default=100.0)
    parser.add_argument("--out", default=None)
    args = parser.parse_args()
    path = args.out or os.path.join(tempfile.mkdtemp(), "gas.pgerec")
    world = gas_world(args.bodies)
    world.run_until(0.0)  # compile/load the kernels outside the timing
    started = time.perf_counter()
    with Recorder(world, path, frame_rate=args.fps):
        world.run_until(args.seconds)
    record_s = time.perf_counter() - started
    size = os.path.getsize(path)
    started = time.perf_counter()
    recording = open_recording(path)
    load_s = time.perf_counter() - started
    started = time.perf_counter()
    frame = recording.frame(len(recording) // 2)
    frame_s = time.perf_counter() - started
    assert len(frame.circles.ids) == args.bodies
    print("machine,bodies,seconds,fps,frames,collisions,bytes,bytes_per_body_frame,record_s,load_s,frame_ms")
    print(
        f"{platform.node()},{args.bodies},{args.seconds:g},{args.fps:g},{len(recording)},"
        f"{recording.event_counts['collisions']},{size},{size / len(recording) / args.bodies:.2f},"
        f"{record_s:.2f},{load_s:.3f},{frame_s * 1e3:.2f}"
    )
    if args.out is None:
        os.remove(path)


if __name__ == "__main__":
    main()
