"""Borrowed arrays (pge.core.borrow): the event loop's state and the contact solve's arrays,
the same arrays without owner records."""

from __future__ import annotations

import sys

import numpy as np
import pytest
from numba import njit
from numba.core.errors import TypingError

from pge.core.borrow import borrowed, borrowed_array


@njit
def _write_through(S):
    B = borrowed(S)
    B[0][1, 2] = 7.5
    B[1][3] = -4
    return B[0].shape[0], B[0].shape[1], B[1].shape[0], B[0][1, 2] + B[1][3]


@njit
def _borrow_in_loop(S, rounds):
    # Borrowed views made and dropped many times: nothing may be freed or leaked on the way.
    total = 0.0
    for k in range(rounds):
        B = borrowed(S)
        total += B[0][k % B[0].shape[0], 0]
    return total


@njit
def _scaled_rows(vel, rows):
    # passed through a helper call per row, as the contact solve's sweeps do
    total = 0.0
    for k in range(rows.shape[0]):
        total += _row_push(borrowed_array(vel), borrowed_array(rows), k)
    return total


@njit
def _row_push(vel, rows, k):
    vel[k % vel.shape[0]] += rows[k, 0]
    return vel[k % vel.shape[0]]


def test_a_borrowed_array_is_the_callers_array_and_keeps_its_owner():
    vel = np.zeros(3)
    rows = np.arange(10.0).reshape(5, 2).copy()
    references = sys.getrefcount(vel), sys.getrefcount(rows)
    total = _scaled_rows(vel, rows)
    assert vel.tolist() == [0.0 + 6.0, 2.0 + 8.0, 4.0]
    assert total == 0.0 + 2.0 + 4.0 + 6.0 + 10.0
    assert (sys.getrefcount(vel), sys.getrefcount(rows)) == references
    assert vel.flags.owndata and rows.flags.owndata


def test_only_arrays_can_be_borrowed_one_at_a_time():
    @njit
    def scalar(x):
        return borrowed_array(x)

    with pytest.raises(TypingError):
        scalar(1.0)


def test_borrowed_arrays_are_the_callers_arrays():
    F = np.zeros((4, 3))
    I = np.zeros(5, dtype=np.int64)
    assert _write_through((F, I)) == (4, 3, 5, 3.5)
    assert F[1, 2] == 7.5 and I[3] == -4
    assert F.sum() == 7.5 and I.sum() == -4


def test_borrowing_keeps_the_arrays_alive_and_whole():
    F = np.arange(12.0).reshape(4, 3).copy()
    I = np.zeros(2, dtype=np.int64)
    S = (F, I)
    _borrow_in_loop(S, 1)
    references = sys.getrefcount(F), sys.getrefcount(I)
    assert _borrow_in_loop(S, 1000) == sum(F[k % 4, 0] for k in range(1000))
    assert (sys.getrefcount(F), sys.getrefcount(I)) == references
    assert F.flags.owndata and np.array_equal(F, np.arange(12.0).reshape(4, 3))


def test_only_tuples_of_arrays_can_be_borrowed():
    @njit
    def scalar_member(S):
        return borrowed(S)[0]

    with pytest.raises(TypingError):
        scalar_member((np.zeros(2), 1.0))
