"""Overlap after a turning polygon settles flat (engine bug at a0d1512): polygon 8 rocks on the
floor, touching circle 4; at the collision that settles it, it is turned about its contact corner
until its edge lies flat (_settle_turning) and that turn pushes it 2.4e-7 into circle 4.
Expected: no overlap (the settle turn must not move the body into a neighbour). e < 1, gravity, no friction."""
from pge import World
h = float.fromhex
world = World(gravity=(0.0, -9.81), elasticity=1.0, frame_rate=10.0)
bodies = {}
bodies[0] = world.add_box(h('-0x1.999999999999ap-4'), h('-0x1.999999999999ap-4'), h('0x1.3333333333333p+0'), h('0x1.999999999999ap-4'), fixed=True, name='floor')
bodies[1] = world.add_box(h('-0x1.999999999999ap-4'), h('0x1.0000000000000p+0'), h('0x1.3333333333333p+0'), h('0x1.999999999999ap-4'), fixed=True, name='ceiling')
bodies[2] = world.add_box(h('-0x1.999999999999ap-4'), h('-0x1.999999999999ap-4'), h('0x1.999999999999ap-4'), h('0x1.3333333333333p+0'), fixed=True, name='left')
bodies[3] = world.add_box(h('0x1.0000000000000p+0'), h('-0x1.999999999999ap-4'), h('0x1.999999999999ap-4'), h('0x1.3333333333333p+0'), fixed=True, name='right')
bodies[4] = world.add_circle((h('0x1.4c2a04286efc2p-1'), h('0x1.63e359e2df7f9p-2')), h('0x1.312828a8deda8p-5'), mass=h('0x1.3db595c8c862ep+0'), velocity=(h('0x1.e32c2e6f02212p-3'), h('0x1.6403815fb0eafp-1')), angular_velocity=h('-0x1.9e42250b971a0p-1'), elasticity=h('0x1.bddd506bd74a3p-2'), friction=h('0x0.0p+0'))
bodies[5] = world.add_polygon(((h('0x1.422b2ee645041p-1'), h('0x1.909d89132ae4bp-1')), (h('0x1.4b7d77dd43e26p-1'), h('0x1.785d1f298f47ep-1')), (h('0x1.5dbe7b3eb66fap-1'), h('0x1.7d1bc5cb2b6b9p-1')), (h('0x1.5994909cf53aep-1'), h('0x1.94544ed96fe0fp-1'))), mass=h('0x1.b423f4103a091p-1'), velocity=(h('0x1.e2aec899d751cp-1'), h('-0x1.0e7dccde78967p+0')), angular_velocity=h('-0x1.5021d69ff6c16p+3'), elasticity=h('0x1.656b51e6397d6p-1'), friction=h('0x0.0p+0'))
bodies[6] = world.add_polygon(((h('0x1.0e15686ff1e7bp-1'), h('0x1.376a21a36bb33p-2')), (h('0x1.184769546ed04p-1'), h('0x1.16f9516544006p-2')), (h('0x1.250155aeb8963p-1'), h('0x1.04edf4535caa0p-2')), (h('0x1.328d9ddb3f5acp-1'), h('0x1.1a49dbf3bc205p-2')), (h('0x1.2f8fd60493ecbp-1'), h('0x1.44a2213cb2470p-2')), (h('0x1.1e1f2be4c9359p-1'), h('0x1.4c279ff26736ap-2'))), mass=h('0x1.53e90f3583089p+0'), velocity=(h('-0x1.0b1c0873cdda5p-3'), h('0x1.0e189f4aa86c7p+0')), angular_velocity=h('-0x1.17e6d6739d7ecp+3'), elasticity=h('0x1.143960fe83fc2p-1'), friction=h('0x0.0p+0'))
bodies[7] = world.add_circle((h('0x1.13fc5217e8d81p-1'), h('0x1.2310bec9d5dcep-3')), h('0x1.01e0e6366b926p-4'), mass=h('0x1.3c8d0a37f55d4p-1'), velocity=(h('0x1.17be0a0cc3159p-3'), h('0x1.7698c68e67f10p-3')), angular_velocity=h('0x1.7baba8dda2dd0p+2'), elasticity=h('0x1.0859a5056d897p-1'), friction=h('0x0.0p+0'))
bodies[8] = world.add_polygon(((h('0x1.6f2798cef6e78p-1'), h('0x1.614e84b646968p-1')), (h('0x1.6f1025b7e78ccp-1'), h('0x1.3f4d7f5c16a90p-1')), (h('0x1.8c773119b2e34p-1'), h('0x1.2e38addae58b5p-1')), (h('0x1.a9f5af928d948p-1'), h('0x1.3f24e1b3e45b2p-1')), (h('0x1.aa0d22a99cef5p-1'), h('0x1.6125e70e14489p-1')), (h('0x1.8ca61747d198dp-1'), h('0x1.723ab88f45665p-1'))), mass=h('0x1.6610e94a35a1cp-1'), velocity=(h('-0x1.74cc6deb0275bp+0'), h('-0x1.fa8ed8d574e54p-3')), angular_velocity=h('0x1.e48a9dcf2fd38p+2'), elasticity=h('0x1.ae181bc87fce6p-1'), friction=h('0x0.0p+0'))
bodies[0].friction = h('0x0.0p+0')
bodies[1].friction = h('0x0.0p+0')
bodies[2].friction = h('0x0.0p+0')
bodies[3].friction = h('0x0.0p+0')
# -- check: the deepest overlap at every event, from the engine's own overlap_depth
moving = [b for b in world.bodies if not b.is_fixed]
worst = 0.0
for ev in world.events(10.0):
    for i, a in enumerate(moving):
        for b in moving[:i]:
            d = world.overlap_depth(a, b)
            if d > max(worst, 1e-12):
                worst = d
                print(f"overlap {d:.3g} of {a.label()} and {b.label()} at {ev}")
                print(f"   {a.label()}: angle {a.angle!r} spin {a.angular_velocity!r} resting on {a.resting_on}")
                print(f"   {b.label()}: angle {b.angle!r} spin {b.angular_velocity!r} resting on {b.resting_on}")
