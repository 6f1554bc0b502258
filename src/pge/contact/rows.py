"""The island step's contact rows: one row per contact point, its columns after the
manifold's, and the small helpers that read and write them.

A row starts as a manifold row (``pge.contact.manifold``: point, normal, separation, feature
key; ``_points_at`` appends a pair's, chosen by the two bodies' shapes); the step adds its
lever arms, effective masses, targets and impulses, and per pair of bodies what its sweeps
use again and again (on the pair's first row, ``_pair_constants``). ``pairs`` holds, per
row, the two bodies' local indices in the island (-1: a fixed body) and their ids; a pair's
one or two points are adjacent rows. Every stage of the step (``pge.contact.island``) and
the modules it calls (``solve``, ``energy``, ``arcs``, ``pushout``) work on these rows.
"""

from __future__ import annotations

from pge._jit_cache import njit
from pge.contact.manifold import (
    NCOLUMNS,
    NX,
    NY,
    circle_circle_points,
    circle_polygon_points,
    polygon_polygon_points,
)
from pge.core import layout as L
from pge.core.tuning import (
    FACE_DIP,
    FACE_HYSTERESIS,
)

# a body's ``KIND`` when it is a circle (``pge.toi.CIRCLE``)
CIRCLE = 0
# columns of the solver's contact rows, after the manifold's
RAX, RAY, RBX, RBY, KN, KT, TARGET, LAMBDA_N, LAMBDA_T, MU, IMPACT = range(NCOLUMNS, NCOLUMNS + 11)
# ... each row's two bodies' inverse mass and inertia (the second's unused where it is fixed)
MA, IA, MB, IB = range(NCOLUMNS + 11, NCOLUMNS + 15)
# ... and on a pair's first row, what its sweeps use again and again: the lever arms of its
# friction (the midpoint of its two points, or its one point), the effective mass along the
# tangent there, and its two points' normal coupling ``K12`` and ``DET = K11 K22 - K12^2``
FAX, FAY, FBX, FBY, KF, K12, DET = range(NCOLUMNS + 15, NCOLUMNS + 22)
# ... and what a turning body's arc adds to a point's separation at the step's end beyond the
# straight-line motion of its contact point where it is at mid-step (``_midstep_rows``)
ARC = NCOLUMNS + 22
# ... and its point's normal speed now where the contact is now, before a turning pair's rows
# move to mid-step (there a turning body's point may close where the contact does not)
APPROACH = NCOLUMNS + 23
# ... and the most a push-out's lift may close its point (a speed, at most 0; -inf where the
# straight line is the motion) so that its gap on the step's solved motion stays above its
# floor at the step's instants (``_solved_arcs``; the straight line's own: ``_lift_floor``)
CLOSABLE = NCOLUMNS + 24
# ... and the least lift speed at its point that its gaps inside the step ask for, where the
# push-out holds a turning pair's point at the step's end in a row of its own (0 where they
# ask for none; ``_solved_arcs``)
ASKED = NCOLUMNS + 25
NSOLVE = NCOLUMNS + 26


@njit(cache=True)
def _points_at(F, I, OL, i, xi, yi, si, j, xj, yj, sj, margin, rows, count):
    """Append the manifold of bodies ``i`` at ``(xi, yi)`` and ``j`` at ``(xj, yj)`` (normal
    from j to i), their outlines (polygons) the rows of ``OL`` from ``si`` and ``sj``."""
    if I[i, L.KIND] == CIRCLE:
        if I[j, L.KIND] == CIRCLE:
            return circle_circle_points(xi, yi, F[i, L.RADIUS], xj, yj, F[j, L.RADIUS], margin, rows, count)
        return circle_polygon_points(xi, yi, F[i, L.RADIUS], xj, yj, OL, sj, I[j, L.OUTLINE_N], False, margin, rows,
                                     count)
    if I[j, L.KIND] == CIRCLE:
        return circle_polygon_points(xj, yj, F[j, L.RADIUS], xi, yi, OL, si, I[i, L.OUTLINE_N], True, margin, rows,
                                     count)
    scale = F[i, L.REACH] + F[j, L.REACH]
    return polygon_polygon_points(xi, yi, OL, si, I[i, L.OUTLINE_N], xj, yj, sj, I[j, L.OUTLINE_N], margin,
                                  FACE_HYSTERESIS * scale, FACE_DIP * scale,
                                  rows, count)


@njit(cache=True, inline="always")
def _lever_arms(rows, r, rax, ray, rbx, rby):
    """Set row ``r``'s lever arms and, from them, its normal's and tangent's effective masses
    (its normal and its bodies' inverse masses and inertias already set)."""
    nx = rows[r, NX]
    ny = rows[r, NY]
    rows[r, RAX] = rax
    rows[r, RAY] = ray
    rows[r, RBX] = rbx
    rows[r, RBY] = rby
    ran = rax * ny - ray * nx
    rbn = rbx * ny - rby * nx
    rat = rax * nx + ray * ny
    rbt = rbx * nx + rby * ny
    rows[r, KN] = rows[r, MA] + rows[r, MB] + rows[r, IA] * ran * ran + rows[r, IB] * rbn * rbn
    rows[r, KT] = rows[r, MA] + rows[r, MB] + rows[r, IA] * rat * rat + rows[r, IB] * rbt * rbt


@njit(cache=True, inline="always")
def _pair_end(pairs, count, c):
    """The row after the last of the pair whose first row is ``c`` (a pair's rows are
    adjacent)."""
    d = c + 1
    while d < count and pairs[d, 2] == pairs[c, 2] and pairs[d, 3] == pairs[c, 3]:
        d += 1
    return d


@njit(cache=True)
def _pair_constants(rows, pairs, count):
    """Fill each pair's first row with its friction's lever arms and effective mass and its
    two points' normal coupling (``FAX`` to ``DET``), from the rows' arms and masses."""
    c = 0
    while c < count:
        pair = _in_block(pairs, count, c)
        if pair:
            rax, ray, rbx, rby = _midpoint(rows, c)
        else:
            rax, ray, rbx, rby = rows[c, RAX], rows[c, RAY], rows[c, RBX], rows[c, RBY]
        nx = rows[c, NX]
        ny = rows[c, NY]
        tx = -ny
        ty = nx
        rat = rax * ty - ray * tx
        rbt = rbx * ty - rby * tx
        rows[c, FAX] = rax
        rows[c, FAY] = ray
        rows[c, FBX] = rbx
        rows[c, FBY] = rby
        rows[c, KF] = rows[c, MA] + rows[c, MB] + rows[c, IA] * rat * rat + rows[c, IB] * rbt * rbt
        if pair:
            d = c + 1
            k12 = rows[c, MA] + rows[c, MB]
            k12 += rows[c, IA] * (rows[c, RAX] * ny - rows[c, RAY] * nx) * (rows[d, RAX] * ny - rows[d, RAY] * nx)
            k12 += rows[c, IB] * (rows[c, RBX] * ny - rows[c, RBY] * nx) * (rows[d, RBX] * ny - rows[d, RBY] * nx)
            rows[c, K12] = k12
            rows[c, DET] = rows[c, KN] * rows[d, KN] - k12 * k12
            c += 2
        else:
            c += 1


@njit(cache=True, inline="always")
def _push_at(rows, vel, pairs, c, jx, jy, rax, ray, rbx, rby):
    """Apply the impulse ``(jx, jy)`` at lever arms ``ra`` (first body) and ``rb`` (second,
    which takes it reversed; a fixed body does not move) to the velocities ``vel`` of row
    ``c``'s two bodies."""
    ka = pairs[c, 0]
    vel[ka, 0] += jx * rows[c, MA]
    vel[ka, 1] += jy * rows[c, MA]
    vel[ka, 2] += (rax * jy - ray * jx) * rows[c, IA]
    kb = pairs[c, 1]
    if kb >= 0:
        vel[kb, 0] -= jx * rows[c, MB]
        vel[kb, 1] -= jy * rows[c, MB]
        vel[kb, 2] -= (rbx * jy - rby * jx) * rows[c, IB]


@njit(cache=True, inline="always")
def _push(rows, vel, pairs, c, jn, jt):
    """Apply impulse ``jn`` along the normal and ``jt`` along the tangent at row ``c``'s point."""
    nx = rows[c, NX]
    ny = rows[c, NY]
    _push_at(rows, vel, pairs, c, jn * nx - jt * ny, jn * ny + jt * nx, rows[c, RAX], rows[c, RAY], rows[c, RBX],
             rows[c, RBY])


@njit(cache=True, inline="always")
def _relative_at(vel, pairs, c, rax, ray, rbx, rby):
    """Relative velocity in ``vel`` (first body minus second) of row ``c``'s bodies at lever arms
    ``ra`` and ``rb``."""
    ka = pairs[c, 0]
    kb = pairs[c, 1]
    ux = vel[ka, 0] - vel[ka, 2] * ray
    uy = vel[ka, 1] + vel[ka, 2] * rax
    if kb >= 0:
        ux -= vel[kb, 0] - vel[kb, 2] * rby
        uy -= vel[kb, 1] + vel[kb, 2] * rbx
    return ux, uy


@njit(cache=True, inline="always")
def _relative(vel, pairs, rows, c):
    """Relative velocity in ``vel`` of row ``c``'s contact point (first body minus second)."""
    return _relative_at(vel, pairs, c, rows[c, RAX], rows[c, RAY], rows[c, RBX], rows[c, RBY])


@njit(cache=True, inline="always")
def _midpoint(rows, c):
    """Lever arms of the midpoint of rows ``c`` and ``c + 1`` (a pair's two points)."""
    d = c + 1
    return (
        0.5 * (rows[c, RAX] + rows[d, RAX]),
        0.5 * (rows[c, RAY] + rows[d, RAY]),
        0.5 * (rows[c, RBX] + rows[d, RBX]),
        0.5 * (rows[c, RBY] + rows[d, RBY]),
    )


@njit(cache=True)
def _in_block(pairs, count, first):
    """Whether row ``first + 1`` is the second point of ``first``'s pair."""
    return first + 1 < count and pairs[first + 1, 2] == pairs[first, 2] and pairs[first + 1, 3] == pairs[first, 3]
