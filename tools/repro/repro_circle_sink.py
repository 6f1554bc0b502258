"""circle_circle misses the re-contact of two touching circles that separate at a rounding-level
speed while their relative acceleration presses them together (engine bug at a0d1512; the
working tree's roots.py change seems to address it).

Found in a scene: a ball falling onto a ball that slides on the floor with friction (the
lower ball's friction deceleration makes the relative acceleration non-zero, so
first_descent's quartic path is taken). A collision leaves them overlapping by rounding
(c0 = -8.7e-19) and separating at ~2e-17 m/s (c1 = +3.5e-18) while pressed (c2 = -0.85):
the gap never gets above rounding, so the "immediate" rule (c0 <= 0 and c1 < 0, or c1 == 0
and c2 < 0) does not fire, no passage from p > 0 exists, and the kernel answers inf: the
upper ball sinks into the lower one unseen (8e-6 m after 1.3 ms, 5% of the radii by 0.03 s).
Expected: a contact now (0.0 or a few 1e-18 s). Observed: inf, on both the quartic and the
quadratic path. (The uncommitted roots.py change in /work/main returns 2.05e-18.)
"""
from pge.numerics.roots import first_descent
from pge.toi.circle_circle import circle_circle

# (dx, dy, dvx, dvy, dax, day) of the upper ball relative to the lower, radii, horizon
print("circle_circle:", circle_circle(0.043678747246580746, 0.07168379389555551, 0.2298046360480966,
                                      -0.14002577247323444, -4.905, -9.81,
                                      0.05098295756448332, 0.03295987577041888, 0.1))
h = float.fromhex
c = (h('-0x1.0000000000000p-60'), h('0x1.0000000000000p-58'), h('-0x1.b0a9b92712536p-1'),
     h('0x1.f8c0974a9b5c8p-3'), h('0x1.e12e353f7cedap+4'))
print("first_descent quartic:", first_descent(*c, 0.1, True))
print("same without c3, c4 (quadratic path):", first_descent(c[0], c[1], c[2], 0.0, 0.0, 0.1, True))
