"""Extracted FMUs kept between runs, so that an FMU is unpacked (and its numba kernels compiled) once.

An FMU's folder in the cache is named by its GUID (instantiation token) and the SHA-256 of the file, so a
rebuilt FMU that kept its GUID never meets an old extraction. It is extracted with the same checks as a fresh
one (safezip.py) into a temporary folder beside its final place, then renamed: a folder in the cache is whole,
and two processes extracting the same FMU at once both end up using the one that was renamed first. The numba
caches our FMUs' kernels write next to their sources (``__pycache__``) stay in that folder, so the second set-up
of an FMU neither unpacks nor compiles (the FMU set-up figure of bench/bench_fmu.py).

Within one process a cached folder serves one live instance at a time: a second instance of the same FMU gets
a fresh temporary extraction, as FMI 2.0's ``canBeInstantiatedOnlyOncePerProcess`` FMUs need (their binary
then loads from a different path, so a separate copy of the library).
"""
from __future__ import annotations

import hashlib
import os
import re
import shutil
import threading
from pathlib import Path

from rotorcosim.components.cache import cache_dir

from rotorcosim.fmus.safezip import safe_extract

_lock = threading.Lock()
_in_use: set[Path] = set()


def _key(path: Path, guid: str) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for chunk in iter(lambda: f.read(1 << 20), b""):
            h.update(chunk)
    tag = re.sub(r"[^A-Za-z0-9_.-]", "_", guid or "noguid")[:64]
    return f"{tag}-{h.hexdigest()[:24]}"


def acquire(path: str | Path, guid: str, what: str = "FMU", prefix: str = "rcs_fmu_") -> tuple[Path, bool]:
    """The folder ``path`` is extracted in, and whether it is the cache's (keep it) or a fresh one (remove it).

    Call :func:`release` with the folder when the instance is freed."""
    path = Path(path)
    base = cache_dir("fmu")
    if base is not None:
        try:
            final = base / _key(path, guid)
            with _lock:
                busy = final in _in_use
            if not busy:
                if not final.is_dir():
                    base.mkdir(parents=True, exist_ok=True)
                    tmp = safe_extract(path, what, prefix=".part_", parent=base)
                    try:
                        os.replace(tmp, final)
                    except OSError:  # another process renamed its copy first: use that one
                        shutil.rmtree(tmp, ignore_errors=True)
                with _lock:
                    if final not in _in_use and final.is_dir():
                        _in_use.add(final)
                        return final, True
        except OSError:  # a cache that cannot be written (read-only home, full disk): extract as if there were none
            pass
    return safe_extract(path, what, prefix=prefix), False


def release(folder: Path, keep: bool) -> None:
    """Done with ``folder``: kept in the cache (free for the next instance), or removed."""
    with _lock:
        _in_use.discard(folder)
    if not keep:
        shutil.rmtree(folder, ignore_errors=True)


def clear() -> None:
    """Remove every cached FMU extraction (``rotorcosim`` never needs them: they are rebuilt on demand)."""
    base = cache_dir("fmu")
    if base is not None and base.is_dir():
        shutil.rmtree(base, ignore_errors=True)

