"""Collision response: restitution rules and the normal impulse.

Bodies translate only (rotation physics comes later), so a contact exchanges
an impulse ``j`` along the unit contact normal ``n`` (pointing from body b
towards body a): ``v_a += j n / m_a`` and ``v_b -= j n / m_b`` with
``j = -(1 + e) (v_a - v_b) . n / (1 / m_a + 1 / m_b)``. Fixed bodies have
``1 / m = 0``. Momentum is conserved by construction and, with ``e = 1``, so
is kinetic energy.
"""

from __future__ import annotations

import math
from typing import Callable

__all__ = ["RESTITUTION_RULES", "restitution_rule", "normal_impulse"]

#: How the elasticities of two touching bodies combine into one restitution
#: coefficient. Every rule returns ``e`` for two bodies of equal elasticity
#: ``e`` and lies between the two values, so energy can never increase.
RESTITUTION_RULES: dict[str, Callable[[float, float], float]] = {
    "min": min,
    "max": max,
    "mean": lambda a, b: 0.5 * (a + b),
    "geometric": lambda a, b: a if a == b else math.sqrt(a * b),
}


def restitution_rule(name: str) -> Callable[[float, float], float]:
    """The combining function called ``name``; ValueError naming the choices otherwise."""
    try:
        return RESTITUTION_RULES[name]
    except (KeyError, TypeError):
        raise ValueError(
            f"restitution rule must be one of {sorted(RESTITUTION_RULES)}, got {name!r}"
        ) from None


def normal_impulse(normal_speed: float, inv_mass_a: float, inv_mass_b: float, restitution: float) -> float:
    """Magnitude of the impulse along the normal for an approach speed ``normal_speed`` < 0.

    ``normal_speed`` is ``(v_a - v_b) . n``. The result is positive for an
    approaching pair and makes the separation speed ``-restitution *
    normal_speed``.
    """
    return -(1.0 + restitution) * normal_speed / (inv_mass_a + inv_mass_b)
