"""Matchsticks: knock the sides out of four matchboxes to free the balls trapped inside.

Each matchbox is four thin fixed boxes (the matchsticks) around a blue ball
bouncing inside it. Three thrown balls (gold, steel, copper) fly around the
room; whenever one hits a matchstick, the stick is knocked out with ``rm()``.
A freed blue ball that reaches the floor is collected (removed).

What it shows: ``on_collision_with(sticks, knock_out)`` with one list shared
by the three thrown balls and kept *by reference*: the balls are made first
and the sticks are appended to the list afterwards, yet every stick counts;
``event.collision_between()`` to find which stick was hit; fixed polygons
removed in the middle of a run; an ``at_time`` countdown; ``text``.

The boxes do not topple: sticks are removed rather than knocked over, since
rotation physics has not landed yet. Every elasticity is 1, so nothing comes
to rest (the trapped balls start a little above their box floors and keep
bouncing). The ``RESULT`` line gives sticks left and knocked out (16 in all)
and blue balls freed and collected.
"""

import sys

import pge  # first: it keeps pygame from printing its banner
from pygame.locals import QUIT

WALL = 0.01
STICK = 0.01
DURATION = 15.0

pge.interactive()
pge.display_set_mode([800, 800])
pge.slow_down(2.0)
pge.elasticity(1.0)

wood = pge.rgb(0.55, 0.35, 0.2)
match_colour = pge.rgb(0.9, 0.75, 0.45)
blue = pge.rgb(0.2, 0.35, 0.9)
white = pge.white()

state = {"knocked": 0, "collected": 0, "clock": None, "left": int(DURATION)}
sticks = []  # shared by reference: filled after the thrown balls are made
trapped = []


def knock_out(ball, event):
    for obj in event.collision_between():
        if obj in sticks:
            sticks.remove(obj)
            obj.rm()
            state["knocked"] += 1


thrown = [
    pge.circle(0.19, 0.8, 0.04, pge.rgb(0.95, 0.8, 0.2)).mass(1.25).velocity(0.8, -0.5),
    pge.circle(0.57, 0.75, 0.04, pge.rgb(0.75, 0.75, 0.8)).mass(1.0).velocity(-0.7, 0.9),
    pge.circle(0.81, 0.7, 0.04, pge.rgb(0.8, 0.45, 0.2)).mass(0.75).velocity(-1.1, -0.2),
]
for ball in thrown:
    ball.on_collision_with(sticks, knock_out)

# the room
floor = pge.box(0.0, 0.0, 1.0, WALL, wood).fix()
pge.box(0.0, 1.0 - WALL, 1.0, WALL, wood).fix()
pge.box(0.0, 0.0, WALL, 1.0, wood).fix()
pge.box(1.0 - WALL, 0.0, WALL, 1.0, wood).fix()


def matchbox(x, y, width, height):
    """Four sticks around a blue ball, which starts a little above the box floor."""
    sticks.append(pge.box(x, y, width, STICK, match_colour).fix())  # floor
    sticks.append(pge.box(x, y + height - STICK, width, STICK, match_colour).fix())  # lid
    sticks.append(pge.box(x, y + STICK, STICK, height - 2 * STICK, match_colour).fix())  # left side
    sticks.append(pge.box(x + width - STICK, y + STICK, STICK, height - 2 * STICK, match_colour).fix())
    ball = pge.circle(x + width / 2, y + STICK + 0.06, 0.035, blue).mass(1.5).velocity(0.15, 0.0)
    trapped.append(ball)


for k in range(4):
    matchbox(0.08 + 0.23 * k, 0.1, 0.17, 0.2)


def collect(floor_object, event):
    for obj in event.collision_between():
        if obj in trapped:
            trapped.remove(obj)
            obj.rm()
            state["collected"] += 1


floor.on_collision(collect)


def countdown(event, unused):
    state["left"] -= 1
    if state["clock"] is not None:
        state["clock"].rm()
    state["clock"] = pge.text(0.8, 0.95, f"{state['left']:2d}", white, 50, 1)
    if state["left"] > 0:
        pge.at_time(1.0 * 2.0, countdown)  # at_time counts wall seconds: slow_down 2 = 1 simulated second


pge.register_handler(lambda event: sys.exit(0), [QUIT])
pge.gravity()
pge.at_time(0.0, countdown)
pge.run(DURATION)
print(
    f"RESULT example=matchsticks sticks={len(sticks)} knocked={state['knocked']} collected={state['collected']} "
    f"trapped={len(trapped)} thrown={len(thrown)} countdown={state['left']} time={pge.get_time():.6f}"
)
