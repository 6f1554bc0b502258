"""Toppling: a ball knocks over a tall block while crates and a spinning wedge tumble down.

A ball rolls into a tall block standing on the floor and hits it above its
centre: the block tips over its far corner and falls flat. Two crates dropped
at an angle (one of them spinning), clear of the block's fall, land on a corner,
tip, rock and settle on a face; a spinning triangle bounces about and comes to
rest too.

What it shows: rotation with exact contact times (corners of turning polygons
are predicted, never stepped), the rigid-body impulse with friction
(``obj.friction(mu)``: impacts start and stop spins), ``obj.rotate(angle)``
and ``obj.rvel(omega)`` to start bodies turned and turning, and islands (bodies
in persistent contact, solved together and sleeping once still) ending the
bounces: after a couple of seconds nothing moves and no more events happen.

Run it in a window with ``python examples/toppling.py`` (ESC quits), or
headless with ``PGE_HEADLESS=1 python examples/toppling.py``. At the end it
prints one ``RESULT`` line: whether the block toppled (it lies on its side),
how many bodies rest or sleep, whether the last seconds were quiet (no event), and
whether any two bodies overlap.
"""

import math
import sys

import pge  # first: it keeps pygame from printing its banner
from pygame.locals import K_ESCAPE, KEYDOWN, QUIT

DURATION = 6.0
QUIET_FROM = 4.0

pge.interactive()
pge.display_set_mode([800, 800])
pge.slow_down(2.0)
pge.elasticity(0.5)

wood = pge.rgb(0.55, 0.35, 0.2)
floor = pge.box(0.0, 0.0, 1.0, 0.05, wood).fix().friction(0.5)
pge.box(0.0, 0.05, 0.02, 0.95, wood).fix()
pge.box(0.98, 0.05, 0.02, 0.95, wood).fix()

block = pge.box(0.3, 0.05, 0.04, 0.2, pge.rgb(0.85, 0.25, 0.2)).mass(0.2).friction(0.5)
ball = pge.circle(0.08, 0.22, 0.03, pge.rgb(0.95, 0.8, 0.2)).mass(0.3).velocity(1.5, 0.0).friction(0.2)
crate = pge.box(0.6, 0.45, 0.1, 0.1, pge.rgb(0.3, 0.55, 0.9)).mass(0.5).friction(0.5).rotate(0.5)
plank = pge.box(0.76, 0.67, 0.12, 0.06, pge.rgb(0.3, 0.7, 0.4)).mass(0.5).friction(0.5).rotate(-0.9).rvel(3.0)
wedge = pge.poly3(0.84, 0.85, 0.94, 0.85, 0.89, 0.93, pge.rgb(0.6, 0.3, 0.8)).mass(0.2).friction(0.5).rvel(-6.0)
movers = [block, ball, crate, plank, wedge]

events = {"last": 0.0}


def hit(obj, event):
    """Remember when the last collision happened."""
    events["last"] = pge.get_time()


for mover in movers:
    mover.on_collision(hit)


def key_pressed(event):
    if event.key == K_ESCAPE:
        sys.exit(0)


pge.register_handler(lambda event: sys.exit(0), [QUIT])
pge.register_handler(key_pressed, [KEYDOWN])
pge.gravity()

pge.run(DURATION)

angle = block.get_angle()
toppled = abs(abs(math.remainder(angle, math.pi)) - math.pi / 2) < 1e-6
resting = sum(1 for mover in movers if mover.body.resting_on is not None or mover.body.asleep)
quiet = events["last"] < QUIET_FROM
overlapping = len(block.body.world.overlaps(1e-9))
print(
    f"RESULT example=toppling time={pge.get_time():.6f} toppled={toppled} block_angle={angle:.6f} "
    f"resting={resting}/{len(movers)} quiet={quiet} last_hit={events['last']:.6f} overlaps={overlapping}"
)
