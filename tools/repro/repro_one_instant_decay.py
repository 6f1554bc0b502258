"""An event storm at one instant without gravity: scene seed 748 of tests/test_rotation.py with
15 bodies (inelastic, no gravity, friction). Found 2026-11-23 by ``survey.py overlap --seeds 700
800 --count 15`` (1 of 800 scenes). At t = 1.0900 polygon 12 collides with the ceiling again and
again at one instant, its velocity and spin shrinking by a constant factor each time (about 0.9993)
instead of settling in one go: sequential impulses at two contact points converging slowly, which
only a simultaneous solve of the two points would end. Before 2026-11-23 the decay ran down to a
denormal speed (1e-310), whose travel horizon overflowed to inf and made the body's swept box NaN;
the grid lost the body and a circle passed 6% into it at t = 4.06. With the box kept finite the
scene ended in the event-storm error. Fixed 2026-11-23: a free body that a collision leaves slower
than 1e-150 of its size per second is stopped (``engine.NO_SPEED``). Expected: no storm."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "tests"))
from test_rotation import build_spinning_scene  # noqa: E402

world, walls, bodies = build_spinning_scene(748, 15, elastic=False, gravity=False, friction=True)
try:
    world.run_until(2.0)
    print(f"no storm: t = {world.time}, {world.stats['events']} events")
except RuntimeError as error:
    print(error)
