"""Springs: a chain of balls hanging from the ceiling, and a bungee rope that snaps.

What it shows: ``pge.spring(ob1, ob2, k, d, l)`` between fixed boxes and balls
with a mass, ``draw`` to see a spring, ``when(l, p)`` calling ``p(event,
spring)`` once when a spring's length reaches ``l``, and ``rm()`` on a spring.

The chain: four balls of mass m hang one below the other on damped springs of
stiffness k and rest length l0, released with every spring at its rest
length. They bounce, the dampers take the energy out, and the chain settles
where each spring carries the weight of the balls below it: spring j (from
the top, j = 1..4) is l0 + (5 - j) m g / k long. The summary prints the
lengths reached and their largest difference from these analytic values.

The bungee: a ball hangs on a slack rope (tension-only, as PGE's springs are:
it pulls when stretched and never pushes). Dropped, it stretches the rope
until the rope reaches 0.45 and snaps (``when`` calls ``rm()``); the ball
falls on to the floor.

Run it in a window with ``python examples/springs_chain.py`` (ESC quits), or
headless with ``PGE_HEADLESS=1 python examples/springs_chain.py``. At the end
it prints one ``RESULT`` line.
"""

import sys

import pge  # first: it keeps pygame from printing its banner
from pygame.locals import K_ESCAPE, KEYDOWN, QUIT

G = -9.81
N = 4
MASS = 0.05
STIFFNESS = 40.0
DAMPING = 1.5
REST = 0.1
SNAP = 0.45
DURATION = 20.0

pge.interactive()
pge.display_set_mode([800, 800])

steel = pge.rgb(0.6, 0.6, 0.65)
wood = pge.rgb(0.55, 0.35, 0.2)
pge.box(0.0, 0.0, 1.0, 0.02, wood).fix()  # the floor
pge.box(0.05, 0.97, 0.9, 0.03, wood).fix()  # the ceiling

# The chain: an anchor under the ceiling, then N balls each REST below the one above.
anchor = pge.box(0.33, 0.93, 0.04, 0.04, steel).fix()
above, y = anchor, 0.95
chain = []
for j in range(N):
    y -= REST
    ball = pge.circle(0.35, y, 0.02, pge.rgb(0.95, 0.75 - 0.15 * j, 0.2)).mass(MASS)
    chain.append(pge.spring(above, ball, STIFFNESS, DAMPING, REST).draw(steel, 0.006))
    above = ball

# The bungee: a ball on a rope that snaps when stretched to SNAP.
hook = pge.box(0.68, 0.93, 0.04, 0.04, steel).fix()
jumper = pge.circle(0.7, 0.85, 0.03, pge.rgb(0.3, 0.55, 0.9)).mass(0.1)
snapped = []


def snap(event, rope):
    """The rope reached SNAP: note when and how long it was, then take it away."""
    snapped.append((event.get_time(), rope.spring.length))
    rope.rm()


rope = pge.spring(hook, jumper, 5.0, 0.0).draw(pge.rgb(0.9, 0.3, 0.3), 0.004).when(SNAP, snap)


def key_pressed(event):
    if event.key == K_ESCAPE:
        sys.exit(0)


pge.register_handler(lambda event: sys.exit(0), [QUIT])
pge.register_handler(key_pressed, [KEYDOWN])
pge.gravity(G)
pge.run(DURATION)

lengths = [spring.spring.length for spring in chain]
expected = [REST + (N - j) * MASS * -G / STIFFNESS for j in range(N)]
worst = max(abs(a - b) for a, b in zip(lengths, expected))
snap_time, snap_length = snapped[0] if snapped else (float("nan"), float("nan"))
print(
    f"RESULT example=springs_chain time={pge.get_time():.6f} springs={sum(not s.deleted for s in [*chain, rope])} "
    f"lengths={','.join(f'{x:.9f}' for x in lengths)} expected={','.join(f'{x:.9f}' for x in expected)} "
    f"max_error={worst:.3e} snaps={len(snapped)} snap_time={snap_time:.6f} snap_length={snap_length:.12f} "
    f"rope_deleted={rope.deleted} jumper_y={jumper.get_ypos():.6f}"
)
