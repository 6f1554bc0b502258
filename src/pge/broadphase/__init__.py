"""Broad phase: swept bounds and the conservative short-circuit test.

The grid that holds the swept boxes lives with the event loop in
``pge.core.engine`` (its cells are linked lists in the body arrays).
"""

from pge.broadphase.bounds import cannot_touch_before, lecture_cannot_touch, swept_range, travel_horizon

__all__ = ["cannot_touch_before", "lecture_cannot_touch", "swept_range", "travel_horizon"]
