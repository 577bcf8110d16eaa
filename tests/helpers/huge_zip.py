"""A zip archive holding an entry of gigabytes that costs nothing to build: the entry is stored (not compressed)
zero bytes, written as a hole of a sparse file, its CRC-32 computed without reading them (the CRC of n zero bytes
is an affine map of the running CRC, squared log2(n) times).

>>> import tempfile, pathlib, zipfile
>>> p = sparse_zip(pathlib.Path(tempfile.mkdtemp()) / "a.zip", {"small.txt": b"hi"}, "zeros.bin", 3000)
>>> with zipfile.ZipFile(p) as z:
...     z.read("small.txt"), z.read("zeros.bin") == bytes(3000)
(b'hi', True)
"""
from __future__ import annotations

import struct
import zlib
from pathlib import Path


def _apply(cols, const, c):
    out = const
    i = 0
    while c:
        if c & 1:
            out ^= cols[i]
        c >>= 1
        i += 1
    return out


def crc32_of_zeros(n: int) -> int:
    """``zlib.crc32(bytes(n))`` in O(log n) work."""
    one = zlib.crc32(b"\0", 0)
    cols, const = [zlib.crc32(b"\0", 1 << i) ^ one for i in range(32)], one   # f_1(c) = L c + k
    acc = None                                                                    # f over the bits of n so far
    while n:
        if n & 1:
            acc = (cols, const) if acc is None else \
                ([_apply(cols, 0, x) for x in acc[0]], _apply(cols, const, acc[1]))
        cols, const = [_apply(cols, 0, x) for x in cols], _apply(cols, const, const)   # f_2m = f_m o f_m
        n >>= 1
    return 0 if acc is None else acc[1]


def sparse_zip(path: Path, small: dict[str, bytes], huge: str, size: int) -> Path:
    """Write ``path``: the entries ``small`` (stored), then ``huge`` of ``size`` zero bytes (stored, a hole of
    the file); sizes up to 4 GiB - 1 (no zip64)."""
    assert size < 2 ** 32
    entries = [(n, len(b), zlib.crc32(b), b) for n, b in small.items()] + [(huge, size, crc32_of_zeros(size), None)]
    central = b""
    with open(path, "wb") as f:
        for name, n, crc, data in entries:
            offset = f.tell()
            raw = name.encode()
            f.write(struct.pack("<IHHHHHIIIHH", 0x04034B50, 20, 0, 0, 0, 0x21, crc, n, n, len(raw), 0) + raw)
            if data is None:
                f.seek(n, 1)
            else:
                f.write(data)
            central += struct.pack("<IHHHHHHIIIHHHHHII", 0x02014B50, 20, 20, 0, 0, 0, 0x21, crc, n, n, len(raw),
                                   0, 0, 0, 0, 0o100644 << 16, offset) + raw
        start = f.tell()
        f.write(central)
        f.write(struct.pack("<IHHHHIIH", 0x06054B50, 0, 0, len(entries), len(entries), len(central), start, 0))
    return path
