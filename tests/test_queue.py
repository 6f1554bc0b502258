"""The event queue (``pge.core.queue``): the slots' heap pops in (time, key, slot) order, and
the horizons' heap, moved in place, always has the earliest horizon first."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from pge.core import layout as L
from pge.core import queue
from pge.core.state import EngineState

#: few distinct times, so that ties (decided by key, then slot or body) are common
TIMES = st.sampled_from([0.0, 0.5, 1.0, 1.0, 2.0, 3.5, math.inf])


def horizon_key(i: int) -> int:
    return (L.HORIZON_EVENT << L.KIND_SHIFT) | i


def engine_state(bodies: int, slots: int) -> EngineState:
    state = EngineState(capacity=bodies, event_capacity=slots)
    state.Q[L.MIN_FREE] = 0
    return state


@settings(max_examples=60, deadline=None)
@given(st.lists(st.one_of(st.tuples(st.just("push"), TIMES.filter(math.isfinite), st.integers(0, 5)),
                          st.just(("pop",))), max_size=60))
def test_the_slots_pop_by_time_then_key_then_slot(operations):
    state = engine_state(4, 64)
    S = state.S
    queued = set()
    for op in operations:
        if op[0] == "push":
            _, t, body = op
            key = (L.COLLISION << L.KIND_SHIFT) | body
            slot = int(state.free[state.Q[L.FREE_N] - 1])
            queue.push(S, t, key, body, -1, 0, 0, 0)
            queued.add((t, key, slot))
        elif queued:
            slot, t, key = queue.pop_earliest(S)
            earliest = min(queued)
            assert (t, key, slot) == earliest
            queued.remove(earliest)
    assert state.Q[L.HEAP_N] == len(queued)


def check_horizons(state: EngineState, expected: dict[int, float]) -> None:
    """The heap holds exactly ``expected`` (body -> horizon), each body where it says, in heap
    order, and the earliest first."""
    n = int(state.Q[L.HORIZON_N])
    assert n == len(expected)
    times = state.horizon_time[:n]
    bodies = state.horizon_index[:n, 0]
    assert dict(zip(bodies.tolist(), times.tolist())) == expected
    for i in range(state.horizon_index.shape[0]):
        k = int(state.horizon_index[i, 1])
        assert (k >= 0) == (i in expected)
        if k >= 0:
            assert bodies[k] == i
    for k in range(1, n):
        parent = (k - 1) // queue.ARITY
        assert (times[parent], bodies[parent]) < (times[k], bodies[k])
    if expected:
        first = min(expected, key=lambda i: (expected[i], i))
        assert bodies[0] == first and times[0] == expected[first]


@settings(max_examples=80, deadline=None)
@given(st.lists(st.tuples(st.sampled_from(["set", "drop"]), st.integers(0, 11), TIMES), max_size=80))
def test_horizons_moved_in_place_keep_the_earliest_first(operations):
    state = engine_state(12, 64)
    S = state.S
    expected: dict[int, float] = {}
    for op, i, t in operations:
        if op == "set":
            queue.set_horizon(S, i, t)
            if t == math.inf:
                expected.pop(i, None)
            else:
                expected[i] = t
        else:
            queue.drop_horizon(S, i)
            expected.pop(i, None)
        check_horizons(state, expected)


@settings(max_examples=60, deadline=None)
@given(st.dictionaries(st.integers(0, 7), TIMES.filter(math.isfinite), max_size=6),
       st.lists(st.tuples(TIMES.filter(math.isfinite), st.integers(0, 3), st.integers(0, 7)), max_size=6))
def test_the_earliest_event_is_taken_from_the_right_heap(horizons, slots):
    """Between the two heaps the loop takes the smaller ``(time, key)``: a collision before a
    horizon at the same time (its kind is smaller), a horizon before a timer or a frame."""
    state = engine_state(8, 64)
    S = state.S
    for i, t in horizons.items():
        queue.set_horizon(S, i, t)
    keys = []
    for t, kind, body in slots:
        key = (kind << L.KIND_SHIFT) | body
        queue.push(S, t, key, body, -1, 0, 0, 0)
        keys.append((t, key))
    if not horizons and not slots:
        assert not queue.next_is_horizon(S)
        return
    first_horizon = min(((t, horizon_key(i)) for i, t in horizons.items()), default=(math.inf, np.inf))
    first_slot = min(keys, default=(math.inf, np.inf))
    assert queue.next_is_horizon(S) == (bool(horizons) and (not keys or first_horizon < first_slot))
