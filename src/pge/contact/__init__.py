"""Contact: bodies in persistent contact form islands, whose contacts are
solved together at steps of fixed length while every other contact stays exact.

``manifold``: the touching points of two bodies now; ``island``: one step of an island (the
compiled step, its stages in order), on the contact rows of ``rows``, with the contact solve
in ``solve``, the energy stage and the lift's payment in ``energy``, what turning pairs'
straight lines miss in ``arcs`` and the push-out in ``pushout``; ``islands``: which bodies
form which island, their steps and their sleep (Python, on the World's internal timers). See
docs/contact.md.
"""
