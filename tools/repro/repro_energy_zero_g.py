"""Kinetic energy rises at a collision in zero gravity (engine behaviour at a0d1512, against the
claim "energy never increases"): a spinning polygon (5) pressed between the ceiling and a ball
(7) at one instant; the ball-polygon contact closes at 1.8e-4 m/s and, its gap being pressed
shut by the spin (press_rate < 0), the pivot rule sends it off at v_min = sqrt(2 |g| h) instead,
adding energy (+1.9e-6 J, 2.3e-6 of the total), again at each of the following bounces of
the run. Presumably the pivot rule (engine._pivot): its docstring allows m |g''| h per event.
Friction 0..1, elasticities < 1, no gravity. The pivot rule went with the resting-contact rules
of that time, since removed; kept as a check: it prints every collision that gains energy, none
now."""
from pge import World, Collision
h = float.fromhex
world = World(gravity=(0.0, 0.0), elasticity=1.0, frame_rate=None)
bodies = {}
bodies[0] = world.add_box(h('-0x1.999999999999ap-4'), h('-0x1.999999999999ap-4'), h('0x1.3333333333333p+0'), h('0x1.999999999999ap-4'), fixed=True, name='floor')
bodies[1] = world.add_box(h('-0x1.999999999999ap-4'), h('0x1.0000000000000p+0'), h('0x1.3333333333333p+0'), h('0x1.999999999999ap-4'), fixed=True, name='ceiling')
bodies[2] = world.add_box(h('-0x1.999999999999ap-4'), h('-0x1.999999999999ap-4'), h('0x1.999999999999ap-4'), h('0x1.3333333333333p+0'), fixed=True, name='left')
bodies[3] = world.add_box(h('0x1.0000000000000p+0'), h('-0x1.999999999999ap-4'), h('0x1.999999999999ap-4'), h('0x1.3333333333333p+0'), fixed=True, name='right')
bodies[4] = world.add_polygon(((h('0x1.21bedf72c6d49p-3'), h('0x1.3f65ae9aed2f7p-1')), (h('0x1.b6fca9b998268p-3'), h('0x1.37b90eada5330p-1')), (h('0x1.86f36d74c24bfp-3'), h('0x1.5bdf2a78a1c82p-1'))), mass=h('0x1.0c6caeebf94c9p+0'), velocity=(h('0x1.71a98e5c9904cp-1'), h('0x1.69d31165243e1p-2')), angular_velocity=h('-0x1.1ae174c73942cp+4'), elasticity=h('0x1.eda22bd3b5118p-2'), friction=h('0x1.332a1858028d0p-5'))
bodies[5] = world.add_polygon(((h('0x1.296d2a736088ap-1'), h('0x1.e264fef303a29p-1')), (h('0x1.1229d34731dc5p-1'), h('0x1.df90f6a20dd28p-1')), (h('0x1.14fddb9827ac6p-1'), h('0x1.c84d9f75df263p-1')), (h('0x1.2c4132c45658bp-1'), h('0x1.cb21a7c6d4f64p-1'))), mass=h('0x1.2f8292d766e1cp-1'), velocity=(h('-0x1.3136d99f31627p-1'), h('-0x1.4797ab32fe46ep-1')), angular_velocity=h('0x1.b5f8da7de0210p+1'), elasticity=h('0x1.81ec82e8e6a5ap-5'), friction=h('0x1.c4c68c0becd78p-3'))
bodies[6] = world.add_circle((h('0x1.4a48e7b1e0704p-2'), h('0x1.95f8fe4d4278dp-1')), h('0x1.1c5bb0694dfbep-5'), mass=h('0x1.7557bfe9048f2p+0'), velocity=(h('0x1.78abf28e894d0p-2'), h('0x1.95059b7ab97bdp-1')), angular_velocity=h('-0x1.46a98be0d27ccp+2'), elasticity=h('0x1.0a6c43b4e5762p-1'), friction=h('0x1.012f0320f4e18p-4'))
bodies[7] = world.add_circle((h('0x1.54ee7b974a5b8p-1'), h('0x1.bbd24e1a51da4p-2')), h('0x1.393fa10a17d7ep-5'), mass=h('0x1.2e05d6415b1fcp+0'), velocity=(h('-0x1.60c693810090cp-2'), h('0x1.9dad097c115ebp-1')), angular_velocity=h('-0x1.004c59b84072ap+3'), elasticity=h('0x1.8262dcae213bcp-1'), friction=h('0x1.65e29931e8ba8p-1'))
bodies[8] = world.add_circle((h('0x1.0b7b6d5eec9ddp-1'), h('0x1.aaf39618abdd6p-1')), h('0x1.b1fcb69ba8801p-5'), mass=h('0x1.f8631bb3837e0p+0'), velocity=(h('-0x1.c7aeeb642678fp-5'), h('-0x1.b696cee13cfc6p-2')), angular_velocity=h('-0x1.e8e034ae173b5p+3'), elasticity=h('0x1.96bff8340f344p-2'), friction=h('0x1.83a7f9d5e43e0p-1'))
bodies[9] = world.add_polygon(((h('0x1.060dbab2de520p-3'), h('0x1.5b526edaa9395p-1')), (h('0x1.5622f0b041741p-4'), h('0x1.66910f1cfe257p-1')), (h('0x1.5a7df32d7835ep-5'), h('0x1.587d7333145d3p-1')), (h('0x1.74a70e6563e37p-5'), h('0x1.3f2b3706d5a8dp-1')), (h('0x1.704c0be82d21bp-4'), h('0x1.33ec96c480bcbp-1')), (h('0x1.0c980180d93d7p-3'), h('0x1.420032ae6a84fp-1'))), mass=h('0x1.d02ef88747ed0p+0'), velocity=(h('0x1.41df5c2bfbc9cp-4'), h('-0x1.b63dab0bf25b1p-1')), angular_velocity=h('-0x1.dcce6e13292d4p+2'), elasticity=h('0x1.523111087da80p-1'), friction=h('0x1.30513f9fc9851p-1'))
bodies[10] = world.add_polygon(((h('0x1.47f6c4410d32ap-1'), h('0x1.ca94d030f8118p-4')), (h('0x1.513f059284f40p-1'), h('0x1.14b6103d95d2ap-4')), (h('0x1.69bc53463c214p-1'), h('0x1.23223df804962p-4')), (h('0x1.6f96b67a597e9p-1'), h('0x1.e1eae23ddf358p-4')), (h('0x1.5ab776b493419p-1'), h('0x1.24b3f0dc75f1ap-3'))), mass=h('0x1.5dee6d1fab29bp+0'), velocity=(h('-0x1.c1516679f1fc2p-5'), h('-0x1.d83a8a030c62bp-2')), angular_velocity=h('0x1.cff7984704140p+2'), elasticity=h('0x1.b184f35c34f1dp-2'), friction=h('0x1.6ee9d698b0ce9p-1'))
bodies[0].friction = h('0x1.5829bf9c65390p-3')
bodies[1].friction = h('0x1.df9fd6fcc5540p-4')
bodies[2].friction = h('0x1.e2f460df71db0p-5')
bodies[3].friction = h('0x1.8955d5926548ep-1')
before = world.kinetic_energy()
for ev in world.events(10.0):
    if isinstance(ev, Collision):
        now = world.kinetic_energy()
        if now > before * (1 + 1e-12):
            print(f"kinetic energy {before!r} -> {now!r} (+{now - before:.3g} J, +{(now - before) / before:.3g} relative) at {ev}")
        before = now
