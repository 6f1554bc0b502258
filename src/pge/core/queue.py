"""The event queue: a binary heap of event slots with lazy invalidation.

A slot holds an event's five ints of data (``slot_data``); the heap holds slot
numbers ordered by ``(time, key, slot)``, and keeps each entry's time and key
beside it (``heap_time``, ``heap_key``, indexed by heap position), so that
sifting compares neighbouring memory and never reads a slot. The key carries
the event kind in its top bits, so equal times pop in kind order (see
``pge.core.layout``), and for a collision the two body ids, smaller first.
Entries are never removed early: each carries the invalidation counters of
its bodies and is dropped when popped if one has moved on.
"""

from __future__ import annotations

from pge._jit_cache import njit

from pge.core import layout as L


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
    heap = S.heap
    heap_time = S.heap_time
    heap_key = S.heap_key
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
        parent = (i - 1) >> 1
        if _before(heap_time[parent], heap_key[parent], heap[parent], t, key, slot):
            break
        heap[i] = heap[parent]
        heap_time[i] = heap_time[parent]
        heap_key[i] = heap_key[parent]
        i = parent
    heap[i] = slot
    heap_time[i] = t
    heap_key[i] = key


@njit(cache=True, inline="always")
def pop_earliest(S):
    """Remove the earliest entry from the heap, put its slot back on the free list, and
    return ``(slot, time, key)``.

    The slot's data stay readable until the next ``push``.
    """
    Q = S.Q
    heap = S.heap
    heap_time = S.heap_time
    heap_key = S.heap_key
    free = S.free
    top = heap[0]
    top_time = heap_time[0]
    top_key = heap_key[0]
    n = Q[L.HEAP_N] - 1
    Q[L.HEAP_N] = n
    if n > 0:
        last = heap[n]
        last_time = heap_time[n]
        last_key = heap_key[n]
        i = 0
        while True:
            child = 2 * i + 1
            if child >= n:
                break
            right = child + 1
            if right < n and _before(heap_time[right], heap_key[right], heap[right], heap_time[child], heap_key[child], heap[child]):
                child = right
            if _before(last_time, last_key, last, heap_time[child], heap_key[child], heap[child]):
                break
            heap[i] = heap[child]
            heap_time[i] = heap_time[child]
            heap_key[i] = heap_key[child]
            i = child
        heap[i] = last
        heap_time[i] = last_time
        heap_key[i] = last_key
    free[Q[L.FREE_N]] = top
    Q[L.FREE_N] += 1
    return top, top_time, top_key
