"""Contact: bodies in persistent contact form islands, whose contacts are
solved together at steps of fixed length while every other contact stays exact.

``manifold``: the touching points of two bodies now; ``island``: one step of an island (the
compiled solve); ``islands``: which bodies form which island, their steps and their sleep
(Python, on the World's internal timers). See docs/contact.md.
"""
