"""Where Numba keeps the engine's compiled kernels.

Numba's own cache notices when a function's file changes, but not when a
function it calls in *another* file does, so after an upgrade or an edit it
could load stale machine code. pge therefore keys the cache directory by a
hash of every compiled module's source: any change anywhere gets a fresh
cache. A user's ``NUMBA_CACHE_DIR`` is respected.
"""

from __future__ import annotations

import hashlib
import os
from pathlib import Path

_COMPILED_PACKAGES = ("numerics", "toi", "broadphase", "core", "contact")


def source_hash() -> str:
    """Short hash of the source of every module that holds compiled kernels."""
    root = Path(__file__).parent
    digest = hashlib.sha256()
    for package in _COMPILED_PACKAGES:
        for path in sorted((root / package).glob("*.py")):
            digest.update(path.name.encode())
            digest.update(path.read_bytes())
    return digest.hexdigest()[:16]


def configure() -> None:
    """Point Numba's cache at a directory named after the current kernel sources."""
    if os.environ.get("NUMBA_CACHE_DIR"):
        return
    import numba

    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    directory = Path(base) / "pge" / "numba" / source_hash()
    try:
        directory.mkdir(parents=True, exist_ok=True)
    except OSError:
        return  # not writable: Numba falls back to its own choice
    numba.config.CACHE_DIR = str(directory)


configure()
