"""Parameter values off by a unit factor: the ranges components declare next to their parameters
(``Variable(..., plausible=(low, high))``, SI) and the one-line warnings of a value outside them.

A value outside its plausible range is legal (a user may mean it), so it is a warning, not an error; where a
common unit factor (10^3, 10^6, their inverses: mm for m, N/mm for N/m, MPa for Pa) brings the value into the
range, the warning names it.

>>> from rotorcosim.components.contract import Variable
>>> v = Variable("k_spring", "parameter", unit="N/m", start=5.254e6, plausible=(1e5, 1e8))
>>> warning("damper0", v, 5254.0)
'damper0.k_spring = 5254 N/m is outside its plausible range 1e+05 to 1e+08 N/m: 1000 times too small? (a value in N/mm where N/m is meant)'
>>> warning("damper0", v, 5.254e6) is None
True
"""
from __future__ import annotations

import math
from typing import Any

#: what a value read in the wrong unit looks like, by the unit it should have been in and the factor it is off
SLIPS = {("N/m", 1e3): "a value in N/mm where N/m is meant", ("m", 1e-3): "a value in mm where m is meant",
         ("Pa", 1e6): "a value in MPa where Pa is meant", ("Pa", 1e5): "a value in bar where Pa is meant"}


def _unit_hint(value: float, lo: float, hi: float, unit: str) -> str:
    """``: 1000 times too small? (...)`` when a unit factor brings ``value`` into ``[lo, hi]``, else ''."""
    for factor in (1e3, 1e-3, 1e6, 1e-6, 1e5):
        if lo <= value * factor <= hi:
            times = f"{factor:g} times too small" if factor > 1 else f"{1 / factor:g} times too large"
            what = SLIPS.get((unit, factor), "a unit prefix slipped")
            return f": {times}? ({what})"
    return ""


def warning(component: str, v, value: Any) -> str | None:
    """The one-line warning for parameter ``v`` of ``component`` set to ``value``, or None (in range, no range
    declared, or not a finite scalar number)."""
    if v.plausible is None or isinstance(value, bool):
        return None
    try:
        x = float(value)
    except (TypeError, ValueError):
        return None
    lo, hi = v.plausible
    if not math.isfinite(x) or lo <= x <= hi:
        return None
    unit = "" if v.unit in ("1", "") else f" {v.unit}"
    return (f"{component}.{v.name} = {x:.4g}{unit} is outside its plausible range {lo:.3g} to {hi:.3g}{unit}"
            + _unit_hint(x, lo, hi, v.unit))


def warnings_of(comp) -> list[str]:
    """The warnings of every parameter of component ``comp`` (an instance) that its user set (``comp.explicit``)
    outside its declared plausible range."""
    out = []
    for v in comp.variables:
        if v.causality == "parameter" and v.name in getattr(comp, "explicit", ()):
            w = warning(comp.name, v, comp.p.get(v.name))
            if w is not None:
                out.append(w)
    return out


def event_warnings(comp, t_end: float) -> list[str]:
    """One line per event parameter of component ``comp`` (``Variable(..., event="the fuel cut")``) whose time is
    at or after ``t_end``, the end of the run [s]: the event never happens in it, and the results mean a run
    without it."""
    out = []
    for v in comp.variables:
        if v.causality != "parameter" or not v.event:
            continue
        try:
            t = float(comp.p.get(v.name))
        except (TypeError, ValueError):
            continue
        if math.isfinite(t) and t >= 0.0 and t >= t_end:
            out.append(f"{comp.name}.{v.name} = {t:.6g} s is at or after the end of the run (t = {t_end:.6g} s): "
                       f"{v.event} never happens in it")
    return out
