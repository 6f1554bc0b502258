"""The event queue: a binary heap of event slots with lazy invalidation.

Slots live in parallel arrays (time, key, five ints of data); the heap holds
slot numbers ordered by ``(time, key, slot)``. The key carries the event
kind in its top bits, so equal times pop in kind order (see
``pge.core.layout``), and for a collision the two body ids, smaller first.
Entries are never removed early: each carries the invalidation counters of
its bodies and is dropped when popped if one has moved on.
"""

from __future__ import annotations

from pge._jit_cache import njit

from pge.core import layout as L


@njit(cache=True, inline="always")
def _earlier(slot_time, slot_key, s1, s2):
    t1 = slot_time[s1]
    t2 = slot_time[s2]
    if t1 != t2:
        return t1 < t2
    k1 = slot_key[s1]
    k2 = slot_key[s2]
    if k1 != k2:
        return k1 < k2
    return s1 < s2


@njit(cache=True, inline="always")
def push(S, t, key, a, b, count_a, count_b, feature):
    """Queue an event; the caller guarantees a free slot (``Q[MIN_FREE]``)."""
    Q = S[4]
    heap = S[8]
    slot_time = S[9]
    slot_key = S[10]
    slot_data = S[11]
    free = S[12]
    n_free = Q[L.FREE_N] - 1
    slot = free[n_free]
    Q[L.FREE_N] = n_free
    slot_time[slot] = t
    slot_key[slot] = key
    slot_data[slot, 0] = a
    slot_data[slot, 1] = b
    slot_data[slot, 2] = count_a
    slot_data[slot, 3] = count_b
    slot_data[slot, 4] = feature
    i = Q[L.HEAP_N]
    Q[L.HEAP_N] = i + 1
    while i > 0:
        parent = (i - 1) >> 1
        above = heap[parent]
        if _earlier(slot_time, slot_key, above, slot):
            break
        heap[i] = above
        i = parent
    heap[i] = slot


@njit(cache=True, inline="always")
def pop_earliest(S):
    """Remove the earliest slot from the heap, put it back on the free list, return it.

    The slot's contents stay readable until the next ``push``.
    """
    Q = S[4]
    heap = S[8]
    slot_time = S[9]
    slot_key = S[10]
    free = S[12]
    top = heap[0]
    n = Q[L.HEAP_N] - 1
    Q[L.HEAP_N] = n
    if n > 0:
        last = heap[n]
        i = 0
        while True:
            child = 2 * i + 1
            if child >= n:
                break
            if child + 1 < n and _earlier(slot_time, slot_key, heap[child + 1], heap[child]):
                child += 1
            if _earlier(slot_time, slot_key, last, heap[child]):
                break
            heap[i] = heap[child]
            i = child
        heap[i] = last
    free[Q[L.FREE_N]] = top
    Q[L.FREE_N] += 1
    return top
