"""Rotation: spinning polygons thrown past tilted ramps, their spins changed by every hit.

What it shows: ``obj.rotate(a)`` turns an object about its centre to angle
``a`` (radians) and ``obj.rvel(w)`` gives it an angular velocity; from then on
it turns in closed form, the engine predicts the exact time a turning corner
meets anything, and off-centre hits start, stop and reverse spins (the
rigid-body impulse). ``get_angle()`` / ``get_rvel()`` read both back. Also
shown: poly3, poly5, poly6 and ``polygon(points, colour)``, fixed ramps tilted
with ``rotate``, a per-object elasticity.

Under gravity with elasticity 1 nothing settles; the one box with elasticity
0.99 loses energy slowly. The ``RESULT`` line gives the collision count,
whether every shape turned away from its starting angle and had its spin
changed by a hit, and whether every body is still inside the room.
"""

import math
import sys

import pge  # first: it keeps pygame from printing its banner
from pygame.locals import QUIT

WALL = 0.01
DURATION = 8.0

pge.interactive()
pge.display_set_mode([800, 800])
pge.slow_down(2.0)
pge.elasticity(1.0)

wood = pge.rgb(0.55, 0.35, 0.2)
ramp_colour = pge.rgb(0.6, 0.6, 0.65)

pge.box(0.0, 0.0, 1.0, WALL, wood).fix()
pge.box(0.0, 1.0 - WALL, 1.0, WALL, wood).fix()
pge.box(0.0, 0.0, WALL, 1.0, wood).fix()
pge.box(1.0 - WALL, 0.0, WALL, 1.0, wood).fix()

ramps = [
    pge.box(0.1, 0.35, 0.35, 0.02, ramp_colour).fix().rotate(-0.35),
    pge.box(0.55, 0.25, 0.35, 0.02, ramp_colour).fix().rotate(0.3),
]


def regular(cx, cy, radius, sides):
    return [
        (cx + radius * math.cos(2 * math.pi * k / sides), cy + radius * math.sin(2 * math.pi * k / sides))
        for k in range(sides)
    ]


p5 = [value for point in regular(0.45, 0.8, 0.05, 5) for value in point]
p6 = [value for point in regular(0.65, 0.85, 0.045, 6) for value in point]
settings = [
    (pge.box(0.15, 0.75, 0.08, 0.08, pge.rgb(0.9, 0.3, 0.2)), math.pi / 4, 3.0),
    (pge.poly3(0.3, 0.6, 0.38, 0.6, 0.34, 0.68, pge.rgb(0.95, 0.8, 0.2)), 0.5, -2.0),
    (pge.poly5(*p5, pge.rgb(0.3, 0.6, 0.9)), 0.2, 1.0),
    (pge.poly6(*p6, pge.rgb(0.4, 0.8, 0.4)), 0.0, 0.5),
    (pge.polygon(regular(0.82, 0.65, 0.05, 7), pge.rgb(0.8, 0.4, 0.8)), 1.0, -1.5),
]
shapes = []
for obj, angle, spin in settings:
    obj.mass(1.0).velocity(0.3, 0.0).rotate(angle).rvel(spin)
    shapes.append(obj)
shapes[0].elasticity(0.99)  # a per-object elasticity: this box loses 1% per bounce

ball = pge.circle(0.5, 0.5, 0.03, pge.white()).mass(0.5).velocity(-0.4, 0.6)
hits = [0]


def count(obj, event):
    hits[0] += 1


for obj in shapes + [ball]:
    obj.on_collision(count)

pge.register_handler(lambda event: sys.exit(0), [QUIT])
pge.gravity()
pge.run(DURATION)

turned = all(obj.get_angle() != angle for (obj, angle, _) in settings)
spins_changed = all(obj.get_rvel() != spin for (obj, _, spin) in settings)
ramps_still = ramps[0].get_angle() == -0.35 and ramps[1].get_angle() == 0.3
inside = all(WALL <= obj.get_xpos() <= 1 - WALL and WALL <= obj.get_ypos() <= 1 - WALL for obj in shapes + [ball])
print(
    f"RESULT example=rotation collisions={hits[0]} turned={turned} spins_changed={spins_changed} "
    f"ramps_still={ramps_still} inside={inside} time={pge.get_time():.6f}"
)
