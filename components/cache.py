"""Where rotorcosim keeps what it can rebuild but would rather not: one root for every on-disk cache.

``$ROTORCOSIM_CACHE`` if set, else ``~/.cache/rotorcosim``; ``ROTORCOSIM_CACHE=off`` (or 0/no/false) disables
every cache. Users of it: the damper's tables (damper/table_cache.py) and the extracted, compiled FMUs
(fmus/extraction_cache.py). A cache that cannot be written is skipped by its user, never an error.
"""
from __future__ import annotations

import os
from pathlib import Path

OFF = ("off", "0", "no", "false")


def cache_root() -> Path | None:
    """The cache root, or None when caching is switched off."""
    root = os.environ.get("ROTORCOSIM_CACHE", "")
    if root.lower() in OFF:
        return None
    return Path(root) if root else Path.home() / ".cache" / "rotorcosim"


def cache_dir(kind: str) -> Path | None:
    """The folder of one kind of cache (not created here), or None when caching is off."""
    root = cache_root()
    return None if root is None else root / kind


#: while a helper process builds cached results ahead of this process (master/compiled/ahead.py): the function that waits
#: for one of them (None: no helper)
_ahead = None


def await_ahead(key: str) -> None:
    """Before building the cached result ``key``: wait while a helper process builds it (then the cache has it);
    returns at once when there is no helper or the helper has not taken it (this process builds it)."""
    if _ahead is not None:
        _ahead(key)


def set_ahead(hook) -> None:
    """Install (or remove, with None) the waiting function of :func:`await_ahead`."""
    global _ahead
    _ahead = hook
