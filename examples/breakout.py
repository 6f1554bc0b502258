"""Breakout: knock out 27 bricks with a ball, keep it in play with the paddle.

What it shows: fixed boxes removed with ``rm()`` from their own collision
callback in the middle of a run, a paddle moved from keyboard handlers
(``register_handler`` with KEYDOWN/KEYUP; LEFT and RIGHT arrows), a floor
that loses a life and creates a new ball *inside a callback* (it joins the
simulation when the callback returns), a score ``text`` that is replaced
as the game goes, and ``at_time`` timers (a one-second clock).

There is no gravity and every elasticity is 1, so the ball keeps its speed.
The paddle is a very heavy moving box: the ball bounces off it almost as off
a wall, and the paddle's own callback cancels the little vertical speed it
picks up. In a window the game goes on until every brick is knocked out or
the last life is lost (the controls are written at the top of the window);
Escape or closing the window quits. Headless (``PGE_HEADLESS=1``) input
handlers never fire, so the paddle stands still and the ball alone decides a
20-second game: the final ``RESULT`` line gives the bricks left and knocked
out, the lives left and the balls used.
"""

import sys

import pge  # first: it keeps pygame from printing its banner
from pygame.locals import K_ESCAPE, K_LEFT, K_RIGHT, KEYDOWN, KEYUP, QUIT
from pge.classic.runloop import headless  # True without a window (PGE_HEADLESS=1 or pge.batch())

WALL = 0.01
PADDLE_SPEED = 0.6
DURATION = 20.0  # simulated seconds of a headless game (a window plays until the game ends)

pge.interactive()
pge.display_set_mode([800, 800])
pge.slow_down(1.0)
pge.elasticity(1.0)

wood = pge.rgb(0.55, 0.35, 0.2)
brick_colour = pge.rgb(0.15, 0.25, 0.7)
gold = pge.rgb(0.95, 0.8, 0.2)
white = pge.white()

ceiling = pge.box(0.0, 1.0 - WALL, 1.0, WALL, wood).fix()
left = pge.box(0.0, 0.0, WALL, 1.0, wood).fix()
right = pge.box(1.0 - WALL, 0.0, WALL, 1.0, wood).fix()
floor = pge.box(0.0, 0.0, 1.0, WALL, pge.rgb(0.6, 0.1, 0.1)).fix()

state = {"bricks": 0, "knocked": 0, "lives": 3, "balls": 0, "score_text": None, "seconds": 0}


def show_score():
    if state["score_text"] is not None:
        state["score_text"].rm()
    words = f"bricks {state['bricks']}  lives {state['lives']}"
    state["score_text"] = pge.text(0.05, 0.97, words, white, 30, 1)


def game_over(words, x):
    pge.text(x, 0.5, words, white, 80, 2)
    if not headless():
        pge.text(0.32, 0.4, "Escape or close the window to quit", white, 24, 2)


def brick_hit(brick, event):
    brick.rm()
    state["bricks"] -= 1
    state["knocked"] += 1
    show_score()
    if state["bricks"] == 0:
        game_over("Winner", 0.35)


for row in range(3):
    for column in range(9):
        pge.box(0.05 + column * 0.1, 0.7 + row * 0.08, 0.08, 0.05, brick_colour).fix().on_collision(brick_hit)
        state["bricks"] += 1


def paddle_hit(paddle_object, event):
    paddle_object.put_yvel(0.0)  # the paddle only slides sideways
    others = [o for o in event.collision_between() if o is not paddle_object]
    if others and others[0] in (left, right):
        paddle_object.put_xvel(0.0)


paddle = pge.box(0.42, 0.06, 0.16, 0.02, pge.rgb(0.8, 0.8, 0.85)).mass(1000.0).on_collision(paddle_hit)


def new_ball():
    state["balls"] += 1
    return pge.circle(0.5, 0.3, 0.02, gold).mass(1.0).velocity(0.31, 0.52)


def floor_hit(floor_object, event):
    for other in event.collision_between():
        if other.type == pge.circle_t:
            other.rm()
            state["lives"] -= 1
            show_score()
            if state["lives"] > 0:
                new_ball()  # created in a callback: joins the simulation when this returns
            else:
                game_over("Game over", 0.3)


floor.on_collision(floor_hit)
new_ball()
show_score()
if not headless():
    pge.text(0.52, 0.97, "left/right arrows: paddle   Esc: quit", white, 22, 1)


def tick(event, unused):
    state["seconds"] += 1
    pge.at_time(1.0, tick)


def result():
    print(
        f"RESULT example=breakout bricks={state['bricks']} knocked={state['knocked']} lives={state['lives']} "
        f"balls={state['balls']} seconds={state['seconds']} time={pge.get_time():.6f}"
    )


def quit_game(event=None):
    result()
    sys.exit(0)


def key_down(event):
    if event.key == K_LEFT:
        paddle.put_xvel(-PADDLE_SPEED)
    elif event.key == K_RIGHT:
        paddle.put_xvel(PADDLE_SPEED)
    elif event.key == K_ESCAPE:
        quit_game()


def key_up(event):
    if event.key in (K_LEFT, K_RIGHT):
        paddle.put_xvel(0.0)


pge.register_handler(key_down, [KEYDOWN])
pge.register_handler(key_up, [KEYUP])
pge.register_handler(quit_game, [QUIT])
pge.at_time(1.0, tick)
# a window plays on until the player quits (the game's end stays on screen); headless runs DURATION
pge.run(DURATION if headless() else -1)
result()
