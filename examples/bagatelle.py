"""Bagatelle: balls drop through a field of pins into scoring cups.

What it shows: many fixed circles (pins) and thin fixed boxes (cup walls),
balls created by an ``at_time`` timer that re-arms itself (and by mouse
clicks in a window, at the clicked x via ``pyg_to_unit_coord``), cup floors
whose ``on_collision`` callback scores the ball and removes it with ``rm()``,
eye-candy (a background board at level -1, the score as text at level 1),
moving balls colliding with each other under gravity.

Every elasticity is 1, so nothing ever comes to rest: balls bounce through
the pins until a cup floor takes them. (Below 1, a ball could come to rest on
a pin or a cup edge, which the engine cannot yet do without infinitely many
bounces.) The ``RESULT`` line gives balls launched, scored and still in play,
and the score; launched = scored + in play.
"""

import sys

import pge  # first: it keeps pygame from printing its banner
from pygame.locals import MOUSEBUTTONDOWN, QUIT

WALL = 0.01
BALL = 0.018
DURATION = 12.0
CUPS = [(0.01, 10), (0.2, 30), (0.4, 50), (0.6, 30), (0.8, 10)]  # left edge of each cup, points

pge.interactive()
pge.display_set_mode([700, 700])
pge.slow_down(1.5)
pge.elasticity(1.0)

wood = pge.rgb(0.5, 0.3, 0.15)
steel = pge.rgb(0.75, 0.75, 0.8)
brass = pge.rgb(0.85, 0.65, 0.2)
felt = pge.rgb(0.05, 0.25, 0.12)
white = pge.white()

pge.box(0.0, 0.0, 1.0, 1.0, felt, -1)  # the board, drawn behind everything
pge.box(0.0, 1.0 - WALL, 1.0, WALL, wood).fix()
pge.box(0.0, 0.0, WALL, 1.0, wood).fix()
pge.box(1.0 - WALL, 0.0, WALL, 1.0, wood).fix()

for row in range(6):
    count = 9 if row % 2 == 0 else 8
    offset = 0.1 if row % 2 == 0 else 0.15
    for k in range(count):
        pge.circle(offset + 0.1 * k, 0.78 - 0.09 * row, 0.012, steel).fix()

state = {"launched": 0, "scored": 0, "score": 0, "in_play": set(), "text": None}


def show_score():
    if state["text"] is not None:
        state["text"].rm()
    state["text"] = pge.text(0.03, 0.975, f"score {state['score']}", white, 30, 1)


def make_cup_floor(points):
    def scored(floor, event):
        for obj in event.collision_between():
            if obj in state["in_play"]:
                obj.rm()
                state["in_play"].discard(obj)
                state["scored"] += 1
                state["score"] += points
                show_score()

    return scored


for left, points in CUPS:
    width = 0.2 if left > 0.01 else 0.19
    pge.box(left, 0.0, width, WALL, wood).fix().on_collision(make_cup_floor(points))
    if left > 0.01:
        pge.box(left - 0.004, WALL, 0.008, 0.12, brass).fix()
    pge.text(left + 0.07, 0.08, str(points), brass, 28, 1)


def free(x, y):
    """True if no ball in play is near (x, y): a new ball must not overlap another."""
    return all((b.get_xpos() - x) ** 2 + (b.get_ypos() - y) ** 2 > (3 * BALL) ** 2 for b in state["in_play"])


def launch(x):
    if not free(x, 0.93):
        return False
    ball = pge.circle(x, 0.93, BALL, pge.rgb(0.9, 0.9, 0.95)).mass(1.0).velocity(0.05, 0.0)
    state["in_play"].add(ball)
    state["launched"] += 1
    return True


drops = [0.23, 0.52, 0.77, 0.38, 0.61, 0.14, 0.86, 0.47]


def timed_drop(event, unused):
    if not launch(drops[state["launched"] % len(drops)] + 0.003 * state["launched"]):
        pge.at_time(0.1, timed_drop)  # the drop point is taken: try again shortly
    elif state["launched"] < 20:
        pge.at_time(0.5, timed_drop)


def mouse(event):
    x, unused = pge.pyg_to_unit_coord(event.pos)
    launch(min(max(x, 0.05), 0.95))


pge.register_handler(mouse, [MOUSEBUTTONDOWN])
pge.register_handler(lambda event: sys.exit(0), [QUIT])
pge.gravity()
show_score()
pge.at_time(0.0, timed_drop)
pge.run(DURATION)
in_play = len(state["in_play"])
print(
    f"RESULT example=bagatelle launched={state['launched']} scored={state['scored']} in_play={in_play} "
    f"score={state['score']} time={pge.get_time():.6f}"
)
