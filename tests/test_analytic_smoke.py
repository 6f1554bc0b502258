"""Smoke-level analytic checks of the engine core (the full suites live beside this file)."""

import math

import pge


def test_ball_dropped_on_floor_first_touches_at_sqrt_2h_over_g():
    """A ball released at rest h above a fixed floor touches it at sqrt(2h/g)."""
    g, h, r = 9.81, 0.3, 0.05
    world = pge.World(gravity=(0.0, -g))
    world.add_box(0.0, 0.0, 1.0, 0.1, fixed=True)
    world.add_circle((0.5, 0.1 + h + r), r, mass=1.0)
    times = []
    world.on_collision(lambda event: times.append(event.time))
    world.run_until(0.5)
    expected = math.sqrt(2.0 * h / g)
    assert abs(times[0] - expected) <= 1e-12 * expected


def test_showcase_conserves_energy_and_never_overlaps(tmp_path):
    """The README's main job runs, conserves energy with elasticity 1 and writes its picture."""
    from pge.showcase import run_showcase

    summary = run_showcase(tmp_path, duration=1.0)
    assert (tmp_path / "showcase.gif").stat().st_size > 1000
    assert (tmp_path / "showcase.pgerec").stat().st_size > 1000
    assert abs(summary["energy_drift"]) < 1e-9
    assert summary["worst_overlap"] <= 1e-9
    assert summary["collisions"] > 100
    assert (tmp_path / "showcase.png").stat().st_size > 1000
