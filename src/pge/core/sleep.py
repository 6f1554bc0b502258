"""Sleeping islands: a pile that static contact forces can hold stops, and makes no events.

Resting contact (``pge.core.contact``) carries a body on one support. A body
leaning on two others, or wedged between them, has no single support: under
the pivot rule it keeps making tiny bounces, thousands per simulated second,
each lift paid for out of energy it hardly has. When the pivot rule fires on
a pair that is nearly still, ``try_sleep`` gathers the *island* around it: the
bodies touching it (within a rest height), and the bodies touching those, up
to fixed bodies. If every one of them is nearly still and there are contact
forces that hold them all where they are (non-negative normal forces inside
their friction cones, balancing each body's free acceleration and keeping it
from turning: ``equilibrium``), the whole island falls asleep: velocities,
spins and accelerations become zero. Stopping only takes energy away, and
bodies that do not move cannot overlap.

An island sleeps as a ring (``I[SLEEP_NEXT]``) and wakes as a whole
(``wake``): when a collision involves one of its bodies, or the World changes
one of them. Its bodies then get their free accelerations back, with zero
velocity, and what rests on them is released. A sleeping body is a support
others may rest on (``pge.core.contact.grounded``).
"""

from __future__ import annotations

import math

import numpy as np
from pge._jit_cache import njit

from pge.core import layout as L
from pge.core.contact import combine, detach, release_riders
from pge.core.grid import gather
from pge.core.motion import advance, orient
from pge.numerics.linalg import solve_spd

CIRCLE = 0
#: the most bodies one island may have (larger piles keep bouncing)
MAX_ISLAND = 24
#: the most contact points an island's solve may have
MAX_POINTS = 96
#: a body is nearly still when ``|v| + |omega| reach`` is below this many pivot speeds
STILL_FACTOR = 2.0
#: touching: closer than this many rest heights (of the larger bounding radius)
TOUCH_FACTOR = 2.0
#: the equilibrium's residual, relative to each body's weight, that counts as balanced
BALANCE = 1e-6
#: a body that failed to fall asleep tries again after this many pivot flight times
RETRY_FACTOR = 1.0


@njit(cache=True)
def asleep(I, x):
    """True if body ``x`` is asleep."""
    return I[x, L.SLEEP_NEXT] >= 0


@njit(cache=True)
def wake(S, x, out, count, t):
    """Wake body ``x``'s island (no-op if it is awake): every body gets its free
    acceleration back at zero velocity, and what rests on them is released. The
    woken and released bodies are appended to ``out`` from ``count``; returns the new
    count."""
    F = S[0]
    I = S[1]
    if I[x, L.SLEEP_NEXT] < 0:
        return count
    S[13][L.S_WAKES] += 1
    m = x
    while True:
        following = I[m, L.SLEEP_NEXT]
        I[m, L.SLEEP_NEXT] = -1
        advance(F, m, t)
        F[m, L.AX] = F[m, L.FREE_AX]
        F[m, L.AY] = F[m, L.FREE_AY]
        out[count] = m
        count += 1
        count = release_riders(S, m, out, count, t)
        m = following
        if m == x or m < 0:
            break
    return count


@njit(cache=True)
def _pivot_speed(F, P, x):
    """The pivot rule's lift speed for body ``x`` under its own free acceleration."""
    accel = math.hypot(F[x, L.FREE_AX], F[x, L.FREE_AY])
    return math.sqrt(2.0 * accel * P[L.REST_HEIGHT] * F[x, L.REACH])


@njit(cache=True)
def _nearly_still(F, I, P, x, t):
    """True if body ``x`` (not fixed) moves slower than ``STILL_FACTOR`` pivot speeds."""
    vx = F[x, L.VX] + F[x, L.AX] * (t - F[x, L.T0])
    vy = F[x, L.VY] + F[x, L.AY] * (t - F[x, L.T0])
    spin = abs(F[x, L.OMEGA]) * F[x, L.REACH] if I[x, L.KIND] != CIRCLE else 0.0
    return math.hypot(vx, vy) + spin <= STILL_FACTOR * _pivot_speed(F, P, x)


@njit(cache=True)
def try_sleep(S, a, b, out, count, t):
    """Put the island around bodies ``a`` and ``b`` to sleep if it is nearly still and
    static contact forces can hold it; returns ``(slept, count)``, with the island's
    bodies appended to ``out`` from ``count`` when it fell asleep.
    """
    F = S[0]
    I = S[1]
    P = S[3]
    Q = S[4]
    members = np.empty(MAX_ISLAND, dtype=np.int64)
    n = 0
    for x in (a, b):
        if I[x, L.FIXED] == 0:
            if not _nearly_still(F, I, P, x, t) or t - F[x, L.SLEEP_TRY] < _retry(F, P, x):
                return False, count
            members[n] = x
            n += 1
    if n == 0:
        return False, count
    # Contacts: (i, j, point x, point y, normal x, normal y), normal from j towards i.
    pairs = np.empty((MAX_POINTS, 2), dtype=np.int64)
    geometry = np.empty((MAX_POINTS, 4))
    points = 0
    k = 0
    while k < n:
        i = members[k]
        k += 1
        advance(F, i, t)
        orient(F, I, S[2], S[18], i, t)
        found = S[15][: gather(S, i)].copy()
        for j in found:
            if I[j, L.ALIVE] == 0:
                continue
            place = -1
            for e in range(n):
                if members[e] == j:
                    place = e
            listed = place >= 0
            if listed and place < k - 1:
                continue  # this pair was looked at from j
            advance(F, j, t)
            orient(F, I, S[2], S[18], j, t)
            tolerance = TOUCH_FACTOR * P[L.REST_HEIGHT] * max(F[i, L.REACH], F[j, L.REACH])
            before = points
            points = _touching_points(S, i, j, tolerance, pairs, geometry, points)
            if points < 0:
                return _fail(F, members, n, t, count)
            if points == before or listed or I[j, L.FIXED] != 0:
                continue
            if not _nearly_still(F, I, P, j, t) or n == MAX_ISLAND:
                return _fail(F, members, n, t, count)
            members[n] = j
            n += 1
            if I[j, L.SLEEP_NEXT] >= 0:
                # Part of a sleeping island: take all of it (its load changes).
                m = I[j, L.SLEEP_NEXT]
                while m != j:
                    if n == MAX_ISLAND:
                        return _fail(F, members, n, t, count)
                    members[n] = m
                    n += 1
                    m = I[m, L.SLEEP_NEXT]
    if not equilibrium(F, I, Q, members, n, pairs, geometry, points):
        return _fail(F, members, n, t, count)
    for e in range(n):
        x = members[e]
        if I[x, L.SUPPORT] >= 0:
            detach(S, x)
    for e in range(n):
        x = members[e]
        count = release_riders(S, x, out, count, t)  # none but members rest on members
        F[x, L.VX] = 0.0
        F[x, L.VY] = 0.0
        F[x, L.OMEGA] = 0.0
        F[x, L.ALPHA] = 0.0
        F[x, L.AX] = 0.0
        F[x, L.AY] = 0.0
        I[x, L.SLEEP_NEXT] = members[(e + 1) % n]
        out[count] = x
        count += 1
    S[13][L.S_SLEEPS] += 1
    return True, count


@njit(cache=True)
def _retry(F, P, x):
    """How long after a failed attempt body ``x`` waits before trying again."""
    accel = math.hypot(F[x, L.FREE_AX], F[x, L.FREE_AY])
    if not accel > 0.0:
        return 0.0
    return RETRY_FACTOR * 2.0 * _pivot_speed(F, P, x) / accel


@njit(cache=True)
def _fail(F, members, n, t, count):
    """Note a failed attempt on the bodies looked at; returns ``(False, count)``."""
    for e in range(n):
        F[members[e], L.SLEEP_TRY] = t
    return False, count


@njit(cache=True)
def _touching_points(S, i, j, tolerance, pairs, geometry, points):
    """Append the contact points of bodies ``i`` and ``j`` if they are within
    ``tolerance`` of touching (none otherwise); returns the new number of points, or
    -1 if they do not fit."""
    F = S[0]
    I = S[1]
    OL = S[2]
    if I[i, L.KIND] == CIRCLE and I[j, L.KIND] == CIRCLE:
        dx = F[i, L.X] - F[j, L.X]
        dy = F[i, L.Y] - F[j, L.Y]
        d = math.hypot(dx, dy)
        if not (d > 0.0 and d - F[i, L.RADIUS] - F[j, L.RADIUS] <= tolerance):
            return points
        nx = dx / d
        ny = dy / d
        return _append(pairs, geometry, points, i, j, F[j, L.X] + F[j, L.RADIUS] * nx, F[j, L.Y] + F[j, L.RADIUS] * ny, nx, ny)
    if I[i, L.KIND] == CIRCLE or I[j, L.KIND] == CIRCLE:
        c = i if I[i, L.KIND] == CIRCLE else j
        g = j if c == i else i
        gap, nx, ny = _circle_gap(F, I, OL, c, g)
        if not gap <= tolerance:
            return points
        px = F[c, L.X] - F[c, L.RADIUS] * nx
        py = F[c, L.Y] - F[c, L.RADIUS] * ny
        if c == i:
            return _append(pairs, geometry, points, i, j, px, py, nx, ny)
        return _append(pairs, geometry, points, i, j, px, py, -nx, -ny)
    # Two polygons: the face of greatest separation carries the contact.
    best = -math.inf
    owner = i
    face = 0
    for side in range(2):
        o = i if side == 0 else j
        other = j if side == 0 else i
        for f in range(I[o, L.OUTLINE_N]):
            s = _face_separation(F, I, OL, o, f, other)
            if s > best:
                best = s
                owner = o
                face = f
    if not best <= tolerance:
        return points
    other = j if owner == i else i
    row = I[owner, L.OUTLINE_START] + face
    nx = OL[row, 2]
    ny = OL[row, 3]
    tx = -ny
    ty = nx
    qx = F[owner, L.X] + OL[row, 0]
    qy = F[owner, L.Y] + OL[row, 1]
    lo = math.inf
    hi = -math.inf
    start = I[other, L.OUTLINE_START]
    for k in range(I[other, L.OUTLINE_N]):
        wx = F[other, L.X] + OL[start + k, 0] - qx
        wy = F[other, L.Y] + OL[start + k, 1] - qy
        if wx * nx + wy * ny <= best + tolerance:
            u = wx * tx + wy * ty
            lo = min(lo, u)
            hi = max(hi, u)
    lo = max(lo, 0.0)
    hi = min(hi, OL[row, 4])
    if lo > hi:  # corner against corner: the nearer end of the face
        lo = hi = min(max(0.5 * (lo + hi), 0.0), OL[row, 4])
    sign = 1.0 if other == i else -1.0  # the normal must point from j towards i
    points = _append(pairs, geometry, points, i, j, qx + lo * tx, qy + lo * ty, sign * nx, sign * ny)
    if points >= 0 and hi - lo > 1e-9 * OL[row, 4]:
        points = _append(pairs, geometry, points, i, j, qx + hi * tx, qy + hi * ty, sign * nx, sign * ny)
    return points


@njit(cache=True)
def _append(pairs, geometry, points, i, j, px, py, nx, ny):
    if points < 0 or points >= pairs.shape[0]:
        return -1
    pairs[points, 0] = i
    pairs[points, 1] = j
    geometry[points, 0] = px
    geometry[points, 1] = py
    geometry[points, 2] = nx
    geometry[points, 3] = ny
    return points + 1


@njit(cache=True)
def _circle_gap(F, I, OL, c, g):
    """Gap between circle ``c`` and polygon ``g``, and the normal from ``g`` towards the
    centre: ``(gap, nx, ny)``."""
    start = I[g, L.OUTLINE_START]
    n = I[g, L.OUTLINE_N]
    px = F[c, L.X] - F[g, L.X]
    py = F[c, L.Y] - F[g, L.Y]
    best = -math.inf
    face = 0
    for k in range(n):
        s = OL[start + k, 2] * (px - OL[start + k, 0]) + OL[start + k, 3] * (py - OL[start + k, 1])
        if s > best:
            best = s
            face = k
    row = start + face
    # The foot on the face's line: inside the face, the face is nearest; else a corner.
    u = -OL[row, 3] * (px - OL[row, 0]) + OL[row, 2] * (py - OL[row, 1])
    if best <= 0.0 or 0.0 <= u <= OL[row, 4]:
        return best - F[c, L.RADIUS], OL[row, 2], OL[row, 3]
    nearest = math.inf
    nx = OL[row, 2]
    ny = OL[row, 3]
    for k in range(n):
        dx = px - OL[start + k, 0]
        dy = py - OL[start + k, 1]
        d = math.hypot(dx, dy)
        if d < nearest and d > 0.0:
            nearest = d
            nx = dx / d
            ny = dy / d
    return nearest - F[c, L.RADIUS], nx, ny


@njit(cache=True)
def _face_separation(F, I, OL, o, f, other):
    """Least distance of ``other``'s corners beyond face ``f`` of polygon ``o``."""
    row = I[o, L.OUTLINE_START] + f
    nx = OL[row, 2]
    ny = OL[row, 3]
    qx = F[o, L.X] + OL[row, 0]
    qy = F[o, L.Y] + OL[row, 1]
    start = I[other, L.OUTLINE_START]
    least = math.inf
    for k in range(I[other, L.OUTLINE_N]):
        s = (F[other, L.X] + OL[start + k, 0] - qx) * nx + (F[other, L.Y] + OL[start + k, 1] - qy) * ny
        least = min(least, s)
    return least


@njit(cache=True)
def equilibrium(F, I, Q, members, n, pairs, geometry, points):
    """Whether contact forces can hold the island still: non-negative normal forces
    inside their friction cones (each cone spanned by its two edges) such that every
    member's forces cancel its weight ``m a_free`` and turn it not at all.

    A non-negative least-squares fit (``nnls``) of the forces; the island balances
    when every member's residual is within ``BALANCE`` of its weight (force and
    torque, the torque over the bounding radius).
    """
    columns = 0
    for k in range(points):
        mu = combine(F[pairs[k, 0], L.FRICTION], F[pairs[k, 1], L.FRICTION], Q[L.FRICTION_RULE])
        columns += 2 if mu > 0.0 else 1
    rows = 3 * n
    A = np.zeros((rows, max(columns, 1)))
    target = np.zeros(rows)
    scale = np.empty(n)
    for e in range(n):
        x = members[e]
        weight = math.hypot(F[x, L.FREE_AX], F[x, L.FREE_AY]) / F[x, L.INV_MASS]
        scale[e] = 1.0 / weight if weight > 0.0 else 1.0
        target[3 * e] = -F[x, L.FREE_AX] / F[x, L.INV_MASS] * scale[e]
        target[3 * e + 1] = -F[x, L.FREE_AY] / F[x, L.INV_MASS] * scale[e]
    c = 0
    for k in range(points):
        i = pairs[k, 0]
        j = pairs[k, 1]
        px = geometry[k, 0]
        py = geometry[k, 1]
        nx = geometry[k, 2]
        ny = geometry[k, 3]
        mu = combine(F[i, L.FRICTION], F[j, L.FRICTION], Q[L.FRICTION_RULE])
        edges = 2 if mu > 0.0 else 1
        for side in range(edges):
            sign = 1.0 if side == 0 else -1.0
            dx = nx - sign * mu * ny if mu > 0.0 else nx
            dy = ny + sign * mu * nx if mu > 0.0 else ny
            for e in range(n):
                x = members[e]
                if x == i:
                    direction = 1.0
                elif x == j:
                    direction = -1.0
                else:
                    continue
                lever = 1.0 / F[x, L.REACH] if F[x, L.REACH] > 0.0 else 1.0
                A[3 * e, c] += direction * dx * scale[e]
                A[3 * e + 1, c] += direction * dy * scale[e]
                rx = px - F[x, L.X]
                ry = py - F[x, L.Y]
                A[3 * e + 2, c] += direction * (rx * dy - ry * dx) * scale[e] * lever
            c += 1
    forces = nnls(A, target)
    for e in range(n):
        worst = 0.0
        for r in range(3 * e, 3 * e + 3):
            total = -target[r]
            for q in range(columns):
                total += A[r, q] * forces[q]
            worst = max(worst, abs(total))
        if worst > BALANCE:
            return False
    return True


@njit(cache=True)
def nnls(A, b):
    """Non-negative least squares: ``x >= 0`` minimising ``|A x - b|`` (the active-set
    method of Lawson and Hanson; each passive-set fit by regularised normal equations)."""
    rows, cols = A.shape
    x = np.zeros(cols)
    z = np.zeros(cols)
    passive = np.zeros(cols, dtype=np.bool_)
    residual = np.empty(rows)
    size = 0.0
    for r in range(rows):
        for q in range(cols):
            size = max(size, abs(A[r, q]))
    tolerance = 1e-12 * (1.0 + size * cols)
    for _ in range(3 * cols + 10):
        for r in range(rows):
            total = b[r]
            for q in range(cols):
                total -= A[r, q] * x[q]
            residual[r] = total
        best = -1
        most = tolerance
        for q in range(cols):
            if not passive[q]:
                slope = 0.0
                for r in range(rows):
                    slope += A[r, q] * residual[r]
                if slope > most:
                    most = slope
                    best = q
        if best < 0:
            break  # no column can lower the residual any more
        passive[best] = True
        for _ in range(cols + 1):
            _passive_fit(A, b, passive, z)
            step = 1.0
            for q in range(cols):
                if passive[q] and z[q] <= 0.0:
                    step = min(step, x[q] / (x[q] - z[q]) if x[q] > z[q] else 0.0)
            for q in range(cols):
                if passive[q]:
                    x[q] += step * (z[q] - x[q])
            if step == 1.0:
                break
            for q in range(cols):
                if passive[q] and x[q] <= tolerance:
                    x[q] = 0.0
                    passive[q] = False
        if not passive[best]:
            break  # the column that entered was dropped again: rounding, no progress
    return x


@njit(cache=True)
def _passive_fit(A, b, passive, z):
    """Least-squares fit of ``b`` by the passive columns of ``A`` into ``z`` (others 0)."""
    rows, cols = A.shape
    index = np.empty(cols, dtype=np.int64)
    p = 0
    for q in range(cols):
        z[q] = 0.0
        if passive[q]:
            index[p] = q
            p += 1
    if p == 0:
        return
    M = np.zeros((p, p))
    rhs = np.zeros(p)
    for u in range(p):
        cu = index[u]
        for r in range(rows):
            rhs[u] += A[r, cu] * b[r]
        for v in range(u + 1):
            cv = index[v]
            total = 0.0
            for r in range(rows):
                total += A[r, cu] * A[r, cv]
            M[u, v] = total
            M[v, u] = total
    ridge = 0.0
    for u in range(p):
        ridge += M[u, u]
    ridge = 1e-13 * ridge / p + 1e-300
    for u in range(p):
        M[u, u] += ridge
    solution = solve_spd(M, rhs, ridge)
    for u in range(p):
        z[index[u]] = solution[u]
