"""Scenes and file builders shared by the recording, export and CLI tests."""

from __future__ import annotations

import struct
from fractions import Fraction

from pge import World
from pge.recording import Recorder

GRAVITY = (0.25, -9.81)


def falling_scene() -> tuple[World, list]:
    """Five discs and a triangle thrown upwards in a big box; nothing touches before t = 1.

    Returns the world and each moving body's (position, velocity) at t = 0.
    """
    world = World(gravity=GRAVITY, bounds=(0.0, 0.0, 1.0, 1.0))
    starts = []
    for k in range(5):
        position, velocity = (0.1 + 0.2 * k, 0.5 + 0.01 * k), (0.05 * k - 0.1, 1.0 + 0.3 * k)
        world.add_circle(position, 0.02 + 0.002 * k, mass=1.0, velocity=velocity)
        starts.append((position, velocity))
    world.add_polygon([(0.4, 0.2), (0.47, 0.2), (0.43, 0.26)], mass=2.0, velocity=(0.1, 0.2))
    return world, starts


def bouncing_scene() -> World:
    """Discs and a box bouncing in a closed unit box (many collisions), one disc coloured by data."""
    world = World(gravity=(0.0, -9.81), elasticity=1.0)
    world.add_box(0.0, 0.0, 1.0, 0.05, fixed=True, name="floor")
    world.add_box(0.0, 0.95, 1.0, 0.05, fixed=True, name="ceiling")
    world.add_box(0.0, 0.05, 0.05, 0.9, fixed=True, name="left")
    world.add_box(0.95, 0.05, 0.05, 0.9, fixed=True, name="right")
    world.add_circle((0.3, 0.5), 0.2, mass=1.0, velocity=(1.3, 0.7), data={"colour": (250, 20, 20)}, name="big")
    world.add_circle((0.75, 0.3), 0.05, mass=0.2, velocity=(-0.9, 2.0))
    world.add_box(0.7, 0.7, 0.1, 0.1, mass=0.5, velocity=(-0.5, -1.0))
    return world


def record_small(path, until: float = 0.5, frame_rate: float = 20.0) -> World:
    """Record ``bouncing_scene`` into ``path`` (a small file with collisions) and return the world."""
    world = bouncing_scene()
    with Recorder(world, path, frame_rate=frame_rate):
        world.run_until(until)
    return world


# ----------------------------------------------------------- original output.raw


def cmd(name: str) -> bytes:
    """A command header: two letters and a NUL."""
    return name.encode() + b"\0"


def short(n: int) -> bytes:
    return struct.pack(">H", n)


def card(n: int) -> bytes:
    return struct.pack(">I", n)


def fract(value) -> bytes:
    """The original's exact-fraction encoding of a non-negative value."""
    value = Fraction(value)
    if value == 0:
        return b"\0"
    if value == 1:
        return b"\1"
    whole, rest = divmod(value.numerator, value.denominator)
    if whole == 0:
        return b"\2" + struct.pack(">QQ", value.numerator, value.denominator)
    return b"\3" + struct.pack(">QQQ", whole, rest, value.denominator)


def point(x, y) -> bytes:
    return fract(x) + fract(y)


def sleep(seconds: float) -> bytes:
    return cmd("sl") + struct.pack("<d", seconds)


def disc(x, y, r, colour: int) -> bytes:
    return cmd("dC") + point(x, y) + fract(r) + short(colour)


def polygon(corners, colour: int) -> bytes:
    return cmd("dP") + short(len(corners)) + b"".join(point(x, y) for x, y in corners) + short(colour)


def border() -> bytes:
    return cmd("dp") + short(4) + point(0, 0) + point(1, 0) + point(1, 1) + point(0, 1) + fract(Fraction(1, 100))


def raw_batch_file(frames: int = 4) -> bytes:
    """A batch-mode output.raw as the original writes it: frame 1 registers colours, then
    ``frames`` drawn frames, each a disc moving right by 1/10 and a fixed red triangle."""
    data = cmd("fn") + card(1)
    data += cmd("rc") + short(8) + fract(Fraction(1, 2)) + fract(Fraction(1, 4)) + fract(1)
    data += cmd("rc") + short(3) + fract(1) + fract(0) + fract(0)
    data += cmd("fb")
    for k in range(frames):
        data += sleep(0.01)
        data += cmd("fn") + card(k + 2) + sleep(0.01) + border()
        data += disc(Fraction(1, 10) + Fraction(k, 10), Fraction(1, 2), Fraction(1, 10), 8)
        data += polygon([(Fraction(6, 10), Fraction(1, 10)), (Fraction(9, 10), Fraction(1, 10)), (Fraction(3, 4), Fraction(3, 10))], 3)
        data += cmd("fb") + cmd("fb")
    return data
