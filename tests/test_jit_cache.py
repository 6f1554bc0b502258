"""pge._jit_cache: the kernels' decorator and cache key."""

from pge import _jit_cache
from pge._jit_cache import njit


@njit
def _shift(x, up):
    return x + 1 if up else x - 1


@njit
def _callers(x):
    # Constant arguments from compiled code: Numba's own dispatcher would type them as
    # literals and compile _shift once per distinct constant.
    return _shift(x, True) + _shift(x, False) + _shift(0, True) + _shift(x, x > 0)


def test_constant_arguments_share_one_compiled_version():
    assert _callers(2) == 3 + 1 + 1 + 3
    assert _callers(2.5) == 3.5 + 1.5 + 1 + 3.5
    assert sorted(str(s) for s in _shift.signatures) == ["(float64, bool)", "(int64, bool)"]


def test_the_decorator_is_part_of_the_cache_key(tmp_path, monkeypatch):
    # A change to how kernels are compiled must not load machine code made the old way.
    before = _jit_cache.source_hash()
    real_read = type(tmp_path).read_bytes

    def read_bytes(path):
        data = real_read(path)
        return data + b"#" if path.name == "_jit_cache.py" else data

    monkeypatch.setattr(type(tmp_path), "read_bytes", read_bytes)
    assert _jit_cache.source_hash() != before
