"""Drawing worlds: pictures with Pillow (no display needed)."""

from pge.render.image import render_image, save_png

__all__ = ["render_image", "save_png"]
