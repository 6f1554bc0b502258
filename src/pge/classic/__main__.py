"""``python -m pge.classic [--headless] SCRIPT [ARGS...]``: run a PGE game script."""

import sys

from pge.classic.script import main

sys.exit(main())
