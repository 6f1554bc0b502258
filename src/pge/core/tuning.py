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

# ---- islands: bodies in persistent contact (pge.contact; docs/contact.md) -----------------

#: seconds between two steps of an awake island (World(contact_step=...) overrides it)
ISLAND_STEP = 1.0 / 240.0
#: a step is cut short where a gap closes sooner (its impact then has its restitution) or a
#: polygon turns faster than MAX_TURN, but never below the island's floor: this fraction of
#: ISLAND_STEP, or (its contact rows + 1) / ROW_BUDGET of it where that is less. A cut step
#: solves the whole island, so the floor bounds what one body's bounces and spins cost the
#: others: at most about ROW_BUDGET rows of cut steps per ISLAND_STEP
SHORTEST_STEP = 0.25
#: (see SHORTEST_STEP)
ROW_BUDGET = 4096.0
#: a step cut where a body struck within it would travel further than the manifold looked is
#: at least this fraction of ISLAND_STEP: soundness first, so this cut may go below the floor
SHORTEST_REACH_STEP = 1e-6
#: an island's step is no longer than this angle over its fastest-turning polygon's spin
#: (down to its floor): the step's forces keep the directions of its start while corners
#: move on arcs, which leaves overlaps of about MAX_TURN^2 / 2 of a reach for the next step
#: to push out
MAX_TURN = 0.01
#: a point with a gap that closes within this fraction of ISLAND_STEP, fast enough to bounce,
#: bounces at the step's start, from its gap, instead of cutting the step short at its
#: arrival: a pile's bounces then cost at most 1 / BOUNCE_WINDOW steps per ISLAND_STEP, not
#: one step each (the bounce comes early by at most this fraction of a step's travel, and
#: with the speed of now: no energy is gained)
BOUNCE_WINDOW = 0.25
#: points of an island whose gaps close within this fraction of ISLAND_STEP of each other
#: take their impacts together (a face landing level to rounding lands as a face)
SIMULTANEOUS = 1e-3
#: the contact forces of an island's step may do positive work only within this fraction of
#: the island's kinetic energy and the work its accelerations do over the step (rounding);
#: beyond it the energy stage (``_no_gain``) scales the island's relative velocities back
ENERGY_ROUNDING = 1e-13
#: two contact normals are parallel (one fixed face) where the sine of their angle is below
#: this: a part pressed only on such faces without friction keeps its momentum along them
#: while it pays for a lift (``pge.contact.energy._kept_motion``)
PARALLEL = 1e-9
#: at most this many sweeps of the sequential-impulse solve at each step (it always returns)
ISLAND_ITERATIONS = 400
#: at most this many sweeps of the impact stage (inelastic, so every sweep only takes kinetic
#: energy out: stopped early, it leaves a little approach for the force stage and the next step)
IMPACT_ITERATIONS = 16
#: the solve stops early once no contact's speed is off by more than this times h |a| (the
#: speed gravity gives in one step)
SOLVE_TOLERANCE = 1e-6
#: ... and gives up once SOLVE_STALL sweeps in a row have not brought its worst error below
#: STALL_GAIN times its lowest so far (stalled: friction's sweeps on a pile wander)
SOLVE_STALL = 64
STALL_GAIN = 0.5
#: after this many sweeps that did not converge, the solve finishes exactly (on the sweeps'
#: active set, else by Lemke's method): sweeps are cheap but converge slowly on piles, and
#: four are enough to find the active set at most steps
EXACT_AFTER = 4
#: an active set whose answer breaks a condition of the problem moves (principal pivoting)
#: at most this many times (then the last step's set is tried, then Lemke's method)
SET_TRIES = 3
#: the exact solve is tried when the problem has at most this many unknowns (a point each,
#: three for a pair's friction)
LCP_LIMIT = 240
#: ... and the impact stage's by Lemke's method when it has at most this many (where the
#: exact finish fails, the impact stage's sweeps stop after IMPACT_ITERATIONS and leave an
#: approach that the force stage, whose force is constant over the step, can only turn round
#: by the step's end: a point still closing at u sinks by u h / 4 at mid-step)
IMPACT_LCP_LIMIT = 240
#: a pair is in an island's manifold while its gap is below its step travel plus this times
#: the smaller bounding radius (so that resting contacts stay listed)
CONTACT_MARGIN = 0.01
#: the part of an overlap a step pushes out (the rest at the following steps)
PUSH_RATE = 0.8
#: the instants inside a step, as fractions of it, where the push-out holds each point's gap
#: on the step's solved motion as well as at its end (pge.contact.arcs._solved_arcs)
STEP_INSTANTS = (0.25, 0.5, 0.75)
#: ... and where a gap there asks the lift for more, the instant between them where it asks
#: most, found by this many golden-section steps around the instant that asked most
#: (pge.contact.arcs._most_asked: a gap's dip is flat near its deepest while the lift's
#: displacement still rises, so between three instants a gap held at them dipped by a sixth
#: of its deficit)
INSTANT_REFINEMENTS = 8
#: ... and at this many evenly spaced instants where a point of the pair changes features
#: within the step (a circle passing a turning polygon's corner: its gap has a kink there,
#: and between three instants it dipped by up to 4.5e-7)
FEATURE_INSTANTS = 16
#: a turning pair's point is held by the push-out at its pose at the step's end as well
#: (pge.contact.pushout._with_ends) where a polygon of the pair turns by more than this
#: (radians) over the step: below it the two poses' normals and lever arms move a lift's
#: point apart by less than a millionth of the lift's own displacement
END_TURN = 1e-6
#: ... where some point overlaps by more than this times its pair's smaller bounding radius
#: (overlaps of rounding's size are only kept from growing)
PUSH_SLOP = 1e-10
#: a gap below this times the smaller bounding radius is touching (restitution may act)
TOUCHING = 1e-6
#: polygons' reference face: the second polygon's face only if its separation is larger by
#: more than this times the sum of bounding radii (no flicker between steps of two faces
#: that rest level on each other). A point's separation can read this much below the pair's
#: separating-axis distance, an overlap the push-out then moves out, so it is rounding's size:
#: at 1e-3 a corner resting on a face read as sunk 5.9e-5 into it and was flung off at 2 m/s
FACE_HYSTERESIS = 1e-8
#: ... but not where the incident face dips towards the reference face's line beyond the
#: face's end by more than this times the sum of bounding radii (the reference polygon's
#: corner meets the incident face there: the other face is the reference)
FACE_DIP = 1e-9
#: an island falls asleep when every body's mean speed (plus spin times reach) stays below
#: this times sqrt(|acceleration| * reach) for SLEEP_TIME seconds
SLEEP_SPEED = 0.01
SLEEP_TIME = 0.5
#: ... and while no point of it overlaps by more than this times its pair's smaller bounding
#: radius (an overlap being pushed out is motion: asleep, it would stay)
SLEEP_OVERLAP = 1e-8
