"""Where Numba keeps the engine's compiled kernels.

Numba's own cache notices when a function's file changes, but not when a
function it calls in *another* file does, so after an upgrade or an edit it
could load stale machine code. pge therefore keys the cache directory by a
hash of every compiled module's source: any change anywhere gets a fresh
cache. A user's ``NUMBA_CACHE_DIR`` is respected.

It also holds ``njit``, the decorator of every engine kernel (see its
docstring for why it is not Numba's own); this file
is part of the hash, since it decides which machine code the kernels get.
"""

from __future__ import annotations

import hashlib
import os
from pathlib import Path

import numba
from numba.core import types
from numba.core.registry import CPUDispatcher

_COMPILED_PACKAGES = ("numerics", "toi", "broadphase", "core", "contact")


def source_hash() -> str:
    """Short hash of the source of every module that holds compiled kernels."""
    root = Path(__file__).parent
    digest = hashlib.sha256()
    digest.update(Path(__file__).read_bytes())
    for package in _COMPILED_PACKAGES:
        for path in sorted((root / package).glob("*.py")):
            digest.update(path.name.encode())
            digest.update(path.read_bytes())
    return digest.hexdigest()[:16]


def configure() -> None:
    """Point Numba's cache at a directory named after the current kernel sources."""
    if os.environ.get("NUMBA_CACHE_DIR"):
        return
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    directory = Path(base) / "pge" / "numba" / source_hash()
    try:
        directory.mkdir(parents=True, exist_ok=True)
    except OSError:
        return  # not writable: Numba falls back to its own choice
    numba.config.CACHE_DIR = str(directory)


class KernelDispatcher(CPUDispatcher):
    """A CPU dispatcher that compiles calls from compiled code for non-literal types."""

    def get_call_template(self, args, kws):
        """Numba's, with the literal values of the argument types dropped (see ``njit``)."""
        args = tuple(types.unliteral(a) for a in args)
        kws = {k: types.unliteral(v) for k, v in kws.items()}
        return super().get_call_template(args, kws)


def njit(func=None, **options):
    """``numba.njit`` for pge's kernels: one compiled version per argument *type*.

    Numba's own dispatchers, called from compiled code with a constant argument
    (``wake(S, a, group, 0, t)``, ``presses_into_neighbour(..., False, t)``), type
    it as a literal (``Literal[int](0)``) and compile a separate version of the
    callee, and of everything it calls, for every distinct constant: one in eight of
    the signatures of a cold start were such duplicates. Here a call's argument
    types lose their literal values before the callee is chosen, so every call
    site shares one version; LLVM still sees the constant wherever it inlines.
    Options are those of ``numba.njit``; used bare or as ``njit(cache=True)``.
    """
    if func is not None:
        return njit(**options)(func)
    if numba.config.DISABLE_JIT:
        return lambda f: f
    cache = options.pop("cache", False)
    targetoptions = {"nopython": True, **options}

    def decorate(f):
        dispatcher = KernelDispatcher(py_func=f, locals={}, targetoptions=targetoptions)
        if cache:
            dispatcher.enable_caching()
        return dispatcher

    return decorate


configure()
