"""The staggered scheme's estimated error against its true error: a staggered run's summary beside a monolithic
run's of the same scenario and duration.

The true error of a Table 4 result is measured in the terms its estimate is given in (results.estimated_errors):
a temperature's difference in percent of its rise above the run's initial temperature (at least the hold's
RISE_FLOOR_K), any other result's in percent of the monolithic value. ``ratio`` is estimate / true with both
raised to ``FLOOR_PCT`` (two tiny errors are alike, whatever their ratio).
"""
from __future__ import annotations

from rotorcosim.master.manipulator.error_estimate import RISE_FLOOR_K

from .results import TEMPERATURES

#: errors below this [%] count as this much in the ratio
FLOOR_PCT = 0.05


def rows(staggered: dict, monolithic: dict) -> list[dict]:
    """One row per Table 4 result with an estimate: ``bearing``, ``key``, ``estimated_pct``, ``true_pct``,
    ``ratio`` (summary.json dicts of the two runs)."""
    est = (staggered.get("estimated_error") or {}).get("per_result_pct") or {}
    rise = ((staggered.get("hold") or {}).get("output_rise")) or {}
    out = []
    for k, per in est.items():
        s, m = staggered["bearings"][k], monolithic["bearings"][k]
        for key, e in per.items():
            if s.get(key) is None or m.get(key) is None:
                continue
            diff = abs(s[key] - m[key])
            if key in TEMPERATURES:
                r = rise.get(f"thermal{k}.{TEMPERATURES[key]}")
                # the staggered run's rise, less its own share of the difference: the monolithic run's rise
                scale = max(abs(r[0] - (s[key] - m[key])), RISE_FLOOR_K) if r else None
            else:
                scale = abs(m[key]) or None
            if scale is None:
                continue
            true = 100.0 * diff / scale
            out.append({"bearing": k, "key": key, "estimated_pct": e, "true_pct": true,
                        "ratio": max(e, FLOOR_PCT) / max(true, FLOOR_PCT)})
    return out


def largest(rows_: list[dict]) -> dict:
    """The run's estimate (the largest of its results') against its largest true error."""
    if not rows_:
        return {"estimated_pct": None, "true_pct": None, "ratio": None}
    e = max(r["estimated_pct"] for r in rows_)
    t = max(r["true_pct"] for r in rows_)
    return {"estimated_pct": e, "true_pct": t, "ratio": max(e, FLOOR_PCT) / max(t, FLOOR_PCT)}


def table(staggered: dict, monolithic: dict) -> dict:
    """A comparison's ``estimated_error``: ``per_result`` (:func:`rows`) and ``largest`` (:func:`largest`)."""
    r = rows(staggered, monolithic)
    return {"per_result": r, "largest": largest(r)}
