"""Seeing a World: pictures, notebook display, inline animations, and the left-the-world warning.

``World.picture``, ``World._repr_png_``, ``World.animate`` and
``World.record`` are thin methods over the functions here, so the World
class stays about the physics. ``check_escapes`` runs at the end of each
run (never per event): it warns, once per body, about a moving body that has
left the world's bounds (and every fixed body) and can no longer come back.
"""

from __future__ import annotations

import io
import numbers
import tempfile
import warnings
from pathlib import Path

import numpy as np

from pge.core import layout as L

__all__ = ["LeftWorldWarning", "picture", "png_bytes", "animate", "check_escapes", "picture_size"]

#: the longer side, in pixels, of a picture when no size is given.
DEFAULT_SIDE = 800
#: the longer side of the picture a notebook shows for a World.
NOTEBOOK_SIDE = 400
#: frames per second of ``World.animate`` when neither it nor the world has a frame rate.
ANIMATE_RATE = 30.0


class LeftWorldWarning(UserWarning):
    """A moving body left the world's bounds, beyond every fixed body, moving away, and its
    acceleration cannot turn it back: no wall will ever touch it again."""


def picture_size(bounds, size) -> tuple[int, int]:
    """``(width, height)`` in pixels: ``size`` itself if a pair, else the longer side
    (``size`` pixels, default ``DEFAULT_SIDE``) with the aspect of ``bounds``."""
    if size is None:
        size = DEFAULT_SIDE
    if isinstance(size, numbers.Integral) and not isinstance(size, bool):
        if not 1 <= size <= 16384:
            raise ValueError(f"picture: size must be from 1 to 16384 pixels, got {size}")
        x0, y0, x1, y1 = bounds
        w, h = x1 - x0, y1 - y0
        k = size / max(w, h)
        return max(1, round(w * k)), max(1, round(h * k))
    try:
        width, height = size
    except (TypeError, ValueError):
        raise TypeError(f"picture: size must be pixels on the longer side or (width, height), got {size!r}") from None
    for v in (width, height):
        if isinstance(v, bool) or not isinstance(v, numbers.Integral) or not 1 <= v <= 16384:
            raise ValueError(f"picture: width and height must be whole numbers from 1 to 16384, got {size!r}")
    return int(width), int(height)


def picture(world, path=None, size=None, bounds=None):
    """A Pillow picture of ``world`` now (``pge.render.image.render_image``), also written
    to ``path`` as PNG if given; returns the ``PIL.Image``."""
    from pge.render.image import render_image

    if bounds is None:
        bounds = world.bounds
    else:
        try:
            x0, y0, x1, y1 = (float(v) for v in bounds)
        except (TypeError, ValueError):
            raise TypeError(f"picture: bounds must be (x0, y0, x1, y1), got {bounds!r}") from None
        if not (x1 > x0 and y1 > y0):
            raise ValueError(f"picture: bounds must satisfy x0 < x1 and y0 < y1, got {bounds!r}")
        bounds = (x0, y0, x1, y1)
    image = render_image(world, picture_size(bounds, size), bounds)
    if path is not None:
        path = Path(path)
        path.parent.mkdir(parents=True, exist_ok=True)
        image.save(path, format="PNG")
    return image


def png_bytes(world, size=NOTEBOOK_SIDE) -> bytes:
    """The picture of ``world`` as PNG bytes (what Jupyter shows for a World)."""
    buffer = io.BytesIO()
    picture(world, size=size).save(buffer, format="PNG")
    return buffer.getvalue()


def animate(world, until, frame_rate=None, title=None):
    """Run ``world`` until time ``until``, recording it, and return a ``pge.viewer.Animation``.

    ``frame_rate`` (frames per second of simulated time) defaults to the
    world's, or ``ANIMATE_RATE``; the world's own rate is left as it was.
    """
    from pge.recording import Recorder, open_recording
    from pge.viewer import Animation, recording_data

    if isinstance(until, bool) or not isinstance(until, numbers.Real):
        raise TypeError(f"animate: until must be a time in seconds, got {until!r}")
    if not until >= world.time:
        raise ValueError(f"animate: until {until!r} is before the current time {world.time!r}")
    before = world.frame_rate
    rate = frame_rate if frame_rate is not None else (before or ANIMATE_RATE)
    with tempfile.TemporaryDirectory(prefix="pge-animate-") as folder:
        path = Path(folder) / "run.pgerec"
        try:
            with Recorder(world, path, frame_rate=rate):
                world.run_until(until)
        finally:
            if world.frame_rate != before:
                world.frame_rate = before
        data = recording_data(open_recording(path), title=title or f"World run to t = {float(until):g} s")
    return Animation(data)


def check_escapes(world, stacklevel: int = 3) -> None:
    """Warn (``LeftWorldWarning``, once per body) about each moving body that is wholly
    outside the world's bounds and every fixed body on some side, moving away from them,
    with an acceleration that is zero or points away too: on its own it can never come back."""
    handles = world._handles
    if not handles:
        return
    warned = world.__dict__.setdefault("_escape_warned", set())
    state = world._state
    every = np.fromiter(handles, dtype=np.int64, count=len(handles))
    still = state.I[every, L.FIXED] != 0
    ids, fixed = every[~still], every[still]
    if not len(ids):
        return
    F = state.F

    def now(rows, p0, v0, a):
        acc = F[rows, a]
        dt = world.time - F[rows, L.T0]
        return F[rows, p0] + (F[rows, v0] + 0.5 * acc * dt) * dt, F[rows, v0] + acc * dt, acc

    reach = F[ids, L.REACH]
    x0, y0, x1, y1 = world.bounds
    gone = np.zeros(len(ids), dtype=bool)
    for p0, v0, a, low, high in ((L.X, L.VX, L.AX, x0, x1), (L.Y, L.VY, L.AY, y0, y1)):
        if len(fixed):
            # walls may stand outside the bounds (a wide window's table): the world reaches them too
            where = now(fixed, p0, v0, a)[0]
            low = min(low, float((where - F[fixed, L.REACH]).min()))
            high = max(high, float((where + F[fixed, L.REACH]).max()))
        pos, vel, acc = now(ids, p0, v0, a)
        gone |= (pos - reach > high) & (vel > 0) & (acc >= 0)
        gone |= (pos + reach < low) & (vel < 0) & (acc <= 0)
    for i in ids[gone].tolist():
        if i in warned:
            continue
        warned.add(i)
        body = handles[i]
        (x, y), (vx, vy) = body.position, body.velocity
        warnings.warn(
            f"{body.label()} left the world's bounds {world.bounds} at t = {world.time:g} s, at ({x:.4g}, {y:.4g}) "
            f"moving away at ({vx:.4g}, {vy:.4g}), and its acceleration cannot bring it back: no wall or "
            "fixed body will touch it again (add walls, or give World(bounds=...) room for it)",
            LeftWorldWarning,
            stacklevel=stacklevel,
        )
