"""Snooker: pot ten reds with the cue ball on a table in a wide window.

What it shows: a window that is not square (1000 x 560 pixels: the table is
1.7 units long), the cue ball struck with ``apply_impulse`` along
``normalise(sub_coord(target, cue))``, aiming with the mouse
(``pyg_to_unit_coord``), pockets that are fixed circles whose
``on_collision`` callback pots the ball with ``rm()``, the cue ball put back
on its spot by a timer once the spot is free, and cloth friction done by the
game itself: a timer every 0.05 s slows every ball by 1.5 % with
``put_xvel``/``put_yvel`` (reading and writing velocities changes nothing
else) and stops balls slower than 0.01.

There is no gravity, so the default elasticity 0.98 is safe: balls roll to a
stop on the cloth, they never come to rest *on* a surface. In a window you
play: click where the cue ball should go (the controls are written under the
score); the frame ends when every red is potted, and Escape or closing the
window quits. Headless (no mouse), or with ``--demo``, the game plays itself
for 20 seconds: a break at the start, then every 3 seconds the cue ball is
struck at the nearest red. The ``RESULT`` line gives reds potted and left (10
in all), shots, cue-ball fouls, ball-ball collisions, and whether every ball
left is on the cloth.
"""

import math
import sys

import pge  # first: it keeps pygame from printing its banner
from pygame.locals import K_ESCAPE, KEYDOWN, MOUSEBUTTONDOWN, QUIT
from pge.classic.runloop import headless  # True without a window (PGE_HEADLESS=1 or pge.batch())

X0, Y0, X1, Y1 = 0.08, 0.08, 1.70, 0.89  # the cloth inside the cushions
R = 0.026
SPOT = (0.45, 0.485)
DURATION = 20.0  # simulated seconds of a demo (headless, or --demo); a player's game runs until quit
SHOT = 0.9  # impulse of a shot (the cue ball's mass is 1)

pge.interactive()
pge.display_set_mode([1000, 560])
DEMO = headless() or "--demo" in sys.argv[1:]  # only a demo shoots by itself
pge.slow_down(1.0)

cushion = pge.rgb(0.25, 0.15, 0.08)
cloth = pge.rgb(0.05, 0.45, 0.2)
red = pge.rgb(0.8, 0.1, 0.1)
white = pge.white()
black = pge.rgb(0.02, 0.02, 0.02)

pge.box(X0, Y0, X1 - X0, Y1 - Y0, cloth, -1)
pge.box(X0 - 0.05, Y0 - 0.05, X1 - X0 + 0.1, 0.05, cushion).fix()
pge.box(X0 - 0.05, Y1, X1 - X0 + 0.1, 0.05, cushion).fix()
pge.box(X0 - 0.05, Y0, 0.05, Y1 - Y0, cushion).fix()
pge.box(X1, Y0, 0.05, Y1 - Y0, cushion).fix()

state = {"potted": 0, "fouls": 0, "shots": 0, "kisses": 0, "cue": None, "text": None}
reds = []


def show():
    if state["text"] is not None:
        state["text"].rm()
    words = f"potted {state['potted']}   shots {state['shots']}   fouls {state['fouls']}"
    state["text"] = pge.text(0.1, 0.99, words, white, 28, 1)


def potted(pocket, event):
    for ball in event.collision_between():
        if ball is state["cue"]:
            ball.rm()
            state["cue"] = None
            state["fouls"] += 1
            pge.at_time(1.0, respot)
        elif ball in reds:
            ball.rm()
            reds.remove(ball)
            state["potted"] += 1
            if not reds:
                pge.text(0.55, 0.55, "All reds potted!", white, 60, 2)
    show()


for x, y in [(X0, Y0), (X0, Y1), ((X0 + X1) / 2, Y0 - 0.012), ((X0 + X1) / 2, Y1 + 0.012), (X1, Y0), (X1, Y1)]:
    pge.circle(x, y, 0.045, black).fix().on_collision(potted)


def kiss(ball, event):
    first, second = event.collision_between()
    if first.type == pge.circle_t and second.type == pge.circle_t and ball is first:
        state["kisses"] += 1


for row in range(4):
    for k in range(row + 1):
        x = 1.25 + row * (2 * R + 0.002) * math.sqrt(3) / 2
        y = SPOT[1] + (k - row / 2) * (2 * R + 0.002)
        reds.append(pge.circle(x, y, R, red).mass(1.0).on_collision(kiss))


def place_cue():
    state["cue"] = pge.circle(SPOT[0], SPOT[1], R, white).mass(1.0).on_collision(kiss)


def respot(event, unused):
    free = all(math.hypot(b.get_xpos() - SPOT[0], b.get_ypos() - SPOT[1]) > 3 * R for b in reds)
    if free:
        place_cue()
    else:
        pge.at_time(0.5, respot)


def strike(x, y):
    cue = state["cue"]
    if cue is None:
        return
    aim = pge.sub_coord([x, y], cue.get_unit_coord())
    if pge.magnitude(aim) > 0:
        cue.apply_impulse(pge.normalise(aim), SHOT)
        state["shots"] += 1
        show()


def cloth_friction(event, unused):
    for ball in reds + ([state["cue"]] if state["cue"] is not None else []):
        vx, vy = ball.get_xvel(), ball.get_yvel()
        if math.hypot(vx, vy) < 0.01:
            ball.put_xvel(0.0)
            ball.put_yvel(0.0)
        else:
            ball.put_xvel(vx * 0.985)
            ball.put_yvel(vy * 0.985)
    pge.at_time(0.05, cloth_friction)


def next_shot(event, unused):
    cue = state["cue"]
    if cue is not None and reds:
        target = min(reds, key=lambda b: pge.magnitude(pge.sub_coord(b.get_unit_coord(), cue.get_unit_coord())))
        strike(target.get_xpos(), target.get_ypos())
    pge.at_time(3.0, next_shot)


def mouse(event):
    x, y = pge.pyg_to_unit_coord(event.pos)
    strike(x, y)


def result():
    on_table = reds + ([state["cue"]] if state["cue"] is not None else [])
    inside = all(
        X0 + R - 1e-9 <= b.get_xpos() <= X1 - R + 1e-9 and Y0 + R - 1e-9 <= b.get_ypos() <= Y1 - R + 1e-9
        for b in on_table
    )
    print(
        f"RESULT example=snooker potted={state['potted']} reds={len(reds)} shots={state['shots']} "
        f"fouls={state['fouls']} kisses={state['kisses']} inside={inside} time={pge.get_time():.6f}"
    )


def quit_game(event=None):
    result()
    sys.exit(0)


def key(event):
    if event.key == K_ESCAPE:
        quit_game()


place_cue()
show()
if not DEMO:
    pge.text(1.02, 0.99, "click: shoot the cue ball at the mouse   Esc: quit", white, 20, 1)
pge.register_handler(mouse, [MOUSEBUTTONDOWN])
pge.register_handler(key, [KEYDOWN])
pge.register_handler(quit_game, [QUIT])
if DEMO:
    pge.at_time(0.0, lambda event, unused: strike(1.25, SPOT[1] + 0.004))  # the break
    pge.at_time(3.0, next_shot)
pge.at_time(0.05, cloth_friction)
pge.run(DURATION if DEMO else -1)
result()
