"""The island step's contact solve: impulses on the rows' points that meet their targets
under Coulomb friction.

Each stage of the step (impacts, forces, push-out; ``pge.contact.island``) is a
complementarity problem (the push-out without friction), solved by sequential impulses
(projected Gauss-Seidel: ``_solve``, ``_sweeps``) and, where a few sweeps do not converge,
exactly (``_exact``): on the sweeps' active set (one linear solve, and a few more where
principal pivoting moves a wrong set), else by Lemke's method (``pge.numerics.lcp``) on
Stewart and Trinkle's formulation.
"""

from __future__ import annotations

import math

import numpy as np

from pge._jit_cache import njit
from pge.contact.manifold import (
    NX,
    NY,
    PX,
    PY,
)
from pge.contact.rows import (
    DET,
    FAX,
    FAY,
    FBX,
    FBY,
    K12,
    KF,
    KN,
    KT,
    LAMBDA_N,
    LAMBDA_T,
    MU,
    RAX,
    RAY,
    RBX,
    RBY,
    TARGET,
    _in_block,
    _push,
    _push_at,
    _relative,
    _relative_at,
)
from pge.core import layout as L
from pge.core.borrow import borrowed_array
from pge.numerics.lcp import lemke
from pge.core.tuning import (
    EXACT_AFTER,
    LCP_LIMIT,
    SET_TRIES,
    SOLVE_STALL,
    SOLVE_TOLERANCE,
    STALL_GAIN,
)

# what an active set gave (``_active_set``)
SET_SOLVED, SET_MOVED, SET_WRONG = range(3)


@njit(cache=True, inline="always")
def _friction(vel, rows, pairs, c):
    """Row ``c``'s friction impulse, within the cone of its normal impulse; returns its change."""
    if not (rows[c, KT] > 0.0 and rows[c, MU] > 0.0):
        return 0.0
    ux, uy = _relative(vel, pairs, rows, c)
    ut = -ux * rows[c, NY] + uy * rows[c, NX]
    limit = rows[c, MU] * rows[c, LAMBDA_N]
    old = rows[c, LAMBDA_T]
    new = min(max(old - ut / rows[c, KT], -limit), limit)
    rows[c, LAMBDA_T] = new
    _push(rows, vel, pairs, c, 0.0, new - old)
    return abs(new - old)


@njit(cache=True, inline="always")
def _normal(vel, rows, pairs, c):
    """Row ``c``'s normal impulse alone (never pulling); returns its change."""
    if not rows[c, KN] > 0.0:
        return 0.0
    ux, uy = _relative(vel, pairs, rows, c)
    un = ux * rows[c, NX] + uy * rows[c, NY]
    old = rows[c, LAMBDA_N]
    new = max(old + (rows[c, TARGET] - un) / rows[c, KN], 0.0)
    rows[c, LAMBDA_N] = new
    _push(rows, vel, pairs, c, new - old, 0.0)
    return abs(new - old)


@njit(cache=True, inline="always")
def _friction_pair(vel, rows, pairs, c):
    """The friction of a pair's two points (rows ``c`` and ``c + 1``) as one impulse at their
    midpoint, within the cone of their summed normal impulses: the two points' tangential
    constraints are one (the pair slides or sticks as a whole), and solving them apart makes
    the sweeps fight over how to share it. Kept in row ``c``; returns its change."""
    d = c + 1
    tx = -rows[c, NY]
    ty = rows[c, NX]
    mu = rows[c, MU]
    kt = rows[c, KF]
    if not (kt > 0.0 and mu > 0.0):
        return 0.0
    rax, ray, rbx, rby = rows[c, FAX], rows[c, FAY], rows[c, FBX], rows[c, FBY]
    ux, uy = _relative_at(vel, pairs, c, rax, ray, rbx, rby)
    ut = ux * tx + uy * ty
    limit = mu * (rows[c, LAMBDA_N] + rows[d, LAMBDA_N])
    old = rows[c, LAMBDA_T] + rows[d, LAMBDA_T]
    new = min(max(old - ut / kt, -limit), limit)
    rows[c, LAMBDA_T] = new
    rows[d, LAMBDA_T] = 0.0
    _push_at(rows, vel, pairs, c, (new - old) * tx, (new - old) * ty, rax, ray, rbx, rby)
    return abs(new - old)


@njit(cache=True, inline="always")
def _into_cone(vel, rows, pairs, c, size):
    """Bring the friction of the pair at row ``c`` (``size`` points) back into the cone of
    its normal impulses, which the normal update that follows the friction update may have
    shrunk (a warm start that pressed harder than the step needs: gravity switched off);
    left outside, a sweep that changes nothing more would end with friction acting where
    nothing presses. Returns its change."""
    mu = rows[c, MU]
    if not mu > 0.0:
        return 0.0
    pressed = rows[c, LAMBDA_N] + (rows[c + 1, LAMBDA_N] if size == 2 else 0.0)
    limit = mu * pressed
    old = rows[c, LAMBDA_T]
    if abs(old) <= limit:
        return 0.0
    new = limit if old > 0.0 else -limit
    rows[c, LAMBDA_T] = new
    tx = -rows[c, NY]
    ty = rows[c, NX]
    if size == 2:
        _push_at(rows, vel, pairs, c, (new - old) * tx, (new - old) * ty, rows[c, FAX], rows[c, FAY], rows[c, FBX],
                 rows[c, FBY])
    else:
        _push(rows, vel, pairs, c, 0.0, new - old)
    return abs(new - old)


@njit(cache=True, inline="always")
def _normal_pair(vel, rows, pairs, c):
    """The normal impulses of rows ``c`` and ``c + 1`` (two points of one pair, sharing a
    normal) solved together: the 2x2 complementarity problem ``u = K x + b >= target``,
    ``x >= 0``, ``x (u - target) = 0``, by trying its four cases (both pushing, one, none).
    Falls back to the rows one at a time when ``K`` is too ill-conditioned or no case fits
    (rounding). Returns the largest change."""
    d = c + 1
    nx = rows[c, NX]
    ny = rows[c, NY]
    k11 = rows[c, KN]
    k22 = rows[d, KN]
    k12 = rows[c, K12]
    det = rows[c, DET]
    if not (k11 > 0.0 and k22 > 0.0 and det > 1e-6 * k11 * k22):
        return max(_normal(vel, rows, pairs, c), _normal(vel, rows, pairs, d))
    ux, uy = _relative(vel, pairs, rows, c)
    u1 = ux * nx + uy * ny
    ux, uy = _relative(vel, pairs, rows, d)
    u2 = ux * nx + uy * ny
    a1 = rows[c, LAMBDA_N]
    a2 = rows[d, LAMBDA_N]
    # u - target as a function of the new impulses x: K x + b
    b1 = u1 - rows[c, TARGET] - (k11 * a1 + k12 * a2)
    b2 = u2 - rows[d, TARGET] - (k12 * a1 + k22 * a2)
    x1 = (-k22 * b1 + k12 * b2) / det
    x2 = (k12 * b1 - k11 * b2) / det
    if not (x1 >= 0.0 and x2 >= 0.0):
        x1 = -b1 / k11
        x2 = 0.0
        if not (x1 >= 0.0 and k12 * x1 + b2 >= 0.0):
            x1 = 0.0
            x2 = -b2 / k22
            if not (x2 >= 0.0 and k12 * x2 + b1 >= 0.0):
                x1 = 0.0
                x2 = 0.0
                if not (b1 >= 0.0 and b2 >= 0.0):
                    return max(_normal(vel, rows, pairs, c), _normal(vel, rows, pairs, d))
    rows[c, LAMBDA_N] = x1
    rows[d, LAMBDA_N] = x2
    _push(rows, vel, pairs, c, x1 - a1, 0.0)
    _push(rows, vel, pairs, d, x2 - a2, 0.0)
    return max(abs(x1 - a1), abs(x2 - a2))


@njit(cache=True)
def _solve(F, vel, rows, pairs, count, speed, down_x, down_y, most, lemke_limit):
    """Sequential impulses over the pairs: the warm start, then sweeps, each pair taking
    friction at its points (within the cone of their normal impulses) then its normal
    impulses (never pulling; a pair's two points together, ``_normal_pair``), until no
    point's speed is off by more than ``SOLVE_TOLERANCE`` times ``speed`` (``_residual``).
    Sweeps converge slowly on tall stacks and piles (their rate falls with the square of the
    height), so after ``EXACT_AFTER`` that did not the problem is solved exactly
    (``_exact``, by Lemke's method too only for at most ``lemke_limit`` unknowns); where that
    cannot be done, the sweeps go on, for at most ``most`` in all. Returns the number of
    sweeps."""
    starts, sizes, blocks = _blocks(pairs, count)
    # Sweep the pairs in order of height against the acceleration (bottom to top, then back):
    # in a stack, a load then passes all the way down, and the reactions all the way up, in
    # one pair of sweeps, where an arbitrary order needs many.
    height = np.empty(blocks)
    for b in range(blocks):
        c = starts[b]
        height[b] = -(rows[c, PX] * down_x + rows[c, PY] * down_y)
    order = np.argsort(height)
    starts = starts[order]
    sizes = sizes[order]
    # The sweeps pass vel, rows and pairs (this call's arguments, which its caller keeps
    # alive) through small inlined helpers a few times per pair per sweep: borrowed, they
    # count no references there.
    return _sweeps(F, borrowed_array(vel), borrowed_array(rows), borrowed_array(pairs), count, starts, sizes, blocks,
                   speed, most, lemke_limit)


@njit(cache=True)
def _sweeps(F, vel, rows, pairs, count, starts, sizes, blocks, speed, most, lemke_limit):
    """``_solve``'s warm start and sweeps over the pairs in the order ``starts`` (first rows)
    and ``sizes`` (points); ``vel``, ``rows`` and ``pairs`` are borrowed."""
    for b in range(blocks):
        c = starts[b]
        _push(rows, vel, pairs, c, rows[c, LAMBDA_N], 0.0)
        if sizes[b] == 2:
            d = c + 1
            _push(rows, vel, pairs, d, rows[d, LAMBDA_N], 0.0)
            total = rows[c, LAMBDA_T] + rows[d, LAMBDA_T]
            limit = rows[c, MU] * (rows[c, LAMBDA_N] + rows[d, LAMBDA_N])
            total = min(max(total, -limit), limit)
            rows[c, LAMBDA_T] = total
            rows[d, LAMBDA_T] = 0.0
            _push_at(rows, vel, pairs, c, -total * rows[c, NY], total * rows[c, NX], rows[c, FAX], rows[c, FAY],
                     rows[c, FBX], rows[c, FBY])
        else:
            limit = rows[c, MU] * rows[c, LAMBDA_N]
            rows[c, LAMBDA_T] = min(max(rows[c, LAMBDA_T], -limit), limit)
            _push(rows, vel, pairs, c, 0.0, rows[c, LAMBDA_T])
    warm = rows[:count, LAMBDA_N:LAMBDA_T + 1].copy()  # the last step's answer, as started
    best = math.inf
    best_at = 0
    for sweep in range(most):
        change = 0.0
        for q in range(blocks):
            # Sweeps alternate direction (symmetric Gauss-Seidel): a load passes down a
            # stack, and a reaction up it, within one pair of sweeps.
            b = q if sweep % 2 == 0 else blocks - 1 - q
            c = starts[b]
            if sizes[b] == 2:
                change = max(change, _friction_pair(vel, rows, pairs, c))
                change = max(change, _normal_pair(vel, rows, pairs, c))
            else:
                change = max(change, _friction(vel, rows, pairs, c))
                change = max(change, _normal(vel, rows, pairs, c))
            change = max(change, _into_cone(vel, rows, pairs, c, sizes[b]))
        residual = _residual(vel, rows, pairs, count, starts, sizes, blocks) if change != 0.0 else 0.0
        if residual <= SOLVE_TOLERANCE * speed:
            return sweep + 1
        if sweep == EXACT_AFTER - 1 and _exact(F, vel, rows, pairs, count, starts, sizes, blocks, speed, warm, lemke_limit):
            return sweep + 1
        # On a pile too big for the exact finish, sweeps with friction stall short of the
        # tolerance (the worst point's error wanders instead of falling): once SOLVE_STALL
        # sweeps in a row have not brought it below STALL_GAIN of its lowest, more buy nothing.
        if residual < STALL_GAIN * best:
            best = residual
            best_at = sweep
        elif sweep - best_at >= SOLVE_STALL:
            return sweep + 1
    return most


@njit(cache=True, inline="always")
def _arms(rows, c):
    """Lever arms of the friction of the pair whose first row is ``c``: its point, or the
    midpoint of its two (``_pair_constants``)."""
    return rows[c, FAX], rows[c, FAY], rows[c, FBX], rows[c, FBY]


@njit(cache=True)
def _directions(F, rows, pairs, count, starts, blocks):
    """The solve's constraint directions: every row's normal, then the friction (tangent at
    the point, or at the midpoint of a pair's two points) of every block with friction.
    Returns ``(ja, jb, body_a, body_b, row, nf)``: each direction's coefficients on its two
    bodies' ``(vx, vy, spin)`` (``jb`` for the second, reversed), their local indices (-1:
    fixed), the row it belongs to, and how many friction directions there are."""
    friction = 0
    for b in range(blocks):
        if rows[starts[b], MU] > 0.0:
            friction += 1
    n = count + friction
    ja = np.zeros((n, 3))
    jb = np.zeros((n, 3))
    body_a = np.empty(n, dtype=np.int64)
    body_b = np.empty(n, dtype=np.int64)
    row = np.empty(n, dtype=np.int64)
    k = 0
    for c in range(count + blocks):
        if c < count:
            r = c
            dx = rows[r, NX]
            dy = rows[r, NY]
            rax, ray, rbx, rby = rows[r, RAX], rows[r, RAY], rows[r, RBX], rows[r, RBY]
        else:
            r = starts[c - count]
            if not rows[r, MU] > 0.0:
                continue
            dx = -rows[r, NY]
            dy = rows[r, NX]
            rax, ray, rbx, rby = _arms(rows, r)
        ja[k, 0] = dx
        ja[k, 1] = dy
        ja[k, 2] = rax * dy - ray * dx
        jb[k, 0] = -dx
        jb[k, 1] = -dy
        jb[k, 2] = -(rbx * dy - rby * dx)
        body_a[k] = pairs[r, 0]
        body_b[k] = pairs[r, 1]
        row[k] = r
        k += 1
    return ja, jb, body_a, body_b, row, friction


@njit(cache=True)
def _operator(F, vel, rows, pairs, count, ja, jb, body_a, body_b, row):
    """The contact problem along the solve's directions: ``W = J M^-1 J^T``, the speeds
    along them with no contact impulse (``base``), the impulses now, and each local body's
    inverse mass and inertia. Returns ``(W, base, impulse, inverse)``."""
    n = ja.shape[0]
    inverse = np.zeros((vel.shape[0], 3))
    for k in range(n):
        for side in range(2):
            x = body_a[k] if side == 0 else body_b[k]
            if x >= 0:
                i = pairs[row[k], 2 + side]
                inverse[x, 0] = F[i, L.INV_MASS]
                inverse[x, 1] = F[i, L.INV_MASS]
                inverse[x, 2] = F[i, L.INV_INERTIA]
    W = np.zeros((n, n))
    speeds = np.zeros(n)
    impulse = np.zeros(n)
    for k in range(n):
        for side in range(2):
            x = body_a[k] if side == 0 else body_b[k]
            if x >= 0:
                for d in range(3):
                    speeds[k] += (ja[k, d] if side == 0 else jb[k, d]) * vel[x, d]
        impulse[k] = rows[row[k], LAMBDA_N] if k < count else rows[row[k], LAMBDA_T]
        for q in range(k + 1):
            total = 0.0
            for sk in range(2):
                xk = body_a[k] if sk == 0 else body_b[k]
                if xk < 0:
                    continue
                for sq in range(2):
                    xq = body_a[q] if sq == 0 else body_b[q]
                    if xq != xk:
                        continue
                    for d in range(3):
                        left = ja[k, d] if sk == 0 else jb[k, d]
                        right = ja[q, d] if sq == 0 else jb[q, d]
                        total += left * inverse[xk, d] * right
            W[k, q] = total
            W[q, k] = total
    base = speeds.copy()
    for k in range(n):
        for q in range(n):
            base[k] -= W[k, q] * impulse[q]
    return W, base, impulse, inverse


@njit(cache=True, inline="always")
def _load(normal, pairs, count, first):
    """The normal impulse (from ``normal``, indexed by row) on the pair whose first row is
    ``first``: one point's, or its two points' together."""
    if _in_block(pairs, count, first):
        return normal[first] + normal[first + 1]
    return normal[first]


@njit(cache=True)
def _cholesky_solve(A, b):
    """Solve ``A x = b`` for symmetric positive definite ``A`` (Cholesky); ``ok`` false when
    a pivot is not positive."""
    m = b.shape[0]
    C = np.zeros((m, m))
    for j in range(m):
        d = A[j, j]
        for k in range(j):
            d -= C[j, k] * C[j, k]
        if not d > 0.0:
            return b, False
        C[j, j] = math.sqrt(d)
        for i in range(j + 1, m):
            e = A[i, j]
            for k in range(j):
                e -= C[i, k] * C[j, k]
            C[i, j] = e / C[j, j]
    y = b.copy()
    for i in range(m):
        for k in range(i):
            y[i] -= C[i, k] * y[k]
        y[i] /= C[i, i]
    for i in range(m - 1, -1, -1):
        for k in range(i + 1, m):
            y[i] -= C[k, i] * y[k]
        y[i] /= C[i, i]
    return y, True


@njit(cache=True)
def _active_set(W, base, rows, pairs, row, count, nf, impulse):
    """The exact answer on the active set of ``impulse`` (the sweeps' or the last step's):
    which points push (``l > 0``), which pairs stick and which slide, and which way. On that
    set the problem is linear: a pushing point's normal speed is its target, a sticking
    pair's sliding speed zero, a sliding pair's friction ``mu`` times its normal impulses
    against the slide (``_set_system``). The answer nearest ``impulse`` among those that
    solve it (``_set_solve``) fixes the share of redundant points (a face on three points, a
    statically indeterminate pile) and leaves the rest exact.

    Returns ``(impulses, state)``: ``SET_SOLVED`` when the answer satisfies every condition
    of the problem (the set was right); ``SET_MOVED`` when it does not, with the next set to
    try (``_next_set``); ``SET_WRONG`` when the set's system cannot be solved."""
    n = count + nf
    unknown, columns, sign, slides = _set_unknowns(rows, pairs, row, count, nf, impulse)
    m = columns.shape[0]
    if m == 0:
        return impulse, SET_WRONG
    A, b = _set_system(W, base, rows, pairs, row, count, nf, unknown, columns, sign)
    start = np.empty(m)
    for j in range(m):
        start[j] = impulse[columns[j]]
    y, ok = _set_solve(A, b, start, slides)
    if not ok:
        return impulse, SET_WRONG
    fresh = np.zeros(n)
    for j in range(m):
        fresh[columns[j]] = y[j]
    for f in range(nf):
        if sign[f] != 0.0:
            first = row[count + f]
            fresh[count + f] = sign[f] * rows[first, MU] * _load(fresh, pairs, count, first)
    speeds = base.copy()
    for k in range(n):
        for q in range(n):
            speeds[k] += W[k, q] * fresh[q]
    moved = _next_set(speeds, np.abs(base).max(), rows, pairs, row, count, nf, unknown, sign, fresh)
    return fresh, SET_MOVED if moved else SET_SOLVED


@njit(cache=True)
def _next_set(speeds, scale, rows, pairs, row, count, nf, unknown, sign, fresh):
    """Check the answer ``fresh`` of an active set (``unknown``, ``sign``: ``_set_unknowns``)
    against every condition of the problem, at the ``speeds`` it gives, and where one fails
    move the set (principal pivoting), in ``fresh`` itself: a point that pulls stops
    pushing, a point without impulse that closes faster than its target pushes, a sticking
    pair whose friction leaves its cone slides, a sliding pair that slides the way its
    friction pushes sticks. Returns whether anything moved. Rounding is tolerated to 1e-9
    of ``scale``, the largest speed without contact impulses."""
    tolerance = 1e-9 * (scale + 1e-300)
    moved = False
    # friction first, against this answer's loads
    side = np.zeros(nf)  # the next set: -1 or 1 slides that way, 0 sticks
    for f in range(nf):
        k = count + f
        first = row[k]
        limit = rows[first, MU] * _load(fresh, pairs, count, first)
        if unknown[k] >= 0:
            if abs(fresh[k]) > limit * (1.0 + 1e-9):
                side[f] = 1.0 if fresh[k] > 0.0 else -1.0
                moved = True
        elif sign[f] != 0.0:
            if sign[f] * speeds[k] > tolerance:
                moved = True
            else:
                side[f] = sign[f]
    largest = 0.0
    for a in range(count):
        largest = max(largest, fresh[a])
    for a in range(count):
        if fresh[a] < 0.0:
            fresh[a] = 0.0
            moved = True
        elif unknown[a] < 0 and speeds[a] < rows[a, TARGET] - tolerance:
            # pushing from next time: any positive start will do, the solve finds its value
            fresh[a] = 1e-12 * largest if largest > 0.0 else 1.0
            moved = True
    # the friction of the next set, within the next loads: at the cone's edge where it
    # slides, strictly inside where it sticks
    for f in range(nf):
        k = count + f
        first = row[k]
        limit = rows[first, MU] * _load(fresh, pairs, count, first)
        if side[f] != 0.0:
            fresh[k] = side[f] * limit
        else:
            fresh[k] = min(max(fresh[k], -0.5 * limit), 0.5 * limit)
    return moved


@njit(cache=True)
def _set_unknowns(rows, pairs, row, count, nf, impulse):
    """The unknowns of the active set of ``impulse``: every pushing point's normal impulse
    and every sticking pair's friction (``unknown[k]``: the unknown of direction ``k``, -1
    for none; ``columns[j]``: the direction of unknown ``j``), the direction each sliding
    pair slides (``sign``, 0 where it sticks or has no friction), and whether any does."""
    n = count + nf
    unknown = -np.ones(n, dtype=np.int64)
    columns = np.empty(n, dtype=np.int64)
    m = 0
    for a in range(count):
        if impulse[a] > 0.0:
            unknown[a] = m
            columns[m] = a
            m += 1
    sign = np.zeros(nf)
    slides = False
    for f in range(nf):
        first = row[count + f]
        limit = rows[first, MU] * _load(impulse, pairs, count, first)
        if abs(impulse[count + f]) < limit * (1.0 - 1e-9):
            unknown[count + f] = m
            columns[m] = count + f
            m += 1
        elif impulse[count + f] != 0.0:
            sign[f] = 1.0 if impulse[count + f] > 0.0 else -1.0
            slides = True
    return unknown, columns[:m], sign, slides


@njit(cache=True)
def _set_system(W, base, rows, pairs, row, count, nf, unknown, columns, sign):
    """The linear problem ``A y = b`` on an active set: row ``e`` says that direction
    ``columns[e]`` reaches its target speed (a point's ``TARGET``, a sticking pair's zero);
    column ``j`` is what unknown ``j`` does to the speeds, a pushing point's normal impulse
    bringing with it the friction ``sign mu`` times it where its pair slides."""
    m = columns.shape[0]
    # the sliding friction direction a point's normal impulse drags along (-1: none)
    drags = -np.ones(count, dtype=np.int64)
    for f in range(nf):
        if sign[f] != 0.0:
            first = row[count + f]
            drags[first] = count + f
            if _in_block(pairs, count, first):
                drags[first + 1] = count + f
    A = np.empty((m, m))
    b = np.empty(m)
    for e in range(m):
        k = columns[e]
        for j in range(m):
            q = columns[j]
            total = W[k, q]
            if q < count and drags[q] >= 0:
                g = drags[q]
                total += sign[g - count] * rows[row[g], MU] * W[k, g]
            A[e, j] = total
        b[e] = (rows[k, TARGET] if k < count else 0.0) - base[k]
    return A, b


@njit(cache=True)
def _set_solve(A, b, start, slides):
    """The solution of ``A y = b`` nearest ``start``, pulled towards it by a tiny ``eps``
    (which only decides directions ``A`` leaves free). Where no pair slides, ``A`` is part
    of ``W`` (symmetric, positive semi-definite): ``(A + eps) y = b + eps start``, one
    Cholesky solve. Else in least squares, ``(A^T A + eps) y = A^T b + eps start``.
    Returns ``(y, ok)``; ``ok`` false when a pivot is not positive."""
    m = b.shape[0]
    if not slides:
        N = A.copy()
        r = b.copy()
        scale = 0.0
        for i in range(m):
            scale = max(scale, N[i, i])
        eps = 1e-12 * scale
    else:
        N = np.empty((m, m))
        r = np.zeros(m)
        scale = 0.0
        for i in range(m):
            for j in range(i + 1):
                total = 0.0
                for e in range(m):
                    total += A[e, i] * A[e, j]
                N[i, j] = total
                N[j, i] = total
            scale = max(scale, N[i, i])
            for e in range(m):
                r[i] += A[e, i] * b[e]
        eps = 1e-13 * scale
    for i in range(m):
        N[i, i] += eps
        r[i] += eps * start[i]
    return _cholesky_solve(N, r)


@njit(cache=True)
def _lemke_solve(W, base, rows, pairs, row, count, nf):
    """The problem as Stewart and Trinkle's LCP with Coulomb friction (exact in 2D),
    solved by Lemke's method. Unknowns: each row's normal impulse ``l >= 0``; each block's
    friction ``f+ - f-`` (``f+, f- >= 0``) and its sliding speed ``s >= 0``. Returns
    ``(impulses, ok)``; ``ok`` false on a ray or a budget run out."""
    size = count + 3 * nf
    M = np.zeros((size, size))
    q = np.zeros(size)
    plus = count
    minus = count + nf
    slide = count + 2 * nf
    for a in range(count):
        q[a] = base[a] - rows[a, TARGET]
        for b in range(count):
            M[a, b] = W[a, b]
        for f in range(nf):
            M[a, plus + f] = W[a, count + f]
            M[a, minus + f] = -W[a, count + f]
    for f in range(nf):
        t = count + f
        q[plus + f] = base[t]
        q[minus + f] = -base[t]
        for b in range(count):
            M[plus + f, b] = W[t, b]
            M[minus + f, b] = -W[t, b]
        for g in range(nf):
            M[plus + f, plus + g] = W[t, count + g]
            M[plus + f, minus + g] = -W[t, count + g]
            M[minus + f, plus + g] = -W[t, count + g]
            M[minus + f, minus + g] = W[t, count + g]
        M[plus + f, slide + f] = 1.0
        M[minus + f, slide + f] = 1.0
        M[slide + f, plus + f] = -1.0
        M[slide + f, minus + f] = -1.0
        first = row[t]
        mu = rows[first, MU]
        M[slide + f, first] = mu
        if _in_block(pairs, count, first):
            M[slide + f, first + 1] = mu
    z, ok = lemke(M, q, 8 * size + 64)
    fresh = np.empty(count + nf)
    for a in range(count):
        fresh[a] = z[a]
    for f in range(nf):
        fresh[count + f] = z[plus + f] - z[minus + f]
    return fresh, ok


@njit(cache=True)
def _exact(F, vel, rows, pairs, count, starts, sizes, blocks, speed, warm, lemke_limit):
    """Solve the step's contacts exactly: a pushing point reaches its target normal speed
    and no point closes faster than it; a sliding pair's friction is ``mu`` times its normal
    impulses, against the slide; a sticking pair stops sliding, within the cone. Three ways,
    in order, each answer checked (``_accept``) before the next is tried: from the sweeps'
    active set, then from the last step's (``warm``, the impulses the sweeps started from)
    (``_on_set``: one linear solve per set, right at most steps of a pile), then as a
    complementarity problem by Lemke's method (``_lemke_solve``, for at most ``lemke_limit``
    unknowns). Replaces the impulses and velocities and returns true with the first answer
    that checks out; leaves them alone otherwise (a ray, or too many unknowns: the sweeps go
    on)."""
    ja, jb, body_a, body_b, row, nf = _directions(F, rows, pairs, count, starts, blocks)
    n = ja.shape[0]
    if count + 3 * nf > LCP_LIMIT:
        return False
    W, base, impulse, inverse = _operator(F, vel, rows, pairs, count, ja, jb, body_a, body_b, row)
    if _on_set(vel, rows, pairs, count, starts, sizes, blocks, speed, ja, jb, body_a, body_b, row, nf, W, base,
               impulse, inverse, impulse):
        return True
    # the last step's active set: a pile's contacts mostly keep theirs from step to step
    last = np.empty(n)
    for k in range(n):
        last[k] = warm[row[k], 0] if k < count else warm[row[k], 1]
    if _on_set(vel, rows, pairs, count, starts, sizes, blocks, speed, ja, jb, body_a, body_b, row, nf, W, base,
               impulse, inverse, last):
        return True
    if count + 3 * nf > lemke_limit:
        return False
    fresh, ok = _lemke_solve(W, base, rows, pairs, row, count, nf)
    return ok and _accept(vel, rows, pairs, count, starts, sizes, blocks, speed, ja, jb, body_a, body_b, row, nf,
                          impulse, inverse, fresh)


@njit(cache=True)
def _on_set(vel, rows, pairs, count, starts, sizes, blocks, speed, ja, jb, body_a, body_b, row, nf, W, base,
            impulse, inverse, guess):
    """Solve on the active set of ``guess`` (``_active_set``) and take the answer if it
    checks out (``_accept``); where it breaks a condition of the problem, on the set it
    moves to, at most ``SET_TRIES`` sets in all. Returns whether an answer was taken."""
    for _ in range(SET_TRIES):
        fresh, state = _active_set(W, base, rows, pairs, row, count, nf, guess)
        if state == SET_SOLVED:
            return _accept(vel, rows, pairs, count, starts, sizes, blocks, speed, ja, jb, body_a, body_b, row, nf,
                           impulse, inverse, fresh)
        if state == SET_WRONG:
            return False
        guess = fresh
    return False


@njit(cache=True)
def _accept(vel, rows, pairs, count, starts, sizes, blocks, speed, ja, jb, body_a, body_b, row, nf, impulse,
            inverse, fresh):
    """Take the impulses ``fresh`` (from ``impulse``, along the directions ``ja``, ``jb``) if
    the velocities they give pass the sweeps' own test (``_residual`` within
    ``SOLVE_TOLERANCE`` of ``speed``): then the rows' impulses and ``vel`` are replaced and
    the answer is true; else nothing changes."""
    moved = vel.copy()
    for k in range(ja.shape[0]):
        change = fresh[k] - impulse[k]
        for side in range(2):
            x = body_a[k] if side == 0 else body_b[k]
            if x >= 0:
                for d in range(3):
                    moved[x, d] += inverse[x, d] * (ja[k, d] if side == 0 else jb[k, d]) * change
    old = rows[:count, LAMBDA_N:LAMBDA_T + 1].copy()
    for a in range(count):
        rows[a, LAMBDA_N] = fresh[a]
        rows[a, LAMBDA_T] = 0.0
    for f in range(nf):
        rows[row[count + f], LAMBDA_T] = fresh[count + f]
    if _residual(moved, rows, pairs, count, starts, sizes, blocks) <= SOLVE_TOLERANCE * speed:
        vel[:, :] = moved
        return True
    rows[:count, LAMBDA_N:LAMBDA_T + 1] = old
    return False


@njit(cache=True)
def _blocks(pairs, count):
    """The rows of each pair (one or two points, consecutive in the manifold): the first row
    and the number of rows of every block, and how many blocks."""
    starts = np.empty(count, dtype=np.int64)
    sizes = np.empty(count, dtype=np.int64)
    blocks = 0
    c = 0
    while c < count:
        starts[blocks] = c
        if _in_block(pairs, count, c):
            sizes[blocks] = 2
        else:
            sizes[blocks] = 1
        c += sizes[blocks]
        blocks += 1
    return starts[:blocks], sizes[:blocks], blocks


@njit(cache=True)
def _residual(vel, rows, pairs, count, starts, sizes, blocks):
    """How far the impulses are from solving the contacts, as a speed: the largest error of
    a pushing point's normal speed, of a point closing faster than its target, or of a
    sticking pair's (or point's) sliding speed. A friction impulse at its cone's edge to
    rounding slides: rounding relative to the problem's largest impulse as well as to the
    pair's own limit (an exact answer whose friction on a point pressed by 7e-10 fell short
    of the edge by 2.6e-18, in a pile pressed by 0.01, read as sticking and was refused)."""
    worst = 0.0
    pressed = 0.0
    for c in range(count):
        pressed = max(pressed, rows[c, LAMBDA_N])
    for c in range(count):
        ux, uy = _relative(vel, pairs, rows, c)
        gap = ux * rows[c, NX] + uy * rows[c, NY] - rows[c, TARGET]
        if rows[c, LAMBDA_N] > 0.0:
            worst = max(worst, abs(gap))
        else:
            worst = max(worst, -gap)
    for b in range(blocks):
        c = starts[b]
        if rows[c, MU] <= 0.0:
            continue
        if sizes[b] == 2:
            ux, uy = _relative_at(vel, pairs, c, rows[c, FAX], rows[c, FAY], rows[c, FBX], rows[c, FBY])
            limit = rows[c, MU] * (rows[c, LAMBDA_N] + rows[c + 1, LAMBDA_N])
        else:
            ux, uy = _relative(vel, pairs, rows, c)
            limit = rows[c, MU] * rows[c, LAMBDA_N]
        # sticking, not at the cone's edge: short of it by more than 1e-9 of the pair's own
        # limit and by more than the rounding of the problem's largest impulse
        if limit - abs(rows[c, LAMBDA_T]) > max(1e-9 * limit, 1e-12 * pressed):
            worst = max(worst, abs(-ux * rows[c, NY] + uy * rows[c, NX]))
    return worst
