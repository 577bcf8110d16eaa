"""The measured values a calibration fits (``targets.csv``) and how a run's summary is read against them.

``targets.csv`` columns: ``case`` (a named case of the SPEC; empty: the scenario as is), ``result`` (a dotted path
into summary.json, e.g. ``final_outputs.node.T`` or ``bearings.0.whirl_amplitude_mm``), ``value`` (measured, in
summary.json's units), optional ``weight`` (default 1), ``uncertainty`` (instead of a weight: the weight is
1 / uncertainty for linear residuals and value / uncertainty for log ones, i.e. the relative uncertainty) and
``holdout`` (1: a validation target, not fitted). Lines starting with ``#`` are comments.

>>> lookup({"final_outputs": {"node.T": 310.0}}, "final_outputs.node.T")
310.0
>>> lookup({"bearings": {"0": {"T_C": 70.5}}}, "bearings.0.T_C")
70.5
>>> value_of({"final_outputs": {"m1.x": [0.25]}}, "final_outputs.m1.x"), lookup({"a": [1.0, 2.0]}, "a.1")
(0.25, 2.0)
"""
from __future__ import annotations

import csv
import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from rotorcosim.components.bounded_read import read_table_text

#: a result is "within +-30 %" when 1 - BAND <= ours / target <= 1 + BAND, "within x2" when 0.5 <= ratio <= 2
BAND = 0.30


class TargetError(ValueError):
    """A mistake in a targets file, or a target no run can give: one line naming the file, row and column."""


@dataclass
class Target:
    """One measured value: ``case``, ``result`` (dotted path), ``value``, ``weight``, ``holdout``."""
    case: str
    result: str
    value: float
    weight: float = 1.0
    holdout: bool = False

    @property
    def label(self) -> str:
        """``result @ case`` (the case only when it has a name)."""
        return f"{self.result} @ {self.case}" if self.case else self.result


def lookup(summary: dict, path: str) -> Any:
    """The value at the dotted ``path`` in ``summary``; a key may itself hold dots (``final_outputs.node.T``:
    the key ``node.T`` of ``final_outputs``), the longest key that matches is taken. KeyError when absent."""
    parts = path.split(".")
    node: Any = summary
    i = 0
    while i < len(parts):
        if isinstance(node, list):  # a vector's element by its index: final_outputs.rotor.X.1
            try:
                node, i = node[int(parts[i])], i + 1
            except (ValueError, IndexError):
                raise KeyError(path) from None
            continue
        if not isinstance(node, dict):
            raise KeyError(path)
        for j in range(len(parts), i, -1):
            key = ".".join(parts[i:j])
            if key in node:
                node, i = node[key], j
                break
        else:
            raise KeyError(path)
    return node


def value_of(summary: dict, path: str) -> float | None:
    """The number at ``path`` (:func:`lookup`; a one-element list counts as its element), or None when the summary
    lacks it or holds no finite number."""
    try:
        v = lookup(summary, path)
    except KeyError:
        return None
    if isinstance(v, list) and len(v) == 1:
        v = v[0]
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
        return None
    return float(v)


def read_targets(path: str | Path, cases: dict[str, dict], residual: str = "log") -> list[Target]:
    """The targets of ``path`` (see the module's docstring). ``cases``: the SPEC's named cases (a target's case
    must be one of them, or empty); ``residual``: ``"log"`` needs positive values."""
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"targets file {path}: no such file")
    text = read_table_text(path, "targets file")
    rows = list(csv.reader(line for line in text.splitlines() if line.strip() and not line.lstrip().startswith("#")))
    if not rows:
        raise TargetError(f"targets file {path}: empty")
    head = [h.strip() for h in rows[0]]
    twice = sorted({h for h in head if head.count(h) > 1})
    if twice:   # the row's last cell of that name would be read, the others dropped without a word
        raise TargetError(f"targets file {path}: column(s) {', '.join(map(repr, twice))} given twice in its header")
    for col in ("case", "result", "value"):
        if col not in head:
            raise TargetError(f"targets file {path}: no column {col!r} (columns: case, result, value[, weight]"
                              f"[, uncertainty][, holdout])")
    extra = set(head) - {"case", "result", "value", "weight", "uncertainty", "holdout"}
    if extra:
        raise TargetError(f"targets file {path}: unknown column(s) {', '.join(sorted(extra))}")
    out, seen = [], set()
    for n, row in enumerate(rows[1:], 2):
        where = f"targets file {path} line {n}"
        if len(row) != len(head):
            raise TargetError(f"{where}: {len(row)} values for {len(head)} columns")
        r = dict(zip(head, (x.strip() for x in row)))
        case = r["case"]
        if case and case not in cases:
            known = ", ".join(repr(c) for c in cases) or "none (only the case \"\", the scenario as is)"
            raise TargetError(f"{where}: case {case!r} is not one of the SPEC's cases ({known})")
        if not r["result"]:
            raise TargetError(f"{where}: empty result")
        value = _float(where, "value", r["value"])
        weight = _float(where, "weight", r.get("weight") or "1")
        if weight <= 0:
            raise TargetError(f"{where}: weight must be > 0, got {weight:g}")
        if r.get("uncertainty"):
            if r.get("weight"):
                raise TargetError(f"{where}: give weight or uncertainty, not both")
            u = _float(where, "uncertainty", r["uncertainty"])
            if u <= 0:
                raise TargetError(f"{where}: uncertainty must be > 0, got {u:g}")
            weight = abs(value) / u if residual == "log" else 1.0 / u
        hold = r.get("holdout") or "0"
        if hold not in ("0", "1"):
            raise TargetError(f"{where}: holdout must be 0 or 1, got {hold!r}")
        if residual == "log" and value <= 0:
            raise TargetError(f"{where}: {r['result']} = {value:g}: log residuals need positive values (drop the "
                              f"target or use residual = \"linear\")")
        if (case, r["result"]) in seen:
            raise TargetError(f"{where}: {r['result']} of case {case!r} is given twice")
        seen.add((case, r["result"]))
        out.append(Target(case, r["result"], value, weight, hold == "1"))
    if not out:
        raise TargetError(f"targets file {path}: no targets, only its header: give one measured value a row (case, "
                          "result, value)")
    if not any(not t.holdout for t in out):
        raise TargetError(f"targets file {path}: every target is a holdout: nothing to fit")
    return out


#: the unit of a summary.json result by the end of its name (bearings.0.whirl_amplitude_mm: mm)
UNITS = {"_mm": "mm", "_C": "degC", "_W": "W", "_MPa": "MPa", "_N": "N", "_s": "s", "_K": "K", "_m": "m"}
#: a target this many times ours at the start (or ours this many times the target) is likely in another unit
UNIT_SLIP = 10.0


def unit_warnings(targets: list[Target], ours: list[float | None]) -> list[str]:
    """A line for each target that looks written in another unit than summary.json's, from ours at the start
    (``ours``, one per target): a factor :data:`UNIT_SLIP` or more apart, of the other sign, or a ``_C`` result
    nearer ours + 273.15 than ours (kelvin). A warning, not a refusal: a start may be that far off."""
    out = []
    for t, v in zip(targets, ours):
        if v is None or v == 0 or t.value == 0:
            continue
        unit = next((u for s, u in UNITS.items() if t.result.endswith(s)), None)
        ratio = t.value / v
        kelvin = unit == "degC" and abs(t.value - 273.15 - v) < abs(t.value - v)
        if kelvin or ratio < 0 or not 1 / UNIT_SLIP < ratio < UNIT_SLIP:
            out.append(f"target {t.label}: {t.value:g} is {ratio:.3g} times ours at the start ({v:g}): is it in "
                       f"summary.json's unit{f' ({unit})' if unit else ''}?" + (" (it reads as kelvin)" if kelvin else ""))
    return out


def _float(where: str, col: str, text: str) -> float:
    try:
        v = float(text)
    except ValueError:
        raise TargetError(f"{where}: {col} {text!r} is not a number") from None
    if not math.isfinite(v):
        raise TargetError(f"{where}: {col} {text!r} is not finite")
    return v


def residual(target: Target, ours: float | None, kind: str, failed: float) -> float:
    """One weighted residual: ``weight * log(ours / value)`` (``kind`` "log") or ``weight * (ours - value)``;
    ``failed`` (in the residual's own unit, before the weight) for a missing or unusable value of ours."""
    if ours is None or (kind == "log" and ours <= 0):
        return target.weight * failed
    if kind == "log":
        return target.weight * math.log(ours / target.value)
    return target.weight * (ours - target.value)


def score(targets: list[Target], values: list[float | None]) -> dict:
    """How close ``values`` (ours, one per target) are: targets, within +-30 % and within x2 (counts), the RMS of
    log(ours / target), and the targets outside x2."""
    n30 = nx2 = 0
    logs, outside = [], []
    for t, v in zip(targets, values):
        ratio = v / t.value if v is not None and t.value != 0 else None
        if ratio is not None and ratio > 0:
            logs.append(math.log(ratio))
        in30 = ratio is not None and 1 - BAND <= ratio <= 1 + BAND
        inx2 = ratio is not None and 0.5 <= ratio <= 2.0
        n30 += in30
        nx2 += inx2
        if not inx2:
            outside.append(t.label)
    return {"targets": len(targets), "within_30pct": n30, "within_x2": nx2,
            "rms_log_ratio": math.sqrt(sum(x * x for x in logs) / len(logs)) if logs else None,
            "outside_x2": outside}
