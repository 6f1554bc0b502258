import math, random, time, sys
from pge import World
def scene(seed, n=12):
    rng = random.Random(seed)
    e = rng.choice([0.0, 0.3, 0.5, 0.8, 0.98])
    w = World(gravity=(0, -9.81), elasticity=e, bounds=(0, 0, 1, 1))
    w.add_box(0, 0, 1, 0.05, fixed=True, friction=rng.choice([0, 0.3, 0.8]))
    w.add_box(0, 0.05, 0.05, 0.95, fixed=True)
    w.add_box(0.95, 0.05, 0.05, 0.95, fixed=True)
    placed = []
    for k in range(n):
        for _ in range(100):
            x = rng.uniform(0.12, 0.88); y = rng.uniform(0.15, 0.9); r = rng.uniform(0.025, 0.05)
            if all(math.hypot(x - a, y - b) > r + c + 0.01 for a, b, c in placed):
                break
        placed.append((x, y, r))
        mu = rng.choice([0, 0.2, 0.6])
        if rng.random() < 0.3:
            w.add_circle((x, y), r, mass=1.0, friction=mu, velocity=(rng.uniform(-1, 1), rng.uniform(-1, 1)))
        else:
            s = rng.randint(3, 6); ph = rng.uniform(0, 6.3)
            w.add_polygon([(x + r * math.cos(ph + 2 * math.pi * j / s), y + r * math.sin(ph + 2 * math.pi * j / s)) for j in range(s)],
                          mass=1.0, friction=mu, angular_velocity=rng.uniform(-10, 10), velocity=(rng.uniform(-1, 1), rng.uniform(-1, 1)))
    return w, e
for seed in range(int(sys.argv[1]), int(sys.argv[2])):
    w, e = scene(seed)
    t0 = time.time(); worst = 0.0; status = "ok"
    try:
        for T in range(1, 11):
            w.run_until(float(T))
            worst = max([worst] + [d for _, _, d in w.overlaps()])
            if time.time() - t0 > 15: status = f"slow@{T}"; break
    except Exception as ex:
        status = f"ERR {ex!s:.100}"
    rest = sum(1 for b in w.bodies if not b.is_fixed and b.resting_on is not None)
    print(seed, e, status, f"{time.time()-t0:.1f}s", w.stats['events'], f"overlap={worst:.1e}", f"rest={rest}/12", flush=True)
