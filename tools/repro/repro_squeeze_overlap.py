"""An overlap in a four-body squeeze on a frictionless floor: scene seed 0 of tests/test_rotation.py
(10 bodies, inelastic, gravity, no friction), run for the full 10 s. At t = 8.10676 circle 10,
resting on sliding polygon 12, and polygon 13, sliding on the floor, were found 4.5e-9 apart
inside each other when polygon 8 pushed 13 into the circle; the squeeze then resolved with
overlaps up to 3.3e-6 of their sizes (the tests allow 1e-9). Measured 2026-11-22 at 22b4600.

Fixed at b2abef2: the circle was touching 13's corner to rounding, leaving it at 5e-9 m/s and
pushed back by its rest acceleration; circle_polygon answered "never" for a gap that never becomes
positive (its feature polynomials ran without the "closes again from the peak" rule). Kept as a
regression check, with the tests' bounds: pairs no island holds must not overlap by more than
1e-9 (each one that does is printed), pairs an island's step holds by no more than
``ISLAND_OVERLAP`` (its integration error). It prints ``worst overlap outside islands 0`` and
a worst within islands of 1.5e-4 now (the scene takes another path since then)."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "tests"))
from test_rotation import ISLAND_OVERLAP, build_spinning_scene, worst_overlap  # noqa: E402

world, walls, bodies = build_spinning_scene(0, 10, elastic=False, gravity=True, friction=False)
worst = inside = 0.0
for event in world.events(8.2):
    depth, what = worst_overlap(world, bodies, within_islands=False)
    if depth > 1e-9 and depth > worst:
        worst = depth
        print(f"t = {event.time:.9f}: overlap {depth:.3g} ({what})", flush=True)
    depth, what = worst_overlap(world, bodies, within_islands=True)
    if depth > ISLAND_OVERLAP and depth > inside:
        print(f"t = {event.time:.9f}: overlap {depth:.3g} within an island ({what})", flush=True)
    inside = max(inside, depth)
print(f"worst overlap outside islands {worst:.3g}, within islands {inside:.3g} (bound {ISLAND_OVERLAP:g})")
