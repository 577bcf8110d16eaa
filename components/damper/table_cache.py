"""On-disk cache of the fast model's tables (60 factorisations of the Reynolds operator, ~1.6 s per damper geometry).

Every process of a run or a sweep would otherwise rebuild the same tables. The file name is the SHA-256 of
the table's arguments and of the source of the modules that compute it (reynolds_fe.py, fast.py), so a
changed solver never reads an old table; the arrays are stored bit-for-bit (.npz), so a cached run gives the
same numbers as an uncached one. Location: the folder ``damper`` of the cache root (components/cache.py).
A cache that cannot be written (read-only home) is silently skipped:
the table is then only kept in memory.
"""
from __future__ import annotations

import hashlib
import os
import tempfile
from pathlib import Path

import numpy as np

from ..cache import await_ahead, cache_dir

_SOURCES = ("reynolds_fe.py", "fast.py")


def _directory() -> Path | None:
    return cache_dir("damper")


def key(*args) -> str:
    h = hashlib.sha256(repr(tuple(float(a) for a in args)).encode())
    here = Path(__file__).parent
    for name in _SOURCES:
        h.update((here / name).read_bytes())
    return h.hexdigest()[:32]


def load(k: str) -> dict | None:
    d = _directory()
    if d is None:
        return None
    await_ahead(f"damper/{k}")  # a helper process may be building it (master/compiled/ahead.py)
    path = d / f"table_{k}.npz"
    try:
        with np.load(path) as f:
            return {name: f[name] for name in f.files}
    except (OSError, ValueError, KeyError):
        return None


def save(k: str, arrays: dict) -> None:
    d = _directory()
    if d is None:
        return
    try:
        d.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=d, suffix=".part")
        with os.fdopen(fd, "wb") as f:
            np.savez(f, **arrays)
        os.replace(tmp, d / f"table_{k}.npz")   # atomic: parallel processes never read half a file
    except OSError:
        pass


def enabled() -> bool:
    """Is the cache on (components/cache.py)?"""
    return _directory() is not None


def exists(k: str) -> bool:
    """Is table ``k`` in the cache (False when caching is off)?"""
    d = _directory()
    return d is not None and (d / f"table_{k}.npz").is_file()
