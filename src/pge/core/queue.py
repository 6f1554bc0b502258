"""The event queue: a four-ary heap of event slots with lazy invalidation, and the bodies'
horizons in a heap of their own, moved in place.

A slot holds an event's five ints of data (``slot_data``); the heap holds slot
numbers ordered by ``(time, key, slot)``, and keeps each entry's time
(``heap_time``) and key with its slot (``heap_entry``) by heap position, so that
sifting never reads a slot. The key carries the event kind in its top bits, so
equal times pop in kind order (see ``pge.core.layout``), and for a collision the
two body ids, smaller first. Entries are never removed early: each carries the
invalidation counters of its bodies and is dropped when popped if one has moved on.

Four children a node, not two: a large queue (a hundred thousand bodies keep
about as many entries) spends its time waiting on memory, and four children
halve the levels a sift passes while their times share one cache line
(``heap_time`` is laid out for it, ``pge.core.state``). The order is total, so
the entries pop in the same order whatever the heap's shape.

The horizons (``pge.core.predict``: when a moving body's swept box runs out) are not slots:
each moving body has one entry in a second four-ary heap (by position: ``horizon_time``,
and the body in ``horizon_index[k, 0]``; by body: its position, ``horizon_index[i, 1]``),
which a new horizon moves in place. Lazily, every collision would leave both bodies' old
horizons behind as stale entries, about one stale pop an event in a gas; in place there
are none, and the horizons' heap holds one entry per moving body. Its order is the queue's
for horizon entries (``(time, key)``, the key the body's id under the kind's bits), and the
loop takes the earlier of the two heaps' first entries (``next_is_horizon``).
"""

from __future__ import annotations

import math

from pge._jit_cache import njit

from pge.core import layout as L

_INF = math.inf

#: children of a heap node: node ``i``'s are ``ARITY i + 1`` to ``ARITY i + ARITY``
ARITY = 4


@njit(cache=True, inline="always")
def _before(t1, k1, s1, t2, k2, s2):
    """Whether entry ``(t1, k1, s1)`` pops before ``(t2, k2, s2)``: by time, then key, then slot."""
    if t1 != t2:
        return t1 < t2
    if k1 != k2:
        return k1 < k2
    return s1 < s2


@njit(cache=True, inline="always")
def push(S, t, key, a, b, count_a, count_b, feature):
    """Queue an event; the caller guarantees a free slot (``Q[MIN_FREE]``)."""
    Q = S.Q
    heap_time = S.heap_time
    heap_entry = S.heap_entry
    slot_data = S.slot_data
    free = S.free
    n_free = Q[L.FREE_N] - 1
    slot = free[n_free]
    Q[L.FREE_N] = n_free
    slot_data[slot, 0] = a
    slot_data[slot, 1] = b
    slot_data[slot, 2] = count_a
    slot_data[slot, 3] = count_b
    slot_data[slot, 4] = feature
    i = Q[L.HEAP_N]
    Q[L.HEAP_N] = i + 1
    while i > 0:
        parent = (i - 1) // ARITY
        if _before(heap_time[parent], heap_entry[parent, 0], heap_entry[parent, 1], t, key, slot):
            break
        heap_time[i] = heap_time[parent]
        heap_entry[i, 0] = heap_entry[parent, 0]
        heap_entry[i, 1] = heap_entry[parent, 1]
        i = parent
    heap_time[i] = t
    heap_entry[i, 0] = key
    heap_entry[i, 1] = slot


@njit(cache=True, inline="always")
def pop_earliest(S):
    """Remove the earliest entry from the heap, put its slot back on the free list, and
    return ``(slot, time, key)``.

    The slot's data stay readable until the next ``push``.
    """
    Q = S.Q
    heap_time = S.heap_time
    heap_entry = S.heap_entry
    free = S.free
    top_time = heap_time[0]
    top_key = heap_entry[0, 0]
    top = heap_entry[0, 1]
    n = Q[L.HEAP_N] - 1
    Q[L.HEAP_N] = n
    if n > 0:
        last_time = heap_time[n]
        last_key = heap_entry[n, 0]
        last = heap_entry[n, 1]
        i = 0
        while True:
            first = ARITY * i + 1
            if first >= n:
                break
            # The earliest child: times decide but for ties, so keys are read only then.
            child = first
            child_time = heap_time[first]
            for c in range(first + 1, min(first + ARITY, n)):
                c_time = heap_time[c]
                if c_time < child_time or (
                    c_time == child_time
                    and _before(c_time, heap_entry[c, 0], heap_entry[c, 1], child_time, heap_entry[child, 0], heap_entry[child, 1])
                ):
                    child = c
                    child_time = c_time
            if _before(last_time, last_key, last, child_time, heap_entry[child, 0], heap_entry[child, 1]):
                break
            heap_time[i] = child_time
            heap_entry[i, 0] = heap_entry[child, 0]
            heap_entry[i, 1] = heap_entry[child, 1]
            i = child
        heap_time[i] = last_time
        heap_entry[i, 0] = last_key
        heap_entry[i, 1] = last
    free[Q[L.FREE_N]] = top
    Q[L.FREE_N] += 1
    return top, top_time, top_key


# ------------------------------------------------------------------ the horizons


@njit(cache=True, inline="always")
def _horizon_before(t1, i1, t2, i2):
    """Whether body ``i1``'s horizon at ``t1`` comes before body ``i2``'s at ``t2``."""
    return t1 < t2 or (t1 == t2 and i1 < i2)


@njit(cache=True)
def _horizon_move(times, index, k, t, i, n):
    """Put body ``i``'s horizon ``t`` in the heap of ``n`` entries, starting from position
    ``k``: up while it comes before its parent, else down while a child comes before it.

    Called, not inlined, with the two arrays it needs: every inlined copy of ``place``
    (with ``set_horizon`` inside) would type and compile its own, seconds each on a cold
    start, and a call passing two arrays costs a few nanoseconds."""
    if k > 0 and _horizon_before(t, i, times[(k - 1) // ARITY], index[(k - 1) // ARITY, 0]):
        while k > 0:
            parent = (k - 1) // ARITY
            if _horizon_before(times[parent], index[parent, 0], t, i):
                break
            times[k] = times[parent]
            index[k, 0] = index[parent, 0]
            index[index[k, 0], 1] = k
            k = parent
    else:
        while True:
            first = ARITY * k + 1
            if first >= n:
                break
            child = first
            child_time = times[first]
            child_body = index[first, 0]
            for c in range(first + 1, min(first + ARITY, n)):
                if _horizon_before(times[c], index[c, 0], child_time, child_body):
                    child = c
                    child_time = times[c]
                    child_body = index[c, 0]
            if _horizon_before(t, i, child_time, child_body):
                break
            times[k] = child_time
            index[k, 0] = child_body
            index[child_body, 1] = k
            k = child
    times[k] = t
    index[k, 0] = i
    index[i, 1] = k


@njit(cache=True, inline="always")
def drop_horizon(S, i):
    """Take body ``i``'s horizon out of the queue (no-op if it has none)."""
    Q = S.Q
    index = S.horizon_index
    k = index[i, 1]
    if k < 0:
        return
    index[i, 1] = -1
    n = Q[L.HORIZON_N] - 1
    Q[L.HORIZON_N] = n
    if k == n:
        return
    _horizon_move(S.horizon_time, index, k, S.horizon_time[n], index[n, 0], n)


@njit(cache=True, inline="always")
def set_horizon(S, i, t):
    """Body ``i``'s horizon is ``t`` from now on (inf: none), in place of any it had."""
    Q = S.Q
    if t == _INF:
        drop_horizon(S, i)
        return
    index = S.horizon_index
    k = index[i, 1]
    if k < 0:
        k = Q[L.HORIZON_N]
        Q[L.HORIZON_N] = k + 1
    _horizon_move(S.horizon_time, index, k, t, i, Q[L.HORIZON_N])


@njit(cache=True, inline="always")
def next_is_horizon(S):
    """Whether the earliest event is the horizons' first (else the slots' first, or none)."""
    Q = S.Q
    if Q[L.HORIZON_N] == 0:
        return False
    if Q[L.HEAP_N] == 0:
        return True
    t = S.horizon_time[0]
    top = S.heap_time[0]
    if t != top:
        return t < top
    return ((L.HORIZON_EVENT << L.KIND_SHIFT) | S.horizon_index[0, 0]) < S.heap_entry[0, 0]
