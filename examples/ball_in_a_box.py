"""Ball in a box: three balls bounce under gravity inside four walls, for ever.

What it shows: walls built from fixed boxes, balls with a mass and a start
velocity, ``pge.gravity()``, ``on_collision`` callbacks with the original's
argument order ``(obj, event)``, ``event.collision_between()`` and
``pge.get_time()`` inside a callback, ``draw_collision`` frames, ``local_fps``.

Everything has elasticity 1 (``pge.elasticity(1.0)``), so the balls never come
to rest: energy is conserved exactly by the engine, which the summary checks.
(With an elasticity below 1 a ball settles on the floor: once its bounces are
lower than the engine's rest height it rests and slides instead of bouncing
ever more often.)

Run it in a window with ``python examples/ball_in_a_box.py`` (ESC quits), or
headless with ``PGE_HEADLESS=1 python examples/ball_in_a_box.py``. At the end it
prints one ``RESULT`` line: bounces, whether every ball is still inside the box,
and the relative drift of the total energy.
"""

import sys

import pge  # first: it keeps pygame from printing its banner
from pygame.locals import K_ESCAPE, KEYDOWN, QUIT

WALL = 0.02
G = -9.81
DURATION = 10.0

pge.interactive()
pge.velocity_damping(1.0)  # the energy check reads velocities: reads must not damp them
pge.display_set_mode([800, 800])
pge.slow_down(2.0)
pge.elasticity(1.0)

wood = pge.rgb(0.55, 0.35, 0.2)
pge.box(0.0, 0.0, 1.0, WALL, wood).fix()
pge.box(0.0, 1.0 - WALL, 1.0, WALL, wood).fix()
pge.box(0.0, 0.0, WALL, 1.0, wood).fix()
pge.box(1.0 - WALL, 0.0, WALL, 1.0, wood).fix()

bounces = {"walls": 0, "balls": 0}
last_hit = [0.0]


def bounced(ball, event):
    """Count the collision once (both balls' callbacks see a ball-ball collision)."""
    first, second = event.collision_between()
    if first.type == pge.circle_t and second.type == pge.circle_t:
        if ball is first:
            bounces["balls"] += 1
    else:
        bounces["walls"] += 1
    last_hit[0] = pge.get_time()


radius = {}
balls = []
for x, y, r, colour, mass, vx, vy in [
    (0.3, 0.7, 0.06, pge.rgb(0.95, 0.8, 0.2), 1.0, 0.4, 0.0),
    (0.7, 0.5, 0.04, pge.rgb(0.85, 0.25, 0.2), 0.5, -0.3, 1.0),
    (0.5, 0.25, 0.05, pge.rgb(0.3, 0.55, 0.9), 0.8, 0.2, 2.0),
]:
    ball = pge.circle(x, y, r, colour).mass(mass).velocity(vx, vy).on_collision(bounced)
    radius[ball] = r
    balls.append(ball)


def energy():
    total = 0.0
    for ball in balls:
        vx, vy = ball.get_xvel(), ball.get_yvel()
        total += ball.get_mass() * (0.5 * (vx * vx + vy * vy) - G * ball.get_ypos())
    return total


def key_pressed(event):
    if event.key == K_ESCAPE:
        sys.exit(0)


pge.register_handler(lambda event: sys.exit(0), [QUIT])
pge.register_handler(key_pressed, [KEYDOWN])
pge.gravity(G)
pge.draw_collision(True, False)
pge.local_fps()

start = energy()
pge.run(DURATION)
drift = (energy() - start) / abs(start)

inside = all(
    WALL + radius[b] - 1e-9 <= b.get_xpos() <= 1.0 - WALL - radius[b] + 1e-9
    and WALL + radius[b] - 1e-9 <= b.get_ypos() <= 1.0 - WALL - radius[b] + 1e-9
    for b in balls
)
print(
    f"RESULT example=ball_in_a_box time={pge.get_time():.6f} wall_bounces={bounces['walls']} "
    f"ball_bounces={bounces['balls']} last_hit={last_hit[0]:.6f} inside={inside} "
    f"energy_drift={drift:.3e} frames={pge.get_frame_no()}"
)
