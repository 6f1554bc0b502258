"""Hard-disc gas: the collision rate against density, by a pge sweep, against Enskog's theory.

This file is both a scene for ``pge sweep`` (it defines ``scene(seed, **params)``) and the study
that runs the sweep, averages the seeds and draws the plot::

    python examples/studies/gas_sweep.py                          # the study: sweep, table, plot
    python examples/studies/gas_sweep.py --seeds 4 --until 5      # quicker
    pge sweep examples/studies/gas_sweep.py --param density=0.05:0.4:8 --seeds 20 --until 10 --out results/gas

It needs the sweep and plot extras: ``pip install -e '.[sweep,plot]'``. docs/sweeps.md shows
the result and derives the formula.

Theory (2D hard discs of diameter sigma, number density n, temperature kT = m <v^2> / 2):
two discs collide when the impact parameter of their relative motion is within sigma either
side, a target of width 2 sigma, and the mean relative speed of a 2D Maxwell gas is
sqrt(pi kT / m) (the mean speed sqrt(pi kT / 2m) of a particle of reduced mass m/2). So the
collision frequency of one disc in the dilute gas is z0 = 2 n sigma sqrt(pi kT / m). Enskog's
correction multiplies it by the pair distribution at contact g(sigma), the factor by which
neighbours at contact are more frequent than in the ideal gas; Henderson's approximation
for discs at area fraction eta is g(sigma) = (1 - 7 eta / 16) / (1 - eta)^2
(D. Henderson, Mol. Phys. 30, 971 (1975); z_E = z0 g(sigma) as in Chapman and Cowling,
The Mathematical Theory of Non-uniform Gases, ch. 16, for the 2D case).
"""

from __future__ import annotations

import math

from pge import World
from pge.scenes import disc_gas

#: Thickness of the four fixed walls lying just outside the unit box (as in benchmarks/gas.py).
WALL = 0.05


def scene(seed: int, density: float = 0.1, n: int = 200, speed: float = 1.0, elasticity: float = 1.0) -> World:
    """``n`` equal unit-mass discs covering the fraction ``density`` of the unit box, all at ``speed``.

    The discs' placement and directions are ``pge.scenes.disc_gas(n, density, speed, seed)``,
    the hard-disc gas of benchmarks/gas.py; the box is four fixed walls of elasticity 1.
    """
    gas = disc_gas(n, area_fraction=density, speed=speed, seed=seed)
    world = World(elasticity=elasticity, bounds=gas.box)
    x0, y0, x1, y1 = gas.box
    width, height = x1 - x0, y1 - y0
    world.add_box(x0 - WALL, y0 - WALL, width + 2 * WALL, WALL, fixed=True, elasticity=1.0)
    world.add_box(x0 - WALL, y1, width + 2 * WALL, WALL, fixed=True, elasticity=1.0)
    world.add_box(x0 - WALL, y0, WALL, height, fixed=True, elasticity=1.0)
    world.add_box(x1, y0, WALL, height, fixed=True, elasticity=1.0)
    for position, velocity in zip(gas.positions, gas.velocities):
        world.add_circle(position, gas.radius, mass=1.0, velocity=velocity, elasticity=elasticity)
    return world


def enskog_rate(eta: float, n: int, speed: float, area: float = 1.0, contact: bool = True) -> float:
    """Collisions per disc per second of ``n`` discs at area fraction ``eta`` and speed ``speed``.

    ``z = 2 n sigma sqrt(pi kT / m) g(sigma)`` with number density n / area, sigma the diameter,
    kT / m = speed^2 / 2 (every disc starts at ``speed``; elastic collisions keep the energy),
    and Henderson's g(sigma) (1 if ``contact`` is False: the dilute-gas rate).
    """
    number_density = n / area
    sigma = 2.0 * math.sqrt(eta * area / (math.pi * n))
    kt_over_m = 0.5 * speed * speed
    g = (1.0 - 7.0 * eta / 16.0) / (1.0 - eta) ** 2 if contact else 1.0
    return 2.0 * number_density * sigma * math.sqrt(math.pi * kt_over_m) * g


def main(argv=None) -> None:
    """Run the sweep, print measured against predicted rates, write the plot."""
    import argparse

    import pge

    parser = argparse.ArgumentParser(description="hard-disc gas: collision rate against density")
    parser.add_argument("--densities", default="0.05:0.4:8", help="area fractions, A:B:N or a list")
    parser.add_argument("--n", type=int, default=200, help="discs per run (default 200)")
    parser.add_argument("--seeds", type=int, default=10, help="seeds per density (default 10)")
    parser.add_argument("--until", type=float, default=10.0, help="simulated seconds per run (default 10)")
    parser.add_argument("--out", default="results/gas_sweep", help="Parquet output (default results/gas_sweep)")
    parser.add_argument("--plot", default="gas_sweep.png", help="picture to write (default gas_sweep.png)")
    parser.add_argument("--workers", type=int, default=None, help="local worker processes (default: one per core)")
    args = parser.parse_args(argv)

    runs = pge.sweep(
        __file__,
        {"density": args.densities, "n": args.n},
        seeds=args.seeds,
        until=args.until,
        out=args.out,
        workers=args.workers,
    )
    failed = runs[runs.error_type.notna()]
    if len(failed):
        print(f"{len(failed)} runs failed, first: {failed.error_type.iloc[0]}: {failed.error_message.iloc[0]}")
    runs = runs[runs.error_type.isna()].copy()
    # Each pair collision is a collision for both discs: per-disc rate = 2 * pairs / (N * t).
    runs["rate"] = 2.0 * runs.pair_collisions / (runs.n * runs.sim_time)
    table = runs.groupby("density").agg(
        rate=("rate", "mean"), spread=("rate", "std"), seeds=("rate", "size"), wall=("wall_time", "mean")
    )
    table["error"] = table.spread / table.seeds**0.5
    table["enskog"] = [enskog_rate(eta, args.n, 1.0) for eta in table.index]
    table["dilute"] = [enskog_rate(eta, args.n, 1.0, contact=False) for eta in table.index]
    table["ratio"] = table.rate / table.enskog
    print(f"{'eta':>6} {'measured z':>11} {'+-':>6} {'Enskog z':>9} {'ratio':>6} {'dilute z':>9} {'run s':>6}")
    for eta, row in table.iterrows():
        print(
            f"{eta:6.3f} {row.rate:11.3f} {row.error:6.3f} {row.enskog:9.3f} {row.ratio:6.3f} "
            f"{row.dilute:9.3f} {row.wall:6.2f}"
        )

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fine = [0.005 * i for i in range(1, 91)]
    figure, axes = plt.subplots(figsize=(6.4, 4.4), dpi=120)
    axes.plot(fine, [enskog_rate(eta, args.n, 1.0) for eta in fine], label="Enskog, Henderson g(σ)")
    axes.plot(fine, [enskog_rate(eta, args.n, 1.0, contact=False) for eta in fine], "--", label="dilute gas, g = 1")
    axes.errorbar(table.index, table.rate, yerr=table.error, fmt="o", color="black", label="pge sweep")
    axes.set_xlabel("area fraction η")
    axes.set_ylabel("collisions per disc per second")
    axes.set_title(f"Hard-disc gas, N = {args.n}, {args.seeds} seeds x {args.until:g} s per point")
    axes.legend()
    axes.grid(alpha=0.3)
    figure.tight_layout()
    figure.savefig(args.plot)
    print(f"plot written to {args.plot}")


if __name__ == "__main__":
    main()
