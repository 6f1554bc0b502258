"""The collision impulse with restitution, Coulomb friction and angular terms.

At a contact with unit normal ``n`` (from b towards a) and tangent
``t = (-n_y, n_x)``, the relative velocity of the two contact points is
``u = (u_n, u_t)`` (``u_n < 0``: approaching). An impulse ``J = (j_n, j_t)``
on a (and ``-J`` on b) changes it by ``K J``, where the symmetric positive
semi-definite *contact-space inverse mass* ``K`` sums, over the two bodies,
``m^-1 (d1 . d2) + I^-1 (r x d1)(r x d2)`` for the directions ``d1, d2`` and
the lever arm ``r`` from the body's centroid to the contact point.

The impulse (``contact_impulse``) is chosen in three steps:

1. *Stick*: the impulse that leaves ``u_n' = -e u_n`` and ``u_t' = 0``, if it
   lies in the friction cone ``|j_t| <= mu j_n``.
2. Otherwise *slide*: ``J = j_n (1, mu s)`` with ``s`` the sign the sticking
   impulse wanted, ``j_n`` chosen so that ``u_n' = -e u_n``; if that is
   impossible (``K_nn + mu s K_nt <= 0``, the Painleve case) the frictionless
   impulse ``J0 = (-(1 + e) u_n / K_nn, 0)``.
3. *Energy guard*: the change of kinetic energy is
   ``dE(J) = J . u + J.K J / 2``; ``dE(J0) = -(1 - e^2) u_n^2 / (2 K_nn) <= 0``.
   With coupling (``K_nt != 0``) Newton's restitution plus friction can gain
   energy; then ``J`` is pulled back along the segment towards ``J0`` to the
   point where ``dE = 0``. ``dE`` is convex, so the whole way back is
   dissipative; the friction cone is convex and holds ``J0``, and ``u_n'`` is
   linear in ``J`` and non-negative at both ends, so the result still
   separates and obeys Coulomb's law. Energy never increases.
"""

from __future__ import annotations

import math

from pge._jit_cache import njit

@njit(cache=True, inline="always")
def energy_change(jn, jt, un, ut, knn, knt, ktt):
    """Change of kinetic energy when impulse ``(jn, jt)`` acts at a contact with relative
    velocity ``(un, ut)`` and contact-space inverse mass ``[[knn, knt], [knt, ktt]]``."""
    return jn * un + jt * ut + 0.5 * (knn * jn * jn + 2.0 * knt * jn * jt + ktt * jt * jt)


@njit(cache=True, inline="always")
def _pull_back(base, a, b):
    """The energy guard's step: the largest ``s`` in [0, 1] with ``base + b s + a s^2 / 2 <= 0``,
    the energy change along the segment from an impulse that takes energy out (``base <= 0``)
    to one that gains (``a > 0``: convex), computed stably and shrunk by a few ulps so that
    rounding cannot leave it just above zero."""
    disc = b * b - 2.0 * a * base
    root = math.sqrt(max(disc, 0.0))
    if b > 0.0:
        s = -2.0 * base / (b + root) if b + root > 0.0 else 0.0
    else:
        s = (root - b) / a
    return min(max(s * (1.0 - 4.0 * 2.0**-52), 0.0), 1.0)


@njit(cache=True)
def contact_impulse(un, ut, knn, knt, ktt, restitution, mu):
    """Normal and tangential impulse ``(jn, jt)`` on body a for an approaching contact.

    ``un < 0`` and ``ut``: relative velocity of a's contact point to b's along
    the normal and tangent; ``knn, knt, ktt``: contact-space inverse mass
    (``knn > 0``); ``restitution`` in [0, 1]; ``mu >= 0`` Coulomb's
    coefficient. See the module docstring for the rule; the result never
    increases the kinetic energy and leaves ``u_n' >= 0``.
    """
    e = restitution
    jn0 = -(1.0 + e) * un / knn
    if mu == 0.0 or ktt <= 0.0:
        return jn0, 0.0
    det = knn * ktt - knt * knt
    want_n = -(1.0 + e) * un  # the change of u_n that restitution asks for
    want_t = -ut
    sign = 0.0
    jn = jn0
    jt = 0.0
    found = False
    if det > 1e-12 * knn * ktt:
        stick_n = (ktt * want_n - knt * want_t) / det
        stick_t = (knn * want_t - knt * want_n) / det
        if stick_n > 0.0 and abs(stick_t) <= mu * stick_n:
            jn = stick_n
            jt = stick_t
            found = True
        elif stick_t != 0.0:
            sign = math.copysign(1.0, stick_t)
    if not found:
        if sign == 0.0:
            slip = ut + knt * jn0  # tangential velocity the frictionless impulse leaves
            if slip == 0.0:
                return jn0, 0.0
            sign = -math.copysign(1.0, slip)
        denominator = knn + mu * sign * knt
        if denominator > 0.0:
            jn = want_n / denominator
            jt = mu * sign * jn
        else:
            return jn0, 0.0
    gain = energy_change(jn, jt, un, ut, knn, knt, ktt)
    if gain <= 0.0:
        return jn, jt
    # Pull back towards the frictionless impulse until no energy is gained.
    dn = jn - jn0
    dt = jt
    base = energy_change(jn0, 0.0, un, ut, knn, knt, ktt)  # <= 0
    a = knn * dn * dn + 2.0 * knt * dn * dt + ktt * dt * dt
    b = dn * un + dt * ut + knn * jn0 * dn + knt * jn0 * dt
    if a <= 0.0:
        return jn0, 0.0
    s = _pull_back(base, a, b)
    return jn0 + s * dn, s * dt


# ---------------------------------------------------------------- two points of one face


@njit(cache=True, inline="always")
def _patch_energy(l1, l2, jt, u1, u2, ut, k11, k12, k22, k1t, k2t, ktt):
    """Change of kinetic energy when impulses ``l1``, ``l2`` (normal, at the two points) and
    ``jt`` (tangential, at their midpoint) act, ``J . u + J.K J / 2``."""
    quad = (
        k11 * l1 * l1 + k22 * l2 * l2 + ktt * jt * jt
        + 2.0 * (k12 * l1 * l2 + k1t * l1 * jt + k2t * l2 * jt)
    )
    return l1 * u1 + l2 * u2 + jt * ut + 0.5 * quad


@njit(cache=True)
def _normal_lcp(m11, m12, m21, m22, w1, w2, slack):
    """The two normal impulses ``l >= 0`` with ``M l >= w`` and ``l_i (M l - w)_i = 0``
    (within ``slack`` of a speed), by its four cases in the order both, the first, the second,
    none; ``(l1, l2, found)``."""
    det = m11 * m22 - m12 * m21
    if det > 1e-12 * abs(m11 * m22):
        l1 = (m22 * w1 - m12 * w2) / det
        l2 = (m11 * w2 - m21 * w1) / det
        if l1 >= 0.0 and l2 >= 0.0:
            return l1, l2, True
    if m11 > 0.0:
        l1 = w1 / m11
        if l1 >= 0.0 and m21 * l1 >= w2 - slack:
            return l1, 0.0, True
    if m22 > 0.0:
        l2 = w2 / m22
        if l2 >= 0.0 and m12 * l2 >= w1 - slack:
            return 0.0, l2, True
    if w1 <= slack and w2 <= slack:
        return 0.0, 0.0, True
    return 0.0, 0.0, False


@njit(cache=True)
def _stick(u1, u2, ut, k11, k12, k22, k1t, k2t, ktt, w1, w2, mu, slack):
    """The sticking impulse (``ut' = 0``) with the normal conditions of ``_normal_lcp`` and
    friction inside its cone, trying both points, the first, the second; ``(l1, l2, jt,
    found, sign)``, ``sign`` the direction the two-point sticking friction wanted (0: none
    found)."""
    sign = 0.0
    # both points: the 3x3 system K x = (w1, w2, -ut), by Cramer's rule
    c11 = k22 * ktt - k2t * k2t
    c12 = k12 * ktt - k2t * k1t
    c13 = k12 * k2t - k22 * k1t
    det = k11 * c11 - k12 * c12 + k1t * c13
    if det > 1e-12 * k11 * k22 * ktt:
        wt = -ut
        l1 = (w1 * c11 - k12 * (w2 * ktt - k2t * wt) + k1t * (w2 * k2t - k22 * wt)) / det
        l2 = (k11 * (w2 * ktt - k2t * wt) - w1 * (k12 * ktt - k1t * k2t) + k1t * (k12 * wt - w2 * k1t)) / det
        jt = (k11 * (k22 * wt - w2 * k2t) - k12 * (k12 * wt - w2 * k1t) + w1 * (k12 * k2t - k22 * k1t)) / det
        if l1 >= 0.0 and l2 >= 0.0:
            if abs(jt) <= mu * (l1 + l2):
                return l1, l2, jt, True, 0.0
            sign = math.copysign(1.0, jt)
    # one point: the 2x2 system on its normal and the friction
    for first in (True, False):
        kn = k11 if first else k22
        knt = k1t if first else k2t
        w = w1 if first else w2
        d = kn * ktt - knt * knt
        if not d > 1e-12 * kn * ktt:
            continue
        ln = (ktt * w + knt * ut) / d
        jt = (-kn * ut - knt * w) / d
        if ln < 0.0 or abs(jt) > mu * ln:
            continue
        if first:
            if k12 * ln + k2t * jt >= w2 - slack:
                return ln, 0.0, jt, True, sign
        elif k12 * ln + k1t * jt >= w1 - slack:
            return 0.0, ln, jt, True, sign
    return 0.0, 0.0, 0.0, False, sign


@njit(cache=True)
def patch_impulse(u1, u2, ut, k11, k12, k22, k1t, k2t, ktt, restitution, mu):
    """Impulses ``(l1, l2, jt)`` on body a where a face meets a face: normal impulses at the
    patch's two ends and one tangential impulse at their midpoint.

    ``u1``, ``u2``: relative normal velocities of the two ends (negative: approaching; at
    least one approaches); ``ut``: relative tangential velocity at the midpoint; ``k..``: the
    contact-space inverse mass over those three directions (symmetric, positive
    semi-definite). Newton's restitution at each end: an approaching end leaves at ``-e u``
    or faster, and exactly so where it takes an impulse (complementarity); an end that
    separates keeps separating. Coulomb friction on the pair: sticking (``ut' = 0``) where
    the cone ``|jt| <= mu (l1 + l2)`` allows, else sliding at ``mu`` times the normal
    impulses, against the slip sticking would undo. Both ends take the impact together, so
    that a face landing flat to rounding lands as a face: the result is continuous in the
    ends' speeds (where one end's impulse alone leaves the other separating, it is the
    single-point impulse there), where choosing one end would set a body turning on a
    difference of rounding. Energy guard: simultaneous restitution at two points can gain
    energy, so the impulse is pulled back towards the inelastic frictionless one (which only
    takes energy out) until it gains none.
    """
    e = restitution
    w1 = -(1.0 + e) * u1 if u1 < 0.0 else -u1
    w2 = -(1.0 + e) * u2 if u2 < 0.0 else -u2
    slack = 1e-12 * (abs(u1) + abs(u2) + abs(ut))
    # the inelastic frictionless impulse: the anchor of the energy guard
    i1, i2, found = _normal_lcp(k11, k12, k12, k22, -u1, -u2, slack)
    if not found:
        i1, i2 = 0.0, 0.0
    l1, l2, found = _normal_lcp(k11, k12, k12, k22, w1, w2, slack)
    if not found:
        l1, l2 = i1, i2
    jt = 0.0
    if mu > 0.0 and ktt > 0.0:
        s1, s2, st, stuck, sign = _stick(u1, u2, ut, k11, k12, k22, k1t, k2t, ktt, w1, w2, mu, slack)
        if stuck:
            l1, l2, jt = s1, s2, st
        else:
            if sign == 0.0:
                slip = ut + k1t * l1 + k2t * l2  # what the frictionless impulse leaves
                sign = -math.copysign(1.0, slip) if slip != 0.0 else 0.0
            if sign != 0.0:
                f = mu * sign
                p1, p2, ok = _normal_lcp(k11 + f * k1t, k12 + f * k1t, k12 + f * k2t, k22 + f * k2t, w1, w2, slack)
                if ok:
                    l1, l2, jt = p1, p2, f * (p1 + p2)
    gain = _patch_energy(l1, l2, jt, u1, u2, ut, k11, k12, k22, k1t, k2t, ktt)
    if gain <= 0.0:
        return l1, l2, jt
    # Pull back along the segment towards (i1, i2, 0), where dE <= 0: dE is convex on it.
    base = _patch_energy(i1, i2, 0.0, u1, u2, ut, k11, k12, k22, k1t, k2t, ktt)
    d1 = l1 - i1
    d2 = l2 - i2
    dt = jt
    a = k11 * d1 * d1 + k22 * d2 * d2 + ktt * dt * dt + 2.0 * (k12 * d1 * d2 + k1t * d1 * dt + k2t * d2 * dt)
    b = (
        d1 * u1 + d2 * u2 + dt * ut
        + i1 * (k11 * d1 + k12 * d2 + k1t * dt) + i2 * (k12 * d1 + k22 * d2 + k2t * dt)
    )
    if a <= 0.0:
        return i1, i2, 0.0
    s = _pull_back(base, a, b)
    return i1 + s * d1, i2 + s * d2, s * dt
