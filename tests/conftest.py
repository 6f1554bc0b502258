"""Test-wide settings.

Under CI (``CI`` set) the property tests draw the same examples on every run (Hypothesis'
``derandomize``), so that whether a submission lands never depends on a draw; run locally they
draw new examples each time and keep exploring. A failure found either way becomes an explicit
``@example`` of its test.
"""

import os

from hypothesis import settings

settings.register_profile("ci", derandomize=True, print_blob=True)
if os.environ.get("CI"):
    settings.load_profile("ci")
