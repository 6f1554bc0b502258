"""Column layout of the engine's arrays, shared by the compiled loop and the World.

The engine keeps every body in one row of a float array ``F`` and one row of
an int array ``I`` (array-of-structures: one body's hot fields share cache
lines). Module-level integers are compile-time constants for Numba.
"""

# ---- F: float64 per body -------------------------------------------------
# Rows are whole cache lines (NF a multiple of 8, the array aligned: ``pge.core.state``). The
# first line holds what the broad phase reads of every candidate (most are rejected by their
# boxes), the second what a prediction reads of a candidate that passed.
BOX_X0, BOX_Y0, BOX_X1, BOX_Y1 = 0, 1, 2, 3  # swept box over [now, HORIZON]
HORIZON = 4  # end of the time span the swept box covers
X, Y = 5, 6  # reference position (centre or area centroid) at time T0
T0 = 7  # the body's own reference time ("delayed state")
VX, VY = 8, 9  # velocity at T0 (zero for a fixed body)
AX, AY = 10, 11  # total constant acceleration (own + gravity; zero if fixed)
REACH = 12  # bounding radius about the reference point
RADIUS = 13  # circle radius (0 for polygons)
OMEGA = 14
ALPHA = 15  # angular acceleration: an island's contact torque over its current step
INV_MASS = 16  # 1 / mass, 0 for fixed bodies
ELASTICITY = 17
EXT_X0, EXT_Y0, EXT_X1, EXT_Y1 = 18, 19, 20, 21  # shape's box relative to the reference point
OWN_AX, OWN_AY = 22, 23  # the body's own acceleration, on top of gravity
ANGLE = 24
HELD_VX, HELD_VY = 25, 26  # velocity kept while fixed, restored by unfix
MASS = 27  # nan until given
FREE_AX, FREE_AY = 28, 29  # own acceleration + gravity (zero if fixed): what the body feels when free
FRICTION = 30  # Coulomb friction coefficient
SPRING_AX, SPRING_AY = 31, 32  # acceleration from springs, held constant between refreshes
INV_INERTIA = 33  # 1 / moment of inertia about the reference point, 0 for fixed bodies
ORIENT = 34  # the angle the body's outline rows in OL are turned to
HELD_OMEGA = 35  # angular velocity kept while fixed, restored by unfix
LAST_HIT = 36  # time of the body's last collision (with I[LAST_OTHER])
NF = 40  # 37 used, padded to five cache lines

# ---- I: int64 per body -------------------------------------------------------
# Rows are two cache lines; the first holds what the broad phase and a prediction read of a
# candidate.
KIND = 0  # pge.toi.CIRCLE or POLYGON
FIXED = 1
COUNT = 2  # invalidation counter: events carry it and are stale once it moves on
ALIVE = 3
NEXT = 4  # the next body in the cell's linked list
MARK = 5  # pair-once mark used while predicting a group of bodies
ISLAND = 6  # the island the body belongs to (-1: none), see pge.contact
OUTLINE_START = 7  # polygon rows in the outline array
OUTLINE_N = 8
CELL = 9  # grid cell of a moving body (-1: not in the grid)
PREV = 10  # the previous body in the cell's linked list
NOTIFY = 11  # collisions of this body are reported to Python
STAMP = 12  # de-duplication stamp used while gathering candidates
LAST_OTHER = 13  # the body of its last collision (-1: none)
NI = 16  # 14 used, padded to two cache lines

# ---- P: float64 world parameters --------------------------------------------
TIME = 0
GRID_X0, GRID_Y0 = 1, 2
CELL_SIZE, INV_CELL = 3, 4
TRAVEL = 5  # distance a moving body may travel within one horizon
MARGIN = 6  # safety margin added to every swept box
OVERLAP_TOLERANCE = 7
REST_HEIGHT = 8  # a contact whose bounce would rise less than this times the smaller reach is persistent
STORM_START = 9  # time of the first event of the current run of close events (the progress watch)
CONTACT_STEP = 10  # the islands' step length h
NP = 11

# ---- Q: int64 world parameters -----------------------------------------------
GRID_NX, GRID_NY = 0, 1
RULE = 2  # restitution rule code (see pge.response)
STAMP_COUNTER = 3
MARK_COUNTER = 4
HEAP_N = 5  # entries in the heap
FREE_N = 6  # free event slots
MIN_FREE = 7  # the loop returns NEED_SPACE when fewer slots are free
FRICTION_RULE = 8  # how two friction coefficients combine (codes as RULE)
PENDING_N = 9  # bodies waiting in `pending` to be predicted
PENDING_DONE = 10  # how many of them are done
PENDING_MARK = 11  # pair-once mark of the current batch
HORIZON_N = 12  # entries in the horizons' heap (pge.core.queue)
STORM_RUN = 13  # events in the current run of close events (the progress watch), kept across returns
STORM_CAP = 14  # events a run may hold before it is a storm (set by Python from the number of bodies)
FAST_BODY = 15  # a body whose travel step the clock cannot resolve (-1: none), found by `place`
STORM_KINDS = 16  # first of NKINDS counts, one per event kind, of the current run
EXCUSED_N = 20  # pairs in `excused`: they overlapped when the run began and do not collide yet
BROADPHASE = 21  # broad-phase switches (bits below; 0: every stage on, the sound default)
NQ = 22

# ---- Q[BROADPHASE] bits: stages switched off to measure what they save (World.broadphase)
NO_SHORT_CIRCUIT = 1  # skip cannot_touch_before: every box-overlapping pair is solved exactly
NO_BOXES = 2  # skip the swept-box overlap check (the window is still min(h_i, h_j))
NO_GRID = 4  # candidates are every body in the grid or fixed, not the neighbouring cells'
LECTURE_TEST = 8  # the lecture's unsound short-circuit test instead of cannot_touch_before

# ---- stats: int64 counters ---------------------------------------------------
STAT_NAMES = (
    "events",
    "collisions",
    "pair_collisions",
    "horizons",
    "timers",
    "frames",
    "stale",
    "grazes",
    "candidates",
    "box_rejects",
    "bound_rejects",
    "predictions",
    "hits",
    "sleeps",
    "wakes",
    "joins",
    "island_steps",
)
(
    S_EVENTS,
    S_COLLISIONS,
    S_PAIR_COLLISIONS,
    S_HORIZONS,
    S_TIMERS,
    S_FRAMES,
    S_STALE,
    S_GRAZES,
    S_CANDIDATES,
    S_BOX_REJECTS,
    S_BOUND_REJECTS,
    S_PREDICTIONS,
    S_HITS,
    S_SLEEPS,
    S_WAKES,
    S_JOINS,
    S_ISLAND_STEPS,
) = range(17)
NSTATS = 17

# ---- event kinds (high bits of the heap key; equal times pop in this order) --
COLLISION, HORIZON_EVENT, TIMER, FRAME = 0, 1, 2, 3
NKINDS = 4
KIND_SHIFT = 58
ID_SHIFT = 29

# ---- out: the record of the event that returned control to Python -----------
OUT_TIME, OUT_A, OUT_B, OUT_PX, OUT_PY, OUT_NX, OUT_NY, OUT_IMPULSE, OUT_SPEED, OUT_ID, OUT_EPOCH = range(11)
OUT_JOIN = 11  # what the collision in `out` asks of the islands: one of the codes below
#: what ``out[OUT_JOIN]`` asks of the islands: nothing; join the two
#: bodies' islands (a persistent contact); wake the island hit (no join); take the impact
#: into the island hit, whose step solves it with its contacts (no impulse applied yet)
NO_JOIN, JOIN, WAKE, ABSORB = 0.0, 1.0, 2.0, 3.0
#: a face that met a face with both ends taking the impact (``pge.core.engine.patch_collide``):
#: 1.0, then the two ends, their normal impulses and the friction impulse at their midpoint
OUT_PATCH, OUT_X1, OUT_Y1, OUT_X2, OUT_Y2, OUT_L1, OUT_L2, OUT_JT = range(12, 20)
NOUT = 20

# ---- return codes of the loop --------------------------------------------------
DONE = 0  # the next event is after `until`
COLLIDED = 1  # a collision Python wants to hear about
FIRED_TIMER = 2
FIRED_FRAME = 3
NEED_SPACE = 4  # grow the event arrays and call again
EMPTY = 5  # no events left
STORM = 6  # a run of events the clock cannot separate: a zero-time, Zeno or creeping loop
TOO_FAST = 7  # a body moves too fast for the clock (``Q[FAST_BODY]`` names it)
JOINED = 8  # a slow collision (in `out`) joins its bodies' islands: Python merges them

# ---- outline array columns ------------------------------------------------------
O_X, O_Y, O_NX, O_NY, O_LENGTH = 0, 1, 2, 3, 4
