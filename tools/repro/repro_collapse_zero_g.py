"""Zero gravity, friction, elasticities < 1: circle 6 between the left wall and circle 8 (and
the floor nearby) collide ever faster around t = 0.644567239 (inelastic collapse; without
gravity there is no resting contact to end it). At a0d1512 run_until(1.0) ends after ~20 s
of computing with RuntimeError("event storm: 1000000 collisions at time 0.6445672390096088
...", last between circle 6 and circle 8). Expected: it returns."""
from pge import World
h = float.fromhex
world = World(gravity=(0.0, 0.0), elasticity=1.0, frame_rate=None)
bodies = {}
bodies[0] = world.add_box(h('-0x1.999999999999ap-4'), h('-0x1.999999999999ap-4'), h('0x1.3333333333333p+0'), h('0x1.999999999999ap-4'), fixed=True, name='floor')
bodies[1] = world.add_box(h('-0x1.999999999999ap-4'), h('0x1.0000000000000p+0'), h('0x1.3333333333333p+0'), h('0x1.999999999999ap-4'), fixed=True, name='ceiling')
bodies[2] = world.add_box(h('-0x1.999999999999ap-4'), h('-0x1.999999999999ap-4'), h('0x1.999999999999ap-4'), h('0x1.3333333333333p+0'), fixed=True, name='left')
bodies[3] = world.add_box(h('0x1.0000000000000p+0'), h('-0x1.999999999999ap-4'), h('0x1.999999999999ap-4'), h('0x1.3333333333333p+0'), fixed=True, name='right')
bodies[4] = world.add_polygon(((h('0x1.ac7f15b76df31p-2'), h('0x1.17cb5b7cbdd23p-2')), (h('0x1.e750d7cbd95e9p-2'), h('0x1.3699c4437ba62p-2')), (h('0x1.b37bebeddfb5bp-2'), h('0x1.52994f7eaf17fp-2'))), mass=h('0x1.0710adf659518p-1'), velocity=(h('-0x1.47c4203081ff3p-3'), h('0x1.122f8dd329732p-2')), angular_velocity=h('-0x1.3531d0b6e8900p+2'), elasticity=h('0x1.e75a2326a0c19p-9'), friction=h('0x1.e5a45a315f41ep-1'))
bodies[5] = world.add_polygon(((h('0x1.2a6f18e4c5da1p-1'), h('0x1.effa833659c59p-2')), (h('0x1.284456c68681bp-1'), h('0x1.08dedffe1faa9p-1')), (h('0x1.19b7acdfa5ef3p-1'), h('0x1.11b3a1f6d97aep-1')), (h('0x1.09bdda9ab303fp-1'), h('0x1.0bd521f9d3074p-1')), (h('0x1.045e9801d0d27p-1'), h('0x1.f75d9391696abp-2')), (h('0x1.0da57e691ab6ap-1'), h('0x1.dad3b097c0ca5p-2')), (h('0x1.1e9634b03ffa9p-1'), h('0x1.d78a16536281fp-2'))), mass=h('0x1.3dd4b3b42fe0ep+0'), velocity=(h('-0x1.3b87a57611d20p-1'), h('0x1.39615fc6b6514p+0')), angular_velocity=h('0x1.f4dd1a99948dcp+3'), elasticity=h('0x1.9f0e13f642f4ap-1'), friction=h('0x1.ab118413facc8p-4'))
bodies[6] = world.add_circle((h('0x1.b471c59246fa5p-2'), h('0x1.6e464bc70f395p-3')), h('0x1.ed14ada3a5327p-6'), mass=h('0x1.47e648c9408f4p-1'), velocity=(h('-0x1.e9f845dc19656p-1'), h('-0x1.1cba64839a5f5p-2')), angular_velocity=h('-0x1.06d629e286a35p+4'), elasticity=h('0x1.95cd5048f63c9p-4'), friction=h('0x1.51bad68a0f200p-3'))
bodies[7] = world.add_circle((h('0x1.56fce6c7962dfp-1'), h('0x1.45f94b6619369p-2')), h('0x1.f9f2467b4e5d0p-5'), mass=h('0x1.4d4a95f6f9d43p+0'), velocity=(h('-0x1.15d531204dda5p-3'), h('-0x1.e8e5641e4498bp-2')), angular_velocity=h('-0x1.e11df62ffd149p+3'), elasticity=h('0x1.aabf3de8991d2p-3'), friction=h('0x1.250819ca804b0p-1'))
bodies[8] = world.add_circle((h('0x1.55f56d2873cb7p-2'), h('0x1.adfb6f954b614p-4')), h('0x1.e5844de981b92p-5'), mass=h('0x1.222dbae55230ap+0'), velocity=(h('-0x1.0b4e6f6913481p+0'), h('-0x1.67ee0619daa94p-1')), angular_velocity=h('-0x1.de9163a0a0ee8p+3'), elasticity=h('0x1.fa79901ca4dd3p-3'), friction=h('0x1.5e05e34488a38p-1'))
bodies[9] = world.add_polygon(((h('0x1.1b75719d7c577p-1'), h('0x1.3a127668f5ee3p-1')), (h('0x1.1dbb9c2b76710p-1'), h('0x1.2a95e9afc5bcap-1')), (h('0x1.2608d99ced1ecp-1'), h('0x1.23384116ee1a9p-1')), (h('0x1.31513d9a87685p-1'), h('0x1.23288321ecf60p-1')), (h('0x1.3ef1005a1fe5cp-1'), h('0x1.25a69f43d4086p-1')), (h('0x1.410e127b865fcp-1'), h('0x1.38df918b46da5p-1')), (h('0x1.35a5fb09bd9c7p-1'), h('0x1.3e94b875b2ce0p-1')), (h('0x1.24403a29ac3bbp-1'), h('0x1.46cacd73166b8p-1'))), mass=h('0x1.16b5f53de3e38p+0'), velocity=(h('-0x1.6897418c423d5p-4'), h('0x1.257e56acb8212p-5')), angular_velocity=h('-0x1.357fa5f2a224fp+4'), elasticity=h('0x1.f6e2b7f675ba0p-4'), friction=h('0x1.a10dca1122d5ap-1'))
bodies[10] = world.add_polygon(((h('0x1.5a4a332e5060bp-2'), h('0x1.bc1dd10b58928p-1')), (h('0x1.3c64b8735c7e9p-2'), h('0x1.a4ae52359ffd0p-1')), (h('0x1.4e660b013a7c2p-2'), h('0x1.8a61d4d1a0346p-1')), (h('0x1.82bf40e69a46bp-2'), h('0x1.81060c9ef5fc6p-1')), (h('0x1.b204f79cfa88ap-2'), h('0x1.8fa70c3bf5ea6p-1')), (h('0x1.b89e58cd98233p-2'), h('0x1.ab40c43c4ea8ap-1')), (h('0x1.91934150417bep-2'), h('0x1.bf0a93423a0c7p-1'))), mass=h('0x1.abffdfa4d8363p+0'), velocity=(h('-0x1.cac4bf69585f5p-2'), h('-0x1.e1ebff83e00b9p-1')), angular_velocity=h('-0x1.cd636be2c6bc8p+3'), elasticity=h('0x1.235c2334e071bp-4'), friction=h('0x1.bdf8410022802p-2'))
bodies[0].friction = h('0x1.50e32479f9d0cp-1')
bodies[1].friction = h('0x1.b50ab4bf849e6p-2')
bodies[2].friction = h('0x1.d0f75effa5750p-2')
bodies[3].friction = h('0x1.2c5be526bdc05p-1')
import time
start = time.time()
world.run_until(0.6445)
print("reached", world.time, "in", round(time.time() - start, 2), "s; now running to 1.0", flush=True)
world.run_until(1.0)
print("returned after", round(time.time() - start, 1), "s", world.stats)
