"""The pge recording format, version 1: constants, record framing and columns.

The full specification is ``docs/recording-format.md``. In short::

    file    = prelude record*
    prelude = MAGIC (8 bytes) major (u16 LE) minor (u16 LE)
    record  = length (u32 LE) crc (u32 LE) payload (length bytes)
    crc     = CRC-32 (zlib) of the 4 length bytes followed by the payload
    payload = one MessagePack map whose key "k" names the kind of record

Shape and event data sit in the payload as *columns*: little-endian arrays
whose bytes are shuffled (all first bytes of the elements, then all second
bytes, ...) and zlib-compressed, which halves the size of float64 positions
(their sign/exponent bytes repeat) while keeping every bit.
"""

from __future__ import annotations

import struct
import zlib

import numpy as np

__all__ = [
    "MAGIC",
    "FORMAT_VERSION",
    "PRELUDE",
    "RECORD_HEAD",
    "MAX_RECORD",
    "SUFFIX",
    "HEADER",
    "BODIES",
    "COLOURS",
    "FRAME",
    "END",
    "ID",
    "REAL",
    "COLOUR",
    "COUNT",
    "record_bytes",
    "pack_column",
    "unpack_column",
]

#: first 8 bytes of every file; the \x89 and \n catch 7-bit and text-mode transfers.
MAGIC = b"\x89PGEREC\n"
#: (major, minor): a reader refuses a newer major; minor bumps only add map keys.
FORMAT_VERSION = (1, 0)
PRELUDE = struct.Struct("<8sHH")
RECORD_HEAD = struct.Struct("<II")
#: no record may claim more than this many bytes (a larger length is corruption).
MAX_RECORD = 1 << 30
SUFFIX = ".pgerec"

# record kinds (the payload's "k")
HEADER = "header"
BODIES = "bodies"
COLOURS = "colours"
FRAME = "frame"
END = "end"

# column element types
ID = np.dtype("<i8")
REAL = np.dtype("<f8")
COLOUR = np.dtype("<u2")
COUNT = np.dtype("<u4")


def record_bytes(payload: bytes) -> bytes:
    """One framed record: length, CRC-32 of length and payload, payload."""
    length = struct.pack("<I", len(payload))
    return length + struct.pack("<I", zlib.crc32(payload, zlib.crc32(length))) + payload


def pack_column(values, dtype: np.dtype) -> bytes:
    """``values`` as a shuffled, zlib-compressed little-endian column of ``dtype``."""
    array = np.ascontiguousarray(values, dtype=dtype).reshape(-1)
    planes = array.view(np.uint8).reshape(-1, dtype.itemsize).T
    return zlib.compress(np.ascontiguousarray(planes).tobytes(), 6)


def unpack_column(blob: bytes, dtype: np.dtype, count: int) -> np.ndarray:
    """The ``count`` elements of ``dtype`` packed by ``pack_column``.

    Raises ValueError if the blob does not decompress to exactly that many elements.
    """
    raw = zlib.decompress(blob)
    if len(raw) != count * dtype.itemsize:
        raise ValueError(f"column holds {len(raw)} bytes, expected {count} x {dtype.itemsize}")
    planes = np.frombuffer(raw, dtype=np.uint8).reshape(dtype.itemsize, count)
    return np.ascontiguousarray(planes.T).view(dtype).reshape(count)
