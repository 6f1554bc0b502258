"""Livelock: two spinning circles with friction and e=0 graze for ever at one instant.

Expected: the events up to 0.05 s. Observed: after the first (sticking, e = 0) collision the
kernel (translational c1 = -4.5e-17 < 0, overlapping by rounding) predicts a contact now, but
collide() computes the normal speed with the spin terms omega x r and gets exactly 0.0, not
< 0: a graze, nothing changes, the pair is predicted again at the same instant, for ever.
At d2126de run_until never returned; at a0d1512 the storm watchdog raises RuntimeError
("event storm: 1000000 collisions at time 0.04165650529550962 ...").
Without friction, or without the initial spins, it does not happen.
"""
from pge import World
w = World(gravity=(0.0, -9.81), elasticity=0.0, bounds=(0, 0, 1, 1))
a = w.add_circle((0.2979906630636345, 0.9082176500196211), 0.03989288880633947, mass=1.760694019126658,
                 velocity=(0.5846948518416122, -1.2866932182626927), angular_velocity=-19.711546627023733, friction=1.0)
b = w.add_circle((0.3340481455015375, 0.733809171856975), 0.05819627758333601, mass=0.9323053557169774,
                 velocity=(0.21483027485665504, 0.5981897800255815), angular_velocity=-1.945104252898517, friction=1.0)
for ev in w.events(0.05):
    print(ev, w.stats["grazes"], flush=True)
print("returned", w.stats)
