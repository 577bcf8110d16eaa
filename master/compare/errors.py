"""The relative difference of a staggered result from the monolithic one, per quantity.

``rel_error_pct(a, b) = 100 |a - b| / |b|`` with ``a`` the staggered and ``b`` the monolithic value (0 when both
are 0; None when it cannot be formed: a value missing or not finite, or ``b = 0`` alone). A temperature is
compared in the unit its summary gives it (degrees C in the shipped cases), so the error is relative to its
value above 0 degrees C.

>>> pair(1.01, 1.0)["rel_error_pct"] > 0.99, pair(None, 1.0)["rel_error_pct"], pair(0.0, 0.0)["rel_error_pct"]
(True, None, 0.0)
>>> within([pair(1.01, 1.0), pair(2.0, 2.0)], 2.0)
(1.0000000000000009, True)
"""
from __future__ import annotations

import math
from typing import Iterable


def rel_error_pct(a, b) -> float | None:
    """``100 |a - b| / |b|`` (0 when both are 0; None when it cannot be formed: a missing or non-finite value,
    ``b = 0`` alone)."""
    if isinstance(a, bool) or isinstance(b, bool) or not isinstance(a, (int, float)) \
            or not isinstance(b, (int, float)) or not (math.isfinite(a) and math.isfinite(b)):
        return None
    if b == 0.0:
        return 0.0 if a == 0.0 else None
    return 100.0 * abs(a - b) / abs(b)


def pair(a, b) -> dict:
    """One quantity of a comparison: ``{"staggered": a, "monolithic": b, "rel_error_pct": ...}``."""
    return {"staggered": a, "monolithic": b, "rel_error_pct": rel_error_pct(a, b)}


def within(entries: Iterable[dict], tolerance_pct: float) -> tuple[float | None, bool]:
    """(largest relative error, all within ``tolerance_pct``) of ``entries`` (:func:`pair` dicts); an error that
    cannot be formed counts as not within, and no entry at all as within (the caller says whether an empty
    group is a pass)."""
    errs = [e["rel_error_pct"] for e in entries]
    known = [e for e in errs if e is not None]
    return (max(known) if known else None), (None not in errs and all(e <= tolerance_pct for e in errs))
