"""A Zeno run the pivot rule does not catch: scene seed 0 of tests/test_rotation.py (10 bodies,
inelastic, gravity, friction). Circle 7 rests on the floor; spinning polygon 5 (-10.9 rad/s)
presses on its side. Between t = 0.66 and 0.6634 they collide about 396,000 times, each
closing at ~7e-10 m/s with impulses of ~1e-9: the circle is nudged, friction stops it, and the
polygon's corner comes back. Measured 2026-11-22 at 242e381: 3.3 million events reach only
t = 0.666 in 100 s. Expected: t = 1 within seconds (the contact is pressed and should rest or
lift under the pivot rule). The pivot rule went with the resting-contact rules of that time,
since removed; kept as a check: t = 0.67 in a fraction of a second now."""
import os
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "tests"))
from test_rotation import build_spinning_scene  # noqa: E402

world, walls, bodies = build_spinning_scene(0, 10, elastic=False, gravity=True, friction=True)
start = time.perf_counter()
for until in (0.66, 0.6634, 0.67):
    world.run_until(until)
    print(f"t = {until} in {time.perf_counter() - start:.1f} s; {world.stats['collisions']} collisions", flush=True)
