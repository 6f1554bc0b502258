"""A Zeno run of collisions between circles 5 and 12 (gravity, elasticities < 1, no friction,
spinning polygons beside them) accumulates at t = 0.58720628807959...: the pending 5-12
collision times converge geometrically until time stops moving. At db1be72 run_until never
returned; at a0d1512 the new storm watchdog raises RuntimeError("event storm: 1000000
collisions ..."). Expected: run_until(1.0) returns (the pair comes to rest or separates)."""
from pge import World
h = float.fromhex
world = World(gravity=(0.0, -9.81), elasticity=1.0, frame_rate=None)
bodies = {}
bodies[0] = world.add_box(h('-0x1.999999999999ap-4'), h('-0x1.999999999999ap-4'), h('0x1.3333333333333p+0'), h('0x1.999999999999ap-4'), fixed=True, name='floor')
bodies[1] = world.add_box(h('-0x1.999999999999ap-4'), h('0x1.0000000000000p+0'), h('0x1.3333333333333p+0'), h('0x1.999999999999ap-4'), fixed=True, name='ceiling')
bodies[2] = world.add_box(h('-0x1.999999999999ap-4'), h('-0x1.999999999999ap-4'), h('0x1.999999999999ap-4'), h('0x1.3333333333333p+0'), fixed=True, name='left')
bodies[3] = world.add_box(h('0x1.0000000000000p+0'), h('-0x1.999999999999ap-4'), h('0x1.999999999999ap-4'), h('0x1.3333333333333p+0'), fixed=True, name='right')
bodies[4] = world.add_circle((h('0x1.ad525c0e369dfp-2'), h('0x1.19a24194c87dfp-3')), h('0x1.0bad31d0a9ebap-5'), mass=h('0x1.26264e014445ep-1'), velocity=(h('0x1.4d643e1c7526dp-7'), h('-0x1.88a1e590a7498p-1')), angular_velocity=h('-0x1.2352bde35501ep+4'), elasticity=h('0x1.65f55f4d938e6p-1'), friction=h('0x0.0p+0'))
bodies[5] = world.add_circle((h('0x1.3a97a91595416p-1'), h('0x1.01ec0e5997863p-1')), h('0x1.e6318ae323b1ap-5'), mass=h('0x1.5c2b4101d12a0p+0'), velocity=(h('0x1.1d762b228b5bep-1'), h('-0x1.6c3a68b41064fp-1')), angular_velocity=h('-0x1.ff980e6c805c0p+1'), elasticity=h('0x1.e3f5b230ad714p-3'), friction=h('0x0.0p+0'))
bodies[6] = world.add_polygon(((h('0x1.93a27f42c114dp-2'), h('0x1.660412613f83bp-1')), (h('0x1.b6979ca794c59p-2'), h('0x1.7162795c5e1bcp-1')), (h('0x1.ba9c67cfeaec0p-2'), h('0x1.86236e17f467ap-1')), (h('0x1.9caa2ce14893ap-2'), h('0x1.94a62cefe399cp-1')), (h('0x1.734dbfc038aa6p-2'), h('0x1.91fd6e7012f8cp-1')), (h('0x1.5dac6d784b725p-2'), h('0x1.8029cfd60f148p-1')), (h('0x1.6c0fed52d2a1cp-2'), h('0x1.6c97d0c59cef7p-1'))), mass=h('0x1.eb4f237d847c7p+0'), velocity=(h('-0x1.1a1070f210febp-4'), h('0x1.300e744e0665cp-1')), angular_velocity=h('0x1.33ef2490be4e0p+2'), elasticity=h('0x1.41a2cab919fe8p-1'), friction=h('0x0.0p+0'))
bodies[7] = world.add_polygon(((h('0x1.ef2db3e67333bp-3'), h('0x1.308482d05f080p-1')), (h('0x1.ff4189533740bp-3'), h('0x1.22f174e615eb4p-1')), (h('0x1.194bb26254b88p-2'), h('0x1.1d5dc6081eda7p-1')), (h('0x1.26be9212dfd83p-2'), h('0x1.24b8b1eb66849p-1')), (h('0x1.2b2a374eddc39p-2'), h('0x1.2ead6b67e9414p-1')), (h('0x1.27f5bfa72a757p-2'), h('0x1.3979f9d20c628p-1')), (h('0x1.19118484459cbp-2'), h('0x1.3c3b9bd2d96a4p-1'))), mass=h('0x1.aaa7dc5f50448p-1'), velocity=(h('-0x1.383850b202db8p-2'), h('0x1.54598ffe521d8p-1')), angular_velocity=h('-0x1.395f5c42ca680p+3'), elasticity=h('0x1.a94617bb27a39p-2'), friction=h('0x0.0p+0'))
bodies[8] = world.add_polygon(((h('0x1.64ab8cae308a2p-1'), h('0x1.56f69f1de1172p-2')), (h('0x1.65318ba2c3335p-1'), h('0x1.2e81bc9809476p-2')), (h('0x1.787abf2162842p-1'), h('0x1.247dfd16228cep-2')), (h('0x1.8cd85b9acacecp-1'), h('0x1.3899b991b88d4p-2')), (h('0x1.85b455996518ep-1'), h('0x1.602052e4d10afp-2')), (h('0x1.711aa9e7cc2d5p-1'), h('0x1.73c5fca025760p-2'))), mass=h('0x1.032711de6593dp+0'), velocity=(h('-0x1.8e9f6140a6575p-2'), h('0x1.723333ee1febep-5')), angular_velocity=h('-0x1.fac169ef8d030p+3'), elasticity=h('0x1.5bb4ce68c2517p-1'), friction=h('0x0.0p+0'))
bodies[9] = world.add_circle((h('0x1.1b5f1c28c5802p-2'), h('0x1.c475eedf3d8c3p-1')), h('0x1.4bde3729414acp-5'), mass=h('0x1.f6654088d59e8p+0'), velocity=(h('0x1.f7fc5db4beed4p-1'), h('-0x1.f6bfc39e28470p-3')), angular_velocity=h('0x1.1bc20bd57dd44p+3'), elasticity=h('0x1.bb65c76a76774p-2'), friction=h('0x0.0p+0'))
bodies[10] = world.add_polygon(((h('0x1.a0e0209346890p-1'), h('0x1.28490c4c5b133p-1')), (h('0x1.ae3f1e0beba86p-1'), h('0x1.0d738becae497p-1')), (h('0x1.bfe625fc2a486p-1'), h('0x1.06e14d6374181p-1')), (h('0x1.c8306eeb46308p-1'), h('0x1.17d9d5955345bp-1')), (h('0x1.ca7c4195bbebap-1'), h('0x1.2d07ca0d9fe51p-1')), (h('0x1.b53c7295f3b8cp-1'), h('0x1.3b010eae1635ep-1'))), mass=h('0x1.147dc8d88b440p-1'), velocity=(h('-0x1.25f32d7952458p-5'), h('-0x1.20da04501375ap-1')), angular_velocity=h('0x1.d428fe3880700p-2'), elasticity=h('0x1.4e5893ef5b677p-2'), friction=h('0x0.0p+0'))
bodies[11] = world.add_circle((h('0x1.4eda4bdf5e684p-3'), h('0x1.03a7bdc13ef78p-2')), h('0x1.e2c467f342e45p-5'), mass=h('0x1.636c8c7e09204p+0'), velocity=(h('0x1.a1e14af727afcp-1'), h('-0x1.0a5bdd08996fcp+0')), angular_velocity=h('-0x1.bc397d1633cc0p+3'), elasticity=h('0x1.858654c7fb6e7p-2'), friction=h('0x0.0p+0'))
bodies[12] = world.add_circle((h('0x1.772c2f2652fc6p-1'), h('0x1.a347a439628b4p-1')), h('0x1.b4b06ec171cf8p-5'), mass=h('0x1.08ed787c72092p+0'), velocity=(h('-0x1.7b4724493cd99p-2'), h('-0x1.251a5ac2070bap-2')), angular_velocity=h('-0x1.6dccb458a1624p+3'), elasticity=h('0x1.c07d2a8368484p-4'), friction=h('0x0.0p+0'))
bodies[0].friction = h('0x0.0p+0')
bodies[1].friction = h('0x0.0p+0')
bodies[2].friction = h('0x0.0p+0')
bodies[3].friction = h('0x0.0p+0')
import time
start = time.time()
world.run_until(0.5872)
print("reached", world.time, "in", round(time.time() - start, 2), "s; now running to 1.0", flush=True)
world.run_until(1.0)
print("returned", world.stats)
