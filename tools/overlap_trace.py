"""Where a corpus scene's overlaps first appear: every pair that overlaps beyond a threshold,
with the time it first did, its deepest overlap, and whether the pair was in its island's
manifold at that island's last step.

    .venv/bin/python tools/overlap_trace.py 113 --until 5              # sampled 8 times a step
    .venv/bin/python tools/overlap_trace.py 113 --until 5 --every 1e-5 --threshold 1e-7

The corpus's benchmark samples overlaps every 0.1 s (``tools/corpus.py``); this samples the
scene as finely as asked, so that the deepest overlaps and the bodies that make them can be
traced (docs/contact.md, "Gaps").
"""

from __future__ import annotations

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import corpus  # noqa: E402  (tools/corpus.py: the scenes)

from pge.contact import islands as islands_module  # noqa: E402
from pge.contact.island import contact_bodies  # noqa: E402
from pge.core import layout as L  # noqa: E402
from pge.core.tuning import ISLAND_STEP  # noqa: E402


class _Manifolds:
    """The pairs of each island's manifold at its last step, per member, recorded by
    wrapping ``Islands._step``."""

    def __init__(self) -> None:
        self.last: dict[int, tuple[float, set]] = {}
        self._step = islands_module.Islands._step

    def __enter__(self):
        record = self

        def step(islands, k, t):
            record._step(islands, k, t)
            island = islands.islands.get(k)
            if island is not None:
                firsts, seconds = contact_bodies(island.keys)
                pairs = {frozenset(p) for p in zip(firsts.tolist(), seconds.tolist())}
                for i in island.members:
                    record.last[i] = (t, pairs)

        islands_module.Islands._step = step
        return self

    def __exit__(self, *exc) -> None:
        islands_module.Islands._step = self._step


def trace(seed: int, until: float, every: float, threshold: float) -> list[dict]:
    """One row per pair that overlapped by more than ``threshold`` at some sample."""
    world = corpus.scene(seed)
    state = world._state
    first: dict[frozenset, dict] = {}
    with _Manifolds() as manifolds:
        t = 0.0
        while t < until:
            t = min(until, t + every)
            world.run_until(t)
            for a, b, depth in world.overlaps(threshold):
                pair = frozenset((a.id, b.id))
                row = first.get(pair)
                if row is not None:
                    if depth > row["deepest"]:
                        row["deepest"], row["deepest_at"] = depth, t
                    continue
                moving = [i for i in (a.id, b.id) if not state.I[i, L.FIXED]]
                step, pairs = manifolds.last.get(moving[0], (None, set()))
                first[pair] = {
                    "pair": tuple(sorted(pair)),
                    "first": t,
                    "depth": depth,
                    "deepest": depth,
                    "deepest_at": t,
                    "last_step": step,
                    "in_manifold": pair in pairs,
                    "bodies": [
                        {
                            "id": i,
                            "kind": "circle" if state.I[i, L.KIND] == 0 else "polygon",
                            "fixed": bool(state.I[i, L.FIXED]),
                            "island": int(state.I[i, L.ISLAND]),
                            "spin": float(state.F[i, L.OMEGA]),
                            "reach": float(state.F[i, L.REACH]),
                        }
                        for i in (a.id, b.id)
                    ],
                }
    return sorted(first.values(), key=lambda row: -row["deepest"])


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("seed", type=int)
    parser.add_argument("--until", type=float, default=20.0)
    parser.add_argument("--every", type=float, default=ISLAND_STEP / 8, help="seconds between samples")
    parser.add_argument("--threshold", type=float, default=1e-9)
    parser.add_argument("--top", type=int, default=10)
    args = parser.parse_args(argv)
    rows = trace(args.seed, args.until, args.every, args.threshold)
    print(f"scene {args.seed}: {len(rows)} pairs overlapped beyond {args.threshold:g} "
          f"(sampled every {args.every:.3g} s up to {args.until:g} s)")
    for row in rows[: args.top]:
        print(f"pair {row['pair']}: first at {row['first']:.5f} s by {row['depth']:.2e}, deepest {row['deepest']:.2e} at {row['deepest_at']:.5f} s; "
              f"island's last step {row['last_step']}, in its manifold: {row['in_manifold']}")
        for body in row["bodies"]:
            print(f"    {body}")


if __name__ == "__main__":
    main()
