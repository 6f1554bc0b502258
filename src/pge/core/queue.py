"""The event queue: a four-ary heap of event slots with lazy invalidation.

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
"""

from __future__ import annotations

from pge._jit_cache import njit

from pge.core import layout as L

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
