"""Energy gain (engine bug?): a spinning pentagon strikes a ball that rests (sliding) on the
floor; gravity 9.81, friction, low elasticity. The collision raises kinetic + potential
energy by ~2.6e-3 J (the pentagon loses 6.8e-3 J of translation but gains 8.2e-3 J of spin).
Expected: no gain (at most the pivot rule's documented m |g''| h, ~1e-4 J here; the pivot rule
went with the resting-contact rules of that time, since removed). Kept as a check: it prints
every collision up to 0.05 s; none gains now.
"""
from pge import World, Collision
h = float.fromhex
G = 9.81
world = World(gravity=(0.0, -G), bounds=(0.0, 0.0, 1.0, 1.0))
world.add_box(-0.1, -0.1, 1.2, 0.1, fixed=True, friction=0.9817486495318765, name="floor")
r = h('0x1.874be953a3df8p-5')
ball = world.add_circle((h('0x1.d8c7475b0ea9ap-1'), r), r, mass=h('0x1.823a3cc30eee0p-1'),
                        velocity=(h('0x1.ea6ca9940221bp-2'), 0.0), angular_velocity=h('-0x1.40da89c1623bbp+3'),
                        friction=h('0x1.294d60c925764p-2'), elasticity=h('0x1.60dbb0d2db940p-2'))
pent = world.add_polygon([(h(x), h(y)) for x, y in [('0x1.c4a1e17cf54a2p-1', '0x1.171a6296bfc6bp-3'), ('0x1.b43c6227b8f4bp-1', '0x1.e6fd2d4b5d0b7p-4'),
                          ('0x1.b385efa980b01p-1', '0x1.4c554f58284fep-4'), ('0x1.c3acb66cba2ddp-1', '0x1.390c8846d7dd6p-4'),
                          ('0x1.d2a518da24dc0p-1', '0x1.942231b62b2c9p-4')]],
                         mass=h('0x1.8859b95bedc12p-1'), velocity=(h('0x1.6174cbd241854p-5'), h('-0x1.0f45a788d33a6p-1')),
                         angular_velocity=h('0x1.6d41dae6fb297p+5'), friction=h('0x1.65037105497cdp-1'), elasticity=h('0x1.4d2c7d5b5f10dp-5'))

def energy():
    return world.kinetic_energy() + sum(b.mass * G * b.position[1] for b in (ball, pent))

before = energy()
for ev in world.events(0.05):
    if isinstance(ev, Collision):
        now = energy()
        print(f"t={ev.time:.12f} {ev.a.label()} / {ev.b.label()} approach {ev.approach_speed:.3g}: "
              f"energy {before:.9f} -> {now:.9f} ({now - before:+.3g} J); ball resting on {ball.resting_on}")
        before = now
