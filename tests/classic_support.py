"""Shared fixtures of the classic-API tests: a fresh, headless PGE session per test."""

from __future__ import annotations

import pytest

import pge
from pge.classic import reset


@pytest.fixture
def session(monkeypatch):
    """A fresh headless pge session (PGE_HEADLESS=1), reset again afterwards; yields the pge module."""
    monkeypatch.setenv("PGE_HEADLESS", "1")
    reset()
    yield pge
    reset()


def walls(thickness: float = 0.01, colour=None):
    """Four fixed boxes lining the unit square: floor, ceiling, left, right."""
    colour = colour or pge.rgb(0.5, 0.3, 0.1)
    t = thickness
    return [
        pge.box(0.0, 0.0, 1.0, t, colour).fix(),
        pge.box(0.0, 1.0 - t, 1.0, t, colour).fix(),
        pge.box(0.0, 0.0, t, 1.0, colour).fix(),
        pge.box(1.0 - t, 0.0, t, 1.0, colour).fix(),
    ]
