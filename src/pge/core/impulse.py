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
    disc = b * b - 2.0 * a * base
    root = math.sqrt(max(disc, 0.0))
    if b > 0.0:
        s = -2.0 * base / (b + root) if b + root > 0.0 else 0.0
    else:
        s = (root - b) / a
    s = min(max(s * (1.0 - 4.0 * 2.0**-52), 0.0), 1.0)
    return jn0 + s * dn, s * dt
