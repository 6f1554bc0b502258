"""The pygame-ce window: the one module of pge that imports pygame.

``PygameDisplay`` implements the drawing protocol of ``pge.render.protocol``
for a window of any size. The world is drawn at a uniform scale of
``min(width, height)`` pixels per unit with the origin at the bottom-left
corner and y up, so the unit square always fits and circles stay round; in a
window wider (or taller) than square the extra room shows the world beyond
x = 1 (or y = 1).

Circles are the bulk of most scenes, so they are stamped from cached sprites
(one per radius in pixels and colour) with ``Surface.fblits`` in one call:
5000 circles take a few milliseconds. Objects that are not fully opaque use
per-surface alpha (sprites) and ``pygame.gfxdraw`` (polygons).
"""

from __future__ import annotations

import os
from itertools import repeat

import numpy as np

os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")

import pygame  # after setting PYGAME_HIDE_SUPPORT_PROMPT above
import pygame.gfxdraw

__all__ = ["PygameDisplay", "WindowError", "font", "DEFAULT_SIZE"]

#: raised when no window can be opened (no display, no video driver).
WindowError = pygame.error

#: window size when none was given with display_set_mode.
DEFAULT_SIZE = (800, 800)
_SPRITE_CACHE = 4096
_TEXT_CACHE = 256
_fonts: dict[int, pygame.font.Font] = {}


def font(size: int) -> pygame.font.Font:
    """pygame's default font, ``size`` pixels high (cached per size)."""
    if not pygame.font.get_init():
        pygame.font.init()
    found = _fonts.get(size)
    if found is None:
        found = _fonts[size] = pygame.font.Font(None, size)
    return found


def _palette(colours) -> tuple[list, np.ndarray]:
    """Distinct colours and, for each item of ``colours``, the index of its colour."""
    found: dict = {}
    index = np.fromiter((found.setdefault(c, len(found)) for c in colours), dtype=np.int64, count=len(colours))
    return list(found), index


class PygameDisplay:
    """A pygame window showing the unit-square world, y up."""

    draws = True

    def __init__(self, size=None, fullscreen: bool = False, caption: str = "pge") -> None:
        pygame.display.init()
        flags = pygame.FULLSCREEN if fullscreen else 0
        if size is None:
            size = (0, 0) if fullscreen else DEFAULT_SIZE
        self.surface = pygame.display.set_mode(tuple(int(v) for v in size), flags)
        pygame.display.set_caption(caption)
        self.width, self.height = self.surface.get_size()
        #: pixels per world unit
        self.scale = float(min(self.width, self.height))
        self._sprites: dict = {}
        self._texts: dict = {}
        self._mixer = None

    # ------------------------------------------------------------- mapping

    def to_pixels(self, x: float, y: float) -> tuple[float, float]:
        """Pixel coordinates (continuous) of the world point ``(x, y)``."""
        return (x * self.scale, self.height - y * self.scale)

    def to_world(self, px: float, py: float) -> tuple[float, float]:
        """World coordinates of the pixel position ``(px, py)``."""
        return (px / self.scale, (self.height - py) / self.scale)

    # ------------------------------------------------------------- drawing

    def begin_frame(self, background) -> None:
        self.surface.fill(background[:3])

    def circles(self, xs, ys, radii, colours, index=None) -> None:
        if len(xs) == 0:
            return
        s = self.scale
        rp = np.maximum(np.rint(np.asarray(radii) * s), 1.0).astype(np.int64)
        left = (np.rint(np.asarray(xs) * s).astype(np.int64) - rp).tolist()
        top = (np.rint(self.height - np.asarray(ys) * s).astype(np.int64) - rp).tolist()
        if index is None:
            if isinstance(colours[0], int):  # one colour for all
                colours, index = [colours], np.zeros(len(rp), dtype=np.int64)
            else:
                colours, index = _palette(colours)
        # one sprite per (radius in pixels, colour): find the distinct pairs with numpy
        count = len(colours)
        keys = rp * count + np.asarray(index, dtype=np.int64)
        distinct, which = np.unique(keys, return_inverse=True)
        table = [self._sprite(key // count, colours[key % count]) for key in distinct.tolist()]
        if len(table) == 1:
            sprites = repeat(table[0])
        else:
            lookup = np.empty(len(table), dtype=object)
            lookup[:] = table
            sprites = lookup[which.reshape(-1)].tolist()
        self.surface.fblits(list(zip(sprites, zip(left, top))))

    def circle(self, x, y, r, colour) -> None:
        self.circles((x,), (y,), (r,), colour)

    def polygon(self, points, colour) -> None:
        pixels = [self.to_pixels(x, y) for x, y in points]
        if colour[3] >= 255:
            pygame.draw.polygon(self.surface, colour[:3], pixels)
        elif colour[3] > 0:
            pygame.gfxdraw.filled_polygon(self.surface, [(round(px), round(py)) for px, py in pixels], colour)

    def text(self, x, y, s, colour, size) -> None:
        key = (s, size, colour)
        image = self._texts.get(key)
        if image is None:
            image = font(size).render(s, True, colour[:3])
            if colour[3] < 255:
                image.set_alpha(colour[3])
            if len(self._texts) >= _TEXT_CACHE:
                self._texts.clear()
            self._texts[key] = image
        px, py = self.to_pixels(x, y)
        self.surface.blit(image, (round(px), round(py)))

    def end_frame(self) -> None:
        pygame.display.flip()

    def _sprite(self, r: int, colour):
        key = (r, colour)
        sprite = self._sprites.get(key)
        if sprite is None:
            rgb = tuple(colour[:3])
            clear = (255, 0, 255) if rgb != (255, 0, 255) else (0, 255, 0)
            sprite = pygame.Surface((2 * r, 2 * r)).convert()
            sprite.fill(clear)
            pygame.draw.circle(sprite, rgb, (r, r), r)
            sprite.set_colorkey(clear, pygame.RLEACCEL)
            if colour[3] < 255:
                sprite.set_alpha(colour[3])
            if len(self._sprites) >= _SPRITE_CACHE:
                self._sprites.clear()
            self._sprites[key] = sprite
        return sprite

    # ------------------------------------------------------ input and output

    def events(self) -> list:
        return pygame.event.get()

    def is_quit(self, event) -> bool:
        return event.type == pygame.QUIT

    def key_name(self, event) -> str | None:
        if event.type != pygame.KEYDOWN:
            return None
        return pygame.key.name(event.key)

    def play(self, name: str) -> None:
        """Play the sound file ``name``; raises OSError if it cannot be loaded."""
        if self._mixer is None:
            try:
                pygame.mixer.init()
                self._mixer = True
            except pygame.error:
                self._mixer = False
        if not self._mixer:
            return  # no audio device: like the original, play nothing
        try:
            pygame.mixer.Sound(name).play()
        except (pygame.error, FileNotFoundError) as error:
            raise OSError(f"play: cannot load sound file {name!r}: {error}") from None

    def save(self, path) -> None:
        """Write the frame on screen to ``path`` (PNG if the name ends in .png)."""
        pygame.image.save(self.surface, str(path))

    def pixel(self, px: int, py: int) -> tuple[int, int, int]:
        """Colour of the pixel at column ``px``, row ``py`` of the frame on screen."""
        return tuple(self.surface.get_at((px, py)))[:3]

    def close(self) -> None:
        if self._mixer:
            pygame.mixer.quit()
        pygame.display.quit()
