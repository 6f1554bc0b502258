"""The uniform grid: moving bodies in per-cell linked lists, fixed bodies in static lists.

A moving body sits in the cell holding its swept box's lower-left corner;
cells are at least as wide as any moving box, so every box overlapping a
query box has its corner in the query's cells or one row or column below.
Fixed bodies are listed in every cell their box covers (``static_start`` /
``static_items``, rebuilt from Python when fixed bodies change). Positions
outside the grid are clamped to the border cells, which keeps it sound.
"""

from __future__ import annotations

from pge._jit_cache import njit

from pge.core import layout as L
from pge.core.prefetch import prefetch_row


@njit(cache=True, inline="always")
def cell_index(P, value, origin, count):
    """Clamped cell index along one axis."""
    f = (value - origin) * P[L.INV_CELL]
    if not f > 0.0:
        return 0
    if f >= count - 1:
        return count - 1
    return int(f)


@njit(cache=True, inline="always")
def unlink(S, i):
    """Take moving body ``i`` out of its cell's list (no-op if it is in none)."""
    I = S.I
    head = S.head
    c = I[i, L.CELL]
    if c < 0:
        return
    before = I[i, L.PREV]
    after = I[i, L.NEXT]
    if before >= 0:
        I[before, L.NEXT] = after
    else:
        head[c] = after
    if after >= 0:
        I[after, L.PREV] = before
    I[i, L.CELL] = -1


@njit(cache=True, inline="always")
def file_in_cell(S, i):
    """Put moving body ``i`` in the cell of its box's lower-left corner."""
    F = S.F
    I = S.I
    P = S.P
    Q = S.Q
    head = S.head
    c = cell_index(P, F[i, L.BOX_X0], P[L.GRID_X0], Q[L.GRID_NX]) * Q[L.GRID_NY] + cell_index(
        P, F[i, L.BOX_Y0], P[L.GRID_Y0], Q[L.GRID_NY]
    )
    if c == I[i, L.CELL]:
        return
    unlink(S, i)
    first = head[c]
    I[i, L.NEXT] = first
    I[i, L.PREV] = -1
    if first >= 0:
        I[first, L.PREV] = i
    head[c] = i
    I[i, L.CELL] = c


@njit(cache=True)
def gather(S, i, pad=0.0):
    """Write into ``scratch`` every body whose box may overlap body ``i``'s box grown by
    ``pad`` on every side; return how many.

    Moving bodies come from the lists of the box's cells and of one more row
    and column below; fixed bodies (only for a moving ``i``) from the static
    lists, de-duplicated by stamp.
    """
    F = S.F
    I = S.I
    P = S.P
    Q = S.Q
    head = S.head
    static_start = S.static_start
    static_items = S.static_items
    scratch = S.scratch
    stamp = Q[L.STAMP_COUNTER] + 1
    Q[L.STAMP_COUNTER] = stamp
    nx = Q[L.GRID_NX]
    ny = Q[L.GRID_NY]
    ix0 = cell_index(P, F[i, L.BOX_X0] - pad, P[L.GRID_X0], nx) - 1
    iy0 = cell_index(P, F[i, L.BOX_Y0] - pad, P[L.GRID_Y0], ny) - 1
    ix1 = cell_index(P, F[i, L.BOX_X1] + pad, P[L.GRID_X0], nx)
    iy1 = cell_index(P, F[i, L.BOX_Y1] + pad, P[L.GRID_Y0], ny)
    if ix0 < 0:
        ix0 = 0
    if iy0 < 0:
        iy0 = 0
    moving = I[i, L.FIXED] == 0
    # Each cell's list is walked one row after the other; their first rows are asked for
    # together first, so that the walks start without waiting each in turn.
    for ix in range(ix0, ix1 + 1):
        for iy in range(iy0, iy1 + 1):
            j = head[ix * ny + iy]
            if j >= 0:
                prefetch_row(I, j)
    count = 0
    for ix in range(ix0, ix1 + 1):
        for iy in range(iy0, iy1 + 1):
            c = ix * ny + iy
            j = head[c]
            while j >= 0:
                if j != i:
                    scratch[count] = j
                    count += 1
                    # its box is read next (``predict``): the load overlaps the list's walk
                    prefetch_row(F, j)
                j = I[j, L.NEXT]
            if moving:
                for k in range(static_start[c], static_start[c + 1]):
                    j = static_items[k]
                    if I[j, L.STAMP] != stamp and j != i:
                        I[j, L.STAMP] = stamp
                        scratch[count] = j
                        count += 1
    return count


@njit(cache=True)
def gather_all(S, i):
    """Every body ``gather`` could ever return for body ``i``, ignoring the cells.

    Writes into ``scratch`` each other body filed in the grid (the moving ones)
    and, for a moving ``i``, each live fixed body; returns how many. This is the
    all-pairs candidate list that ``World.broadphase = {"grid": False}`` asks for,
    to measure what the grid saves; it is a superset of ``gather``'s, so the
    predictions (and the events) are the same.
    """
    I = S.I
    Q = S.Q
    scratch = S.scratch
    # Bump the stamp as gather does, so that code reading stamps sees the same state.
    Q[L.STAMP_COUNTER] += 1
    moving = I[i, L.FIXED] == 0
    count = 0
    for j in range(I.shape[0]):
        if j == i or I[j, L.ALIVE] == 0:
            continue
        if I[j, L.CELL] >= 0 or (moving and I[j, L.FIXED] != 0):
            scratch[count] = j
            count += 1
    return count
