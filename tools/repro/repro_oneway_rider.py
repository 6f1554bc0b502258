"""A rider did not load its support (one-way coupling): found 2026-11-22 while tracing energy
seeds 120, 173 and 338 of ``survey.py energy --gravity``, which gain energy between events, not
at a collision.

A box (0.4 x 0.1, m 1, friction 0) slides at 2 m/s on a frictionless floor; a box (0.1 x 0.1, m 1,
friction 0.5) is dropped onto it with no horizontal speed. Friction between them should speed the
top box up and slow the bottom one down, keeping the horizontal momentum (2 kg m/s: the floor
pushes only vertically) and losing energy. The engine speeds the top box up but does not slow the
bottom one while the top one rides it, so the momentum and the energy rise until the top box slides
off its back (2.0 -> 2.41 kg m/s, +0.18 J in 0.08 s). Fixed the same day by solving each pile
of resting bodies together (the resting-contact rules of that time, since removed). Islands
solve the two boxes' contacts together too; kept as a check: the momentum stays 2.0 and the
energy never rises.
"""
from pge import World

G = 9.81
world = World(gravity=(0.0, -G), elasticity=0.0, bounds=(-1.0, -1.0, 5.0, 3.0))
floor = world.add_box(-1.0, -0.2, 6.0, 0.2, fixed=True, friction=0.0, name="floor")
low = world.add_box(0.0, 1e-4, 0.4, 0.1, mass=1.0, elasticity=0.0, friction=0.0, name="low")
world.run_until(0.05)
low.velocity = (2.0, 0.0)
top = world.add_box(0.1, 0.1 + 1e-3, 0.1, 0.1, mass=1.0, elasticity=0.0, friction=0.5, name="top")


def energy():
    return world.kinetic_energy() + G * (low.mass * low.position[1] + top.mass * top.position[1])


print(" t      momentum  energy   low v   top v   top rests on low")
for k in range(0, 21):
    world.run_until(0.05 + 0.01 * k)
    momentum = low.mass * low.velocity[0] + top.mass * top.velocity[0]
    print(f"{world.time:.2f}  {momentum:8.4f}  {energy():7.4f}  {low.velocity[0]:6.4f}  {top.velocity[0]:6.4f}  "
          f"{top.resting_on is low}")
