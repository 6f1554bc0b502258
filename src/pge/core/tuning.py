"""Tuning constants of the engine's progress guarantee, in one place.

The guarantee (docs/architecture.md, "Progress"): every ``run`` returns or raises after a
bounded amount of work per simulated second, for a scene of bounded size. Two checks give it:

* a body's travel step (``P[TRAVEL]``) must span at least ``MIN_TICKS`` ticks of the clock
  (ulps of the current time), else the body is *too fast* for the clock and the run raises
  before any event uses its swept box; so every horizon moves the clock on by at least that;
* a run of more than ``STORM_LIMIT + STORM_PER_BODY * N`` events (every kind, counted across
  returns to Python) that all lie within ``max(STORM_SPAN, STORM_TICKS * cap)`` ulps of the
  run's first is a *storm*: the clock cannot separate them (a zero-time loop, a Zeno run, a
  creeping clock) and the run raises, naming the bodies.
"""

#: events in a run the clock cannot separate before it is a storm (plus STORM_PER_BODY per body)
STORM_LIMIT = 1_000_000
#: how many more events a storm may hold per body row (N simultaneous bounces are legitimate)
STORM_PER_BODY = 64
#: seconds: a run of events within this of its first is one instant
STORM_SPAN = 1e-9
#: or within this many clock ticks per event of the cap (a clock that creeps a few ulps at a time)
STORM_TICKS = 8.0
#: a travel step shorter than this many clock ticks is beyond what the clock can resolve
MIN_TICKS = 64.0
