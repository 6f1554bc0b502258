"""Render a world's current state to an image with Pillow.

The world's ``bounds`` map to the picture with y pointing up, as in PGE.
Shapes are drawn at 3x resolution and downsampled, for smooth edges.
"""

from __future__ import annotations

from pathlib import Path

from PIL import Image, ImageDraw

__all__ = ["render_image", "save_png", "PALETTE"]

#: colours given to moving bodies in turn (fixed bodies are grey).
PALETTE = (
    (230, 85, 70),
    (70, 140, 230),
    (250, 190, 60),
    (90, 190, 110),
    (170, 100, 210),
    (60, 200, 200),
)
FIXED_COLOUR = (120, 120, 130)
BACKGROUND = (18, 20, 28)
_SUPERSAMPLE = 3


def render_image(world, size=(800, 800), bounds=None) -> Image.Image:
    """A picture of ``world`` at its current time.

    ``size`` is ``(width, height)`` in pixels; ``bounds`` ``(x0, y0, x1, y1)``
    the world rectangle shown (default: the world's bounds). A body's colour
    is ``body.data["colour"]`` when given as an RGB tuple, else from PALETTE.
    """
    width, height = size
    x0, y0, x1, y1 = bounds if bounds is not None else world.bounds
    big = (width * _SUPERSAMPLE, height * _SUPERSAMPLE)
    sx = big[0] / (x1 - x0)
    sy = big[1] / (y1 - y0)
    image = Image.new("RGB", big, BACKGROUND)
    draw = ImageDraw.Draw(image)

    def pixel(x, y):
        return ((x - x0) * sx, (y1 - y) * sy)

    for body in world.bodies:
        colour = None
        if isinstance(body.data, dict):
            colour = body.data.get("colour")
        if colour is None:
            colour = FIXED_COLOUR if body.is_fixed else PALETTE[body.id % len(PALETTE)]
        if body.kind == "circle":
            cx, cy = pixel(*body.position)
            rx = body.shape.radius * sx
            ry = body.shape.radius * sy
            draw.ellipse((cx - rx, cy - ry, cx + rx, cy + ry), fill=tuple(colour))
        else:
            draw.polygon([pixel(x, y) for x, y in body.vertices], fill=tuple(colour))
    return image.resize(size, Image.LANCZOS)


def save_png(world, path, size=(800, 800), bounds=None) -> Path:
    """Write ``render_image(world, size, bounds)`` to ``path`` as PNG; returns the path."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    render_image(world, size, bounds).save(path, format="PNG")
    return path
