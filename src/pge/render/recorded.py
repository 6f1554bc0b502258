"""Pictures of recorded frames (``pge.recording.RecordedFrame``) with Pillow.

Same conventions as ``pge.render.image``: the recording's bounds fill the
picture, y points up, shapes are drawn at ``supersample`` times the size and
downsampled for smooth edges (``supersample=1`` draws directly: exact colours
at shape interiors, hard edges).
"""

from __future__ import annotations

import numpy as np
from PIL import Image, ImageDraw

__all__ = ["render_frame"]


def render_frame(recording, frame, size=(512, 512), supersample: int = 2, bounds=None) -> Image.Image:
    """An RGB picture of ``frame`` of ``recording``, ``size = (width, height)`` pixels.

    ``bounds`` ``(x0, y0, x1, y1)`` is the world rectangle shown (default: the
    recording's). Colours are looked up in ``recording.colours``.
    """
    width, height = size
    scale = max(1, int(supersample))
    big = (width * scale, height * scale)
    x0, y0, x1, y1 = recording.bounds if bounds is None else bounds
    sx = big[0] / (x1 - x0)
    sy = big[1] / (y1 - y0)
    colours = recording.colours
    image = Image.new("RGB", big, colours[recording.background])
    draw = ImageDraw.Draw(image)

    circles = frame.circles
    if len(circles.ids):
        px = (circles.centres[:, 0] - x0) * sx
        py = (y1 - circles.centres[:, 1]) * sy
        rx = circles.radii * sx
        ry = circles.radii * sy
        boxes = np.column_stack((px - rx, py - ry, px + rx, py + ry)).tolist()
        for box, colour in zip(boxes, circles.colours.tolist()):
            draw.ellipse(box, fill=colours[colour])
    polygons = frame.polygons
    if len(polygons.ids):
        pixels = np.column_stack(((polygons.vertices[:, 0] - x0) * sx, (y1 - polygons.vertices[:, 1]) * sy))
        starts = polygons.starts.tolist()
        for k, colour in enumerate(polygons.colours.tolist()):
            corners = [tuple(p) for p in pixels[starts[k] : starts[k + 1]].tolist()]
            draw.polygon(corners, fill=colours[colour])
    if scale == 1:
        return image
    return image.resize(size, Image.LANCZOS)
